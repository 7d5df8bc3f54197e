/* acd/eval.h: the yardstick for 3D decompositions (ours or a peer's): how well the union of the
 * parts' convex hulls matches the mesh. Method and accuracy: docs/eval.md.
 *
 * Usage:
 *   acd_eval_params prm = acd_eval_default_params();
 *   acd_eval_report rep;
 *   if (acd_eval_parts(&mesh, &parts, &prm, &rep, &err) == ACD_OK) { ... }
 *
 * Figures (all distances divided by the mesh's bounding-box diagonal):
 *  - volumes: mesh (divergence theorem, exact up to rounding), sum of hull volumes (exact),
 *    union of hulls (Monte Carlo); IoU |M n U| / |M u U|, coverage |M n U| / |M|,
 *    excess |U \ M| / |M| from the same stratified samples (fixed seed: deterministic).
 *  - the two-sided distance between the mesh surface and the boundary of the union of hulls:
 *    max and mean from the mesh to the union's boundary and back; concavity_max the larger max. */
#ifndef ACD_EVAL_H
#define ACD_EVAL_H

#include "acd/base.h"
#include "acd/hull.h"
#include "acd/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ACD_EVAL_PARAMS_COOKIE 0x41434445u

typedef struct acd_eval_params {
    uint32_t cookie;          /* set by acd_eval_default_params */
    size_t samples;           /* volume samples (stratified grid, one per cell); default 1000000 */
    size_t surface_samples;   /* points on the mesh surface and candidate points on the hulls'
                                 surfaces, each; default 200000 */
    uint64_t seed;            /* default 1 */
    acd_progress_fn progress; /* optional; may cancel */
    void *progress_user;
} acd_eval_params;

acd_eval_params acd_eval_default_params(void);

typedef struct acd_eval_report {
    size_t parts;              /* parts given */
    size_t degenerate_parts;   /* parts whose hull is flat (dim < 3): no volume, left out of the union */
    size_t hull_vertices;      /* sum over the parts of their hull's vertex count */
    double mesh_volume;        /* |signed volume| of the mesh */
    double hull_volume_sum;
    double union_volume;       /* Monte Carlo */
    double iou, coverage, excess;
    double mesh_to_hulls_max, mesh_to_hulls_mean; /* mesh surface -> boundary of the union */
    double hulls_to_mesh_max, hulls_to_mesh_mean; /* boundary of the union -> mesh surface */
    double concavity_max;      /* max of the two maxima */
    double diagonal;           /* the mesh's bounding-box diagonal (the unit of the distances) */
    double boundary_spacing;   /* mean spacing of the samples of the union's boundary (relative):
                                  the error bound of the distances not computed exactly */
    size_t inexact_distances;  /* mesh points whose distance used the boundary samples */
    size_t samples;            /* volume samples actually taken */
    size_t surface_samples;
    size_t boundary_samples;   /* hull-surface samples found on the union's boundary */
    uint64_t seed;
    int mesh_closed;           /* 1: exact inside test (ray crossings), 0: generalized winding number */
    double seconds;
} acd_eval_report;

/* Scores the decomposition `parts` of `mesh`: the convex hull of each part's vertices is taken.
 * Fails on an empty mesh or one enclosing no volume (ACD_ERR_DEGENERATE), bad indices or
 * non-finite coordinates or coordinates beyond 1e60 in the mesh or the parts (ACD_ERR_INVALID_INPUT),
 * no part with a solid hull (ACD_ERR_DEGENERATE). */
acd_status acd_eval_parts(const acd_mesh *mesh, const acd_mesh_parts *parts, const acd_eval_params *params,
                          acd_eval_report *out, acd_error *err);

/* The same with the hulls given (dim < 3 hulls count as degenerate parts). */
acd_status acd_eval_hulls(const acd_mesh *mesh, const acd_hull *hulls, size_t nhulls, const acd_eval_params *params,
                          acd_eval_report *out, acd_error *err);

/* The report as JSON text (the keys of `acd eval --json`, docs/eval.md); malloc'd, caller frees. */
acd_status acd_eval_report_json(const acd_eval_report *r, char **json, acd_error *err);

#ifdef __cplusplus
}
#endif
#endif
