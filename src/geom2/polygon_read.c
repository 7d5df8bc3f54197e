/* geom2/polygon_read: format detection and the public entry points of the 2D readers. */
#include <cjson/cJSON.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/polygon.h"
#include "core/error.h"
#include "geom2/geojson.h"
#include "geom2/poly_io.h"
#include "geom2/topojson.h"
#include "geom2/wkt.h"

/* Detects the format from the first significant character: '{' or '[' is JSON (GeoJSON, or
 * TopoJSON when the parsed root's "type" is "Topology"), a letter WKT, and a digit, sign, '.' or
 * '#' (comment) Lien's .poly. */
static acd_polygon_format detect(const char *t, size_t n) {
    size_t i = 0;
    if (n >= 3 && (unsigned char)t[0] == 0xEF && (unsigned char)t[1] == 0xBB && (unsigned char)t[2] == 0xBF) i = 3;
    while (i < n && (t[i] == ' ' || t[i] == '\t' || t[i] == '\r' || t[i] == '\n' || t[i] == '\f' || t[i] == '\v')) i++;
    if (i >= n) return ACD_POLY_FORMAT_AUTO;
    char c = t[i];
    if (c == '{' || c == '[') return ACD_POLY_FORMAT_GEOJSON;
    if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z')) return ACD_POLY_FORMAT_WKT;
    if ((c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.' || c == '#') return ACD_POLY_FORMAT_POLY;
    return ACD_POLY_FORMAT_AUTO;
}

static size_t bounded_strlen(const char *t, size_t len) {
    const char *z = memchr(t, '\0', len);
    return z ? (size_t)(z - t) : len;
}

/* GeoJSON or TopoJSON (fmt says which, or AUTO for either), parsed once. */
static acd_status parse_json(acd_polygon_set *out, const char *text, size_t len, acd_polygon_format fmt,
                             const acd_polygon_read_options *o, const char *name, acd_error *err) {
    cJSON *root = acd_json_parse(text, len, name, err);
    if (!root) return ACD_ERR_PARSE;
    acd_status st;
    if (acd_json_is_topology(root)) {
        st = acd_topojson_from_json(out, root, name, o->object, o->feature, err);
    } else if (fmt == ACD_POLY_FORMAT_TOPOJSON) {
        st = acd_fail(err, ACD_ERR_PARSE, "%s: not TopoJSON: expected an object with \"type\": \"Topology\"", name);
    } else if (o->object) {
        st = acd_fail(err, ACD_ERR_INVALID_ARGUMENT,
                      "%s: an object name ('%.60s') selects a TopoJSON object; this file is GeoJSON", name, o->object);
    } else {
        st = acd_geojson_from_json(out, root, name, o->feature, err);
    }
    cJSON_Delete(root);
    return st;
}

acd_status acd_polygon_set_parse_opts(acd_polygon_set *out, const char *text, size_t len,
                                      const acd_polygon_read_options *opts, const char *name,
                                      acd_polygon_fixes *fixes, acd_error *err) {
    if (!out) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_polygon_set_parse: NULL output");
    memset(out, 0, sizeof *out);
    if (!text) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_polygon_set_parse: NULL text");
    acd_polygon_read_options defaults;
    memset(&defaults, 0, sizeof defaults);
    const acd_polygon_read_options *o = opts ? opts : &defaults;
    acd_polygon_format fmt = o->format;
    if (!name) name = "<input>";
    len = bounded_strlen(text, len);
    /* skip a UTF-8 byte order mark */
    if (len >= 3 && (unsigned char)text[0] == 0xEF && (unsigned char)text[1] == 0xBB && (unsigned char)text[2] == 0xBF) {
        text += 3;
        len -= 3;
    }
    if (fmt == ACD_POLY_FORMAT_AUTO) {
        fmt = detect(text, len);
        if (fmt == ACD_POLY_FORMAT_AUTO)
            return acd_fail(err, ACD_ERR_PARSE,
                            "%s: cannot tell the format: expected a .poly file (starting with the number of chains), "
                            "GeoJSON or TopoJSON ('{') or WKT (POLYGON/MULTIPOLYGON)%s",
                            name, len ? "" : " but the input is empty");
        if (fmt == ACD_POLY_FORMAT_GEOJSON) fmt = ACD_POLY_FORMAT_AUTO; /* JSON: GeoJSON or TopoJSON */
    }
    if ((o->feature || o->object) && (fmt == ACD_POLY_FORMAT_POLY || fmt == ACD_POLY_FORMAT_WKT))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT,
                        "%s: a feature or object selector applies to GeoJSON and TopoJSON only, not to %s", name,
                        fmt == ACD_POLY_FORMAT_POLY ? ".poly" : "WKT");
    acd_status st;
    switch (fmt) {
    case ACD_POLY_FORMAT_POLY: {
        size_t ignored = 0;
        st = acd_poly_parse(out, text, len, name, &ignored, err);
        if (fixes) fixes->chains_ignored += ignored;
        break;
    }
    case ACD_POLY_FORMAT_AUTO: /* JSON detected */
    case ACD_POLY_FORMAT_GEOJSON:
    case ACD_POLY_FORMAT_TOPOJSON: st = parse_json(out, text, len, fmt, o, name, err); break;
    case ACD_POLY_FORMAT_WKT: st = acd_wkt_parse(out, text, len, name, err); break;
    default: return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_polygon_set_parse: unknown format %d", (int)fmt);
    }
    if (st != ACD_OK) return st;
    if (out->count == 0) {
        acd_polygon_set_free(out);
        return acd_fail(err, ACD_ERR_DEGENERATE, "%s: contains no polygon", name);
    }
    for (size_t i = 0; i < out->count; i++) {
        st = acd_polygon_normalize(&out->polygons[i], fixes, err);
        if (st != ACD_OK) {
            acd_polygon_set_free(out);
            return st;
        }
    }
    return ACD_OK;
}

acd_status acd_polygon_set_parse(acd_polygon_set *out, const char *text, size_t len, acd_polygon_format fmt,
                                 const char *name, acd_polygon_fixes *fixes, acd_error *err) {
    acd_polygon_read_options o;
    memset(&o, 0, sizeof o);
    o.format = fmt;
    return acd_polygon_set_parse_opts(out, text, len, &o, name, fixes, err);
}

acd_status acd_polygon_set_read_file(acd_polygon_set *out, const char *path, acd_polygon_format fmt,
                                     acd_polygon_fixes *fixes, acd_error *err) {
    acd_polygon_read_options o;
    memset(&o, 0, sizeof o);
    o.format = fmt;
    return acd_polygon_set_read_file_opts(out, path, &o, fixes, err);
}

acd_status acd_polygon_set_read_file_opts(acd_polygon_set *out, const char *path,
                                          const acd_polygon_read_options *opts, acd_polygon_fixes *fixes,
                                          acd_error *err) {
    if (!out) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_polygon_set_read_file: NULL output");
    memset(out, 0, sizeof *out);
    if (!path) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_polygon_set_read_file: NULL path");
    FILE *f = fopen(path, "rb");
    if (!f) return acd_fail(err, ACD_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    if (!buf) {
        fclose(f);
        return acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory reading the file", path);
    }
    for (;;) {
        if (n == cap) {
            if (cap > SIZE_MAX / 2) break;
            char *nb = realloc(buf, cap * 2);
            if (!nb) {
                free(buf);
                fclose(f);
                return acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory reading the file (%zu bytes so far)", path, n);
            }
            buf = nb;
            cap *= 2;
        }
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (got == 0) break;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        return acd_fail(err, ACD_ERR_IO, "%s: read error after %zu bytes", path, n);
    }
    acd_status st = acd_polygon_set_parse_opts(out, buf, n, opts, path, fixes, err);
    free(buf);
    return st;
}
