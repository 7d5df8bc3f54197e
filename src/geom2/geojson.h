/* geom2/geojson: GeoJSON (RFC 7946) polygon reader, with cJSON. */
#ifndef ACD_GEOM2_GEOJSON_H
#define ACD_GEOM2_GEOJSON_H

#include <cjson/cJSON.h>

#include "acd/polygon.h"

/* Parses GeoJSON text: every Polygon (and every polygon of a MultiPolygon), found at the top
 * level, in a Feature, a FeatureCollection or a GeometryCollection, becomes one polygon of out
 * (not normalized). Other geometry types are skipped. */
acd_status acd_geojson_parse(acd_polygon_set *out, const char *text, size_t len, const char *name, acd_error *err);

/* The same on parsed JSON. feature != NULL keeps only the Features it selects
 * (geom2/feature_select.h); none selected is an error naming the selector. */
acd_status acd_geojson_from_json(acd_polygon_set *out, const cJSON *root, const char *name, const char *feature,
                                 acd_error *err);

/* Parses JSON text (len bytes), or returns NULL after an error naming line, column and byte
 * offset (also for content after the value). The caller frees with cJSON_Delete. */
cJSON *acd_json_parse(const char *text, size_t len, const char *name, acd_error *err);

/* 1 if root is an object whose "type" is "Topology" (TopoJSON). */
int acd_json_is_topology(const cJSON *root);

#endif
