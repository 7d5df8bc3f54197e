/* Tests of geom3/pca: Jacobi eigen-solver against matrices built from known eigenpairs (including
 * repeated, zero, tiny and huge eigenvalues), A v = lambda v residuals, orthonormality, sign
 * convention, and PCA of points on known planes/lines with weights. */
#include "testutil.h"

#include <math.h>
#include <string.h>

#include "core/rng.h"
#include "geom3/pca.h"

/* A random rotation from a random unit quaternion. */
static void random_rotation(acd_rng *r, double R[3][3]) {
    double q[4], n = 0;
    for (int i = 0; i < 4; i++) {
        q[i] = 2 * acd_rng_uniform(r) - 1;
        n += q[i] * q[i];
    }
    n = sqrt(n);
    for (int i = 0; i < 4; i++) q[i] /= n;
    double w = q[0], x = q[1], y = q[2], z = q[3];
    double M[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                      {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                      {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    memcpy(R, M, sizeof M);
}

static void check_decomposition(const double A[3][3], const double val[3], const double vec[3][3]) {
    double norm = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) norm = fmax(norm, fabs(A[i][j]));
    for (int i = 0; i < 3; i++) {
        if (i > 0) assert_true(val[i - 1] >= val[i]);
        for (int r = 0; r < 3; r++) { /* A v - lambda v */
            double av = A[r][0] * vec[i][0] + A[r][1] * vec[i][1] + A[r][2] * vec[i][2];
            assert_true(fabs(av - val[i] * vec[i][r]) <= 1e-13 * (norm > 0 ? norm : 1));
        }
        for (int j = 0; j < 3; j++) {
            double d = vec[i][0] * vec[j][0] + vec[i][1] * vec[j][1] + vec[i][2] * vec[j][2];
            assert_true(fabs(d - (i == j)) < 1e-14);
        }
    }
    /* right-handed */
    const double *x = vec[0], *y = vec[1], *z = vec[2];
    double det = x[0] * (y[1] * z[2] - y[2] * z[1]) - x[1] * (y[0] * z[2] - y[2] * z[0]) + x[2] * (y[0] * z[1] - y[1] * z[0]);
    assert_true(fabs(det - 1) < 1e-14);
}

static void test_eigen_known(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 31);
    double spectra[][3] = {{3, 2, 1},     {5, 5, 1},         {1, 1, 1},      {2, 0, 0},         {1, 1e-12, 0},
                           {7, -2, -9},   {1e200, 1, 1e-200}, {1e-300, 5e-301, 0}, {4, 4, 4e-15}, {0, 0, 0}};
    for (size_t si = 0; si < sizeof spectra / sizeof spectra[0]; si++)
        for (int rep = 0; rep < 20; rep++) {
            double R[3][3], A[3][3], val[3], vec[3][3];
            random_rotation(&r, R);
            const double *l = spectra[si];
            for (int i = 0; i < 3; i++) /* A = R diag(l) R^T */
                for (int j = 0; j < 3; j++) A[i][j] = R[i][0] * l[0] * R[j][0] + R[i][1] * l[1] * R[j][1] + R[i][2] * l[2] * R[j][2];
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < i; j++) A[i][j] = A[j][i] = 0.5 * (A[i][j] + A[j][i]);
            acd_eigen_sym3((const double(*)[3])A, val, vec);
            double sorted[3] = {l[0], l[1], l[2]};
            for (int i = 0; i < 3; i++)
                for (int j = i + 1; j < 3; j++)
                    if (sorted[j] > sorted[i]) {
                        double t = sorted[i];
                        sorted[i] = sorted[j];
                        sorted[j] = t;
                    }
            double big = fmax(fabs(sorted[0]), fabs(sorted[2]));
            for (int i = 0; i < 3; i++) assert_true(fabs(val[i] - sorted[i]) <= 1e-14 * (big > 0 ? big : 1));
            check_decomposition((const double(*)[3])A, val, (const double(*)[3])vec);
            /* sign convention */
            for (int i = 0; i < 2; i++) {
                int b = 0;
                for (int k = 1; k < 3; k++)
                    if (fabs(vec[i][k]) > fabs(vec[i][b])) b = k;
                assert_true(vec[i][b] > 0);
            }
            /* a simple eigenvalue's vector matches the rotation's column up to sign */
            if (sorted[0] > sorted[1] * (1 + 1e-6) + 1e-300 && si != 6 && si != 7) {
                int col = l[0] == sorted[0] ? 0 : (l[1] == sorted[0] ? 1 : 2);
                double d = fabs(vec[0][0] * R[0][col] + vec[0][1] * R[1][col] + vec[0][2] * R[2][col]);
                assert_true(fabs(d - 1) < 1e-12);
            }
        }
    /* diagonal and already-sorted inputs */
    double D[3][3] = {{1, 0, 0}, {0, 3, 0}, {0, 0, 2}}, val[3], vec[3][3];
    acd_eigen_sym3((const double(*)[3])D, val, vec);
    assert_true(val[0] == 3 && val[1] == 2 && val[2] == 1);
    assert_true(vec[0][1] == 1 && vec[1][2] == 1 && fabs(vec[2][0]) == 1);
}

static void test_pca_plane_and_line(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 32);
    double n[3] = {1, -2, 2}; /* |n| = 3 */
    double u[3] = {2, 1, 0}, v[3] = {-2, 4, 5};  /* both orthogonal to n */
    double o[3] = {1e6, -3e6, 2e6};
    size_t N = 500;
    double pts[3 * 500], wts[500];
    for (size_t i = 0; i < N; i++) {
        double a = acd_rng_uniform(&r) - 0.5, b = acd_rng_uniform(&r) - 0.5;
        for (int k = 0; k < 3; k++) pts[3 * i + k] = o[k] + 30 * a * u[k] + 3 * b * v[k];
        wts[i] = acd_rng_uniform(&r);
    }
    acd_pca p;
    acd_error err;
    assert_int_equal(acd_pca_points(pts, N, NULL, &p, &err), ACD_OK);
    double dn = fabs(p.axes[2][0] * n[0] + p.axes[2][1] * n[1] + p.axes[2][2] * n[2]) / 3;
    assert_true(fabs(dn - 1) < 1e-12);
    assert_true(p.values[2] < 1e-12 * p.values[0]);
    assert_true(p.total_weight == (double)N);
    /* centroid equals the mean of the points (plane offset) */
    double mean[3] = {0, 0, 0};
    for (size_t i = 0; i < N; i++)
        for (int k = 0; k < 3; k++) mean[k] += pts[3 * i + k] / (double)N;
    for (int k = 0; k < 3; k++) assert_true(fabs(p.centroid[k] - mean[k]) < 1e-6);
    /* weighted: the same plane */
    assert_int_equal(acd_pca_points(pts, N, wts, &p, &err), ACD_OK);
    dn = fabs(p.axes[2][0] * n[0] + p.axes[2][1] * n[1] + p.axes[2][2] * n[2]) / 3;
    assert_true(fabs(dn - 1) < 1e-12);
    /* the much longer u direction is the first axis */
    double du = fabs(p.axes[0][0] * u[0] + p.axes[0][1] * u[1] + p.axes[0][2] * u[2]) / sqrt(5);
    assert_true(du > 0.99);
    /* points on a line: one non-zero eigenvalue */
    for (size_t i = 0; i < N; i++) {
        double a = acd_rng_uniform(&r);
        for (int k = 0; k < 3; k++) pts[3 * i + k] = o[k] + a * v[k];
    }
    assert_int_equal(acd_pca_points(pts, N, NULL, &p, &err), ACD_OK);
    assert_true(p.values[1] < 1e-12 * p.values[0]);
    double dv = fabs(p.axes[0][0] * v[0] + p.axes[0][1] * v[1] + p.axes[0][2] * v[2]) / sqrt(45);
    assert_true(fabs(dv - 1) < 1e-12);
    /* a known covariance: the 8 corners of a box with sides 2, 4, 6 */
    double box[24];
    for (int c = 0; c < 8; c++) {
        box[3 * c] = (c & 1) ? 1 : -1;
        box[3 * c + 1] = (c & 2) ? 2 : -2;
        box[3 * c + 2] = (c & 4) ? 3 : -3;
    }
    assert_int_equal(acd_pca_points(box, 8, NULL, &p, &err), ACD_OK);
    assert_true(fabs(p.values[0] - 9) < 1e-14 && fabs(p.values[1] - 4) < 1e-14 && fabs(p.values[2] - 1) < 1e-14);
    assert_true(fabs(fabs(p.axes[0][2]) - 1) < 1e-15 && fabs(fabs(p.axes[2][0]) - 1) < 1e-15);
    /* weights concentrate: zero weight points are ignored */
    double w8[8] = {1, 0, 0, 0, 0, 0, 0, 1};
    assert_int_equal(acd_pca_points(box, 8, w8, &p, &err), ACD_OK);
    assert_true(fabs(p.values[0] - 14) < 1e-13 && fabs(p.values[1]) < 1e-13);
}

static void test_pca_bad_input(void **state) {
    (void)state;
    acd_pca p;
    acd_error err;
    double pts[6] = {0, 0, 0, 1, NAN, 0};
    assert_int_equal(acd_pca_points(pts, 0, NULL, &p, &err), ACD_ERR_DEGENERATE);
    assert_int_equal(acd_pca_points(pts, 2, NULL, &p, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "point 1"));
    pts[4] = 0;
    double w[2] = {0, 0};
    assert_int_equal(acd_pca_points(pts, 2, w, &p, &err), ACD_ERR_DEGENERATE);
    w[1] = -1;
    assert_int_equal(acd_pca_points(pts, 2, w, &p, &err), ACD_ERR_INVALID_INPUT);
    double one[3] = {1, 2, 3};
    assert_int_equal(acd_pca_points(one, 1, NULL, &p, &err), ACD_OK);
    assert_true(p.values[0] == 0 && p.centroid[2] == 3);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_eigen_known),
        cmocka_unit_test(test_pca_plane_and_line),
        cmocka_unit_test(test_pca_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
