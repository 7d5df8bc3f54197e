/* eval/verify2d: independent check that components partition a polygon with holes and meet the
 * tau bound (Lien, dissertation Eqns 2.1, 3.1; spec ../shared/spec/acd2d.md §1.2-§1.3, §12).
 *
 * A list of counterclockwise simple components C_i is a decomposition of P exactly when each
 * C_i lies in P, their interiors are pairwise disjoint, and sum area(C_i) = area(P) (then the
 * union is P up to a null set, and both are closed). Each of the three is checked directly:
 *   inside / disjoint: for two regions X, Y (a component, or the input with its holes) no edge
 *     of X properly crosses one of Y; every edge of X is split at the vertices of Y lying on it,
 *     and the midpoints of the pieces and the vertices of X are located in Y (and the other way
 *     round). For a component vs. the input: nothing of X outside Y, nothing of Y's boundary
 *     inside X. For two components: nothing of one inside the other, and not every piece of X
 *     on the boundary of Y (a duplicate). With no proper crossing, two simple polygons'
 *     interiors meet iff a boundary piece of one lies inside the other or they coincide.
 *   areas: compensated shoelace sums.
 * Sides and crossings use the exact predicates; a point within `tol` of a boundary counts as on
 * it, to absorb rounding in Steiner points: tol = max(ACD_TOL_REL_DIST x the input's extent,
 * 4 DBL_EPSILON x the largest coordinate magnitude). The second term is the rounding of a
 * computed point (a Steiner point, or this file's own midpoints and feet) far from the origin:
 * no double lies closer to the segment it was computed on, so a smaller tolerance would reject
 * exact decompositions of translated inputs (a polygon of extent 1 at 1e9 has a spacing of
 * 1.2e-7 between doubles).
 * Efficiency: components are paired through a uniform grid of bounding boxes; each region keeps
 * y-buckets of its edges, used both to locate points and to list its edges near a box; edge
 * pairs are found by a sweep over x. */
#include "eval/verify2d.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/predicates.h"
#include "core/tolerance.h"
#include "geom2/seg_dist.h"
#include "eval/concavity2d_ref.h"

/* ------------------------------------------------------------------ small geometry helpers */

typedef struct box {
    double x0, y0, x1, y1;
} box;

static int box_meets(box a, box b) {
    return a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1;
}

static box box_grow(box a, double t) {
    box r = {a.x0 - t, a.y0 - t, a.x1 + t, a.y1 + t};
    return r;
}

static box seg_box(acd_vec2 a, acd_vec2 b, double t) {
    box r = {fmin(a.x, b.x) - t, fmin(a.y, b.y) - t, fmax(a.x, b.x) + t, fmax(a.y, b.y) + t};
    return r;
}

/* Rounding of a point computed from coordinates of magnitude up to that of the input: a few
 * units in the last place of the largest coordinate (see the file comment). */
#define V2D_ROUND_ULPS 4.0
static double round_tol(const acd_polygon *input) {
    double m = 0;
    size_t n = acd_polygon_num_points(input);
    for (size_t i = 0; i < n; i++) m = fmax(m, fmax(fabs(input->points[i].x), fabs(input->points[i].y)));
    return V2D_ROUND_ULPS * DBL_EPSILON * m;
}

/* the input's perimeter (bounds the area moved by rounding points on its edges) */
static double perimeter(const acd_polygon *input) {
    double s = 0;
    for (size_t r = 0; r < input->nrings; r++) {
        const acd_vec2 *p = acd_polygon_ring(input, r);
        size_t n = acd_polygon_ring_size(input, r);
        for (size_t i = 0; i < n; i++) s += hypot(p[(i + 1) % n].x - p[i].x, p[(i + 1) % n].y - p[i].y);
    }
    return s;
}

static double seg_param(acd_vec2 q, acd_vec2 a, acd_vec2 b) {
    double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
    return l2 > 0 ? ((q.x - a.x) * dx + (q.y - a.y) * dy) / l2 : 0;
}

/* Neumaier compensated sum. */
typedef struct ksum {
    double s, c;
} ksum;

static void ks_add(ksum *k, double v) {
    double t = k->s + v;
    if (fabs(k->s) >= fabs(v))
        k->c += (k->s - t) + v;
    else
        k->c += (v - t) + k->s;
    k->s = t;
}

static void ring_area_add(const acd_vec2 *p, size_t n, ksum *k) {
    for (size_t i = 0; i < n; i++) {
        acd_vec2 a = p[i], b = p[i + 1 == n ? 0 : i + 1];
        double p1 = a.x * b.y, e1 = fma(a.x, b.y, -p1);
        double p2 = b.x * a.y, e2 = fma(b.x, a.y, -p2);
        ks_add(k, p1);
        ks_add(k, -p2);
        ks_add(k, e1);
        ks_add(k, -e2);
    }
}

double acd_v2d_ring_area(const acd_vec2 *pts, size_t n) {
    ksum k = {0, 0};
    ring_area_add(pts, n, &k);
    return 0.5 * (k.s + k.c);
}

/* q lies on the closed segment a-b, exactly (orientation 0 and inside its box) */
static int same_pt(acd_vec2 a, acd_vec2 b) { return a.x == b.x && a.y == b.y; }

static int on_seg_exact(acd_vec2 q, acd_vec2 a, acd_vec2 b) {
    if (q.x < fmin(a.x, b.x) || q.x > fmax(a.x, b.x) || q.y < fmin(a.y, b.y) || q.y > fmax(a.y, b.y)) return 0;
    return acd_ref_orient(a, b, q) == 0;
}

/* Does edge a->b cross the horizontal ray from q towards +x (half-open in y)? Exact. */
static int ray_crosses(acd_vec2 a, acd_vec2 b, acd_vec2 q) {
    if ((a.y > q.y) == (b.y > q.y)) return 0;
    double o = acd_ref_orient(a, b, q);
    return b.y > a.y ? o > 0 : o < 0;
}

int acd_v2d_classify_point(const acd_vec2 *pts, const size_t *ring_start, size_t nrings, acd_vec2 q, double tol) {
    int inside = 0;
    for (size_t r = 0; r < nrings; r++) {
        size_t s = ring_start[r], e = ring_start[r + 1];
        for (size_t i = s; i < e; i++) {
            acd_vec2 a = pts[i], b = pts[i + 1 == e ? s : i + 1];
            if (on_seg_exact(q, a, b) || acd_seg_dist2(q, a, b) <= tol) return 0;
            if (ray_crosses(a, b, q)) inside ^= 1;
        }
    }
    return inside ? 1 : -1;
}

/* ------------------------------------------------------------------ regions with y-buckets */

typedef struct region {
    const acd_vec2 *p;
    size_t n;        /* points = edges; edge i runs p[i] -> p[nxt[i]] */
    size_t *nxt, *prv;
    box bb;          /* exact bounding box */
    size_t nb;       /* y-buckets over [bb.y0 - tol, bb.y1 + tol] */
    double by0, bh;
    size_t *bs, *be; /* CSR: bucket b holds edges be[bs[b] .. bs[b+1]-1] */
    unsigned *stamp;
    unsigned cur;
} region;

static void region_free(region *r) {
    free(r->nxt);
    free(r->prv);
    free(r->bs);
    free(r->be);
    free(r->stamp);
    memset(r, 0, sizeof *r);
}

static size_t bucket_of(const region *r, double y) {
    double f = (y - r->by0) / r->bh;
    if (!(f > 0)) return 0;
    if (f >= (double)r->nb) return r->nb - 1;
    return (size_t)f;
}

static int region_init(region *r, const acd_vec2 *p, const size_t *ring_start, size_t nrings, size_t n, double tol) {
    memset(r, 0, sizeof *r);
    r->p = p;
    r->n = n;
    r->nxt = malloc((n ? n : 1) * sizeof *r->nxt);
    r->prv = malloc((n ? n : 1) * sizeof *r->prv);
    r->stamp = calloc(n ? n : 1, sizeof *r->stamp);
    if (!r->nxt || !r->prv || !r->stamp) return -1;
    for (size_t k = 0; k < nrings; k++) {
        size_t s = ring_start ? ring_start[k] : 0, e = ring_start ? ring_start[k + 1] : n;
        for (size_t i = s; i < e; i++) {
            r->nxt[i] = i + 1 == e ? s : i + 1;
            r->prv[r->nxt[i]] = i;
        }
    }
    r->bb = (box){INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++) {
        r->bb.x0 = fmin(r->bb.x0, p[i].x);
        r->bb.y0 = fmin(r->bb.y0, p[i].y);
        r->bb.x1 = fmax(r->bb.x1, p[i].x);
        r->bb.y1 = fmax(r->bb.y1, p[i].y);
    }
    r->nb = (size_t)sqrt((double)n);
    if (r->nb < 1) r->nb = 1;
    r->by0 = r->bb.y0 - tol;
    r->bh = (r->bb.y1 + tol - r->by0) / (double)r->nb;
    if (!(r->bh > 0)) {
        r->nb = 1;
        r->bh = 1;
    }
    r->bs = calloc(r->nb + 1, sizeof *r->bs);
    if (!r->bs) return -1;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t i = 0; i < n; i++) {
            box b = seg_box(p[i], p[r->nxt[i]], tol);
            size_t lo = bucket_of(r, b.y0), hi = bucket_of(r, b.y1);
            for (size_t k = lo; k <= hi; k++) {
                if (pass == 0)
                    r->bs[k + 1]++;
                else
                    r->be[r->bs[k]++] = i;
            }
        }
        if (pass == 0) {
            for (size_t k = 0; k < r->nb; k++) r->bs[k + 1] += r->bs[k];
            r->be = malloc((r->bs[r->nb] ? r->bs[r->nb] : 1) * sizeof *r->be);
            if (!r->be) return -1;
        } else {
            for (size_t k = r->nb; k > 0; k--) r->bs[k] = r->bs[k - 1];
            r->bs[0] = 0;
        }
    }
    return 0;
}

static int region_classify(const region *r, acd_vec2 q, double tol) {
    if (q.x < r->bb.x0 - tol || q.x > r->bb.x1 + tol || q.y < r->bb.y0 - tol || q.y > r->bb.y1 + tol) return -1;
    size_t b = bucket_of(r, q.y);
    int inside = 0;
    for (size_t k = r->bs[b]; k < r->bs[b + 1]; k++) {
        size_t i = r->be[k];
        acd_vec2 a = r->p[i], c = r->p[r->nxt[i]];
        if (on_seg_exact(q, a, c) || acd_seg_dist2(q, a, c) <= tol) return 0;
        if (ray_crosses(a, c, q)) inside ^= 1;
    }
    return inside ? 1 : -1;
}

/* The segment e0-e1 (around m) lies on one edge of r, exactly. */
static int region_piece_on(const region *r, acd_vec2 e0, acd_vec2 e1, acd_vec2 m) {
    if (m.y < r->by0 || m.y > r->by0 + r->bh * (double)r->nb) return 0;
    size_t b = bucket_of(r, m.y);
    for (size_t k = r->bs[b]; k < r->bs[b + 1]; k++) {
        size_t i = r->be[k];
        acd_vec2 a = r->p[i], c = r->p[r->nxt[i]];
        if (on_seg_exact(e0, a, c) && on_seg_exact(e1, a, c)) return 1;
    }
    return 0;
}

/* q lies exactly on r's boundary (a vertex or inside an edge). */
static int region_on_exact(const region *r, acd_vec2 q) {
    if (q.y < r->by0 || q.y > r->by0 + r->bh * (double)r->nb) return 0;
    size_t b = bucket_of(r, q.y);
    for (size_t k = r->bs[b]; k < r->bs[b + 1]; k++) {
        size_t i = r->be[k];
        if (on_seg_exact(q, r->p[i], r->p[r->nxt[i]])) return 1;
    }
    return 0;
}

/* Where the open segment e0 -> e1 lies relative to r (1 inside, -1 outside, 0 on its boundary),
 * decided exactly from e0 and the direction to e1, when e0 lies exactly on r's boundary (a vertex
 * or inside an edge) or at more than tol from it; the segment must cross no edge of r and hold
 * no vertex of r. Returns 2 when undecided (e0 within tol of the boundary but not on it): the
 * caller then locates the midpoint. Midpoints are rounded, by more than the tolerance far from
 * the origin, and could fall on the wrong side of a sliver thinner than the rounding. */
static int region_classify_piece(const region *r, acd_vec2 e0, acd_vec2 e1, double tol) {
    if (e0.y >= r->by0 && e0.y <= r->by0 + r->bh * (double)r->nb) {
        size_t b = bucket_of(r, e0.y);
        for (size_t k = r->bs[b]; k < r->bs[b + 1]; k++) {
            size_t i = r->be[k];
            acd_vec2 a = r->p[i], c = r->p[r->nxt[i]];
            if (same_pt(e0, a)) { /* at vertex a: the interior wedge between u -> a and a -> c */
                acd_vec2 u = r->p[r->prv[i]];
                double oc = acd_ref_orient(a, c, e1), ou = acd_ref_orient(u, a, e1);
                if (oc == 0 && (e1.x - a.x) * (c.x - a.x) + (e1.y - a.y) * (c.y - a.y) > 0) return 0;
                if (ou == 0 && (e1.x - a.x) * (u.x - a.x) + (e1.y - a.y) * (u.y - a.y) > 0) return 0;
                int in = acd_ref_orient(u, a, c) > 0 ? (ou > 0 && oc > 0) : (ou > 0 || oc > 0);
                return in ? 1 : -1;
            }
            if (!same_pt(e0, c) && on_seg_exact(e0, a, c)) { /* inside edge a -> c: its side */
                double o = acd_ref_orient(a, c, e1);
                return o > 0 ? 1 : o < 0 ? -1 : 0;
            }
        }
    }
    int w = region_classify(r, e0, tol);
    return w == 0 ? 2 : w;
}

static unsigned next_stamp(region *r) {
    if (++r->cur == 0) {
        memset(r->stamp, 0, r->n * sizeof *r->stamp);
        r->cur = 1;
    }
    return r->cur;
}

/* Edges of r whose (tol-grown) boxes meet q, appended to out (capacity r->n). */
static size_t region_edges_in(region *r, box q, double tol, size_t *out) {
    unsigned st = next_stamp(r);
    size_t m = 0;
    if (!box_meets(q, box_grow(r->bb, tol))) return 0;
    size_t lo = bucket_of(r, q.y0), hi = bucket_of(r, q.y1);
    for (size_t b = lo; b <= hi; b++)
        for (size_t k = r->bs[b]; k < r->bs[b + 1]; k++) {
            size_t i = r->be[k];
            if (r->stamp[i] == st) continue;
            /* stamp only the listed edges: count_outside takes the unstamped ones as outside */
            if (box_meets(q, seg_box(r->p[i], r->p[r->nxt[i]], tol))) {
                r->stamp[i] = st;
                out[m++] = i;
            }
        }
    return m;
}

/* ------------------------------------------------------------------ the verifier's state */

typedef struct split {
    int side; /* 0: X, 1: Y */
    size_t edge;
    double t;
    acd_vec2 q; /* the other region's vertex splitting the edge */
} split;

typedef struct sweep_item {
    double x0, x1, y0, y1;
    int side;
    size_t edge;
} sweep_item;

typedef struct verifier {
    double tol;
    /* scratch, grown on demand */
    size_t *ex, *ey;
    size_t cap_ex, cap_ey;
    sweep_item *items;
    size_t cap_items;
    split *splits;
    size_t nsplits, cap_splits;
} verifier;

/* Makes room for `need` elements of size elem in `old` (capacity *cap); *out receives the array
 * (old itself when it was big enough or the reallocation failed). 0, or -1 when out of memory. */
static int grow_raw(void *old, void **out, size_t *cap, size_t need, size_t elem) {
    *out = old;
    if (need <= *cap) return 0;
    size_t c = *cap ? *cap : 64;
    while (c < need) c *= 2;
    void *q = realloc(old, c * elem);
    if (!q) return -1;
    *out = q;
    *cap = c;
    return 0;
}

static int add_split(verifier *v, int side, size_t edge, double t, acd_vec2 q) {
    void *mem;
    int r = grow_raw(v->splits, &mem, &v->cap_splits, v->nsplits + 1, sizeof *v->splits);
    v->splits = mem;
    if (r) return -1;
    v->splits[v->nsplits++] = (split){side, edge, t, q};
    return 0;
}

static int cmp_split(const void *a, const void *b) {
    const split *p = a, *q = b;
    if (p->side != q->side) return p->side - q->side;
    if (p->edge != q->edge) return p->edge < q->edge ? -1 : 1;
    return (p->t > q->t) - (p->t < q->t);
}

static int cmp_item(const void *a, const void *b) {
    const sweep_item *p = a, *q = b;
    if (p->x0 != q->x0) return p->x0 < q->x0 ? -1 : 1;
    if (p->side != q->side) return p->side - q->side;
    return (p->edge > q->edge) - (p->edge < q->edge);
}

/* Outcome of locating one region's boundary pieces in another region. */
typedef struct side_stats {
    size_t in, on, out;
    acd_vec2 in_pt, out_pt; /* first example of each */
    size_t in_edge, out_edge;
} side_stats;

static void count(side_stats *s, int where, acd_vec2 q, size_t edge) {
    if (where > 0) {
        if (!s->in) {
            s->in_pt = q;
            s->in_edge = edge;
        }
        s->in++;
    } else if (where < 0) {
        if (!s->out) {
            s->out_pt = q;
            s->out_edge = edge;
        }
        s->out++;
    } else {
        s->on++;
    }
}

typedef struct interaction {
    int crossing; /* 1: an edge of X properly crosses one of Y */
    size_t cx, cy;
    acd_vec2 cross_pt;
    side_stats sx, sy; /* X's pieces located in Y, Y's in X */
    size_t ex_count, ey_count;
} interaction;

/* Locates the pieces of X's listed edges (split at the recorded points) and its vertices in Y. */
static void locate_side(verifier *v, const region *X, const region *Y, const size_t *edges, size_t ne, int side,
                        const split *sp, size_t nsp, side_stats *s) {
    size_t k = 0;
    /* edges[] need not be sorted; splits are sorted by edge: look them up by binary search */
    for (size_t a = 0; a < ne; a++) {
        size_t e = edges[a];
        acd_vec2 p0 = X->p[e], p1 = X->p[X->nxt[e]];
        count(s, region_classify(Y, p0, v->tol), p0, e);
        acd_vec2 e0 = p0;
        /* first split of this edge */
        size_t lo = 0, hi = nsp;
        while (lo < hi) {
            size_t mid = (lo + hi) / 2;
            if (sp[mid].side < side || (sp[mid].side == side && sp[mid].edge < e))
                lo = mid + 1;
            else
                hi = mid;
        }
        k = lo;
        double t0 = 0;
        for (;;) {
            int at_split = k < nsp && sp[k].side == side && sp[k].edge == e;
            double t1 = at_split ? sp[k].t : 1.0;
            acd_vec2 e1 = at_split ? sp[k].q : p1;
            if (t1 > t0) {
                double tm = 0.5 * (t0 + t1);
                acd_vec2 m = {p0.x + tm * (p1.x - p0.x), p0.y + tm * (p1.y - p0.y)};
                /* a piece lying exactly on an edge of Y is on its boundary, whatever the rounding of m */
                int where = region_piece_on(Y, e0, e1, m) ? 0 : region_classify_piece(Y, e0, e1, v->tol);
                /* undecided, or a piece along the boundary within the tolerance (a rounded point;
                 * a piece between two points exactly on the boundary is decided exactly: a sliver
                 * thinner than the tolerance, between three nearly collinear vertices, is not on it) */
                if (where == 2 || (where != 0 && !region_on_exact(Y, e1))) {
                    int wm = region_classify(Y, m, v->tol);
                    if (where == 2 || wm == 0) where = wm;
                }
                count(s, where, m, e);
            }
            if (t1 >= 1.0) break;
            t0 = t1;
            e0 = e1;
            k++;
        }
    }
}

/* Counts the edges of r not listed by the last region_edges_in as outside (example: the first). */
static void count_outside(const region *r, size_t listed, side_stats *s) {
    if (listed == r->n) return;
    size_t first = 0;
    while (first < r->n && r->stamp[first] == r->cur) first++;
    if (first == r->n) return;
    count(s, -1, r->p[first], first);
    s->out += r->n - listed - 1;
}

static double min4(double a, double b, double c, double d) {
    return fmin(fmin(a, b), fmin(c, d));
}

/* Computes how X and Y meet (see the file comment). Returns 0, or -1 when out of memory. */
static int interact(verifier *v, region *X, region *Y, interaction *it) {
    memset(it, 0, sizeof *it);
    double tol = v->tol;
    box q = {fmax(X->bb.x0, Y->bb.x0) - tol, fmax(X->bb.y0, Y->bb.y0) - tol, fmin(X->bb.x1, Y->bb.x1) + tol,
             fmin(X->bb.y1, Y->bb.y1) + tol};
    size_t need = X->n > Y->n ? X->n : Y->n;
    void *t;
    int r = grow_raw(v->ex, &t, &v->cap_ex, need, sizeof *v->ex);
    v->ex = t;
    if (r) return -1;
    r = grow_raw(v->ey, &t, &v->cap_ey, need, sizeof *v->ey);
    v->ey = t;
    if (r) return -1;
    size_t nx = 0, ny = 0;
    if (q.x0 <= q.x1 && q.y0 <= q.y1) {
        nx = region_edges_in(X, q, tol, v->ex);
        ny = region_edges_in(Y, q, tol, v->ey);
    } else {
        next_stamp(X);
        next_stamp(Y);
    }
    it->ex_count = nx;
    it->ey_count = ny;
    r = grow_raw(v->items, &t, &v->cap_items, nx + ny, sizeof *v->items);
    v->items = t;
    if (r) return -1;
    size_t ni = 0;
    for (size_t a = 0; a < nx; a++) {
        box b = seg_box(X->p[v->ex[a]], X->p[X->nxt[v->ex[a]]], tol);
        v->items[ni++] = (sweep_item){b.x0, b.x1, b.y0, b.y1, 0, v->ex[a]};
    }
    for (size_t a = 0; a < ny; a++) {
        box b = seg_box(Y->p[v->ey[a]], Y->p[Y->nxt[v->ey[a]]], tol);
        v->items[ni++] = (sweep_item){b.x0, b.x1, b.y0, b.y1, 1, v->ey[a]};
    }
    if (ni > 1) qsort(v->items, ni, sizeof *v->items, cmp_item);
    v->nsplits = 0;
    for (size_t i = 0; i < ni; i++) {
        const sweep_item *A = &v->items[i];
        for (size_t j = i + 1; j < ni && v->items[j].x0 <= A->x1; j++) {
            const sweep_item *B = &v->items[j];
            if (A->side == B->side || A->y0 > B->y1 || B->y0 > A->y1) continue;
            size_t e = A->side == 0 ? A->edge : B->edge, f = A->side == 0 ? B->edge : A->edge;
            acd_vec2 a0 = X->p[e], a1 = X->p[X->nxt[e]], c0 = Y->p[f], c1 = Y->p[Y->nxt[f]];
            double da0 = acd_seg_dist2(a0, c0, c1), dc0 = acd_seg_dist2(c0, a0, a1);
            if (acd_ref_segrel(a0, a1, c0, c1) == ACD_SEG_PROPER &&
                min4(da0, acd_seg_dist2(a1, c0, c1), dc0, acd_seg_dist2(c1, a0, a1)) > tol) {
                it->crossing = 1;
                it->cx = e;
                it->cy = f;
                /* the crossing point, for the message */
                double d1 = acd_ref_orient(c0, c1, a0), d2 = acd_ref_orient(c0, c1, a1);
                double t = d1 / (d1 - d2);
                it->cross_pt = (acd_vec2){a0.x + t * (a1.x - a0.x), a0.y + t * (a1.y - a0.y)};
                return 0;
            }
            /* a vertex of one lying on the other edge splits that edge */
            /* within tol splits only an edge with a computed (rounded) end: between two points
             * exactly on the other's boundary an edge passing near a vertex is a sliver's side */
            if ((on_seg_exact(c0, a0, a1) ||
                 (dc0 <= tol && !(region_on_exact(Y, a0) && region_on_exact(Y, a1)))) &&
                !same_pt(c0, a0) && !same_pt(c0, a1) &&
                acd_seg_dist2(c0, a0, a0) > tol && acd_seg_dist2(c0, a1, a1) > tol) {
                double t = seg_param(c0, a0, a1);
                if (t > 0 && t < 1 && add_split(v, 0, e, t, c0)) return -1;
            }
            if ((on_seg_exact(a0, c0, c1) ||
                 (da0 <= tol && !(region_on_exact(X, c0) && region_on_exact(X, c1)))) &&
                !same_pt(a0, c0) && !same_pt(a0, c1) &&
                acd_seg_dist2(a0, c0, c0) > tol && acd_seg_dist2(a0, c1, c1) > tol) {
                double t = seg_param(a0, c0, c1);
                if (t > 0 && t < 1 && add_split(v, 1, f, t, a0)) return -1;
            }
        }
    }
    if (v->nsplits > 1) qsort(v->splits, v->nsplits, sizeof *v->splits, cmp_split);
    locate_side(v, X, Y, v->ex, nx, 0, v->splits, v->nsplits, &it->sx);
    locate_side(v, Y, X, v->ey, ny, 1, v->splits, v->nsplits, &it->sy);
    /* edges outside the common box lie outside the other region altogether */
    count_outside(X, nx, &it->sx);
    count_outside(Y, ny, &it->sy);
    return 0;
}

/* ------------------------------------------------------------------ the checks */

/* Two non-adjacent edges of the region cross properly: returns 1 and the edges. */
static int self_crossing(verifier *v, const region *r, size_t *e1, size_t *e2, int *oom) {
    *oom = 0;
    void *t;
    int g = grow_raw(v->items, &t, &v->cap_items, r->n, sizeof *v->items);
    v->items = t;
    if (g) {
        *oom = 1;
        return 0;
    }
    for (size_t i = 0; i < r->n; i++) {
        box b = seg_box(r->p[i], r->p[r->nxt[i]], 0);
        v->items[i] = (sweep_item){b.x0, b.x1, b.y0, b.y1, 0, i};
    }
    qsort(v->items, r->n, sizeof *v->items, cmp_item);
    for (size_t i = 0; i < r->n; i++) {
        const sweep_item *A = &v->items[i];
        for (size_t j = i + 1; j < r->n && v->items[j].x0 <= A->x1; j++) {
            const sweep_item *B = &v->items[j];
            if (A->y0 > B->y1 || B->y0 > A->y1) continue;
            size_t e = A->edge, f = B->edge;
            if (r->nxt[e] == f || r->nxt[f] == e) continue;
            acd_vec2 a0 = r->p[e], a1 = r->p[r->nxt[e]], c0 = r->p[f], c1 = r->p[r->nxt[f]];
            if (acd_ref_segrel(a0, a1, c0, c1) == ACD_SEG_PROPER &&
                min4(acd_seg_dist2(a0, c0, c1), acd_seg_dist2(a1, c0, c1), acd_seg_dist2(c0, a0, a1), acd_seg_dist2(c1, a0, a1)) >
                    v->tol) {
                *e1 = e < f ? e : f;
                *e2 = e < f ? f : e;
                return 1;
            }
        }
    }
    return 0;
}

const char *acd_verify2d_check_name(acd_verify2d_check c) {
    switch (c) {
    case ACD_V2D_PASS: return "pass";
    case ACD_V2D_INVALID: return "invalid component";
    case ACD_V2D_CLOCKWISE: return "clockwise component";
    case ACD_V2D_SELF_INTERSECTION: return "self-intersecting component";
    case ACD_V2D_OUTSIDE: return "component outside the input";
    case ACD_V2D_OVERLAP: return "overlapping components";
    case ACD_V2D_AREA: return "areas do not add up";
    case ACD_V2D_HULL: return "bad hull";
    case ACD_V2D_CONCAVITY: return "concavity above tau";
    }
    return "unknown";
}

acd_verify2d_options acd_verify2d_default_options(void) {
    acd_verify2d_options o;
    memset(&o, 0, sizeof o);
    o.tau = 0;
    o.measure = ACD2D_MEASURE_SL;
    o.notch_tolerance = 1e-5;
    o.area_rel_tol = ACD_TOL_REL_MEASURE;
    o.check_concavity = 1;
    o.component_base = 0;
    return o;
}

static acd_status fail(acd_verify2d_report *rep, acd_verify2d_check c, long comp, long other) {
    rep->failed = c;
    rep->component = comp;
    rep->other = other;
    return ACD_ERR_VERIFY;
}

/* Grid of component bounding boxes, for finding the pairs that may meet. */
typedef struct grid {
    size_t g;
    box bb;
    double cw, ch;
    size_t *cs, *ce; /* CSR */
} grid;

static size_t cell_coord(double v, double lo, double w, size_t g) {
    double f = (v - lo) / w;
    if (!(f > 0)) return 0;
    if (f >= (double)g) return g - 1;
    return (size_t)f;
}

static int grid_build(grid *gr, region *rs, size_t count, double tol) {
    memset(gr, 0, sizeof *gr);
    gr->bb = (box){INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < count; i++) {
        gr->bb.x0 = fmin(gr->bb.x0, rs[i].bb.x0 - tol);
        gr->bb.y0 = fmin(gr->bb.y0, rs[i].bb.y0 - tol);
        gr->bb.x1 = fmax(gr->bb.x1, rs[i].bb.x1 + tol);
        gr->bb.y1 = fmax(gr->bb.y1, rs[i].bb.y1 + tol);
    }
    gr->g = (size_t)ceil(sqrt((double)count));
    if (gr->g < 1) gr->g = 1;
    if (gr->g > 1024) gr->g = 1024;
    gr->cw = (gr->bb.x1 - gr->bb.x0) / (double)gr->g;
    gr->ch = (gr->bb.y1 - gr->bb.y0) / (double)gr->g;
    if (!(gr->cw > 0)) gr->cw = 1;
    if (!(gr->ch > 0)) gr->ch = 1;
    size_t nc = gr->g * gr->g;
    gr->cs = calloc(nc + 1, sizeof *gr->cs);
    if (!gr->cs) return -1;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t i = 0; i < count; i++) {
            box b = box_grow(rs[i].bb, tol);
            size_t x0 = cell_coord(b.x0, gr->bb.x0, gr->cw, gr->g), x1 = cell_coord(b.x1, gr->bb.x0, gr->cw, gr->g);
            size_t y0 = cell_coord(b.y0, gr->bb.y0, gr->ch, gr->g), y1 = cell_coord(b.y1, gr->bb.y0, gr->ch, gr->g);
            for (size_t y = y0; y <= y1; y++)
                for (size_t x = x0; x <= x1; x++) {
                    size_t c = y * gr->g + x;
                    if (pass == 0)
                        gr->cs[c + 1]++;
                    else
                        gr->ce[gr->cs[c]++] = i;
                }
        }
        if (pass == 0) {
            for (size_t c = 0; c < nc; c++) gr->cs[c + 1] += gr->cs[c];
            gr->ce = malloc((gr->cs[nc] ? gr->cs[nc] : 1) * sizeof *gr->ce);
            if (!gr->ce) return -1;
        } else {
            for (size_t c = nc; c > 0; c--) gr->cs[c] = gr->cs[c - 1];
            gr->cs[0] = 0;
        }
    }
    return 0;
}

static void grid_free(grid *gr) {
    free(gr->cs);
    free(gr->ce);
}

/* The ring of the input on whose boundary the midpoint of a-b lies (0 if none is found). */
static size_t ring_of_boundary_point(const acd_polygon *input, const region *in, acd_vec2 a, acd_vec2 b,
                                     double tol) {
    acd_vec2 m = {0.5 * (a.x + b.x), 0.5 * (a.y + b.y)};
    size_t bk = bucket_of(in, m.y);
    for (size_t k = in->bs[bk]; k < in->bs[bk + 1]; k++) {
        size_t e = in->be[k];
        if (acd_seg_dist2(m, in->p[e], in->p[in->nxt[e]]) <= tol) {
            size_t r = 0;
            while (r + 1 < input->nrings && input->ring_start[r + 1] <= e) r++;
            return r;
        }
    }
    return 0;
}

/* For the message of a missing piece: the midpoint of an input edge (or of a piece of it between
 * the components' vertices) that lies on no component. Only run after a failure: O(n m). */
static int uncovered_boundary_point(const acd_polygon *input, const region *rs, size_t count, double tol,
                                    acd_vec2 *out) {
    for (size_t r = 0; r < input->nrings; r++) {
        const acd_vec2 *p = acd_polygon_ring(input, r);
        size_t n = acd_polygon_ring_size(input, r);
        for (size_t i = 0; i < n; i++) {
            acd_vec2 a = p[i], b = p[i + 1 == n ? 0 : i + 1];
            /* probe a few points along the edge */
            for (int k = 1; k < 8; k += 2) {
                double t = k / 8.0;
                acd_vec2 q = {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
                int covered = 0;
                for (size_t c = 0; c < count && !covered; c++) covered = region_classify(&rs[c], q, tol) >= 0;
                if (!covered) {
                    *out = q;
                    return 1;
                }
            }
        }
    }
    return 0;
}

static const char *measure_name(acd2d_measure m) {
    switch (m) {
    case ACD2D_MEASURE_SL: return "sl";
    case ACD2D_MEASURE_SP: return "sp";
    case ACD2D_MEASURE_H1: return "h1";
    case ACD2D_MEASURE_H2: return "h2";
    }
    return "?";
}

static void fmt_pt(char *buf, size_t size, acd_vec2 p) {
    snprintf(buf, size, "(%.17g, %.17g)", p.x, p.y);
}

acd_status acd_verify2d(const acd_polygon *input, const acd_vec2 *const *components, const size_t *sizes,
                        size_t count, const acd_verify2d_options *optp, acd_verify2d_report *report,
                        acd_error *err) {
    acd_verify2d_options opt = optp ? *optp : acd_verify2d_default_options();
    acd_verify2d_report dummy, *rep = report ? report : &dummy;
    memset(rep, 0, sizeof *rep);
    rep->component = rep->other = rep->max_concavity_component = -1;
    acd_error_clear(err);
    if (!input || input->nrings == 0 || (count && (!components || !sizes)))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_verify2d: no input polygon or no component arrays");
    size_t nin = acd_polygon_num_points(input);
    acd_scale sc = acd_scale_of_points(&input->points[0].x, nin, 2);
    verifier v;
    memset(&v, 0, sizeof v);
    double rtol = round_tol(input);
    v.tol = fmax(sc.dist, rtol);
    size_t B = opt.component_base;
    char pa[96], pb[96];

    /* input area */
    ksum kin = {0, 0};
    for (size_t r = 0; r < input->nrings; r++)
        ring_area_add(acd_polygon_ring(input, r), acd_polygon_ring_size(input, r), &kin);
    rep->input_area = 0.5 * (kin.s + kin.c);

    region *rs = calloc(count ? count : 1, sizeof *rs);
    region in;
    memset(&in, 0, sizeof in);
    grid gr;
    memset(&gr, 0, sizeof gr);
    acd_status st = ACD_OK;
    if (!rs) return acd_fail(err, ACD_ERR_NOMEM, "acd_verify2d: out of memory for %zu components", count);

    /* 1. each component on its own */
    ksum kc = {0, 0};
    for (size_t i = 0; i < count && st == ACD_OK; i++) {
        const acd_vec2 *p = components[i];
        size_t n = sizes[i];
        if (n < 3 || !p) {
            st = acd_fail(err, ACD_ERR_VERIFY, "component %zu has %zu points (at least 3 needed)", B + i, n);
            fail(rep, ACD_V2D_INVALID, (long)i, -1);
            break;
        }
        for (size_t k = 0; k < n; k++)
            if (!isfinite(p[k].x) || !isfinite(p[k].y)) {
                st = acd_fail(err, ACD_ERR_VERIFY, "component %zu: vertex %zu has a non-finite coordinate", B + i, k);
                fail(rep, ACD_V2D_INVALID, (long)i, -1);
                break;
            }
        if (st != ACD_OK) break;
        double a = acd_v2d_ring_area(p, n);
        if (!(a > 0)) {
            st = acd_fail(err, ACD_ERR_VERIFY,
                          "component %zu is not counterclockwise: signed area %.17g (vertex 0 at (%.17g, %.17g))",
                          B + i, a, p[0].x, p[0].y);
            fail(rep, ACD_V2D_CLOCKWISE, (long)i, -1);
            break;
        }
        ks_add(&kc, a);
        if (region_init(&rs[i], p, NULL, 1, n, v.tol)) {
            st = acd_fail(err, ACD_ERR_NOMEM, "acd_verify2d: out of memory");
            break;
        }
        size_t e1, e2;
        int oom;
        if (self_crossing(&v, &rs[i], &e1, &e2, &oom)) {
            fmt_pt(pa, sizeof pa, p[e1]);
            fmt_pt(pb, sizeof pb, p[e2]);
            st = acd_fail(err, ACD_ERR_VERIFY, "component %zu is not simple: its edge %zu from %s crosses edge %zu from %s",
                          B + i, e1, pa, e2, pb);
            fail(rep, ACD_V2D_SELF_INTERSECTION, (long)i, -1);
        } else if (oom) {
            st = acd_fail(err, ACD_ERR_NOMEM, "acd_verify2d: out of memory");
        }
    }
    rep->components_area = kc.s + kc.c;

    /* 2. each component inside the input */
    if (st == ACD_OK && region_init(&in, input->points, input->ring_start, input->nrings, nin, v.tol))
        st = acd_fail(err, ACD_ERR_NOMEM, "acd_verify2d: out of memory");
    for (size_t i = 0; i < count && st == ACD_OK; i++) {
        interaction it;
        if (interact(&v, &rs[i], &in, &it)) {
            st = acd_fail(err, ACD_ERR_NOMEM, "acd_verify2d: out of memory");
            break;
        }
        if (it.crossing) {
            fmt_pt(pa, sizeof pa, it.cross_pt);
            st = acd_fail(err, ACD_ERR_VERIFY,
                          "component %zu reaches outside the input: its edge %zu crosses the input's boundary "
                          "(edge %zu) near %s",
                          B + i, it.cx, it.cy, pa);
        } else if (it.sx.out) {
            fmt_pt(pa, sizeof pa, it.sx.out_pt);
            st = acd_fail(err, ACD_ERR_VERIFY,
                          "component %zu reaches outside the input: the point %s on its edge %zu is outside", B + i, pa,
                          it.sx.out_edge);
        } else if (it.sy.in) {
            fmt_pt(pa, sizeof pa, it.sy.in_pt);
            st = acd_fail(err, ACD_ERR_VERIFY,
                          "component %zu reaches outside the input: the input's boundary point %s lies inside it",
                          B + i, pa);
        } else if (!it.sx.in) {
            /* its whole boundary lies on the input's: it is bounded by one ring, and must not be
             * a hole's */
            size_t ring = ring_of_boundary_point(input, &in, components[i][0], components[i][1], v.tol);
            if (ring > 0) {
                st = acd_fail(err, ACD_ERR_VERIFY, "component %zu reaches outside the input: it fills hole %zu",
                              B + i, ring);
            }
        }
        if (st != ACD_OK) fail(rep, ACD_V2D_OUTSIDE, (long)i, -1);
    }

    /* 3. components pairwise interior-disjoint. Components share their cut ends exactly (cut ends
     * are points of both, or lie exactly on the other's edge), so only ACD_TOL_REL_DIST x extent
     * is allowed here: a cut end rounded off the other component's edge by more is an overlap or
     * a gap, however far from the origin the input lies. */
    v.tol = sc.dist;
    if (st == ACD_OK && count > 1 && grid_build(&gr, rs, count, v.tol))
        st = acd_fail(err, ACD_ERR_NOMEM, "acd_verify2d: out of memory");
    for (size_t c = 0; st == ACD_OK && count > 1 && c < gr.g * gr.g; c++) {
        for (size_t a = gr.cs[c]; a < gr.cs[c + 1] && st == ACD_OK; a++)
            for (size_t b = a + 1; b < gr.cs[c + 1] && st == ACD_OK; b++) {
                size_t i = gr.ce[a], j = gr.ce[b];
                box bi = box_grow(rs[i].bb, v.tol), bj = box_grow(rs[j].bb, v.tol);
                if (!box_meets(bi, bj)) continue;
                /* visit each pair once: in the cell of the low corner of the boxes' intersection */
                size_t cx = cell_coord(fmax(bi.x0, bj.x0), gr.bb.x0, gr.cw, gr.g);
                size_t cy = cell_coord(fmax(bi.y0, bj.y0), gr.bb.y0, gr.ch, gr.g);
                if (cy * gr.g + cx != c) continue;
                if (i > j) {
                    size_t t = i;
                    i = j;
                    j = t;
                }
                rep->pairs_checked++;
                interaction it;
                if (interact(&v, &rs[i], &rs[j], &it)) {
                    st = acd_fail(err, ACD_ERR_NOMEM, "acd_verify2d: out of memory");
                    break;
                }
                if (it.crossing) {
                    fmt_pt(pa, sizeof pa, it.cross_pt);
                    st = acd_fail(err, ACD_ERR_VERIFY,
                                  "components %zu and %zu overlap: edge %zu of component %zu crosses edge %zu of "
                                  "component %zu near %s",
                                  B + i, B + j, it.cx, B + i, it.cy, B + j, pa);
                } else if (it.sx.in) {
                    fmt_pt(pa, sizeof pa, it.sx.in_pt);
                    st = acd_fail(err, ACD_ERR_VERIFY,
                                  "components %zu and %zu overlap: the point %s on edge %zu of component %zu lies "
                                  "inside component %zu",
                                  B + i, B + j, pa, it.sx.in_edge, B + i, B + j);
                } else if (it.sy.in) {
                    fmt_pt(pa, sizeof pa, it.sy.in_pt);
                    st = acd_fail(err, ACD_ERR_VERIFY,
                                  "components %zu and %zu overlap: the point %s on edge %zu of component %zu lies "
                                  "inside component %zu",
                                  B + i, B + j, pa, it.sy.in_edge, B + j, B + i);
                } else if (!it.sx.in && !it.sx.out && !it.sy.in && !it.sy.out) {
                    st = acd_fail(err, ACD_ERR_VERIFY, "components %zu and %zu overlap: they are the same polygon",
                                  B + i, B + j);
                }
                if (st != ACD_OK) fail(rep, ACD_V2D_OVERLAP, (long)i, (long)j);
            }
    }

    v.tol = fmax(sc.dist, rtol);
    /* 4. areas add up */
    if (st == ACD_OK) {
        double diff = rep->components_area - rep->input_area;
        /* points rounded off the input's edges move at most perimeter x rtol of area */
        double lim = opt.area_rel_tol * fabs(rep->input_area) + perimeter(input) * rtol;
        if (!(fabs(diff) <= lim)) {
            char where[160] = "";
            acd_vec2 gap;
            if (diff < 0 && uncovered_boundary_point(input, rs, count, v.tol, &gap)) {
                fmt_pt(pa, sizeof pa, gap);
                snprintf(where, sizeof where, "; the input's boundary at %s lies on no component", pa);
            }
            st = acd_fail(err, ACD_ERR_VERIFY,
                          "the components' areas add up to %.17g but the input's area is %.17g (difference %.3g, "
                          "relative %.3g > %.3g): %s%s",
                          rep->components_area, rep->input_area, diff,
                          rep->input_area != 0 ? fabs(diff) / fabs(rep->input_area) : INFINITY, opt.area_rel_tol,
                          diff < 0 ? "part of the input is not covered (a missing piece)"
                                   : "the components cover more than the input",
                          where);
            fail(rep, ACD_V2D_AREA, -1, -1);
        }
    }

    /* 5. concavity within tau */
    if (st == ACD_OK && opt.check_concavity) {
        double bound = opt.tau + v.tol;
        rep->max_concavity = 0;
        for (size_t i = 0; i < count; i++) {
            size_t w;
            double c = acd_verify2d_concavity(components[i], sizes[i], opt.measure, opt.tau, opt.notch_tolerance, &w);
            if (c < 0) {
                st = acd_fail(err, ACD_ERR_NOMEM, "acd_verify2d: out of memory");
                break;
            }
            if (c > rep->max_concavity || rep->max_concavity_component < 0) {
                rep->max_concavity = c;
                rep->max_concavity_component = (long)i;
            }
            if (c > bound) {
                fmt_pt(pa, sizeof pa, components[i][w]);
                st = acd_fail(err, ACD_ERR_VERIFY,
                              "component %zu has concavity %.17g > tau %.17g (measure %s, at its vertex %zu %s)",
                              B + i, c, opt.tau, measure_name(opt.measure), w, pa);
                fail(rep, ACD_V2D_CONCAVITY, (long)i, -1);
                break;
            }
        }
    }

    for (size_t i = 0; i < count; i++) region_free(&rs[i]);
    free(rs);
    region_free(&in);
    grid_free(&gr);
    free(v.ex);
    free(v.ey);
    free(v.items);
    free(v.splits);
    return st;
}

acd_status acd_verify2d_result(const acd_polygon *input, const acd2d_result *res, const acd2d_params *params,
                               size_t component_base, acd_verify2d_report *report, acd_error *err) {
    acd_verify2d_report dummy, *rep = report ? report : &dummy;
    if (!res) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_verify2d_result: no result");
    size_t n = res->ncomponents;
    const acd_vec2 **pts = malloc((n ? n : 1) * sizeof *pts);
    size_t *sz = malloc((n ? n : 1) * sizeof *sz);
    if (!pts || !sz) {
        free(pts);
        free(sz);
        return acd_fail(err, ACD_ERR_NOMEM, "acd_verify2d_result: out of memory");
    }
    for (size_t i = 0; i < n; i++) {
        pts[i] = res->components[i].points;
        sz[i] = res->components[i].npoints;
    }
    acd_verify2d_options o = acd_verify2d_default_options();
    o.tau = res->tau;
    o.measure = res->measure;
    if (params) o.notch_tolerance = params->notch_tolerance;
    o.component_base = component_base;
    acd_status st = acd_verify2d(input, pts, sz, n, &o, rep, err);
    free(pts);
    free(sz);
    if (st != ACD_OK) return st;
    /* hulls: convex, counterclockwise, enclosing their components */
    size_t nin = acd_polygon_num_points(input);
    double tol = fmax(acd_scale_of_points(&input->points[0].x, nin, 2).dist, round_tol(input));
    for (size_t i = 0; i < n; i++) {
        const acd2d_component *c = &res->components[i];
        size_t h = c->nhull;
        if (h < 3 || !c->hull || !(acd_v2d_ring_area(c->hull, h) > 0)) {
            fail(rep, ACD_V2D_HULL, (long)i, -1);
            return acd_fail(err, ACD_ERR_VERIFY, "component %zu: its hull has %zu points or is not counterclockwise",
                            component_base + i, h);
        }
        for (size_t k = 0; k < h; k++) {
            acd_vec2 a = c->hull[k], b = c->hull[(k + 1) % h], d = c->hull[(k + 2) % h];
            if (acd_ref_orient(a, b, d) < 0) {
                fail(rep, ACD_V2D_HULL, (long)i, -1);
                return acd_fail(err, ACD_ERR_VERIFY, "component %zu: its hull turns clockwise at hull vertex %zu",
                                component_base + i, (k + 1) % h);
            }
            for (size_t j = 0; j < c->npoints; j++) {
                acd_vec2 q = c->points[j];
                if (acd_ref_orient(a, b, q) < 0 && acd_seg_dist2(q, a, b) > tol) {
                    fail(rep, ACD_V2D_HULL, (long)i, -1);
                    return acd_fail(err, ACD_ERR_VERIFY,
                                    "component %zu: its vertex %zu (%.17g, %.17g) lies outside its hull (edge %zu)",
                                    component_base + i, j, q.x, q.y, k);
                }
            }
        }
    }
    return ACD_OK;
}
