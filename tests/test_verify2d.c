/* Tests of eval/verify2d: the independent checker of 2D decompositions must accept true
 * partitions (including T-junctions, holes and thousands of pieces) and catch a missing piece,
 * overlapping pieces, a piece outside the input, a too-concave piece, a clockwise piece, a
 * duplicated piece and a self-crossing piece, naming the component. Also exact known values of
 * the reference concavity measures. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/verify2d.h"
#include "eval/concavity2d_ref.h"
#include "eval/verify2d.h"

#define N(a) (sizeof(a) / sizeof((a)[0]))

static acd_polygon square_input(double s) {
    acd_vec2 outer[] = {{0, 0}, {s, 0}, {s, s}, {0, s}};
    const acd_vec2 *rings[] = {outer};
    size_t sizes[] = {4};
    acd_polygon p;
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(&p, rings, sizes, 1, &err), ACD_OK);
    return p;
}

/* Runs the verifier with tau = 100 (partition checks only matter) unless told otherwise. */
static acd_status run(const acd_polygon *in, const acd_vec2 *const *c, const size_t *sz, size_t n, double tau,
                      acd_verify2d_report *rep, acd_error *err) {
    acd_verify2d_options o = acd_verify2d_default_options();
    o.tau = tau;
    o.notch_tolerance = 0;
    acd_status st = acd_verify2d(in, c, sz, n, &o, rep, err);
    if (st != ACD_OK) print_message("    verifier says: %s\n", err->message);
    return st;
}

static void test_two_halves_pass(void **state) {
    (void)state;
    acd_polygon in = square_input(2);
    acd_vec2 a[] = {{0, 0}, {1, 0}, {1, 2}, {0, 2}}, b[] = {{1, 0}, {2, 0}, {2, 2}, {1, 2}};
    const acd_vec2 *c[] = {a, b};
    size_t sz[] = {4, 4};
    acd_verify2d_report rep;
    acd_error err;
    assert_int_equal(run(&in, c, sz, 2, 0, &rep, &err), ACD_OK);
    assert_int_equal(rep.failed, ACD_V2D_PASS);
    assert_true(rep.input_area == 4.0);
    assert_true(rep.components_area == 4.0);
    assert_int_equal(rep.pairs_checked, 1);
    acd_polygon_free(&in);
}

static void test_t_junction_pass(void **state) {
    (void)state;
    /* left half whole; right half split in two: vertex (1,1) lies in the middle of a's edge */
    acd_polygon in = square_input(2);
    acd_vec2 a[] = {{0, 0}, {1, 0}, {1, 2}, {0, 2}};
    acd_vec2 b[] = {{1, 0}, {2, 0}, {2, 1}, {1, 1}}, c2[] = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
    const acd_vec2 *c[] = {a, b, c2};
    size_t sz[] = {4, 4, 4};
    acd_error err;
    assert_int_equal(run(&in, c, sz, 3, 0, NULL, &err), ACD_OK);
    acd_polygon_free(&in);
}

static void test_missing_piece(void **state) {
    (void)state;
    acd_polygon in = square_input(2);
    acd_vec2 a[] = {{0, 0}, {1, 0}, {1, 2}, {0, 2}};
    const acd_vec2 *c[] = {a};
    size_t sz[] = {4};
    acd_verify2d_report rep;
    acd_error err;
    assert_int_equal(run(&in, c, sz, 1, 0, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_AREA);
    assert_non_null(strstr(err.message, "not covered"));
    assert_non_null(strstr(err.message, "the input's boundary at (1.25, 0) lies on no component"));
    acd_polygon_free(&in);
}

static void test_overlap(void **state) {
    (void)state;
    acd_polygon in = square_input(2);
    acd_vec2 a[] = {{0, 0}, {1.2, 0}, {1.2, 2}, {0, 2}}, b[] = {{1, 0}, {2, 0}, {2, 2}, {1, 2}};
    const acd_vec2 *c[] = {a, b};
    size_t sz[] = {4, 4};
    acd_verify2d_report rep;
    acd_error err;
    assert_int_equal(run(&in, c, sz, 2, 0, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_OVERLAP);
    assert_int_equal(rep.component, 0);
    assert_int_equal(rep.other, 1);
    assert_non_null(strstr(err.message, "components 0 and 1 overlap"));
    acd_polygon_free(&in);
}

static void test_overlap_without_vertex_inside(void **state) {
    (void)state;
    /* a triangle inscribed in the square, all its vertices on the square's boundary: only the
     * edge midpoints reveal the overlap */
    acd_polygon in = square_input(2);
    acd_vec2 a[] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}}, b[] = {{0, 0}, {2, 0}, {1, 2}};
    const acd_vec2 *c[] = {a, b};
    size_t sz[] = {4, 3};
    acd_verify2d_report rep;
    acd_error err;
    assert_int_equal(run(&in, c, sz, 2, 0, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_OVERLAP);
    acd_polygon_free(&in);
}

static void test_duplicate_piece(void **state) {
    (void)state;
    acd_polygon in = square_input(2);
    acd_vec2 a[] = {{0, 0}, {1, 0}, {1, 2}, {0, 2}}, b[] = {{1, 0}, {2, 0}, {2, 2}, {1, 2}};
    acd_vec2 d[] = {{1, 0}, {2, 0}, {2, 2}, {1, 2}};
    const acd_vec2 *c[] = {a, b, d};
    size_t sz[] = {4, 4, 4};
    acd_verify2d_report rep;
    acd_error err;
    assert_int_equal(run(&in, c, sz, 3, 0, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_OVERLAP);
    assert_int_equal(rep.component, 1);
    assert_int_equal(rep.other, 2);
    assert_non_null(strstr(err.message, "same polygon"));
    acd_polygon_free(&in);
}

static void test_outside(void **state) {
    (void)state;
    acd_polygon in = square_input(2);
    acd_vec2 a[] = {{0, 0}, {1, 0}, {1, 2}, {0, 2}}, b[] = {{1, 0}, {3, 0}, {3, 2}, {1, 2}};
    const acd_vec2 *c[] = {a, b};
    size_t sz[] = {4, 4};
    acd_verify2d_report rep;
    acd_error err;
    assert_int_equal(run(&in, c, sz, 2, 0, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_OUTSIDE);
    assert_int_equal(rep.component, 1);
    assert_non_null(strstr(err.message, "component 1 reaches outside"));
    acd_polygon_free(&in);
}

static void test_outside_crossing(void **state) {
    (void)state;
    /* a piece poking through the boundary with no vertex beyond it being the only clue: the
     * triangle's edge crosses the input's edge */
    acd_polygon in = square_input(2);
    acd_vec2 a[] = {{0.5, 0.5}, {2.5, 1}, {0.5, 1.5}};
    const acd_vec2 *c[] = {a};
    size_t sz[] = {3};
    acd_verify2d_report rep;
    acd_error err;
    assert_int_equal(run(&in, c, sz, 1, 0, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_OUTSIDE);
    acd_polygon_free(&in);
}

static void test_clockwise(void **state) {
    (void)state;
    acd_polygon in = square_input(2);
    acd_vec2 a[] = {{0, 0}, {1, 0}, {1, 2}, {0, 2}}, b[] = {{1, 0}, {1, 2}, {2, 2}, {2, 0}};
    const acd_vec2 *c[] = {a, b};
    size_t sz[] = {4, 4};
    acd_verify2d_report rep;
    acd_error err;
    assert_int_equal(run(&in, c, sz, 2, 0, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_CLOCKWISE);
    assert_int_equal(rep.component, 1);
    assert_non_null(strstr(err.message, "component 1 is not counterclockwise"));
    acd_polygon_free(&in);
}

static void test_self_crossing_and_invalid(void **state) {
    (void)state;
    acd_polygon in = square_input(2);
    /* a bow tie with positive total area: (0,0) (2,0) (0,1) (2,2) ... */
    acd_vec2 a[] = {{0, 0}, {2, 0}, {2, 2}, {1, 0.5}, {0, 2}, {1.5, 1}};
    const acd_vec2 *c[] = {a};
    size_t sz[] = {6};
    acd_verify2d_report rep;
    acd_error err;
    assert_int_equal(run(&in, c, sz, 1, 0, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_SELF_INTERSECTION);
    acd_vec2 two[] = {{0, 0}, {1, 1}};
    const acd_vec2 *c2[] = {two};
    size_t sz2[] = {2};
    assert_int_equal(run(&in, c2, sz2, 1, 0, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_INVALID);
    acd_vec2 nan[] = {{0, 0}, {1, 0}, {NAN, 1}};
    const acd_vec2 *c3[] = {nan};
    size_t sz3[] = {3};
    assert_int_equal(run(&in, c3, sz3, 1, 0, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_INVALID);
    acd_polygon_free(&in);
}

/* L shape: hull (0,0) (2,0) (2,1) (1,2) (0,2); the notch (1,1) lies 1/sqrt(2) from the bridge
 * (2,1)-(1,2) both straight and along a path, and there is no hazard. */
static const acd_vec2 L_shape[] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};

static void test_too_concave(void **state) {
    (void)state;
    const acd_vec2 *rings[] = {L_shape};
    size_t sizes[] = {6};
    acd_polygon in;
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(&in, rings, sizes, 1, &err), ACD_OK);
    const acd_vec2 *c[] = {L_shape};
    acd_verify2d_report rep;
    assert_int_equal(run(&in, c, sizes, 1, 0.7, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_CONCAVITY);
    assert_int_equal(rep.component, 0);
    assert_non_null(strstr(err.message, "component 0 has concavity"));
    assert_non_null(strstr(err.message, "vertex 3"));
    assert_int_equal(run(&in, c, sizes, 1, 0.71, &rep, &err), ACD_OK);
    assert_true(fabs(rep.max_concavity - sqrt(0.5)) < 1e-15);
    /* and split at the notch it passes at tau = 0 */
    acd_vec2 a[] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {0, 1}}, b[] = {{0, 1}, {1, 1}, {1, 2}, {0, 2}};
    const acd_vec2 *c2[] = {a, b};
    size_t sz2[] = {5, 4};
    assert_int_equal(run(&in, c2, sz2, 2, 0, &rep, &err), ACD_OK);
    assert_true(rep.max_concavity == 0);
    acd_polygon_free(&in);
}

static void test_measures_known_values(void **state) {
    (void)state;
    for (int m = 0; m < 4; m++) {
        size_t w;
        double c = acd_verify2d_concavity(L_shape, 6, (acd2d_measure)m, 0, 0, &w);
        assert_true(fabs(c - sqrt(0.5)) < 1e-15);
        assert_int_equal(w, 3);
    }
    /* A hook (CCW): bottom bar [0,10]x[0,2], right post [8,10]x[2,10], top lip [2,10]x[8,10].
     * Hull (0,0) (10,0) (10,10) (2,10) (0,2); bridge (2,10)->(0,2) on the line 4x - y + 2 = 0;
     * pocket (2,10) (2,8) (8,8) (8,2) (0,2); notches (8,8) and (8,2). The edge (2,8)->(8,8)
     * runs against the bridge direction: a hazard. (8,8) hides under the lip: its shortest
     * path goes to (2,8) (length 6), then drops perpendicularly (2/sqrt 17). */
    acd_vec2 hook[] = {{0, 0}, {10, 0}, {10, 10}, {2, 10}, {2, 8}, {8, 8}, {8, 2}, {0, 2}};
    double conc[8];
    size_t hz = 0;
    const double r17 = sqrt(17.0);
    assert_int_equal(acd_ref_vertex_concavity(hook, 8, ACD2D_MEASURE_SL, 0, 0, conc, &hz), 0);
    assert_int_equal(hz, 1);
    assert_true(fabs(conc[5] - 26 / r17) < 1e-12);
    assert_true(fabs(conc[6] - 32 / r17) < 1e-12);
    assert_true(fabs(conc[4] - 2 / r17) < 1e-12);
    assert_true(conc[0] == 0 && conc[1] == 0 && conc[2] == 0 && conc[3] == 0 && conc[7] == 0);
    assert_int_equal(acd_ref_vertex_concavity(hook, 8, ACD2D_MEASURE_SP, 0, 0, conc, NULL), 0);
    assert_true(fabs(conc[5] - (6 + 2 / r17)) < 1e-12);
    assert_true(fabs(conc[6] - 32 / r17) < 1e-12); /* the drop from (8,2) is unobstructed */
    assert_int_equal(acd_ref_vertex_concavity(hook, 8, ACD2D_MEASURE_H1, 0, 0, conc, NULL), 0);
    assert_true(fabs(conc[5] - (6 + 2 / r17)) < 1e-12);
    /* H2: SL when the pocket's SL maximum (32/sqrt 17 = 7.76) exceeds tau, else SP */
    assert_int_equal(acd_ref_vertex_concavity(hook, 8, ACD2D_MEASURE_H2, 1, 0, conc, NULL), 0);
    assert_true(fabs(conc[5] - 26 / r17) < 1e-12);
    assert_int_equal(acd_ref_vertex_concavity(hook, 8, ACD2D_MEASURE_H2, 8, 0, conc, NULL), 0);
    assert_true(fabs(conc[5] - (6 + 2 / r17)) < 1e-12);
    size_t w;
    assert_true(fabs(acd_verify2d_concavity(hook, 8, ACD2D_MEASURE_SP, 0, 0, &w) - 32 / r17) < 1e-12);
    assert_int_equal(w, 6);
    /* a V pocket without hazard: every measure gives the depth 7 at the notch (5,3) */
    acd_vec2 vee[] = {{0, 0}, {10, 0}, {10, 10}, {5, 3}, {0, 10}};
    for (int m = 0; m < 4; m++) {
        double c = acd_verify2d_concavity(vee, 5, (acd2d_measure)m, 0, 0, &w);
        assert_int_equal(w, 3);
        assert_true(fabs(c - 7) < 1e-12);
    }
}

/* SP directly on the hook's pocket polygon (chain from one bridge end to the other), and on a
 * spiral whose bottom must go around corners. */
static void test_sp_pocket(void **state) {
    (void)state;
    acd_vec2 q[] = {{2, 10}, {2, 8}, {8, 8}, {8, 2}, {0, 2}};
    double d[5];
    const double r17 = sqrt(17.0);
    assert_int_equal(acd_ref_pocket_sp(q, 5, d), 0);
    assert_true(d[0] == 0 && d[4] == 0);
    assert_true(fabs(d[1] - 2 / r17) < 1e-12);
    assert_true(fabs(d[2] - (6 + 2 / r17)) < 1e-12);
    assert_true(fabs(d[3] - 32 / r17) < 1e-12);
    /* Pocket (clockwise, interior on the right), bridge (0,0)-(10,0) on top: the box
     * [0,10]x[-10,0] minus a wall [0,8]x[-6,-4] hanging from the left side. The bottom-left
     * corner goes to the wall's corner (8,-6), then straight up past (8,-4). */
    acd_vec2 s[] = {{10, 0}, {10, -10}, {0, -10}, {0, -6}, {8, -6}, {8, -4}, {0, -4}, {0, 0}};
    double ds[8];
    assert_int_equal(acd_ref_pocket_sp(s, 8, ds), 0);
    assert_true(fabs(ds[1] - 10) < 1e-12);
    assert_true(fabs(ds[2] - (hypot(8, 4) + 6)) < 1e-12);
    assert_true(fabs(ds[3] - (8 + 6)) < 1e-12);
    assert_true(fabs(ds[4] - 6) < 1e-12);
    assert_true(fabs(ds[5] - 4) < 1e-12);
    assert_true(fabs(ds[6] - 4) < 1e-12);
}

/* A square with a square hole, cut into 4 trapezoids around the hole: passes; a piece
 * covering the hole fails as outside. */
static void test_hole(void **state) {
    (void)state;
    acd_vec2 outer[] = {{0, 0}, {4, 0}, {4, 4}, {0, 4}};
    acd_vec2 hole[] = {{1, 1}, {1, 3}, {3, 3}, {3, 1}};
    const acd_vec2 *rings[] = {outer, hole};
    size_t sizes[] = {4, 4};
    acd_polygon in;
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(&in, rings, sizes, 2, &err), ACD_OK);
    acd_vec2 s[] = {{0, 0}, {4, 0}, {3, 1}, {1, 1}}, e[] = {{4, 0}, {4, 4}, {3, 3}, {3, 1}};
    acd_vec2 n[] = {{4, 4}, {0, 4}, {1, 3}, {3, 3}}, w[] = {{0, 4}, {0, 0}, {1, 1}, {1, 3}};
    const acd_vec2 *c[] = {s, e, n, w};
    size_t sz[] = {4, 4, 4, 4};
    acd_verify2d_report rep;
    assert_int_equal(run(&in, c, sz, 4, 0, &rep, &err), ACD_OK);
    assert_true(rep.input_area == 12.0);
    /* the same with the south piece replaced by a piece that also covers the hole */
    acd_vec2 big[] = {{0, 0}, {4, 0}, {3, 3}, {1, 3}};
    const acd_vec2 *c2[] = {big, e, n, w};
    assert_int_equal(run(&in, c2, sz, 4, 0, &rep, &err), ACD_ERR_VERIFY);
    assert_true(rep.failed == ACD_V2D_OUTSIDE || rep.failed == ACD_V2D_OVERLAP);
    assert_int_equal(rep.component, 0);
    /* a piece exactly filling the hole is outside */
    acd_vec2 plug[] = {{1, 1}, {3, 1}, {3, 3}, {1, 3}};
    const acd_vec2 *c3[] = {s, e, n, w, plug};
    size_t sz3[] = {4, 4, 4, 4, 4};
    assert_int_equal(run(&in, c3, sz3, 5, 0, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_OUTSIDE);
    assert_int_equal(rep.component, 4);
    acd_polygon_free(&in);
}

/* A k x k grid of unit squares, with every square's right edge split at a Steiner-like point
 * computed with rounding, partitions the big square; shifting one square breaks it. */
static void test_many_components(void **state) {
    (void)state;
    enum { K = 70 };
    acd_polygon in = square_input(K);
    acd_vec2 *pts = malloc(K * K * 5 * sizeof *pts);
    const acd_vec2 **c = malloc(K * K * sizeof *c);
    size_t *sz = malloc(K * K * sizeof *sz);
    assert_non_null(pts);
    assert_non_null(c);
    assert_non_null(sz);
    for (int y = 0; y < K; y++)
        for (int x = 0; x < K; x++) {
            acd_vec2 *p = pts + (size_t)(y * K + x) * 4;
            p[0] = (acd_vec2){x, y};
            p[1] = (acd_vec2){x + 1, y};
            p[2] = (acd_vec2){x + 1, y + 1};
            p[3] = (acd_vec2){x, y + 1};
            c[y * K + x] = p;
            sz[y * K + x] = 4;
        }
    acd_verify2d_report rep;
    acd_error err;
    assert_int_equal(run(&in, c, sz, K * K, 0, &rep, &err), ACD_OK);
    assert_true(rep.pairs_checked >= 2 * K * (K - 1));
    assert_true(rep.pairs_checked <= 4 * K * K);
    assert_true(fabs(rep.components_area - K * K) <= 1e-9 * K * K);
    /* shift square (10, 20) right by 0.25 */
    acd_vec2 *p = pts + (size_t)(20 * K + 10) * 4;
    for (int i = 0; i < 4; i++) p[i].x += 0.25;
    assert_int_equal(run(&in, c, sz, K * K, 0, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_OVERLAP);
    assert_true(rep.component == 20 * K + 10 || rep.other == 20 * K + 10);
    free(pts);
    free(c);
    free(sz);
    acd_polygon_free(&in);
}

/* Rounded Steiner points: a cut ends at a point computed on a slanted input edge, which is on
 * that edge only up to rounding; the verifier must accept it. */
static void test_rounded_steiner(void **state) {
    (void)state;
    acd_vec2 outer[] = {{0, 0}, {3, 0}, {3, 1}, {0, 2}};
    const acd_vec2 *rings[] = {outer};
    size_t sizes[] = {4};
    acd_polygon in;
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(&in, rings, sizes, 1, &err), ACD_OK);
    int inexact = 0;
    for (int k = 1; k < 10; k++) {
        double s = k / 10.0;
        acd_vec2 t = {3 + s * (0 - 3), 1 + s * (2 - 1)};
        if (acd_ref_orient(outer[2], outer[3], t) != 0) inexact++;
        acd_vec2 a[] = {{0, 0}, {1, 0}, t, {0, 2}}, b[] = {{1, 0}, {3, 0}, {3, 1}, t};
        const acd_vec2 *c[] = {a, b};
        size_t sz[] = {4, 4};
        assert_int_equal(run(&in, c, sz, 2, 100, NULL, &err), ACD_OK);
    }
    assert_true(inexact > 0); /* the tolerance was exercised */
    acd_polygon_free(&in);
}

static void test_area_compensated(void **state) {
    (void)state;
    /* a unit square far from the origin */
    acd_vec2 sq[] = {{1e8, 1e8}, {1e8 + 1, 1e8}, {1e8 + 1, 1e8 + 1}, {1e8, 1e8 + 1}};
    assert_true(acd_v2d_ring_area(sq, 4) == 1.0);
    int r = acd_v2d_classify_point(sq, (size_t[]){0, 4}, 1, (acd_vec2){1e8 + 0.5, 1e8 + 0.5}, 0);
    assert_int_equal(r, 1);
    r = acd_v2d_classify_point(sq, (size_t[]){0, 4}, 1, (acd_vec2){1e8 + 1, 1e8 + 0.5}, 0);
    assert_int_equal(r, 0);
    r = acd_v2d_classify_point(sq, (size_t[]){0, 4}, 1, (acd_vec2){1e8 + 2, 1e8 + 0.5}, 0);
    assert_int_equal(r, -1);
}

/* Two L-shaped pieces whose boxes overlap in a square that no edge of either enters: not the
 * same polygon (the verifier once said so, on the monkey scaled by 1e6, because edges it had
 * looked at but not listed counted as listed); the missing middle is then the failure. */
static void test_boxes_meet_edges_do_not(void **state) {
    (void)state;
    acd_polygon in = square_input(5);
    acd_vec2 a[] = {{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}};
    acd_vec2 b[] = {{4.5, 1.5}, {5, 1.5}, {5, 5}, {1.5, 5}, {1.5, 4.5}, {4.5, 4.5}};
    const acd_vec2 *c[] = {a, b};
    size_t sz[] = {6, 6};
    acd_verify2d_report rep;
    acd_error err;
    assert_int_equal(run(&in, c, sz, 2, 100, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_AREA);
    acd_polygon_free(&in);
}

/* Far from the origin (1e9: doubles 1.2e-7 apart). Components sharing exact diagonals pass: the
 * midpoints the verifier locates are rounded off the diagonals by up to half that spacing, far
 * above ACD_TOL_REL_DIST x extent (it once rejected every exact Hertel-Mehlhorn decomposition of
 * a translated polygon); a cut end rounded off a slanted input edge passes too. */
static void test_far_exact_and_rounded(void **state) {
    (void)state;
    const double T = 1e9;
    acd_vec2 outer[] = {{T + 0.1, T + 0.3}, {T + 3.7, T + 0.1}, {T + 3.3, T + 1.9}, {T + 0.2, T + 2.3}};
    const acd_vec2 *rings[] = {outer};
    size_t sizes[] = {4};
    acd_polygon in;
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(&in, rings, sizes, 1, &err), ACD_OK);
    acd_vec2 a[] = {outer[0], outer[1], outer[2]}, b[] = {outer[0], outer[2], outer[3]};
    const acd_vec2 *c[] = {a, b};
    size_t sz[] = {3, 3};
    assert_int_equal(run(&in, c, sz, 2, 100, NULL, &err), ACD_OK);
    int inexact = 0;
    for (int k = 1; k < 10; k++) {
        double s = k / 10.0;
        acd_vec2 t = {outer[2].x + s * (outer[3].x - outer[2].x), outer[2].y + s * (outer[3].y - outer[2].y)};
        if (acd_ref_orient(outer[2], outer[3], t) != 0) inexact++;
        acd_vec2 p[] = {outer[0], outer[1], t, outer[3]}, q[] = {outer[1], outer[2], t};
        const acd_vec2 *cc[] = {p, q};
        size_t zz[] = {4, 3};
        assert_int_equal(run(&in, cc, zz, 2, 100, NULL, &err), ACD_OK);
    }
    assert_true(inexact > 0);
    acd_polygon_free(&in);
}

/* Far from the origin, a cut end w computed on an earlier cut P Q and rounded into the component
 * on the other side (a T-junction off by a fraction of the spacing of doubles) is an overlap
 * between components, caught; with w also in that component (a shared cut end) it passes. */
static void test_far_t_junction(void **state) {
    (void)state;
    const double T = 1e9;
    acd_polygon in = square_input(2);
    for (size_t i = 0; i < 4; i++) {
        in.points[i].x += T;
        in.points[i].y += T;
    }
    acd_vec2 O = in.points[0], X = in.points[1], Z = in.points[2], Y = in.points[3];
    acd_vec2 P = {T + 0.7, T}, Q = {T + 1.3, T + 2}, R = {T + 2, T + 1};
    int overlaps = 0;
    for (int k = 1; k < 20; k++) {
        double s = k / 20.0;
        acd_vec2 w = {P.x + s * (Q.x - P.x), P.y + s * (Q.y - P.y)};
        acd_vec2 a[] = {O, P, Q, Y}, a2[] = {O, P, w, Q, Y};
        acd_vec2 b[] = {P, X, R, w}, c2[] = {w, R, Z, Q};
        const acd_vec2 *c[] = {a, b, c2}, *cs[] = {a2, b, c2};
        size_t sz[] = {4, 4, 4}, szs[] = {5, 4, 4};
        acd_verify2d_report rep;
        acd_error err;
        assert_int_equal(run(&in, cs, szs, 3, 100, NULL, &err), ACD_OK);
        if (acd_ref_orient(P, Q, w) > 0) { /* w inside a */
            assert_int_equal(run(&in, c, sz, 3, 100, &rep, &err), ACD_ERR_VERIFY);
            assert_int_equal(rep.failed, ACD_V2D_OVERLAP);
            overlaps++;
        }
    }
    assert_true(overlaps > 0);
    acd_polygon_free(&in);
}

/* acd_verify2d_result on a hand-made result: passes, then a hull missing a corner, a clockwise
 * hull and a result claiming a smaller tau fail. */
static void test_result_hulls(void **state) {
    (void)state;
    const acd_vec2 *rings[] = {L_shape};
    size_t sizes[] = {6};
    acd_polygon in;
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(&in, rings, sizes, 1, &err), ACD_OK);
    acd_vec2 a[] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {0, 1}}, b[] = {{0, 1}, {1, 1}, {1, 2}, {0, 2}};
    acd_vec2 ha[] = {{0, 0}, {2, 0}, {2, 1}, {0, 1}}, hb[] = {{0, 1}, {1, 1}, {1, 2}, {0, 2}};
    acd2d_component comps[2] = {
        {.points = a, .npoints = 5, .hull = ha, .nhull = 4, .node = 1},
        {.points = b, .npoints = 4, .hull = hb, .nhull = 4, .node = 2},
    };
    acd2d_result res;
    memset(&res, 0, sizeof res);
    res.tau = 0;
    res.measure = ACD2D_MEASURE_SL;
    res.components = comps;
    res.ncomponents = 2;
    acd2d_params prm = acd2d_default_params();
    acd_verify2d_report rep;
    assert_int_equal(acd_verify2d_result(&in, &res, &prm, 0, &rep, &err), ACD_OK);
    acd_vec2 bad[] = {{0, 0}, {2, 0}, {2, 1}}; /* misses (0,1) */
    comps[0].hull = bad;
    comps[0].nhull = 3;
    assert_int_equal(acd_verify2d_result(&in, &res, &prm, 7, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_HULL);
    assert_non_null(strstr(err.message, "component 7"));
    acd_vec2 cw[] = {{0, 1}, {2, 1}, {2, 0}, {0, 0}};
    comps[0].hull = cw;
    comps[0].nhull = 4;
    assert_int_equal(acd_verify2d_result(&in, &res, &prm, 0, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_HULL);
    /* the whole L as one component claimed at tau 0.5 */
    comps[0] = (acd2d_component){.points = (acd_vec2 *)L_shape, .npoints = 6, .hull = ha, .nhull = 4};
    acd_vec2 hl[] = {{0, 0}, {2, 0}, {2, 1}, {1, 2}, {0, 2}};
    comps[0].hull = hl;
    comps[0].nhull = 5;
    res.ncomponents = 1;
    res.tau = 0.5;
    assert_int_equal(acd_verify2d_result(&in, &res, &prm, 0, &rep, &err), ACD_ERR_VERIFY);
    assert_int_equal(rep.failed, ACD_V2D_CONCAVITY);
    res.tau = 0.75;
    assert_int_equal(acd_verify2d_result(&in, &res, &prm, 0, &rep, &err), ACD_OK);
    acd_polygon_free(&in);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_two_halves_pass),
        cmocka_unit_test(test_t_junction_pass),
        cmocka_unit_test(test_missing_piece),
        cmocka_unit_test(test_overlap),
        cmocka_unit_test(test_overlap_without_vertex_inside),
        cmocka_unit_test(test_duplicate_piece),
        cmocka_unit_test(test_outside),
        cmocka_unit_test(test_outside_crossing),
        cmocka_unit_test(test_clockwise),
        cmocka_unit_test(test_self_crossing_and_invalid),
        cmocka_unit_test(test_too_concave),
        cmocka_unit_test(test_measures_known_values),
        cmocka_unit_test(test_sp_pocket),
        cmocka_unit_test(test_hole),
        cmocka_unit_test(test_many_components),
        cmocka_unit_test(test_rounded_steiner),
        cmocka_unit_test(test_area_compensated),
        cmocka_unit_test(test_boxes_meet_edges_do_not),
        cmocka_unit_test(test_far_exact_and_rounded),
        cmocka_unit_test(test_far_t_junction),
        cmocka_unit_test(test_result_hulls),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
