/* corise/valley: bridges (hull edges), valleys (shortest vertex paths) and valley concavity,
 * CoRiSe §3 Step 1, §4 and Eq. 1 (Liu, Xi, Lien, CAD 2016); spec corise.md §2.2-2.3. */
#include "corise/valley.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "acd/polygon.h"
#include "acd2/concavity_sp.h"
#include "core/error.h"
#include "core/predicates.h"
#include "geom2/seg_sweep.h"
#ifdef _OPENMP
#include <omp.h>
#endif

/* Rings at least this long are tested for simplicity by a sweep instead of all pairs. */
#define POLYGON_SWEEP_MIN 48

/* Brute force, O(m^2), exact. */
static int polygon_is_simple_brute(const acd_vec2 *p, size_t m) {
    for (size_t i = 0; i < m; i++) {
        double a0[2] = {p[i].x, p[i].y}, a1[2] = {p[(i + 1) % m].x, p[(i + 1) % m].y};
        double axlo = fmin(a0[0], a1[0]), axhi = fmax(a0[0], a1[0]), aylo = fmin(a0[1], a1[1]), ayhi = fmax(a0[1], a1[1]);
        for (size_t j = i + 1; j < m; j++) {
            double b0[2] = {p[j].x, p[j].y}, b1[2] = {p[(j + 1) % m].x, p[(j + 1) % m].y};
            int adjacent = j == i + 1 || (i == 0 && j == m - 1);
            /* strictly separated bounding boxes: no common point (exact comparisons), the
               segments are disjoint; skips the predicates for most pairs */
            if (!adjacent && (fmax(b0[0], b1[0]) < axlo || fmin(b0[0], b1[0]) > axhi || fmax(b0[1], b1[1]) < aylo ||
                              fmin(b0[1], b1[1]) > ayhi))
                continue;
            acd_seg_relation r = acd_segments_relation(a0, a1, b0, b1);
            if (adjacent ? r == ACD_SEG_OVERLAP || r == ACD_SEG_PROPER : r != ACD_SEG_DISJOINT) return 0;
        }
    }
    return 1;
}

/* Edges e and f of the ring of POLYGON_SWEEP_MIN or more vertices meet where they should not. */
typedef struct simple_ctx {
    const acd_vec2 *p;
    size_t m;
    int conflict;
} simple_ctx;

static acd_status sweep_pair(void *ctx, size_t e, size_t f) {
    const simple_ctx *c = ctx;
    size_t i = e < f ? e : f, j = e < f ? f : e, m = c->m;
    const acd_vec2 *p = c->p;
    double a0[2] = {p[i].x, p[i].y}, a1[2] = {p[(i + 1) % m].x, p[(i + 1) % m].y};
    double b0[2] = {p[j].x, p[j].y}, b1[2] = {p[(j + 1) % m].x, p[(j + 1) % m].y};
    int adjacent = j == i + 1 || (i == 0 && j == m - 1);
    acd_seg_relation r = acd_segments_relation(a0, a1, b0, b1);
    int bad = adjacent ? r == ACD_SEG_OVERLAP || r == ACD_SEG_PROPER : r != ACD_SEG_DISJOINT;
    if (bad) ((simple_ctx *)ctx)->conflict = 1;
    return bad ? ACD_ERR_INVALID_INPUT : ACD_OK;
}

/* The projected polygon p[0..m) (chain, closed by the lid p[m-1] -> p[0]) is simple: no two
 * non-adjacent edges meet, adjacent edges meet only at their shared vertex. Exact; a Shamos-Hoey
 * sweep (geom2/seg_sweep, which finds a conflicting pair iff the brute force does) for rings of
 * POLYGON_SWEEP_MIN vertices or more without a zero-length edge, else the brute force. */
static int polygon_is_simple(const acd_vec2 *p, size_t m) {
    if (m < POLYGON_SWEEP_MIN) return polygon_is_simple_brute(p, m);
    for (size_t i = 0; i < m; i++)
        if (p[i].x == p[(i + 1) % m].x && p[i].y == p[(i + 1) % m].y) return polygon_is_simple_brute(p, m);
    size_t *next = malloc(m * sizeof *next);
    if (!next) return polygon_is_simple_brute(p, m);
    for (size_t i = 0; i < m; i++) next[i] = (i + 1) % m;
    simple_ctx c = {p, m, 0};
    acd_error e;
    acd_status st = acd_sweep_edges(p, next, m, sweep_pair, &c, NULL, NULL, &e);
    free(next);
    if (st == ACD_OK) return 1;
    if (c.conflict) return 0;
    return polygon_is_simple_brute(p, m); /* the sweep could not run (memory): same answer the slow way */
}

/* Eq. 1 projection of q against the bridge from a along the unit direction u, of length L:
 * (abscissa along u, distance to the segment). The one place it is computed, so that the bound
 * below and the concavity agree bit for bit. */
static inline void project(const double *q, const double *a, const double *u, double L, acd_vec2 *out) {
    double d[3] = {q[0] - a[0], q[1] - a[1], q[2] - a[2]};
    double x = d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
    double s = x < 0 ? 0 : x > L ? L : x;
    double e[3] = {d[0] - s * u[0], d[1] - s * u[1], d[2] - s * u[2]};
    out->x = x;
    out->y = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
}

/* The bridge's direction and length, as acd_corise_chain_concavity computes them. */
static inline double bridge_dir(const double *a, const double *b, double u[3]) {
    double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double L = sqrt(ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2]);
    u[0] = u[1] = u[2] = 0;
    if (L > 0)
        for (int k = 0; k < 3; k++) u[k] = ab[k] / L;
    return L;
}

void acd_corise_chain_bound(const double *vertices, const uint32_t *chain, size_t m, double *bound, int *exact) {
    *bound = 0;
    *exact = 1;
    if (m < 3) return;
    const double *a = vertices + 3 * (size_t)chain[0], *b = vertices + 3 * (size_t)chain[m - 1];
    double u[3];
    double L = bridge_dir(a, b, u);
    double best = 0, prev = 0;
    for (size_t t = 1; t + 1 < m; t++) {
        acd_vec2 q;
        project(vertices + 3 * (size_t)chain[t], a, u, L, &q);
        if (q.x < prev) *exact = 0;
        prev = q.x;
        if (q.y > best) best = q.y;
    }
    if (L < prev) *exact = 0;
    *bound = best;
}

acd_status acd_corise_chain_concavity(const double *vertices, const uint32_t *chain, size_t m, double *conc,
                                      double *max, size_t *argmax, acd_corise_conc_kind *kind, acd_error *err) {
    if (!vertices || (!chain && m)) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "corise: NULL chain");
    if (max) *max = 0;
    if (argmax) *argmax = 0;
    if (kind) *kind = ACD_CORISE_CONC_TRIVIAL;
    if (m < 3) {
        if (conc)
            for (size_t t = 0; t < m; t++) conc[t] = 0;
        return ACD_OK;
    }
    acd_vec2 *p = malloc(m * sizeof *p);
    double *c = conc ? conc : malloc(m * sizeof *c);
    if (!p || !c) {
        free(p);
        if (!conc) free(c);
        return acd_fail(err, ACD_ERR_NOMEM, "corise: out of memory for a valley of %zu vertices", m);
    }
    const double *a = vertices + 3 * (size_t)chain[0], *b = vertices + 3 * (size_t)chain[m - 1];
    double u[3];
    double L = bridge_dir(a, b, u);
    int monotone = 1;
    for (size_t t = 0; t < m; t++) {
        project(vertices + 3 * (size_t)chain[t], a, u, L, &p[t]);
        if (t == 0) p[t].x = 0, p[t].y = 0;
        if (t == m - 1) p[t].x = L, p[t].y = 0;
        c[t] = p[t].y;
        if (t > 0 && p[t].x < p[t - 1].x) monotone = 0;
    }
    acd_corise_conc_kind how = ACD_CORISE_CONC_MONOTONE;
    if (!monotone) {
        how = ACD_CORISE_CONC_FALLBACK;
        if (L > 0 && polygon_is_simple(p, m)) {
            acd2_sp_work w;
            memset(&w, 0, sizeof w);
            acd_status st = acd2_sp_pocket(p, m, 0, m - 1, c, &w);
            acd2_sp_work_free(&w);
            if (st != ACD_OK) {
                free(p);
                if (!conc) free(c);
                return acd_fail(err, st, "corise: shortest paths in the concavity polygon of a %zu-vertex valley", m);
            }
            c[0] = c[m - 1] = 0;
            how = ACD_CORISE_CONC_SP;
        }
    }
    double best = 0;
    size_t arg = 0;
    for (size_t t = 0; t < m; t++)
        if (c[t] > best) best = c[t], arg = t;
    if (max) *max = best;
    if (argmax) *argmax = arg;
    if (kind) *kind = how;
    free(p);
    if (!conc) free(c);
    return ACD_OK;
}

/* ---- valley search ------------------------------------------------------------------------ */

/* A* from a to b (Euclidean distance to b as the heuristic: consistent, because every edge costs
 * at least its length, so the first time b is settled its path is optimal) on the edge graph
 * with edge cost
 *     |uv| * (1 + ACD_CORISE_VALLEY_TIEBREAK * (dev(u) + dev(v)) / (2 |ab|)),
 * dev = distance to the bridge segment: among paths of (almost) equal length the one closest to
 * the bridge wins. Without it, the many equal-length staircases of a regular grid tie and the
 * id tie-break picks an extreme one, which reads as false concavity (docs/corise.md). The
 * workspace is reused across bridges; stamps avoid clearing it. */
typedef struct vs_item {
    double cost; /* key: g + h (A*) */
    double g;    /* cost from a */
    uint32_t v;
} vs_item;

/* A vertex's state in one search, in one record (32 bytes) so that touching a vertex costs one
 * cache line on a mesh too large for the cache (separate arrays cost one each). */
typedef struct vs_node {
    double cost; /* from a */
    double dev;  /* distance to the bridge segment */
    double h;    /* A* heuristic: distance to b */
    uint32_t pred;
    uint32_t mark; /* 2 * run + settled: the fields above are valid when mark >> 1 == run */
} vs_node;

typedef struct valley_search {
    size_t nv;
    vs_node *node;
    uint32_t run; /* < 2^31 */
    vs_item *heap;
    size_t nheap, cap;
    uint32_t *path;
    size_t cap_path;
    size_t pops; /* heap pops of all the searches, to poll every ACD_CORISE_POLL_POPS */
} valley_search;

static void vs_free(valley_search *s) {
    free(s->node);
    free(s->heap);
    free(s->path);
    memset(s, 0, sizeof *s);
}

static int vs_init(valley_search *s, size_t nv) {
    memset(s, 0, sizeof *s);
    s->nv = nv;
    size_t n = nv ? nv : 1;
    s->node = calloc(n, sizeof *s->node);
    return s->node != NULL;
}

static int vs_less(vs_item x, vs_item y) { return x.cost < y.cost || (x.cost == y.cost && x.v < y.v); }

static int vs_push(valley_search *s, double cost, double gcost, uint32_t v) {
    if (s->nheap == s->cap) {
        size_t nc = s->cap ? 2 * s->cap : 256;
        vs_item *h = realloc(s->heap, nc * sizeof *h);
        if (!h) return 0;
        s->heap = h;
        s->cap = nc;
    }
    size_t i = s->nheap++;
    vs_item it = {cost, gcost, v};
    while (i > 0) {
        size_t p = (i - 1) / 2;
        if (!vs_less(it, s->heap[p])) break;
        s->heap[i] = s->heap[p];
        i = p;
    }
    s->heap[i] = it;
    return 1;
}

static vs_item vs_pop(valley_search *s) {
    vs_item top = s->heap[0], last = s->heap[--s->nheap];
    size_t i = 0, n = s->nheap;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= n) break;
        if (c + 1 < n && vs_less(s->heap[c + 1], s->heap[c])) c++;
        if (!vs_less(s->heap[c], last)) break;
        s->heap[i] = s->heap[c];
        i = c;
    }
    if (n) s->heap[i] = last;
    return top;
}

static double seg_dist(const double *p, const double *a, const double *u, double L) {
    double d[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    double x = d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
    double t = x < 0 ? 0 : x > L ? L : x;
    double e[3] = {d[0] - t * u[0], d[1] - t * u[1], d[2] - t * u[2]};
    return sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
}

/* Valley from a to b into s->path (*len vertices, a first) and its Euclidean *length.
 * Returns 1 when found, 0 when b is unreachable, -1 when out of memory, -2 when poll said stop. */
static int vs_valley(valley_search *s, const acd_edge_graph *g, const double *V, uint32_t a, uint32_t b, size_t *len,
                     double *length, acd3_poll *poll) {
    if (++s->run >= UINT32_C(1) << 31) { /* mark wrap-around: clear */
        memset(s->node, 0, s->nv * sizeof *s->node);
        s->run = 1;
    }
    uint32_t run = s->run;
    vs_node *N = s->node;
    const double *pa = V + 3 * (size_t)a, *pb = V + 3 * (size_t)b;
    double u[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
    double L = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int k = 0; k < 3; k++) u[k] = L > 0 ? u[k] / L : 0;
    double kappa = L > 0 ? ACD_CORISE_VALLEY_TIEBREAK / (2 * L) : 0;
    s->nheap = 0;
    N[a].mark = 2 * run;
    N[a].cost = 0;
    N[a].pred = ACD_NO_VERTEX;
    N[a].dev = seg_dist(pa, pa, u, L);
    if (!vs_push(s, L, 0, a)) return -1;
    int found = 0;
    while (s->nheap) {
        if (poll && ++s->pops % ACD_CORISE_POLL_POPS == 0 && acd3_poll_stop(poll)) return -2;
        vs_item it = vs_pop(s);
        uint32_t x = it.v;
        if ((N[x].mark & 1) || it.g > N[x].cost) continue; /* x was touched in this run */
        N[x].mark |= 1;
        if (x == b) {
            found = 1;
            break;
        }
        double dx = N[x].dev;
        for (size_t k = g->row[x]; k < g->row[x + 1]; k++) {
            uint32_t y = g->adj[k];
            vs_node *ny = &N[y];
            int seen = ny->mark >> 1 == run;
            if (seen && (ny->mark & 1)) continue;
            if (!seen) { /* first touch in this run: its distances, once */
                const double *py = V + 3 * (size_t)y;
                ny->dev = seg_dist(py, pa, u, L);
                ny->h = sqrt((py[0] - pb[0]) * (py[0] - pb[0]) + (py[1] - pb[1]) * (py[1] - pb[1]) +
                               (py[2] - pb[2]) * (py[2] - pb[2]));
            }
            double c = it.g + g->length[g->adj_edge[k]] * (1 + kappa * (dx + ny->dev));
            if (!seen || c < ny->cost) {
                ny->mark = 2 * run;
                ny->cost = c;
                ny->pred = x;
                if (!vs_push(s, c + ny->h, c, y)) return -1;
            }
        }
    }
    if (!found) return 0;
    size_t n = 0;
    for (uint32_t x = b; x != ACD_NO_VERTEX; x = N[x].pred) n++;
    if (n > s->cap_path) {
        uint32_t *p = realloc(s->path, n * sizeof *p);
        if (!p) return -1;
        s->path = p;
        s->cap_path = n;
    }
    size_t i = n;
    double sum = 0;
    for (uint32_t x = b; x != ACD_NO_VERTEX; x = N[x].pred) {
        s->path[--i] = x;
        if (N[x].pred != ACD_NO_VERTEX) {
            const double *p = V + 3 * (size_t)x, *q = V + 3 * (size_t)N[x].pred;
            sum += sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
        }
    }
    *len = n;
    *length = sum;
    return 1;
}

/* ---- bridges and valleys ------------------------------------------------------------------ */

typedef struct vpair {
    uint32_t a, b;
} vpair;

static int cmp_vpair(const void *x, const void *y) {
    const vpair *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    return (p->b > q->b) - (p->b < q->b);
}

static int cmp_u32(const void *x, const void *y) {
    uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return (a > b) - (a < b);
}

void acd_corise_bridges_free(acd_corise_bridges *b) {
    if (!b) return;
    free(b->bridge);
    free(b->hull_vertex);
    free(b->path);
    memset(b, 0, sizeof *b);
}

acd_status acd_corise_bridges_compute(const acd_mesh *m, const acd_edge_graph *g, acd_corise_bridges *out,
                                      acd_error *err) {
    return acd_corise_bridges_compute_ex(m, g, 0, out, err);
}

acd_status acd_corise_bridges_compute_ex(const acd_mesh *m, const acd_edge_graph *g, int clamp_depth,
                                         acd_corise_bridges *out, acd_error *err) {
    return acd_corise_bridges_compute_mt(m, g, clamp_depth, 1, NULL, out, err);
}

/* Per-thread workspace of the bridge loop. */
typedef struct bridge_worker {
    valley_search vs;
    double *conc;
    size_t cap_conc;
    double *depth; /* depth below the hull per vertex (NAN: not yet), with the clamp */
} bridge_worker;

/* The valley of br (a, b set) and its concavity: br->count, length (INFINITY when b is
 * unreachable), concavity, deepest, kind; *path (malloc'd) the valley's vertices. */
static acd_status one_bridge(bridge_worker *w, const acd_mesh *m, const acd_edge_graph *g, const acd_hull *h,
                             int clamp_depth, acd3_poll *poll, acd_corise_bridge *br, uint32_t **path) {
    size_t len = 0;
    double length = 0;
    int r = vs_valley(&w->vs, g, m->vertices, br->a, br->b, &len, &length, poll);
    if (r == -2) return ACD_ERR_CANCELLED;
    if (r < 0) return ACD_ERR_NOMEM;
    if (r == 0) {
        br->length = INFINITY;
        return ACD_OK;
    }
    uint32_t *p = malloc(len * sizeof *p);
    if (!p) return ACD_ERR_NOMEM;
    memcpy(p, w->vs.path, len * sizeof *p);
    *path = p;
    br->count = len;
    br->length = length;
    if (len > w->cap_conc) {
        double *nc = realloc(w->conc, len * sizeof *nc);
        if (!nc) return ACD_ERR_NOMEM;
        w->conc = nc;
        w->cap_conc = len;
    }
    acd_error e;
    acd_status st = acd_corise_chain_concavity(m->vertices, p, len, w->conc, NULL, NULL, &br->kind, &e);
    if (st != ACD_OK) return st;
    /* a valley point on the hull's surface is not concave: clamp by its depth below it */
    br->concavity = 0;
    br->deepest = 0;
    for (size_t k = 0; k < len; k++) {
        double c = w->conc[k];
        if (clamp_depth && h->dim == 3 && c != 0) { /* c = 0 stays 0 whatever the depth */
            uint32_t v = p[k];
            if (isnan(w->depth[v])) w->depth[v] = -acd_hull_plane_distance(h, m->vertices + 3 * (size_t)v);
            if (w->depth[v] < c) c = w->depth[v] > 0 ? w->depth[v] : 0;
        }
        if (c > br->concavity) br->concavity = c, br->deepest = k;
    }
    return ACD_OK;
}

acd_status acd_corise_bridges_compute_mt(const acd_mesh *m, const acd_edge_graph *g, int clamp_depth, int nthreads,
                                         acd3_poll *poll, acd_corise_bridges *out, acd_error *err) {
    if (!m || !g || !out) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "corise: NULL argument");
    memset(out, 0, sizeof *out);
    out->hull_dim = -1;
    if (g->nvertices != m->nvertices)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "corise: edge graph has %zu vertices, mesh %zu", g->nvertices,
                        m->nvertices);
    acd_status st = ACD_OK;
    uint8_t *used = calloc(m->nvertices ? m->nvertices : 1, 1);
    uint32_t *ids = malloc((m->nvertices ? m->nvertices : 1) * sizeof *ids);
    double *pts = malloc((m->nvertices ? m->nvertices : 1) * 3 * sizeof *pts);
    vpair *pairs = NULL;
    acd_hull h;
    memset(&h, 0, sizeof h);
    bridge_worker *wk = NULL;
    uint32_t **bpath = NULL;
    acd_status *bst = NULL;
    size_t nb = 0;
    int nt = 1;
    if (!used || !ids || !pts) goto nomem;
    for (size_t t = 0; t < 3 * m->ntriangles; t++) {
        if (m->triangles[t] >= m->nvertices) {
            st = acd_fail(err, ACD_ERR_INVALID_INPUT, "corise: triangle %zu uses vertex %u, but the mesh has %zu", t / 3,
                          m->triangles[t], m->nvertices);
            goto done;
        }
        used[m->triangles[t]] = 1;
    }
    size_t np = 0;
    for (size_t v = 0; v < m->nvertices; v++)
        if (used[v]) {
            ids[np] = (uint32_t)v;
            memcpy(pts + 3 * np, m->vertices + 3 * v, 3 * sizeof(double));
            np++;
        }
    if ((st = acd_hull_compute(pts, np, &h, err)) != ACD_OK) goto done;
    if (acd3_poll_stop(poll)) goto cancelled;
    out->hull_dim = h.dim;
    if (h.dim < 2 || h.ntriangles == 0) goto done;
    out->hull_vertex = malloc(h.nvertices * sizeof *out->hull_vertex);
    if (!out->hull_vertex) goto nomem;
    for (size_t i = 0; i < h.nvertices; i++) out->hull_vertex[i] = ids[h.source[i]];
    out->nhull = h.nvertices;
    qsort(out->hull_vertex, out->nhull, sizeof *out->hull_vertex, cmp_u32);
    pairs = malloc(3 * h.ntriangles * sizeof *pairs);
    if (!pairs) goto nomem;
    size_t ne = 0;
    for (size_t t = 0; t < h.ntriangles; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t x = ids[h.source[h.triangles[3 * t + k]]], y = ids[h.source[h.triangles[3 * t + (k + 1) % 3]]];
            if (x == y) continue;
            pairs[ne++] = (vpair){x < y ? x : y, x < y ? y : x};
        }
    qsort(pairs, ne, sizeof *pairs, cmp_vpair);
    for (size_t i = 0; i < ne; i++)
        if (i == 0 || cmp_vpair(&pairs[i], &pairs[i - 1]) != 0) pairs[nb++] = pairs[i];
    out->bridge = calloc(nb ? nb : 1, sizeof *out->bridge);
    if (!out->bridge) goto nomem;
    /* every bridge's valley and concavity depend on that bridge alone (each worker's search
       stamps and depth memo give the same values whatever it ran before), so the bridges are
       shared among the threads and their valleys concatenated in bridge order afterwards */
#ifdef _OPENMP
    if (nthreads > 1 && nb >= ACD_CORISE_PARALLEL_MIN_BRIDGES && m->ntriangles >= ACD_CORISE_PARALLEL_MIN_FACES &&
        !omp_in_parallel())
        nt = nthreads;
#endif
    wk = calloc((size_t)nt, sizeof *wk);
    bpath = calloc(nb ? nb : 1, sizeof *bpath);
    bst = calloc(nb ? nb : 1, sizeof *bst);
    if (!wk || !bpath || !bst) goto nomem;
    for (int t = 0; t < nt; t++) {
        if (!vs_init(&wk[t].vs, m->nvertices)) goto nomem;
        if (clamp_depth && h.dim == 3) { /* depth below the hull per vertex, computed on first use */
            wk[t].depth = malloc(m->nvertices * sizeof *wk[t].depth);
            if (!wk[t].depth) goto nomem;
            for (size_t v = 0; v < m->nvertices; v++) wk[t].depth[v] = NAN;
        }
    }
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 4) num_threads(nt) if (nt > 1)
#endif
    for (long i = 0; i < (long)nb; i++) {
        int t = 0;
#ifdef _OPENMP
        t = omp_get_thread_num();
#endif
        out->bridge[i].a = pairs[i].a;
        out->bridge[i].b = pairs[i].b;
        /* once the poll said stop, the other bridges are skipped (the flag, no callback) */
        bst[i] = acd3_poll_stopped(poll) ? ACD_ERR_CANCELLED
                                         : one_bridge(&wk[t], m, g, &h, clamp_depth, poll, &out->bridge[i], &bpath[i]);
    }
    if (acd3_poll_stopped(poll)) goto cancelled;
    size_t cap_path = 0;
    for (size_t i = 0; i < nb; i++) {
        acd_corise_bridge *br = &out->bridge[i];
        if (bst[i] != ACD_OK) {
            st = acd_fail(err, bst[i], "corise: the valley of bridge (%u, %u) of a %zu-vertex mesh (out of memory)", br->a,
                          br->b, m->nvertices);
            goto done;
        }
        br->first = out->npath;
        if (!isfinite(br->length)) {
            out->unreachable++;
            continue;
        }
        size_t len = br->count;
        if (out->npath + len > cap_path) {
            size_t nc = cap_path ? 2 * cap_path : 1024;
            while (nc < out->npath + len) nc *= 2;
            uint32_t *np2 = realloc(out->path, nc * sizeof *np2);
            if (!np2) goto nomem;
            out->path = np2;
            cap_path = nc;
        }
        memcpy(out->path + out->npath, bpath[i], len * sizeof *out->path);
        out->npath += len;
        if (br->kind == ACD_CORISE_CONC_FALLBACK) out->fallbacks++;
    }
    out->nbridges = nb;
    goto done;
cancelled:
    st = acd_fail(err, ACD_ERR_CANCELLED, "corise: cancelled by the progress callback computing the valleys of a %zu-vertex mesh",
                  m->nvertices);
    goto done;
nomem:
    st = acd_fail(err, ACD_ERR_NOMEM, "corise: out of memory computing bridges of a %zu-vertex mesh", m->nvertices);
done:
    free(used);
    free(ids);
    free(pts);
    free(pairs);
    acd_hull_free(&h);
    if (wk)
        for (int t = 0; t < nt; t++) {
            vs_free(&wk[t].vs);
            free(wk[t].conc);
            free(wk[t].depth);
        }
    free(wk);
    if (bpath)
        for (size_t i = 0; i < nb; i++) free(bpath[i]);
    free(bpath);
    free(bst);
    if (st != ACD_OK) acd_corise_bridges_free(out);
    return st;
}
