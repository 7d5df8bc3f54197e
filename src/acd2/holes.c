/* acd2/holes: hole resolution (Lien dissertation IV.A.2 "concavity of hole points", IV.A.2.b
 * principal axis, Eqn 4.1; IV.A.2.c hole concavity, Eqn 4.2; IV.B ordering, Fig. 23; Alg. 5
 * line 4; spec acd2d.md §4.6 with ★ decisions §11 A6-A8, A16).
 *
 * design:
 *  1. for every hole, the two principal-axis extremes p, q (unweighted covariance eigenvector);
 *  2. for every alive hole and extreme e (a notch of P): aim at the nearest boundary point
 *     strictly inside e's resolving cone (vertices and perpendicular feet on edges, over the
 *     outer ring and all alive holes), or along the cone bisector when there is none; shoot a
 *     ray from e towards it; the first boundary point met is e's target (visible by
 *     construction: exact re-check in acd2_shoot_multi);
 *  3. a hole whose target (for either extreme; the nearer one) is on the outer ring is ready;
 *     merge the ready hole with the largest Eqn 4.2 value
 *        concavity(x) + |x - p| + |p - cw(p)|      (delta = concavity(P0) is common to all)
 *     where x is the target and concavity(x) its stored concavity (a merged hole's value for
 *     points on merged holes);
 *  4. when no hole is ready (each is hidden behind others), splice the hole whose target is the
 *     nearest point on another hole into that hole, and go on;
 *  5. when no hole has any target (fallback, not in the dissertation): bridge the hole with the
 *     rightmost vertex M to a vertex it sees, found along the ray to the right of M (Eberly's
 *     hole bridging, as in geom2/triangulate.c) and checked exactly (bridge_target); it always
 *     exists for valid rings, so valid input is never refused here.
 * Cost: O(h N) per merge (h holes, N vertices). */
#include "acd2/holes.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd2/cut.h"
#include "core/error.h"

void acd2_pa_extremes(const acd_vec2 *p, size_t n, size_t *lo, size_t *hi) {
    double cx = 0, cy = 0;
    for (size_t i = 0; i < n; i++) { cx += p[i].x; cy += p[i].y; }
    cx /= (double)n;
    cy /= (double)n;
    double sxx = 0, sxy = 0, syy = 0;
    for (size_t i = 0; i < n; i++) {
        double dx = p[i].x - cx, dy = p[i].y - cy;
        sxx += dx * dx; sxy += dx * dy; syy += dy * dy;
    }
    double th = 0.5 * atan2(2 * sxy, sxx - syy);
    double ex = cos(th), ey = sin(th);
    size_t a = 0, b = 0;
    double mn = INFINITY, mx = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        double t = (p[i].x - cx) * ex + (p[i].y - cy) * ey;
        if (t < mn) { mn = t; a = i; }
        if (t > mx) { mx = t; b = i; }
    }
    *lo = a;
    *hi = b;
}

static int ring_from(acd2_ring *r, const acd_vec2 *p, size_t n, int64_t id0) {
    memset(r, 0, sizeof *r);
    if (acd2_ring_reserve(r, n)) return -1;
    for (size_t i = 0; i < n; i++) {
        r->p[i] = p[i];
        r->id[i] = id0 + (int64_t)i;
        r->c[i] = 0;
        r->be[i] = -1;
    }
    r->n = n;
    return 0;
}

acd_status acd2_holes_init(acd2_holes *hs, const acd_polygon *poly, const double *outer_conc, double far,
                           acd_error *err) {
    memset(hs, 0, sizeof *hs);
    size_t np = acd_polygon_num_points(poly);
    hs->nh = poly->nrings - 1;
    hs->alive = hs->nh;
    hs->far = far;
    hs->next_id = (int64_t)np;
    hs->idcap = (int64_t)np + 4 * (int64_t)hs->nh + 8;
    hs->idconc = calloc((size_t)hs->idcap, sizeof *hs->idconc);
    hs->h = calloc(hs->nh ? hs->nh : 1, sizeof *hs->h);
    if (!hs->idconc || !hs->h) goto nomem;
    if (ring_from(&hs->outer, acd_polygon_ring(poly, 0), acd_polygon_ring_size(poly, 0), 0)) goto nomem;
    for (size_t k = 0; k < hs->outer.n; k++) hs->idconc[k] = outer_conc[k];
    for (size_t i = 0; i < hs->nh; i++) {
        acd2_hole *h = &hs->h[i];
        if (ring_from(&h->ring, acd_polygon_ring(poly, i + 1), acd_polygon_ring_size(poly, i + 1),
                      (int64_t)poly->ring_start[i + 1]))
            goto nomem;
        acd2_pa_extremes(h->ring.p, h->ring.n, &h->ext[0], &h->ext[1]);
        h->alive = 1;
    }
    return ACD_OK;
nomem:
    acd2_holes_free(hs);
    return acd_fail(err, ACD_ERR_NOMEM, "out of memory while preparing %zu holes", poly->nrings - 1);
}

void acd2_holes_free(acd2_holes *hs) {
    acd2_ring_free(&hs->outer);
    for (size_t i = 0; i < hs->nh; i++) acd2_ring_free(&hs->h[i].ring);
    free(hs->h);
    free(hs->idconc);
    memset(hs, 0, sizeof *hs);
}

/* target: see holes.h (acd2_target) */
typedef acd2_target target;

/* nearest point of segment (a, b) to R (strictly inside the cone u R w), if any */
static int nearest_on_edge(acd_vec2 u, acd_vec2 R, acd_vec2 w, acd_vec2 a, acd_vec2 b, acd_vec2 *out) {
    double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
    if (!(l2 > 0)) return 0;
    double s = ((R.x - a.x) * dx + (R.y - a.y) * dy) / l2;
    if (!(s > 0 && s < 1)) return 0;
    acd_vec2 f = {a.x + s * dx, a.y + s * dy};
    if (acd2_same(f, R) || !acd2_in_resolving_cone(u, R, w, f)) return 0;
    *out = f;
    return 1;
}

/* rings[0] = outer, rings[1 + k] = alive hole idx[k] */
static void find_target(const acd2_holes *hs, const acd2_ring *rings, size_t nr, size_t self, size_t e,
                        target *t) {
    const acd2_ring *hr = &rings[self];
    size_t n = hr->n;
    acd_vec2 u = hr->p[acd2_prev(e, n)], R = hr->p[e], w = hr->p[acd2_next(e, n)];
    t->ok = 0;
    t->from = R;
    t->aim_dist = INFINITY;
    if (acd2_orient_sign(u, R, w) >= 0) return; /* not a notch of P (degenerate extreme) */
    double best = INFINITY;
    acd_vec2 aim = R;
    int aim_vertex = 0;
    for (size_t g = 0; g < nr; g++) {
        const acd2_ring *rg = &rings[g];
        for (size_t k = 0; k < rg->n; k++) {
            acd_vec2 q = rg->p[k];
            if (!acd2_same(q, R) && acd2_in_resolving_cone(u, R, w, q)) {
                double d = hypot(q.x - R.x, q.y - R.y);
                if (d < best) { best = d; aim = q; aim_vertex = 1; }
            }
            size_t k2 = acd2_next(k, rg->n);
            if (g == self && (k == e || k2 == e)) continue;
            acd_vec2 f;
            if (nearest_on_edge(u, R, w, q, rg->p[k2], &f)) {
                double d = hypot(f.x - R.x, f.y - R.y);
                if (d < best) { best = d; aim = f; aim_vertex = 0; }
            }
        }
    }
    if (best == INFINITY) { /* bisector of the cone */
        double ax = R.x - u.x, ay = R.y - u.y, bx = R.x - w.x, by = R.y - w.y;
        double la = hypot(ax, ay), lb = hypot(bx, by);
        double dx = ax / la + bx / lb, dy = ay / la + by / lb, l = hypot(dx, dy);
        if (!(l > 0)) return;
        aim.x = R.x + dx / l * hs->far;
        aim.y = R.y + dy / l * hs->far;
    } else {
        t->aim_dist = best;
        /* A vertex is shot at exactly (the segment ends on the boundary, so something is met).
         * A foot on an edge is rounded off the edge's line: shoot along its direction past the
         * whole polygon, so that an edge crossing is always met. (Aiming at 2 * foot - R, or at
         * 2 * vertex - R, which is rounded off the line through the vertex, let the ray graze a
         * vertex and end in the interior: "no hole could be connected", tests/data/2d/
         * star120-hole-refused.poly.) */
        if (!aim_vertex) {
            aim.x = R.x + (aim.x - R.x) / best * hs->far;
            aim.y = R.y + (aim.y - R.y) / best * hs->far;
        }
    }
    acd2_hit hit;
    if (acd2_shoot_multi(rings, nr, self, e, aim, &hit)) return;
    t->ok = 1;
    t->owner = hit.ring;
    t->hit = hit;
    t->e = e;
    t->dist = hypot(hit.z.x - R.x, hit.z.y - R.y);
    const acd2_ring *hg = &rings[hit.ring];
    t->ida = hg->id[hit.j];
    t->idb = hit.is_vertex ? -1 : hg->id[acd2_next(hit.j, hg->n)];
}

/* splices hole ring `h` (merge from its vertex e) into ring `dst` at hit (vertex or edge) */
static int splice(acd2_ring *dst, const acd2_ring *h, size_t e, const acd2_hit *hit, int64_t new_id, double weld) {
    acd2_ring out = {0};
    size_t n = dst->n, j = hit->j;
    acd_vec2 U = dst->p[j], V = dst->p[acd2_next(j, n)];
    int rc = 0;
    rc |= acd2_ring_append_range(&out, dst, 0, j + 1);
    if (!hit->is_vertex) rc |= acd2_ring_push(&out, hit->z, new_id);
    rc |= acd2_ring_append_range(&out, h, e, h->n);
    rc |= acd2_ring_push(&out, h->p[e], h->id[e]);
    if (hit->is_vertex) rc |= acd2_ring_push(&out, dst->p[j], dst->id[j]);
    else rc |= acd2_ring_push(&out, hit->z, new_id);
    if (j + 1 < n) rc |= acd2_ring_append_range(&out, dst, j + 1, n - j - 1);
    /* a new point rounded off an earlier slit's edge U V by more than the weld distance (far from
     * the origin) goes into the slit's other side V U too, so both sides stay one segment pair */
    if (!rc && !hit->is_vertex && acd2_line_offset(U, V, hit->z) > weld &&
        acd2_ring_insert_on_edge(&out, V, U, hit->z, new_id) < 0)
        rc = 1;
    if (rc) {
        acd2_ring_free(&out);
        return -1;
    }
    acd2_ring_free(dst);
    *dst = out;
    return 0;
}

static double anchor_conc(const acd2_holes *hs, const target *t) {
    int64_t a = t->ida, b = t->idb;
    double c = a >= 0 && a < hs->idcap ? hs->idconc[a] : 0;
    double cb = b >= 0 && b < hs->idcap ? hs->idconc[b] : 0;
    return cb > c ? cb : c;
}

/* does the new slit (e, z) change the target t of an extreme of a remaining hole? It does when
 * it has a point strictly inside the extreme's cone nearer than the current aim, or when it
 * touches the current diagonal. */
static int slit_affects(const acd2_ring *hr, size_t ext, const target *t, acd_vec2 e, acd_vec2 z) {
    size_t n = hr->n;
    acd_vec2 u = hr->p[acd2_prev(ext, n)], R = hr->p[ext], w = hr->p[acd2_next(ext, n)];
    if (!t->ok) return 1;
    const acd_vec2 ends[2] = {e, z};
    for (int k = 0; k < 2; k++)
        if (!acd2_same(ends[k], R) && acd2_in_resolving_cone(u, R, w, ends[k]) &&
            hypot(ends[k].x - R.x, ends[k].y - R.y) <= t->aim_dist)
            return 1;
    acd_vec2 f;
    if (nearest_on_edge(u, R, w, e, z, &f) && hypot(f.x - R.x, f.y - R.y) <= t->aim_dist) return 1;
    const double A[2] = {R.x, R.y}, B[2] = {t->hit.z.x, t->hit.z.y}, C[2] = {e.x, e.y}, D[2] = {z.x, z.y};
    return acd_segments_relation(A, B, C, D) != ACD_SEG_DISJOINT;
}

/* Does edge (a, b) block the diagonal (m, v)? It may meet it only at m or v, and only at an end
 * of the edge (exact: acd_segments_relation). */
static int edge_blocks(acd_vec2 m, acd_vec2 v, acd_vec2 a, acd_vec2 b) {
    const double M[2] = {m.x, m.y}, V[2] = {v.x, v.y}, A[2] = {a.x, a.y}, B[2] = {b.x, b.y};
    acd_seg_relation rel = acd_segments_relation(M, V, A, B);
    if (rel == ACD_SEG_DISJOINT) return 0;
    if (rel != ACD_SEG_TOUCH) return 1;
    int ea = acd2_same(a, m) || acd2_same(a, v), eb = acd2_same(b, m) || acd2_same(b, v);
    if (ea && eb) return 0; /* a copy of the diagonal itself (cannot happen for a valid input) */
    if (!ea && !eb) return 1; /* an edge end inside the diagonal, or m / v inside the edge */
    /* one end of the edge is m or v: blocked when the other end, m or v lies inside the other
     * segment (touch away from the shared end point) */
    acd_vec2 o = ea ? b : a, s = ea ? a : b;
    const double O[2] = {o.x, o.y};
    if (acd_point_on_segment(O, M, V)) return 1;
    acd_vec2 far_end = acd2_same(s, m) ? v : m;
    const double F[2] = {far_end.x, far_end.y};
    return acd_point_on_segment(F, A, B);
}

/* Is the diagonal from vertex m of ring rm to vertex v of ring rv valid: it leaves both into the
 * interior (exact wedge tests) and meets no ring except at its two ends? */
static int diagonal_ok(const acd2_ring *rings, size_t nr, size_t rm, size_t m, size_t rv, size_t v) {
    const acd2_ring *a = &rings[rm], *b = &rings[rv];
    acd_vec2 M = a->p[m], V = b->p[v];
    if (acd2_same(M, V)) return 0;
    if (!acd2_in_wedge(a->p[acd2_prev(m, a->n)], M, a->p[acd2_next(m, a->n)], V)) return 0;
    if (!acd2_in_wedge(b->p[acd2_prev(v, b->n)], V, b->p[acd2_next(v, b->n)], M)) return 0;
    for (size_t g = 0; g < nr; g++)
        for (size_t k = 0; k < rings[g].n; k++)
            if (edge_blocks(M, V, rings[g].p[k], rings[g].p[acd2_next(k, rings[g].n)])) return 0;
    return 1;
}

typedef struct bridge_cand {
    double tan, d2;
    size_t g, k;
} bridge_cand;

static int bridge_cand_cmp(const void *x, const void *y) {
    const bridge_cand *a = x, *b = y;
    if (a->tan != b->tan) return a->tan < b->tan ? -1 : 1;
    if (a->d2 != b->d2) return a->d2 < b->d2 ? -1 : 1;
    if (a->g != b->g) return a->g < b->g ? -1 : 1;
    return (a->k > b->k) - (a->k < b->k);
}

/* The fallback connection (classic hole bridging, D. Eberly, "Triangulation by ear clipping";
 * the same idea as geom2/triangulate.c step 2, on these rings): the alive hole with the rightmost
 * vertex M (largest x, ties: largest y) sees, along the ray to the right of M, the nearest
 * crossed edge facing it, of the outer ring (merged holes included) or of another alive hole;
 * that edge's end P of larger x, or the vertex inside the triangle (M, I, P) with the smallest
 * angle to the ray, is visible from M. Every candidate is checked exactly (diagonal_ok) in that
 * order; when none passes (rounding of I), the exact ray shot from M to the right ends on the
 * first boundary point met (a vertex or a new point on an edge). Sets *gsel (ring index) and t;
 * returns 0, -1 when nothing is found (cannot happen for valid rings), -2 when out of memory. */
static int bridge_target(const acd2_holes *hs, const acd2_ring *rings, size_t nr, size_t *gsel, target *t) {
    size_t gm = 0, m = 0;
    for (size_t g = 1; g < nr; g++)
        for (size_t k = 0; k < rings[g].n; k++) {
            acd_vec2 q = rings[g].p[k];
            if (gm == 0 || q.x > rings[gm].p[m].x || (q.x == rings[gm].p[m].x && q.y > rings[gm].p[m].y)) {
                gm = g;
                m = k;
            }
        }
    if (gm == 0) return -1;
    acd_vec2 M = rings[gm].p[m];
    /* 1. the nearest upward edge (interior on its left, i.e. facing M) crossing the ray */
    double bx = INFINITY;
    size_t eg = 0, ek = 0;
    int found = 0;
    for (size_t g = 0; g < nr; g++) {
        if (g == gm) continue;
        for (size_t k = 0; k < rings[g].n; k++) {
            acd_vec2 a = rings[g].p[k], b = rings[g].p[acd2_next(k, rings[g].n)];
            if (!(a.y <= M.y && M.y <= b.y && a.y < b.y)) continue;
            if (acd2_orient_sign(a, b, M) <= 0) continue;
            double x = a.x + (M.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if (x < M.x) x = M.x;
            if (!found || x < bx) { bx = x; eg = g; ek = k; found = 1; }
        }
    }
    size_t ncand = 0;
    bridge_cand *cs = NULL;
    if (found) {
        size_t total = 0;
        for (size_t g = 0; g < nr; g++) total += rings[g].n;
        cs = malloc((total + 1) * sizeof *cs);
        if (!cs) return -2;
        size_t k2 = acd2_next(ek, rings[eg].n);
        size_t pk = rings[eg].p[ek].x >= rings[eg].p[k2].x ? ek : k2;
        acd_vec2 Pp = rings[eg].p[pk], I = {bx, M.y};
        cs[ncand++] = (bridge_cand){-1, 0, eg, pk};
        int tri = acd2_orient_sign(M, I, Pp);
        for (size_t g = 0; tri != 0 && g < nr; g++) {
            if (g == gm) continue;
            for (size_t k = 0; k < rings[g].n; k++) {
                acd_vec2 x = rings[g].p[k];
                if (x.x < M.x || acd2_same(x, Pp)) continue;
                int o1 = acd2_orient_sign(M, I, x), o2 = acd2_orient_sign(I, Pp, x), o3 = acd2_orient_sign(Pp, M, x);
                if (o1 * tri < 0 || o2 * tri < 0 || o3 * tri < 0) continue;
                double dx = x.x - M.x, dy = x.y - M.y;
                cs[ncand++] = (bridge_cand){dx > 0 ? fabs(dy) / dx : INFINITY, dx * dx + dy * dy, g, k};
            }
        }
        qsort(cs, ncand, sizeof *cs, bridge_cand_cmp);
    }
    t->ok = 0;
    for (size_t i = 0; i < ncand && !t->ok; i++) {
        const acd2_ring *rg = &rings[cs[i].g];
        acd_vec2 V = rg->p[cs[i].k];
        /* the copy of V (an earlier slit duplicates points) that the diagonal enters */
        for (size_t g = 0; g < nr && !t->ok; g++)
            for (size_t k = 0; k < rings[g].n && !t->ok; k++)
                if (g != gm && acd2_same(rings[g].p[k], V) && diagonal_ok(rings, nr, gm, m, g, k)) {
                    t->ok = 1;
                    t->hit = (acd2_hit){g, 1, k, V};
                }
    }
    free(cs);
    if (!t->ok) {
        acd_vec2 aim = {M.x + hs->far, M.y};
        if (acd2_shoot_multi(rings, nr, gm, m, aim, &t->hit) || t->hit.ring == gm) return -1;
        t->ok = 1;
    }
    const acd2_ring *hg = &rings[t->hit.ring];
    t->owner = t->hit.ring;
    t->e = m;
    t->from = M;
    t->dist = hypot(t->hit.z.x - M.x, t->hit.z.y - M.y);
    t->aim_dist = t->dist;
    t->ida = hg->id[t->hit.j];
    t->idb = t->hit.is_vertex ? -1 : hg->id[acd2_next(t->hit.j, hg->n)];
    *gsel = gm;
    return 0;
}

acd_status acd2_holes_step(acd2_holes *hs, acd_vec2 seg[2], int *into_outer, double *value, acd_error *err) {
    size_t nr = 1 + hs->alive;
    acd2_ring *rings = malloc(nr * sizeof *rings);
    size_t *which = malloc(nr * sizeof *which);
    size_t *slot = malloc((hs->nh ? hs->nh : 1) * sizeof *slot);
    if (!rings || !which || !slot) {
        free(rings); free(which); free(slot);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory while merging holes");
    }
    rings[0] = hs->outer;
    size_t k = 1;
    for (size_t i = 0; i < hs->nh; i++)
        if (hs->h[i].alive) { rings[k] = hs->h[i].ring; which[k] = i; slot[i] = k; k++; }
    /* (re)compute the targets that are not cached; owners are kept as hole indices + 1 */
    for (size_t g = 1; g < nr; g++) {
        acd2_hole *h = &hs->h[which[g]];
        for (int x = 0; x < 2; x++) {
            if (h->cached[x]) continue;
            find_target(hs, rings, nr, g, h->ext[x], &h->t[x]);
            if (h->t[x].ok) h->t[x].owner = h->t[x].owner == 0 ? 0 : which[h->t[x].owner] + 1;
            h->cached[x] = 1;
        }
    }
    int best_ready = -1, best_other = -1, pick_ready = 0, pick_other = 0;
    double best_val = -INFINITY, best_dist = INFINITY;
    for (size_t g = 1; g < nr; g++) {
        const acd2_hole *h = &hs->h[which[g]];
        const target *t = h->t;
        int pick = -1;
        for (int x = 0; x < 2; x++)
            if (t[x].ok && t[x].owner == 0 && (pick < 0 || t[x].dist < t[pick].dist)) pick = x;
        if (pick >= 0) {
            acd_vec2 P = h->ring.p[t[pick].e], Q = h->ring.p[h->ext[1 - pick]];
            double val = anchor_conc(hs, &t[pick]) + t[pick].dist + hypot(P.x - Q.x, P.y - Q.y);
            if (val > best_val) { best_val = val; best_ready = (int)g; pick_ready = pick; }
        } else {
            for (int x = 0; x < 2; x++)
                if (t[x].ok && t[x].owner != which[g] + 1 && t[x].dist < best_dist) {
                    best_dist = t[x].dist;
                    best_other = (int)g;
                    pick_other = x;
                }
        }
    }
    acd_status st = ACD_OK;
    size_t g;
    target t;
    acd_vec2 Q; /* the antipode of the merge vertex (Eqn 4.2's |p - cw(p)|) */
    if ((best_ready < 0 && best_other < 0) || hs->force_bridge) {
        /* no hole has a target by its resolving cones: the bridge that always exists */
        int rc = bridge_target(hs, rings, nr, &g, &t);
        if (rc == -2) {
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory while bridging a hole");
            goto done;
        }
        if (rc) {
            st = acd_fail(err, ACD_ERR_INTERNAL,
                          "no hole could be connected to the outer boundary or another hole (%zu holes left)",
                          hs->alive);
            goto done;
        }
        const acd2_hole *hb = &hs->h[which[g]];
        acd_vec2 M = hb->ring.p[t.e], A = hb->ring.p[hb->ext[0]], B = hb->ring.p[hb->ext[1]];
        Q = hypot(A.x - M.x, A.y - M.y) >= hypot(B.x - M.x, B.y - M.y) ? A : B;
    } else {
        g = (size_t)(best_ready >= 0 ? best_ready : best_other);
        int pick = best_ready >= 0 ? pick_ready : pick_other;
        const acd2_hole *hp = &hs->h[which[g]];
        /* fresh target (ring positions for the splice); the geometry is that of the cached one */
        find_target(hs, rings, nr, g, hp->ext[pick], &t);
        if (!t.ok || t.owner == g) {
            st = acd_fail(err, ACD_ERR_INTERNAL, "hole %zu: its connection vanished", which[g]);
            goto done;
        }
        Q = hp->ring.p[hp->ext[1 - pick]];
    }
    size_t hidx = which[g];
    acd2_hole *h = &hs->h[hidx];
    acd_vec2 P = h->ring.p[t.e];
    seg[0] = P;
    seg[1] = t.hit.z;
    int64_t nid = hs->next_id;
    if (nid >= hs->idcap) {
        st = acd_fail(err, ACD_ERR_INTERNAL, "too many new points while merging holes");
        goto done;
    }
    size_t into = 0; /* 0 = outer, else hole index + 1 */
    if (t.owner == 0) {
        double val = anchor_conc(hs, &t) + t.dist + hypot(P.x - Q.x, P.y - Q.y);
        hs->idconc[nid] = anchor_conc(hs, &t);
        if (splice(&hs->outer, &h->ring, t.e, &t.hit, nid, hs->weld)) {
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory while merging a hole");
            goto done;
        }
        for (size_t q = 0; q < h->ring.n; q++)
            if (h->ring.id[q] >= 0 && h->ring.id[q] < hs->idcap) hs->idconc[h->ring.id[q]] = val;
        *into_outer = 1;
        *value = val;
    } else {
        into = which[t.owner] + 1;
        acd2_hole *J = &hs->h[into - 1];
        hs->idconc[nid] = 0;
        if (splice(&J->ring, &h->ring, t.e, &t.hit, nid, hs->weld)) {
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory while merging two holes");
            goto done;
        }
        acd2_pa_extremes(J->ring.p, J->ring.n, &J->ext[0], &J->ext[1]);
        J->cached[0] = J->cached[1] = 0;
        *into_outer = 0;
        *value = 0;
    }
    if (!t.hit.is_vertex) hs->next_id++;
    acd2_ring_free(&h->ring);
    h->alive = 0;
    hs->alive--;
    /* update the other holes' cached targets: owners and the new slit */
    for (size_t i = 0; i < hs->nh; i++) {
        acd2_hole *J = &hs->h[i];
        if (!J->alive) continue;
        for (int x = 0; x < 2; x++) {
            if (!J->cached[x]) continue;
            target *tt = &J->t[x];
            if (tt->ok && tt->owner == hidx + 1) tt->owner = into;
            if (slit_affects(&J->ring, J->ext[x], tt, seg[0], seg[1])) J->cached[x] = 0;
        }
    }
done:
    free(rings);
    free(which);
    free(slot);
    return st;
}
