/* acd2/cut: Resolve(P, r) for a notch r of a component (Lien dissertation IV.B Alg. 5; cut choice
 * IV.D.1 Eqn 4.3 with s_c, s_d; spec acd2d.md §5.2-§5.5 and ★ decisions §5.4, §11 A9, A12, A19).
 *
 * design:
 *  1. score every vertex x strictly inside r's resolving cone by
 *     f = (1 + s_c conc(x)) / (s_d |r x|) (ties: shorter, then smaller id);
 *  2. ray mode: shoot from r towards the best x and stop at the first boundary point, a vertex or
 *     a new point on an edge (no candidate: shoot along the cone bisector);
 *     diagonal mode: the best x that r sees; none: fall back to the bisector ray;
 *  3. split the ring into r..end and end..r.
 * Every side, crossing and cone decision is an exact predicate. The new point on an edge is
 * computed from the two orientation values as a + s (b - a), 0 < s < 1; the open cut segment is
 * then re-checked exactly against every edge and vertex, and a nearer blocker (possible only by
 * rounding of the ordering parameter) replaces the hit. */
#include "acd2/cut.h"

#include <math.h>
#include <stdlib.h>

/* parameter of q (collinear with R, x) along R -> x, by the dominant coordinate */
static double param_on(acd_vec2 R, acd_vec2 x, acd_vec2 q) {
    double dx = x.x - R.x, dy = x.y - R.y;
    if (fabs(dx) >= fabs(dy)) return (q.x - R.x) / dx;
    return (q.y - R.y) / dy;
}

/* point of edge (k, k+1) of ring on the line R x; 1 / 2 when it rounds onto the first / second end */
static int edge_point(const acd2_ring *ring, size_t k, acd_vec2 R, acd_vec2 x, acd_vec2 *z) {
    size_t k2 = acd2_next(k, ring->n);
    acd_vec2 a = ring->p[k], b = ring->p[k2];
    double oa = acd2_orient(R, x, a), ob = acd2_orient(R, x, b);
    double s = oa / (oa - ob);
    if (!(s > 0)) s = 0;
    if (!(s < 1)) s = 1;
    z->x = a.x + s * (b.x - a.x);
    z->y = a.y + s * (b.y - a.y);
    if (s == 0 || acd2_same(*z, a)) return 1;
    if (s == 1 || acd2_same(*z, b)) return 2;
    return 0;
}

static int in_wedge_at(const acd2_ring *ring, size_t v, acd_vec2 R) {
    size_t n = ring->n;
    return acd2_in_wedge(ring->p[acd2_prev(v, n)], ring->p[v], ring->p[acd2_next(v, n)], R);
}

static void set_edge_hit(const acd2_ring *rings, size_t ring, size_t k, acd_vec2 R, acd_vec2 aim, acd2_hit *hit) {
    acd_vec2 z;
    const acd2_ring *rg = &rings[ring];
    int e = edge_point(rg, k, R, aim, &z);
    hit->ring = ring;
    if (e) {
        hit->is_vertex = 1;
        hit->j = e == 1 ? k : acd2_next(k, rg->n);
        hit->z = rg->p[hit->j];
    } else {
        hit->is_vertex = 0;
        hit->j = k;
        hit->z = z;
    }
}

/* bounding box of a segment; a cheap exact rejection before any predicate */
typedef struct box { double x0, x1, y0, y1; } box;
static box seg_box(acd_vec2 a, acd_vec2 b) {
    box r = {fmin(a.x, b.x), fmax(a.x, b.x), fmin(a.y, b.y), fmax(a.y, b.y)};
    return r;
}
static int out_pt(const box *b, acd_vec2 p) { return p.x < b->x0 || p.x > b->x1 || p.y < b->y0 || p.y > b->y1; }
static int out_seg(const box *b, acd_vec2 p, acd_vec2 q) {
    return (p.x < b->x0 && q.x < b->x0) || (p.x > b->x1 && q.x > b->x1) || (p.y < b->y0 && q.y < b->y0) ||
           (p.y > b->y1 && q.y > b->y1);
}

static int find_first(const acd2_ring *rings, size_t nrings, size_t rr, size_t r, acd_vec2 x, acd2_hit *hit) {
    acd_vec2 R = rings[rr].p[r];
    double best_t = INFINITY;
    int found = 0;
    box bb = seg_box(R, x);
    for (size_t g = 0; g < nrings; g++) {
        const acd2_ring *ring = &rings[g];
        size_t n = ring->n;
        for (size_t v = 0; v < n; v++) {
            if (out_pt(&bb, ring->p[v])) continue;
            if ((g == rr && v == r) || acd2_same(ring->p[v], R)) continue;
            if (acd2_orient_sign(R, x, ring->p[v]) != 0) continue;
            if (!acd2_between(R, x, ring->p[v], 1)) continue;
            if (found && hit->is_vertex && acd2_same(ring->p[v], hit->z)) {
                if (in_wedge_at(ring, v, R) && !in_wedge_at(&rings[hit->ring], hit->j, R)) {
                    hit->ring = g;
                    hit->j = v;
                }
                continue;
            }
            double t = param_on(R, x, ring->p[v]);
            if (t < best_t) {
                best_t = t;
                hit->is_vertex = 1;
                hit->ring = g;
                hit->j = v;
                hit->z = ring->p[v];
                found = 1;
            }
        }
    }
    int edge = 0;
    size_t eg = 0, ek = 0;
    for (size_t g = 0; g < nrings; g++) {
        const acd2_ring *ring = &rings[g];
        size_t n = ring->n;
        for (size_t k = 0; k < n; k++) {
            size_t k2 = acd2_next(k, n);
            if (g == rr && (k == r || k2 == r)) continue;
            acd_vec2 a = ring->p[k], b = ring->p[k2];
            if (out_seg(&bb, a, b)) continue;
            int sa = acd2_orient_sign(R, x, a), sb = acd2_orient_sign(R, x, b);
            if (!((sa > 0 && sb < 0) || (sa < 0 && sb > 0))) continue;
            if (acd2_orient_sign(a, b, R) <= 0 || acd2_orient_sign(a, b, x) >= 0) continue;
            double orr = acd2_orient(a, b, R), ox = acd2_orient(a, b, x);
            double t = orr / (orr - ox);
            if (t < best_t) {
                best_t = t;
                edge = 1;
                eg = g;
                ek = k;
                found = 1;
            }
        }
    }
    if (!found) return -1;
    if (edge) set_edge_hit(rings, eg, ek, R, x, hit);
    return 0;
}

/* Exact re-check of the open segment R -> hit->z. Returns 1 when it is clear; otherwise the
 * blocker (a vertex, or an edge crossing the segment) in *bg, *bv, *blk. */
static int verify(const acd2_ring *rings, size_t nrings, size_t rr, size_t r, const acd2_hit *hit, size_t *bg, int *bv,
                  size_t *blk) {
    acd_vec2 R = rings[rr].p[r], Z = hit->z;
    const double Rd[2] = {R.x, R.y}, Zd[2] = {Z.x, Z.y};
    box bb = seg_box(R, Z);
    for (size_t g = 0; g < nrings; g++) {
        const acd2_ring *ring = &rings[g];
        size_t n = ring->n;
        for (size_t v = 0; v < n; v++) {
            acd_vec2 q = ring->p[v];
            if (out_pt(&bb, q)) continue;
            if (acd2_same(q, R) || acd2_same(q, Z)) continue;
            if (acd2_orient_sign(R, Z, q) == 0 && acd2_between(R, Z, q, 0)) {
                *bg = g; *bv = 1; *blk = v;
                return 0;
            }
        }
        for (size_t k = 0; k < n; k++) {
            size_t k2 = acd2_next(k, n);
            if (g == rr && (k == r || k2 == r)) continue;
            if (g == hit->ring) {
                if (!hit->is_vertex && k == hit->j) continue;
                if (hit->is_vertex && (k == hit->j || k2 == hit->j)) continue;
            }
            if (out_seg(&bb, ring->p[k], ring->p[k2])) continue;
            const double A[2] = {ring->p[k].x, ring->p[k].y}, B[2] = {ring->p[k2].x, ring->p[k2].y};
            if (acd_segments_relation(Rd, Zd, A, B) == ACD_SEG_PROPER) {
                *bg = g; *bv = 0; *blk = k;
                return 0;
            }
        }
    }
    return 1;
}

int acd2_shoot_multi(const acd2_ring *rings, size_t nrings, size_t rr, size_t r, acd_vec2 x, acd2_hit *hit) {
    if (find_first(rings, nrings, rr, r, x, hit)) return -1;
    for (int iter = 0; iter < 64; iter++) {
        int bv = 0;
        size_t bg = 0, blk = 0;
        if (verify(rings, nrings, rr, r, hit, &bg, &bv, &blk)) return 0;
        /* a blocker nearer than the chosen point (rounding of the ordering): take it */
        if (bv) {
            hit->ring = bg;
            hit->is_vertex = 1;
            hit->j = blk;
            hit->z = rings[bg].p[blk];
        } else {
            set_edge_hit(rings, bg, blk, rings[rr].p[r], hit->z, hit);
        }
    }
    return -1;
}

int acd2_shoot(const acd2_ring *ring, size_t r, acd_vec2 x, acd2_hit *hit) {
    return acd2_shoot_multi(ring, 1, 0, r, x, hit);
}

typedef struct cand {
    size_t v;
    double f, d;
    int64_t id;
} cand;

static int cand_better(const cand *a, const cand *b) {
    if (a->f != b->f) return a->f > b->f;
    if (a->d != b->d) return a->d < b->d;
    return a->id < b->id;
}

static int cand_cmp(const void *x, const void *y) {
    const cand *a = x, *b = y;
    if (cand_better(a, b)) return -1;
    if (cand_better(b, a)) return 1;
    return 0;
}

static int shoot_bisector(const acd2_ring *ring, size_t r, const acd2_cut_opts *o, acd2_hit *hit) {
    size_t n = ring->n;
    acd_vec2 u = ring->p[acd2_prev(r, n)], R = ring->p[r], w = ring->p[acd2_next(r, n)];
    double ax = R.x - u.x, ay = R.y - u.y, bx = R.x - w.x, by = R.y - w.y;
    double la = hypot(ax, ay), lb = hypot(bx, by);
    if (!(la > 0 && lb > 0)) return -1;
    double dx = ax / la + bx / lb, dy = ay / la + by / lb;
    double l = hypot(dx, dy);
    if (!(l > 0)) return -1;
    acd_vec2 x = {R.x + dx / l * o->far, R.y + dy / l * o->far};
    return acd2_shoot(ring, r, x, hit);
}

int acd2_choose_cut(const acd2_ring *ring, const double *conc, size_t r, const acd2_cut_opts *o, acd2_hit *hit) {
    size_t n = ring->n;
    acd_vec2 u = ring->p[acd2_prev(r, n)], R = ring->p[r], w = ring->p[acd2_next(r, n)];
    if (o->mode == ACD2D_CUT_RAY) {
        cand best = {SIZE_MAX, 0, 0, 0};
        for (size_t v = 0; v < n; v++) {
            if (v == r) continue;
            acd_vec2 q = ring->p[v];
            double d = hypot(q.x - R.x, q.y - R.y);
            if (!(d > 0)) continue;
            cand c = {v, (1.0 + o->sc * conc[v]) / (o->sd * d), d, ring->id[v]};
            if (best.v != SIZE_MAX && !cand_better(&c, &best)) continue; /* score first: cheap */
            if (!acd2_in_resolving_cone(u, R, w, q)) continue;
            best = c;
        }
        if (best.v == SIZE_MAX) return shoot_bisector(ring, r, o, hit);
        return acd2_shoot(ring, r, ring->p[best.v], hit);
    }
    /* diagonal mode: best visible vertex inside the cone */
    cand *cs = malloc((n ? n : 1) * sizeof *cs);
    if (!cs) return -2;
    size_t nc = 0;
    for (size_t v = 0; v < n; v++) {
        if (v == r) continue;
        acd_vec2 q = ring->p[v];
        if (!acd2_in_resolving_cone(u, R, w, q)) continue;
        double d = hypot(q.x - R.x, q.y - R.y);
        if (!(d > 0)) continue;
        cs[nc].v = v;
        cs[nc].d = d;
        cs[nc].f = (1.0 + o->sc * conc[v]) / (o->sd * d);
        cs[nc].id = ring->id[v];
        nc++;
    }
    qsort(cs, nc, sizeof *cs, cand_cmp);
    for (size_t i = 0; i < nc; i++) {
        acd2_hit h;
        if (acd2_shoot(ring, r, ring->p[cs[i].v], &h)) continue;
        if (h.is_vertex && acd2_same(h.z, ring->p[cs[i].v])) {
            *hit = h;
            free(cs);
            return 0;
        }
    }
    free(cs);
    return shoot_bisector(ring, r, o, hit);
}

int acd2_split(const acd2_ring *ring, size_t r, const acd2_hit *hit, int64_t new_id, acd2_ring *a, acd2_ring *b) {
    size_t n = ring->n, j = hit->j;
    a->n = b->n = 0;
    if (hit->is_vertex) {
        size_t ca = (j + n - r) % n + 1, cb = (r + n - j) % n + 1;
        if (acd2_ring_append_range(a, ring, r, ca)) return -1;
        if (acd2_ring_append_range(b, ring, j, cb)) return -1;
    } else {
        size_t j2 = acd2_next(j, n);
        size_t ca = (j + n - r) % n + 1, cb = (r + n - j2) % n + 1;
        if (acd2_ring_append_range(a, ring, r, ca) || acd2_ring_push(a, hit->z, new_id)) return -1;
        if (acd2_ring_push(b, hit->z, new_id) || acd2_ring_append_range(b, ring, j2, cb)) return -1;
    }
    acd2_ring_clean(a);
    acd2_ring_clean(b);
    return 0;
}
