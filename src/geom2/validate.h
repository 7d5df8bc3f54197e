/* geom2/validate: normalization and validation of polygons with holes (internal entry points).
 *
 * The public functions are acd_polygon_normalize and acd_polygon_validate (acd/polygon.h).
 * Here: the same validation with the intersection test selectable, so that tests can cross-check
 * the sweep line and the adaptive subdivision against the O(n^2) brute force. */
#ifndef ACD_GEOM2_VALIDATE_H
#define ACD_GEOM2_VALIDATE_H

#include "acd/polygon.h"

typedef enum acd_validate_method {
    ACD_VALIDATE_FAST = 0, /* the default: sweep line, O(n log n) */
    ACD_VALIDATE_SUBDIV,   /* adaptive box subdivision: about O(n log n) on natural input */
    ACD_VALIDATE_BRUTE     /* every pair of edges, O(n^2): for tests */
} acd_validate_method;

acd_status acd_polygon_validate_with(const acd_polygon *p, size_t index, acd_validate_method method,
                                     acd_error *err);

/* Orientation of ring r of p: +1 counterclockwise, -1 clockwise, 0 if undecidable (fewer than 3
 * vertices, non-finite or all collinear). Decided by the exact orientation of the lowest
 * (then leftmost) vertex with its neighbours, falling back to the sign of the area. */
int acd_polygon_ring_orientation(const acd_polygon *p, size_t r);

#endif
