/* geom2/polygon_write: writers (stub). */
#include "acd/polygon.h"
#include "core/error.h"

acd_status acd_polygon_set_write_poly(const acd_polygon_set *s, const char *path, acd_error *err) {
    (void)s;
    return acd_fail(err, ACD_ERR_UNSUPPORTED, "%s: .poly writer not implemented yet", path);
}
acd_status acd_polygon_set_write_geojson(const acd_polygon_set *s, const char *path, acd_error *err) {
    (void)s;
    return acd_fail(err, ACD_ERR_UNSUPPORTED, "%s: GeoJSON writer not implemented yet", path);
}
