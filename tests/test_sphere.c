/* Tests of geom3/sphere: minimum enclosing sphere against brute force (smallest of the balls through
 * 2, 3, 4 points that contain every point) on random sets, known values, degenerate sets. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "geom3/sphere.h"

static double d3(const double *a, const double *b) {
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Ball with the points on its boundary and centre in their affine hull (-1 radius if degenerate). */
static double ball_through(const double *const *s, int k, double c[3]) {
    if (k == 2) {
        for (int i = 0; i < 3; i++) c[i] = 0.5 * (s[0][i] + s[1][i]);
        return 0.5 * d3(s[0], s[1]);
    }
    /* centre = s0 + sum a_j e_j with 2 e_i . x = |e_i|^2, solved by Gaussian elimination in the
     * Gram system: G a = b/2 with G_ij = e_i . e_j */
    double e[3][3], G[3][4];
    int m = k - 1;
    for (int j = 0; j < m; j++)
        for (int i = 0; i < 3; i++) e[j][i] = s[j + 1][i] - s[0][i];
    for (int i = 0; i < m; i++) {
        for (int j = 0; j < m; j++) G[i][j] = e[i][0] * e[j][0] + e[i][1] * e[j][1] + e[i][2] * e[j][2];
        G[i][3] = 0.5 * G[i][i];
    }
    for (int col = 0; col < m; col++) {
        int piv = col;
        for (int r = col + 1; r < m; r++)
            if (fabs(G[r][col]) > fabs(G[piv][col])) piv = r;
        if (fabs(G[piv][col]) < 1e-12) return -1;
        for (int j = 0; j < 4; j++) {
            double t = G[col][j];
            G[col][j] = G[piv][j];
            G[piv][j] = t;
        }
        for (int r = 0; r < m; r++) {
            if (r == col) continue;
            double f = G[r][col] / G[col][col];
            for (int j = 0; j < 4; j++) G[r][j] -= f * G[col][j];
        }
    }
    for (int i = 0; i < 3; i++) {
        c[i] = s[0][i];
        for (int j = 0; j < m; j++) c[i] += G[j][3] / G[j][j] * e[j][i];
    }
    return d3(c, s[0]);
}

static double brute_radius(const double *p, size_t n) {
    double best = INFINITY;
    if (n == 1) return 0;
    for (size_t a = 0; a < n; a++)
        for (size_t b = a + 1; b < n; b++)
            for (size_t cc = b; cc < n; cc++)
                for (size_t dd = cc; dd < n; dd++) {
                    const double *s[4] = {p + 3 * a, p + 3 * b, p + 3 * cc, p + 3 * dd};
                    int k = cc == b ? 2 : (dd == cc ? 3 : 4);
                    double c[3];
                    double r = ball_through(s, k, c);
                    if (r < 0 || r >= best) continue;
                    int ok = 1;
                    for (size_t i = 0; i < n && ok; i++)
                        if (d3(c, p + 3 * i) > r * (1 + 1e-12)) ok = 0;
                    if (ok) best = r;
                }
    return best;
}

static void check_encloses(const acd_sphere *s, const double *p, size_t n) {
    for (size_t i = 0; i < n; i++) assert_true(d3(s->center, p + 3 * i) <= s->radius * (1 + 1e-15));
}

static void test_random_vs_brute_force(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 41);
    for (int trial = 0; trial < 60; trial++) {
        size_t n = 1 + (size_t)acd_rng_below(&r, 14);
        double p[3 * 16];
        int kind = trial % 4; /* 0 cube, 1 flat (z = 0), 2 on a sphere, 3 with duplicates */
        for (size_t i = 0; i < n; i++) {
            for (int k = 0; k < 3; k++) p[3 * i + k] = 2 * acd_rng_uniform(&r) - 1;
            if (kind == 1) p[3 * i + 2] = 0;
            if (kind == 2) {
                double l = d3(p + 3 * i, (double[3]){0, 0, 0});
                for (int k = 0; k < 3; k++) p[3 * i + k] /= l;
            }
            if (kind == 3 && i > 0 && i % 2 == 0) memcpy(p + 3 * i, p + 3 * (i / 2), 3 * sizeof(double));
        }
        acd_sphere s;
        acd_error err;
        assert_int_equal(acd_min_sphere(p, n, &s, &err), ACD_OK);
        check_encloses(&s, p, n);
        double rb = brute_radius(p, n);
        if (fabs(s.radius - rb) > 1e-10 * (1 + rb)) print_message("trial %d n %zu: %.17g vs brute %.17g\n", trial, n, s.radius, rb);
        assert_true(fabs(s.radius - rb) <= 1e-10 * (1 + rb));
    }
}

static void test_known_values(void **state) {
    (void)state;
    acd_sphere s;
    acd_error err;
    /* cube corners + interior: radius sqrt(3)/2 about the centre, at a far offset and scale */
    double scales[] = {1, 1e-100, 1e100};
    for (int si = 0; si < 3; si++) {
        double sc = scales[si], off = 5 * sc;
        double p[3 * 20];
        size_t n = 0;
        for (int c = 0; c < 8; c++, n++)
            for (int k = 0; k < 3; k++) p[3 * n + k] = ((c >> k) & 1) * sc + off;
        for (int i = 0; i < 12; i++, n++)
            for (int k = 0; k < 3; k++) p[3 * n + k] = (0.2 + 0.05 * i) * sc + off;
        assert_int_equal(acd_min_sphere(p, n, &s, &err), ACD_OK);
        check_encloses(&s, p, n);
        assert_true(fabs(s.radius / sc - sqrt(3) / 2) < 1e-12);
        for (int k = 0; k < 3; k++) assert_true(fabs((s.center[k] - off) / sc - 0.5) < 1e-12);
    }
    /* many points on the unit sphere plus interior points: radius 1 */
    acd_rng r;
    acd_rng_seed(&r, 42);
    size_t n = 5000;
    double *p = malloc(3 * n * sizeof *p);
    assert_non_null(p);
    for (size_t i = 0; i < n; i++) {
        double l;
        do {
            for (int k = 0; k < 3; k++) p[3 * i + k] = 2 * acd_rng_uniform(&r) - 1;
            l = d3(p + 3 * i, (double[3]){0, 0, 0});
        } while (l < 0.1 || l > 1);
        if (i % 2 == 0)
            for (int k = 0; k < 3; k++) p[3 * i + k] /= l;
    }
    assert_int_equal(acd_min_sphere(p, n, &s, &err), ACD_OK);
    check_encloses(&s, p, n);
    assert_true(s.radius <= 1 + 1e-12 && s.radius > 0.999);
    /* determinism */
    acd_sphere s2;
    assert_int_equal(acd_min_sphere(p, n, &s2, &err), ACD_OK);
    assert_memory_equal(&s, &s2, sizeof s);
    /* collinear: half the segment */
    for (size_t i = 0; i < 100; i++) {
        double t = acd_rng_uniform(&r);
        if (i == 10) t = 0;
        if (i == 50) t = 1;
        for (int k = 0; k < 3; k++) p[3 * i + k] = (double)k + t * (3.0 - 2.0 * k);
    }
    assert_int_equal(acd_min_sphere(p, 100, &s, &err), ACD_OK);
    check_encloses(&s, p, 100);
    assert_true(fabs(s.radius - 0.5 * sqrt(9 + 1 + 1)) < 1e-12);
    /* coplanar regular polygon: circumradius */
    for (size_t i = 0; i < 12; i++) {
        double a = 2 * 3.14159265358979323846 * (double)i / 12;
        p[3 * i] = 2 * cos(a);
        p[3 * i + 1] = 2 * sin(a);
        p[3 * i + 2] = 7;
    }
    assert_int_equal(acd_min_sphere(p, 12, &s, &err), ACD_OK);
    assert_true(fabs(s.radius - 2) < 1e-12 && fabs(s.center[2] - 7) < 1e-12);
    /* single point, all duplicates */
    double one[6] = {1, 2, 3, 1, 2, 3};
    assert_int_equal(acd_min_sphere(one, 2, &s, &err), ACD_OK);
    assert_true(s.radius == 0 && s.center[0] == 1 && s.center[2] == 3);
    free(p);
}

static void test_bad_input(void **state) {
    (void)state;
    acd_sphere s;
    acd_error err;
    double p[6] = {0, 0, 0, INFINITY, 0, 0};
    assert_int_equal(acd_min_sphere(p, 0, &s, &err), ACD_ERR_DEGENERATE);
    assert_int_equal(acd_min_sphere(p, 2, &s, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "point 1"));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_vs_brute_force),
        cmocka_unit_test(test_known_values),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
