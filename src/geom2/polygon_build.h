/* geom2/polygon_build: incremental construction of a polygon set by the readers.
 *
 * The readers (.poly, GeoJSON, WKT) call begin_polygon / begin_ring / add_point as they scan;
 * storage grows geometrically with the data actually read, so a huge declared count never
 * allocates before the points are there. */
#ifndef ACD_GEOM2_POLYGON_BUILD_H
#define ACD_GEOM2_POLYGON_BUILD_H

#include "acd/polygon.h"

typedef struct acd_pbuild {
    acd_vec2 *pts; /* points of the open polygon */
    size_t npts, cap_pts;
    size_t *rings; /* ring starts of the open polygon */
    size_t nrings, cap_rings;
    acd_polygon *polys; /* finished polygons */
    size_t npolys, cap_polys;
    int open; /* a polygon is open */
} acd_pbuild;

void acd_pbuild_init(acd_pbuild *b);
void acd_pbuild_free(acd_pbuild *b);
/* Ends the open polygon (if any) and opens a new one. */
acd_status acd_pbuild_begin_polygon(acd_pbuild *b, acd_error *err);
/* Opens a new ring in the open polygon (which must exist). */
acd_status acd_pbuild_begin_ring(acd_pbuild *b, acd_error *err);
acd_status acd_pbuild_add_point(acd_pbuild *b, double x, double y, acd_error *err);
/* Points of the ring being built and their number. */
acd_vec2 *acd_pbuild_ring(acd_pbuild *b, size_t *n);
/* Drops the ring being built (e.g. an EMPTY ring). */
void acd_pbuild_drop_ring(acd_pbuild *b);
/* Ends the open polygon (no-op if none). A polygon with no ring is discarded. */
acd_status acd_pbuild_end_polygon(acd_pbuild *b, acd_error *err);
/* Ends the open polygon and moves the finished ones into out (b is left empty). */
acd_status acd_pbuild_take(acd_pbuild *b, acd_polygon_set *out, acd_error *err);

#endif
