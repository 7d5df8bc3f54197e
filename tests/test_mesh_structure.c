/* Tests of the structural modules: the half-edge view (twins, valences, edge lists) and vertex
 * welding (exact and tolerance), as properties checked against brute force. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/mesh.h"
#include "core/rng.h"
#include "mesh/halfedge.h"
#include "mesh/weld.h"

/* A random triangle soup over a small vertex pool: many shared, boundary and non-manifold edges. */
static void random_mesh(acd_mesh *m, size_t nv, size_t nt, uint64_t seed) {
    acd_rng r;
    acd_rng_seed(&r, seed);
    m->nvertices = nv;
    m->ntriangles = nt;
    m->vertices = calloc(3 * nv, sizeof(double));
    m->triangles = malloc(3 * nt * sizeof(uint32_t));
    assert_non_null(m->vertices);
    assert_non_null(m->triangles);
    for (size_t i = 0; i < 3 * nt; i++) m->triangles[i] = (uint32_t)acd_rng_below(&r, nv);
}

static void test_halfedges_against_brute_force(void **state) {
    (void)state;
    for (uint64_t seed = 1; seed <= 5; seed++) {
        acd_mesh m;
        random_mesh(&m, 12, 60, seed);
        acd_halfedges he;
        acd_error err;
        assert_int_equal(acd_halfedges_build(&m, &he, &err), ACD_OK);
        assert_int_equal(he.nhalfedges, 180);
        size_t listed = 0;
        for (uint32_t e = 0; e < he.nedges; e++) {
            uint32_t a = he.edge_v[2 * e], b = he.edge_v[2 * e + 1];
            assert_true(a < b);
            /* brute force: the half-edges joining a and b in non-degenerate triangles */
            uint32_t count = 0;
            for (uint32_t h = 0; h < 180; h++) {
                const uint32_t *t = m.triangles + (h - h % 3);
                if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
                uint32_t x = acd_he_from(&m, h), y = acd_he_to(&m, h);
                if ((x == a && y == b) || (x == b && y == a)) {
                    count++;
                    assert_int_equal(he.edge[h], e);
                }
            }
            assert_int_equal(acd_edge_valence(&he, e), count);
            listed += count;
            for (uint32_t k = he.edge_start[e]; k < he.edge_start[e + 1]; k++) assert_int_equal(he.edge[he.edge_he[k]], e);
        }
        size_t live = 0;
        for (uint32_t h = 0; h < 180; h++) {
            live += he.edge[h] != ACD_HE_NONE;
            uint32_t g = he.twin[h];
            if (g != ACD_HE_NONE) {
                assert_int_equal(he.twin[g], h);
                assert_int_equal(he.edge[g], he.edge[h]);
                assert_int_equal(acd_edge_valence(&he, he.edge[h]), 2);
            } else if (he.edge[h] != ACD_HE_NONE) {
                assert_int_not_equal(acd_edge_valence(&he, he.edge[h]), 2);
            }
        }
        assert_int_equal(listed, live);
        acd_halfedges_free(&he);
        /* an index out of range is refused, naming the triangle */
        m.triangles[7] = 12;
        assert_int_equal(acd_halfedges_build(&m, &he, &err), ACD_ERR_INVALID_INPUT);
        assert_non_null(strstr(err.message, "triangle 2"));
        acd_mesh_free(&m);
    }
}

static void test_weld_exact_against_brute_force(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 9);
    size_t n = 3000;
    double *v = malloc(3 * n * sizeof *v);
    uint32_t *remap = malloc(n * sizeof *remap);
    assert_non_null(v);
    assert_non_null(remap);
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) v[3 * i + (size_t)k] = (double)acd_rng_below(&r, 4) - 1.5; /* few values */
    v[0] = 0.0;
    v[3] = -0.0; /* -0 equals +0 */
    v[1] = v[4];
    v[2] = v[5];
    size_t u;
    assert_true(acd_weld_exact(v, n, remap, &u));
    assert_int_equal(remap[0], remap[1]);
    size_t next = 0;
    for (size_t i = 0; i < n; i++) {
        assert_true(remap[i] <= next);
        if (remap[i] == next) next++;
        for (size_t j = 0; j < i; j += 7) {
            int same = v[3 * i] == v[3 * j] && v[3 * i + 1] == v[3 * j + 1] && v[3 * i + 2] == v[3 * j + 2];
            assert_int_equal(same, remap[i] == remap[j]);
        }
    }
    assert_int_equal(next, u);
    assert_true(u <= 5 * 5 * 5); /* 4 values per coordinate, plus the 0 of the first two points */
    free(v);
    free(remap);
}

static void test_weld_tolerance_clusters(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 10);
    /* 50 well-separated centres, 20 jittered copies each (jitter << tol << spacing) */
    size_t n = 1000;
    double *v = malloc(3 * n * sizeof *v);
    uint32_t *remap = malloc(n * sizeof *remap);
    assert_non_null(v);
    assert_non_null(remap);
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            v[3 * i + (size_t)k] = (double)((i % 50) * (k + 1) % 50) + 1e-9 * (acd_rng_uniform(&r) - 0.5);
    size_t u;
    assert_true(acd_weld_tolerance(v, n, 1e-6, remap, &u));
    assert_int_equal(u, 50);
    for (size_t i = 0; i < n; i++) assert_int_equal(remap[i], remap[i % 50]);
    acd_weld_compact(v, n, remap);
    assert_true(fabs(v[3 * 49] - (double)(49 % 50)) < 1e-8);
    free(v);
    free(remap);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_halfedges_against_brute_force),
        cmocka_unit_test(test_weld_exact_against_brute_force),
        cmocka_unit_test(test_weld_tolerance_clusters),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
