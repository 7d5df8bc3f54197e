/* geom2/geojson: GeoJSON polygon reader (stub, replaced below). */
#include "geom2/geojson.h"

#include "core/error.h"

acd_status acd_geojson_parse(acd_polygon_set *out, const char *text, size_t len, const char *name, acd_error *err) {
    (void)out, (void)text, (void)len;
    return acd_fail(err, ACD_ERR_UNSUPPORTED, "%s: GeoJSON input is not supported yet", name);
}
