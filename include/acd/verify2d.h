/* acd/verify2d.h: independent check of a 2D decomposition (spec ../shared/spec/acd2d.md §12).
 *
 * Rechecks, without using the decomposition code, that a list of components is a partition of
 * a polygon with holes into pieces whose concavity is within tau:
 *   - every component has >= 3 finite points, is counterclockwise (positive area) and has no
 *     two edges crossing properly (touching and overlapping edges, as in the zero-width slits
 *     left by hole merges, are allowed);
 *   - every component lies inside the input (no edge crosses the input's boundary, no point of
 *     a component outside it, no point of the input's boundary inside a component);
 *   - the components' interiors are pairwise disjoint (no crossing edges, no point of one
 *     strictly inside another, no duplicated component);
 *   - the components' areas (compensated sums) add up to the input's area within
 *     area_rel_tol (1e-9) relative. With the two checks above this means their union is the
 *     input: a missing piece shows as an area deficit;
 *   - the concavity of every component, recomputed by a separate straightforward
 *     implementation of the measure (SL: distance to the bridge line; SP: shortest path to the
 *     bridge inside the pocket by Dijkstra over the pocket's visibility graph; H1, H2: the
 *     hazard rule of §3.3), is at most tau (plus ACD_TOL_REL_DIST times the input's extent).
 *
 * Exact predicates decide sides and crossings; points computed by the decomposition (Steiner
 * points) may be off the segment they were cut from by rounding, so a point within
 * max(ACD_TOL_REL_DIST x extent, 4 DBL_EPSILON x the largest coordinate magnitude) of the
 * input's boundary counts as on it (the second term: far from the origin no double lies nearer);
 * between two components only ACD_TOL_REL_DIST x extent (cut ends must be shared exactly).
 * Points exactly on an edge, and edge pieces exactly along one, are recognized exactly.
 * Pairs of components are found with a bounding-box grid and edges with per-component
 * y-buckets, so thousands of components are checked in near-linear time. */
#ifndef ACD_VERIFY2D_H
#define ACD_VERIFY2D_H

#include "acd/acd2d.h"
#include "acd/base.h"
#include "acd/polygon.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Which check failed (the first one found, in the order listed). */
typedef enum acd_verify2d_check {
    ACD_V2D_PASS = 0,
    ACD_V2D_INVALID,           /* fewer than 3 points or a non-finite coordinate */
    ACD_V2D_CLOCKWISE,         /* not counterclockwise: signed area <= 0 */
    ACD_V2D_SELF_INTERSECTION, /* two edges of one component cross */
    ACD_V2D_OUTSIDE,           /* a component reaches outside the input */
    ACD_V2D_OVERLAP,           /* two components' interiors intersect */
    ACD_V2D_AREA,              /* the areas do not add up: part of the input is not covered */
    ACD_V2D_HULL,              /* a reported hull is not convex or does not enclose its component */
    ACD_V2D_CONCAVITY          /* concavity above tau */
} acd_verify2d_check;

/* Static name of a check ("clockwise", "overlap", ...). */
const char *acd_verify2d_check_name(acd_verify2d_check c);

typedef struct acd_verify2d_options {
    double tau;               /* concavity bound, model units (default 0) */
    acd2d_measure measure;    /* measure for the concavity check (default SL) */
    double notch_tolerance;   /* a vertex is a notch when (v-u)x(w-v) < -notch_tolerance; 0 = exact
                                 (default 1e-5, as acd2d_default_params) */
    double area_rel_tol;      /* relative tolerance of the area sum (default ACD_TOL_REL_MEASURE = 1e-9) */
    int check_concavity;      /* non-zero: check the tau bound (default 1) */
    size_t component_base;    /* number of the first component in messages (default 0) */
} acd_verify2d_options;

acd_verify2d_options acd_verify2d_default_options(void);

typedef struct acd_verify2d_report {
    acd_verify2d_check failed;  /* ACD_V2D_PASS when everything holds */
    long component;             /* first component involved in the failure (local index), or -1 */
    long other;                 /* second component (overlap), or -1 */
    double input_area;          /* compensated area of the input */
    double components_area;     /* compensated sum of the components' areas */
    double max_concavity;       /* recomputed, over all components checked (0 if not checked) */
    long max_concavity_component;
    size_t pairs_checked;       /* component pairs whose bounding boxes meet */
} acd_verify2d_report;

/* Checks that components[0..count-1] (component i has sizes[i] points, counterclockwise, first
 * point not repeated) decompose `input` (normalized: outer ring CCW, holes CW). `opt` may be
 * NULL (defaults); `report` may be NULL. Returns ACD_OK when every check passes,
 * ACD_ERR_VERIFY with a message naming the failing component (and where) otherwise,
 * ACD_ERR_NOMEM or ACD_ERR_INVALID_ARGUMENT. */
acd_status acd_verify2d(const acd_polygon *input, const acd_vec2 *const *components, const size_t *sizes,
                        size_t count, const acd_verify2d_options *opt, acd_verify2d_report *report,
                        acd_error *err);

/* Same for an acd2d_result: tau and measure from the result, notch tolerance from params (may be
 * NULL: default), and additionally that every reported hull is convex, counterclockwise and
 * encloses its component. */
acd_status acd_verify2d_result(const acd_polygon *input, const acd2d_result *res, const acd2d_params *params,
                               size_t component_base, acd_verify2d_report *report, acd_error *err);

/* The verifier's own concavity of a simple counterclockwise polygon (no holes): the maximum,
 * over its notches, of the vertex concavity under measure m (tau is used by H2 only).
 * `witness` (may be NULL) receives the vertex attaining it (n if there is no notch, value 0).
 * Returns a negative value when out of memory. O(n log n) for SL; SP is O(k^2 * k) per pocket
 * of k vertices in the worst case. */
double acd_verify2d_concavity(const acd_vec2 *pts, size_t n, acd2d_measure m, double tau,
                              double notch_tolerance, size_t *witness);

#ifdef __cplusplus
}
#endif
#endif
