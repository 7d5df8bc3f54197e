/* Tests of core/predicates: exact signs against 128-bit integer arithmetic on near-degenerate
 * inputs, where plain floating point gets the sign wrong. */
#include "testutil.h"

#include <math.h>

#include "core/predicates.h"
#include "core/rng.h"

typedef __int128 i128;

static int sign128(i128 v) { return (v > 0) - (v < 0); }

static int exact_orient2d(const int64_t a[2], const int64_t b[2], const int64_t c[2]) {
    i128 l = (i128)(a[0] - c[0]) * (b[1] - c[1]);
    i128 r = (i128)(a[1] - c[1]) * (b[0] - c[0]);
    return sign128(l - r);
}

static void test_orient2d_exactly_collinear(void **state) {
    (void)state;
    /* points on y = x with awkward coordinates: exactly collinear, naive formula often is not 0 */
    acd_rng r;
    acd_rng_seed(&r, 1);
    int naive_wrong = 0;
    for (int i = 0; i < 20000; i++) {
        double t[3];
        for (int k = 0; k < 3; k++) t[k] = (acd_rng_uniform(&r) - 0.5) * 1e3 + 0.1;
        double a[2] = {t[0], t[0]}, b[2] = {t[1], t[1]}, c[2] = {t[2], t[2]};
        assert_int_equal(acd_orient2d_sign(a, b, c), 0);
        double naive = (a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0]);
        (void)naive;
    }
    /* a classic near-collinear case: the naive determinant gives a wrong non-zero sign */
    for (int i = 0; i < 256; i++) {
        double a[2] = {0.5 + i * 0x1p-53, 0.5}, b[2] = {12, 12}, c[2] = {24, 24};
        double naive = (a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0]);
        int expect = i == 0 ? 0 : -1; /* a is right of the line y=x by i ulps: clockwise turn */
        assert_int_equal(acd_orient2d_sign(a, b, c), expect);
        if ((naive > 0) - (naive < 0) != expect) naive_wrong++;
    }
    assert_true(naive_wrong > 0); /* the test exercises the exact path */
}

static void test_orient2d_random_integers(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 2);
    for (int i = 0; i < 100000; i++) {
        int64_t a[2], b[2], c[2];
        int64_t base = (int64_t)(acd_rng_below(&r, 1ull << 50)) - (1ll << 49);
        for (int k = 0; k < 2; k++) {
            /* nearly collinear: c close to the line through a and b */
            a[k] = base + (int64_t)acd_rng_below(&r, 1000);
            b[k] = base + (int64_t)acd_rng_below(&r, 1ull << 40);
        }
        for (int k = 0; k < 2; k++) c[k] = 2 * b[k] - a[k] + (int64_t)acd_rng_below(&r, 3) - 1;
        double da[2] = {(double)a[0] * 0x1p-30, (double)a[1] * 0x1p-30};
        double db[2] = {(double)b[0] * 0x1p-30, (double)b[1] * 0x1p-30};
        double dc[2] = {(double)c[0] * 0x1p-30, (double)c[1] * 0x1p-30};
        assert_int_equal(acd_orient2d_sign(da, db, dc), exact_orient2d(a, b, c));
    }
}

static int exact_orient3d(const int64_t a[3], const int64_t b[3], const int64_t c[3], const int64_t d[3]) {
    i128 u[3], v[3], w[3];
    for (int k = 0; k < 3; k++) { u[k] = a[k] - d[k]; v[k] = b[k] - d[k]; w[k] = c[k] - d[k]; }
    i128 det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
    return sign128(det);
}

static void test_orient3d_random_integers(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 3);
    int zeros = 0;
    for (int i = 0; i < 50000; i++) {
        int64_t a[3], b[3], c[3], d[3];
        for (int k = 0; k < 3; k++) {
            a[k] = (int64_t)acd_rng_below(&r, 1u << 28);
            b[k] = (int64_t)acd_rng_below(&r, 1u << 28);
            c[k] = (int64_t)acd_rng_below(&r, 1u << 28);
        }
        /* d = a + (b-a) + (c-a) + tiny offset: nearly coplanar */
        for (int k = 0; k < 3; k++) d[k] = b[k] + c[k] - a[k] + (int64_t)acd_rng_below(&r, 3) - 1;
        double fa[3], fb[3], fc[3], fd[3];
        for (int k = 0; k < 3; k++) {
            fa[k] = (double)a[k] * 0x1p-20 + 1000.0;
            fb[k] = (double)b[k] * 0x1p-20 + 1000.0;
            fc[k] = (double)c[k] * 0x1p-20 + 1000.0;
            fd[k] = (double)d[k] * 0x1p-20 + 1000.0;
        }
        int e = exact_orient3d(a, b, c, d);
        zeros += e == 0;
        assert_int_equal(acd_orient3d_sign(fa, fb, fc, fd), e);
    }
    assert_true(zeros > 0);
}

static void test_orient3d_orientation_convention(void **state) {
    (void)state;
    double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    double below[3] = {0.2, 0.2, -1}, above[3] = {0.2, 0.2, 1};
    assert_true(acd_orient3d(a, b, c, below) > 0);
    assert_true(acd_orient3d(a, b, c, above) < 0);
}

static void test_incircle(void **state) {
    (void)state;
    double a[2] = {1, 0}, b[2] = {0, 1}, c[2] = {-1, 0};
    double in[2] = {0, 0.5}, out[2] = {0, 2}, on[2] = {0, -1};
    assert_true(acd_incircle(a, b, c, in) > 0);
    assert_true(acd_incircle(a, b, c, out) < 0);
    assert_true(acd_incircle(a, b, c, on) == 0);
}

static void test_segments(void **state) {
    (void)state;
    double p0[2] = {0, 0}, p1[2] = {2, 2}, q0[2] = {0, 2}, q1[2] = {2, 0};
    assert_int_equal(acd_segments_relation(p0, p1, q0, q1), ACD_SEG_PROPER);
    double t0[2] = {1, 1}, t1[2] = {3, 0};
    assert_int_equal(acd_segments_relation(p0, p1, t0, t1), ACD_SEG_TOUCH);
    double o0[2] = {1, 1}, o1[2] = {3, 3};
    assert_int_equal(acd_segments_relation(p0, p1, o0, o1), ACD_SEG_OVERLAP);
    double e0[2] = {2, 2}, e1[2] = {3, 3};
    assert_int_equal(acd_segments_relation(p0, p1, e0, e1), ACD_SEG_TOUCH);
    double d0[2] = {3, 3}, d1[2] = {4, 4};
    assert_int_equal(acd_segments_relation(p0, p1, d0, d1), ACD_SEG_DISJOINT);
    double f0[2] = {0, 1}, f1[2] = {-1, 5};
    assert_int_equal(acd_segments_relation(p0, p1, f0, f1), ACD_SEG_DISJOINT);
    assert_true(acd_point_on_segment(t0, p0, p1));
    assert_false(acd_point_on_segment(d0, p0, p1));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_orient2d_exactly_collinear),
        cmocka_unit_test(test_orient2d_random_integers),
        cmocka_unit_test(test_orient3d_random_integers),
        cmocka_unit_test(test_orient3d_orientation_convention),
        cmocka_unit_test(test_incircle),
        cmocka_unit_test(test_segments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
