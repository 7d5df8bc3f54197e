/* core/tolerance: named tolerances, all relative to the scale of the input.
 *
 * Decisions about topology (sides, crossings, notches) use the exact predicates and need no
 * tolerance. Tolerances appear only where a quantity is compared with a length or an area that
 * came out of inexact arithmetic (computed intersection points, areas summed over pieces,
 * volumes after a cut). Each is a multiple of the input's extent (bounding-box diagonal). */
#ifndef ACD_CORE_TOLERANCE_H
#define ACD_CORE_TOLERANCE_H

#include <stddef.h>

#include "core/error.h"

/* Relative length below which two computed points are the same point. */
#define ACD_TOL_REL_WELD 1e-12
/* Relative length under which a computed distance counts as zero (concavity, hull distance). */
#define ACD_TOL_REL_DIST 1e-10
/* Relative tolerance for areas and volumes that must add up (partition checks). */
#define ACD_TOL_REL_MEASURE 1e-9

/* Largest coordinate magnitude accepted for geometry (2D polygons, 3D meshes). The exact
 * predicates are exact only while their products do not overflow: orient3d multiplies three
 * coordinate differences and insphere five, so 1e60 keeps every product below 1e301. Real data
 * is many orders of magnitude below; larger input is refused with a message naming the vertex. */
#define ACD_COORD_MAX 1e60

/* Smallest model accepted for 3D geometry (the largest extent of its bounding box; a model of no
 * extent is left to the callers' degeneracy checks). Below it the products of coordinate
 * differences (exact predicates, volumes: the size to the 3rd to 6th power) leave the range of
 * normal doubles and decisions change: CGAL's star.off scaled exactly by 2^-266 gave 25 parts
 * instead of 11 at tau 0.05; below about 1e-103 volumes underflow to 0. The mirror of
 * ACD_COORD_MAX (docs/results/3d-robustness.md). */
#define ACD_EXTENT_MIN 1e-60

typedef struct acd_scale {
    double extent;  /* bounding-box diagonal of the input (>= tiny positive) */
    double weld;    /* ACD_TOL_REL_WELD * extent */
    double dist;    /* ACD_TOL_REL_DIST * extent */
} acd_scale;

/* Checks that every coordinate of n points of dimension dim is finite and at most ACD_COORD_MAX
 * in magnitude; fails with ACD_ERR_INVALID_INPUT naming the first offending vertex. */
acd_status acd_check_coordinates(const double *pts, size_t n, int dim, acd_error *err);

/* Checks that the largest bounding-box extent of n points of dimension dim is 0 or at least
 * ACD_EXTENT_MIN; fails with ACD_ERR_INVALID_INPUT naming the extent otherwise. */
acd_status acd_check_extent(const double *pts, size_t n, int dim, acd_error *err);

/* Scale of n points of dimension dim (2 or 3) stored contiguously. */
acd_scale acd_scale_of_points(const double *pts, size_t n, int dim);

#endif
