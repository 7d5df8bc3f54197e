/* Brute-force minimum convex decomposition for the exact2d tests: enumerate sets of pairwise
 * non-crossing diagonals of a small simple polygon (one ring, counterclockwise, exact predicates)
 * and keep the smallest whose pieces are all convex (every angular sector at every vertex is at
 * most 180 degrees). Header-only, static functions. */
#ifndef ACD_TESTS_EXACT2D_BRUTE_H
#define ACD_TESTS_EXACT2D_BRUTE_H

#include <math.h>
#include <stdlib.h>

#include "acd/polygon.h"
#include "core/predicates.h"

#define BR_MAXN 14
#define BR_V2(p) ((const double *)(const void *)(p))

typedef struct br_ctx {
    const acd_vec2 *v;
    int n, nd;
    int da[BR_MAXN * BR_MAXN], db[BR_MAXN * BR_MAXN];
    unsigned char cross[BR_MAXN * BR_MAXN][BR_MAXN * BR_MAXN];
    int chosen[BR_MAXN * BR_MAXN], nch, best;
} br_ctx;

/* 1 if the ring is simple (no two non-adjacent edges meet, adjacent ones only at their vertex). */
static inline int br_is_simple(const acd_vec2 *v, int n) {
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++) {
            const double *a = BR_V2(&v[i]), *b = BR_V2(&v[(i + 1) % n]), *c = BR_V2(&v[j]), *d = BR_V2(&v[(j + 1) % n]);
            acd_seg_relation r = acd_segments_relation(a, b, c, d);
            int adjacent = (j == i + 1) || (i == 0 && j == n - 1);
            if (!adjacent && r != ACD_SEG_DISJOINT) return 0;
            if (adjacent && (r == ACD_SEG_OVERLAP || r == ACD_SEG_PROPER)) return 0;
        }
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            if (v[i].x == v[j].x && v[i].y == v[j].y) return 0;
    return 1;
}

/* Is direction v[a]->t strictly inside the interior angle at a (ring counterclockwise)? */
static inline int br_in_cone(const acd_vec2 *v, int n, int a, const double *t) {
    const double *p = BR_V2(&v[(a + n - 1) % n]), *x = BR_V2(&v[a]), *q = BR_V2(&v[(a + 1) % n]);
    int conv = acd_orient2d_sign(p, x, q), s1 = acd_orient2d_sign(p, x, t), s2 = acd_orient2d_sign(x, q, t);
    if (conv >= 0) return s1 > 0 && s2 > 0;
    return s1 > 0 || s2 > 0;
}

static inline int br_valid_diag(const acd_vec2 *v, int n, int a, int b) {
    if ((a + 1) % n == b || (b + 1) % n == a || a == b) return 0;
    const double *pa = BR_V2(&v[a]), *pb = BR_V2(&v[b]);
    for (int i = 0; i < n; i++) {
        int j = (i + 1) % n;
        if (i != a && i != b && acd_point_on_segment(BR_V2(&v[i]), pa, pb)) return 0;
        if (i == a || i == b || j == a || j == b) continue;
        if (acd_segments_relation(pa, pb, BR_V2(&v[i]), BR_V2(&v[j])) != ACD_SEG_DISJOINT) return 0;
    }
    return br_in_cone(v, n, a, pb) && br_in_cone(v, n, b, pa);
}

static inline double br_angle(const acd_vec2 *v, int n, int x, int to) {
    const acd_vec2 *o = &v[x], *nx = &v[(x + 1) % n], *t = &v[to];
    double ux = nx->x - o->x, uy = nx->y - o->y, wx = t->x - o->x, wy = t->y - o->y;
    double a = atan2(ux * wy - uy * wx, ux * wx + uy * wy);
    return a < 0 ? a + 6.283185307179586 : a;
}

/* All sectors at all vertices convex with the chosen diagonals? */
static inline int br_convex(const br_ctx *c) {
    int n = c->n;
    for (int x = 0; x < n; x++) {
        int nb[BR_MAXN + 2], k = 0;
        nb[k++] = (x + 1) % n;
        for (int q = 0; q < c->nch; q++) {
            int d = c->chosen[q];
            if (c->da[d] == x) nb[k++] = c->db[d];
            else if (c->db[d] == x) nb[k++] = c->da[d];
        }
        /* sort the diagonal ends by angle from the edge to the next vertex */
        for (int i = 1; i < k; i++)
            for (int j = i; j > 1 && br_angle(c->v, n, x, nb[j]) < br_angle(c->v, n, x, nb[j - 1]); j--) {
                int t = nb[j];
                nb[j] = nb[j - 1];
                nb[j - 1] = t;
            }
        nb[k++] = (x + n - 1) % n;
        for (int i = 0; i + 1 < k; i++) {
            const double *o = BR_V2(&c->v[x]), *u = BR_V2(&c->v[nb[i]]), *w = BR_V2(&c->v[nb[i + 1]]);
            int s = acd_orient2d_sign(o, u, w);
            if (s < 0) return 0;
            if (s == 0 && (u[0] - o[0]) * (w[0] - o[0]) + (u[1] - o[1]) * (w[1] - o[1]) > 0) return 0;
        }
    }
    return 1;
}

static inline void br_search(br_ctx *c, int from) {
    if (c->nch + 1 >= c->best) return;
    if (br_convex(c)) {
        c->best = c->nch + 1;
        return;
    }
    for (int d = from; d < c->nd; d++) {
        int ok = 1;
        for (int q = 0; q < c->nch && ok; q++)
            if (c->cross[d][c->chosen[q]]) ok = 0;
        if (!ok) continue;
        c->chosen[c->nch++] = d;
        br_search(c, d + 1);
        c->nch--;
    }
}

/* Minimum number of convex pieces (no Steiner points) of the simple counterclockwise ring v[0..n-1]. */
static inline int br_mcd(const acd_vec2 *v, int n) {
    static br_ctx c; /* large; tests are single-threaded */
    c.v = v;
    c.n = n;
    c.nd = 0;
    for (int a = 0; a < n; a++)
        for (int b = a + 2; b < n; b++)
            if (br_valid_diag(v, n, a, b)) {
                c.da[c.nd] = a;
                c.db[c.nd] = b;
                c.nd++;
            }
    for (int d = 0; d < c.nd; d++)
        for (int e = 0; e < c.nd; e++)
            c.cross[d][e] = acd_segments_relation(BR_V2(&v[c.da[d]]), BR_V2(&v[c.db[d]]), BR_V2(&v[c.da[e]]),
                                                  BR_V2(&v[c.db[e]])) == ACD_SEG_PROPER;
    c.nch = 0;
    c.best = n; /* a triangulation has n - 2 pieces */
    br_search(&c, 0);
    return c.best;
}

#endif
