/* acd3/trim: hulls trimmed within a coverage budget (params.trim_coverage, `acd 3d --trim-coverage F`;
 * docs/acd3d.md "Trimmed hulls").
 *
 * A part's convex hull holds the part and the air over its concave relief. Where a hull facet spans
 * a few protruding tips (the skin of a scan), a plane a little below the facet cuts off a cap of
 * the hull that is mostly air and holds a sliver of the part. This pass cuts such caps, greedily
 * by the ratio of the hull volume removed to the part volume removed, while the part volume
 * removed stays within `budget` (model units, summed over all parts). The union of the trimmed
 * hulls then covers all of the input but at most `budget` of its volume (each part is covered by
 * its own hull outside the caps cut from it; each cut charges the part volume it takes out of its
 * hull exactly, the part beyond its plane and inside the hull's earlier cuts (acd3_trim_tree_charge),
 * so the charges sum to the parts' volume outside their hulls, an upper bound of the union's; the
 * choice scores a cap by an upper bound of that, its loss less its plane's base: a cut made from an
 * earlier cut's own plane, deeper, holds the part beyond the first plane, which the first charged),
 * and the hulls stay convex (each is the hull of its old vertices below the
 * plane and of its edges' crossings). A cut is taken only when it raises the IoU of input and union:
 * removing hull volume g holding part volume l does when g / l > 1 + U / V (U the hulls' volume
 * sum, V the input's), the floor used here. A cut is also refused when it would leave the part's
 * surface, or the section it exposes, farther than a distance bound from the hull or from the input's
 * surface (acd3_trim_hulls_within: a thin feature holds little volume, but cut off whole it is far
 * from the hulls; docs/acd3d.md "The distance bound").
 *
 * Candidates: every hull facet's plane moved inward by ACD3_TRIM_DEPTHS depths (fractions of the
 * cube root of the part's initial hull volume), and each cut's own plane moved inward likewise; a cut
 * must remove at least min_gain of hull volume. With the input given, a facet plane holding one of the
 * part's internal walls (a part triangle off the input's surface: a face a cut made) is not a
 * candidate: a cap under it would take the part's layer along the wall out of every hull, and the
 * union's boundary would run through the solid (docs/results/3d-armadillo.md).
 * With max_vertices >= 4 a cut leaving more hull vertices than that is refused (the hull is then
 * left as it is). When the input (the mesh the parts tile; NULL: not checked) intersects itself, a
 * part that intersects itself (acd_mesh_self_intersections) keeps its whole hull: its signed
 * volumes, which the budget is accounted in, are not the volume inside it (found on three_peaks.off,
 * whose hole is closed by a cap crossing the surface). The parts of an input that does not are not
 * tested: a joined part's internal walls (a section twice, opposite ways) count as intersections
 * there, but cancel in the signed volumes. Deterministic for any thread count: the planes of all
 * hulls are measured in parallel (with the input's test), the rounds of cuts are sequential
 * (ACD3_TRIM_BATCH distinct hulls per round, by ratio). */
#ifndef ACD_ACD3_TRIM_H
#define ACD_ACD3_TRIM_H

#include <stddef.h>

#include "acd/acd3d.h"
#include "acd/base.h"
#include "geom3/bvh.h"

/* min_gain as acd3d_decompose passes it: a cut removes at least this fraction of the input's volume
 * of hull volume */
#define ACD3_TRIM_MIN_GAIN_REL 1e-5

typedef struct acd3_trim_stats {
    size_t cuts;          /* caps cut off */
    double removed_hull;  /* hull volume removed (sum over the cuts) */
    double removed_part;  /* part volume the cuts took out of their hulls (sum over the cuts, each exact
                             up to rounding: the parts' volume outside their trimmed hulls, >= the
                             volume the union of hulls leaves uncovered) */
    double max_depth;     /* deepest cut, model units (how far below its old facet a plane went) */
    size_t skipped;       /* solid parts left whole because they intersect themselves */
    double max_distance;  /* the distance bound: no part vertex farther than this from its trimmed hull */
    size_t refused_far;   /* cuts refused by it after being made (others are refused by a lower bound
                             before: the part's reach beyond the plane) */
} acd3_trim_stats;

/* Trees the caller built already (acd3d_decompose: the merge's and the budget pass's), used instead
 * of building them again; each NULL, or a tree that acd_bvh_is_over the mesh's own arrays (the tree
 * acd_bvh_build makes of them; one over other arrays is not used: built here). The result is the
 * same, bit for bit (the losses are summed in the tree's order: the same tree, the same sums). */
typedef struct acd3_trim_trees {
    const acd_bvh *input;        /* the input's tree (its self-crossing test, the walls' surface test) */
    const acd_bvh *const *parts; /* NULL, or per part its tree (the losses, its self-crossing test, its
                                    triangles near a plane asked to be a wall) */
} acd3_trim_trees;

/* Trims parts[i].hull (and hull_volume) of solid parts in place, setting parts[i].trimmed_volume,
 * as acd3_trim_hulls_within with max_distance the largest concavity of the solid parts (the run's
 * own bound on how far a part's surface lies from its hull: the merge tolerance for joined parts,
 * tau for split ones; docs/acd3d.md "Trimmed hulls"). */
acd_status acd3_trim_hulls(acd3d_part *parts, size_t nparts, double input_volume, double budget, double min_gain,
                           size_t max_vertices, const acd_mesh *input, const acd3_trim_trees *trees, int threads,
                           acd_progress_fn progress, void *progress_user, acd3_trim_stats *stats, acd_error *err);

/* Trims parts[i].hull (and hull_volume) of solid parts in place, setting parts[i].trimmed_volume.
 * budget, min_gain: model volume units; budget <= 0 does nothing. progress: NULL or called from the
 * calling thread between rounds (fraction of the budget spent); non-zero cancels
 * (ACD_ERR_CANCELLED, the parts' hulls then partly trimmed: the caller discards the result). trees:
 * NULL or the trees the caller has (acd3_trim_trees), read only. max_distance (model units;
 * INFINITY: no bound): a cut is refused when it would leave a vertex of the part farther than this
 * from the trimmed hull (so the part's surface: the distance to a convex set is largest at a
 * triangle's corner), or, with the input given, a point of the part's internal walls (triangles off
 * the input's surface) beyond its plane farther than this less the part's reach beyond the plane
 * from the input's surface (so the section the cut exposes stays within max_distance of the input's
 * surface; sampled, the sampling step taken off the bound). Refused depths of a plane stay refused
 * (the hull only shrinks). */
acd_status acd3_trim_hulls_within(acd3d_part *parts, size_t nparts, double input_volume, double budget,
                                  double min_gain, size_t max_vertices, double max_distance, const acd_mesh *input,
                                  const acd3_trim_trees *trees, int threads, acd_progress_fn progress,
                                  void *progress_user, acd3_trim_stats *stats, acd_error *err);

#endif
