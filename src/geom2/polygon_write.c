/* geom2/polygon_write: writers of polygon sets as Lien's .poly, GeoJSON and WKT.
 *
 * Coordinates are printed with %.17g, which reads back to the same double, so
 * write-then-read is the identity on normalized polygons. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/polygon.h"
#include "core/error.h"

typedef struct sbuf {
    char *p;
    size_t len, cap;
    int oom;
} sbuf;

static void sb_printf(sbuf *b, const char *fmt, ...) ACD_PRINTF(2, 3);

static void sb_printf(sbuf *b, const char *fmt, ...) {
    if (b->oom) return;
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        size_t room = b->cap - b->len;
        int k = vsnprintf(b->p ? b->p + b->len : NULL, room, fmt, ap);
        va_end(ap);
        if (k < 0) {
            b->oom = 1;
            return;
        }
        if ((size_t)k < room) {
            b->len += (size_t)k;
            return;
        }
        size_t nc = b->cap ? b->cap * 2 : 4096;
        while (nc - b->len <= (size_t)k) nc *= 2;
        char *q = realloc(b->p, nc);
        if (!q) {
            b->oom = 1;
            return;
        }
        b->p = q;
        b->cap = nc;
    }
}

static acd_status check_finite(const acd_polygon_set *s, acd_error *err) {
    for (size_t i = 0; i < s->count; i++) {
        const acd_polygon *p = &s->polygons[i];
        for (size_t r = 0; r < p->nrings; r++)
            for (size_t k = 0; k < acd_polygon_ring_size(p, r); k++) {
                acd_vec2 v = acd_polygon_ring(p, r)[k];
                if (!isfinite(v.x) || !isfinite(v.y))
                    return acd_fail(err, ACD_ERR_INVALID_INPUT,
                                    "cannot write polygon %zu: chain %zu vertex %zu has a non-finite coordinate", i,
                                    r, k);
            }
    }
    return ACD_OK;
}

static acd_status finish(sbuf *b, char **text, size_t *len, acd_error *err) {
    if (b->oom || !b->p) {
        free(b->p);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory writing polygons");
    }
    *text = b->p;
    if (len) *len = b->len;
    return ACD_OK;
}

acd_status acd_polygon_set_to_poly_text(const acd_polygon_set *s, char **text, size_t *len, acd_error *err) {
    if (!s || !text) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_polygon_set_to_poly_text: NULL argument");
    *text = NULL;
    acd_status st = check_finite(s, err);
    if (st != ACD_OK) return st;
    sbuf b = {0};
    size_t chains = 0;
    for (size_t i = 0; i < s->count; i++) chains += s->polygons[i].nrings;
    sb_printf(&b, "# %zu polygon(s), written by acd %s\n%zu\n", s->count, ACD_VERSION_STRING, chains);
    for (size_t i = 0; i < s->count; i++) {
        const acd_polygon *p = &s->polygons[i];
        for (size_t r = 0; r < p->nrings; r++) {
            size_t n = acd_polygon_ring_size(p, r);
            const acd_vec2 *v = acd_polygon_ring(p, r);
            sb_printf(&b, "%zu %s\n", n, r == 0 ? "out" : "in");
            for (size_t k = 0; k < n; k++) sb_printf(&b, "%.17g %.17g\n", v[k].x, v[k].y);
            for (size_t k = 0; k < n; k++) sb_printf(&b, k + 1 < n ? "%zu " : "%zu\n", k + 1);
        }
    }
    return finish(&b, text, len, err);
}

static void geojson_rings(sbuf *b, const acd_polygon *p) {
    sb_printf(b, "[");
    for (size_t r = 0; r < p->nrings; r++) {
        size_t n = acd_polygon_ring_size(p, r);
        const acd_vec2 *v = acd_polygon_ring(p, r);
        sb_printf(b, r ? ", [" : "[");
        for (size_t k = 0; k <= n; k++) { /* GeoJSON rings repeat the first position at the end */
            acd_vec2 q = v[k < n ? k : 0];
            sb_printf(b, k ? ", [%.17g, %.17g]" : "[%.17g, %.17g]", q.x, q.y);
        }
        sb_printf(b, "]");
    }
    sb_printf(b, "]");
}

acd_status acd_polygon_set_to_geojson_text(const acd_polygon_set *s, int multipolygon, char **text, size_t *len,
                                           acd_error *err) {
    if (!s || !text)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_polygon_set_to_geojson_text: NULL argument");
    *text = NULL;
    acd_status st = check_finite(s, err);
    if (st != ACD_OK) return st;
    sbuf b = {0};
    if (multipolygon) {
        sb_printf(&b, "{\"type\": \"MultiPolygon\", \"coordinates\": [");
        for (size_t i = 0; i < s->count; i++) {
            if (i) sb_printf(&b, ",\n  ");
            geojson_rings(&b, &s->polygons[i]);
        }
        sb_printf(&b, "]}\n");
    } else {
        sb_printf(&b, "{\"type\": \"FeatureCollection\", \"features\": [");
        for (size_t i = 0; i < s->count; i++) {
            sb_printf(&b, "%s\n  {\"type\": \"Feature\", \"properties\": {\"index\": %zu}, \"geometry\": "
                          "{\"type\": \"Polygon\", \"coordinates\": ",
                      i ? "," : "", i);
            geojson_rings(&b, &s->polygons[i]);
            sb_printf(&b, "}}");
        }
        sb_printf(&b, "\n]}\n");
    }
    return finish(&b, text, len, err);
}

static void wkt_rings(sbuf *b, const acd_polygon *p) {
    sb_printf(b, "(");
    for (size_t r = 0; r < p->nrings; r++) {
        size_t n = acd_polygon_ring_size(p, r);
        const acd_vec2 *v = acd_polygon_ring(p, r);
        sb_printf(b, r ? ", (" : "(");
        for (size_t k = 0; k <= n; k++) { /* closed, like GeoJSON */
            acd_vec2 q = v[k < n ? k : 0];
            sb_printf(b, k ? ", %.17g %.17g" : "%.17g %.17g", q.x, q.y);
        }
        sb_printf(b, ")");
    }
    sb_printf(b, ")");
}

acd_status acd_polygon_set_to_wkt_text(const acd_polygon_set *s, char **text, size_t *len, acd_error *err) {
    if (!s || !text) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_polygon_set_to_wkt_text: NULL argument");
    *text = NULL;
    acd_status st = check_finite(s, err);
    if (st != ACD_OK) return st;
    sbuf b = {0};
    if (s->count == 1) {
        sb_printf(&b, "POLYGON ");
        wkt_rings(&b, &s->polygons[0]);
    } else if (s->count == 0) {
        sb_printf(&b, "MULTIPOLYGON EMPTY");
    } else {
        sb_printf(&b, "MULTIPOLYGON (");
        for (size_t i = 0; i < s->count; i++) {
            if (i) sb_printf(&b, ",\n  ");
            wkt_rings(&b, &s->polygons[i]);
        }
        sb_printf(&b, ")");
    }
    sb_printf(&b, "\n");
    return finish(&b, text, len, err);
}

acd_status acd_polygon_write_text_file(const char *path, const char *text, size_t len, acd_error *err) {
    if (!path) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "NULL output path");
    int to_stdout = strcmp(path, "-") == 0;
    FILE *f = to_stdout ? stdout : fopen(path, "wb");
    if (!f) return acd_fail(err, ACD_ERR_IO, "%s: cannot open for writing", path);
    size_t put = fwrite(text, 1, len, f);
    int bad = put != len || fflush(f) != 0;
    if (!to_stdout && fclose(f) != 0) bad = 1;
    if (bad) return acd_fail(err, ACD_ERR_IO, "%s: write error", path);
    return ACD_OK;
}

acd_status acd_polygon_set_write_poly(const acd_polygon_set *s, const char *path, acd_error *err) {
    char *text;
    size_t len;
    acd_status st = acd_polygon_set_to_poly_text(s, &text, &len, err);
    if (st != ACD_OK) return st;
    st = acd_polygon_write_text_file(path, text, len, err);
    free(text);
    return st;
}

acd_status acd_polygon_set_write_geojson(const acd_polygon_set *s, const char *path, acd_error *err) {
    char *text;
    size_t len;
    acd_status st = acd_polygon_set_to_geojson_text(s, 0, &text, &len, err);
    if (st != ACD_OK) return st;
    st = acd_polygon_write_text_file(path, text, len, err);
    free(text);
    return st;
}
