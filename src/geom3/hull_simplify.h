/* geom3/hull_simplify: a convex polytope with at most N vertices that encloses a point set (a
 * part), for physics engines that cap the vertex count of a convex collider.
 *
 * Method (docs/eval.md, "Hull simplification"): take the hull of a subset of k hull vertices chosen
 * by farthest-point sampling, push every facet plane of that small hull outward until no input point
 * lies beyond it (plus a margin of ACD_TOL_REL_DIST times the diagonal), and intersect the pushed
 * half-spaces (by the dual hull). The intersection can have more vertices than the subset (at most
 * 2F - 4 for F facets), so k is lowered until it has at most N. k = 4 always succeeds (four pushed
 * facets of a tetrahedron meet in four vertices). */
#ifndef ACD_GEOM3_HULL_SIMPLIFY_H
#define ACD_GEOM3_HULL_SIMPLIFY_H

#include <stddef.h>

#include "acd/base.h"
#include "acd/hull.h"

/* Enclosing convex polytope of n points (3 doubles each) with at most max_vertices (>= 4) vertices.
 * When the points' hull already has at most max_vertices vertices it is returned unchanged.
 * The output's `source` is UINT32_MAX for vertices that are not input points. Every input point p
 * satisfies acd_hull_plane_distance(out, p) <= ACD_TOL_REL_DIST * diagonal. Flat input (dim < 3)
 * with more than max_vertices hull vertices is ACD_ERR_UNSUPPORTED; max_vertices < 4 is
 * ACD_ERR_INVALID_ARGUMENT. */
acd_status acd_hull_simplify(const double *points, size_t n, size_t max_vertices, acd_hull *out, acd_error *err);

#endif
