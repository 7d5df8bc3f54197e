/* geom2/seg_dist: the distance from a point to a segment in the plane, computed relative to the
 * segment's start. q - a and b - a are exact for nearby points, so the distance keeps offsets far
 * below the spacing of doubles at the coordinates' magnitude; a foot point a + t (b - a) in
 * absolute coordinates would be rounded to that spacing and hide them far from the origin
 * (docs/acd2d.md "Far from the origin"). Shared by acd2/resolution and eval/verify2d. */
#ifndef ACD_GEOM2_SEG_DIST_H
#define ACD_GEOM2_SEG_DIST_H

#include <math.h>

#include "acd/polygon.h"

static inline double acd_seg_dist2(acd_vec2 q, acd_vec2 a, acd_vec2 b) {
    double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
    double qx = q.x - a.x, qy = q.y - a.y;
    double t = l2 > 0 ? (qx * dx + qy * dy) / l2 : 0;
    if (t < 0) t = 0;
    if (t > 1) t = 1;
    return hypot(qx - t * dx, qy - t * dy);
}

#endif
