/* core/tolerance: named tolerances, all relative to the scale of the input.
 *
 * Decisions about topology (sides, crossings, notches) use the exact predicates and need no
 * tolerance. Tolerances appear only where a quantity is compared with a length or an area that
 * came out of inexact arithmetic (computed intersection points, areas summed over pieces,
 * volumes after a cut). Each is a multiple of the input's extent (bounding-box diagonal). */
#ifndef ACD_CORE_TOLERANCE_H
#define ACD_CORE_TOLERANCE_H

#include <stddef.h>

/* Relative length below which two computed points are the same point. */
#define ACD_TOL_REL_WELD 1e-12
/* Relative length under which a computed distance counts as zero (concavity, hull distance). */
#define ACD_TOL_REL_DIST 1e-10
/* Relative tolerance for areas and volumes that must add up (partition checks). */
#define ACD_TOL_REL_MEASURE 1e-9

typedef struct acd_scale {
    double extent;  /* bounding-box diagonal of the input (>= tiny positive) */
    double weld;    /* ACD_TOL_REL_WELD * extent */
    double dist;    /* ACD_TOL_REL_DIST * extent */
} acd_scale;

/* Scale of n points of dimension dim (2 or 3) stored contiguously. */
acd_scale acd_scale_of_points(const double *pts, size_t n, int dim);

#endif
