/* acd3/leaf_test: the hull-distance stopping test (`--stop hull`, acd3d_params.stop; docs/acd3d.md
 * "Stopping test").
 *
 * The decomposition's measure (acd3/measure) is the depth of each vertex below the plane of its
 * bridge patch. The patches cluster hull facets within eps = eps_ratio * tau of each other, so a
 * vertex can be measured up to about eps deeper than it lies below the hull's boundary: a part the
 * measure puts above tau can already be within tau of its hull. This test accepts such a part as a
 * leaf when its surface S and the boundary B of its hull H are within `limit` of each other in
 * both directions, each direction bounded from above:
 *
 *   d_in  >= max over x in S of dist(x, B). For x in H, dist(x, B) = min over the facet planes f
 *          of -(n_f.x + d_f) (unit normals, H the intersection of its facets' half-spaces). Each
 *          term is affine in x, so over a triangle T of S
 *            max_{x in T} min_f (-(n_f.x + d_f)) <= min_f max_{corners c of T} (-(n_f.c + d_f)),
 *          which is the bound used per triangle (exact at the vertices); a triangle whose bound
 *          is above the limit is subdivided (midpoints) before the part is refused.
 *   d_out >= max over x in B of dist(x, S): the merge pass's facet subdivision
 *          (acd3_merge_hull_reach: every piece of a hull facet has a point q of S within the
 *          limit of all its corners, so of all its points, |x - q| being convex).
 *
 * Both are upper bounds, so an accepted part really has Hausdorff distance <= limit between its
 * surface and its hull's boundary (in floating point: the hull planes and the distances are
 * rounded; the caller's limit includes the same rounding length as the measure's test).
 * In surface mode S is an open patch and B includes the hull facets spanning its openings: a
 * patch showing its inner side to its hull (spec §3.4's concave hull vertices) is accepted only
 * when even those facets are within the limit of it. */
#ifndef ACD_ACD3_LEAF_TEST_H
#define ACD_ACD3_LEAF_TEST_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "acd/hull.h"
#include "acd/mesh.h"
#include "acd3/merge.h"
#include "geom3/bvh.h"

/* Tests part (its triangles) against its hull H (dim 3; any other dim is refused). hint: a
 * vertex to test first (the measure's witness: the likeliest to be deep), or UINT32_MAX.
 * *accepted = 1 when both bounds are <= limit, with *bound = max(d_in, d_out) (an upper bound of
 * the Hausdorff distance between the part's surface and H's boundary); else *accepted = 0 and
 * *bound is a value above limit. Fails only on allocation failure. Deterministic. */
acd_status acd3_leaf_test(const acd_mesh *part, const acd_hull *H, double limit, uint32_t hint, int *accepted,
                          double *bound, acd_error *err);
/* The same, handing out what the test built for the merge's set-up (acd3_merge_kept) instead of freeing
 * it: *bvh (when not NULL) the part's triangle tree, built over part's own arrays when the test gets
 * to d_out (else left empty, nnodes 0); *table (when not NULL) H's facet table at limit over that tree
 * when the part is accepted (acd3_merge_hull_reach_table; else left empty, key NULL). The caller frees
 * both (acd_bvh_free, acd3_facet_table_free), also on failure. */
acd_status acd3_leaf_test_keep(const acd_mesh *part, const acd_hull *H, double limit, uint32_t hint, int *accepted,
                               double *bound, acd_bvh *bvh, acd3_facet_table *table, acd_error *err);

#endif
