/* Tests of the 2D decomposition (acd2d): known concavities, partition properties, holes,
 * hierarchy readout, cancellation and argument checks. */
#include "testutil.h"

#include <math.h>
#include <string.h>

#include "acd/acd2d.h"
#include "acd2d_check.h"
#include "core/rng.h"

#define PI 3.14159265358979323846

static acd_polygon make_poly(const acd_vec2 *const *rings, const size_t *sizes, size_t nr) {
    acd_polygon p;
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(&p, rings, sizes, nr, &err), ACD_OK);
    return p;
}

/* star-shaped polygon (simple by construction): n vertices at increasing angles */
static acd_polygon random_star(uint64_t seed, size_t n, double rin, double rout) {
    acd_rng rng;
    acd_rng_seed(&rng, seed);
    acd_vec2 *p = malloc(n * sizeof *p);
    assert_non_null(p);
    for (size_t i = 0; i < n; i++) {
        double a = 2 * PI * ((double)i + 0.8 * acd_rng_uniform(&rng)) / (double)n;
        double r = rin + (rout - rin) * acd_rng_uniform(&rng);
        p[i].x = r * cos(a);
        p[i].y = r * sin(a);
    }
    const acd_vec2 *rings[1] = {p};
    size_t sizes[1] = {n};
    acd_polygon poly = make_poly(rings, sizes, 1);
    free(p);
    return poly;
}

static const acd_vec2 L[] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};

static void test_l_shape_concavity(void **state) {
    (void)state;
    size_t w;
    double c = acd2d_concavity(L, 6, ACD2D_MEASURE_SL, 0, &w);
    assert_true(fabs(c - 1 / sqrt(2)) < 1e-15);
    assert_int_equal(w, 3);
    /* a convex polygon has concavity 0 and no witness */
    const acd_vec2 sq[] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    assert_true(acd2d_concavity(sq, 4, ACD2D_MEASURE_SL, 0, &w) == 0);
    assert_true(w == SIZE_MAX);
}

static void test_l_shape_decompose(void **state) {
    (void)state;
    const acd_vec2 *rings[1] = {L};
    size_t sizes[1] = {6};
    acd_polygon poly = make_poly(rings, sizes, 1);
    acd2d_params prm = acd2d_default_params();
    acd2d_result res;
    acd_error err;
    assert_int_equal(acd2d_decompose(&poly, &prm, &res, &err), ACD_OK);
    assert_int_equal(res.ncomponents, 2);
    assert_int_equal(res.ncuts, 1);
    assert_int_equal(res.input_notches, 1);
    assert_int_equal(ck_result(&res, &prm, 3.0, 1), 0);
    /* the Eqn 4.3 cut from the notch (1,1): shortest candidates in the cone are (0,... ) ends */
    assert_true(res.cuts[0][0].x == 1 && res.cuts[0][0].y == 1);
    acd2d_result_free(&res);
    /* tau above the notch's concavity: the L is one component */
    prm.tau = 0.8;
    assert_int_equal(acd2d_decompose(&poly, &prm, &res, &err), ACD_OK);
    assert_int_equal(res.ncomponents, 1);
    assert_true(fabs(res.components[0].concavity - 1 / sqrt(2)) < 1e-15);
    acd2d_result_free(&res);
    acd_polygon_free(&poly);
}

static void check_all_measures(const acd_polygon *poly, double tau, int expect_convex) {
    double area = acd_polygon_area(poly);
    for (int m = 0; m < 4; m++) {
        acd2d_params prm = acd2d_default_params();
        prm.tau = tau;
        prm.measure = (acd2d_measure)m;
        acd2d_result res;
        acd_error err;
        acd_status st = acd2d_decompose(poly, &prm, &res, &err);
        if (st == ACD_ERR_UNSUPPORTED) continue;
        if (st != ACD_OK) print_message("%s\n", err.message);
        assert_int_equal(st, ACD_OK);
        assert_int_equal(ck_result(&res, &prm, area, 1), 0);
        if (expect_convex)
            for (size_t i = 0; i < res.ncomponents; i++) assert_true(res.components[i].concavity == 0);
        acd2d_result_free(&res);
    }
}

static void test_random_stars(void **state) {
    (void)state;
    for (uint64_t s = 1; s <= 12; s++) {
        acd_polygon p = random_star(s, 12 + 7 * s, 1.0, 3.0);
        check_all_measures(&p, 0, 1);
        check_all_measures(&p, 0.3, 0);
        acd_polygon_free(&p);
    }
}

static void test_square_with_holes(void **state) {
    (void)state;
    const acd_vec2 outer[] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    const acd_vec2 h1[] = {{2, 2}, {2, 4}, {4, 4}, {4, 2}};           /* clockwise */
    const acd_vec2 h2[] = {{6, 6}, {6, 8}, {8.5, 7.9}, {8, 6}};       /* clockwise */
    const acd_vec2 h3[] = {{6, 1}, {5.5, 3}, {8, 3}, {7, 2}, {8, 1}}; /* clockwise, with a notch */
    const acd_vec2 *rings[4] = {outer, h1, h2, h3};
    size_t sizes[4] = {4, 4, 4, 5};
    acd_polygon poly = make_poly(rings, sizes, 4);
    double area = acd_polygon_area(&poly);
    assert_true(area > 80 && area < 100);
    const double taus[] = {0, 0.5, 2, 100};
    for (int t = 0; t < 4; t++) {
        acd2d_params prm = acd2d_default_params();
        prm.tau = taus[t];
        acd2d_result res;
        acd_error err;
        acd_status st = acd2d_decompose(&poly, &prm, &res, &err);
        if (st != ACD_OK) print_message("%s\n", err.message);
        assert_int_equal(st, ACD_OK);
        assert_int_equal(res.input_holes, 3);
        assert_int_equal(ck_result(&res, &prm, area, 1), 0);
        assert_true(res.ncomponents >= 2); /* a hole cannot stay: at least two pieces */
        /* the first three tree operations are the hole merges */
        assert_true(res.nodes[0].is_hole_merge && res.nodes[1].is_hole_merge && res.nodes[2].is_hole_merge);
        assert_false(res.nodes[0].acceptable);
        acd2d_result_free(&res);
    }
    acd_polygon_free(&poly);
}

static int same_result(const acd2d_result *a, const acd2d_result *b) {
    if (a->ncomponents != b->ncomponents || a->ncuts != b->ncuts) return 0;
    for (size_t i = 0; i < a->ncomponents; i++) {
        if (a->components[i].npoints != b->components[i].npoints) return 0;
        if (memcmp(a->components[i].points, b->components[i].points, a->components[i].npoints * sizeof(acd_vec2)))
            return 0;
    }
    for (size_t i = 0; i < a->ncuts; i++)
        if (memcmp(a->cuts[i], b->cuts[i], sizeof a->cuts[i])) return 0;
    return 1;
}

static void test_hierarchy_readout(void **state) {
    (void)state;
    acd_polygon p = random_star(99, 200, 1.0, 4.0);
    for (int m = 0; m < 3; m++) {
        acd2d_params prm = acd2d_default_params();
        prm.measure = (acd2d_measure)m;
        acd2d_result fine;
        acd_error err;
        acd_status st = acd2d_decompose(&p, &prm, &fine, &err);
        if (st == ACD_ERR_UNSUPPORTED) continue;
        assert_int_equal(st, ACD_OK);
        const double taus[] = {0, 0.05, 0.2, 0.5, 1, 3};
        size_t prev = SIZE_MAX;
        for (int t = 0; t < 6; t++) {
            acd2d_result coarse, fresh;
            assert_int_equal(acd2d_result_at_tau(&fine, taus[t], &coarse, &err), ACD_OK);
            prm.tau = taus[t];
            assert_int_equal(acd2d_decompose(&p, &prm, &fresh, &err), ACD_OK);
            assert_true(same_result(&coarse, &fresh));
            assert_true(coarse.ncomponents <= prev);
            prev = coarse.ncomponents;
            acd2d_result_free(&coarse);
            acd2d_result_free(&fresh);
        }
        acd2d_result tmp;
        assert_int_equal(acd2d_result_at_tau(&fine, -1, &tmp, &err), ACD_ERR_INVALID_ARGUMENT);
        acd2d_result_free(&fine);
    }
    acd_polygon_free(&p);
}

/* every node's polygon (stored or rebuilt) has the area of its subtree's components */
static void test_node_polygons(void **state) {
    (void)state;
    acd_polygon p = random_star(5, 120, 1.0, 4.0);
    acd2d_params prm = acd2d_default_params();
    acd2d_result res;
    acd_error err;
    assert_int_equal(acd2d_decompose(&p, &prm, &res, &err), ACD_OK);
    double *leaf_area = calloc(res.nnodes, sizeof *leaf_area);
    for (size_t i = 0; i < res.ncomponents; i++) {
        int v = res.components[i].node;
        double a = ck_ring_area(res.components[i].points, res.components[i].npoints);
        while (v >= 0) { leaf_area[v] += a; v = res.nodes[v].parent; }
    }
    size_t empty = 0;
    for (size_t v = 0; v < res.nnodes; v++) {
        acd_polygon q;
        empty += res.nodes[v].polygon.nrings == 0;
        assert_int_equal(acd2d_node_polygon(&res, (int)v, &q, &err), ACD_OK);
        double a = acd_polygon_area(&q);
        assert_true(fabs(a - leaf_area[v]) <= 1e-9 * leaf_area[0]);
        if (v == 0) assert_true(q.ring_start[1] == p.ring_start[1] && !memcmp(q.points, p.points, p.ring_start[1] * sizeof *q.points));
        acd_polygon_free(&q);
    }
    assert_true(empty > 0); /* inner nodes are rebuilt, not stored */
    free(leaf_area);
    acd2d_result_free(&res);
    acd_polygon_free(&p);
}

/* Lemma A.3: with SP (and H1), no piece is more concave than its parent (spec §11 A10) */
static void test_sp_monotone(void **state) {
    (void)state;
    for (uint64_t seed = 1; seed <= 6; seed++) {
        acd_polygon p = random_star(seed * 31, 150, 1.0, 5.0);
        for (int m = ACD2D_MEASURE_SP; m <= ACD2D_MEASURE_H1; m++) {
            acd2d_params prm = acd2d_default_params();
            prm.measure = (acd2d_measure)m;
            acd2d_result res;
            acd_error err;
            assert_int_equal(acd2d_decompose(&p, &prm, &res, &err), ACD_OK);
            for (size_t v = 1; v < res.nnodes; v++) {
                int par = res.nodes[v].parent;
                if (res.nodes[par].is_hole_merge || !res.nodes[par].acceptable) continue;
                if (res.nodes[v].concavity > res.nodes[par].concavity * (1 + 1e-12) + 1e-12) {
                    print_message("seed %llu measure %d node %zu: %.17g > parent %.17g\n", (unsigned long long)seed, m, v,
                                  res.nodes[v].concavity, res.nodes[par].concavity);
                    fail();
                }
            }
            acd2d_result_free(&res);
        }
        acd_polygon_free(&p);
    }
}

static int cancel_after(void *user, double f, const char *stage) {
    (void)f;
    (void)stage;
    int *n = user;
    return ++*n > 5;
}

static void test_cancel_and_args(void **state) {
    (void)state;
    acd_polygon p = random_star(7, 300, 1.0, 4.0);
    acd2d_params prm = acd2d_default_params();
    int calls = 0;
    prm.progress = cancel_after;
    prm.progress_user = &calls;
    acd2d_result res;
    acd_error err;
    assert_int_equal(acd2d_decompose(&p, &prm, &res, &err), ACD_ERR_CANCELLED);
    assert_int_equal(res.ncomponents, 0);
    acd2d_params bad = prm;
    bad.cookie = 0;
    assert_int_equal(acd2d_decompose(&p, &bad, &res, &err), ACD_ERR_INVALID_ARGUMENT);
    bad = acd2d_default_params();
    bad.tau = -1;
    assert_int_equal(acd2d_decompose(&p, &bad, &res, &err), ACD_ERR_INVALID_ARGUMENT);
    bad.tau = NAN;
    assert_int_equal(acd2d_decompose(&p, &bad, &res, &err), ACD_ERR_INVALID_ARGUMENT);
    acd2d_measure m;
    assert_true(acd2d_measure_parse("H1", &m) && m == ACD2D_MEASURE_H1);
    assert_false(acd2d_measure_parse("h3", &m));
    assert_string_equal(acd2d_measure_name(ACD2D_MEASURE_SP), "sp");
    acd_polygon_free(&p);
}

static void test_normalize_and_determinism(void **state) {
    (void)state;
    acd_polygon p = random_star(11, 150, 1.0, 4.0);
    acd2d_params prm = acd2d_default_params();
    prm.tau = 0.05;
    prm.normalize = 1;
    acd2d_result a, b;
    acd_error err;
    assert_int_equal(acd2d_decompose(&p, &prm, &a, &err), ACD_OK);
    assert_int_equal(acd2d_decompose(&p, &prm, &b, &err), ACD_OK);
    assert_true(same_result(&a, &b));
    assert_true(a.tau > 0.05 && a.tau < 0.05 * 5.0); /* R is about 1..4 */
    acd2d_result_free(&a);
    acd2d_result_free(&b);
    acd_polygon_free(&p);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_l_shape_concavity),  cmocka_unit_test(test_l_shape_decompose),
        cmocka_unit_test(test_random_stars),       cmocka_unit_test(test_square_with_holes),
        cmocka_unit_test(test_hierarchy_readout),  cmocka_unit_test(test_node_polygons), cmocka_unit_test(test_sp_monotone),  cmocka_unit_test(test_cancel_and_args),
        cmocka_unit_test(test_normalize_and_determinism),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
