/* Tests of geom3/surface_split: torus cut along meridians and longitudes (cylinder, two cylinders,
 * disk), a grid cut by an open path across it (two patches) and by an interior slit (one patch, slit
 * opened), a sphere-like hull cut by a closed loop; Euler characteristics, vertex counts, areas. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "core/rng.h"
#include "geom3/edge_map.h"
#include "geom3/surface_split.h"

static void torus_grid(int nu, int nv, acd_mesh *m) {
    m->nvertices = (size_t)nu * (size_t)nv;
    m->ntriangles = 2 * m->nvertices;
    m->vertices = malloc(3 * m->nvertices * sizeof(double));
    m->triangles = malloc(3 * m->ntriangles * sizeof(uint32_t));
    assert_non_null(m->vertices);
    assert_non_null(m->triangles);
    const double pi = 3.14159265358979323846;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            double u = 2 * pi * i / nu, v = 2 * pi * j / nv;
            double *p = m->vertices + 3 * (size_t)(i * nv + j);
            p[0] = (2 + 0.5 * cos(v)) * cos(u);
            p[1] = (2 + 0.5 * cos(v)) * sin(u);
            p[2] = 0.5 * sin(v);
        }
    size_t t = 0;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            uint32_t a = (uint32_t)(i * nv + j), b = (uint32_t)(((i + 1) % nu) * nv + j);
            uint32_t c = (uint32_t)(((i + 1) % nu) * nv + (j + 1) % nv), d = (uint32_t)(i * nv + (j + 1) % nv);
            uint32_t *q = m->triangles + 3 * t;
            q[0] = a, q[1] = b, q[2] = c, q[3] = a, q[4] = c, q[5] = d;
            t += 2;
        }
}

/* Euler characteristic V - E + F of a mesh (E: distinct undirected edges). */
static long euler(const acd_mesh *m) {
    acd_edge_map em;
    assert_int_equal(acd_edge_map_build(m->triangles, m->ntriangles, NULL, &em, NULL), ACD_OK);
    size_t e = 0;
    for (size_t i = 0; i < em.n; i++) {
        uint32_t a = (uint32_t)(em.key[i] >> 32), b = (uint32_t)em.key[i];
        if (a < b || acd_edge_map_find(&em, b, a) == ACD_EDGE_NONE) e++;
    }
    acd_edge_map_free(&em);
    return (long)m->nvertices - (long)e + (long)m->ntriangles;
}

static double area(const acd_mesh *m) {
    double s = 0;
    for (size_t t = 0; t < m->ntriangles; t++) {
        const double *a = m->vertices + 3 * m->triangles[3 * t], *b = m->vertices + 3 * m->triangles[3 * t + 1],
                     *c = m->vertices + 3 * m->triangles[3 * t + 2];
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        s += 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    return s;
}

/* Common checks: faces partitioned, geometry and sources consistent, area conserved. */
static void check_split(const acd_mesh *m, const acd_split_result *r) {
    size_t tot = 0;
    double a = 0;
    for (size_t p = 0; p < r->npatches; p++) {
        const acd_patch *pc = &r->patches[p];
        tot += pc->mesh.ntriangles;
        a += area(&pc->mesh);
        for (size_t t = 0; t < pc->mesh.ntriangles; t++) {
            uint32_t f = pc->source_face[t];
            assert_int_equal(r->face_patch[f], p);
            for (int i = 0; i < 3; i++)
                assert_int_equal(pc->source_vertex[pc->mesh.triangles[3 * t + i]], m->triangles[3 * f + i]);
        }
        for (size_t v = 0; v < pc->mesh.nvertices; v++)
            assert_memory_equal(pc->mesh.vertices + 3 * v, m->vertices + 3 * pc->source_vertex[v], 3 * sizeof(double));
    }
    assert_int_equal(tot, m->ntriangles);
    assert_true(fabs(a - area(m)) < 1e-12 * area(m));
}

static void test_torus_cuts(void **state) {
    (void)state;
    int nu = 12, nv = 8;
    acd_mesh m;
    torus_grid(nu, nv, &m);
    assert_int_equal(euler(&m), 0);
    acd_split_result r;
    acd_error err;
    uint32_t mer[8], mer2[8], lon[12];
    for (int j = 0; j < nv; j++) mer[j] = (uint32_t)(0 * nv + j), mer2[j] = (uint32_t)(6 * nv + j);
    for (int i = 0; i < nu; i++) lon[i] = (uint32_t)(i * nv + 0);
    /* one meridian: a cylinder (one patch, chi 0, nv more vertices) */
    assert_int_equal(acd_surface_split_path(&m, mer, (size_t)nv, 1, &r, &err), ACD_OK);
    assert_int_equal(r.npatches, 1);
    assert_int_equal(r.cut_edges, (size_t)nv);
    assert_int_equal(r.patches[0].mesh.nvertices, m.nvertices + (size_t)nv);
    assert_int_equal(euler(&r.patches[0].mesh), 0);
    check_split(&m, &r);
    acd_split_result_free(&r);
    /* two meridians: two cylinders of equal size */
    uint32_t both[32];
    for (int j = 0; j < nv; j++) {
        both[2 * j] = mer[j], both[2 * j + 1] = mer[(j + 1) % nv];
        both[2 * nv + 2 * j] = mer2[j], both[2 * nv + 2 * j + 1] = mer2[(j + 1) % nv];
    }
    assert_int_equal(acd_surface_split_edges(&m, both, 2 * (size_t)nv, &r, &err), ACD_OK);
    assert_int_equal(r.npatches, 2);
    assert_int_equal(r.patches[0].mesh.ntriangles, r.patches[1].mesh.ntriangles);
    for (int p = 0; p < 2; p++) assert_int_equal(euler(&r.patches[p].mesh), 0);
    check_split(&m, &r);
    acd_split_result_free(&r);
    /* meridian + longitude: a disk (chi 1) with nu * nv + nu + nv + 1 vertices */
    uint32_t ml[40];
    size_t k = 0;
    for (int j = 0; j < nv; j++) ml[k++] = mer[j], ml[k++] = mer[(j + 1) % nv];
    for (int i = 0; i < nu; i++) ml[k++] = lon[i], ml[k++] = lon[(i + 1) % nu];
    assert_int_equal(acd_surface_split_edges(&m, ml, k / 2, &r, &err), ACD_OK);
    assert_int_equal(r.npatches, 1);
    assert_int_equal(euler(&r.patches[0].mesh), 1);
    assert_int_equal(r.patches[0].mesh.nvertices, (size_t)(nu * nv + nu + nv + 1));
    check_split(&m, &r);
    acd_split_result_free(&r);
    acd_mesh_free(&m);
}

static void grid(int n, acd_mesh *m) {
    m->nvertices = (size_t)(n + 1) * (size_t)(n + 1);
    m->ntriangles = 2 * (size_t)n * (size_t)n;
    m->vertices = malloc(3 * m->nvertices * sizeof(double));
    m->triangles = malloc(3 * m->ntriangles * sizeof(uint32_t));
    assert_non_null(m->vertices);
    assert_non_null(m->triangles);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            double *p = m->vertices + 3 * (size_t)(j * (n + 1) + i);
            p[0] = i, p[1] = j, p[2] = 0.1 * i * j;
        }
    size_t t = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)n + 2, d = a + (uint32_t)n + 1;
            uint32_t *q = m->triangles + 3 * t;
            q[0] = a, q[1] = b, q[2] = c, q[3] = a, q[4] = c, q[5] = d;
            t += 2;
        }
}

static void test_grid_paths(void **state) {
    (void)state;
    int n = 6;
    acd_mesh m;
    grid(n, &m);
    acd_split_result r;
    acd_error err;
    /* open path across the grid along x = 3: two patches of 3 x 6 cells */
    uint32_t across[7];
    for (int j = 0; j <= n; j++) across[j] = (uint32_t)(j * (n + 1) + 3);
    assert_int_equal(acd_surface_split_path(&m, across, 7, 0, &r, &err), ACD_OK);
    assert_int_equal(r.npatches, 2);
    assert_int_equal(r.patches[0].mesh.ntriangles, 36);
    assert_int_equal(r.patches[0].mesh.nvertices, 28);
    assert_int_equal(r.patches[1].mesh.nvertices, 28);
    check_split(&m, &r);
    acd_split_result_free(&r);
    /* interior slit from (1,3) to (5,3): one patch, the 3 interior slit vertices doubled, the slit
     * opened into a hole (an annulus, chi 0) */
    uint32_t slit[5];
    for (int i = 1; i <= 5; i++) slit[i - 1] = (uint32_t)(3 * (n + 1) + i);
    assert_int_equal(acd_surface_split_path(&m, slit, 5, 0, &r, &err), ACD_OK);
    assert_int_equal(r.npatches, 1);
    assert_int_equal(r.patches[0].mesh.nvertices, m.nvertices + 3);
    assert_int_equal(euler(&r.patches[0].mesh), 0);
    check_split(&m, &r);
    acd_split_result_free(&r);
    /* closed square loop around the centre cells: inner disk and outer annulus */
    uint32_t sq[8] = {2 * 7 + 2, 2 * 7 + 3, 2 * 7 + 4, 3 * 7 + 4, 4 * 7 + 4, 4 * 7 + 3, 4 * 7 + 2, 3 * 7 + 2};
    assert_int_equal(acd_surface_split_path(&m, sq, 8, 1, &r, &err), ACD_OK);
    assert_int_equal(r.npatches, 2);
    size_t inner = r.patches[0].mesh.ntriangles < r.patches[1].mesh.ntriangles ? 0 : 1;
    assert_int_equal(r.patches[inner].mesh.ntriangles, 8);
    assert_int_equal(euler(&r.patches[inner].mesh), 1);
    assert_int_equal(euler(&r.patches[1 - inner].mesh), 0);
    check_split(&m, &r);
    acd_split_result_free(&r);
    /* no cut: one patch equal to the input */
    assert_int_equal(acd_surface_split_edges(&m, NULL, 0, &r, &err), ACD_OK);
    assert_int_equal(r.npatches, 1);
    assert_int_equal(r.patches[0].mesh.nvertices, m.nvertices);
    acd_split_result_free(&r);
    /* errors: a non-edge, a vertex out of range */
    uint32_t bad[2] = {0, 8 + 8};
    assert_int_equal(acd_surface_split_edges(&m, bad, 1, &r, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "not an edge"));
    bad[1] = 1000;
    assert_int_equal(acd_surface_split_edges(&m, bad, 1, &r, &err), ACD_ERR_INVALID_INPUT);
    acd_mesh_free(&m);
}

static void test_closed_loop_on_hull(void **state) {
    (void)state;
    /* faces of a random convex hull with centroid above z = 0 and their complement: the boundary
     * of that face set is a set of closed loops; each side's components come out as patches */
    acd_rng r;
    acd_rng_seed(&r, 61);
    for (int trial = 0; trial < 20; trial++) {
        size_t n = 30 + (size_t)acd_rng_below(&r, 100);
        double *p = malloc(3 * n * sizeof *p);
        assert_non_null(p);
        for (size_t i = 0; i < 3 * n; i++) p[i] = 2 * acd_rng_uniform(&r) - 1;
        acd_hull h;
        assert_int_equal(acd_hull_compute(p, n, &h, NULL), ACD_OK);
        acd_mesh m = {h.vertices, h.nvertices, h.triangles, h.ntriangles};
        uint8_t *up = malloc(m.ntriangles);
        uint32_t *cut = malloc(6 * m.ntriangles * sizeof *cut);
        assert_non_null(up);
        assert_non_null(cut);
        for (size_t t = 0; t < m.ntriangles; t++) {
            double z = 0;
            for (int i = 0; i < 3; i++) z += m.vertices[3 * m.triangles[3 * t + i] + 2];
            up[t] = z > 0;
        }
        size_t nc = 0;
        for (size_t t = 0; t < m.ntriangles; t++)
            for (int i = 0; i < 3; i++) {
                uint32_t u = h.neighbors[3 * t + i];
                if (up[t] && !up[u]) {
                    cut[2 * nc] = m.triangles[3 * t + i];
                    cut[2 * nc + 1] = m.triangles[3 * t + (i + 1) % 3];
                    nc++;
                }
            }
        acd_split_result res;
        acd_error err;
        assert_int_equal(acd_surface_split_edges(&m, cut, nc, &res, &err), ACD_OK);
        check_split(&m, &res);
        /* no patch mixes up and down faces, and every cut edge is a boundary edge of two patches */
        for (size_t t = 0; t < m.ntriangles; t++)
            for (int i = 0; i < 3; i++) {
                uint32_t u = h.neighbors[3 * t + i];
                if (up[t] == up[u]) continue;
                assert_true(res.face_patch[t] != res.face_patch[u]);
            }
        if (nc > 0) assert_true(res.npatches >= 2);
        acd_split_result_free(&res);
        free(up);
        free(cut);
        acd_hull_free(&h);
        free(p);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_torus_cuts),
        cmocka_unit_test(test_grid_paths),
        cmocka_unit_test(test_closed_loop_on_hull),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
