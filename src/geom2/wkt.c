/* geom2/wkt: WKT polygon reader (stub, replaced below). */
#include "geom2/wkt.h"

#include "core/error.h"

acd_status acd_wkt_parse(acd_polygon_set *out, const char *text, size_t len, const char *name, acd_error *err) {
    (void)out, (void)text, (void)len;
    return acd_fail(err, ACD_ERR_UNSUPPORTED, "%s: WKT input is not supported yet", name);
}
