/* Tests of corise/regions (Eqs. 4-7) and corise/cut (sequential binary cuts, Eq. 8) on the
 * trench box: two ridges, must-link regions on their own sides of the trench, and a cut that
 * separates the two halves inside the trench. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "corise/cut.h"
#include "corise/regions.h"
#include "corise_meshes.h"

typedef struct trench {
    double h, depth, xc, halfwidth;
} trench;

static double trench_top(double x, double y, const void *u) {
    (void)y;
    const trench *t = u;
    double d = fabs(x - t->xc) / t->halfwidth;
    return t->h - (d < 1 ? t->depth * (1 - d) : 0);
}

static double centroid_x(const acd_mesh *m, size_t f) {
    const uint32_t *T = m->triangles + 3 * f;
    return (m->vertices[3 * T[0]] + m->vertices[3 * T[1]] + m->vertices[3 * T[2]]) / 3.0;
}

static void test_trench_regions_and_cut(void **state) {
    (void)state;
    trench tr = {1.0, 0.6, 1.0, 0.25};
    acd_mesh m;
    cm_heightfield_box(&m, 16, 8, 8, 2.0, 1.0, trench_top, &tr);
    acd_edge_graph g;
    acd_corise_bridges b;
    acd_corise_ridges r;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &g, &err), ACD_OK);
    assert_int_equal(acd_corise_bridges_compute(&m, &g, &b, &err), ACD_OK);
    assert_int_equal(acd_corise_ridges_compute(&b, 0.3, &r, &err), ACD_OK);
    assert_int_equal(r.nridges, 2);
    size_t nf = m.ntriangles, nsub = 0;
    uint32_t *ml = malloc(nf * sizeof *ml), *part = malloc(nf * sizeof *part);
    assert_int_equal(acd_corise_regions(&m, &g, &b, &r, 0.3, ml, &nsub, &err), ACD_OK);
    assert_true(nsub >= 6);
    size_t count[2] = {0, 0}, fuzzy = 0;
    for (size_t f = 0; f < nf; f++) {
        if (ml[f] == ACD_CORISE_FUZZY) {
            fuzzy++;
            continue;
        }
        assert_true(ml[f] < 2);
        count[ml[f]]++;
        double x = centroid_x(&m, f);
        /* ridge 0 = corners at x = 0, ridge 1 = corners at x = 2: must-link stays on its side */
        if (ml[f] == 0) assert_true(x < 1.0);
        if (ml[f] == 1) assert_true(x > 1.0);
    }
    assert_true(count[0] > 0 && count[1] > 0 && fuzzy > 0);
    size_t nparts = 0;
    assert_int_equal(acd_corise_cut(&m, &b, &r, ml, NULL, part, &nparts, &err), ACD_OK);
    assert_int_equal(nparts, 2);
    uint32_t left = part[0]; /* facet 0 is on the top at x in [0, 0.125] */
    size_t n_left = 0;
    for (size_t f = 0; f < nf; f++) {
        assert_true(part[f] < 2);
        double x = centroid_x(&m, f);
        if (x < 0.75) assert_int_equal(part[f], left);
        if (x > 1.25) assert_int_equal(part[f], 1 - left);
        if (ml[f] != ACD_CORISE_FUZZY) assert_int_equal(part[f], ml[f] == 0 ? left : 1 - left);
        n_left += part[f] == left;
    }
    /* the cut runs along the trench bottom x = 1, the cheapest (concave) loop around the box:
     * every facet lies entirely on one side of x = 1 */
    for (size_t f = 0; f < nf; f++) {
        const uint32_t *T = m.triangles + 3 * f;
        for (int k = 0; k < 3; k++) {
            double x = m.vertices[3 * T[k]];
            if (part[f] == left) assert_true(x <= 1.0 + 1e-12);
            else assert_true(x >= 1.0 - 1e-12);
        }
    }
    assert_int_equal(n_left, nf / 2); /* the box is symmetric about x = 1 */
    /* bad parameters */
    acd_corise_cut_params p = acd_corise_cut_default_params();
    p.alpha = 1.5;
    assert_int_equal(acd_corise_cut(&m, &b, &r, ml, &p, part, &nparts, &err), ACD_ERR_INVALID_ARGUMENT);
    free(ml);
    free(part);
    acd_corise_ridges_free(&r);
    acd_corise_bridges_free(&b);
    acd_edge_graph_free(&g);
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_trench_regions_and_cut)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
