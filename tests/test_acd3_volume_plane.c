/* Tests of acd3/volume_plane (the volume planes of the tight pipeline's cut choice and of the merge
 * refinement's estimates; docs/acd3d.md "Hull tightness", "Triangulation density"):
 * - acd3_volume_plane_sides is the sum of the hull volumes of the two pieces a cut gives: on a
 *   voxel U (volume 7, hull 9) 9 for a plane across the arms or the base, 8 for a plane between
 *   the arms (each side's hull a pentagonal prism of volume 4), and the cube's volume for any
 *   plane through a cube;
 * - it depends on the surface only: on a bumpy sphere and its midpoint subdivision (the same
 *   surface, four times the triangles; the midpoints and the new edges' crossings lie in the hull
 *   of the old triangles' points on their side and crossings) the same volumes within rounding,
 *   for axis-aligned and oblique planes;
 * - acd3_volume_planes_scored on a part small enough to be scored whole (every vertex, every
 *   crossing: the estimate and the full search alike): on the U the best plane is the one between
 *   the arms (score 8), the scores ascend, each is the exact sides' volume of the plane returned,
 *   and at most the hull volume of the whole (9).
 * (What the sample of a large part does on finer triangulations: docs/acd3d.md "Triangulation
 * density", measured on bunny00 x4 and x16.) */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "acd3/volume_plane.h"
#include "shapes.h"

static void voxel_u(acd_mesh *m) {
    unsigned char occ[9] = {1, 1, 1, 1, 0, 1, 1, 0, 1}; /* rows y = 0, 1, 2; the notch at x = 1, y >= 1 */
    assert_true(mg_voxels(m, occ, 3, 3, 1));
}

static double sides(const acd_mesh *m, double nx, double ny, double nz, double px, double py, double pz) {
    double l = sqrt(nx * nx + ny * ny + nz * nz);
    const double n[3] = {nx / l, ny / l, nz / l}, p[3] = {px, py, pz};
    return acd3_volume_plane_sides(m, n, p);
}

static void test_sides_exact(void **state) {
    (void)state;
    acd_mesh u;
    voxel_u(&u);
    assert_true(fabs(mg_volume(&u) - 7) < 1e-12);
    /* across the base or the arms: the pieces' hulls fill the U's hull (3 x 3 x 1) */
    assert_true(fabs(sides(&u, 0, 1, 0, 0, 0.5, 0) - 9) < 1e-9);
    assert_true(fabs(sides(&u, 0, 1, 0, 0, 1.5, 0) - 9) < 1e-9);
    assert_true(fabs(sides(&u, 0, 0, 1, 0, 0, 0.3) - 9) < 1e-9);
    /* between the arms at x = c in [1, 2]: hulls 2c + 1 and 2 (3 - c) + 1 */
    for (double c = 1.1; c < 2; c += 0.3) assert_true(fabs(sides(&u, 1, 0, 0, c, 0, 0) - 8) < 1e-9);
    /* through one arm (c < 1): the other side's hull is a box again */
    assert_true(fabs(sides(&u, 1, 0, 0, 0.5, 0, 0) - 9) < 1e-9);
    acd_mesh_free(&u);
    acd_mesh c;
    unsigned char one = 1;
    assert_true(mg_voxels(&c, &one, 1, 1, 1));
    assert_true(fabs(sides(&c, 1, 0, 0, 0.25, 0, 0) - 1) < 1e-9);
    assert_true(fabs(sides(&c, 1, 2, 3, 0.5, 0.5, 0.5) - 1) < 1e-9);
    assert_true(fabs(sides(&c, -1, 1, 0.5, 0.3, 0.6, 0.2) - 1) < 1e-9);
    acd_mesh_free(&c);
}

/* m's every triangle split in four at its edges' midpoints, each edge's midpoint made once. */
static void midpoint_subdivide(const acd_mesh *m, acd_mesh *out) {
    size_t nv = m->nvertices, nt = m->ntriangles;
    /* the midpoint of edge (a, b), a < b: found by a linear scan of a's list (small meshes) */
    uint32_t *ea = malloc(3 * nt * sizeof *ea), *eb = malloc(3 * nt * sizeof *eb), ne = 0;
    memset(out, 0, sizeof *out);
    out->vertices = malloc(3 * (nv + 3 * nt) * sizeof *out->vertices);
    out->triangles = malloc(12 * nt * sizeof *out->triangles);
    assert_true(ea && eb && out->vertices && out->triangles);
    memcpy(out->vertices, m->vertices, 3 * nv * sizeof *out->vertices);
    for (size_t t = 0; t < nt; t++) {
        const uint32_t *T = m->triangles + 3 * t;
        uint32_t M[3];
        for (int e = 0; e < 3; e++) {
            uint32_t a = T[e], b = T[(e + 1) % 3];
            if (a > b) a ^= b, b ^= a, a ^= b;
            uint32_t k = 0;
            while (k < ne && !(ea[k] == a && eb[k] == b)) k++;
            if (k == ne) {
                ea[ne] = a, eb[ne] = b, ne++;
                for (int d = 0; d < 3; d++)
                    out->vertices[3 * (nv + k) + d] = (m->vertices[3 * (size_t)a + d] + m->vertices[3 * (size_t)b + d]) / 2;
            }
            M[e] = (uint32_t)(nv + k);
        }
        const uint32_t q[12] = {T[0], M[0], M[2], M[0], T[1], M[1], M[2], M[1], T[2], M[0], M[1], M[2]};
        memcpy(out->triangles + 12 * t, q, sizeof q);
    }
    out->nvertices = nv + ne;
    out->ntriangles = 4 * nt;
    free(ea);
    free(eb);
}

static void test_sides_subdivision(void **state) {
    (void)state;
    acd_mesh m, s;
    assert_true(mg_radial(&m, 16, 10, mg_bumpy_r, NULL));
    midpoint_subdivide(&m, &s);
    assert_int_equal(s.ntriangles, 4 * m.ntriangles);
    assert_true(s.nvertices > 3 * m.nvertices);
    assert_true(fabs(mg_volume(&s) - mg_volume(&m)) <= 1e-12 * mg_volume(&m)); /* the same solid */
    static const double planes[][6] = {{1, 0, 0, 0, 0, 0},      {0, 1, 0, 0, 0.3, 0},   {0, 0, 1, 0, 0, -0.4},
                                       {1, 1, 0, 0.1, 0.2, 0},  {1, -2, 3, 0, 0, 0.5},  {0.3, 0.2, -1, 0.4, -0.1, 0.2}};
    for (size_t i = 0; i < sizeof planes / sizeof planes[0]; i++) {
        const double *q = planes[i];
        double a = sides(&m, q[0], q[1], q[2], q[3], q[4], q[5]), b = sides(&s, q[0], q[1], q[2], q[3], q[4], q[5]);
        assert_true(a > 0);
        assert_true(fabs(b - a) <= 1e-9 * a);
    }
    acd_mesh_free(&m);
    acd_mesh_free(&s);
}

static void test_planes_scored_whole(void **state) {
    (void)state;
    acd_mesh u;
    voxel_u(&u);
    for (int est = 0; est < 2; est++) {
        acd3_plane_candidate c[3];
        double score[3], whole = 0;
        /* est: an estimate whose sample is the whole U (fewer vertices and triangles than it takes) */
        int n = acd3_volume_planes_scored(&u, 3, est ? 400 : 0, 3, c, score, &whole);
        assert_int_equal(n, 3);
        assert_true(fabs(whole - 9) < 1e-9);
        for (int i = 0; i < n; i++) {
            const double *nr = c[i].normal;
            assert_true(fabs(nr[0] * nr[0] + nr[1] * nr[1] + nr[2] * nr[2] - 1) < 1e-12);
            assert_string_equal(c[i].kind, "volume");
            if (i > 0) assert_true(score[i] >= score[i - 1]);
            assert_true(score[i] <= whole * (1 + 1e-9));
            assert_true(fabs(acd3_volume_plane_sides(&u, c[i].normal, c[i].point) - score[i]) <= 1e-9 * score[i]);
        }
        /* the best: between the arms (x in (1, 2)), the others 9 */
        assert_true(fabs(score[0] - 8) < 1e-9);
        assert_true(fabs(fabs(c[0].normal[0]) - 1) < 1e-9);
        assert_true(c[0].point[0] > 1 && c[0].point[0] < 2);
        assert_true(fabs(score[1] - 9) < 1e-9 && fabs(score[2] - 9) < 1e-9);
        /* nmax and naxes bound what is returned */
        assert_int_equal(acd3_volume_planes_scored(&u, 1, est ? 400 : 0, 3, c, score, NULL), 1);
        assert_true(fabs(score[0] - 8) < 1e-9);
    }
    acd_mesh_free(&u);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sides_exact),
        cmocka_unit_test(test_sides_subdivision),
        cmocka_unit_test(test_planes_scored_whole),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
