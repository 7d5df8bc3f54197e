/* acd2/ring: growable struct-of-arrays ring and exact local tests (spec acd2d.md §3.0, §5.3). */
#include "acd2/ring.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int acd2_ring_reserve(acd2_ring *r, size_t cap) {
    if (cap <= r->cap) return 0;
    size_t nc = r->cap ? r->cap : 8;
    while (nc < cap) nc *= 2;
    acd_vec2 *p = realloc(r->p, nc * sizeof *p);
    if (!p) return -1;
    r->p = p;
    int64_t *id = realloc(r->id, nc * sizeof *id);
    if (!id) return -1;
    r->id = id;
    double *c = realloc(r->c, nc * sizeof *c);
    if (!c) return -1;
    r->c = c;
    int64_t *be = realloc(r->be, nc * sizeof *be);
    if (!be) return -1;
    r->be = be;
    r->cap = nc;
    return 0;
}

int acd2_ring_push(acd2_ring *r, acd_vec2 p, int64_t id) {
    if (r->n == r->cap && acd2_ring_reserve(r, r->n + 1)) return -1;
    r->p[r->n] = p;
    r->id[r->n] = id;
    r->c[r->n] = 0;
    r->be[r->n] = -1;
    r->n++;
    return 0;
}

void acd2_ring_free(acd2_ring *r) {
    free(r->p);
    free(r->id);
    free(r->c);
    free(r->be);
    memset(r, 0, sizeof *r);
}

int acd2_ring_append_range(acd2_ring *dst, const acd2_ring *src, size_t from, size_t count) {
    if (acd2_ring_reserve(dst, dst->n + count)) return -1;
    size_t k = from;
    for (size_t c = 0; c < count; c++) {
        dst->p[dst->n] = src->p[k];
        dst->id[dst->n] = src->id[k];
        dst->c[dst->n] = src->c ? src->c[k] : 0;
        dst->be[dst->n] = src->be ? src->be[k] : -1;
        dst->n++;
        k = acd2_next(k, src->n);
    }
    return 0;
}

double acd2_ring_area2(const acd_vec2 *p, size_t n) {
    if (n < 3) return 0.0;
    double s = 0.0;
    for (size_t i = 1; i + 1 < n; i++) {
        double ax = p[i].x - p[0].x, ay = p[i].y - p[0].y;
        double bx = p[i + 1].x - p[0].x, by = p[i + 1].y - p[0].y;
        s += ax * by - ay * bx;
    }
    return s;
}

int acd2_ring_insert_on_edge(acd2_ring *r, acd_vec2 from, acd_vec2 to, acd_vec2 z, int64_t id) {
    size_t n = r->n, k = 0;
    for (; k < n; k++)
        if (acd2_same(r->p[k], from) && acd2_same(r->p[acd2_next(k, n)], to)) break;
    if (k == n) return 0;
    if (acd2_ring_reserve(r, n + 1)) return -1;
    size_t at = k + 1; /* z goes between k and k + 1 (at the end when k + 1 wraps) */
    memmove(r->p + at + 1, r->p + at, (n - at) * sizeof *r->p);
    memmove(r->id + at + 1, r->id + at, (n - at) * sizeof *r->id);
    memmove(r->c + at + 1, r->c + at, (n - at) * sizeof *r->c);
    memmove(r->be + at + 1, r->be + at, (n - at) * sizeof *r->be);
    r->p[at] = z;
    r->id[at] = id;
    r->c[at] = 0;
    r->n = n + 1;
    for (size_t i = 0; i < r->n; i++) r->be[i] = -1;
    return 1;
}

double acd2_line_offset(acd_vec2 a, acd_vec2 b, acd_vec2 z) {
    double dx = b.x - a.x, dy = b.y - a.y, l = hypot(dx, dy);
    if (!(l > 0)) return hypot(z.x - a.x, z.y - a.y);
    return fabs(acd2_orient(a, b, z)) / l;
}

void acd2_ring_clean(acd2_ring *r) {
    int changed = 1;
    while (changed && r->n >= 3) {
        changed = 0;
        size_t k = 0;
        for (size_t i = 0; i < r->n; i++) { /* drop repeats of the previous kept vertex */
            if (k > 0 && acd2_same(r->p[i], r->p[k - 1])) { changed = 1; continue; }
            r->p[k] = r->p[i];
            r->id[k] = r->id[i];
            r->c[k] = r->c[i];
            r->be[k] = r->be[i];
            k++;
        }
        while (k > 1 && acd2_same(r->p[k - 1], r->p[0])) { k--; changed = 1; }
        r->n = k;
        if (r->n < 3) break;
        /* spikes u, v, u: remove v and the second u */
        for (size_t i = 0; i < r->n && r->n >= 3; i++) {
            size_t a = acd2_prev(i, r->n), c = acd2_next(i, r->n);
            if (acd2_same(r->p[a], r->p[c])) {
                size_t lo = i < c ? i : c, hi = i < c ? c : i;
                /* delete positions i and c (c may have wrapped to 0) */
                memmove(r->p + hi, r->p + hi + 1, (r->n - hi - 1) * sizeof *r->p);
                memmove(r->id + hi, r->id + hi + 1, (r->n - hi - 1) * sizeof *r->id);
                memmove(r->c + hi, r->c + hi + 1, (r->n - hi - 1) * sizeof *r->c);
                memmove(r->be + hi, r->be + hi + 1, (r->n - hi - 1) * sizeof *r->be);
                r->n--;
                memmove(r->p + lo, r->p + lo + 1, (r->n - lo - 1) * sizeof *r->p);
                memmove(r->id + lo, r->id + lo + 1, (r->n - lo - 1) * sizeof *r->id);
                memmove(r->c + lo, r->c + lo + 1, (r->n - lo - 1) * sizeof *r->c);
                memmove(r->be + lo, r->be + lo + 1, (r->n - lo - 1) * sizeof *r->be);
                r->n--;
                changed = 1;
                break;
            }
        }
    }
}

int acd2_ring_find_repeat(const acd2_ring *r, size_t *i, size_t *j, unsigned char *mark, int64_t id_limit) {
    /* mark[] has id_limit entries, all zero on entry and on exit */
    int found = 0;
    size_t fi = 0, fj = 0;
    for (size_t k = 0; k < r->n && !found; k++) {
        int64_t id = r->id[k];
        if (id < 0 || id >= id_limit) continue;
        if (mark[id]) {
            found = 1;
            fj = k;
            for (size_t q = 0; q < k; q++)
                if (r->id[q] == id) { fi = q; break; }
        }
        mark[id] = 1;
    }
    for (size_t k = 0; k < r->n; k++)
        if (r->id[k] >= 0 && r->id[k] < id_limit) mark[r->id[k]] = 0;
    if (found) { *i = fi; *j = fj; }
    return found;
}

int acd2_in_wedge(acd_vec2 u, acd_vec2 v, acd_vec2 w, acd_vec2 q) {
    int a = acd2_orient_sign(u, v, q), b = acd2_orient_sign(v, w, q);
    if (acd2_orient_sign(u, v, w) > 0) return a > 0 && b > 0;
    /* reflex or straight: the complement of the closed convex exterior cone */
    return a > 0 || b > 0;
}

int acd2_between(acd_vec2 a, acd_vec2 b, acd_vec2 q, int incl_b) {
    double dx = b.x - a.x, dy = b.y - a.y;
    double lo, hi, t;
    if ((dx < 0 ? -dx : dx) >= (dy < 0 ? -dy : dy)) {
        lo = a.x; hi = b.x; t = q.x;
    } else {
        lo = a.y; hi = b.y; t = q.y;
    }
    if (incl_b && t == hi) return 1;
    if (lo < hi) return t > lo && t < hi;
    return t < lo && t > hi;
}
