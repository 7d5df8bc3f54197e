/* acd/acd3d.h: approximate convex decomposition of polyhedra, solid and surface
 * (Lien, dissertation Ch. V; Lien & Amato, "Approximate convex decomposition of polyhedra";
 * spec ../shared/spec/acd3d.md).
 *
 * Usage:
 *   acd3d_params prm = acd3d_default_params();
 *   prm.tau = 0.05;                       // relative to the minimum enclosing sphere's radius
 *   acd3d_result res;
 *   if (acd3d_decompose(&mesh, &prm, &res, &err) == ACD_OK) { ...; acd3d_result_free(&res); }
 *
 * The tightest hulls at a part budget (the CLI's `acd 3d MESH --budget 40`):
 *   acd3d_params prm = acd3d_budget_params(40);  // then change any field, e.g. prm.merge_refine = 0
 */
#ifndef ACD_ACD3D_H
#define ACD_ACD3D_H

#include "acd/base.h"
#include "acd/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum acd3d_mode {
    ACD3D_SOLID = 0, /* parts are closed solids: cut by planes, sections capped */
    ACD3D_SURFACE    /* parts are surface patches: split along cut loops, never capped */
} acd3d_mode;

typedef enum acd3d_weight {
    ACD3D_WEIGHT_RATIO = 0, /* W = omega / gamma (paper Eqn 4), default */
    ACD3D_WEIGHT_PRODUCT    /* W = omega * gamma (dissertation Eqn 5.2) */
} acd3d_weight;

typedef enum acd3d_resolver {
    ACD3D_RESOLVER_GLOBAL = 0, /* solid mode: the global cut's plane first (knots, pocket cuts, the
                                  minimum-weight cycle of the cut graph; dissertation §V.B.2-3),
                                  then the planes through the most concave vertex */
    ACD3D_RESOLVER_WITNESS,    /* only the planes through the most concave vertex */
    ACD3D_RESOLVER_NOTCH       /* the resolver without feature grouping (spec §5.4, decision A14):
                                  the plane through the most reflex edge at the most concave
                                  vertex, bisecting its dihedral angle (notch cutting), then only
                                  the planes through that vertex perpendicular to the principal
                                  axes; the witness planes when that vertex has no reflex edge.
                                  The "without
                                  FG" variant of Figs 47/48 is this with eps_ratio = 0 (no bridge
                                  clustering) and region_cuts (docs/acd3d.md "Without feature
                                  grouping") */
} acd3d_resolver;

typedef enum acd3d_cut_choice {
    ACD3D_CHOICE_CONCAVITY = 0, /* solid mode: among the candidate cuts, the smallest largest piece
                                   concavity (then fewer pieces); a cut meeting tau or halving the
                                   concavity is taken at once (default) */
    ACD3D_CHOICE_VOLUME,        /* solid mode: planes chosen for the pieces' hull volumes join the
                                   candidates (acd3/volume_plane), every candidate is compared (up to
                                   the budget), and among those whose concavity is within a band of the
                                   best the smallest sum of the pieces' hull volumes wins (CoACD's
                                   objective); docs/acd3d.md "Hull tightness" */
    ACD3D_CHOICE_BAND           /* solid mode: the default's candidates and early acceptance, compared
                                   by ACD3D_CHOICE_VOLUME's rule (a cut that lowers the concavity wins;
                                   a concavity lower by more than half the part's wins, else the
                                   smaller sum of the pieces' hull volumes); no extra cost; fewer
                                   parts on Table 5 (armadillo tau 0.02: 152 -> 123), IoU up or down
                                   by a few thousandths on the target meshes; docs/acd3d.md "Cut
                                   choice by band" */
} acd3d_cut_choice;

typedef enum acd3d_merge_order {
    ACD3D_MERGE_BOUND = 0,  /* the merge pass joins the pair of smallest bound first (default) */
    ACD3D_MERGE_VOLUME      /* the pair whose joined hull adds the least volume (vol conv(A u B) -
                               vol conv A - vol conv B) first */
} acd3d_merge_order;

/* How surface mode splits a part (with the global resolver; docs/acd3d.md "Splitting a surface"). */
typedef enum acd3d_surface_cut {
    ACD3D_SURFACE_STRIP = 0,    /* along the section strip of a cut plane nearest the witness (default) */
    ACD3D_SURFACE_CYCLE,        /* first along the global cut's cycle (pocket cuts, closed with the
                                   paper's dynamic geodesic cuts) when it separates the part and
                                   makes progress, compared with the plane strips */
    ACD3D_SURFACE_CYCLE_WITNESS /* the same, the cycle rooted at a cut through the witness */
} acd3d_surface_cut;

/* When a part whose measure is above tau is nevertheless a leaf (docs/acd3d.md "Stopping test"). */
typedef enum acd3d_stop {
    ACD3D_STOP_MEASURE = 0, /* only the measure decides (the paper's Algorithm 1: concavity <= tau) */
    ACD3D_STOP_HULL         /* also a part whose surface and hull boundary are within tau of each
                               other in both directions (upper bounds, acd3/leaf_test): the measure's
                               bridge patches may over-report by up to eps */
} acd3d_stop;

#define ACD3D_PARAMS_COOKIE 0x41434433u

typedef struct acd3d_params {
    uint32_t cookie;          /* set by acd3d_default_params */
    double tau;               /* concavity tolerance (default 0.05) */
    int tau_absolute;         /* 0: tau is relative to the minimum enclosing sphere's radius (default);
                                 1: tau is in model units */
    acd3d_mode mode;          /* default ACD3D_SOLID */
    double eps_ratio;         /* bridge clustering threshold eps = eps_ratio * tau (default 0.5); 0: no
                                 clustering (every hull facet its own bridge, coplanar ones joined) */
    double delta_ratio;       /* knot threshold delta = delta_ratio * tau (default 0.1) */
    acd3d_weight weight;      /* cut weight of the global cut (default ratio) */
    acd3d_resolver resolver;  /* how solid mode chooses its cut planes (see docs/acd3d.md) */
    size_t max_hulls;         /* 0: no limit; else the cheapest adjacent parts are merged (a split is
                                 undone, smallest parent concavity first) until at most this many
                                 remain; result.max_concavity is the concavity reached */
    size_t max_hull_vertices; /* 0: no limit; else (>= 4) each hull is replaced, when it has more
                                 vertices, by an enclosing polytope with at most this many */
    int threads;              /* 0: as many as cores (OpenMP), at most 1024; results are identical for any count */
    size_t max_depth;         /* recursion guard (default 48), raised by twice the input's genus
                                 (a handle may take a cut that only opens it) */
    int merge;                /* non-zero (default 1): after the decomposition, adjacent parts are
                                 joined cheapest first while the result stays within tau: in solid
                                 mode the joined hull within tau of the joined part and the input
                                 surface within tau of it (acd3/merge), in surface mode the welded
                                 patch measured with the decomposition's own measure
                                 (acd3/surface_merge); docs/acd3d.md "Merge pass". The joined parts
                                 are ACD3D_LEAF_JOINED nodes */
    double merge_tau;         /* the merge pass's tolerance, in the units of tau (relative, or absolute
                                 with tau_absolute); 0 (default): tau, or merge_tau_diag's when set */
    acd3d_merge_order merge_order; /* solid mode's merge pass: which joinable pair first */
    size_t merge_parts;       /* solid mode's merge pass: 0 (default) joins while a pair is joinable;
                                 else it stops as soon as at most this many parts remain */
    size_t merge_refine;      /* solid mode's merge pass with merge_parts: at most this many refinement
                                 steps after the joins (0, default: none); a step cuts a joined part by
                                 the plane saving the most hull volume and joins the cheapest pair, when
                                 the hulls' volume falls (docs/acd3d.md "Hull tightness"); not with
                                 max_hulls */
    size_t budget_parts;      /* solid mode: 0 (default) off; else after the decomposition the parts
                                 are split further, best first by the hull volume a cut saves, until
                                 this many exist, and every part until its surface and hull are
                                 within merge_tau of each other both ways (docs/acd3d.md
                                 "Excess-driven budget"); then the merge pass. Solid mode only, not with max_hulls
                                 (acd3d_decompose: ACD_ERR_INVALID_ARGUMENT) */
    acd3d_cut_choice cut_choice; /* solid mode: how a split's cut is chosen among the candidates */
    acd3d_surface_cut surface_cut; /* surface mode: plane strips only (default), or the global cut's
                                 cycle first */
    acd3d_stop stop;          /* the stopping test (default ACD3D_STOP_MEASURE, the paper's; docs/acd3d.md
                                 "Stopping test" has the measurements behind the default) */
    int region_cuts;          /* non-zero: a plane cuts only its section region at the witness
                                 (spec decision A13), falling back to the whole plane; default 0,
                                 see docs/acd3d.md for the measurements behind the default */
    acd_progress_fn progress; /* optional: called only from the calling thread (it need not be
                                 thread-safe), with the stage named ("checking the input", "measuring
                                 and cutting", "budget: ...", "merge: ..."): between the steps of every
                                 stage and, in the tree, within a part's work (its measure, global
                                 cut and candidate cuts), so that on this machine no call is more than
                                 about half a CPU-second from the next on an 832k-triangle input
                                 (docs/acd3d.md, docs/results/3d-large.md). Non-zero cancels: the call
                                 returns ACD_ERR_CANCELLED soon after (within one such step), with no
                                 result and nothing leaked. It decides nothing: the output is the
                                 same with or without it. */
    void *progress_user;
    double merge_tau_diag;    /* the merge pass's tolerance as a fraction of the input's bounding-box
                                 diagonal (model units: merge_tau_diag x diagonal), used when merge_tau
                                 is 0; 0 (default): unused. Also the budget's limit (budget_parts).
                                 acd3d_decompose turns it into the relative tolerance merge_tau_diag x
                                 diagonal / scale (result.merge_tau_relative): the run is the one
                                 merge_tau = that value gives (with tau relative) */
    double trim_coverage;     /* solid mode: 0 (default): every hull encloses its part. In (0, 0.01]:
                                 the hulls are trimmed at the end (acd3/trim): caps of a hull that are
                                 mostly air over the part's relief are cut off by planes, best ratio of
                                 hull volume to part volume removed first, while the part volume left
                                 outside its hull stays within trim_coverage x the input's volume; the
                                 union of hulls then covers at least 1 - trim_coverage of the input and
                                 the hulls stay convex (docs/acd3d.md "Trimmed hulls"). With
                                 max_hull_vertices, a cut that would exceed it is not made. A part
                                 that intersects itself keeps its whole hull (result.trim_skipped) */
} acd3d_params;

acd3d_params acd3d_default_params(void);

/* The budget pipeline's settings ("the tightest hulls at a part budget", docs/acd3d.md
 * "Excess-driven budget"; the CLI's `acd 3d MESH --budget N`): */
#define ACD3D_BUDGET_TAU 10.0             /* tau (relative): no tau-driven split, the budget splits the input */
#define ACD3D_BUDGET_MERGE_TAU_DIAG 0.0195 /* merge_tau_diag: joined parts within 0.0195 of the diagonal
                                             (under the 0.02 of the concavity target) */
#define ACD3D_BUDGET_MERGE_REFINE 40      /* merge_refine */

#define ACD3D_TRIM_COVERAGE_MAX 0.01 /* trim_coverage: at most 1% of the input's volume left uncovered */

/* acd3d_default_params() set for a part budget of `parts` (> 0): budget_parts = merge_parts = parts,
 * tau = ACD3D_BUDGET_TAU (relative), merge_tau_diag = ACD3D_BUDGET_MERGE_TAU_DIAG (merge_tau 0),
 * cut_choice = ACD3D_CHOICE_VOLUME, merge_order = ACD3D_MERGE_VOLUME, merge_refine =
 * ACD3D_BUDGET_MERGE_REFINE; the rest as acd3d_default_params (solid mode, merge on). Any field may be
 * changed afterwards (a merge_tau > 0 takes precedence over merge_tau_diag). parts 0:
 * acd3d_default_params() unchanged. */
acd3d_params acd3d_budget_params(size_t parts);

/* Why a node of the tree is a leaf. */
typedef enum acd3d_leaf_reason {
    ACD3D_LEAF_NONE = 0,      /* not a leaf: it was split */
    ACD3D_LEAF_TAU,           /* concavity <= tau */
    ACD3D_LEAF_FLAT,          /* no volume (solid) or flat (surface): convex by definition */
    ACD3D_LEAF_NO_CUT,        /* no cut could split it further (the concavity stays above tau; with
                                 budget_parts: a part the budget pass left above merge_tau, its
                                 concavity then its two-sided hull distance bound) */
    ACD3D_LEAF_DEPTH,         /* max_depth reached */
    ACD3D_LEAF_MERGED,        /* a split node made a part again by max_hulls (its children are dropped:
                                 leaf_reason NONE, part -1) */
    ACD3D_LEAF_JOINED,        /* a part made by the merge pass from adjacent parts: a node appended
                                 after the tree (parent -1, no children); the parts it joins keep their
                                 nodes and leaf reasons, with part -1 and merged_into set to it; its
                                 concavity is the merge bound (<= merge_tau, acd3/merge) */
    ACD3D_LEAF_HULL,          /* measure above tau, but (ACD3D_STOP_HULL) the part's surface and its hull's
                                 boundary are within tau of each other both ways; its concavity is
                                 that distance's upper bound (<= tau), not the measure */
    ACD3D_LEAF_REFINED,       /* a piece cut from a part by the merge pass's refinement (merge_refine):
                                 a child of that part's node, always joined into an ACD3D_LEAF_JOINED
                                 node (merged_into set), its concavity that node's bound */
    ACD3D_LEAF_BUDGET         /* a piece cut from a part by the part budget (budget_parts); its
                                 concavity is its two-sided hull distance bound (acd3/leaf_test),
                                 <= merge_tau (one no cut could split is ACD3D_LEAF_NO_CUT) */
} acd3d_leaf_reason;

/* Static name of a leaf reason, as `acd 3d --json` writes it ("split", "tau", "flat", "no_cut",
 * "depth", "merged", "joined", "hull_distance", "refined", "budget"; "unknown" otherwise). */
const char *acd3d_leaf_reason_name(acd3d_leaf_reason r);

typedef struct acd3d_node {
    int parent;               /* -1 for the root */
    int first_child;          /* -1 for a leaf; children are nodes first_child .. first_child+nchildren-1 */
    int nchildren;
    double concavity;         /* of this node's part (model units) */
    double volume;            /* of the part (solid mode; 0 for surfaces) */
    double cut_plane[4];      /* plane n.x + d = 0 used to split it (solid mode), zero for leaves */
    int bodies;               /* 1: the root of an input of several bodies, split into them (solid:
                                 connected solids, each cavity with its shell; surface: edge-connected
                                 patches) before any cut; cut_plane is zero */
    acd3d_leaf_reason leaf_reason;
    int part;                 /* index into parts for leaves, -1 otherwise */
    int merged_into;          /* -1, or the ACD3D_LEAF_JOINED node this part was joined into */
} acd3d_node;

typedef struct acd3d_part {
    acd_mesh mesh;            /* the part: closed (solid) or a surface patch */
    acd_mesh hull;            /* its convex hull, outward triangles */
    double concavity;         /* model units */
    double volume;            /* solid: part volume; surface: 0 */
    double hull_volume;
    int node;
    long genus;               /* handles of the part (Euler characteristic with its boundary loops,
                                 summed over its connected components) */
    size_t boundary_loops;    /* openings of the part (0 for a closed solid) */
    double trimmed_volume;    /* with trim_coverage: the part's volume beyond the planes its hull was
                                 cut by, a plane cut deeper along its own normal counted once (an upper
                                 bound of its volume outside its hull); else 0. The concavity above is
                                 measured against the untrimmed hull */
} acd3d_part;

typedef struct acd3d_result {
    double tau;               /* in model units */
    double merge_tau;         /* the merge pass's tolerance in model units (joined parts meet it) */
    double scale;             /* minimum enclosing sphere radius of the input */
    double tol;               /* model units: a computed concavity or distance up to this counts as zero
                                 (1e-10 of the input's bounding-box diagonal); a part is a leaf of reason
                                 TAU when its concavity is at most tau + tol, so tau = 0 asks for parts
                                 convex up to rounding */
    acd3d_part *parts;
    size_t nparts;
    acd3d_node *nodes;
    size_t nnodes;
    double max_concavity;     /* over the parts, model units */
    double input_volume;
    double seconds;
    double merge_tau_relative; /* the merge tolerance relative to scale as the run used it: params.merge_tau
                                 when given relative, merge_tau_diag x diagonal / scale when derived from
                                 merge_tau_diag (then merge_tau = merge_tau_relative x scale exactly), else
                                 merge_tau / scale (0 when scale is 0) */
    double trimmed_volume;    /* the parts' trimmed_volume summed: at most trim_coverage x input_volume;
                                 the input's volume outside the union of hulls is at most this */
    size_t trim_cuts;         /* caps cut off the hulls (trim_coverage) */
    double trim_depth_max;    /* the deepest trim cut below its hull facet, model units */
    size_t trim_skipped;      /* with trim_coverage: parts whose hulls were left whole because the part
                                 intersects itself (the budget is accounted in signed volumes, which
                                 are not the volume inside a solid that crosses itself) */
    double trim_distance_bound; /* with trim_coverage: no cut left a part vertex farther than this from
                                 its trimmed hull (the parts' largest concavity: the run's own statement
                                 of how far a part's surface may lie from its hull; docs/acd3d.md
                                 "Trimmed hulls"), model units */
    size_t trim_refused_far;  /* with trim_coverage: caps refused by that bound (thin features kept) */
    /* The part budget pass (budget_parts > 0; all 0 / NULL otherwise). It cuts best first until
     * budget_parts parts exist, then (phase 1) keeps cutting parts above the merge tolerance, by cuts
     * that make progress, within caps (docs/acd3d.md "Excess-driven budget"). */
    size_t budget_cuts;        /* cuts the budget pass made, phase 1's included */
    size_t budget_phase1_cuts; /* of them, cuts of parts above the merge tolerance once the budget was spent */
    size_t budget_over;        /* parts the pass left above the merge tolerance (leaf_reason NO_CUT) */
    const char *budget_stop;   /* when budget_over > 0, why phase 1 stopped (a static string: "the phase-1
                                  cut cap was reached", "the atom cap was reached", "a part reached the
                                  phase-1 generation cap", "no cut of a part above the limit splits it with
                                  progress"); NULL when no part is left above the tolerance */
} acd3d_result;

/* Decomposes a closed (solid) or any (surface) triangle mesh. The input should have been
 * validated/repaired (see mesh.h): solid mode refuses open or non-manifold input with a message. */
acd_status acd3d_decompose(const acd_mesh *mesh, const acd3d_params *params, acd3d_result *out, acd_error *err);
void acd3d_result_free(acd3d_result *r);

#ifdef __cplusplus
}
#endif
#endif
