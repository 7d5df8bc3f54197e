/* geom2/hull2d: convex hull of 2D points by Andrew's monotone chain (A. M. Andrew, "Another
 * efficient algorithm for convex hulls in two dimensions", IPL 9(5), 1979), with the exact
 * orientation predicate. Collinear and repeated points are not hull vertices. */
#ifndef ACD_GEOM2_HULL2D_H
#define ACD_GEOM2_HULL2D_H

#include <stddef.h>

#include "acd/polygon.h"

/* Writes the indices of the hull vertices of pts[0..n) to out (capacity n + 1), counterclockwise,
 * starting at the lowest-x (then lowest-y) point; returns their number (0 for n == 0, 1 or 2 for
 * degenerate inputs). `scratch` must hold n + 1 indices. When several points coincide, the one with
 * the smallest index represents them. */
size_t acd_hull2d_indices(const acd_vec2 *pts, size_t n, size_t *out, size_t *scratch);

#endif
