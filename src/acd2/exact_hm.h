/* acd2/exact_hm: Hertel-Mehlhorn convex decomposition over a triangulation (polygons with holes). */
#ifndef ACD_ACD2_EXACT_HM_H
#define ACD_ACD2_EXACT_HM_H

#include "acd/polygon.h"
#include "acd2/exact_pieces.h"

/* Triangulates p (geom2/triangulate) and removes, in a fixed order (increasing half-edge index of
 * the triangulation), every diagonal whose two endpoints stay convex (orient2d >= 0) in the merged
 * piece. The pieces are convex and at most 4 times as many as the minimum (Hertel & Mehlhorn 1983).
 * On success the caller frees *out with acd_index_pieces_free. */
acd_status acd_exact_hm(const acd_polygon *p, acd_index_pieces *out, acd_error *err);

#endif
