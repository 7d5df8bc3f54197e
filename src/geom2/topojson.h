/* geom2/topojson: TopoJSON polygon reader (arcs, quantized delta-encoded arcs with a transform,
 * reversed arc indices, Polygon / MultiPolygon with holes, geometry collections), with cJSON. */
#ifndef ACD_GEOM2_TOPOJSON_H
#define ACD_GEOM2_TOPOJSON_H

#include <cjson/cJSON.h>

#include "acd/polygon.h"

/* Every Polygon (and every polygon of a MultiPolygon) of every object becomes one polygon of out
 * (not normalized). */
acd_status acd_topojson_parse(acd_polygon_set *out, const char *text, size_t len, const char *name, acd_error *err);

/* The same on parsed JSON (root must be a Topology). object != NULL reads only that member of
 * "objects" (an unknown name is an error listing the names); feature != NULL keeps only the
 * geometries it selects (geom2/feature_select.h; none selected is an error). */
acd_status acd_topojson_from_json(acd_polygon_set *out, const cJSON *root, const char *name, const char *object,
                                  const char *feature, acd_error *err);

#endif
