/* acd2/exact_mcd: minimum convex decomposition without Steiner points (Keil-Snoeyink dynamic
 * programming) of a simple polygon without holes. */
#ifndef ACD_ACD2_EXACT_MCD_H
#define ACD_ACD2_EXACT_MCD_H

#include "acd/polygon.h"
#include "acd2/exact_pieces.h"

/* Minimum number of convex pieces whose vertices are vertices of p (p: one ring, either
 * orientation, simple). Refuses polygons with holes (ACD_ERR_UNSUPPORTED). On success the caller
 * frees *out with acd_index_pieces_free. */
acd_status acd_exact_mcd(const acd_polygon *p, acd_index_pieces *out, acd_error *err);

#endif
