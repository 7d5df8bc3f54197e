/* geom2/wkt: Well-Known Text polygon reader. */
#ifndef ACD_GEOM2_WKT_H
#define ACD_GEOM2_WKT_H

#include "acd/polygon.h"

/* Parses WKT text holding one or more POLYGON, MULTIPOLYGON or GEOMETRYCOLLECTION geometries
 * (not normalized). */
acd_status acd_wkt_parse(acd_polygon_set *out, const char *text, size_t len, const char *name, acd_error *err);

#endif
