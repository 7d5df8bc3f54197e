/* eval/verify2d: internal helpers of the 2D decomposition verifier (public API in
 * include/acd/verify2d.h). */
#ifndef ACD_EVAL_VERIFY2D_H
#define ACD_EVAL_VERIFY2D_H

#include "acd/verify2d.h"

/* Signed area of a ring by the shoelace formula with error-free products and compensated
 * (Neumaier) summation: accurate to a few ulps of the result even when the coordinates are
 * far from the origin. */
double acd_v2d_ring_area(const acd_vec2 *pts, size_t n);

/* Where q lies relative to the region bounded by rings (ring_start as in acd_polygon, parity
 * rule): 1 inside, -1 outside, 0 within tol of the boundary. Exact crossing decisions. O(n). */
int acd_v2d_classify_point(const acd_vec2 *pts, const size_t *ring_start, size_t nrings, acd_vec2 q, double tol);

#endif
