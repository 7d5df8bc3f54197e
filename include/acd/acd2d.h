/* acd/acd2d.h: approximate convex decomposition of polygons with holes
 * (Lien, dissertation Ch. IV; spec ../shared/spec/acd2d.md).
 *
 * Usage:
 *   acd2d_params prm = acd2d_default_params();
 *   prm.tau = 0.5;
 *   acd2d_result res;
 *   if (acd2d_decompose(&poly, &prm, &res, &err) == ACD_OK) { ...; acd2d_result_free(&res); }
 */
#ifndef ACD_ACD2D_H
#define ACD_ACD2D_H

#include "acd/base.h"
#include "acd/polygon.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum acd2d_measure {
    ACD2D_MEASURE_SL = 0, /* straight-line distance to the bridge */
    ACD2D_MEASURE_SP,     /* shortest path to the bridge inside the pocket */
    ACD2D_MEASURE_H1,     /* hybrid 1 (IV.A.1.c) */
    ACD2D_MEASURE_H2      /* hybrid 2 (IV.A.1.c) */
} acd2d_measure;

typedef enum acd2d_cut {
    ACD2D_CUT_RAY = 0,    /* a cut from the notch may end at a new point on the boundary (default) */
    ACD2D_CUT_DIAGONAL    /* cuts join two existing vertices */
} acd2d_cut;

#define ACD2D_PARAMS_COOKIE 0x41434432u

typedef struct acd2d_params {
    uint32_t cookie;          /* set by acd2d_default_params; guards against uninitialized params */
    double tau;               /* concavity tolerance, >= 0; model units unless normalize (default 0) */
    acd2d_measure measure;    /* default SL */
    double sc;                /* weight of concavity in cut selection, Eqn 4.3 (default 0.1) */
    double sd;                /* weight of distance in cut selection, Eqn 4.3 (default 1) */
    acd2d_cut cut;            /* default ACD2D_CUT_RAY */
    int normalize;            /* non-zero: tau is relative to R (max distance of outer vertices from their mean) */
    double notch_tolerance;   /* a vertex is a notch when cross((v-u),(w-v)) < -notch_tolerance (raw units;
                                 default 1e-5, reproducing Table 2); 0 means exact predicates */
    acd_progress_fn progress; /* optional; may cancel */
    void *progress_user;
} acd2d_params;

acd2d_params acd2d_default_params(void);
const char *acd2d_measure_name(acd2d_measure m);            /* "sl", "sp", "h1", "h2" */
int acd2d_measure_parse(const char *name, acd2d_measure *out); /* 1 on success */

/* One node of the decomposition tree (Fig. 9b). Node 0 is the input polygon. A node with
 * children was cut (or had a hole merged, then it has one child) by `cut`. Node ids are in
 * preorder. To keep memory linear in the output, `polygon` is stored for the root, the hole-merge
 * steps, the components (leaves) and the few nodes that cannot be rebuilt from their children;
 * it is empty (nrings == 0) for the other inner nodes: get any node's polygon with
 * acd2d_node_polygon. */
typedef struct acd2d_node {
    int parent;              /* -1 for the root */
    int child[2];            /* -1 where absent */
    double concavity;        /* concavity of this node's polygon under the measure */
    acd_vec2 cut[2];         /* the cut (or hole-merging diagonal) applied to this node, if any */
    int is_hole_merge;       /* the operation on this node merged a hole (one child) */
    acd_polygon polygon;     /* this node's polygon (holes still present until merged) */
    int acceptable;          /* 1 if the polygon is simple, without holes or hole-merging slits: only
                                such nodes can be components (acd2d_result_at_tau) */
    size_t ring_offset;      /* split nodes: position of cut[0] in this node's ring (for the rebuild) */
    int cut_new_point;       /* split nodes: cut[1] is a new point inside an edge (1); 2: that point
                                was rounded off its edge and also put into the edge's other side
                                (far from the origin), so the node's polygon keeps it */
} acd2d_node;

typedef struct acd2d_component {
    acd_vec2 *points;        /* counterclockwise simple polygon, first point not repeated */
    size_t npoints;
    acd_vec2 *hull;          /* its convex hull, counterclockwise */
    size_t nhull;
    double concavity;        /* under the measure used */
    int node;                /* the tree node it is */
} acd2d_component;

typedef struct acd2d_result {
    double tau;              /* in model units (after normalization, if requested) */
    acd2d_measure measure;
    size_t input_vertices, input_notches, input_holes;
    acd2d_component *components;
    size_t ncomponents;
    acd_vec2 (*cuts)[2];     /* every cut made, in order */
    size_t ncuts;
    acd2d_node *nodes;
    size_t nnodes;
    double max_concavity;    /* over the components */
    double seconds;          /* wall time of the decomposition */
} acd2d_result;

/* Decomposes one validated polygon with holes. The polygon must pass acd_polygon_validate. */
acd_status acd2d_decompose(const acd_polygon *poly, const acd2d_params *params, acd2d_result *out,
                           acd_error *err);

/* Reads the decomposition for a coarser tolerance tau2 >= result->tau out of the tree without
 * recomputing: out gets the components (and cuts) of the frontier where concavity <= tau2. */
acd_status acd2d_result_at_tau(const acd2d_result *result, double tau2, acd2d_result *out, acd_error *err);

void acd2d_result_free(acd2d_result *r);

/* The polygon of tree node `node` (a copy, freed with acd_polygon_free), stored or rebuilt from
 * the node's descendants (iteratively, O(size of the subtree's rings)). */
acd_status acd2d_node_polygon(const acd2d_result *result, int node, acd_polygon *out, acd_error *err);

/* Concavity of a simple counterclockwise polygon (no holes) under a measure, as the
 * decomposition measures it: the largest concavity of a notch (cross((v-u),(w-v)) < -1e-5, the
 * default notch tolerance), 0 when there is none. `witness` (may be NULL) receives the index of
 * that notch (SIZE_MAX when none). tau matters for H2 only. Returns a negative value when out of
 * memory. */
double acd2d_concavity(const acd_vec2 *pts, size_t n, acd2d_measure m, double tau, size_t *witness);
/* The same with the measure, tau (model units: no normalization) and notch tolerance of params. */
double acd2d_concavity_params(const acd_vec2 *pts, size_t n, const acd2d_params *params, size_t *witness);

#ifdef __cplusplus
}
#endif
#endif
