/* geom3/sphere: minimum enclosing sphere of 3D points.
 *
 * Lien's experiments normalise every model so that its minimum enclosing sphere has radius 1
 * (D Table 4 caption, P Table 1 caption); concavity tolerances tau are given in those units. */
#ifndef ACD_GEOM3_SPHERE_H
#define ACD_GEOM3_SPHERE_H

#include <stddef.h>

#include "acd/base.h"

typedef struct acd_sphere {
    double center[3];
    double radius;
} acd_sphere;

/* Smallest sphere containing the n points (3 doubles each): Welzl's algorithm with Gaertner's
 * move-to-front heuristic on a fixed-seed shuffle (deterministic). Duplicates, collinear and
 * coplanar sets are fine. The radius returned is the largest distance from the centre to a point,
 * so every point is inside in floating point; it exceeds the exact optimum by at most a few ulps of
 * the extent in general position, and by ACD_TOL_REL_DIST x extent in degenerate support sets.
 * ACD_ERR_DEGENERATE for n = 0, ACD_ERR_INVALID_INPUT for NaN/Inf. */
acd_status acd_min_sphere(const double *points, size_t n, acd_sphere *out, acd_error *err);

#endif
