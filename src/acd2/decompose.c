/* acd2/decompose: Approx_CD of a polygon with holes (Lien dissertation Ch. III Alg. 1, Fig. 9;
 * Ch. IV; spec acd2d.md §5.6 with the ★ decisions of §11).
 *
 * design:
 *  1. check and orient the input (outer counterclockwise, holes clockwise); scale, R, tau;
 *  2. measure the outer ring; merge every hole (holes.c), one unary tree node per merge;
 *  3. work stack (explicit, no recursion) of rings; pop a ring, give it the next node id
 *     (preorder), then:
 *     a. if an id repeats (the ring touches itself: a hole-merging slit not yet cut open, or
 *        two loops touching at a point): for a clockwise loop (an enclosed hole), the witness
 *        is the notch of the loop farthest from the pinch (IV.A.2: after a merge a hole point
 *        y has concavity concavity(x) + |x y|, above every outer notch by Eqn 4.2's delta), and
 *        the ring is cut there; two counterclockwise loops are split at the pinch point;
 *     b. otherwise measure; if no notch has concavity > tau (+ a scale-relative epsilon), the
 *        ring is a component (leaf);
 *     c. otherwise cut at the witness (cut.c) and push both pieces.
 *  So a hole merge is always followed by cuts that open its slit: every component is a simple
 *  counterclockwise polygon. Every cut resolves its notch and creates none (Steiner ends have
 *  two angles < 180 degrees), so the number of cuts is bounded; a hard bound guards it anyway.
 *  The progress callback is called between steps with the fraction of the area finished. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "acd/acd2d.h"
#include "acd2/cut.h"
#include "acd2/holes.h"
#include "acd2/pocket.h"
#include "acd2/resolution.h"
#include "acd2/ring.h"
#include "acd2/tree.h"
#include "core/error.h"
#include "core/tolerance.h"
#include "geom2/hull2d.h"

acd2d_params acd2d_default_params(void) {
    acd2d_params p;
    memset(&p, 0, sizeof p);
    p.cookie = ACD2D_PARAMS_COOKIE;
    p.tau = 0;
    p.measure = ACD2D_MEASURE_SL;
    p.sc = 0.1;
    p.sd = 1.0;
    p.cut = ACD2D_CUT_RAY;
    p.normalize = 0;
    p.notch_tolerance = 1e-5;
    return p;
}

static const char *const measure_names[] = {"sl", "sp", "h1", "h2"};

const char *acd2d_measure_name(acd2d_measure m) {
    if ((int)m < 0 || (int)m > 3) return "?";
    return measure_names[m];
}

int acd2d_measure_parse(const char *name, acd2d_measure *out) {
    for (int i = 0; i < 4; i++) {
        const char *a = name, *b = measure_names[i];
        while (*a && *b && (*a | 32) == *b) { a++; b++; }
        if (!*a && !*b) {
            *out = (acd2d_measure)i;
            return 1;
        }
    }
    return 0;
}

typedef struct item {
    acd2_ring ring;
    int node;    /* pre-assigned node, or -1 */
    int parent;
    int which;
} item;

typedef struct ctx {
    const acd2d_params *prm;
    acd2_measure_opts mo;
    acd2_cut_opts co;
    double eps_c;
    acd2_work work;
    double *conc;
    int64_t *be;
    size_t conc_cap;
    unsigned char *mark;
    int64_t mark_cap;
    int64_t next_id;
    item *stack;
    size_t nstack, stack_cap;
    acd2d_node *nodes;
    size_t nnodes, nodes_cap;
    acd2d_component *comps;
    size_t ncomps, comps_cap;
    double total_area, done_area;
    size_t ncuts, max_cuts;
    int far; /* far from the origin: new points may round off their edges by more than the weld
                distance; they are then shared with the edge's other side, and every tree node's
                polygon is stored (and gets the shared points) instead of rebuilt */
} ctx;

#define GROW(ptr, n, cap)                                                        \
    ((n) < (cap) ? 0                                                             \
                 : ((cap) = (cap) ? 2 * (cap) : 16,                              \
                    (ptr = realloc_or_free(ptr, (cap) * sizeof *(ptr))) ? 0 : -1))

static void *realloc_or_free(void *p, size_t sz) {
    void *q = realloc(p, sz);
    if (!q) free(p);
    return q;
}

static int ring_to_polygon(const acd2_ring *r, acd_polygon *out) {
    const acd_vec2 *rings[1] = {r->p};
    size_t sizes[1] = {r->n};
    return acd_polygon_from_rings(out, rings, sizes, 1, NULL) == ACD_OK ? 0 : -1;
}

static int new_node(ctx *c, int parent) {
    if (c->nnodes >= c->nodes_cap) {
        size_t nc = c->nodes_cap ? 2 * c->nodes_cap : 64;
        acd2d_node *nn = realloc(c->nodes, nc * sizeof *nn);
        if (!nn) return -1;
        c->nodes = nn;
        c->nodes_cap = nc;
    }
    acd2d_node *nd = &c->nodes[c->nnodes];
    memset(nd, 0, sizeof *nd);
    nd->parent = parent;
    nd->child[0] = nd->child[1] = -1;
    return (int)c->nnodes++;
}

static int push(ctx *c, acd2_ring *ring, int node, int parent, int which) {
    if (c->nstack >= c->stack_cap) {
        size_t nc = c->stack_cap ? 2 * c->stack_cap : 64;
        item *ns = realloc(c->stack, nc * sizeof *ns);
        if (!ns) return -1;
        c->stack = ns;
        c->stack_cap = nc;
    }
    item *it = &c->stack[c->nstack++];
    it->ring = *ring;
    memset(ring, 0, sizeof *ring);
    it->node = node;
    it->parent = parent;
    it->which = which;
    return 0;
}

static int ensure_buffers(ctx *c, size_t n) {
    if (n > c->conc_cap) {
        size_t nc = c->conc_cap ? c->conc_cap : 64;
        while (nc < n) nc *= 2;
        double *q = realloc(c->conc, nc * sizeof *q);
        if (!q) return -1;
        c->conc = q;
        int64_t *b = realloc(c->be, nc * sizeof *b);
        if (!b) return -1;
        c->be = b;
        c->conc_cap = nc;
    }
    if (c->next_id + 4 > c->mark_cap) {
        int64_t nc = c->mark_cap ? c->mark_cap : 64;
        while (nc < c->next_id + 4) nc *= 2;
        unsigned char *m = realloc(c->mark, (size_t)nc);
        if (!m) return -1;
        memset(m + c->mark_cap, 0, (size_t)(nc - c->mark_cap));
        c->mark = m;
        c->mark_cap = nc;
    }
    return 0;
}

/* Shares a new point z, just put into the edge U -> V of a ring by a cut, with the ring that has
 * the same edge the other way round (V -> U: the other side of an earlier cut, a finished
 * component or a ring still to process, or the other side of a hole-merging slit in one of the
 * pieces a, b). z is rounded off the line U V; far from the origin by more than the cut pieces'
 * tolerances, so without it the neighbour would overlap the pieces or leave a gap (a
 * T-junction). Returns 1 when shared, 0 when no ring has the edge, -1 when out of memory. */
static int share_point(ctx *c, acd2_ring *a, acd2_ring *b, acd_vec2 U, acd_vec2 V, acd_vec2 z, int64_t zid) {
    int rc = acd2_ring_insert_on_edge(a, V, U, z, zid);
    if (rc == 0) rc = acd2_ring_insert_on_edge(b, V, U, z, zid);
    for (size_t i = c->nstack; rc == 0 && i > 0; i--) rc = acd2_ring_insert_on_edge(&c->stack[i - 1].ring, V, U, z, zid);
    if (rc != 0) return rc;
    for (size_t i = c->ncomps; i > 0; i--) {
        acd2d_component *cp = &c->comps[i - 1];
        size_t n = cp->npoints, k = 0;
        for (; k < n; k++)
            if (acd2_same(cp->points[k], V) && acd2_same(cp->points[acd2_next(k, n)], U)) break;
        if (k == n) continue;
        acd_vec2 *np = malloc((n + 1) * sizeof *np), *hull = malloc((n + 2) * sizeof *hull);
        size_t *idx = malloc((n + 2) * sizeof *idx), *scr = malloc((n + 2) * sizeof *scr);
        if (!np || !hull || !idx || !scr) {
            free(np); free(hull); free(idx); free(scr);
            return -1;
        }
        memcpy(np, cp->points, (k + 1) * sizeof *np);
        np[k + 1] = z;
        memcpy(np + k + 2, cp->points + k + 1, (n - k - 1) * sizeof *np);
        size_t nh = acd_hull2d_indices(np, n + 1, idx, scr);
        for (size_t h = 0; h < nh; h++) hull[h] = np[idx[h]];
        free(cp->points);
        free(cp->hull);
        free(idx);
        free(scr);
        cp->points = np;
        cp->npoints = n + 1;
        cp->hull = hull;
        cp->nhull = nh;
        return 1;
    }
    return 0;
}

/* Puts z into every stored tree-node polygon with the edge U -> V or V -> U (far from the origin
 * every node's polygon is stored), so that the hierarchy readouts tile as the components do.
 * 0, or -1 when out of memory. */
static int share_in_nodes(ctx *c, acd_vec2 U, acd_vec2 V, acd_vec2 z) {
    for (size_t i = 0; i < c->nnodes; i++) {
        acd_polygon *pg = &c->nodes[i].polygon;
        for (size_t r = 0; r < pg->nrings; r++) {
            size_t s = pg->ring_start[r], e = pg->ring_start[r + 1], k = s;
            for (; k < e; k++) {
                acd_vec2 a = pg->points[k], b = pg->points[k + 1 == e ? s : k + 1];
                if ((acd2_same(a, U) && acd2_same(b, V)) || (acd2_same(a, V) && acd2_same(b, U))) break;
            }
            if (k == e) continue;
            size_t np = pg->ring_start[pg->nrings];
            acd_vec2 *q = realloc(pg->points, (np + 1) * sizeof *q);
            if (!q) return -1;
            pg->points = q;
            memmove(q + k + 2, q + k + 1, (np - k - 1) * sizeof *q);
            q[k + 1] = z;
            for (size_t t = r + 1; t <= pg->nrings; t++) pg->ring_start[t]++;
            r = pg->nrings; /* one edge per node polygon: U V is one segment of one ring */
        }
    }
    return 0;
}

static acd_status add_component(ctx *c, const acd2_ring *r, double conc, int node, acd_error *err) {
    if (GROW(c->comps, c->ncomps, c->comps_cap)) return acd_fail(err, ACD_ERR_NOMEM, "out of memory (components)");
    acd2d_component *cp = &c->comps[c->ncomps];
    memset(cp, 0, sizeof *cp);
    cp->points = malloc(r->n * sizeof *cp->points);
    cp->hull = malloc((r->n + 1) * sizeof *cp->hull);
    size_t *idx = malloc((r->n + 1) * sizeof *idx), *scr = malloc((r->n + 1) * sizeof *scr);
    if (!cp->points || !cp->hull || !idx || !scr) {
        free(cp->points); free(cp->hull); free(idx); free(scr);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory (component of %zu points)", r->n);
    }
    memcpy(cp->points, r->p, r->n * sizeof *cp->points);
    cp->npoints = r->n;
    size_t nh = acd_hull2d_indices(r->p, r->n, idx, scr);
    for (size_t i = 0; i < nh; i++) cp->hull[i] = r->p[idx[i]];
    cp->nhull = nh;
    cp->concavity = conc;
    cp->node = node;
    free(idx);
    free(scr);
    c->ncomps++;
    c->done_area += 0.5 * acd2_ring_area2(r->p, r->n);
    return ACD_OK;
}

static void free_ctx(ctx *c) {
    acd2_work_free(&c->work);
    free(c->conc);
    free(c->be);
    free(c->mark);
    for (size_t i = 0; i < c->nstack; i++) acd2_ring_free(&c->stack[i].ring);
    free(c->stack);
}

/* witness for a ring whose id repeats at positions i < j; returns 0 (witness set), 1 (split
 * at the pinch instead: *split = 1), -1 (no notch found) */
static int pinch_witness(const acd2_ring *r, size_t i, size_t j, double tol, size_t *w, double *far, int *split) {
    size_t n = r->n;
    double a1 = acd2_ring_area2(r->p + i, j - i);
    /* loop 2: j .. i-1 cyclic; its area is the total minus loop 1 */
    double a2 = acd2_ring_area2(r->p, n) - a1;
    size_t from, cnt;
    if (a1 < 0 && a1 <= a2) { from = i; cnt = j - i; }
    else if (a2 < 0) { from = j; cnt = n - (j - i); }
    else { *split = 1; return 1; }
    *split = 0;
    acd_vec2 X = r->p[i];
    for (int pass = 0; pass < 2; pass++) {
        size_t best = SIZE_MAX;
        double bd = -1;
        for (size_t q = 1, k = acd2_next(from, n); q < cnt; q++, k = acd2_next(k, n)) {
            if (!acd2_is_notch(r->p[acd2_prev(k, n)], r->p[k], r->p[acd2_next(k, n)], pass == 0 ? tol : 0)) continue;
            double d = hypot(r->p[k].x - X.x, r->p[k].y - X.y);
            if (d > bd || (d == bd && r->id[k] < r->id[best])) { bd = d; best = k; }
        }
        if (best != SIZE_MAX) {
            *w = best;
            *far = bd;
            return 0;
        }
    }
    return -1;
}

static acd_status check_input(const acd_polygon *poly, acd_error *err) {
    if (!poly || poly->nrings == 0) return acd_fail(err, ACD_ERR_DEGENERATE, "acd2d: empty polygon");
    for (size_t r = 0; r < poly->nrings; r++) {
        size_t n = acd_polygon_ring_size(poly, r);
        if (n < 3) return acd_fail(err, ACD_ERR_DEGENERATE, "acd2d: chain %zu has %zu vertices (< 3)", r, n);
        const acd_vec2 *p = acd_polygon_ring(poly, r);
        for (size_t i = 0; i < n; i++)
            if (!isfinite(p[i].x) || !isfinite(p[i].y))
                return acd_fail(err, ACD_ERR_INVALID_INPUT, "acd2d: chain %zu vertex %zu is not finite", r, i);
        double a = acd2_ring_area2(p, n);
        if (!(a != 0)) return acd_fail(err, ACD_ERR_DEGENERATE, "acd2d: chain %zu has zero area", r);
    }
    return ACD_OK;
}

static double now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

acd_status acd2d_decompose(const acd_polygon *poly, const acd2d_params *prm, acd2d_result *out, acd_error *err) {
    if (!out) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd2d_decompose: out is NULL");
    memset(out, 0, sizeof *out);
    if (!prm || prm->cookie != ACD2D_PARAMS_COOKIE)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd2d_decompose: params not initialized by acd2d_default_params");
    if (!(prm->tau >= 0) || !isfinite(prm->tau))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd2d_decompose: tau must be finite and >= 0 (got %g)", prm->tau);
    if (!(prm->sc >= 0) || !isfinite(prm->sc) || !(prm->sd > 0) || !isfinite(prm->sd))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd2d_decompose: need sc >= 0 and sd > 0 (got %g, %g)", prm->sc,
                        prm->sd);
    if (!(prm->notch_tolerance >= 0) || !isfinite(prm->notch_tolerance))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd2d_decompose: notch tolerance must be >= 0");
    if ((int)prm->measure < 0 || (int)prm->measure > 3 || ((int)prm->cut != 0 && (int)prm->cut != 1))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd2d_decompose: unknown measure or cut mode");
    acd_status st = check_input(poly, err);
    if (st == ACD_OK) st = acd2_check_resolution(poly, err);
    if (st != ACD_OK) return st;
    double t0 = now_seconds();

    /* oriented copy: outer counterclockwise, holes clockwise */
    acd_polygon P;
    if (acd_polygon_copy(&P, poly) != ACD_OK) return acd_fail(err, ACD_ERR_NOMEM, "out of memory copying the input");
    for (size_t r = 0; r < P.nrings; r++) {
        acd_vec2 *p = P.points + P.ring_start[r];
        size_t n = acd_polygon_ring_size(&P, r);
        double a = acd2_ring_area2(p, n);
        if ((r == 0) != (a > 0))
            for (size_t i = 0; i < n / 2; i++) {
                acd_vec2 t = p[i];
                p[i] = p[n - 1 - i];
                p[n - 1 - i] = t;
            }
    }
    size_t np = acd_polygon_num_points(&P);
    acd_scale sc = acd_scale_of_points(&P.points[0].x, np, 2);
    double R = 0, mx = 0, my = 0;
    size_t n0 = acd_polygon_ring_size(&P, 0);
    for (size_t i = 0; i < n0; i++) { mx += P.points[i].x; my += P.points[i].y; }
    mx /= (double)n0;
    my /= (double)n0;
    for (size_t i = 0; i < n0; i++) {
        double d = hypot(P.points[i].x - mx, P.points[i].y - my);
        if (d > R) R = d;
    }

    ctx c;
    memset(&c, 0, sizeof c);
    c.prm = prm;
    c.mo.measure = prm->measure;
    c.mo.tau = prm->normalize ? prm->tau * R : prm->tau;
    c.mo.notch_tol = prm->notch_tolerance;
    c.co.sc = prm->sc;
    c.co.sd = prm->sd;
    c.co.mode = prm->cut;
    c.co.far = 4 * sc.extent + 1;
    c.co.weld = sc.weld;
    {
        double m = 0;
        for (size_t i = 0; i < np; i++) m = fmax(m, fmax(fabs(P.points[i].x), fabs(P.points[i].y)));
        c.far = DBL_EPSILON * m > sc.weld;
        /* a concavity below the rounding of the coordinates (a shared point's kink) is none */
        c.eps_c = fmax(sc.dist, ACD2_ROUND_ULPS * DBL_EPSILON * m);
    }
    c.next_id = (int64_t)np;
    c.total_area = acd_polygon_area(&P);
    size_t notches = 0;
    for (size_t r = 0; r < P.nrings; r++) {
        const acd_vec2 *p = acd_polygon_ring(&P, r);
        size_t n = acd_polygon_ring_size(&P, r);
        for (size_t i = 0; i < n; i++)
            if (acd2_is_notch(p[acd2_prev(i, n)], p[i], p[acd2_next(i, n)], prm->notch_tolerance)) notches++;
    }
    c.max_cuts = 4 * (np + notches) + 64;
    out->tau = c.mo.tau;
    out->measure = prm->measure;
    out->input_vertices = np;
    out->input_notches = notches;
    out->input_holes = P.nrings - 1;

    acd2_holes hs;
    memset(&hs, 0, sizeof hs);
    acd2_cuts_list cl = {0};
    acd2_ring start = {0};
    int start_node;
    if (ensure_buffers(&c, np + 8)) { st = acd_fail(err, ACD_ERR_NOMEM, "out of memory"); goto fail; }
    {
        /* root */
        int root = new_node(&c, -1);
        if (root < 0 || acd_polygon_copy(&c.nodes[root].polygon, &P) != ACD_OK) {
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
            goto fail;
        }
        start_node = root;
        if (P.nrings > 1) {
            const acd_vec2 *op = acd_polygon_ring(&P, 0);
            int64_t *ids = malloc(n0 * sizeof *ids);
            if (!ids) { st = acd_fail(err, ACD_ERR_NOMEM, "out of memory"); goto fail; }
            for (size_t i = 0; i < n0; i++) ids[i] = (int64_t)i;
            size_t w;
            double delta;
            st = acd2_measure_ring(op, ids, n0, &c.mo, &c.work, c.conc, &w, &delta, NULL, NULL, NULL);
            free(ids);
            if (st != ACD_OK) { st = acd_fail(err, st, "acd2d: measuring the outer boundary failed (%s)", acd_status_string(st)); goto fail; }
            st = acd2_holes_init(&hs, &P, c.conc, c.co.far, err);
            if (st != ACD_OK) goto fail;
            hs.weld = c.far ? c.co.weld : INFINITY; /* near the origin: never shared */
            int cur = root;
            while (hs.alive > 0) {
                if (prm->progress && prm->progress(prm->progress_user, 0.0, "merging holes")) {
                    st = acd_fail(err, ACD_ERR_CANCELLED, "acd2d: cancelled");
                    goto fail;
                }
                acd_vec2 seg[2];
                int into_outer;
                double val;
                st = acd2_holes_step(&hs, seg, &into_outer, &val, err);
                if (st != ACD_OK) goto fail;
                acd2d_node *nd = &c.nodes[cur];
                nd->cut[0] = seg[0];
                nd->cut[1] = seg[1];
                nd->is_hole_merge = 1;
                nd->concavity = delta + val;
                nd->acceptable = 0;
                if (acd2_cuts_push(&cl, seg[0], seg[1])) { st = acd_fail(err, ACD_ERR_NOMEM, "out of memory"); goto fail; }
                int nx = new_node(&c, cur);
                if (nx < 0) { st = acd_fail(err, ACD_ERR_NOMEM, "out of memory"); goto fail; }
                c.nodes[cur].child[0] = nx;
                /* snapshot: outer + remaining holes */
                size_t nr = 1 + hs.alive, k = 0;
                const acd_vec2 **rr = malloc(nr * sizeof *rr);
                size_t *rs = malloc(nr * sizeof *rs);
                if (!rr || !rs) { free(rr); free(rs); st = acd_fail(err, ACD_ERR_NOMEM, "out of memory"); goto fail; }
                rr[k] = hs.outer.p; rs[k++] = hs.outer.n;
                for (size_t q = 0; q < hs.nh; q++)
                    if (hs.h[q].alive) { rr[k] = hs.h[q].ring.p; rs[k++] = hs.h[q].ring.n; }
                st = acd_polygon_from_rings(&c.nodes[nx].polygon, rr, rs, nr, err);
                free(rr);
                free(rs);
                if (st != ACD_OK) goto fail;
                cur = nx;
            }
            start = hs.outer;
            memset(&hs.outer, 0, sizeof hs.outer);
            c.next_id = hs.next_id;
            acd2_holes_free(&hs);
            start_node = cur;
        } else {
            if (acd2_ring_reserve(&start, n0)) { st = acd_fail(err, ACD_ERR_NOMEM, "out of memory"); goto fail; }
            for (size_t i = 0; i < n0; i++) {
                start.p[i] = P.points[i];
                start.id[i] = (int64_t)i;
                start.c[i] = 0;
                start.be[i] = -1;
            }
            start.n = n0;
        }
    }
    if (push(&c, &start, start_node, -1, 0)) { st = acd_fail(err, ACD_ERR_NOMEM, "out of memory"); goto fail; }

    while (c.nstack > 0) {
        item it = c.stack[--c.nstack];
        if (prm->progress &&
            prm->progress(prm->progress_user, c.total_area > 0 ? c.done_area / c.total_area : -1.0, "decomposing")) {
            acd2_ring_free(&it.ring);
            st = acd_fail(err, ACD_ERR_CANCELLED, "acd2d: cancelled");
            goto fail;
        }
        int node = it.node;
        if (node < 0) {
            node = new_node(&c, it.parent);
            if (node < 0) { acd2_ring_free(&it.ring); st = acd_fail(err, ACD_ERR_NOMEM, "out of memory"); goto fail; }
            c.nodes[it.parent].child[it.which] = node;
        }
        acd2_ring *r = &it.ring;
        /* a node's polygon is stored only when it cannot be rebuilt from its children (root,
         * hole merges, components, pinch splits, pieces changed by cleaning); see tree.c */
        if (ensure_buffers(&c, r->n + 8)) { acd2_ring_free(r); st = acd_fail(err, ACD_ERR_NOMEM, "out of memory"); goto fail; }
        size_t wit;
        double val;
        size_t pi, pj;
        int pinched = acd2_ring_find_repeat(r, &pi, &pj, c.mark, c.mark_cap);
        /* the cache is valid for rings with unique ids; be[] is rewritten in place after reading */
        st = acd2_measure_ring(r->p, r->id, r->n, &c.mo, &c.work, c.conc, &wit, &val, pinched ? NULL : r->be, r->c,
                               c.be);
        if (st != ACD_OK) {
            acd2_ring_free(r);
            st = acd_fail(err, st, "acd2d: measuring a component of %zu vertices failed (%s)", r->n, acd_status_string(st));
            goto fail;
        }
        memcpy(r->c, c.conc, r->n * sizeof *r->c);
        if (pinched)
            for (size_t k = 0; k < r->n; k++) r->be[k] = -1;
        else
            memcpy(r->be, c.be, r->n * sizeof *r->be);
        acd2d_node *nd = &c.nodes[node];
        nd->concavity = val;
        nd->acceptable = !pinched;
        if (pinched) {
            int split = 0;
            double farv = 0;
            int rc = pinch_witness(r, pi, pj, prm->notch_tolerance, &wit, &farv, &split);
            if (rc < 0) {
                st = acd_fail(err, ACD_ERR_INTERNAL,
                              "acd2d: a component of %zu vertices touches itself at (%.17g, %.17g) but has no notch to cut",
                              r->n, r->p[pi].x, r->p[pi].y);
                acd2_ring_free(r);
                goto fail;
            }
            if (split) {
                acd2_ring a = {0}, b = {0};
                if (acd2_ring_append_range(&a, r, pi, pj - pi) || acd2_ring_append_range(&b, r, pj, r->n - (pj - pi))) {
                    acd2_ring_free(&a); acd2_ring_free(&b); acd2_ring_free(r);
                    st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
                    goto fail;
                }
                acd2_ring_clean(&a);
                acd2_ring_clean(&b);
                nd->cut[0] = nd->cut[1] = r->p[pi];
                if (nd->polygon.nrings == 0 && ring_to_polygon(r, &nd->polygon)) {
                    acd2_ring_free(&a); acd2_ring_free(&b); acd2_ring_free(r);
                    st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
                    goto fail;
                }
                acd2_ring_free(r);
                if (push(&c, &b, -1, node, 1) || push(&c, &a, -1, node, 0)) {
                    acd2_ring_free(&a); acd2_ring_free(&b);
                    st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
                    goto fail;
                }
                continue;
            }
            nd->concavity = val + farv;
        } else if (wit == SIZE_MAX || val <= c.mo.tau + c.eps_c) {
            if (nd->polygon.nrings == 0 && ring_to_polygon(r, &nd->polygon)) {
                acd2_ring_free(r);
                st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
                goto fail;
            }
            st = add_component(&c, r, val, node, err);
            acd2_ring_free(r);
            if (st != ACD_OK) goto fail;
            continue;
        }
        if (++c.ncuts > c.max_cuts) {
            acd2_ring_free(r);
            st = acd_fail(err, ACD_ERR_INTERNAL, "acd2d: more than %zu cuts; stopping (no progress)", c.max_cuts);
            goto fail;
        }
        acd2_hit hit;
        int rc = acd2_choose_cut(r, c.conc, wit, &c.co, &hit);
        if (rc) {
            st = acd_fail(err, rc == -2 ? ACD_ERR_NOMEM : ACD_ERR_INTERNAL,
                          "acd2d: no cut found from notch (%.17g, %.17g) of a component of %zu vertices", r->p[wit].x,
                          r->p[wit].y, r->n);
            acd2_ring_free(r);
            goto fail;
        }
        acd2_ring a = {0}, b = {0};
        int64_t nid = c.next_id;
        int shared = 0;
        if (acd2_split(r, wit, &hit, nid, &a, &b)) {
            acd2_ring_free(&a); acd2_ring_free(&b); acd2_ring_free(r);
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
            goto fail;
        }
        if (!hit.is_vertex) {
            c.next_id++;
            acd_vec2 U = r->p[hit.j], V = r->p[acd2_next(hit.j, r->n)];
            /* near the origin z is within the weld distance of U V (as the verifier's tolerance
             * allows) and nothing changes; far from it, the neighbour gets z too */
            if (c.far && acd2_line_offset(U, V, hit.z) > c.co.weld) {
                int sh = share_point(&c, &a, &b, U, V, hit.z, nid);
                if (sh < 0) {
                    acd2_ring_free(&a); acd2_ring_free(&b); acd2_ring_free(r);
                    st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
                    goto fail;
                }
                if (sh > 0) shared = 1;
            }
        }
        if (a.n < 3 || b.n < 3 || !(acd2_ring_area2(a.p, a.n) > 0) || !(acd2_ring_area2(b.p, b.n) > 0)) {
            st = acd_fail(err, ACD_ERR_INTERNAL,
                          "acd2d: the cut from (%.17g, %.17g) to (%.17g, %.17g) gives a degenerate piece", r->p[wit].x,
                          r->p[wit].y, hit.z.x, hit.z.y);
            acd2_ring_free(&a); acd2_ring_free(&b); acd2_ring_free(r);
            goto fail;
        }
        nd->cut[0] = r->p[wit];
        nd->cut[1] = hit.z;
        nd->ring_offset = wit;
        nd->cut_new_point = hit.is_vertex ? 0 : shared ? 2 : 1;
        {
            size_t n = r->n, ea = (hit.j + n - wit) % n + 1 + (size_t)!hit.is_vertex;
            size_t eb = hit.is_vertex ? (wit + n - hit.j) % n + 1 : (wit + n - acd2_next(hit.j, n)) % n + 2;
            if ((c.far || a.n != ea || b.n != eb) && nd->polygon.nrings == 0 && ring_to_polygon(r, &nd->polygon)) {
                acd2_ring_free(&a); acd2_ring_free(&b); acd2_ring_free(r);
                st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
                goto fail;
            }
        }
        if (shared && share_in_nodes(&c, r->p[hit.j], r->p[acd2_next(hit.j, r->n)], hit.z)) {
            acd2_ring_free(&a); acd2_ring_free(&b); acd2_ring_free(r);
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
            goto fail;
        }
        acd_vec2 seg[2] = {r->p[wit], hit.z};
        acd2_ring_free(r);
        if (acd2_cuts_push(&cl, seg[0], seg[1]) || push(&c, &b, -1, node, 1) || push(&c, &a, -1, node, 0)) {
            acd2_ring_free(&a); acd2_ring_free(&b);
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
            goto fail;
        }
    }
    out->components = c.comps;
    out->ncomponents = c.ncomps;
    out->nodes = c.nodes;
    out->nnodes = c.nnodes;
    out->cuts = cl.v;
    out->ncuts = cl.n;
    out->max_concavity = 0;
    for (size_t i = 0; i < c.ncomps; i++)
        if (c.comps[i].concavity > out->max_concavity) out->max_concavity = c.comps[i].concavity;
    free_ctx(&c);
    acd_polygon_free(&P);
    out->seconds = now_seconds() - t0;
    return ACD_OK;
fail:
    acd2_ring_free(&start);
    acd2_holes_free(&hs);
    out->components = c.comps;
    out->ncomponents = c.ncomps;
    out->nodes = c.nodes;
    out->nnodes = c.nnodes;
    out->cuts = cl.v;
    out->ncuts = cl.n;
    acd2d_result_free(out);
    free_ctx(&c);
    acd_polygon_free(&P);
    return st;
}

double acd2d_concavity_params(const acd_vec2 *pts, size_t n, const acd2d_params *params, size_t *witness) {
    if (witness) *witness = SIZE_MAX;
    if (!pts || n < 3 || !params) return 0;
    int64_t *ids = malloc(n * sizeof *ids);
    double *conc = malloc(n * sizeof *conc);
    acd2_work w = {0};
    double val = -1;
    if (ids && conc) {
        for (size_t i = 0; i < n; i++) ids[i] = (int64_t)i;
        acd2_measure_opts o = {params->measure, params->tau, params->notch_tolerance};
        size_t wit;
        if (acd2_measure_ring(pts, ids, n, &o, &w, conc, &wit, &val, NULL, NULL, NULL) != ACD_OK) val = -1;
        else if (witness) *witness = wit;
    }
    acd2_work_free(&w);
    free(ids);
    free(conc);
    return val;
}

double acd2d_concavity(const acd_vec2 *pts, size_t n, acd2d_measure m, double tau, size_t *witness) {
    acd2d_params p = acd2d_default_params();
    p.measure = m;
    p.tau = tau;
    return acd2d_concavity_params(pts, n, &p, witness);
}
