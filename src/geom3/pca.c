/* geom3/pca: weighted PCA and the cyclic Jacobi eigenvalue method for symmetric 3x3 matrices
 * (Jacobi 1846; Golub and Van Loan §8.5). Used for ACD's cut-plane fit (Lien D §V.B.3, Eqn 5.3;
 * P §4.3, Eqn 5). Jacobi is chosen over the closed-form cubic because it stays accurate for repeated
 * and tiny eigenvalues (flat or collinear samples), where the trigonometric formula loses digits. */
#include "geom3/pca.h"

#include <math.h>
#include <string.h>

#include "core/error.h"

#define JACOBI_MAX_SWEEPS 64

void acd_eigen_sym3(const double a[3][3], double values[3], double vectors[3][3]) {
    double m[3][3], v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    /* scale by the largest entry so squares neither overflow nor underflow */
    double scale = 0;
    for (int i = 0; i < 3; i++)
        for (int j = i; j < 3; j++)
            if (fabs(a[i][j]) > scale) scale = fabs(a[i][j]);
    if (!(scale > 0)) scale = 1;
    for (int i = 0; i < 3; i++)
        for (int j = i; j < 3; j++) m[i][j] = m[j][i] = a[i][j] / scale;
    for (int sweep = 0; sweep < JACOBI_MAX_SWEEPS; sweep++) {
        double off = fabs(m[0][1]) + fabs(m[0][2]) + fabs(m[1][2]);
        if (off == 0) break; /* diagonal */
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++) {
                double apq = m[p][q];
                if (apq == 0) continue;
                /* negligible next to both diagonal entries (relative, per entry): drop it. This keeps
                 * tiny eigenvalues accurate, unlike a threshold relative to the whole matrix. */
                if (sweep > 3 && fabs(m[p][p]) + 100 * fabs(apq) == fabs(m[p][p]) &&
                    fabs(m[q][q]) + 100 * fabs(apq) == fabs(m[q][q])) {
                    m[p][q] = m[q][p] = 0;
                    continue;
                }
                double theta = (m[q][q] - m[p][p]) / (2 * apq);
                double t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1));
                if (!isfinite(theta)) t = 1 / (2 * theta); /* |theta| overflowed: t ~ 1/(2 theta) */
                double c = 1 / sqrt(t * t + 1), s = t * c;
                for (int k = 0; k < 3; k++) { /* columns p, q */
                    double mkp = m[k][p], mkq = m[k][q];
                    m[k][p] = c * mkp - s * mkq;
                    m[k][q] = s * mkp + c * mkq;
                }
                for (int k = 0; k < 3; k++) { /* rows p, q */
                    double mpk = m[p][k], mqk = m[q][k];
                    m[p][k] = c * mpk - s * mqk;
                    m[q][k] = s * mpk + c * mqk;
                }
                m[p][q] = m[q][p] = 0;
                for (int k = 0; k < 3; k++) {
                    double vkp = v[k][p], vkq = v[k][q];
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
    }
    int order[3] = {0, 1, 2};
    for (int i = 0; i < 3; i++) /* sort decreasing, stable on ties */
        for (int j = i + 1; j < 3; j++)
            if (m[order[j]][order[j]] > m[order[i]][order[i]]) {
                int x = order[i];
                order[i] = order[j];
                order[j] = x;
            }
    for (int i = 0; i < 3; i++) {
        values[i] = m[order[i]][order[i]] * scale;
        double nrm = 0;
        for (int k = 0; k < 3; k++) {
            vectors[i][k] = v[k][order[i]];
            nrm += vectors[i][k] * vectors[i][k];
        }
        nrm = sqrt(nrm);
        for (int k = 0; k < 3; k++) vectors[i][k] /= nrm;
    }
    for (int i = 0; i < 2; i++) {
        int big = 0;
        for (int k = 1; k < 3; k++)
            if (fabs(vectors[i][k]) > fabs(vectors[i][big])) big = k;
        if (vectors[i][big] < 0)
            for (int k = 0; k < 3; k++) vectors[i][k] = -vectors[i][k];
    }
    const double *x = vectors[0], *y = vectors[1];
    double z[3] = {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
    double zn = sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
    for (int k = 0; k < 3; k++) vectors[2][k] = z[k] / zn;
}

acd_status acd_pca_points(const double *points, size_t n, const double *weights, acd_pca *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    if (n == 0) return acd_fail(err, ACD_ERR_DEGENERATE, "pca: no points");
    double wsum = 0, c[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++) {
        const double *p = points + 3 * i;
        double w = weights ? weights[i] : 1.0;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "pca: point %zu has a non-finite coordinate (%g, %g, %g)", i, p[0],
                            p[1], p[2]);
        if (!(w >= 0) || !isfinite(w))
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "pca: point %zu has weight %g (must be finite, >= 0)", i, w);
        wsum += w;
        for (int k = 0; k < 3; k++) c[k] += w * p[k];
    }
    if (!(wsum > 0)) return acd_fail(err, ACD_ERR_DEGENERATE, "pca: the %zu weights sum to zero", n);
    for (int k = 0; k < 3; k++) c[k] /= wsum;
    /* second pass: correct the centroid (compensated mean), then the covariance about it */
    double corr[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++) {
        double w = weights ? weights[i] : 1.0;
        for (int k = 0; k < 3; k++) corr[k] += w * (points[3 * i + k] - c[k]);
    }
    for (int k = 0; k < 3; k++) c[k] += corr[k] / wsum;
    double cov[3][3] = {{0}};
    for (size_t i = 0; i < n; i++) {
        double w = weights ? weights[i] : 1.0;
        double d[3] = {points[3 * i] - c[0], points[3 * i + 1] - c[1], points[3 * i + 2] - c[2]};
        for (int r = 0; r < 3; r++)
            for (int s = r; s < 3; s++) cov[r][s] += w * d[r] * d[s];
    }
    for (int r = 0; r < 3; r++)
        for (int s = r; s < 3; s++) cov[r][s] /= wsum;
    for (int r = 0; r < 3; r++)
        for (int s = 0; s < r; s++) cov[r][s] = cov[s][r];
    for (int r = 0; r < 3; r++)
        for (int s = r; s < 3; s++)
            if (!isfinite(cov[r][s]))
                return acd_fail(err, ACD_ERR_INVALID_INPUT, "pca: covariance overflows (coordinates too large)");
    memcpy(out->centroid, c, sizeof c);
    out->total_weight = wsum;
    acd_eigen_sym3((const double(*)[3])cov, out->values, out->axes);
    return ACD_OK;
}
