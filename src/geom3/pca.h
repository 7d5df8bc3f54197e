/* geom3/pca: principal component analysis of 3D points and a robust symmetric 3x3 eigen-solver.
 *
 * ACD fits the cut plane of a cut loop by PCA on points sampled along it: normal = eigenvector of
 * the smallest eigenvalue, plane through the (weighted) centroid (Lien D §V.B.3, Eqn 5.3; P §4.3). */
#ifndef ACD_GEOM3_PCA_H
#define ACD_GEOM3_PCA_H

#include <stddef.h>

#include "acd/base.h"

/* Eigen-decomposition of the symmetric matrix a (only a[i][j], i <= j, are read) by cyclic Jacobi
 * rotations. values in decreasing order; vectors[i] is the unit eigenvector of values[i]; the signs
 * are fixed: the largest-magnitude component of vectors[0] and vectors[1] is positive (the first one
 * on ties) and vectors[2] = vectors[0] x vectors[1] (a right-handed frame). Entries must be finite. */
void acd_eigen_sym3(const double a[3][3], double values[3], double vectors[3][3]);

typedef struct acd_pca {
    double centroid[3];   /* weighted mean */
    double values[3];     /* eigenvalues of the weighted covariance, decreasing */
    double axes[3][3];    /* axes[i]: unit eigenvector of values[i]; axes[2] is the best-fit plane normal */
    double total_weight;
} acd_pca;

/* PCA of n points (3 doubles each) with optional weights (n doubles, finite, >= 0; NULL: all 1).
 * The covariance is sum w (p - c)(p - c)^T / sum w, computed in two passes about the centroid.
 * ACD_ERR_INVALID_INPUT for NaN/Inf or negative weights, ACD_ERR_DEGENERATE for n = 0 or a zero total
 * weight. */
acd_status acd_pca_points(const double *points, size_t n, const double *weights, acd_pca *out, acd_error *err);

#endif
