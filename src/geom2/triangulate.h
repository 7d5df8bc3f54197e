/* geom2/triangulate: triangulation of a polygon with holes by hole bridging and ear clipping.
 *
 * Used by the exact 2D decompositions (Hertel-Mehlhorn) and by 3D cross-section capping.
 * Every geometric decision uses the exact predicates of core/predicates.h. */
#ifndef ACD_GEOM2_TRIANGULATE_H
#define ACD_GEOM2_TRIANGULATE_H

#include <stddef.h>

#include "acd/base.h"
#include "acd/polygon.h"

/* Flags of acd_triangulate_rings. */
#define ACD_TRI_BEST_EFFORT 1u /* never fail on invalid rings: force progress (see *nforced) */

/* Triangulates the polygon whose rings are points[ring_start[r] .. ring_start[r+1]-1],
 * r = 0 .. nrings-1, ring 0 the outer boundary, the others holes. Ring orientation is free (each
 * ring's orientation is decided exactly and followed accordingly); a ring must not repeat its first
 * point at its end.
 *
 * On success *tris is a malloc'd array of 3 * *ntris point indices (into points), and
 * *ntris = n + 2h - 2 for n points and h holes. Each triangle is counterclockwise; for a valid
 * simple polygon with holes (acd_polygon_validate) the triangles are non-degenerate except where
 * collinear input vertices force a zero-area triangle, and they partition the polygon.
 * *ndegenerate (may be NULL) receives the number of zero-area triangles emitted.
 *
 * Invalid rings (self-touching, crossing holes) are detected when no valid bridge or ear exists:
 * without ACD_TRI_BEST_EFFORT that is ACD_ERR_INVALID_INPUT; with it the function forces progress
 * (bridge to the nearest vertex, clip any convex vertex), counts those steps in *nforced (may be
 * NULL) and returns n + 2h - 2 triangles that then need not partition the region exactly.
 *
 * Errors: ACD_ERR_DEGENERATE for a ring with fewer than 3 points or no rings, ACD_ERR_INVALID_INPUT
 * for non-finite coordinates or invalid rings, ACD_ERR_NOMEM. The caller frees *tris with free(). */
acd_status acd_triangulate_rings(const acd_vec2 *points, const size_t *ring_start, size_t nrings, unsigned flags,
                                 size_t **tris, size_t *ntris, size_t *ndegenerate, size_t *nforced,
                                 acd_error *err);

/* Same for an acd_polygon (indices into p->points). */
acd_status acd_triangulate_polygon(const acd_polygon *p, size_t **tris, size_t *ntris, size_t *ndegenerate,
                                   acd_error *err);

/* 1 if the closed ring pts[0..n-1] (simple, >= 3 points) is counterclockwise: decided exactly by
 * orient2d at its lowest-leftmost vertex (falls back to the sign of the area when that vertex's
 * neighbours are collinear with it). */
int acd_ring_is_ccw(const acd_vec2 *pts, size_t n);

#endif
