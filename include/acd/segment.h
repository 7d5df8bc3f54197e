/* acd/segment.h: mesh segmentation (CoRiSe) and segmentation benchmark metrics.
 *
 * A segmentation of a triangle mesh is one integer label per triangle, in triangle order (the
 * Princeton Segmentation Benchmark's .seg convention); equal labels = same segment. */
#ifndef ACD_SEGMENT_H
#define ACD_SEGMENT_H

#include "acd/base.h"
#include "acd/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* =========================================================================================
 * Segmentation benchmark metrics (helper maxflow; src/corise/segeval.c, docs/segeval.md)
 *
 * The four metrics of X. Chen, A. Golovinskiy, T. Funkhouser, "A benchmark for 3D mesh
 * segmentation", ACM TOG 28(3) 2009, §4: Rand index, Hamming distance (missing and false-alarm
 * rates), global and local consistency error, cut discrepancy. A is the segmentation being
 * evaluated (S1), B the reference (S2, e.g. a human segmentation). All region metrics weight
 * each face by its area (default) or by 1 (face counts). */

typedef enum acd_segeval_weighting {
    ACD_SEGEVAL_WEIGHT_AREA = 0, /* face areas (default) */
    ACD_SEGEVAL_WEIGHT_FACES = 1 /* every face counts 1 */
} acd_segeval_weighting;

typedef struct acd_segeval_options {
    acd_segeval_weighting weighting;
} acd_segeval_options;

/* Defaults: area weighting. */
acd_segeval_options acd_segeval_default_options(void);

typedef struct acd_segeval_result {
    size_t nfaces;
    size_t nsegments_a, nsegments_b; /* distinct labels */
    double total_weight;             /* W: total area, or the face count */
    /* Rand index in [0, 1]: 1 when A and B group every pair of faces alike. The benchmark
     * reports 1 - RI. */
    double rand_index;
    /* Hamming distance: missing rate Rm = D_H(A=>B)/W, false-alarm rate Rf = D_H(B=>A)/W,
     * hamming = (Rm + Rf)/2; each in [0, 1]. */
    double hamming, hamming_rm, hamming_rf;
    /* Consistency errors in [0, 1]; both 0 when one segmentation refines the other. */
    double gce, lce;
    /* Cut discrepancy (needs the mesh; undefined when A or B has no cut edge, or no cut point
     * of one reaches the other's cut along the mesh edges):
     *   cut_discrepancy        = (DCD(A=>B) + DCD(B=>A)) / avg_radius   (the paper's formula)
     *   cut_discrepancy_pooled = (sum d_AB + sum d_BA) / (ncut_a + ncut_b) / avg_radius
     *                            (the pooled mean of the benchmark's distributed program)
     * DCD(X=>Y) is the mean over the cut vertices of X of the shortest-path distance along the
     * mesh edges to the nearest cut vertex of Y. avg_radius is the area-weighted mean distance
     * of the face centroids to the area-weighted centroid of the surface. */
    int cd_defined;
    double cut_discrepancy, cut_discrepancy_pooled;
    double dcd_ab, dcd_ba; /* in mesh units */
    double avg_radius;
    size_t ncut_a, ncut_b;   /* cut vertices of A and B */
    size_t cd_unreachable;   /* cut vertices that cannot reach the other cut (left out) */
} acd_segeval_result;

/* Region metrics only (Rand index, Hamming, GCE, LCE) from two labellings of n faces; weights:
 * n finite values >= 0 with a positive sum, or NULL for face counts. The cut-discrepancy fields
 * are left undefined (cd_defined = 0). */
acd_status acd_segeval_regions(const int *a, const int *b, size_t n, const double *weights,
                               acd_segeval_result *out, acd_error *err);

/* All metrics for two labellings of m's triangles (m->ntriangles labels each). opts may be
 * NULL (defaults). A mesh with zero total area is ACD_ERR_DEGENERATE under area weighting. */
acd_status acd_segeval(const acd_mesh *m, const int *a, const int *b, const acd_segeval_options *opts,
                       acd_segeval_result *out, acd_error *err);

/* ========================================================================================= */

#ifdef __cplusplus
}
#endif
#endif
