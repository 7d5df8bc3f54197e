/* Tests of acd3/knots: Douglas-Peucker in concavity space and knot detection (spec acd3d.md §4.2). */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>

#include "acd3/knots.h"

static void test_dp_keeps_corners_only(void **state) {
    (void)state;
    /* a tent: 0..10 rising to 5 then falling, sampled densely: DP keeps the two ends and the apex */
    enum { M = 21 };
    double x[M], y[M];
    unsigned char keep[M];
    for (int i = 0; i < M; i++) {
        x[i] = i;
        y[i] = i <= 10 ? i * 0.5 : (20 - i) * 0.5;
    }
    assert_true(acd3_douglas_peucker(x, y, M, 0.01, keep));
    int kept = 0;
    for (int i = 0; i < M; i++) kept += keep[i];
    assert_int_equal(kept, 3);
    assert_true(keep[0] && keep[10] && keep[M - 1]);
    /* with a huge threshold only the ends remain */
    assert_true(acd3_douglas_peucker(x, y, M, 100.0, keep));
    kept = 0;
    for (int i = 0; i < M; i++) kept += keep[i];
    assert_int_equal(kept, 2);
}

static void test_dp_every_dropped_point_within_delta(void **state) {
    (void)state;
    /* random walk: every dropped vertex lies within delta of the simplified chain segment spanning it */
    enum { M = 400 };
    double x[M], y[M];
    unsigned char keep[M];
    unsigned s = 12345;
    y[0] = 0;
    for (int i = 0; i < M; i++) {
        x[i] = i * 0.1;
        s = s * 1103515245u + 12345u;
        if (i) y[i] = y[i - 1] + ((double)(s >> 16 & 0x7fff) / 32768.0 - 0.5) * 0.2;
    }
    double delta = 0.15;
    assert_true(acd3_douglas_peucker(x, y, M, delta, keep));
    int a = 0;
    for (int b = 1; b < M; b++) {
        if (!keep[b]) continue;
        for (int k = a + 1; k < b; k++) {
            double dx = x[b] - x[a], dy = y[b] - y[a];
            double t = ((x[k] - x[a]) * dx + (y[k] - y[a]) * dy) / (dx * dx + dy * dy);
            t = t < 0 ? 0 : t > 1 ? 1 : t;
            double ex = x[a] + t * dx - x[k], ey = y[a] + t * dy - y[k];
            assert_true(sqrt(ex * ex + ey * ey) <= delta);
        }
        a = b;
    }
}

static void test_knot_at_concavity_peak(void **state) {
    (void)state;
    /* a path along x from a hull vertex to a hull vertex, dipping into a valley of depth 0.5 at
     * its middle: concavity peaks there; that vertex is the only knot */
    enum { M = 41 };
    double pts[3 * M], conc[M];
    for (int i = 0; i < M; i++) {
        double t = i / (double)(M - 1);
        pts[3 * i] = t * 4.0;
        pts[3 * i + 1] = 0;
        pts[3 * i + 2] = 0;
        conc[i] = 0.5 * (1.0 - fabs(2 * t - 1)); /* tent peaking at the middle */
    }
    uint32_t knots[M];
    size_t n = acd3_find_knots(pts, conc, M, 4.0, 0.05, knots);
    assert_int_equal(n, 1);
    assert_int_equal(knots[0], 20);
    /* a delta above the peak concavity: no knot */
    n = acd3_find_knots(pts, conc, M, 4.0, 0.6, knots);
    assert_int_equal(n, 0);
}

static void test_two_peaks_and_a_valley(void **state) {
    (void)state;
    /* concavity with two peaks (0.4 at 1/4, 0.3 at 3/4) separated by a dip to 0.1: two knots; the
     * dip is a convex turn, not a knot */
    enum { M = 81 };
    double pts[3 * M], conc[M];
    for (int i = 0; i < M; i++) {
        double t = i / (double)(M - 1);
        pts[3 * i] = t * 8.0;
        pts[3 * i + 1] = 0.1 * sin(t * 7); /* arc length no longer uniform in x */
        pts[3 * i + 2] = 0;
        if (t <= 0.25) conc[i] = 0.4 * t / 0.25;
        else if (t <= 0.5) conc[i] = 0.4 - 0.3 * (t - 0.25) / 0.25;
        else if (t <= 0.75) conc[i] = 0.1 + 0.2 * (t - 0.5) / 0.25;
        else conc[i] = 0.3 * (1 - t) / 0.25;
    }
    uint32_t knots[M];
    size_t n = acd3_find_knots(pts, conc, M, 8.0, 0.02, knots);
    assert_int_equal(n, 2);
    assert_true(fabs(conc[knots[0]] - 0.4) < 0.02);
    assert_true(fabs(conc[knots[1]] - 0.3) < 0.02);
    assert_true(knots[0] < knots[1]);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dp_keeps_corners_only),
        cmocka_unit_test(test_dp_every_dropped_point_within_delta),
        cmocka_unit_test(test_knot_at_concavity_peak),
        cmocka_unit_test(test_two_peaks_and_a_valley),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
