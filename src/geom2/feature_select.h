/* geom2/feature_select: which GeoJSON Features / TopoJSON geometries a selector keeps
 * (acd_polygon_read_options.feature, the CLI's --feature). */
#ifndef ACD_GEOM2_FEATURE_SELECT_H
#define ACD_GEOM2_FEATURE_SELECT_H

#include <cjson/cJSON.h>

/* 1 if the JSON object obj (a GeoJSON Feature or a TopoJSON geometry) matches sel:
 *  - "KEY=VALUE": its property KEY (or, for KEY "id", its "id" member) equals VALUE;
 *  - "VALUE": its "id" or any of its properties equals VALUE.
 * A string equals VALUE when the bytes are the same; a number when VALUE reads as the same
 * double. */
int acd_feature_matches(const cJSON *obj, const char *sel);

#endif
