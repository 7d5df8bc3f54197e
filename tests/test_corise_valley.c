/* Tests of corise/valley: Eq. 1 concavity of chains (x-monotone, an overhang measured by shortest
 * paths, a self-intersecting projection), and bridges/valleys of closed height-field boxes
 * (a convex box; a box with a V-shaped trench of known depth). */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "corise/valley.h"
#include "corise_meshes.h"

#define CLOSE(x, y) assert_true(fabs((x) - (y)) <= 1e-12 * (1.0 + fabs(y)))

/* A V in the plane through the x axis tilted by 30 degrees: depth 1.5 at the middle. */
static void test_monotone_chain(void **state) {
    (void)state;
    double c30 = sqrt(3.0) / 2, s30 = 0.5;
    double v[] = {1, 2, 3, 2, 2, 3, 3, 2 + 1.5 * c30, 3 + 1.5 * s30, 4, 2 + 0.5 * c30, 3 + 0.5 * s30, 5, 2, 3};
    uint32_t chain[] = {0, 1, 2, 3, 4};
    double conc[5], max;
    size_t arg;
    acd_corise_conc_kind kind;
    acd_error err;
    assert_int_equal(acd_corise_chain_concavity(v, chain, 5, conc, &max, &arg, &kind, &err), ACD_OK);
    assert_int_equal(kind, ACD_CORISE_CONC_MONOTONE);
    CLOSE(max, 1.5);
    assert_int_equal(arg, 2);
    CLOSE(conc[1], 0.0 + 0.0 * 1.0); /* (2,2,3) lies on the bridge */
    CLOSE(conc[3], 0.5);
    assert_true(conc[0] == 0 && conc[4] == 0);
    /* the same chain read backwards: same values */
    uint32_t rev[] = {4, 3, 2, 1, 0};
    assert_int_equal(acd_corise_chain_concavity(v, rev, 5, conc, &max, &arg, &kind, &err), ACD_OK);
    CLOSE(max, 1.5);
    assert_int_equal(arg, 2);
    /* two vertices: trivial */
    assert_int_equal(acd_corise_chain_concavity(v, chain, 2, conc, &max, &arg, &kind, &err), ACD_OK);
    assert_int_equal(kind, ACD_CORISE_CONC_TRIVIAL);
    assert_true(max == 0 && conc[0] == 0 && conc[1] == 0);
}

/* An overhang (a shelf from the right wall): polygon (0,0) (0,4) (4,4) (4,2.5) (1,2.5) (1,2) (4,2)
 * (4,0), in the plane z = 0 with the bridge (0,0)-(4,0), so Eq. 1 is the identity. By hand:
 * (0,4): 4 (straight down the wall); (4,4): hidden by the shelf, around its tip (1,2.5):
 * sqrt(3^2 + 1.5^2) + 2.5; (4,2.5): 3 + 2.5; (1,2.5): 2.5; (1,2): 2; (4,2): 2. */
static void test_overhang_shortest_paths(void **state) {
    (void)state;
    double v[] = {0, 0, 0, 0, 4, 0, 4, 4, 0, 4, 2.5, 0, 1, 2.5, 0, 1, 2, 0, 4, 2, 0, 4, 0, 0};
    uint32_t chain[] = {0, 1, 2, 3, 4, 5, 6, 7};
    double conc[8], max;
    size_t arg;
    acd_corise_conc_kind kind;
    acd_error err;
    assert_int_equal(acd_corise_chain_concavity(v, chain, 8, conc, &max, &arg, &kind, &err), ACD_OK);
    assert_int_equal(kind, ACD_CORISE_CONC_SP);
    double want[8] = {0, 4, sqrt(11.25) + 2.5, 5.5, 2.5, 2, 2, 0};
    for (int t = 0; t < 8; t++) {
        if (fabs(conc[t] - want[t]) > 1e-12) {
            print_message("vertex %d: concavity %.17g, expected %.17g\n", t, conc[t], want[t]);
            fail();
        }
    }
    CLOSE(max, sqrt(11.25) + 2.5);
    assert_int_equal(arg, 2);
}

/* A projection that crosses itself falls back to the vertical drop y. */
static void test_self_intersecting_fallback(void **state) {
    (void)state;
    double v[] = {0, 0, 0, 3, 2, 0, 1, 2, 0, 1, 0.5, 0, 3.5, 2.5, 0, 4, 0, 0};
    uint32_t chain[] = {0, 1, 2, 3, 4, 5};
    double conc[6], max;
    size_t arg;
    acd_corise_conc_kind kind;
    acd_error err;
    assert_int_equal(acd_corise_chain_concavity(v, chain, 6, conc, &max, &arg, &kind, &err), ACD_OK);
    assert_int_equal(kind, ACD_CORISE_CONC_FALLBACK);
    double want[6] = {0, 2, 2, 0.5, 2.5, 0};
    for (int t = 0; t < 6; t++) CLOSE(conc[t], want[t]);
    CLOSE(max, 2.5);
}

typedef struct trench {
    double h, depth, xc, halfwidth;
} trench;

static double trench_top(double x, double y, const void *u) {
    (void)y;
    const trench *t = u;
    double d = fabs(x - t->xc) / t->halfwidth;
    return t->h - (d < 1 ? t->depth * (1 - d) : 0);
}

/* Every valley is a mesh path from a to b whose length is the sum of its edges. */
static void check_valleys(const acd_mesh *m, const acd_edge_graph *g, const acd_corise_bridges *b) {
    for (size_t i = 0; i < b->nbridges; i++) {
        const acd_corise_bridge *br = &b->bridge[i];
        assert_true(br->a < br->b);
        if (i) assert_true(br->a > b->bridge[i - 1].a || (br->a == b->bridge[i - 1].a && br->b > b->bridge[i - 1].b));
        const uint32_t *p = b->path + br->first;
        assert_true(br->count >= 2);
        assert_int_equal(p[0], br->a);
        assert_int_equal(p[br->count - 1], br->b);
        double len = 0;
        for (size_t k = 0; k + 1 < br->count; k++) {
            uint32_t e = acd_edge_graph_find(g, p[k], p[k + 1]);
            assert_true(e != ACD_NO_VERTEX);
            len += g->length[e];
        }
        assert_true(fabs(len - br->length) <= 1e-12 * len);
        const double *pa = m->vertices + 3 * br->a, *pb = m->vertices + 3 * br->b;
        double d = sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) +
                        (pa[2] - pb[2]) * (pa[2] - pb[2]));
        assert_true(br->length >= d * (1 - 1e-12));
        assert_true(br->concavity >= 0 && br->deepest < br->count);
    }
}

/* Number of coordinates in which the bridge's ends differ (1: a box edge; 2: a face diagonal). */
static int differing(const acd_mesh *m, const acd_corise_bridge *br, double *side) {
    int k = 0;
    double s[2] = {0, 0};
    for (int c = 0; c < 3; c++) {
        double d = fabs(m->vertices[3 * br->a + c] - m->vertices[3 * br->b + c]);
        if (d > 0) {
            if (k < 2) s[k] = d;
            k++;
        }
    }
    if (k == 2) *side = s[0] * s[1] / sqrt(s[0] * s[0] + s[1] * s[1]);
    return k;
}

/* Convex box 1.5 x 1 x 1 on a grid of 0.25 cells: the 18 bridges of the triangulated hull
 * (12 edges, 6 face diagonals). Valleys along edges are straight (C = 0). A face diagonal's valley
 * is a staircase in that flat face; among the many equal-length staircases the tie-break keeps the
 * one hugging the bridge, so C stays below one cell diagonal (without it, up to the corner's
 * distance ab/sqrt(a^2+b^2) = 0.83 on the 1.5 x 1 faces: docs/corise.md). */
static void test_convex_box(void **state) {
    (void)state;
    trench flat = {1.0, 0.0, 0.5, 0.1};
    acd_mesh m;
    cm_heightfield_box(&m, 6, 4, 4, 1.5, 1.0, trench_top, &flat);
    acd_edge_graph g;
    acd_corise_bridges b;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &g, &err), ACD_OK);
    assert_int_equal(acd_corise_bridges_compute(&m, &g, &b, &err), ACD_OK);
    assert_int_equal(b.hull_dim, 3);
    assert_int_equal(b.nhull, 8); /* the box's corners only */
    assert_int_equal(b.nbridges, 18);
    assert_int_equal(b.unreachable, 0);
    assert_int_equal(b.fallbacks, 0);
    check_valleys(&m, &g, &b);
    int edges = 0, diagonals = 0;
    for (size_t i = 0; i < b.nbridges; i++) {
        double bound = 0;
        int k = differing(&m, &b.bridge[i], &bound);
        if (k == 1) {
            edges++;
            assert_true(b.bridge[i].concavity <= 1e-12);
        } else {
            assert_int_equal(k, 2);
            diagonals++;
            assert_true(b.bridge[i].concavity <= bound * (1 + 1e-12));
            assert_true(b.bridge[i].concavity < 0.25 * sqrt(2.0));
        }
    }
    assert_int_equal(edges, 12);
    assert_int_equal(diagonals, 6);
    acd_corise_bridges_free(&b);
    acd_edge_graph_free(&g);
    acd_mesh_free(&m);
}

/* Box 2 x 1 x 1 with a V trench along y at x = 1 (depth 0.6, half-width 0.25): the bridges over
 * the two top edges span the trench; their valleys run along the top boundary rows, down and up
 * the trench, with concavity exactly the depth at the trench bottom. */
static void test_trench_box(void **state) {
    (void)state;
    trench tr = {1.0, 0.6, 1.0, 0.25};
    acd_mesh m;
    cm_heightfield_box(&m, 16, 8, 8, 2.0, 1.0, trench_top, &tr);
    acd_edge_graph g;
    acd_corise_bridges b;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &g, &err), ACD_OK);
    assert_int_equal(acd_corise_bridges_compute(&m, &g, &b, &err), ACD_OK);
    assert_int_equal(b.nhull, 8);
    check_valleys(&m, &g, &b);
    /* top front edge: corner (0,0,1) = vertex 0 to (2,0,1) = vertex 16; back: 136 to 152 */
    int found = 0;
    for (size_t i = 0; i < b.nbridges; i++) {
        const acd_corise_bridge *br = &b.bridge[i];
        if ((br->a == 0 && br->b == 16) || (br->a == 136 && br->b == 152)) {
            found++;
            assert_int_equal(br->kind, ACD_CORISE_CONC_MONOTONE);
            CLOSE(br->concavity, 0.6);
            CLOSE(br->length, 2.0 - 0.5 + 2 * sqrt(0.25 * 0.25 + 0.6 * 0.6));
            assert_int_equal(b.path[br->first + br->deepest], br->a + 8); /* the trench bottom */
            continue;
        }
        double bound = 0;
        int k = differing(&m, br, &bound);
        int top = m.vertices[3 * br->a + 2] > 0.5 && m.vertices[3 * br->b + 2] > 0.5;
        if (k == 1 && !top) assert_true(br->concavity <= 1e-12); /* vertical and bottom edges */
    }
    assert_int_equal(found, 2);
    acd_corise_bridges_free(&b);
    acd_edge_graph_free(&g);
    acd_mesh_free(&m);
}

/* The hull-depth clamp (not in the paper): on the convex box every valley lies on the hull's
 * surface, so every concavity is 0; on the trench box the valleys along the top edges run on the
 * front/back hull faces (0), while the top diagonal crosses the trench bottom (1, 0.5, 0.4) at
 * depth min(0.6 below the top, 0.4 above the bottom, 0.5 from the front and back) = 0.4. */
static void test_hull_depth_clamp(void **state) {
    (void)state;
    trench flat = {1.0, 0.0, 0.5, 0.1}, tr = {1.0, 0.6, 1.0, 0.25};
    acd_mesh m;
    acd_edge_graph g;
    acd_corise_bridges b;
    acd_error err;
    cm_heightfield_box(&m, 6, 4, 4, 1.5, 1.0, trench_top, &flat);
    assert_int_equal(acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &g, &err), ACD_OK);
    assert_int_equal(acd_corise_bridges_compute_ex(&m, &g, 1, &b, &err), ACD_OK);
    assert_int_equal(b.nbridges, 18);
    for (size_t i = 0; i < b.nbridges; i++) assert_true(b.bridge[i].concavity <= 1e-12);
    acd_corise_bridges_free(&b);
    acd_edge_graph_free(&g);
    acd_mesh_free(&m);

    cm_heightfield_box(&m, 16, 8, 8, 2.0, 1.0, trench_top, &tr);
    assert_int_equal(acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &g, &err), ACD_OK);
    assert_int_equal(acd_corise_bridges_compute_ex(&m, &g, 1, &b, &err), ACD_OK);
    double cmax = 0;
    for (size_t i = 0; i < b.nbridges; i++) {
        const acd_corise_bridge *br = &b.bridge[i];
        if ((br->a == 0 && br->b == 16) || (br->a == 136 && br->b == 152)) assert_true(br->concavity <= 1e-12);
        if (br->concavity > cmax) cmax = br->concavity;
    }
    assert_true(fabs(cmax - 0.4) < 1e-12);
    acd_corise_bridges_free(&b);
    acd_edge_graph_free(&g);
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_monotone_chain),
        cmocka_unit_test(test_overhang_shortest_paths),
        cmocka_unit_test(test_self_intersecting_fallback),
        cmocka_unit_test(test_convex_box),
        cmocka_unit_test(test_trench_box),
        cmocka_unit_test(test_hull_depth_clamp),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
