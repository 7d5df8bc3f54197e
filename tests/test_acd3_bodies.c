/* Inputs of several bodies (acd3/decompose split_bodies, docs/acd3d.md "Bodies"): the root is split
 * into its bodies before any cut, so no part holds two separate bodies and no hull spans the space
 * between them. Before, a row of thin plates (as OpenSCAD writes a row of objects into one STL) was
 * measured as one part within tau (the pockets between bodies are not projected) and came out as one
 * hull over the whole row.
 *  1. twelve plates 2 x 2 x 0.2 in a row, solid mode: twelve parts, the root's node marked bodies with
 *     twelve children, each part one body, the hulls' volumes adding up to the input's (boxes: a hull
 *     spanning a gap would add its air); the same parts on 1 and 2 threads;
 *  2. the same in surface mode: twelve patches, each edge-connected;
 *  3. a hollow box (an outer shell with a cavity shell) holding a small box in its cavity: two bodies;
 *     the cavity stays with its shell (volumes add up to the solid's), and no part mixes the small box
 *     with the hollow one;
 *  4. one body (one plate; a box with a cavity): no bodies split, the root is a leaf or cut by a plane;
 *  5. two boxes touching along an edge: refused as non-manifold, then repaired (mesh/repair
 *     split_nonmanifold) into two bodies, two parts. */
// ctest: TIMEOUT 300
#include "testutil.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd/mesh.h"
#include "core/union_find.h"
#include "geom3/volume.h"
#include "acd3d_check.h"

/* Appends the box [lo, hi] to m, outward (inward when flip: a cavity). */
static void add_box(acd_mesh *m, const double lo[3], const double hi[3], int flip) {
    static const uint32_t Q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    size_t b = m->nvertices;
    m->vertices = realloc(m->vertices, 3 * (b + 8) * sizeof *m->vertices);
    m->triangles = realloc(m->triangles, 3 * (m->ntriangles + 12) * sizeof *m->triangles);
    assert_non_null(m->vertices);
    assert_non_null(m->triangles);
    for (int i = 0; i < 8; i++)
        for (int k = 0; k < 3; k++) m->vertices[3 * (b + i) + k] = (i >> k) & 1 ? hi[k] : lo[k];
    for (int q = 0; q < 6; q++) {
        uint32_t t[2][3] = {{Q[q][0], Q[q][1], Q[q][2]}, {Q[q][0], Q[q][2], Q[q][3]}};
        for (int h = 0; h < 2; h++) {
            uint32_t *o = m->triangles + 3 * m->ntriangles++;
            o[0] = (uint32_t)b + t[h][0];
            o[1] = (uint32_t)b + t[h][flip ? 2 : 1];
            o[2] = (uint32_t)b + t[h][flip ? 1 : 2];
        }
    }
    m->nvertices = b + 8;
}

static void plates(acd_mesh *m, int n) {
    memset(m, 0, sizeof *m);
    for (int i = 0; i < n; i++) add_box(m, (double[3]){3.0 * i, 0, 0}, (double[3]){3.0 * i + 2, 2, 0.2}, 0);
}

/* Edge-connected components of m's triangles (vertices shared by index; a part's mesh is indexed). */
static size_t components(const acd_mesh *m) {
    uint32_t *uf = malloc((m->nvertices ? m->nvertices : 1) * sizeof *uf);
    assert_non_null(uf);
    for (size_t v = 0; v < m->nvertices; v++) uf[v] = (uint32_t)v;
    for (size_t t = 0; t < m->ntriangles; t++)
        for (int i = 0; i < 3; i++) acd_uf_union(uf, m->triangles[3 * t + i], m->triangles[3 * t + (i + 1) % 3]);
    size_t c = 0;
    for (size_t v = 0; v < m->nvertices; v++) c += acd_uf_find(uf, (uint32_t)v) == v;
    free(uf);
    return c;
}

static double hull_volumes(const acd3d_result *r) {
    double s = 0;
    for (size_t i = 0; i < r->nparts; i++) s += r->parts[i].hull_volume;
    return s;
}

static void test_plates_solid(void **state) {
    (void)state;
    acd_mesh m;
    plates(&m, 12);
    acd3d_params p = acd3d_default_params();
    acd3d_result r1, r2;
    acd_error err;
    p.threads = 1;
    assert_int_equal(acd3d_decompose(&m, &p, &r1, &err), ACD_OK);
    p.threads = 2;
    assert_int_equal(acd3d_decompose(&m, &p, &r2, &err), ACD_OK);
    assert_int_equal(r1.nparts, 12);
    assert_int_equal(r1.nodes[0].bodies, 1);
    assert_int_equal(r1.nodes[0].nchildren, 12);
    for (int k = 0; k < 4; k++) assert_true(r1.nodes[0].cut_plane[k] == 0);
    double vin = acd_geom3_signed_volume(&m), sum = 0;
    for (size_t i = 0; i < r1.nparts; i++) {
        assert_int_equal(components(&r1.parts[i].mesh), 1);
        assert_true(r1.parts[i].concavity <= r1.tau + r1.tol);
        sum += acd_geom3_signed_volume(&r1.parts[i].mesh);
    }
    assert_true(fabs(sum - vin) <= 1e-12 * vin);
    assert_true(fabs(hull_volumes(&r1) - vin) <= 1e-9 * vin); /* no hull over a gap */
    ck3_same_parts(&r1, &r2);
    acd3d_result_free(&r1);
    acd3d_result_free(&r2);
    acd_mesh_free(&m);
}

static void test_plates_surface(void **state) {
    (void)state;
    acd_mesh m;
    plates(&m, 12);
    acd3d_params p = acd3d_default_params();
    p.mode = ACD3D_SURFACE;
    acd3d_result r;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_int_equal(r.nparts, 12);
    assert_int_equal(r.nodes[0].bodies, 1);
    size_t nt = 0;
    for (size_t i = 0; i < r.nparts; i++) {
        assert_int_equal(components(&r.parts[i].mesh), 1);
        nt += r.parts[i].mesh.ntriangles;
    }
    assert_int_equal(nt, m.ntriangles); /* the patches tile the surface */
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}

static void test_nested(void **state) {
    (void)state;
    acd_mesh m = {0};
    add_box(&m, (double[3]){-2, -2, -2}, (double[3]){2, 2, 2}, 0);
    add_box(&m, (double[3]){-1, -1, -1}, (double[3]){1, 1, 1}, 1);         /* the cavity */
    add_box(&m, (double[3]){-0.5, -0.5, -0.5}, (double[3]){0.5, 0.5, 0.5}, 0); /* a box in it */
    acd3d_params p = acd3d_default_params();
    acd3d_result r;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_int_equal(r.nodes[0].bodies, 1);
    assert_int_equal(r.nodes[0].nchildren, 2);
    /* the first body: the hollow box with its cavity (64 - 8); the second, the small box */
    assert_true(fabs(r.nodes[r.nodes[0].first_child].volume - 56) <= 1e-12 * 56);
    assert_true(fabs(r.nodes[r.nodes[0].first_child + 1].volume - 1) <= 1e-12);
    double sum = 0;
    for (size_t i = 0; i < r.nparts; i++) {
        const acd_mesh *pm = &r.parts[i].mesh;
        size_t inside = 0; /* vertices strictly inside the cavity: the small box's */
        for (size_t v = 0; v < pm->nvertices; v++) {
            const double *x = pm->vertices + 3 * v;
            inside += fabs(x[0]) < 1 && fabs(x[1]) < 1 && fabs(x[2]) < 1;
        }
        assert_true(inside == 0 || inside == pm->nvertices);
        sum += acd_geom3_signed_volume(pm);
    }
    assert_true(fabs(sum - 57) <= 1e-12 * 57);
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}

static void test_one_body(void **state) {
    (void)state;
    acd_mesh m;
    plates(&m, 1);
    acd3d_params p = acd3d_default_params();
    acd3d_result r;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_int_equal(r.nparts, 1);
    assert_int_equal(r.nodes[0].bodies, 0);
    acd3d_result_free(&r);
    acd_mesh_free(&m);
    /* a box with a cavity: two shells, one body */
    memset(&m, 0, sizeof m);
    add_box(&m, (double[3]){-2, -2, -2}, (double[3]){2, 2, 2}, 0);
    add_box(&m, (double[3]){-1, -1, -1}, (double[3]){1, 1, 1}, 1);
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_int_equal(r.nodes[0].bodies, 0);
    assert_true(r.nparts > 1); /* cut by planes: a hollow box is not convex */
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}

/* Two boxes touching along an edge, vertices shared (as CAD booleans write an assembly): not closed
 * (the edge has four faces) until acd_mesh_repair pairs them into the boxes' wedges
 * (split_nonmanifold); then two bodies, two convex parts, volumes adding up. */
static void test_edge_touch_repaired(void **state) {
    (void)state;
    acd_mesh m = {0};
    add_box(&m, (double[3]){0, 0, 0}, (double[3]){1, 1, 1}, 0);
    add_box(&m, (double[3]){1, 1, 0}, (double[3]){2, 2, 1}, 0);
    acd_error err;
    assert_int_equal(acd_mesh_weld(&m, 0, NULL, &err), ACD_OK);
    assert_int_equal(m.nvertices, 14);
    acd3d_params p = acd3d_default_params();
    acd3d_result r;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_NON_MANIFOLD);
    acd_repair_options ro = acd_repair_default_options();
    acd_repair_stats rs;
    assert_int_equal(acd_mesh_repair(&m, &ro, &rs, &err), ACD_OK);
    assert_int_equal(rs.nonmanifold_edges_split, 1);
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_int_equal(r.nodes[0].bodies, 1);
    assert_int_equal(r.nparts, 2);
    for (size_t i = 0; i < r.nparts; i++) {
        assert_true(fabs(r.parts[i].volume - 1) <= 1e-12);
        assert_true(fabs(r.parts[i].hull_volume - 1) <= 1e-12);
    }
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_plates_solid),
        cmocka_unit_test(test_plates_surface),
        cmocka_unit_test(test_nested),
        cmocka_unit_test(test_one_body),
        cmocka_unit_test(test_edge_touch_repaired),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
