/* geom2/polygon: the polygon-with-holes value type (rings in one point array). */
#include "acd/polygon.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

acd_status acd_polygon_from_rings(acd_polygon *out, const acd_vec2 *const *rings, const size_t *ring_sizes,
                                  size_t nrings, acd_error *err) {
    memset(out, 0, sizeof *out);
    size_t total = 0;
    for (size_t r = 0; r < nrings; r++) total += ring_sizes[r];
    out->ring_start = malloc((nrings + 1) * sizeof *out->ring_start);
    out->points = malloc((total ? total : 1) * sizeof *out->points);
    if (!out->ring_start || !out->points) {
        acd_polygon_free(out);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for a polygon of %zu points", total);
    }
    size_t k = 0;
    for (size_t r = 0; r < nrings; r++) {
        out->ring_start[r] = k;
        if (ring_sizes[r]) memcpy(out->points + k, rings[r], ring_sizes[r] * sizeof *out->points);
        k += ring_sizes[r];
    }
    out->ring_start[nrings] = k;
    out->nrings = nrings;
    return ACD_OK;
}

void acd_polygon_free(acd_polygon *p) {
    if (!p) return;
    free(p->points);
    free(p->ring_start);
    memset(p, 0, sizeof *p);
}

void acd_polygon_set_free(acd_polygon_set *s) {
    if (!s) return;
    for (size_t i = 0; i < s->count; i++) acd_polygon_free(&s->polygons[i]);
    free(s->polygons);
    s->polygons = NULL;
    s->count = 0;
}

acd_status acd_polygon_copy(acd_polygon *dst, const acd_polygon *src) {
    memset(dst, 0, sizeof *dst);
    if (src->nrings == 0) return ACD_OK;
    size_t n = acd_polygon_num_points(src);
    dst->ring_start = malloc((src->nrings + 1) * sizeof *dst->ring_start);
    dst->points = malloc((n ? n : 1) * sizeof *dst->points);
    if (!dst->ring_start || !dst->points) {
        acd_polygon_free(dst);
        return ACD_ERR_NOMEM;
    }
    memcpy(dst->ring_start, src->ring_start, (src->nrings + 1) * sizeof *dst->ring_start);
    if (n) memcpy(dst->points, src->points, n * sizeof *dst->points);
    dst->nrings = src->nrings;
    return ACD_OK;
}

/* Shoelace area of one ring, computed relative to its first vertex to limit cancellation. */
static double ring_area(const acd_vec2 *v, size_t n) {
    if (n < 3) return 0.0;
    double s = 0.0;
    for (size_t i = 1; i + 1 < n; i++) {
        double ax = v[i].x - v[0].x, ay = v[i].y - v[0].y;
        double bx = v[i + 1].x - v[0].x, by = v[i + 1].y - v[0].y;
        s += ax * by - ay * bx;
    }
    return 0.5 * s;
}

double acd_polygon_area(const acd_polygon *p) {
    double a = 0.0;
    for (size_t r = 0; r < p->nrings; r++) a += ring_area(acd_polygon_ring(p, r), acd_polygon_ring_size(p, r));
    return a;
}
