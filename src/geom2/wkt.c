/* geom2/wkt: Well-Known Text polygon reader (OGC Simple Features, ISO 13249-3 text form).
 *
 * Accepted: POLYGON, MULTIPOLYGON and GEOMETRYCOLLECTION (nested up to WKT_MAX_DEPTH), each
 * possibly EMPTY, with an optional dimension tag Z, M or ZM (also run together: POLYGONZ).
 * The Z and M values are read and dropped (the polygon is taken in the xy plane). Without a
 * tag a point has 2 coordinates, or 3 (EWKT's implicit Z). An EWKT "SRID=n;" prefix is
 * skipped. Several geometries may follow each other, separated by blanks or ';'. Other
 * geometry types (POINT, LINESTRING, ...) are skipped. Keywords are case-insensitive. */
#include "geom2/wkt.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "geom2/numscan.h"
#include "geom2/polygon_build.h"

#define WKT_MAX_DEPTH 32

typedef struct wkt {
    acd_scan s;
    acd_pbuild b;
    const char *name;
    acd_error *err;
} wkt;

static acd_status wfail(wkt *w, const char *what) {
    char ex[40];
    return acd_fail(w->err, ACD_ERR_PARSE, "%s:%zu: %s (found %s)", w->name, w->s.line, what,
                    acd_scan_excerpt(&w->s, ex, sizeof ex));
}

static void skip(wkt *w) {
    acd_scan_skip_space(&w->s, 0);
}

/* Reads a keyword (letters) into kw, upper-cased; returns its length. */
static size_t keyword(wkt *w, char *kw, size_t size) {
    size_t k = 0;
    while (!acd_scan_eof(&w->s) && isalpha(acd_scan_peek(&w->s))) {
        if (k + 1 < size) kw[k] = (char)toupper(acd_scan_peek(&w->s));
        k++;
        w->s.pos++;
    }
    kw[k + 1 < size ? k : size - 1] = '\0';
    return k;
}

static int accept(wkt *w, char c) {
    skip(w);
    if (acd_scan_peek(&w->s) == (unsigned char)c) {
        w->s.pos++;
        return 1;
    }
    return 0;
}

/* Peeks whether the next keyword is `word` (consumes it if so). */
static int accept_word(wkt *w, const char *word) {
    skip(w);
    size_t save = w->s.pos;
    char kw[16];
    size_t n = keyword(w, kw, sizeof kw);
    if (n && n < sizeof kw && strcmp(kw, word) == 0) return 1;
    w->s.pos = save;
    return 0;
}

/* Number of extra coordinates from a tag: -1 = no tag (0 or 1 extra allowed). */
static int tag_extra(const char *tag) {
    if (!*tag) return -1;
    if (strcmp(tag, "Z") == 0 || strcmp(tag, "M") == 0) return 1;
    if (strcmp(tag, "ZM") == 0) return 2;
    return -2;
}

static acd_status read_point(wkt *w, int extra) {
    double v[4];
    int n = 0;
    for (;;) {
        skip(w);
        if (n == 4) break;
        acd_scan_result r = acd_scan_number(&w->s, &v[n]);
        if (r == ACD_SCAN_NONE) break;
        if (r != ACD_SCAN_OK) return wfail(w, "a coordinate out of the range of double");
        n++;
    }
    if (n < 2) return wfail(w, n == 0 ? "expected a point 'x y'" : "expected the y coordinate");
    if (extra >= 0 ? n != 2 + extra : n > 3) {
        char msg[96];
        snprintf(msg, sizeof msg, "a point has %d coordinates here; expected %d", n, extra >= 0 ? 2 + extra : 2);
        return wfail(w, msg);
    }
    return acd_pbuild_add_point(&w->b, v[0], v[1], w->err);
}

/* '(' ring {',' ring} ')' with ring = '(' point {',' point} ')' */
static acd_status read_polygon_text(wkt *w, int extra) {
    if (accept_word(w, "EMPTY")) return ACD_OK;
    if (!accept(w, '(')) return wfail(w, "expected '(' to open a polygon or EMPTY");
    acd_status st = acd_pbuild_begin_polygon(&w->b, w->err);
    if (st != ACD_OK) return st;
    do {
        if (!accept(w, '(')) return wfail(w, "expected '(' to open a ring");
        st = acd_pbuild_begin_ring(&w->b, w->err);
        if (st != ACD_OK) return st;
        do {
            st = read_point(w, extra);
            if (st != ACD_OK) return st;
        } while (accept(w, ','));
        if (!accept(w, ')')) return wfail(w, "expected ',' or ')' after a point");
    } while (accept(w, ','));
    if (!accept(w, ')')) return wfail(w, "expected ',' or ')' after a ring");
    return acd_pbuild_end_polygon(&w->b, w->err);
}

/* Skips a balanced parenthesized body (or EMPTY) of an unsupported geometry type. */
static acd_status skip_body(wkt *w) {
    if (accept_word(w, "EMPTY")) return ACD_OK;
    if (!accept(w, '(')) return wfail(w, "expected '(' or EMPTY");
    size_t depth = 1;
    while (depth > 0) {
        if (acd_scan_eof(&w->s)) return wfail(w, "unbalanced parentheses");
        int c = acd_scan_peek(&w->s);
        if (c == '\n') w->s.line++;
        if (c == '(') depth++;
        if (c == ')') depth--;
        w->s.pos++;
    }
    return ACD_OK;
}

static acd_status read_geometry(wkt *w, int depth) {
    if (depth > WKT_MAX_DEPTH) return wfail(w, "geometry collections nested too deep");
    skip(w);
    char kw[40];
    size_t n = keyword(w, kw, sizeof kw);
    if (n == 0 || n >= sizeof kw) return wfail(w, "expected a WKT geometry keyword such as POLYGON");
    if (strcmp(kw, "SRID") == 0 && depth == 0) {
        if (!accept(w, '=')) return wfail(w, "expected '=' after SRID");
        skip(w);
        size_t srid;
        if (acd_scan_uint(&w->s, (size_t)-1 / 2, &srid) != ACD_SCAN_OK) return wfail(w, "expected the SRID number");
        if (!accept(w, ';')) return wfail(w, "expected ';' after the SRID");
        return read_geometry(w, depth);
    }
    static const char *const types[] = {"GEOMETRYCOLLECTION", "MULTIPOLYGON", "POLYGON", "MULTILINESTRING",
                                        "LINESTRING", "MULTIPOINT", "POINT", "TRIANGLE", "TIN",
                                        "POLYHEDRALSURFACE", "CIRCULARSTRING", "COMPOUNDCURVE", "CURVEPOLYGON",
                                        "MULTICURVE", "MULTISURFACE"};
    int type = -1;
    const char *tag = "";
    for (int t = 0; t < (int)(sizeof types / sizeof *types); t++) {
        size_t tl = strlen(types[t]);
        if (strncmp(kw, types[t], tl) == 0 && tag_extra(kw + tl) != -2) {
            type = t;
            tag = kw + tl;
            break;
        }
    }
    if (type < 0) {
        char msg[96];
        snprintf(msg, sizeof msg, "unknown WKT geometry type '%s'", kw);
        return wfail(w, msg);
    }
    int extra = tag_extra(tag);
    if (extra == -1) { /* a separate tag word? */
        if (accept_word(w, "ZM")) extra = 2;
        else if (accept_word(w, "Z") || accept_word(w, "M")) extra = 1;
    }
    if (type == 0) { /* GEOMETRYCOLLECTION */
        if (accept_word(w, "EMPTY")) return ACD_OK;
        if (!accept(w, '(')) return wfail(w, "expected '(' after GEOMETRYCOLLECTION");
        do {
            acd_status st = read_geometry(w, depth + 1);
            if (st != ACD_OK) return st;
        } while (accept(w, ','));
        if (!accept(w, ')')) return wfail(w, "expected ',' or ')' in GEOMETRYCOLLECTION");
        return ACD_OK;
    }
    if (type == 1) { /* MULTIPOLYGON */
        if (accept_word(w, "EMPTY")) return ACD_OK;
        if (!accept(w, '(')) return wfail(w, "expected '(' after MULTIPOLYGON");
        do {
            acd_status st = read_polygon_text(w, extra);
            if (st != ACD_OK) return st;
        } while (accept(w, ','));
        if (!accept(w, ')')) return wfail(w, "expected ',' or ')' after a polygon of the MULTIPOLYGON");
        return ACD_OK;
    }
    if (type == 2) return read_polygon_text(w, extra);
    return skip_body(w); /* not polygonal */
}

acd_status acd_wkt_parse(acd_polygon_set *out, const char *text, size_t len, const char *name, acd_error *err) {
    memset(out, 0, sizeof *out);
    wkt w;
    acd_scan_init(&w.s, text, len);
    acd_pbuild_init(&w.b);
    w.name = name ? name : "<input>";
    w.err = err;
    acd_status st = ACD_OK;
    for (;;) {
        skip(&w);
        while (accept(&w, ';')) skip(&w);
        if (acd_scan_eof(&w.s)) break;
        st = read_geometry(&w, 0);
        if (st != ACD_OK) break;
    }
    if (st == ACD_OK) st = acd_pbuild_take(&w.b, out, err);
    acd_pbuild_free(&w.b);
    return st;
}
