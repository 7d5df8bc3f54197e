/* acd2/concavity_sp: SP-concavity, Lien dissertation IV.A.1.b, Alg. 2, Lemmas A.1-A.4, Fig. 16;
 * in the equivalent tree formulation of spec acd2d.md §3.2 (★, exact):
 *
 * design:
 *  1. pocket polygon Q: the pocket chain reversed (counterclockwise) closed by the bridge;
 *  2. triangulate Q by ear clipping (exact orientation; O(k^2) worst case, spec §3.2 "fine in
 *     practice"); if that fails on a degenerate pocket, the walk along the chain (an upper
 *     bound of SP) is used;
 *  3. shortest-path trees T- and T+ rooted at the bridge ends by the funnel algorithm over the
 *     dual tree of the triangulation (Guibas et al. [53]; Lee and Preparata);
 *  4. h(u) = perpendicular distance to the bridge line when u is perpendicularly visible
 *     (both tree paths outward convex, Lemma A.1, and the perpendicular direction between the
 *     first segments of the two tree paths), 0 at the roots, infinity otherwise;
 *     g(v) = min(h(v), |v parent(v)| + g(parent(v))) over each tree;
 *     concavity_SP(v) = min(g-(v), g+(v)). */
#include "acd2/concavity_sp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd2/ring.h"

void acd2_sp_work_free(acd2_sp_work *w) {
    free(w->q); free(w->tri); free(w->adj); free(w->prev); free(w->next);
    for (int s = 0; s < 2; s++) { free(w->par[s]); free(w->dist[s]); free(w->g[s]); }
    free(w->order); free(w->funnel); free(w->tstack);
    memset(w, 0, sizeof *w);
}

static int reserve(acd2_sp_work *w, size_t n) {
    if (n <= w->cap) return 0;
    size_t nc = w->cap ? w->cap : 64;
    while (nc < n) nc *= 2;
    acd2_sp_work_free(w);
    w->q = malloc(nc * sizeof *w->q);
    w->tri = malloc(3 * nc * sizeof *w->tri);
    w->adj = malloc(3 * nc * sizeof *w->adj);
    w->prev = malloc(nc * sizeof *w->prev);
    w->next = malloc(nc * sizeof *w->next);
    for (int s = 0; s < 2; s++) {
        w->par[s] = malloc(nc * sizeof *w->par[s]);
        w->dist[s] = malloc(nc * sizeof *w->dist[s]);
        w->g[s] = malloc(nc * sizeof *w->g[s]);
    }
    w->order = malloc(3 * nc * sizeof *w->order);
    w->tstack = malloc(3 * nc * sizeof *w->tstack);
    w->funnel = NULL;
    if (!w->q || !w->tri || !w->adj || !w->prev || !w->next || !w->order || !w->tstack || !w->par[0] || !w->par[1] ||
        !w->dist[0] || !w->dist[1] || !w->g[0] || !w->g[1]) {
        acd2_sp_work_free(w);
        return -1;
    }
    w->cap = nc;
    return 0;
}

/* point q inside or on triangle (a, b, c), counterclockwise */
static int in_tri(acd_vec2 a, acd_vec2 b, acd_vec2 c, acd_vec2 q) {
    return acd2_orient_sign(a, b, q) >= 0 && acd2_orient_sign(b, c, q) >= 0 && acd2_orient_sign(c, a, q) >= 0;
}

/* ear clipping of q[0..m) (counterclockwise); writes m-2 triangles; returns 0, -1 (no ear:
 * degenerate) or -2 (out of memory).
 * Only reflex vertices can lie in an ear (a convex vertex never becomes reflex while ears are
 * cut); they are bucketed in a uniform grid over the bounding box, so an ear test looks at the
 * reflex vertices in the cells its bounding box overlaps, then decides exactly. */
static int triangulate(acd2_sp_work *w, size_t m) {
    const acd_vec2 *q = w->q;
    size_t *pv = w->prev, *nx = w->next;
    int *rf = w->tstack; /* reflex flag */
    double x0 = q[0].x, x1 = q[0].x, y0 = q[0].y, y1 = q[0].y;
    for (size_t i = 0; i < m; i++) {
        pv[i] = (i + m - 1) % m;
        nx[i] = (i + 1) % m;
        x0 = fmin(x0, q[i].x); x1 = fmax(x1, q[i].x);
        y0 = fmin(y0, q[i].y); y1 = fmax(y1, q[i].y);
    }
    size_t nref = 0;
    for (size_t i = 0; i < m; i++) {
        rf[i] = acd2_orient_sign(q[pv[i]], q[i], q[nx[i]]) <= 0;
        nref += (size_t)rf[i];
    }
    size_t G = 1;
    while (G * G * 2 < nref && G < 1024) G++;
    double sx = x1 > x0 ? (double)G / (x1 - x0) : 0, sy = y1 > y0 ? (double)G / (y1 - y0) : 0;
    size_t *cs = calloc(G * G + 1, sizeof *cs), *items = malloc((nref ? nref : 1) * sizeof *items);
    if (!cs || !items) { free(cs); free(items); return -2; }
#define CELLX(x) ((size_t)fmin((double)(G - 1), fmax(0.0, ((x) - x0) * sx)))
#define CELLY(y) ((size_t)fmin((double)(G - 1), fmax(0.0, ((y) - y0) * sy)))
    for (size_t i = 0; i < m; i++)
        if (rf[i]) cs[CELLY(q[i].y) * G + CELLX(q[i].x) + 1]++;
    for (size_t c = 0; c < G * G; c++) cs[c + 1] += cs[c];
    {
        size_t *fill = malloc((G * G + 1) * sizeof *fill);
        if (!fill) { free(cs); free(items); return -2; }
        memcpy(fill, cs, (G * G + 1) * sizeof *fill);
        for (size_t i = 0; i < m; i++)
            if (rf[i]) items[fill[CELLY(q[i].y) * G + CELLX(q[i].x)]++] = i;
        free(fill);
    }
    size_t left = m, nt = 0, i = 0, guard = 0;
    int rc = 0;
    while (left > 3) {
        size_t a = pv[i], c = nx[i];
        int ear = !rf[i];
        if (ear) {
            acd_vec2 A = q[a], B = q[i], C = q[c];
            double bx0 = fmin(A.x, fmin(B.x, C.x)), bx1 = fmax(A.x, fmax(B.x, C.x));
            double by0 = fmin(A.y, fmin(B.y, C.y)), by1 = fmax(A.y, fmax(B.y, C.y));
            size_t cx0 = CELLX(bx0), cx1 = CELLX(bx1), cy0 = CELLY(by0), cy1 = CELLY(by1);
            for (size_t gy = cy0; gy <= cy1 && ear; gy++)
                for (size_t gx = cx0; gx <= cx1 && ear; gx++)
                    for (size_t t = cs[gy * G + gx]; t < cs[gy * G + gx + 1]; t++) {
                        size_t j = items[t];
                        if (!rf[j]) continue;
                        acd_vec2 P = q[j];
                        if (P.x < bx0 || P.x > bx1 || P.y < by0 || P.y > by1) continue;
                        if (j == a || j == c || acd2_same(P, A) || acd2_same(P, B) || acd2_same(P, C)) continue;
                        if (in_tri(A, B, C, P)) { ear = 0; break; }
                    }
        }
        if (ear) {
            w->tri[3 * nt] = a; w->tri[3 * nt + 1] = i; w->tri[3 * nt + 2] = c;
            nt++;
            nx[a] = c;
            pv[c] = a;
            left--;
            rf[i] = 0;
            if (rf[a] && acd2_orient_sign(q[pv[a]], q[a], q[nx[a]]) > 0) rf[a] = 0;
            if (rf[c] && acd2_orient_sign(q[pv[c]], q[c], q[nx[c]]) > 0) rf[c] = 0;
            i = a;
            guard = 0;
        } else {
            i = c;
            if (++guard > 2 * left) { rc = -1; break; }
        }
    }
#undef CELLX
#undef CELLY
    free(cs);
    free(items);
    if (rc) return rc;
    size_t a = pv[i], c = nx[i];
    w->tri[3 * nt] = a; w->tri[3 * nt + 1] = i; w->tri[3 * nt + 2] = c;
    return 0;
}

typedef struct edge_key { size_t u, v, t; } edge_key;

static int key_cmp(const void *x, const void *y) {
    const edge_key *a = x, *b = y;
    if (a->u != b->u) return a->u < b->u ? -1 : 1;
    if (a->v != b->v) return a->v < b->v ? -1 : 1;
    return 0;
}

static long find_tri(const edge_key *keys, size_t nk, size_t u, size_t v) {
    size_t lo = 0, hi = nk;
    while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        if (keys[mid].u < u || (keys[mid].u == u && keys[mid].v < v)) lo = mid + 1;
        else hi = mid;
    }
    if (lo < nk && keys[lo].u == u && keys[lo].v == v) return (long)keys[lo].t;
    return -1;
}

/* third vertex of triangle t after directed edge u->v */
static size_t third(const size_t *tri, size_t t, size_t v) {
    for (int k = 0; k < 3; k++)
        if (tri[3 * t + k] == v) return tri[3 * t + (k + 1) % 3];
    return SIZE_MAX;
}

typedef struct fitem { size_t A, B, off, len, apex; } fitem;

typedef struct fstate {
    size_t *buf;
    size_t cap, top;
    fitem *st;
    size_t nst, stcap;
} fstate;

static int fpush(fstate *f, size_t A, size_t B, const size_t *seq1, size_t n1, const size_t *seq2, size_t n2,
                 size_t apex) {
    if (f->top + n1 + n2 > f->cap) {
        size_t nc = f->cap ? f->cap : 256;
        while (nc < f->top + n1 + n2) nc *= 2;
        size_t *nb = realloc(f->buf, nc * sizeof *nb);
        if (!nb) return -1;
        f->buf = nb;
        f->cap = nc;
    }
    if (f->nst == f->stcap) {
        size_t nc = f->stcap ? 2 * f->stcap : 64;
        fitem *ns = realloc(f->st, nc * sizeof *ns);
        if (!ns) return -1;
        f->st = ns;
        f->stcap = nc;
    }
    fitem *it = &f->st[f->nst++];
    it->A = A; it->B = B; it->off = f->top; it->len = n1 + n2; it->apex = apex;
    if (n1) memmove(f->buf + f->top, seq1, n1 * sizeof *seq1);
    if (n2) memmove(f->buf + f->top + n1, seq2, n2 * sizeof *seq2);
    f->top += n1 + n2;
    return 0;
}

/* shortest-path tree from root s of the triangulated polygon; order[] receives the vertices in
 * discovery order (parents first); returns the count, or (size_t)-1 when out of memory */
static size_t spt(acd2_sp_work *w, size_t m, const edge_key *keys, size_t nk, size_t s, int side, fstate *f) {
    const acd_vec2 *q = w->q;
    size_t *par = w->par[side];
    double *dist = w->dist[side];
    size_t *order = w->order;
    for (size_t i = 0; i < m; i++) { par[i] = SIZE_MAX; dist[i] = INFINITY; }
    par[s] = s;
    dist[s] = 0;
    size_t no = 0;
    order[no++] = s;
    f->nst = 0;
    f->top = 0;
    size_t nt = m - 2;
    for (size_t t = 0; t < nt; t++) {
        for (int k = 0; k < 3; k++) {
            if (w->tri[3 * t + k] != s) continue;
            size_t x = w->tri[3 * t + (k + 1) % 3], y = w->tri[3 * t + (k + 2) % 3];
            size_t xs[2] = {x, y};
            for (int z = 0; z < 2; z++)
                if (par[xs[z]] == SIZE_MAX) {
                    par[xs[z]] = s;
                    dist[xs[z]] = hypot(q[xs[z]].x - q[s].x, q[xs[z]].y - q[s].y);
                    order[no++] = xs[z];
                }
            size_t fun[3] = {y, s, x};
            if (fpush(f, y, x, fun, 3, NULL, 0, 1)) return (size_t)-1;
        }
    }
    size_t *tmp = NULL;
    size_t tmpcap = 0;
    while (f->nst > 0) {
        fitem it = f->st[--f->nst];
        long t = find_tri(keys, nk, it.A, it.B);
        if (t < 0) { f->top = it.off; continue; } /* polygon edge */
        size_t C = third(w->tri, (size_t)t, it.B);
        if (C == SIZE_MAX) { f->top = it.off; continue; }
        if (it.len + 2 > tmpcap) {
            size_t nc = 2 * (it.len + 2);
            size_t *nt2 = realloc(tmp, nc * sizeof *nt2);
            if (!nt2) { free(tmp); return (size_t)-1; }
            tmp = nt2;
            tmpcap = nc;
        }
        memcpy(tmp, f->buf + it.off, it.len * sizeof *tmp);
        f->top = it.off;
        const size_t *F = tmp;
        size_t ap = it.apex, mlen = it.len;
        /* left chain: F[ap-1..0]; c beyond edge F[i]->F[i+1] (i < ap) when orient(F[i],F[i+1],c) < 0,
         * scanning outward from the apex; right chain likewise with F[i]->F[i+1] for i >= ap */
        size_t T = 0, Tr = 0;
        while (T < ap && acd2_orient_sign(q[F[ap - T - 1]], q[F[ap - T]], q[C]) < 0) T++;
        if (T == 0)
            while (ap + Tr + 1 < mlen && acd2_orient_sign(q[F[ap + Tr]], q[F[ap + Tr + 1]], q[C]) < 0) Tr++;
        size_t pidx = T > 0 ? ap - T : ap + Tr;
        size_t P = F[pidx];
        if (par[C] == SIZE_MAX) {
            par[C] = P;
            dist[C] = dist[P] + hypot(q[C].x - q[P].x, q[C].y - q[P].y);
            order[no++] = C;
        }
        size_t cc[1] = {C};
        int rc;
        if (T > 0) {
            /* door (A, C): F[0..pidx] + C, apex pidx; door (C, B): C + F[pidx..], apex T + 1 */
            rc = fpush(f, it.A, C, F, pidx + 1, cc, 1, pidx);
            rc |= fpush(f, C, it.B, cc, 1, F + pidx, mlen - pidx, T + 1);
        } else if (Tr > 0) {
            rc = fpush(f, it.A, C, F, pidx + 1, cc, 1, ap);
            rc |= fpush(f, C, it.B, cc, 1, F + pidx, mlen - pidx, 1);
        } else {
            rc = fpush(f, it.A, C, F, ap + 1, cc, 1, ap);
            rc |= fpush(f, C, it.B, cc, 1, F + ap, mlen - ap, 1);
        }
        if (rc) { free(tmp); return (size_t)-1; }
    }
    free(tmp);
    return no;
}

/* Fallback for a pocket that cannot be triangulated (degenerate): the length of the walk along the
 * pocket chain to the nearer bridge end. It is a path inside the closed pocket polygon, hence an
 * upper bound of SP: the decomposition may cut more, never accept a piece too concave. */
static void chain_bound(const acd_vec2 *p, size_t n, size_t a, size_t b, double *conc) {
    double acc = 0;
    for (size_t k = acd2_next(a, n); k != b; k = acd2_next(k, n)) {
        size_t q = acd2_prev(k, n);
        acc += hypot(p[k].x - p[q].x, p[k].y - p[q].y);
        conc[k] = acc;
    }
    acc = 0;
    for (size_t k = acd2_prev(b, n); k != a; k = acd2_prev(k, n)) {
        size_t q = acd2_next(k, n);
        acc += hypot(p[k].x - p[q].x, p[k].y - p[q].y);
        if (acc < conc[k]) conc[k] = acc;
    }
}

acd_status acd2_sp_pocket(const acd_vec2 *p, size_t n, size_t a, size_t b, double *conc, acd2_sp_work *w) {
    size_t k = (b + n - a) % n; /* chain a..b has k + 1 vertices */
    size_t m = k + 1;
    if (m < 3) return ACD_OK;
    if (reserve(w, m + 1)) return ACD_ERR_NOMEM;
    /* Q[i] = chain[k - i]: Q[0] = beta+, Q[k] = beta- */
    for (size_t i = 0; i <= k; i++) w->q[i] = p[(a + k - i) % n];
    int tr = triangulate(w, m);
    if (tr == -2) return ACD_ERR_NOMEM;
    if (tr) {
        chain_bound(p, n, a, b, conc);
        return ACD_OK;
    }
    size_t nt = m - 2, nk = 3 * nt;
    edge_key *keys = malloc(nk * sizeof *keys);
    if (!keys) return ACD_ERR_NOMEM;
    for (size_t t = 0; t < nt; t++)
        for (int e = 0; e < 3; e++) {
            keys[3 * t + e].u = w->tri[3 * t + e];
            keys[3 * t + e].v = w->tri[3 * t + (e + 1) % 3];
            keys[3 * t + e].t = t;
        }
    qsort(keys, nk, sizeof *keys, key_cmp);
    fstate f = {0};
    size_t roots[2] = {k, 0}; /* side 0: beta-, side 1: beta+ */
    acd_status st = ACD_OK;
    size_t *ord[2] = {NULL, NULL};
    size_t cnt[2] = {0, 0};
    for (int s = 0; s < 2 && st == ACD_OK; s++) {
        size_t no = spt(w, m, keys, nk, roots[s], s, &f);
        if (no == (size_t)-1) { st = ACD_ERR_NOMEM; break; }
        ord[s] = malloc((no ? no : 1) * sizeof *ord[s]);
        if (!ord[s]) { st = ACD_ERR_NOMEM; break; }
        memcpy(ord[s], w->order, no * sizeof *ord[s]);
        cnt[s] = no;
    }
    free(keys);
    free(f.buf);
    free(f.st);
    if (st != ACD_OK || cnt[0] != m || cnt[1] != m) {
        free(ord[0]);
        free(ord[1]);
        if (st != ACD_OK) return st;
        chain_bound(p, n, a, b, conc); /* degenerate triangulation: fall back */
        return ACD_OK;
    }
    const acd_vec2 *q = w->q;
    acd_vec2 Bm = q[k], Bp = q[0];
    double dx = Bp.x - Bm.x, dy = Bp.y - Bm.y, len = hypot(dx, dy);
    /* outward convexity flags along each tree: path to beta- turns right (or straight) at every
     * vertex seen from v, path to beta+ turns left: the obstacle is on the far side (Lemma A.1) */
    unsigned char *cvx = malloc(2 * m);
    if (!cvx) { free(ord[0]); free(ord[1]); return ACD_ERR_NOMEM; }
    for (int s = 0; s < 2; s++) {
        size_t *par = w->par[s];
        for (size_t i = 0; i < m; i++) {
            size_t v = ord[s][i], u = par[v];
            if (u == v || par[u] == u) { cvx[s * m + v] = 1; continue; }
            int o = acd2_orient_sign(q[v], q[u], q[par[u]]);
            cvx[s * m + v] = cvx[s * m + u] && (s == 0 ? o <= 0 : o >= 0);
        }
    }
    for (int s = 0; s < 2; s++) {
        size_t *par = w->par[s];
        double *g = w->g[s];
        for (size_t i = 0; i < m; i++) {
            size_t v = ord[s][i], u = par[v];
            if (u == v) { g[v] = 0; continue; }
            double h = INFINITY;
            size_t pm = w->par[0][v], pp = w->par[1][v];
            if (cvx[v] && cvx[m + v]) {
                double am = (q[pm].x - q[v].x) * dx + (q[pm].y - q[v].y) * dy;
                double apv = (q[pp].x - q[v].x) * dx + (q[pp].y - q[v].y) * dy;
                if (am <= 0 && apv >= 0 && len > 0) {
                    double o = acd2_orient(Bm, Bp, q[v]);
                    h = o > 0 ? o / len : 0;
                }
            }
            double via = hypot(q[v].x - q[u].x, q[v].y - q[u].y) + g[u];
            g[v] = h < via ? h : via;
        }
    }
    for (size_t i = 1; i < k; i++) {
        size_t ri = (a + k - i) % n;
        double v0 = w->g[0][i], v1 = w->g[1][i];
        conc[ri] = v0 < v1 ? v0 : v1;
    }
    free(cvx);
    free(ord[0]);
    free(ord[1]);
    return ACD_OK;
}
