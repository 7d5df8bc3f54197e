/* geom2/validate: normalization and validation of polygons with holes.
 *
 * Definitions from the dissertation, Ch. II.A.1 (Fig. 6): a polygon with holes is an external
 * boundary dP0 and hole boundaries dP1..dPk; it is simple when no two non-adjacent edges
 * intersect. Here "intersect" includes touching and collinear overlap, and two different
 * rings may not meet at all; every hole lies inside dP0 and outside every other hole (an
 * island inside a hole is a separate polygon). All decisions use the exact predicates.
 *
 * Which pairs of edges get the exact pair test: by default a Shamos-Hoey sweep line
 * (geom2/seg_sweep, O(n log n)); alternatively an adaptive binary subdivision of the bounding box
 * (a box holding more than a few edges is split at its middle along the axis that separates the
 * edges best, each edge going conservatively to every half it may touch; two edges that meet share
 * a leaf, where pairs are tested), or all pairs. All three give the same answer. */
#include "geom2/validate.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/predicates.h"
#include "core/tolerance.h"
#include "geom2/seg_sweep.h"

/* min/max without the NaN rules of fmin/fmax (coordinates are finite here), so they inline */
static inline double dmin(double a, double b) {
    return a < b ? a : b;
}
static inline double dmax(double a, double b) {
    return a > b ? a : b;
}

/* ---------------------------------------------------------------- normalization */

static int ring_extreme_orientation(const acd_vec2 *v, size_t n) {
    if (n < 3) return 0;
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i].x) || !isfinite(v[i].y)) return 0;
    size_t m = 0;
    for (size_t i = 1; i < n; i++)
        if (v[i].y < v[m].y || (v[i].y == v[m].y && v[i].x < v[m].x)) m = i;
    size_t u = (m + n - 1) % n, w = (m + 1) % n;
    double a[2] = {v[u].x, v[u].y}, b[2] = {v[m].x, v[m].y}, c[2] = {v[w].x, v[w].y};
    int s = acd_orient2d_sign(a, b, c);
    if (s != 0) return s;
    /* Only a ring that folds back at its extreme vertex (invalid anyway) gets here. */
    double area = 0.0;
    for (size_t i = 1; i + 1 < n; i++)
        area += (v[i].x - v[0].x) * (v[i + 1].y - v[0].y) - (v[i].y - v[0].y) * (v[i + 1].x - v[0].x);
    return area > 0 ? 1 : area < 0 ? -1 : 0;
}

int acd_polygon_ring_orientation(const acd_polygon *p, size_t r) {
    if (r >= p->nrings) return 0;
    return ring_extreme_orientation(acd_polygon_ring(p, r), acd_polygon_ring_size(p, r));
}

static int same_point(acd_vec2 a, acd_vec2 b) {
    return a.x == b.x && a.y == b.y;
}

acd_status acd_polygon_normalize(acd_polygon *p, acd_polygon_fixes *fixes, acd_error *err) {
    if (!p) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_polygon_normalize: NULL polygon");
    size_t k = 0; /* write position */
    for (size_t r = 0; r < p->nrings; r++) {
        size_t s = p->ring_start[r], e = p->ring_start[r + 1];
        size_t start = k;
        for (size_t i = s; i < e; i++) {
            if (k > start && same_point(p->points[k - 1], p->points[i])) {
                if (fixes) fixes->repeated_dropped++;
                continue;
            }
            p->points[k++] = p->points[i];
        }
        while (k - start > 1 && same_point(p->points[k - 1], p->points[start])) {
            k--;
            if (fixes) fixes->repeated_dropped++;
        }
        p->ring_start[r] = start;
        int o = ring_extreme_orientation(p->points + start, k - start);
        int want = r == 0 ? 1 : -1;
        if (o != 0 && o != want) {
            /* reverse, keeping the first vertex first */
            for (size_t i = start + 1, j = k - 1; i < j; i++, j--) {
                acd_vec2 t = p->points[i];
                p->points[i] = p->points[j];
                p->points[j] = t;
            }
            if (fixes) fixes->rings_reversed++;
        }
    }
    if (p->nrings) p->ring_start[p->nrings] = k;
    return ACD_OK;
}

/* ---------------------------------------------------------------- validation context */

typedef struct vctx {
    const acd_polygon *p;
    size_t index;   /* polygon index for messages */
    size_t n;       /* number of edges = number of points */
    size_t *ring;   /* ring of each edge */
    size_t *next;   /* index of the edge's end point */
    double margin;  /* box expansion for the conservative segment/box test */
    acd_error *err;
} vctx;

static void pt(const vctx *c, size_t i, double out[2]) {
    out[0] = c->p->points[i].x;
    out[1] = c->p->points[i].y;
}

static size_t local(const vctx *c, size_t i) {
    return i - c->p->ring_start[c->ring[i]];
}

static const char *rel_verb(acd_seg_relation rel) {
    switch (rel) {
    case ACD_SEG_PROPER: return "crosses";
    case ACD_SEG_TOUCH: return "touches";
    default: return "overlaps (collinear)";
    }
}

/* Reports edges e and f meeting. For a touch, names the vertex lying on the other edge. */
static acd_status report_pair(const vctx *c, size_t e, size_t f, acd_seg_relation rel) {
    double a0[2], a1[2], b0[2], b1[2];
    pt(c, e, a0);
    pt(c, c->next[e], a1);
    pt(c, f, b0);
    pt(c, c->next[f], b1);
    size_t re = c->ring[e], rf = c->ring[f];
    const char *what = re == rf ? "self-intersects" : "rings meet";
    if (rel == ACD_SEG_TOUCH) {
        /* find a vertex of one edge on the other edge */
        size_t v = SIZE_MAX, on = SIZE_MAX;
        if (acd_point_on_segment(b0, a0, a1)) v = f, on = e;
        else if (acd_point_on_segment(b1, a0, a1)) v = c->next[f], on = e;
        else if (acd_point_on_segment(a0, b0, b1)) v = e, on = f;
        else if (acd_point_on_segment(a1, b0, b1)) v = c->next[e], on = f;
        if (v != SIZE_MAX) {
            double q[2], o0[2], o1[2];
            pt(c, v, q);
            pt(c, on, o0);
            pt(c, c->next[on], o1);
            return acd_fail(c->err, ACD_ERR_INVALID_INPUT,
                            "polygon %zu %s: chain %zu vertex %zu (%.17g, %.17g) touches chain %zu edge %zu-%zu "
                            "((%.17g, %.17g)-(%.17g, %.17g))",
                            c->index, what, c->ring[v], local(c, v), q[0], q[1], c->ring[on], local(c, on),
                            local(c, c->next[on]), o0[0], o0[1], o1[0], o1[1]);
        }
    }
    return acd_fail(c->err, ACD_ERR_INVALID_INPUT,
                    "polygon %zu %s: chain %zu edge %zu-%zu ((%.17g, %.17g)-(%.17g, %.17g)) %s chain %zu edge "
                    "%zu-%zu ((%.17g, %.17g)-(%.17g, %.17g))",
                    c->index, what, re, local(c, e), local(c, c->next[e]), a0[0], a0[1], a1[0], a1[1],
                    rel_verb(rel), rf, local(c, f), local(c, c->next[f]), b0[0], b0[1], b1[0], b1[1]);
}

/* Checks one pair of edges. Adjacent edges of a ring may share their common vertex only. */
static int sgn_diff(double a, double b) {
    return a > b ? 1 : a < b ? -1 : 0;
}

static acd_status check_pair(const vctx *c, size_t e, size_t f) {
    if (e == f) return ACD_OK;
    double a0[2], a1[2], b0[2], b1[2];
    pt(c, e, a0);
    pt(c, c->next[e], a1);
    pt(c, f, b0);
    pt(c, c->next[f], b1);
    /* exact bounding-box rejection */
    if (dmax(a0[0], a1[0]) < dmin(b0[0], b1[0]) || dmax(b0[0], b1[0]) < dmin(a0[0], a1[0]) ||
        dmax(a0[1], a1[1]) < dmin(b0[1], b1[1]) || dmax(b0[1], b1[1]) < dmin(a0[1], a1[1]))
        return ACD_OK;
    if (c->ring[e] == c->ring[f] && (c->next[e] == f || c->next[f] == e)) {
        /* adjacent edges u-v and v-w (or the reverse) share v; they overlap iff u, v, w are
         * collinear with u and w on the same side of v. One orientation instead of four, and
         * none of them an exact zero on the shared vertex. */
        size_t v = c->next[e] == f ? f : e; /* the shared vertex */
        size_t u = v == f ? e : f;          /* start of the edge ending at v */
        size_t w = c->next[v];
        double pu[2], pv[2], pw[2];
        pt(c, u, pu);
        pt(c, v, pv);
        pt(c, w, pw);
        if (c->next[e] == f && c->next[f] == e) return ACD_OK; /* a 2-ring; excluded earlier */
        if (acd_orient2d_sign(pu, pv, pw) != 0) return ACD_OK;
        int sx = sgn_diff(pu[0], pv[0]) * sgn_diff(pw[0], pv[0]);
        int sy = sgn_diff(pu[1], pv[1]) * sgn_diff(pw[1], pv[1]);
        if (sx < 0 || sy < 0) return ACD_OK; /* collinear, on opposite sides: a straight vertex */
        double q[2];
        pt(c, v, q);
        return acd_fail(c->err, ACD_ERR_INVALID_INPUT,
                        "polygon %zu self-intersects: chain %zu folds back on itself at vertex %zu (%.17g, %.17g) "
                        "(its two edges overlap)",
                        c->index, c->ring[v], local(c, v), q[0], q[1]);
    }
    acd_seg_relation rel = acd_segments_relation(a0, a1, b0, b1);
    if (rel == ACD_SEG_DISJOINT) return ACD_OK;
    return report_pair(c, e, f, rel);
}

static acd_status sweep_pair(void *ctx, size_t e, size_t f) {
    return check_pair((const vctx *)ctx, e, f);
}

static acd_status brute_pairs(const vctx *c, const size_t *ids, size_t m) {
    for (size_t i = 0; i < m; i++)
        for (size_t j = i + 1; j < m; j++) {
            acd_status st = check_pair(c, ids[i], ids[j]);
            if (st != ACD_OK) return st;
        }
    return ACD_OK;
}

/* Conservative test: may edge e meet the closed box b (xmin, ymin, xmax, ymax)? Never answers
 * no for an edge that does meet it: the box is first expanded by c->margin, which exceeds the
 * rounding error of the side computations below. */
static int edge_meets_box(const vctx *c, size_t e, const double b[4]) {
    double x0 = b[0] - c->margin, y0 = b[1] - c->margin, x1 = b[2] + c->margin, y1 = b[3] + c->margin;
    acd_vec2 p = c->p->points[e], q = c->p->points[c->next[e]];
    if (dmax(p.x, q.x) < x0 || dmin(p.x, q.x) > x1 || dmax(p.y, q.y) < y0 || dmin(p.y, q.y) > y1) return 0;
    double dx = q.x - p.x, dy = q.y - p.y;
    double s1 = dx * (y0 - p.y) - dy * (x0 - p.x);
    double s2 = dx * (y0 - p.y) - dy * (x1 - p.x);
    double s3 = dx * (y1 - p.y) - dy * (x0 - p.x);
    double s4 = dx * (y1 - p.y) - dy * (x1 - p.x);
    if (s1 > 0 && s2 > 0 && s3 > 0 && s4 > 0) return 0;
    if (s1 < 0 && s2 < 0 && s3 < 0 && s4 < 0) return 0;
    return 1;
}

#define SUBDIV_LEAF 8
#define SUBDIV_MAX_DEPTH 60
/* Growth of a box in the conservative segment/box test: a fraction of the input's extent plus
 * a multiple of the unit roundoff of its largest coordinate. Not a geometric tolerance: any
 * value above the rounding error of the side computation (about 23 eps max|coord|) keeps the
 * test conservative; larger values only cost speed. */
#define SUBDIV_MARGIN_REL_EXTENT 1e-9
#define SUBDIV_MARGIN_ROUNDOFFS 256.0

static acd_status subdivide(const vctx *c, const double box_in[4], const size_t *ids, size_t m, int depth) {
    if (m <= SUBDIV_LEAF || depth >= SUBDIV_MAX_DEPTH) return brute_pairs(c, ids, m);
    /* Shrink the box to the edges' bounding box: two edges meeting in the node meet inside
     * both boxes. */
    double box[4] = {box_in[2], box_in[3], box_in[0], box_in[1]};
    for (size_t i = 0; i < m; i++) {
        acd_vec2 p = c->p->points[ids[i]], q = c->p->points[c->next[ids[i]]];
        box[0] = dmin(box[0], dmin(p.x, q.x));
        box[1] = dmin(box[1], dmin(p.y, q.y));
        box[2] = dmax(box[2], dmax(p.x, q.x));
        box[3] = dmax(box[3], dmax(p.y, q.y));
    }
    box[0] = dmax(box[0], box_in[0]);
    box[1] = dmax(box[1], box_in[1]);
    box[2] = dmin(box[2], box_in[2]);
    box[3] = dmin(box[3], box_in[3]);
    if (box[0] > box[2]) box[0] = box[2] = 0.5 * (box[0] + box[2]); /* only margin-included edges */
    if (box[1] > box[3]) box[1] = box[3] = 0.5 * (box[1] + box[3]);
    size_t *buf = malloc(4 * m * sizeof *buf);
    if (!buf) return acd_fail(c->err, ACD_ERR_NOMEM, "out of memory validating polygon %zu", c->index);
    size_t *lists[4] = {buf, buf + m, buf + 2 * m, buf + 3 * m};
    size_t counts[4] = {0, 0, 0, 0};
    double boxes[4][4];
    double mx = 0.5 * (box[0] + box[2]), my = 0.5 * (box[1] + box[3]);
    /* axis 0: split x at mx (boxes 0,1); axis 1: split y at my (boxes 2,3) */
    memcpy(boxes[0], box, sizeof boxes[0]);
    memcpy(boxes[1], box, sizeof boxes[1]);
    memcpy(boxes[2], box, sizeof boxes[2]);
    memcpy(boxes[3], box, sizeof boxes[3]);
    boxes[0][2] = mx;
    boxes[1][0] = mx;
    boxes[2][3] = my;
    boxes[3][1] = my;
    for (size_t i = 0; i < m; i++)
        for (int k = 0; k < 4; k++)
            if (edge_meets_box(c, ids[i], boxes[k])) lists[k][counts[k]++] = ids[i];
    size_t worst_x = counts[0] > counts[1] ? counts[0] : counts[1];
    size_t worst_y = counts[2] > counts[3] ? counts[2] : counts[3];
    int axis = (worst_y < worst_x || (worst_y == worst_x && counts[2] + counts[3] < counts[0] + counts[1])) ? 1 : 0;
    if (counts[2 * axis] >= m && counts[2 * axis + 1] >= m) {
        free(buf);
        return brute_pairs(c, ids, m); /* the edges cannot be separated here */
    }
    /* keep only the chosen halves, so memory along a recursion path stays O(n) */
    size_t k0 = (size_t)(2 * axis), n0 = counts[k0], n1 = counts[k0 + 1];
    size_t *keep = malloc((n0 + n1 + 1) * sizeof *keep);
    if (!keep) {
        free(buf);
        return acd_fail(c->err, ACD_ERR_NOMEM, "out of memory validating polygon %zu", c->index);
    }
    memcpy(keep, lists[k0], n0 * sizeof *keep);
    memcpy(keep + n0, lists[k0 + 1], n1 * sizeof *keep);
    double b0[4], b1[4];
    memcpy(b0, boxes[k0], sizeof b0);
    memcpy(b1, boxes[k0 + 1], sizeof b1);
    free(buf);
    acd_status st = subdivide(c, b0, keep, n0, depth + 1);
    if (st == ACD_OK) st = subdivide(c, b1, keep + n0, n1, depth + 1);
    free(keep);
    return st;
}

/* Point-in-ring by crossing parity with exact orientation; the point must not lie on the ring. */
static int point_in_ring(const acd_vec2 *v, size_t n, acd_vec2 q) {
    int inside = 0;
    double p[2] = {q.x, q.y};
    for (size_t i = 0, j = n - 1; i < n; j = i++) {
        double a[2] = {v[j].x, v[j].y}, b[2] = {v[i].x, v[i].y};
        int ua = a[1] > p[1], ub = b[1] > p[1];
        if (ua == ub) continue;
        int o = acd_orient2d_sign(a, b, p);
        /* upward edge a->b: crossing right of p iff p left of the edge */
        if ((ub && o > 0) || (ua && o < 0)) inside = !inside;
    }
    return inside;
}

typedef struct ring_box {
    double x0, y0, x1, y1;
    size_t ring;
} ring_box;

static int cmp_ring_box(const void *a, const void *b) {
    const ring_box *p = a, *q = b;
    if (p->x0 < q->x0) return -1;
    if (p->x0 > q->x0) return 1;
    return p->ring < q->ring ? -1 : p->ring > q->ring;
}

typedef struct yquery {
    double x, y;
    size_t id;
} yquery;

static int cmp_yquery(const void *a, const void *b) {
    const yquery *p = a, *q = b;
    if (p->y < q->y) return -1;
    if (p->y > q->y) return 1;
    return p->id < q->id ? -1 : p->id > q->id;
}

/* Crossing parity of many points against one ring at once (same rule as point_in_ring): the
 * points sorted by y, each edge visits only the points in its y-slab [ylo, yhi). */
static void points_in_ring(const acd_vec2 *v, size_t n, yquery *q, size_t nq, unsigned char *inside) {
    qsort(q, nq, sizeof *q, cmp_yquery);
    for (size_t k = 0; k < nq; k++) inside[q[k].id] = 0;
    for (size_t i = 0, j = n - 1; i < n; j = i++) {
        double a[2] = {v[j].x, v[j].y}, b[2] = {v[i].x, v[i].y};
        double ylo = dmin(a[1], b[1]), yhi = dmax(a[1], b[1]);
        double xlo = dmin(a[0], b[0]), xhi = dmax(a[0], b[0]);
        if (!(ylo < yhi)) continue;
        size_t lo = 0, hi = nq; /* first point with y >= ylo */
        while (lo < hi) {
            size_t mid = lo + (hi - lo) / 2;
            if (q[mid].y < ylo) lo = mid + 1;
            else hi = mid;
        }
        int up = b[1] > a[1];
        for (size_t k = lo; k < nq && q[k].y < yhi; k++) {
            if (q[k].x > xhi) continue; /* the edge crosses left of the point */
            int cross;
            if (q[k].x < xlo) cross = 1;
            else {
                double pp[2] = {q[k].x, q[k].y};
                int o = acd_orient2d_sign(a, b, pp);
                cross = up ? o > 0 : o < 0;
            }
            if (cross) inside[q[k].id] ^= 1;
        }
    }
}

static acd_status check_nesting(const vctx *c) {
    const acd_polygon *p = c->p;
    size_t nh = p->nrings - 1;
    if (nh == 0) return ACD_OK;
    yquery *yq = malloc(nh * sizeof *yq);
    unsigned char *in = malloc(nh);
    if (!yq || !in) {
        free(yq);
        free(in);
        return acd_fail(c->err, ACD_ERR_NOMEM, "out of memory validating polygon %zu", c->index);
    }
    for (size_t h = 1; h < p->nrings; h++) {
        acd_vec2 q = acd_polygon_ring(p, h)[0];
        yq[h - 1].x = q.x;
        yq[h - 1].y = q.y;
        yq[h - 1].id = h - 1;
    }
    points_in_ring(acd_polygon_ring(p, 0), acd_polygon_ring_size(p, 0), yq, nh, in);
    free(yq);
    for (size_t h = 1; h < p->nrings; h++)
        if (!in[h - 1]) {
            free(in);
            acd_vec2 q = acd_polygon_ring(p, h)[0];
            return acd_fail(c->err, ACD_ERR_INVALID_INPUT,
                            "polygon %zu: hole chain %zu lies outside the outer boundary (chain 0): its vertex 0 "
                            "(%.17g, %.17g) is outside",
                            c->index, h, q.x, q.y);
        }
    free(in);
    if (nh < 2) return ACD_OK;
    ring_box *bx = malloc(nh * sizeof *bx);
    if (!bx) return acd_fail(c->err, ACD_ERR_NOMEM, "out of memory validating polygon %zu", c->index);
    for (size_t h = 1; h < p->nrings; h++) {
        const acd_vec2 *v = acd_polygon_ring(p, h);
        size_t n = acd_polygon_ring_size(p, h);
        ring_box *b = &bx[h - 1];
        b->x0 = b->x1 = v[0].x;
        b->y0 = b->y1 = v[0].y;
        b->ring = h;
        for (size_t i = 1; i < n; i++) {
            b->x0 = dmin(b->x0, v[i].x);
            b->x1 = dmax(b->x1, v[i].x);
            b->y0 = dmin(b->y0, v[i].y);
            b->y1 = dmax(b->y1, v[i].y);
        }
    }
    qsort(bx, nh, sizeof *bx, cmp_ring_box);
    acd_status st = ACD_OK;
    /* A hole strictly inside hole g has its box strictly inside g's box, so it comes later in
     * x0 order and starts before g's x1. */
    for (size_t i = 0; i < nh && st == ACD_OK; i++)
        for (size_t j = i + 1; j < nh && bx[j].x0 <= bx[i].x1; j++) {
            if (bx[j].x1 > bx[i].x1 || bx[j].y0 < bx[i].y0 || bx[j].y1 > bx[i].y1) continue;
            size_t g = bx[i].ring, h = bx[j].ring;
            acd_vec2 q = acd_polygon_ring(p, h)[0];
            if (point_in_ring(acd_polygon_ring(p, g), acd_polygon_ring_size(p, g), q)) {
                st = acd_fail(c->err, ACD_ERR_INVALID_INPUT,
                              "polygon %zu: hole chain %zu lies inside hole chain %zu (its vertex 0 (%.17g, %.17g) is "
                              "inside); an island in a hole must be a separate polygon",
                              c->index, h, g, q.x, q.y);
                break;
            }
        }
    free(bx);
    return st;
}

static size_t lexmin_vertex(const acd_polygon *p, size_t r) {
    size_t s = p->ring_start[r], e = p->ring_start[r + 1], m = s;
    for (size_t i = s + 1; i < e; i++)
        if (p->points[i].x < p->points[m].x || (p->points[i].x == p->points[m].x && p->points[i].y < p->points[m].y))
            m = i;
    return m;
}

typedef struct ring_order {
    double x, y;
    size_t ring;
} ring_order;

static int cmp_ring_order(const void *a, const void *b) {
    const ring_order *p = a, *q = b;
    if (p->x != q->x) return p->x < q->x ? -1 : 1;
    if (p->y != q->y) return p->y < q->y ? -1 : 1;
    return p->ring < q->ring ? -1 : p->ring > q->ring;
}

/* Nesting of disjoint, correctly oriented rings from the sweep's "edge below" of each ring's
 * lexicographically smallest vertex v: if that edge e belongs to ring r, v is inside r iff the
 * side of e facing up is r's inner side (left of e for the counterclockwise outer ring, right
 * for clockwise holes; up is left of a rightward edge). Otherwise v is at r's level: its parent
 * is r's parent. Rings are taken in the order of their smallest vertices, so r's parent is known
 * first. Valid: the outer ring has no parent and every hole has the outer ring as its parent. */
static acd_status nesting_from_sweep(const vctx *c, const size_t *below) {
    const acd_polygon *p = c->p;
    size_t nr = p->nrings;
    ring_order *ord = malloc(nr * sizeof *ord);
    size_t *parent = malloc(nr * sizeof *parent);
    if (!ord || !parent) {
        free(ord);
        free(parent);
        return acd_fail(c->err, ACD_ERR_NOMEM, "out of memory validating polygon %zu", c->index);
    }
    for (size_t r = 0; r < nr; r++) {
        acd_vec2 v = p->points[lexmin_vertex(p, r)];
        ord[r].x = v.x;
        ord[r].y = v.y;
        ord[r].ring = r;
    }
    qsort(ord, nr, sizeof *ord, cmp_ring_order);
    acd_status st = ACD_OK;
    for (size_t k = 0; k < nr; k++) {
        size_t h = ord[k].ring, e = below[lexmin_vertex(p, h)];
        if (e == SIZE_MAX) {
            parent[h] = SIZE_MAX;
        } else {
            size_t r = c->ring[e];
            acd_vec2 a = p->points[e], b = p->points[c->next[e]];
            int rightward = a.x < b.x || (a.x == b.x && a.y < b.y);
            int inside = r == 0 ? rightward : !rightward;
            parent[h] = inside ? r : parent[r];
        }
    }
    for (size_t h = 0; h < nr && st == ACD_OK; h++) {
        size_t v = lexmin_vertex(p, h);
        acd_vec2 q = p->points[v];
        if (h == 0 && parent[0] != SIZE_MAX) {
            acd_vec2 q0 = acd_polygon_ring(p, parent[0])[0];
            st = acd_fail(c->err, ACD_ERR_INVALID_INPUT,
                          "polygon %zu: hole chain %zu lies outside the outer boundary (chain 0): the outer boundary "
                          "is inside it (its vertex 0 is (%.17g, %.17g))",
                          c->index, parent[0], q0.x, q0.y);
        } else if (h > 0 && parent[h] == SIZE_MAX) {
            st = acd_fail(c->err, ACD_ERR_INVALID_INPUT,
                          "polygon %zu: hole chain %zu lies outside the outer boundary (chain 0): its vertex %zu "
                          "(%.17g, %.17g) is outside",
                          c->index, h, local(c, v), q.x, q.y);
        } else if (h > 0 && parent[h] != 0) {
            st = acd_fail(c->err, ACD_ERR_INVALID_INPUT,
                          "polygon %zu: hole chain %zu lies inside hole chain %zu (its vertex %zu (%.17g, %.17g) is "
                          "inside); an island in a hole must be a separate polygon",
                          c->index, h, parent[h], local(c, v), q.x, q.y);
        }
    }
    free(ord);
    free(parent);
    return st;
}

/* Per-ring checks that need no pairs: size, finiteness, repeats, zero area. */
static acd_status check_rings(const acd_polygon *p, size_t index, acd_error *err) {
    for (size_t r = 0; r < p->nrings; r++) {
        const acd_vec2 *v = acd_polygon_ring(p, r);
        size_t n = acd_polygon_ring_size(p, r);
        for (size_t i = 0; i < n; i++)
            if (!isfinite(v[i].x) || !isfinite(v[i].y))
                return acd_fail(err, ACD_ERR_INVALID_INPUT,
                                "polygon %zu: chain %zu vertex %zu has a non-finite coordinate (%g, %g)", index, r, i,
                                v[i].x, v[i].y);
            else if (fabs(v[i].x) > ACD_COORD_MAX || fabs(v[i].y) > ACD_COORD_MAX)
                return acd_fail(err, ACD_ERR_INVALID_INPUT,
                                "polygon %zu: chain %zu vertex %zu (%g, %g) is beyond the supported coordinate "
                                "magnitude %g (the exact predicates would overflow); scale the input down",
                                index, r, i, v[i].x, v[i].y, ACD_COORD_MAX);
        if (n < 3)
            return acd_fail(err, ACD_ERR_DEGENERATE,
                            "polygon %zu: chain %zu has %zu distinct vertices; a ring needs at least 3", index, r, n);
        for (size_t i = 0; i < n; i++) {
            size_t j = (i + 1) % n;
            if (same_point(v[i], v[j]))
                return acd_fail(err, ACD_ERR_INVALID_INPUT,
                                "polygon %zu: chain %zu vertex %zu (%.17g, %.17g) repeats vertex %zu (a zero-length "
                                "edge; acd_polygon_normalize removes it)",
                                index, r, j, v[j].x, v[j].y, i);
        }
        double a[2] = {v[0].x, v[0].y}, b[2] = {v[1].x, v[1].y};
        int all_collinear = 1;
        for (size_t i = 2; i < n && all_collinear; i++) {
            double q[2] = {v[i].x, v[i].y};
            if (acd_orient2d_sign(a, b, q) != 0) all_collinear = 0;
        }
        if (all_collinear)
            return acd_fail(err, ACD_ERR_DEGENERATE,
                            "polygon %zu: chain %zu has zero area (its %zu vertices from (%.17g, %.17g) are all "
                            "collinear)",
                            index, r, n, v[0].x, v[0].y);
    }
    return ACD_OK;
}

acd_status acd_polygon_validate_with(const acd_polygon *p, size_t index, acd_validate_method method,
                                     acd_error *err) {
    if (!p) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_polygon_validate: NULL polygon");
    if (p->nrings == 0) return acd_fail(err, ACD_ERR_DEGENERATE, "polygon %zu is empty (no rings)", index);
    acd_status st = check_rings(p, index, err);
    if (st != ACD_OK) return st;

    vctx c;
    unsigned char *want = NULL;
    size_t *below = NULL;
    memset(&c, 0, sizeof c);
    c.p = p;
    c.index = index;
    c.err = err;
    c.n = acd_polygon_num_points(p);
    c.ring = malloc(c.n * sizeof *c.ring);
    c.next = malloc(c.n * sizeof *c.next);
    size_t *ids = malloc(c.n * sizeof *ids);
    if (!c.ring || !c.next || !ids) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory validating polygon %zu (%zu vertices)", index, c.n);
        goto done;
    }
    double box[4] = {p->points[0].x, p->points[0].y, p->points[0].x, p->points[0].y};
    double maxabs = 0;
    for (size_t r = 0; r < p->nrings; r++) {
        size_t s = p->ring_start[r], e = p->ring_start[r + 1];
        for (size_t i = s; i < e; i++) {
            c.ring[i] = r;
            c.next[i] = i + 1 < e ? i + 1 : s;
            ids[i] = i;
            acd_vec2 q = p->points[i];
            box[0] = dmin(box[0], q.x);
            box[1] = dmin(box[1], q.y);
            box[2] = dmax(box[2], q.x);
            box[3] = dmax(box[3], q.y);
            maxabs = dmax(maxabs, dmax(fabs(q.x), fabs(q.y)));
        }
    }
    double extent = hypot(box[2] - box[0], box[3] - box[1]);
    c.margin = SUBDIV_MARGIN_REL_EXTENT * extent + SUBDIV_MARGIN_ROUNDOFFS * DBL_EPSILON * maxabs + DBL_MIN;
    if (method == ACD_VALIDATE_BRUTE) st = brute_pairs(&c, ids, c.n);
    else if (method == ACD_VALIDATE_SUBDIV) st = subdivide(&c, box, ids, c.n, 0);
    else {
        /* also ask for the edge below each ring's lexicographically smallest vertex (nesting) */
        want = calloc(c.n, 1);
        below = malloc(c.n * sizeof *below);
        if (!want || !below) {
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory validating polygon %zu (%zu vertices)", index, c.n);
            goto done;
        }
        for (size_t r = 0; r < p->nrings; r++) want[lexmin_vertex(p, r)] = 1;
        st = acd_sweep_edges(p->points, c.next, c.n, sweep_pair, &c, want, below, err);
    }
    if (st != ACD_OK) goto done;

    for (size_t r = 0; r < p->nrings; r++) {
        int o = acd_polygon_ring_orientation(p, r);
        int want = r == 0 ? 1 : -1;
        if (o != want) {
            st = acd_fail(err, ACD_ERR_INVALID_INPUT,
                          "polygon %zu: chain %zu (%s) is %s; the outer ring must be counterclockwise and holes "
                          "clockwise (acd_polygon_normalize fixes this)",
                          index, r, r == 0 ? "outer boundary" : "hole", o > 0 ? "counterclockwise" : "clockwise");
            goto done;
        }
    }
    st = below ? nesting_from_sweep(&c, below) : check_nesting(&c);
done:
    free(c.ring);
    free(c.next);
    free(ids);
    free(want);
    free(below);
    return st;
}

acd_status acd_polygon_validate(const acd_polygon *p, size_t index, acd_error *err) {
    return acd_polygon_validate_with(p, index, ACD_VALIDATE_FAST, err);
}
