/* geom2/geojson: GeoJSON (RFC 7946) polygon reader, with cJSON.
 *
 * Polygon and MultiPolygon geometries are collected wherever they appear: at the top level, as a
 * Feature's geometry, in a FeatureCollection or in (nested) GeometryCollections. Points and
 * lines are skipped; a null geometry or empty coordinates are skipped (an empty geometry).
 * Positions may carry an altitude (3rd and further numbers), which is ignored. Every error
 * names the JSON path, e.g. "features[2].geometry.coordinates[0][5]". */
#include "geom2/geojson.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "geom2/feature_select.h"
#include "geom2/polygon_build.h"

#define GJ_MAX_DEPTH 64
#define GJ_PATH 192

typedef struct gj {
    acd_pbuild b;
    const char *name;
    acd_error *err;
    const char *feature; /* selector (NULL = every polygon) */
    size_t features;     /* Features looked at */
    size_t matched;      /* Features the selector kept */
} gj;

/* Paths longer than GJ_PATH are cut short; they only serve messages. */
static void path_index(char *dst, size_t size, const char *base, const char *field, size_t i) {
    if (snprintf(dst, size, "%s%s[%zu]", base, field, i) >= (int)size) dst[size - 1] = '\0';
}

static void path_field(char *dst, size_t size, const char *base, const char *field) {
    if (snprintf(dst, size, "%s%s%s", base, *base ? "." : "", field) >= (int)size) dst[size - 1] = '\0';
}

static acd_status read_position(gj *g, const cJSON *pos, const char *ring_path, size_t i) {
    char path[GJ_PATH];
    path_index(path, sizeof path, ring_path, "", i);
    if (!cJSON_IsArray(pos))
        return acd_fail(g->err, ACD_ERR_PARSE, "%s: %s: expected a position [x, y]", g->name, path);
    const cJSON *x = pos->child, *y = x ? x->next : NULL;
    if (!x || !y || !cJSON_IsNumber(x) || !cJSON_IsNumber(y))
        return acd_fail(g->err, ACD_ERR_PARSE, "%s: %s: expected a position [x, y] of two numbers", g->name, path);
    if (!isfinite(x->valuedouble) || !isfinite(y->valuedouble))
        return acd_fail(g->err, ACD_ERR_PARSE, "%s: %s: coordinate out of the range of double", g->name, path);
    return acd_pbuild_add_point(&g->b, x->valuedouble, y->valuedouble, g->err);
}

/* Fast path for a well-formed position; falls back to read_position for the message. */
static acd_status add_position(gj *g, const cJSON *pos, const char *ring_path, size_t i) {
    const cJSON *x = cJSON_IsArray(pos) ? pos->child : NULL, *y = x ? x->next : NULL;
    if (x && y && cJSON_IsNumber(x) && cJSON_IsNumber(y) && isfinite(x->valuedouble) && isfinite(y->valuedouble))
        return acd_pbuild_add_point(&g->b, x->valuedouble, y->valuedouble, g->err);
    return read_position(g, pos, ring_path, i);
}

/* coordinates of one Polygon: an array of rings, each an array of positions */
static acd_status read_polygon(gj *g, const cJSON *coords, const char *path) {
    if (!cJSON_IsArray(coords))
        return acd_fail(g->err, ACD_ERR_PARSE, "%s: %s: expected an array of rings", g->name, path);
    if (!coords->child) return ACD_OK; /* empty polygon */
    acd_status st = acd_pbuild_begin_polygon(&g->b, g->err);
    size_t r = 0;
    char rp[GJ_PATH];
    for (const cJSON *ring = coords->child; ring && st == ACD_OK; ring = ring->next, r++) {
        path_index(rp, sizeof rp, path, "", r);
        if (!cJSON_IsArray(ring) || !ring->child)
            return acd_fail(g->err, ACD_ERR_PARSE, "%s: %s: expected a ring (a non-empty array of positions)",
                            g->name, rp);
        st = acd_pbuild_begin_ring(&g->b, g->err);
        size_t i = 0;
        for (const cJSON *pos = ring->child; pos && st == ACD_OK; pos = pos->next, i++)
            st = add_position(g, pos, rp, i);
    }
    if (st == ACD_OK) st = acd_pbuild_end_polygon(&g->b, g->err);
    return st;
}

static acd_status walk(gj *g, const cJSON *node, const char *path, int depth, int keep);

static acd_status walk_array(gj *g, const cJSON *arr, const char *path, const char *field, int depth, int keep) {
    char fp[GJ_PATH], ip[GJ_PATH];
    path_field(fp, sizeof fp, path, field);
    if (!cJSON_IsArray(arr)) return acd_fail(g->err, ACD_ERR_PARSE, "%s: %s: expected an array", g->name, fp);
    size_t i = 0;
    for (const cJSON *it = arr->child; it; it = it->next, i++) {
        path_index(ip, sizeof ip, fp, "", i);
        acd_status st = walk(g, it, ip, depth + 1, keep);
        if (st != ACD_OK) return st;
    }
    return ACD_OK;
}

/* keep: polygons found here are collected (no selector, or inside a selected Feature). */
static acd_status walk(gj *g, const cJSON *node, const char *path, int depth, int keep) {
    const char *where = *path ? path : "top level";
    if (depth > GJ_MAX_DEPTH)
        return acd_fail(g->err, ACD_ERR_PARSE, "%s: %s: geometries nested more than %d deep", g->name, where,
                        GJ_MAX_DEPTH);
    if (cJSON_IsArray(node)) return walk_array(g, node, path, "", depth, keep); /* lenient: a bare list */
    if (!cJSON_IsObject(node))
        return acd_fail(g->err, ACD_ERR_PARSE, "%s: %s: expected a GeoJSON object", g->name, where);
    const cJSON *type = cJSON_GetObjectItemCaseSensitive(node, "type");
    if (!cJSON_IsString(type) || !type->valuestring)
        return acd_fail(g->err, ACD_ERR_PARSE, "%s: %s: expected a \"type\" member (a string)", g->name, where);
    const char *t = type->valuestring;
    char fp[GJ_PATH];
    if (strcmp(t, "FeatureCollection") == 0)
        return walk_array(g, cJSON_GetObjectItemCaseSensitive(node, "features"), path, "features", depth, keep);
    if (strcmp(t, "GeometryCollection") == 0)
        return walk_array(g, cJSON_GetObjectItemCaseSensitive(node, "geometries"), path, "geometries", depth, keep);
    if (strcmp(t, "Feature") == 0) {
        g->features++;
        if (!keep && acd_feature_matches(node, g->feature)) {
            keep = 1;
            g->matched++;
        }
        const cJSON *geom = cJSON_GetObjectItemCaseSensitive(node, "geometry");
        if (!geom || cJSON_IsNull(geom)) return ACD_OK;
        path_field(fp, sizeof fp, path, "geometry");
        return walk(g, geom, fp, depth + 1, keep);
    }
    if (strcmp(t, "Polygon") == 0 || strcmp(t, "MultiPolygon") == 0) {
        const cJSON *coords = cJSON_GetObjectItemCaseSensitive(node, "coordinates");
        path_field(fp, sizeof fp, path, "coordinates");
        if (!coords) return acd_fail(g->err, ACD_ERR_PARSE, "%s: %s: missing \"coordinates\"", g->name, where);
        if (!keep) return ACD_OK;
        if (t[0] == 'P') return read_polygon(g, coords, fp);
        if (!cJSON_IsArray(coords))
            return acd_fail(g->err, ACD_ERR_PARSE, "%s: %s: expected an array of polygons", g->name, fp);
        size_t i = 0;
        char ip[GJ_PATH];
        for (const cJSON *pc = coords->child; pc; pc = pc->next, i++) {
            path_index(ip, sizeof ip, fp, "", i);
            acd_status st = read_polygon(g, pc, ip);
            if (st != ACD_OK) return st;
        }
        return ACD_OK;
    }
    if (strcmp(t, "Point") == 0 || strcmp(t, "MultiPoint") == 0 || strcmp(t, "LineString") == 0 ||
        strcmp(t, "MultiLineString") == 0)
        return ACD_OK; /* not polygonal: skipped */
    return acd_fail(g->err, ACD_ERR_PARSE, "%s: %s: unknown GeoJSON type \"%.40s\"", g->name, where, t);
}

/* 1-based line and column of byte offset off. */
static void line_col(const char *text, size_t off, size_t *line, size_t *col) {
    *line = 1;
    *col = 1;
    for (size_t i = 0; i < off; i++) {
        if (text[i] == '\n') {
            (*line)++;
            *col = 1;
        } else {
            (*col)++;
        }
    }
}

cJSON *acd_json_parse(const char *text, size_t len, const char *name, acd_error *err) {
    if (!name) name = "<input>";
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithLengthOpts(text, len, &end, 0);
    size_t line, col;
    if (!root) {
        size_t off = end && end >= text && end <= text + len ? (size_t)(end - text) : 0;
        line_col(text, off, &line, &col);
        acd_fail(err, ACD_ERR_PARSE, "%s:%zu:%zu: invalid JSON (byte offset %zu)", name, line, col, off);
        return NULL;
    }
    size_t off = end && end >= text && end <= text + len ? (size_t)(end - text) : len;
    while (off < len && (text[off] == ' ' || text[off] == '\t' || text[off] == '\r' || text[off] == '\n')) off++;
    if (off < len) {
        cJSON_Delete(root);
        line_col(text, off, &line, &col);
        acd_fail(err, ACD_ERR_PARSE, "%s:%zu:%zu: unexpected content after the JSON value", name, line, col);
        return NULL;
    }
    return root;
}

int acd_json_is_topology(const cJSON *root) {
    const cJSON *type = cJSON_IsObject(root) ? cJSON_GetObjectItemCaseSensitive(root, "type") : NULL;
    return cJSON_IsString(type) && type->valuestring && strcmp(type->valuestring, "Topology") == 0;
}

acd_status acd_geojson_from_json(acd_polygon_set *out, const cJSON *root, const char *name, const char *feature,
                                 acd_error *err) {
    memset(out, 0, sizeof *out);
    gj g;
    acd_pbuild_init(&g.b);
    g.name = name ? name : "<input>";
    g.err = err;
    g.feature = feature;
    g.features = g.matched = 0;
    acd_status st = walk(&g, root, "", 0, feature == NULL);
    if (st == ACD_OK && feature && g.matched == 0)
        st = acd_fail(err, ACD_ERR_INVALID_INPUT,
                      "%s: no Feature matches the selector '%.80s' (%zu Features looked at; a selector 'VALUE' "
                      "matches the id or any property, 'KEY=VALUE' one property)",
                      g.name, feature, g.features);
    if (st == ACD_OK) st = acd_pbuild_take(&g.b, out, err);
    acd_pbuild_free(&g.b);
    return st;
}

acd_status acd_geojson_parse(acd_polygon_set *out, const char *text, size_t len, const char *name, acd_error *err) {
    memset(out, 0, sizeof *out);
    cJSON *root = acd_json_parse(text, len, name, err);
    if (!root) return ACD_ERR_PARSE;
    acd_status st = acd_geojson_from_json(out, root, name, NULL, err);
    cJSON_Delete(root);
    return st;
}
