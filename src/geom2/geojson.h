/* geom2/geojson: GeoJSON (RFC 7946) polygon reader, with cJSON. */
#ifndef ACD_GEOM2_GEOJSON_H
#define ACD_GEOM2_GEOJSON_H

#include "acd/polygon.h"

/* Parses GeoJSON text: every Polygon (and every polygon of a MultiPolygon), found at the top
 * level, in a Feature, a FeatureCollection or a GeometryCollection, becomes one polygon of out
 * (not normalized). Other geometry types are skipped. */
acd_status acd_geojson_parse(acd_polygon_set *out, const char *text, size_t len, const char *name, acd_error *err);

#endif
