/* Unit tests of the acd2d modules: hull2d, ring tests (notch, cone, wedge), cut choice (Eqn 4.3
 * and s_c), ray shooting (vertex and edge hits), split, principal-axis extremes and the hole
 * merge order (Fig. 23 dependency order with the Eqn 4.2 ranking); far from the origin: inserting a
 * shared cut end into an edge, and the refusal of coordinates that cannot resolve a feature. */
#include "testutil.h"

#include <math.h>
#include <string.h>

#include "acd/acd2d.h"
#include "acd2/cut.h"
#include "acd2/holes.h"
#include "acd2/resolution.h"
#include "acd2/ring.h"
#include "geom2/hull2d.h"

static void ring_of(acd2_ring *r, const acd_vec2 *p, size_t n) {
    memset(r, 0, sizeof *r);
    for (size_t i = 0; i < n; i++) assert_int_equal(acd2_ring_push(r, p[i], (int64_t)i), 0);
}

static void test_hull(void **state) {
    (void)state;
    /* square with points on its edges, a repeated corner and an inner point */
    const acd_vec2 p[] = {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}, {1, 1}, {2, 2}};
    size_t out[11], scr[11];
    size_t nh = acd_hull2d_indices(p, 10, out, scr);
    assert_int_equal(nh, 4);
    assert_int_equal(out[0], 0);
    assert_int_equal(out[1], 2);
    assert_int_equal(out[2], 4); /* the first of the two copies */
    assert_int_equal(out[3], 6);
    const acd_vec2 line[] = {{0, 0}, {1, 1}, {2, 2}, {3, 3}};
    assert_int_equal(acd_hull2d_indices(line, 4, out, scr), 2);
}

static const acd_vec2 L[] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};

static void test_ring_tests(void **state) {
    (void)state;
    assert_true(acd2_is_notch(L[2], L[3], L[4], 0));
    assert_false(acd2_is_notch(L[0], L[1], L[2], 0));
    /* tolerance: a nearly straight vertex is not a notch with 1e-5, is one exactly */
    acd_vec2 a = {0, 0}, b = {1, 1e-7}, c = {2, 0};
    assert_true(acd2_is_notch(a, b, c, 0));
    assert_false(acd2_is_notch(a, b, c, 1e-5));
    /* spec §5.3: direction towards (0,0) from the L's notch is inside the resolving cone */
    assert_true(acd2_in_resolving_cone(L[2], L[3], L[4], L[0]));
    assert_false(acd2_in_resolving_cone(L[2], L[3], L[4], L[1]));
    assert_false(acd2_in_resolving_cone(L[2], L[3], L[4], L[5]));
    /* wedge at the reflex vertex contains (0,0), not (1.5,1.5) */
    assert_true(acd2_in_wedge(L[2], L[3], L[4], L[0]));
    acd_vec2 out = {1.5, 1.5};
    assert_false(acd2_in_wedge(L[2], L[3], L[4], out));
}

static void test_shoot_and_split(void **state) {
    (void)state;
    acd2_ring r;
    ring_of(&r, L, 6);
    acd2_hit h;
    assert_int_equal(acd2_shoot(&r, 3, (acd_vec2){-1, -1}, &h), 0);
    assert_true(h.is_vertex && h.j == 0);
    assert_int_equal(acd2_shoot(&r, 3, (acd_vec2){-1, -3}, &h), 0);
    assert_false(h.is_vertex);
    assert_int_equal(h.j, 0);
    assert_true(h.z.x == 0.5 && h.z.y == 0);
    /* split at the vertex hit: two unit-and-a-half pieces */
    assert_int_equal(acd2_shoot(&r, 3, (acd_vec2){-1, -1}, &h), 0);
    acd2_ring a = {0}, b = {0};
    assert_int_equal(acd2_split(&r, 3, &h, 100, &a, &b), 0);
    assert_int_equal(a.n, 4);
    assert_int_equal(b.n, 4);
    assert_true(fabs(acd2_ring_area2(a.p, a.n) - 3) < 1e-15 && fabs(acd2_ring_area2(b.p, b.n) - 3) < 1e-15);
    /* split at the new point: ids of the new point in both pieces */
    assert_int_equal(acd2_shoot(&r, 3, (acd_vec2){-1, -3}, &h), 0);
    assert_int_equal(acd2_split(&r, 3, &h, 100, &a, &b), 0);
    assert_int_equal(a.id[a.n - 1], 100);
    assert_int_equal(b.id[0], 100);
    assert_true(fabs(acd2_ring_area2(a.p, a.n) + acd2_ring_area2(b.p, b.n) - 6) < 1e-15);
    acd2_ring_free(&a);
    acd2_ring_free(&b);
    acd2_ring_free(&r);
}

static void test_cut_choice(void **state) {
    (void)state;
    /* a square with a V notch from the top: both bottom corners are in the cone at the same
     * distance; s_c decides by their concavity (Eqn 4.3), ties go to the smaller id */
    const acd_vec2 v[] = {{-3, -3}, {3, -3}, {3, 1}, {0, 0}, {-3, 1}};
    acd2_ring r;
    ring_of(&r, v, 5);
    double conc[5] = {0, 0, 0, 0, 0};
    acd2_cut_opts o = {0.1, 1.0, ACD2D_CUT_RAY, 100, 1e-12};
    acd2_hit h;
    assert_int_equal(acd2_choose_cut(&r, conc, 3, &o, &h), 0);
    assert_true(h.is_vertex && h.j == 0);
    conc[1] = 10; /* a concave candidate wins with s_c = 0.1 */
    assert_int_equal(acd2_choose_cut(&r, conc, 3, &o, &h), 0);
    assert_true(h.is_vertex && h.j == 1);
    o.sc = 0; /* s_c = 0: shortest, then smaller id */
    assert_int_equal(acd2_choose_cut(&r, conc, 3, &o, &h), 0);
    assert_true(h.is_vertex && h.j == 0);
    o.sc = 0.1;
    o.sd = 1000; /* s_d rescales every score: same winner (spec §5.2) */
    assert_int_equal(acd2_choose_cut(&r, conc, 3, &o, &h), 0);
    assert_true(h.is_vertex && h.j == 1);
    o.mode = ACD2D_CUT_DIAGONAL;
    assert_int_equal(acd2_choose_cut(&r, conc, 3, &o, &h), 0);
    assert_true(h.is_vertex && h.j == 1);
    acd2_ring_free(&r);
    /* a sharp notch (a thin slit from the top) facing the middle of a long edge: no vertex in
     * its narrow cone, so the bisector ray ends at a new point on the bottom edge (both modes) */
    const acd_vec2 s[] = {{-10, -1}, {10, -1}, {10, 1}, {0.1, 1}, {0, 0}, {-0.1, 1}, {-10, 1}};
    ring_of(&r, s, 7);
    double c7[7] = {0};
    assert_int_equal(acd2_choose_cut(&r, c7, 4, &o, &h), 0);
    assert_false(h.is_vertex);
    o.mode = ACD2D_CUT_RAY;
    assert_int_equal(acd2_choose_cut(&r, c7, 4, &o, &h), 0);
    assert_false(h.is_vertex);
    assert_int_equal(h.j, 0);
    assert_true(fabs(h.z.x) < 1e-12 && h.z.y == -1);
    acd2_ring_free(&r);
}

static void test_pa_extremes(void **state) {
    (void)state;
    acd_vec2 e[64];
    for (int i = 0; i < 64; i++) {
        double t = 2 * 3.14159265358979323846 * i / 64;
        e[i].x = 3 + 5 * cos(t + 0.01);
        e[i].y = -2 + 2 * sin(t + 0.01);
    }
    size_t lo, hi;
    acd2_pa_extremes(e, 64, &lo, &hi);
    assert_true(e[lo].x < -1.9 && e[hi].x > 7.9);
}

static acd_vec2 *diamond(acd_vec2 *d, double cx, double cy, double w, double h) {
    /* clockwise: left, top, right, bottom */
    d[0] = (acd_vec2){cx - w, cy};
    d[1] = (acd_vec2){cx, cy + h};
    d[2] = (acd_vec2){cx + w, cy};
    d[3] = (acd_vec2){cx, cy - h};
    return d;
}

static void test_hole_order(void **state) {
    (void)state;
    /* three diamonds on a line: A near the left wall, C nearer the right wall, B between them
     * (both its tips see only A or C): B depends on a neighbour, so C (largest Eqn 4.2 value)
     * goes first, then B (through C), then A. */
    const acd_vec2 outer[] = {{0, 0}, {30, 0}, {30, 10}, {0, 10}};
    acd_vec2 A[4], B[4], C[4];
    const acd_vec2 *rings[4] = {outer, diamond(A, 4, 5, 3, 1), diamond(B, 12, 5, 3, 1), diamond(C, 20, 5, 3, 1)};
    size_t sizes[4] = {4, 4, 4, 4};
    acd_polygon p;
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(&p, rings, sizes, 4, &err), ACD_OK);
    acd2d_params prm = acd2d_default_params();
    prm.tau = 1000;
    acd2d_result res;
    assert_int_equal(acd2d_decompose(&p, &prm, &res, &err), ACD_OK);
    assert_true(res.nodes[0].is_hole_merge && res.nodes[1].is_hole_merge && res.nodes[2].is_hole_merge);
    assert_true(res.nodes[0].cut[0].x == 23 && res.nodes[0].cut[1].x == 30);
    assert_true(res.nodes[1].cut[0].x == 15 && res.nodes[1].cut[1].x == 17);
    assert_true(res.nodes[2].cut[0].x == 1 && res.nodes[2].cut[1].x == 0);
    /* the nodes hold the polygon with the holes still to merge */
    assert_int_equal(res.nodes[0].polygon.nrings, 4);
    assert_int_equal(res.nodes[1].polygon.nrings, 3);
    assert_int_equal(res.nodes[3].polygon.nrings, 1);
    assert_false(res.nodes[3].acceptable); /* slits */
    for (size_t i = 0; i < res.ncomponents; i++) assert_true(res.nodes[res.components[i].node].acceptable);
    assert_int_equal(res.ncuts >= 4, 1);
    acd2d_result_free(&res);
    acd_polygon_free(&p);
}

/* acd2_ring_insert_on_edge (shared cut ends): inserted between the edge's ends, also on the
 * closing edge, not when the edge is absent or reversed; the bridge cache is reset. */
static void test_insert_on_edge(void **state) {
    (void)state;
    const acd_vec2 p[] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
    acd2_ring r;
    ring_of(&r, p, 4);
    for (size_t i = 0; i < r.n; i++) r.be[i] = 7;
    acd_vec2 z = {1, 0.25};
    assert_int_equal(acd2_ring_insert_on_edge(&r, p[1], p[0], z, 99), 0); /* reversed: absent */
    assert_int_equal(acd2_ring_insert_on_edge(&r, p[0], p[1], z, 99), 1);
    assert_int_equal(r.n, 5);
    assert_true(r.p[1].x == 1 && r.p[1].y == 0.25 && r.id[1] == 99 && r.c[1] == 0);
    assert_true(r.p[2].x == 2 && r.p[2].y == 0 && r.id[2] == 1);
    for (size_t i = 0; i < r.n; i++) assert_true(r.be[i] == -1);
    acd_vec2 w = {-0.25, 1};
    assert_int_equal(acd2_ring_insert_on_edge(&r, p[3], p[0], w, 100), 1); /* closing edge: at the end */
    assert_int_equal(r.n, 6);
    assert_true(r.p[5].x == -0.25 && r.id[5] == 100 && r.p[0].x == 0 && r.p[0].y == 0);
    assert_true(acd2_line_offset(p[0], p[1], z) == 0.25);
    acd2_ring_free(&r);
}

/* acd2_check_resolution: near the origin nothing is refused, however fine; far out a feature
 * below 64 units of the coordinates' rounding is, naming it (short edge, vertex near an edge). */
static void test_resolution(void **state) {
    (void)state;
    acd_vec2 notch[] = {{0, 0}, {1, 0}, {1, 1}, {0.6, 1}, {0.5, 0.5}, {0.4, 1}, {0, 1}};
    const acd_vec2 *rings[1] = {notch};
    size_t sizes[1] = {7};
    acd_polygon p;
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(&p, rings, sizes, 1, &err), ACD_OK);
    assert_int_equal(acd2_check_resolution(&p, &err), ACD_OK);
    for (size_t i = 0; i < 7; i++) { p.points[i].x += 1e12; p.points[i].y += 1e12; } /* doubles 1.2e-4 apart */
    assert_int_equal(acd2_check_resolution(&p, &err), ACD_OK);
    for (size_t i = 0; i < 7; i++) { p.points[i].x += 1e14; p.points[i].y += 1e14; } /* 0.016 apart: 64 DBL_EPSILON M = 1.4 */
    assert_int_equal(acd2_check_resolution(&p, &err), ACD_ERR_DEGENERATE);
    assert_non_null(strstr(err.message, "cannot resolve a feature"));
    acd_polygon_free(&p);
    /* a vertex 1e-6 from an edge not its own, at 1e9: refused (64 DBL_EPSILON M = 1.4e-5) */
    acd_vec2 thin[] = {{0, 0}, {1, 0}, {1, 1}, {0.5, 1e-6}, {0, 1}};
    rings[0] = thin;
    sizes[0] = 5;
    assert_int_equal(acd_polygon_from_rings(&p, rings, sizes, 1, &err), ACD_OK);
    for (size_t i = 0; i < 5; i++) { p.points[i].x += 1e9; p.points[i].y += 1e9; }
    assert_int_equal(acd2_check_resolution(&p, &err), ACD_ERR_DEGENERATE);
    assert_non_null(strstr(err.message, "vertex 3 of chain 0"));
    assert_non_null(strstr(err.message, "from edge 0-1 of chain 0"));
    acd_polygon_free(&p);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_insert_on_edge), cmocka_unit_test(test_resolution),
        cmocka_unit_test(test_hull),        cmocka_unit_test(test_ring_tests),  cmocka_unit_test(test_shoot_and_split),
        cmocka_unit_test(test_cut_choice),  cmocka_unit_test(test_pa_extremes), cmocka_unit_test(test_hole_order),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
