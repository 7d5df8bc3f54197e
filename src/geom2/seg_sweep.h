/* geom2/seg_sweep: does any pair of polygon edges meet where it should not? A Shamos-Hoey
 * sweep line (M. I. Shamos, D. Hoey, "Geometric intersection problems", FOCS 1976), exact.
 *
 * The edges are those of closed rings: edge i runs from pts[i] to pts[next[i]]. The caller's
 * `conflict` callback decides whether a pair that the sweep brings together is a conflict
 * (returns a non-OK status, having filled its error) or allowed (returns ACD_OK; e.g. adjacent
 * edges sharing their common vertex). Every pair of edges that meets is presented to the callback
 * before the sweep passes their leftmost common point, as long as no earlier pair was a conflict,
 * so the sweep finds a conflict iff the brute force over all pairs finds one. O(n log n). */
#ifndef ACD_GEOM2_SEG_SWEEP_H
#define ACD_GEOM2_SEG_SWEEP_H

#include "acd/polygon.h"

typedef acd_status (*acd_sweep_pair_fn)(void *ctx, size_t e, size_t f);

/* Requirements: finite coordinates, no zero-length edge (pts[i] != pts[next[i]]).
 * Optionally (want_below and below both non-NULL): for every vertex v with want_below[v] != 0,
 * below[v] is set to the edge directly below v when the sweep reaches v (the highest edge crossing
 * the vertical line through v under v), or SIZE_MAX if there is none. Meaningful when the sweep
 * returns ACD_OK. */
acd_status acd_sweep_edges(const acd_vec2 *pts, const size_t *next, size_t n, acd_sweep_pair_fn conflict,
                           void *ctx, const unsigned char *want_below, size_t *below, acd_error *err);

#endif
