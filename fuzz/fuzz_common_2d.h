/* fuzz/fuzz_common_2d.h: the shared body of the 2D reader fuzz targets.
 *
 * Parses the input in one format; on success every polygon is validated with the sweep and,
 * when small, with the subdivision and brute force (all must agree), and the set must survive a .poly and a
 * GeoJSON round trip unchanged. A refusal must begin with the input's name, and a line it names
 * ("fuzz:L:") must exist in the input. Any disagreement aborts (a crash for libFuzzer). */
#ifndef ACD_FUZZ_COMMON_2D_H
#define ACD_FUZZ_COMMON_2D_H

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "acd/polygon.h"
#include "geom2/validate.h"
#include "fuzz_refusal.h"

static void fuzz_same_sets(const acd_polygon_set *a, const acd_polygon_set *b) {
    if (a->count != b->count) abort();
    for (size_t i = 0; i < a->count; i++) {
        const acd_polygon *p = &a->polygons[i], *q = &b->polygons[i];
        if (p->nrings != q->nrings) abort();
        if (memcmp(p->ring_start, q->ring_start, (p->nrings + 1) * sizeof(size_t)) != 0) abort();
        if (memcmp(p->points, q->points, acd_polygon_num_points(p) * sizeof(acd_vec2)) != 0) abort();
    }
}

/* Rings that normalization would change (< 3 points after the round trip's own normalization
 * dropping more, e.g. a 1-point ring) make the round trip not the identity; only valid
 * polygons are round-tripped. */
static void fuzz_2d_one(const uint8_t *data, size_t size, acd_polygon_format fmt) {
    acd_polygon_set s;
    acd_error err;
    err.message[0] = '\0';
    if (acd_polygon_set_parse(&s, (const char *)data, size, fmt, "fuzz", NULL, &err) != ACD_OK) {
        fuzz_check_refusal(err.message, "fuzz", data, size, 0);
        return;
    }
    int all_valid = 1;
    for (size_t i = 0; i < s.count; i++) {
        acd_status a = acd_polygon_validate(&s.polygons[i], i, &err);
        if (acd_polygon_num_points(&s.polygons[i]) <= 400) {
            acd_status b = acd_polygon_validate_with(&s.polygons[i], i, ACD_VALIDATE_BRUTE, NULL);
            acd_status d = acd_polygon_validate_with(&s.polygons[i], i, ACD_VALIDATE_SUBDIV, NULL);
            if (a != b || d != b) abort();
        }
        if (a != ACD_OK) all_valid = 0;
    }
    if (all_valid) {
        for (int k = 0; k < 3; k++) {
            char *text;
            size_t len;
            acd_status st = k == 2   ? acd_polygon_set_to_wkt_text(&s, &text, &len, &err)
                            : k == 1 ? acd_polygon_set_to_geojson_text(&s, 0, &text, &len, &err)
                                     : acd_polygon_set_to_poly_text(&s, &text, &len, &err);
            if (st != ACD_OK) abort();
            acd_polygon_set t;
            if (acd_polygon_set_parse(&t, text, len, ACD_POLY_FORMAT_AUTO, "rt", NULL, &err) != ACD_OK) abort();
            fuzz_same_sets(&s, &t);
            acd_polygon_set_free(&t);
            free(text);
        }
    }
    acd_polygon_set_free(&s);
}

#endif
