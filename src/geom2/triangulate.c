/* geom2/triangulate: polygon-with-holes triangulation by hole bridging and ear clipping.
 *
 * References: ear clipping by the two-ears theorem (G. H. Meisters, "Polygons have ears",
 * Amer. Math. Monthly 82, 1975); hole bridging through the rightmost hole vertex (D. Eberly,
 * "Triangulation by ear clipping", Geometric Tools, 2002). The dissertation triangulates pockets
 * with FIST (IV.D.1); this is our own implementation of the same classical method.
 *
 * design:
 *   1. Lay the rings out as one doubly linked node list per ring: the outer ring counterclockwise,
 *      the holes clockwise (each ring's orientation is decided exactly at its lowest vertex), so the
 *      polygon's interior is always on the left.
 *   2. Holes in decreasing order of their rightmost vertex M: find an outer-list node V such that
 *      the segment MV is a valid bridge (it leaves M and V into the interior, checked with exact
 *      cone tests, and it meets no edge of the outer list or of a hole still unmerged except at M
 *      and V, checked with exact orientations). The candidate comes from a ray cast to the right of
 *      M (Eberly) and is validated exactly; if it fails, every outer node is tried by increasing
 *      distance. Splice the hole in through two duplicated nodes (M', V').
 *   3. Ear clipping over the single weakly simple list: a convex node b (exact orient2d > 0) is an
 *      ear when no other reflex or flat node lies in the closed triangle (a, b, c), nodes with the
 *      coordinates of a, b or c excepted (bridge duplicates). A uniform grid over the nodes limits
 *      that test to nearby nodes. When a whole pass finds no ear: drop a flat node (zero-area
 *      triangle, the region is unchanged), then accept an ear blocked only on its boundary, then
 *      (invalid input only) clip any convex node, counted in `forced`.
 *   Each clip removes one node and emits one triangle, so n + 2h - 2 triangles come out. */
#include "geom2/triangulate.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/predicates.h"

#define NONE ((size_t)-1)

/* The coordinates of an acd_vec2 as the double[2] the predicates take. */
#define V2(p) ((const double *)(const void *)(p))

typedef struct tri_ctx {
    const acd_vec2 *pts;
    size_t *pt, *prev, *next; /* per node */
    unsigned char *removed;
    size_t nnodes;
    /* uniform grid over the nodes (CSR) */
    double minx, miny, invw, invh;
    size_t gx, gy;
    size_t *cell_start, *cell_items;
    /* output */
    size_t *tris;
    size_t ntris, ndegenerate, nforced;
} tri_ctx;

static const double *P(const tri_ctx *c, size_t node) {
    return V2(&c->pts[c->pt[node]]);
}

static int same_point(const double *a, const double *b) {
    return a[0] == b[0] && a[1] == b[1];
}

static int orient(const double *a, const double *b, const double *c) {
    return acd_orient2d_sign(a, b, c);
}

/* Is ring r counterclockwise? Decided exactly at its lowest-leftmost vertex, whose neighbours
 * (skipping coincident points) both lie in the upper half-plane; falls back to the area sign. */
static int ring_is_ccw(const acd_vec2 *pts, size_t s, size_t n) {
    size_t lo = 0;
    for (size_t i = 1; i < n; i++) {
        const acd_vec2 *q = &pts[s + i], *b = &pts[s + lo];
        if (q->y < b->y || (q->y == b->y && q->x < b->x)) lo = i;
    }
    const double *v = V2(&pts[s + lo]);
    size_t ia = lo, ic = lo;
    for (size_t k = 1; k < n; k++) {
        ia = (ia + n - 1) % n;
        if (!same_point(V2(&pts[s + ia]), v)) break;
    }
    for (size_t k = 1; k < n; k++) {
        ic = (ic + 1) % n;
        if (!same_point(V2(&pts[s + ic]), v)) break;
    }
    int o = orient(V2(&pts[s + ia]), v, V2(&pts[s + ic]));
    if (o != 0) return o > 0;
    double area = 0;
    for (size_t i = 0; i < n; i++) {
        const acd_vec2 *p = &pts[s + i], *q = &pts[s + (i + 1) % n];
        area += (p->x - v[0]) * (q->y - v[1]) - (q->x - v[0]) * (p->y - v[1]);
    }
    return area >= 0;
}

/* Is direction t inside the interior angle at node x (interior on the left of prev->x->next)? */
static int in_cone(const tri_ctx *c, size_t x, const double *t) {
    const double *a = P(c, c->prev[x]), *v = P(c, x), *b = P(c, c->next[x]);
    int conv = orient(a, v, b);
    int s1 = orient(a, v, t), s2 = orient(v, b, t);
    if (conv > 0) return s1 > 0 && s2 > 0;
    if (conv < 0) return s1 > 0 || s2 > 0;
    /* flat: straight through (a and b on opposite sides of v) or a spike */
    double dot = (a[0] - v[0]) * (b[0] - v[0]) + (a[1] - v[1]) * (b[1] - v[1]);
    if (dot < 0) return s1 > 0;
    return s1 != 0 || s2 != 0;
}

/* Does edge uw block the bridge mv (mv must meet it only at m or v)? */
static int blocks(const double *m, const double *v, const double *u, const double *w) {
    int um = same_point(u, m) || same_point(u, v), wm = same_point(w, m) || same_point(w, v);
    if (um && wm) return 0; /* the same segment (or a degenerate edge at the ends) */
    if (!um && acd_point_on_segment(u, m, v)) return 1;
    if (!wm && acd_point_on_segment(w, m, v)) return 1;
    if (!same_point(m, u) && !same_point(m, w) && acd_point_on_segment(m, u, w)) return 1;
    if (!same_point(v, u) && !same_point(v, w) && acd_point_on_segment(v, u, w)) return 1;
    int o1 = orient(m, v, u), o2 = orient(m, v, w), o3 = orient(u, w, m), o4 = orient(u, w, v);
    return o1 * o2 < 0 && o3 * o4 < 0;
}

/* Is the bridge from hole node hm to outer node ov valid? Unmerged holes are the ring ranges
 * listed in `holes` from index `first` on (their nodes still contiguous rings). */
static int bridge_ok(const tri_ctx *c, size_t hm, size_t ov, const size_t *hole_node, size_t nholes_left) {
    const double *m = P(c, hm), *v = P(c, ov);
    if (same_point(m, v)) return 0;
    if (!in_cone(c, ov, m) || !in_cone(c, hm, v)) return 0;
    size_t p = 0;
    do {
        if (blocks(m, v, P(c, p), P(c, c->next[p]))) return 0;
        p = c->next[p];
    } while (p != 0);
    for (size_t k = 0; k < nholes_left; k++) {
        size_t s = hole_node[k];
        p = s;
        do {
            if (blocks(m, v, P(c, p), P(c, c->next[p]))) return 0;
            p = c->next[p];
        } while (p != s);
    }
    return 1;
}

typedef struct dist_item {
    double d2;
    size_t node;
} dist_item;

static int cmp_dist(const void *a, const void *b) {
    const dist_item *x = a, *y = b;
    if (x->d2 < y->d2) return -1;
    if (x->d2 > y->d2) return 1;
    return (x->node > y->node) - (x->node < y->node);
}

/* Finds the outer node to bridge hole node hm to; NONE when no valid bridge exists. */
static size_t find_bridge(tri_ctx *c, size_t hm, const size_t *hole_node, size_t nholes_left, dist_item *scratch,
                          size_t nouter) {
    const double *m = P(c, hm);
    double hx = m[0], hy = m[1];
    /* 1. ray to the right of M: nearest crossing edge, its endpoint of larger x */
    double best = INFINITY;
    size_t cand = NONE;
    size_t p = 0;
    do {
        size_t q = c->next[p];
        const double *a = P(c, p), *b = P(c, q);
        if (a[1] != b[1] && (hy - a[1]) * (hy - b[1]) <= 0) {
            double x = a[0] + (hy - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
            if (x >= hx && x < best) {
                best = x;
                cand = a[0] >= b[0] ? p : q;
            }
        }
        p = q;
    } while (p != 0);
    if (cand != NONE) {
        /* 2. a reflex node inside triangle (M, I, cand) with the smallest angle to the ray hides
         * cand; prefer it (Eberly). */
        double ipt[2] = {best, hy};
        const double *cp = P(c, cand);
        int tri_o = orient(m, ipt, cp);
        size_t pick = cand;
        double pick_tan = INFINITY, pick_d = INFINITY;
        if (tri_o != 0) {
            p = 0;
            do {
                const double *x = P(c, p);
                if (x[0] >= hx && !same_point(x, cp) &&
                    ((tri_o > 0 && orient(m, ipt, x) >= 0 && orient(ipt, cp, x) >= 0 && orient(cp, m, x) >= 0) ||
                     (tri_o < 0 && orient(m, ipt, x) <= 0 && orient(ipt, cp, x) <= 0 && orient(cp, m, x) <= 0))) {
                    double dx = x[0] - hx, t = dx > 0 ? fabs(x[1] - hy) / dx : INFINITY;
                    double d = dx * dx + (x[1] - hy) * (x[1] - hy);
                    if ((t < pick_tan || (t == pick_tan && d < pick_d)) && in_cone(c, p, m)) {
                        pick = p;
                        pick_tan = t;
                        pick_d = d;
                    }
                }
                p = c->next[p];
            } while (p != 0);
        }
        /* validate the pick; nodes sharing its coordinates (earlier bridges) are tried too */
        const double *pp = P(c, pick);
        p = 0;
        do {
            if (same_point(P(c, p), pp) && bridge_ok(c, hm, p, hole_node, nholes_left)) return p;
            p = c->next[p];
        } while (p != 0);
    }
    /* 3. fallback: every outer node by increasing distance */
    size_t k = 0;
    p = 0;
    do {
        const double *x = P(c, p);
        scratch[k].d2 = (x[0] - hx) * (x[0] - hx) + (x[1] - hy) * (x[1] - hy);
        scratch[k].node = p;
        k++;
        p = c->next[p];
    } while (p != 0 && k < nouter);
    qsort(scratch, k, sizeof *scratch, cmp_dist);
    for (size_t i = 0; i < k; i++)
        if (bridge_ok(c, hm, scratch[i].node, hole_node, nholes_left)) return scratch[i].node;
    return NONE;
}

/* ---- grid ---- */

static size_t cell_x(const tri_ctx *c, double x) {
    double f = (x - c->minx) * c->invw;
    if (!(f > 0)) return 0;
    if (f >= (double)c->gx) return c->gx - 1;
    return (size_t)f;
}
static size_t cell_y(const tri_ctx *c, double y) {
    double f = (y - c->miny) * c->invh;
    if (!(f > 0)) return 0;
    if (f >= (double)c->gy) return c->gy - 1;
    return (size_t)f;
}

static int build_grid(tri_ctx *c) {
    size_t n = c->nnodes;
    double minx = INFINITY, miny = INFINITY, maxx = -INFINITY, maxy = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        const double *p = P(c, i);
        if (p[0] < minx) minx = p[0];
        if (p[0] > maxx) maxx = p[0];
        if (p[1] < miny) miny = p[1];
        if (p[1] > maxy) maxy = p[1];
    }
    size_t g = (size_t)sqrt((double)n / 2.0);
    if (g < 1) g = 1;
    if (g > 2048) g = 2048;
    c->gx = c->gy = g;
    c->minx = minx;
    c->miny = miny;
    c->invw = maxx > minx ? (double)g / (maxx - minx) : 0;
    c->invh = maxy > miny ? (double)g / (maxy - miny) : 0;
    c->cell_start = calloc(g * g + 1, sizeof *c->cell_start);
    c->cell_items = malloc((n ? n : 1) * sizeof *c->cell_items);
    if (!c->cell_start || !c->cell_items) return 0;
    for (size_t i = 0; i < n; i++) {
        const double *p = P(c, i);
        c->cell_start[cell_y(c, p[1]) * g + cell_x(c, p[0]) + 1]++;
    }
    for (size_t k = 0; k < g * g; k++) c->cell_start[k + 1] += c->cell_start[k];
    size_t *fill = malloc((g * g + 1) * sizeof *fill);
    if (!fill) return 0;
    memcpy(fill, c->cell_start, (g * g + 1) * sizeof *fill);
    for (size_t i = 0; i < n; i++) {
        const double *p = P(c, i);
        c->cell_items[fill[cell_y(c, p[1]) * g + cell_x(c, p[0])]++] = i;
    }
    free(fill);
    return 1;
}

/* Is node b an ear? strict = 0: nodes on the closed triangle block; strict = 1: only nodes in its
 * interior block. */
static int is_ear(const tri_ctx *c, size_t b, int strict) {
    size_t ia = c->prev[b], ic = c->next[b];
    const double *a = P(c, ia), *v = P(c, b), *w = P(c, ic);
    if (orient(a, v, w) <= 0) return 0;
    double x0 = fmin(a[0], fmin(v[0], w[0])), x1 = fmax(a[0], fmax(v[0], w[0]));
    double y0 = fmin(a[1], fmin(v[1], w[1])), y1 = fmax(a[1], fmax(v[1], w[1]));
    size_t cx0 = cell_x(c, x0), cx1 = cell_x(c, x1), cy0 = cell_y(c, y0), cy1 = cell_y(c, y1);
    for (size_t cy = cy0; cy <= cy1; cy++) {
        for (size_t cx = cx0; cx <= cx1; cx++) {
            size_t cell = cy * c->gx + cx;
            for (size_t k = c->cell_start[cell]; k < c->cell_start[cell + 1]; k++) {
                size_t p = c->cell_items[k];
                if (c->removed[p] || p == ia || p == b || p == ic) continue;
                const double *x = P(c, p);
                if (x[0] < x0 || x[0] > x1 || x[1] < y0 || x[1] > y1) continue;
                if (same_point(x, a) || same_point(x, v) || same_point(x, w)) continue;
                int o1 = orient(a, v, x), o2 = orient(v, w, x), o3 = orient(w, a, x);
                int inside = strict ? (o1 > 0 && o2 > 0 && o3 > 0) : (o1 >= 0 && o2 >= 0 && o3 >= 0);
                if (!inside) continue;
                if (orient(P(c, c->prev[p]), x, P(c, c->next[p])) <= 0) return 0;
            }
        }
    }
    return 1;
}

static void clip(tri_ctx *c, size_t b) {
    size_t a = c->prev[b], w = c->next[b];
    size_t *t = c->tris + 3 * c->ntris++;
    t[0] = c->pt[a];
    t[1] = c->pt[b];
    t[2] = c->pt[w];
    if (orient(P(c, a), P(c, b), P(c, w)) == 0) c->ndegenerate++;
    c->next[a] = w;
    c->prev[w] = a;
    c->removed[b] = 1;
}

/* A whole pass found no ear: pick a node by the fallback rules (see design, step 3). */
static size_t stuck_pick(tri_ctx *c, size_t start) {
    size_t p = start;
    do {
        if (orient(P(c, c->prev[p]), P(c, p), P(c, c->next[p])) == 0) return p;
        p = c->next[p];
    } while (p != start);
    p = start;
    do {
        if (is_ear(c, p, 1)) return p;
        p = c->next[p];
    } while (p != start);
    c->nforced++;
    p = start;
    do {
        if (orient(P(c, c->prev[p]), P(c, p), P(c, c->next[p])) > 0) return p;
        p = c->next[p];
    } while (p != start);
    return start;
}

static void ear_clip(tri_ctx *c, size_t start, size_t count) {
    size_t ear = start, stop = start;
    while (count > 3) {
        if (is_ear(c, ear, 0)) {
            size_t nx = c->next[ear];
            clip(c, ear);
            count--;
            ear = c->next[nx];
            stop = ear;
            continue;
        }
        ear = c->next[ear];
        if (ear == stop) {
            size_t b = stuck_pick(c, ear);
            size_t nx = c->next[b];
            clip(c, b);
            count--;
            ear = nx;
            stop = ear;
        }
    }
    if (count == 3) clip(c, ear);
}

typedef struct hole_order {
    double x, y;
    size_t ring, node; /* node: the rightmost node */
} hole_order;

static int cmp_hole(const void *a, const void *b) {
    const hole_order *h = a, *k = b;
    if (h->x != k->x) return h->x > k->x ? -1 : 1;
    if (h->y != k->y) return h->y > k->y ? -1 : 1;
    return (h->ring > k->ring) - (h->ring < k->ring);
}

acd_status acd_triangulate_rings(const acd_vec2 *points, const size_t *ring_start, size_t nrings, unsigned flags,
                                 size_t **tris, size_t *ntris, size_t *ndegenerate, size_t *nforced, acd_error *err) {
    *tris = NULL;
    *ntris = 0;
    if (ndegenerate) *ndegenerate = 0;
    if (nforced) *nforced = 0;
    if (nrings == 0) return acd_fail(err, ACD_ERR_DEGENERATE, "triangulation: the polygon has no rings");
    for (size_t r = 0; r < nrings; r++) {
        size_t n = ring_start[r + 1] - ring_start[r];
        if (ring_start[r + 1] < ring_start[r] || n < 3)
            return acd_fail(err, ACD_ERR_DEGENERATE, "triangulation: ring %zu has %zu points (needs at least 3)", r,
                            ring_start[r + 1] >= ring_start[r] ? n : 0);
        for (size_t i = ring_start[r]; i < ring_start[r + 1]; i++)
            if (!isfinite(points[i].x) || !isfinite(points[i].y))
                return acd_fail(err, ACD_ERR_INVALID_INPUT,
                                "triangulation: ring %zu vertex %zu has a non-finite coordinate (%g, %g)", r,
                                i - ring_start[r], points[i].x, points[i].y);
    }
    size_t n = ring_start[nrings] - ring_start[0], nh = nrings - 1;
    size_t cap = n + 2 * nh;
    tri_ctx c;
    memset(&c, 0, sizeof c);
    c.pts = points;
    c.pt = malloc(cap * sizeof *c.pt);
    c.prev = malloc(cap * sizeof *c.prev);
    c.next = malloc(cap * sizeof *c.next);
    c.removed = calloc(cap, 1);
    c.tris = malloc(3 * (cap - 2) * sizeof *c.tris);
    hole_order *ho = malloc((nh ? nh : 1) * sizeof *ho);
    size_t *hole_node = malloc((nh ? nh : 1) * sizeof *hole_node);
    dist_item *scratch = malloc(cap * sizeof *scratch);
    acd_status st = ACD_OK;
    if (!c.pt || !c.prev || !c.next || !c.removed || !c.tris || !ho || !hole_node || !scratch) {
        st = acd_fail(err, ACD_ERR_NOMEM, "triangulation: out of memory for %zu points", n);
        goto done;
    }
    /* 1. node lists: ring r's nodes are ring_start[r]-ring_start[0] .. contiguous */
    for (size_t r = 0; r < nrings; r++) {
        size_t s = ring_start[r], m = ring_start[r + 1] - s, base = s - ring_start[0];
        int ccw = ring_is_ccw(points, s, m);
        int want_ccw = r == 0;
        for (size_t i = 0; i < m; i++) {
            size_t node = base + i;
            c.pt[node] = (ccw == want_ccw) ? s + i : s + (m - 1 - i);
            c.next[node] = base + (i + 1) % m;
            c.prev[node] = base + (i + m - 1) % m;
        }
        if (r > 0) {
            size_t best = base;
            for (size_t i = 1; i < m; i++) {
                const acd_vec2 *q = &points[c.pt[base + i]], *b = &points[c.pt[best]];
                if (q->x > b->x || (q->x == b->x && q->y > b->y)) best = base + i;
            }
            ho[r - 1].x = points[c.pt[best]].x;
            ho[r - 1].y = points[c.pt[best]].y;
            ho[r - 1].ring = r;
            ho[r - 1].node = best;
        }
    }
    c.nnodes = n;
    /* 2. bridge the holes */
    qsort(ho, nh, sizeof *ho, cmp_hole);
    size_t nouter = ring_start[1] - ring_start[0];
    for (size_t k = 0; k < nh; k++) {
        for (size_t j = k + 1; j < nh; j++) hole_node[j - k - 1] = ho[j].node;
        size_t hm = ho[k].node;
        /* the hole's own ring also blocks: list it with the unmerged ones */
        hole_node[nh - k - 1] = hm;
        size_t ov = find_bridge(&c, hm, hole_node, nh - k, scratch, nouter);
        if (ov == NONE) {
            if (!(flags & ACD_TRI_BEST_EFFORT)) {
                const double *m = P(&c, hm);
                st = acd_fail(err, ACD_ERR_INVALID_INPUT,
                              "triangulation: hole ring %zu: no vertex of the boundary is visible from its "
                              "rightmost vertex (%g, %g); the hole crosses or touches another ring",
                              ho[k].ring, m[0], m[1]);
                goto done;
            }
            /* invalid input (a hole outside or crossing the boundary): bridge to the nearest node */
            c.nforced++;
            const double *m = P(&c, hm);
            double bd = INFINITY;
            size_t p = 0;
            do {
                const double *x = P(&c, p);
                double d = (x[0] - m[0]) * (x[0] - m[0]) + (x[1] - m[1]) * (x[1] - m[1]);
                if (d < bd) {
                    bd = d;
                    ov = p;
                }
                p = c.next[p];
            } while (p != 0);
        }
        size_t m2 = c.nnodes++, v2 = c.nnodes++;
        size_t mp = c.prev[hm], vn = c.next[ov];
        c.pt[m2] = c.pt[hm];
        c.pt[v2] = c.pt[ov];
        c.next[ov] = hm;
        c.prev[hm] = ov;
        c.next[mp] = m2;
        c.prev[m2] = mp;
        c.next[m2] = v2;
        c.prev[v2] = m2;
        c.next[v2] = vn;
        c.prev[vn] = v2;
        nouter += ring_start[ho[k].ring + 1] - ring_start[ho[k].ring] + 2;
    }
    /* 3. ear clipping */
    if (!build_grid(&c)) {
        st = acd_fail(err, ACD_ERR_NOMEM, "triangulation: out of memory for the grid of %zu nodes", c.nnodes);
        goto done;
    }
    ear_clip(&c, 0, c.nnodes);
    if (c.ntris != cap - 2) {
        st = acd_fail(err, ACD_ERR_INTERNAL, "triangulation: %zu triangles instead of %zu", c.ntris, cap - 2);
        goto done;
    }
    *tris = c.tris;
    c.tris = NULL;
    *ntris = cap - 2;
    if (ndegenerate) *ndegenerate = c.ndegenerate;
    if (nforced) *nforced = c.nforced;
    if (c.nforced && !(flags & ACD_TRI_BEST_EFFORT)) {
        /* the ear rules failed: the input was not a simple polygon with holes */
        free(*tris);
        *tris = NULL;
        *ntris = 0;
        st = acd_fail(err, ACD_ERR_INVALID_INPUT,
                      "triangulation: the rings do not bound a simple polygon with holes (%zu forced steps)",
                      c.nforced);
    }
done:
    free(c.pt);
    free(c.prev);
    free(c.next);
    free(c.removed);
    free(c.tris);
    free(c.cell_start);
    free(c.cell_items);
    free(ho);
    free(hole_node);
    free(scratch);
    return st;
}

int acd_ring_is_ccw(const acd_vec2 *pts, size_t n) {
    return n < 3 ? 1 : ring_is_ccw(pts, 0, n);
}

acd_status acd_triangulate_polygon(const acd_polygon *p, size_t **tris, size_t *ntris, size_t *ndegenerate,
                                   acd_error *err) {
    if (ndegenerate) *ndegenerate = 0;
    if (!p || !p->nrings) {
        *tris = NULL;
        *ntris = 0;
        return acd_fail(err, ACD_ERR_DEGENERATE, "triangulation: empty polygon");
    }
    return acd_triangulate_rings(p->points, p->ring_start, p->nrings, 0, tris, ntris, ndegenerate, NULL, err);
}
