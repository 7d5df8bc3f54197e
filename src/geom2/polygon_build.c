/* geom2/polygon_build: incremental construction of a polygon set (see polygon_build.h). */
#include "geom2/polygon_build.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

void acd_pbuild_init(acd_pbuild *b) {
    memset(b, 0, sizeof *b);
}

void acd_pbuild_free(acd_pbuild *b) {
    free(b->pts);
    free(b->rings);
    for (size_t i = 0; i < b->npolys; i++) acd_polygon_free(&b->polys[i]);
    free(b->polys);
    memset(b, 0, sizeof *b);
}

/* Makes room for one more element of size elem in *arr (capacity *cap, count n). */
static int grow(void **arr, size_t *cap, size_t n, size_t elem) {
    if (n < *cap) return 1;
    size_t nc = *cap ? *cap * 2 : 16;
    if (nc < *cap || nc > SIZE_MAX / elem) return 0;
    void *p = realloc(*arr, nc * elem);
    if (!p) return 0;
    *arr = p;
    *cap = nc;
    return 1;
}

acd_status acd_pbuild_begin_polygon(acd_pbuild *b, acd_error *err) {
    acd_status st = acd_pbuild_end_polygon(b, err);
    if (st != ACD_OK) return st;
    b->open = 1;
    b->npts = 0;
    b->nrings = 0;
    return ACD_OK;
}

acd_status acd_pbuild_begin_ring(acd_pbuild *b, acd_error *err) {
    if (!b->open) return acd_fail(err, ACD_ERR_INTERNAL, "polygon builder: ring without a polygon");
    if (!grow((void **)&b->rings, &b->cap_rings, b->nrings, sizeof *b->rings))
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory after %zu rings", b->nrings);
    b->rings[b->nrings++] = b->npts;
    return ACD_OK;
}

acd_status acd_pbuild_add_point(acd_pbuild *b, double x, double y, acd_error *err) {
    if (!b->open || b->nrings == 0) return acd_fail(err, ACD_ERR_INTERNAL, "polygon builder: point without a ring");
    if (!grow((void **)&b->pts, &b->cap_pts, b->npts, sizeof *b->pts))
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory after %zu points", b->npts);
    b->pts[b->npts].x = x;
    b->pts[b->npts].y = y;
    b->npts++;
    return ACD_OK;
}

acd_vec2 *acd_pbuild_ring(acd_pbuild *b, size_t *n) {
    if (!b->open || b->nrings == 0 || !b->pts) { /* no point stored yet */
        *n = 0;
        return NULL;
    }
    size_t s = b->rings[b->nrings - 1];
    *n = b->npts - s;
    return b->pts + s;
}

void acd_pbuild_drop_ring(acd_pbuild *b) {
    if (!b->open || b->nrings == 0) return;
    b->npts = b->rings[--b->nrings];
}

acd_status acd_pbuild_end_polygon(acd_pbuild *b, acd_error *err) {
    if (!b->open) return ACD_OK;
    b->open = 0;
    if (b->nrings == 0) return ACD_OK;
    if (!grow((void **)&b->polys, &b->cap_polys, b->npolys, sizeof *b->polys))
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory after %zu polygons", b->npolys);
    acd_polygon *p = &b->polys[b->npolys];
    memset(p, 0, sizeof *p);
    p->ring_start = malloc((b->nrings + 1) * sizeof *p->ring_start);
    p->points = malloc((b->npts ? b->npts : 1) * sizeof *p->points);
    if (!p->ring_start || !p->points) {
        acd_polygon_free(p);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for a polygon of %zu points", b->npts);
    }
    memcpy(p->ring_start, b->rings, b->nrings * sizeof *p->ring_start);
    p->ring_start[b->nrings] = b->npts;
    if (b->npts) memcpy(p->points, b->pts, b->npts * sizeof *p->points);
    p->nrings = b->nrings;
    b->npolys++;
    b->npts = 0;
    b->nrings = 0;
    return ACD_OK;
}

acd_status acd_pbuild_take(acd_pbuild *b, acd_polygon_set *out, acd_error *err) {
    acd_status st = acd_pbuild_end_polygon(b, err);
    if (st != ACD_OK) return st;
    out->polygons = b->polys;
    out->count = b->npolys;
    b->polys = NULL;
    b->npolys = b->cap_polys = 0;
    acd_pbuild_free(b);
    return ACD_OK;
}
