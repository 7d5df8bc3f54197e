/* Tests of SP-concavity (acd2/concavity_sp) against a Dijkstra oracle on the visibility graph
 * of small random pockets (spec acd2d.md §3.2 test oracle), plus known values and the
 * hazard test. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>

#include "acd/acd2d.h"
#include "acd2/concavity_sl.h"
#include "acd2/concavity_sp.h"
#include "acd2/hybrid.h"
#include "acd2/ring.h"
#include "core/predicates.h"
#include "core/rng.h"

/* open segment (p, q) stays inside the simple polygon Q (counterclockwise, m vertices): it crosses
 * no edge properly, passes through no vertex, and its midpoint is inside */
static int inside_point(const acd_vec2 *Q, size_t m, acd_vec2 t) {
    int in = 0;
    for (size_t i = 0, j = m - 1; i < m; j = i++) {
        if ((Q[i].y > t.y) != (Q[j].y > t.y)) {
            double x = Q[j].x + (t.y - Q[j].y) * (Q[i].x - Q[j].x) / (Q[i].y - Q[j].y);
            if (t.x < x) in = !in;
        }
    }
    return in;
}

static int seg_inside(const acd_vec2 *Q, size_t m, acd_vec2 p, acd_vec2 q) {
    const double P[2] = {p.x, p.y}, R[2] = {q.x, q.y};
    for (size_t i = 0; i < m; i++) { /* a boundary edge */
        acd_vec2 a = Q[i], b = Q[(i + 1) % m];
        if ((acd2_same(a, p) && acd2_same(b, q)) || (acd2_same(a, q) && acd2_same(b, p))) return 1;
    }
    for (size_t i = 0; i < m; i++) {
        const double A[2] = {Q[i].x, Q[i].y}, B[2] = {Q[(i + 1) % m].x, Q[(i + 1) % m].y};
        if (acd_segments_relation(P, R, A, B) == ACD_SEG_PROPER) return 0;
        if (!acd2_same(Q[i], p) && !acd2_same(Q[i], q) && acd_point_on_segment(A, P, R)) return 0;
    }
    acd_vec2 mid = {(p.x + q.x) / 2, (p.y + q.y) / 2};
    /* a segment along the boundary counts as inside (paths may touch it) */
    for (size_t i = 0; i < m; i++) {
        const double A[2] = {Q[i].x, Q[i].y}, B[2] = {Q[(i + 1) % m].x, Q[(i + 1) % m].y}, M[2] = {mid.x, mid.y};
        if (acd_point_on_segment(M, A, B)) return 1;
    }
    return inside_point(Q, m, mid);
}

/* oracle: pocket chain c[0..k] (c[0] = beta-, c[k] = beta+), Q = reversed chain */
static void oracle(const acd_vec2 *c, size_t k, double *out) {
    size_t m = k + 1;
    acd_vec2 *Q = malloc(m * sizeof *Q);
    for (size_t i = 0; i < m; i++) Q[i] = c[k - i];
    acd_vec2 Bm = c[0], Bp = c[k];
    double dx = Bp.x - Bm.x, dy = Bp.y - Bm.y, len = hypot(dx, dy);
    double *d = malloc(m * sizeof *d);
    int *done = calloc(m, sizeof *done);
    for (size_t v = 0; v < m; v++) {
        d[v] = INFINITY;
        acd_vec2 p = c[v];
        if (v == 0 || v == k) { d[v] = 0; continue; }
        /* perpendicular drop */
        double s = ((p.x - Bm.x) * dx + (p.y - Bm.y) * dy) / (len * len);
        if (s >= 0 && s <= 1) {
            acd_vec2 f = {Bm.x + s * dx, Bm.y + s * dy};
            if (seg_inside(Q, m, p, f)) d[v] = fabs((p.x - Bm.x) * dy - (p.y - Bm.y) * dx) / len;
        }
        if (seg_inside(Q, m, p, Bm)) d[v] = fmin(d[v], hypot(p.x - Bm.x, p.y - Bm.y));
        if (seg_inside(Q, m, p, Bp)) d[v] = fmin(d[v], hypot(p.x - Bp.x, p.y - Bp.y));
    }
    for (size_t it = 0; it < m; it++) {
        size_t u = SIZE_MAX;
        for (size_t v = 0; v < m; v++)
            if (!done[v] && (u == SIZE_MAX || d[v] < d[u])) u = v;
        done[u] = 1;
        for (size_t v = 0; v < m; v++)
            if (!done[v] && seg_inside(Q, m, c[u], c[v])) d[v] = fmin(d[v], d[u] + hypot(c[u].x - c[v].x, c[u].y - c[v].y));
    }
    for (size_t v = 0; v <= k; v++) out[v] = d[v];
    free(Q);
    free(d);
    free(done);
}

/* random pocket: the chain from (0,0) to (10,0) winds clockwise around (5,5) through angles
 * 225 .. -45 degrees with random radii (star-shaped, so simple with the bridge); the pocket is
 * on the chain's right, above the bridge */
static void random_pocket(acd_rng *rng, acd_vec2 *c, size_t k) {
    const double pi = 3.14159265358979323846;
    c[0].x = 0; c[0].y = 0;
    for (size_t i = 1; i < k; i++) {
        double a = (225.0 - 270.0 * (double)i / (double)k) * pi / 180.0;
        double r = 0.5 + 4.0 * acd_rng_uniform(rng);
        c[i].x = 5 + r * cos(a);
        c[i].y = 5 + r * sin(a);
    }
    c[k].x = 10; c[k].y = 0;
}

static void test_sp_oracle(void **state) {
    (void)state;
    acd_rng rng;
    acd_rng_seed(&rng, 12345);
    acd2_sp_work w = {0};
    for (int trial = 0; trial < 200; trial++) {
        size_t k = 4 + acd_rng_below(&rng, 14);
        acd_vec2 c[32];
        random_pocket(&rng, c, k);
        acd_vec2 ring[40];
        for (size_t i = 0; i <= k; i++) ring[i] = c[i];
        ring[k + 1].x = 5; ring[k + 1].y = -50; /* closes the ring; not part of the pocket */
        size_t n = k + 2;
        double conc[40] = {0}, want[40];
        acd_status st = acd2_sp_pocket(ring, n, 0, k, conc, &w);
        assert_int_equal(st, ACD_OK);
        oracle(c, k, want);
        for (size_t i = 1; i < k; i++) {
            if (fabs(conc[i] - want[i]) > 1e-9 * (1 + want[i])) {
                print_message("trial %d k %zu vertex %zu: sp %.17g oracle %.17g\n", trial, k, i, conc[i], want[i]);
                for (size_t q = 0; q <= k; q++) print_message("  %zu: %.6f %.6f sp %.6f or %.6f\n", q, c[q].x, c[q].y, conc[q], want[q]);
                fail();
            }
        }
    }
    acd2_sp_work_free(&w);
}

static void test_known_values(void **state) {
    (void)state;
    /* V pocket: SP = SL = 5 */
    const acd_vec2 v[] = {{0, 0}, {10, 0}, {10, 10}, {5, 5}, {0, 10}};
    size_t wit;
    assert_true(fabs(acd2d_concavity(v, 5, ACD2D_MEASURE_SP, 0, &wit) - 5) < 1e-12);
    /* W pocket: the two side notches drop straight to the bridge (6), the middle one is 4 */
    const acd_vec2 u[] = {{0, 0}, {10, 0}, {10, 10}, {7, 4}, {5, 6}, {3, 4}, {0, 10}};
    assert_true(fabs(acd2d_concavity(u, 7, ACD2D_MEASURE_SP, 0, &wit) - 6) < 1e-12);
    /* hooked pocket: the notch (2,7) sits under an overhang (y 7..8.5, x 1..6): SL sees 3, the
     * geodesic goes right to (6,7), up to (6,8.5) and up to the bridge: 4 + 1.5 + 1.5 = 7 */
    const acd_vec2 s[] = {{0, 0}, {10, 0}, {10, 10}, {8, 9}, {8, 3}, {2, 3}, {2, 7}, {6, 7}, {6, 8.5}, {1, 8.5}, {0, 10}};
    double conc[16] = {0}, want[16], sl[16] = {0};
    acd2_sp_work w = {0};
    assert_int_equal(acd2_sp_pocket(s, 11, 2, 10, conc, &w), ACD_OK);
    acd_vec2 c[16];
    for (size_t i = 0; i <= 8; i++) c[i] = s[2 + i];
    oracle(c, 8, want);
    for (size_t i = 1; i < 8; i++) assert_true(fabs(conc[2 + i] - want[i]) < 1e-9 * (1 + want[i]));
    assert_true(fabs(conc[6] - 7) < 1e-12);
    acd2_sl_pocket(s, 11, 2, 10, sl);
    assert_true(fabs(sl[6] - 3) < 1e-12);
    assert_true(acd2_pocket_hazard(s, 11, 2, 10));
    assert_false(acd2_pocket_hazard(v, 5, 2, 4));
    acd2_sp_work_free(&w);
}

/* H1 = SP where the pocket has a hazard edge, SL where it has none; H2 keeps SL when SL exceeds
 * tau, else follows H1 (Algs. 3-4) */
static void test_hybrids(void **state) {
    (void)state;
    const acd_vec2 hook[] = {{0, 0}, {10, 0}, {10, 10}, {8, 9}, {8, 3}, {2, 3}, {2, 7}, {6, 7}, {6, 8.5}, {1, 8.5}, {0, 10}};
    const acd_vec2 v[] = {{0, 0}, {10, 0}, {10, 10}, {7, 4}, {5, 6}, {3, 4}, {0, 10}};
    size_t w;
    double sl = acd2d_concavity(hook, 11, ACD2D_MEASURE_SL, 0, &w), sp = acd2d_concavity(hook, 11, ACD2D_MEASURE_SP, 0, &w);
    assert_true(sp > sl + 1);
    assert_true(acd2d_concavity(hook, 11, ACD2D_MEASURE_H1, 0, &w) == sp);
    assert_true(acd2d_concavity(hook, 11, ACD2D_MEASURE_H2, sl - 0.5, &w) == sl); /* SL > tau: keep SL */
    assert_true(acd2d_concavity(hook, 11, ACD2D_MEASURE_H2, sl + 0.5, &w) == sp); /* SL <= tau, hazard: SP */
    double vsl = acd2d_concavity(v, 7, ACD2D_MEASURE_SL, 0, &w);
    assert_true(acd2d_concavity(v, 7, ACD2D_MEASURE_H1, 0, &w) == vsl); /* no hazard: SL */
    assert_true(acd2d_concavity(v, 7, ACD2D_MEASURE_H2, 100, &w) == vsl);
    assert_true(fabs(vsl - 6) < 1e-12);
}

/* a maze whose pocket touches its bridge at collinear vertices (weakly simple pocket polygon):
 * the pocket is split there and SP follows the corridors (regression: SP used to fall back to SL) */
static void test_maze_pocket(void **state) {
    (void)state;
    char path[1024];
    if (!tu_shared_data(path, sizeof path, "polygons-lien/wierd1.poly")) TU_SKIP("wierd1.poly not found");
    acd_polygon_set set;
    acd_error err;
    assert_int_equal(acd_polygon_set_read_file(&set, path, ACD_POLY_FORMAT_AUTO, NULL, &err), ACD_OK);
    const acd_polygon *p = &set.polygons[0];
    size_t n = acd_polygon_ring_size(p, 0), w;
    double sl = acd2d_concavity(p->points, n, ACD2D_MEASURE_SL, 0, &w);
    double sp = acd2d_concavity(p->points, n, ACD2D_MEASURE_SP, 0, &w);
    print_message("maze: SL %g, SP %g\n", sl, sp);
    assert_true(sl < 10 && sp > 150);
    acd_polygon_set_free(&set);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_known_values), cmocka_unit_test(test_sp_oracle),
                                       cmocka_unit_test(test_hybrids), cmocka_unit_test(test_maze_pocket)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
