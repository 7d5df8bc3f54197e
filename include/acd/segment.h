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

/* =========================================================================================
 * Nearly convex segmentation, CoRiSe (G. Liu, Z. Xi, J.-M. Lien, "Nearly convex segmentation of
 * polyhedra through convex ridge separation", CAD 2016; src/corise/, docs/corise.md)
 *
 * Usage:
 *   acd_segment_params prm = acd_segment_default_params();
 *   prm.tau = 0.1;                        // in units of the bounding sphere's radius
 *   acd_segment_result res;
 *   if (acd_segment(&mesh, &prm, &res, &err) == ACD_OK) { ...; acd_segment_result_free(&res); }
 */

#define ACD_SEGMENT_PARAMS_COOKIE 0x41435347u

typedef struct acd_segment_params {
    uint32_t cookie;          /* set by acd_segment_default_params; guards against uninitialized params */
    double tau;               /* valley concavity tolerance, relative to the radius of the bounding
                                 sphere (AABB centre, farthest used vertex); default 0.1 */
    double alpha;             /* Eq. 8 weight of the dihedral term against the length term (default 0.8) */
    double concave_weight;    /* Theta of a concave edge in Eq. 8 (convex edges 1; default 0.3) */
    int clamp_hull_depth;     /* not in the paper: cap each valley point's concavity by its depth
                                 below the hull (docs/corise.md, default and why) */
    size_t max_depth;         /* safety cap on nested cuts (default 64) */
    int threads;              /* OpenMP threads, 0: as many as cores; default 1 (on the shared 2-core
                                 machine 2 threads were slower: docs/corise.md, "Speed"); the
                                 output is the same for any count */
    int prepare;              /* 1 (default): the mesh is prepared first (docs/corise.md, "Input
                                 preparation"): an open mesh with vertices at the same coordinates
                                 (a triangle soup, split texture seams) is welded, then faces are
                                 flipped to agree with their neighbours, closed parts outward
                                 (cavities inward), open parts as most of their faces; faces keep
                                 their order and count. What was done is in the result
                                 (vertices_merged, faces_flipped). 0: segmented as given (concave
                                 edges decided from the given orientation: an inward-facing closed
                                 mesh is segmented as the space around it) */
    acd_progress_fn progress; /* optional; may cancel. Called from the calling thread only: at
                                 milestones (stage "corise") and polled within the steps (stages
                                 "segment: ...", "corise: ..."; docs/corise.md "Progress and
                                 cancellation") */
    void *progress_user;
} acd_segment_params;

acd_segment_params acd_segment_default_params(void);

typedef struct acd_segment_part {
    size_t nfaces;            /* faces labelled with this part */
    double concavity;         /* largest valley concavity of the part, model units */
    double concavity_rel;     /* the same relative to the bounding sphere's radius (compare with tau) */
    acd_mesh hull;            /* convex hull of the part's vertices (acd_hull_compute), outward
                                 triangles; empty when the part is flat (hull_dim < 3) */
    int hull_dim;             /* affine dimension of the part's vertices */
    double hull_volume;       /* volume of hull (0 when flat) */
    double area;              /* surface area of the part's faces */
} acd_segment_part;

typedef struct acd_segment_result {
    uint32_t *labels;         /* nfaces entries: the part of each face, 0 .. nparts-1, parts numbered
                                 by their smallest face */
    size_t nfaces;
    acd_segment_part *parts;
    size_t nparts;
    double tau;               /* relative, as given */
    double scale;             /* radius of the bounding sphere (model units per relative unit) */
    double mesh_volume;       /* signed volume of the input (divergence theorem; meaningful when closed) */
    double hull_volume;       /* sum of the parts' hull volumes */
    size_t cuts;              /* parts that were split */
    size_t depth;             /* deepest nesting of cuts */
    size_t unresolved;        /* parts left deeper than tau (a cut could not split them, or max_depth) */
    double seconds;           /* wall-clock time of acd_segment */
    /* The mesh as segmented (params.prepare): the input's faces in the input's order (labels[f]
     * is face f's), welded when vertices_merged > 0 (vertices renumbered in order of first use),
     * with faces_flipped faces reversed; an exact copy of the input when both are 0. The volumes,
     * areas and hulls above are of it; pass it (not the input) to acd_cage_from_segment or to
     * any check that depends on the orientation or the shared vertices. Freed with the result. */
    acd_mesh mesh;
    size_t vertices_merged;     /* vertices merged into others at the same coordinates (0: not welded) */
    size_t faces_flipped;       /* faces reversed (== nfaces: the input was inside out) */
    size_t nonorientable_parts; /* parts that no orientation makes consistent (Moebius strips;
                                   oriented as far as possible) */
} acd_segment_result;

/* Segments a triangle mesh into nearly convex parts. Concave edges are decided from the faces'
 * orientation and parts are joined through shared vertices, so the mesh is first welded and
 * oriented (params.prepare; result.mesh is the mesh segmented, result.vertices_merged and
 * result.faces_flipped say what changed). Every face gets a label; parts are edge-connected. out is caller-owned, freed with acd_segment_result_free (also safe after a
 * failure). Bad params: ACD_ERR_INVALID_ARGUMENT; no faces: ACD_ERR_DEGENERATE; indices out of
 * range, non-finite coordinates or coordinates beyond 1e60: ACD_ERR_INVALID_INPUT. */
acd_status acd_segment(const acd_mesh *mesh, const acd_segment_params *params, acd_segment_result *out,
                       acd_error *err);
void acd_segment_result_free(acd_segment_result *r);

/* ========================================================================================= */

#ifdef __cplusplus
}
#endif
#endif
