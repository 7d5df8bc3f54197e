/* acd3/merge: joining adjacent parts whose union is nearly convex; see merge.h. */
#include "acd3/merge.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "acd/hull.h"
#include "core/error.h"
#include "geom3/bvh.h"

/* Closest-point queries allowed when scoring one pair; a pair needing more is refused. */
#define MERGE_MAX_QUERIES 100000
/* Hull pieces are not subdivided below this fraction of tau: such a piece (its centroid within
 * tau of the part but its bound above tau) refuses the pair. */
#define MERGE_MIN_RADIUS_REL 1e-3
/* A vertex is on the input surface when within this fraction of the input's bounding-box
 * diagonal of it (cut vertices are interpolated on input edges: off by rounding only). */
#define MERGE_ON_SURFACE_REL 1e-9

typedef struct group {
    int alive;
    double *hv; /* hull vertices */
    size_t nhv;
    double *sv; /* vertices on the input surface */
    size_t nsv;
    const acd_bvh *pbvh; /* the trees of all parts (shared), indexed by members[] */
    uint32_t *adj; /* adjacent live groups, increasing */
    size_t nadj;
    uint32_t *members;
    size_t nmembers;
    double bound;
    double hvol; /* its hull's volume (0 when flat) */
    double *ft;  /* its hull's facets: 9 coordinates each, corners in canonical order, sorted */
    double *fub; /* per facet: an upper bound of the distance from its points to the group (> tau: not bounded) */
    size_t nft;
} group;

typedef struct pair {
    uint32_t a, b; /* a < b */
    int ok;
    double cost;  /* the order: the bound, or (by_volume) the hull volume the join adds */
    double bound; /* max(d_in, bound of d_out) */
    double *ft, *fub; /* ok: the joined hull's facet table (as group.ft, fub), for the join */
    size_t nft;
} pair;

static void pair_free(pair *p) {
    free(p->ft);
    free(p->fub);
    p->ft = p->fub = NULL;
}

static void group_free(group *g) {
    free(g->hv);
    free(g->sv);
    free(g->adj);
    free(g->members);
    free(g->ft);
    free(g->fub);
    memset(g, 0, sizeof *g);
}

void acd3_merge_result_free(acd3_merge_result *r) {
    if (!r) return;
    free(r->group_of);
    free(r->group_size);
    free(r->bound);
    memset(r, 0, sizeof *r);
}

/* Distance from p to the members' triangles, if below lim (else lim or more); q: the closest point
 * found (untouched when none within lim). */
static double dist_group(const group *g, const double p[3], double lim, double q[3]) {
    double d = INFINITY;
    for (size_t m = 0; m < g->nmembers; m++) {
        acd_bvh_closest_result r;
        double l = d < lim ? d : lim;
        if (acd_bvh_closest(&g->pbvh[g->members[m]], p, l * l, &r) && sqrt(r.dist2) < d) {
            d = sqrt(r.dist2);
            memcpy(q, r.point, sizeof r.point);
        }
    }
    return d;
}

static double dist_groups(const group *A, const group *B, const double p[3], double lim, double q[3]) {
    double d = dist_group(A, p, lim, q);
    if (B) {
        double e = dist_group(B, p, d < lim ? d : lim, q);
        if (e < d) d = e;
    }
    return d;
}

static double len3(const double a[3], const double b[3]) {
    double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
    return sqrt(x * x + y * y + z * z);
}

/* The hull of the two groups' hull vertices; 0 when flat or out of memory. */
static int joint_hull(const group *A, const group *B, acd_hull *H) {
    size_t n = A->nhv + B->nhv;
    double *pts = malloc(3 * n * sizeof *pts);
    if (!pts) return 0;
    memcpy(pts, A->hv, 3 * A->nhv * sizeof *pts);
    memcpy(pts + 3 * A->nhv, B->hv, 3 * B->nhv * sizeof *pts);
    acd_status st = acd_hull_compute(pts, n, H, NULL);
    free(pts);
    if (st != ACD_OK || H->dim != 3) {
        acd_hull_free(H);
        return 0;
    }
    return 1;
}

/* Largest distance of the surface vertices of g to the boundary of H, scanning the facets from the
 * one that served the previous vertex and stopping as soon as a vertex cannot raise the maximum.
 * Returns a value > tau as soon as one vertex is deeper than tau. */
static double depth_in_hull(const group *g, const acd_hull *H, double din, double tau, size_t *start) {
    size_t nf = H->ntriangles;
    const double *pl = H->planes;
    for (size_t i = 0; i < g->nsv; i++) {
        const double *v = g->sv + 3 * i;
        double best = INFINITY;
        size_t f = *start, arg = f;
        for (size_t k = 0; k < nf; k++) {
            const double *q = pl + 4 * f;
            double dep = -(q[0] * v[0] + q[1] * v[1] + q[2] * v[2] + q[3]);
            if (dep < best) {
                best = dep;
                arg = f;
                if (best <= din) break;
            }
            f = f + 1 == nf ? 0 : f + 1;
        }
        *start = arg;
        if (best > din) {
            din = best;
            if (din > tau) return din;
        }
    }
    return din;
}

static int cmp_point(const double *a, const double *b) {
    for (int k = 0; k < 3; k++)
        if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
    return 0;
}

static int cmp_facet(const double *a, const double *b) {
    for (int k = 0; k < 3; k++) {
        int c = cmp_point(a + 3 * k, b + 3 * k);
        if (c) return c;
    }
    return 0;
}

/* Facet t of H with its corners in canonical (lexicographic) order. */
static void facet_key(const acd_hull *H, size_t t, double key[9]) {
    const double *p[3];
    for (int k = 0; k < 3; k++) p[k] = H->vertices + 3 * (size_t)H->triangles[3 * t + k];
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2 - i; j++)
            if (cmp_point(p[j], p[j + 1]) > 0) {
                const double *x = p[j];
                p[j] = p[j + 1];
                p[j + 1] = x;
            }
    for (int k = 0; k < 3; k++) memcpy(key + 3 * k, p[k], sizeof(double[3]));
}

/* The bound kept for this facet by group g, or INFINITY. */
static double cached_ub(const group *g, const double key[9]) {
    size_t lo = 0, hi = g->nft;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        int c = cmp_facet(g->ft + 9 * mid, key);
        if (c == 0) return g->fub[mid];
        if (c < 0) lo = mid + 1;
        else hi = mid;
    }
    return INFINITY;
}

static double max_corner_dist(const double tri[9], const double q[3]) {
    return fmax(len3(tri, q), fmax(len3(tri + 3, q), len3(tri + 6, q)));
}

/* An upper bound of the distance from the points of triangle tri to A u B (B may be NULL). For a
 * point q of A u B, every point of a triangle is within max_k |v_k - q| of q (|x - q| is convex,
 * its maximum on the triangle is at a corner). The triangle is subdivided (midpoints, 4 children)
 * until every piece has such a point within tau of all its corners: first the point its parent
 * found (no query), else the closest point q of A u B to its centroid g. Since
 * max_k |v_k - q| <= dist(g) + r (r: the piece's circumradius), this bound is never looser than
 * the Lipschitz one. Returns INFINITY when a centroid is farther than tau, the query budget runs
 * out or pieces get too small. Stack items: the piece's corners (9) and the parent's point (3; NaN
 * for none). */
#define MERGE_WARM_SLACK_REL 1e-9
#define MERGE_ITEM 12
static double facet_ub(const group *A, const group *B, const double tri0[9], double tau, size_t *queries,
                       double **stackp, size_t *capp) {
    double *stack = *stackp;
    size_t n = 1, cap = *capp;
    memcpy(stack, tri0, 9 * sizeof *stack);
    stack[9] = stack[10] = stack[11] = NAN;
    double ub = 0, prev_d = INFINITY, prev_g[3] = {0, 0, 0};
    while (n) {
        double it[MERGE_ITEM];
        memcpy(it, stack + MERGE_ITEM * (--n), sizeof it);
        const double *tri = it, *pq = it + 9;
        int has_pq = !isnan(pq[0]);
        if (has_pq) {
            double b = max_corner_dist(tri, pq);
            if (b <= tau) {
                if (b > ub) ub = b;
                continue;
            }
        }
        double g[3];
        for (int k = 0; k < 3; k++) g[k] = (tri[k] + tri[3 + k] + tri[6 + k]) / 3.0;
        if (++*queries > MERGE_MAX_QUERIES) return INFINITY;
        /* search limit: the distance is 1-Lipschitz, so the previous piece's distance bounds this
         * one's, and so does the parent's point (margins far above the rounding of the
         * closest-point computation) */
        double lim = fmin(tau, (prev_d + len3(g, prev_g)) * (1 + 1e-9) + MERGE_WARM_SLACK_REL * tau);
        double q[3], dq = INFINITY;
        if (has_pq) {
            dq = len3(g, pq);
            lim = fmin(lim, dq * (1 + 1e-9) + MERGE_WARM_SLACK_REL * tau);
        }
        double d = dist_groups(A, B, g, lim, q);
        if (!(d <= dq) && has_pq) { /* nothing nearer than the parent's point was found */
            d = dq;
            memcpy(q, pq, sizeof q);
        }
        if (!(d <= tau)) return INFINITY;
        prev_d = d;
        memcpy(prev_g, g, sizeof prev_g);
        double b = max_corner_dist(tri, q);
        if (b <= tau) {
            if (b > ub) ub = b;
            continue;
        }
        double r = fmax(len3(g, tri), fmax(len3(g, tri + 3), len3(g, tri + 6)));
        if (r < MERGE_MIN_RADIUS_REL * tau) return INFINITY;
        if (n + 4 > cap) {
            double *ns = realloc(stack, 2 * cap * MERGE_ITEM * sizeof *ns);
            if (!ns) return INFINITY;
            stack = *stackp = ns;
            cap = *capp = 2 * cap;
        }
        double m[9]; /* midpoints ab, bc, ca */
        for (int k = 0; k < 3; k++) {
            m[k] = 0.5 * (tri[k] + tri[3 + k]);
            m[3 + k] = 0.5 * (tri[3 + k] + tri[6 + k]);
            m[6 + k] = 0.5 * (tri[6 + k] + tri[k]);
        }
        const double *sub[4][3] = {{tri, m, m + 6}, {m, tri + 3, m + 3}, {m + 6, m + 3, tri + 6}, {m, m + 3, m + 6}};
        for (int s = 0; s < 4; s++) {
            for (int k = 0; k < 3; k++) memcpy(stack + MERGE_ITEM * n + 3 * k, sub[s][k], sizeof(double[3]));
            memcpy(stack + MERGE_ITEM * n + 9, q, sizeof q);
            n++;
        }
    }
    return ub;
}

/* Bounds of the facets of H (the hull of A u B; B may be NULL) into key (9 per facet) and ub;
 * the facets A or B bounded already reuse their bound (a bound of the distance to A alone bounds
 * the distance to A u B). Returns the largest bound, INFINITY as soon as one is above tau
 * (stop_early) or on failure. */
static double hull_facets_ub(const group *A, const group *B, const acd_hull *H, double tau, int stop_early, double *key,
                             double *ub) {
    size_t cap = 256, queries = 0;
    double *stack = malloc(cap * MERGE_ITEM * sizeof *stack);
    if (!stack) return INFINITY;
    double worst = 0;
    for (size_t t = 0; t < H->ntriangles; t++) {
        double *k9 = key + 9 * t;
        facet_key(H, t, k9);
        double u = cached_ub(A, k9);
        if (B) u = fmin(u, cached_ub(B, k9));
        if (!(u <= tau)) {
            double tri[9];
            for (int k = 0; k < 3; k++) memcpy(tri + 3 * k, H->vertices + 3 * (size_t)H->triangles[3 * t + k], sizeof(double[3]));
            u = facet_ub(A, B, tri, tau, &queries, &stack, &cap);
        }
        ub[t] = u;
        if (u > worst) worst = u;
        if (stop_early && !(worst <= tau)) break;
    }
    free(stack);
    return worst;
}

typedef struct facet_rec {
    double key[9];
    double ub;
} facet_rec;

static int cmp_facet_rec(const void *a, const void *b) {
    return cmp_facet(((const facet_rec *)a)->key, ((const facet_rec *)b)->key);
}

/* Sorts a facet table (key: 9 per facet, ub) by key. */
static int sort_facets(double *key, double *ub, size_t nf) {
    facet_rec *fr = malloc((nf ? nf : 1) * sizeof *fr);
    if (!fr) return 0;
    for (size_t t = 0; t < nf; t++) {
        memcpy(fr[t].key, key + 9 * t, sizeof fr[t].key);
        fr[t].ub = ub[t];
    }
    qsort(fr, nf, sizeof *fr, cmp_facet_rec);
    for (size_t t = 0; t < nf; t++) {
        memcpy(key + 9 * t, fr[t].key, sizeof fr[t].key);
        ub[t] = fr[t].ub;
    }
    free(fr);
    return 1;
}

/* g's facet table from its hull H (one part: A = g, B = NULL). */
static int set_facets(group *g, const group *A, const group *B, const acd_hull *H, double tau) {
    size_t nf = H->ntriangles;
    double *key = malloc((nf ? nf : 1) * 9 * sizeof *key), *ub = malloc((nf ? nf : 1) * sizeof *ub);
    if (!key || !ub) {
        free(key), free(ub);
        return 0;
    }
    hull_facets_ub(A, B, H, tau, 0, key, ub);
    if (!sort_facets(key, ub, nf)) {
        free(key), free(ub);
        return 0;
    }
    g->ft = key;
    g->fub = ub;
    g->nft = nf;
    return 1;
}

/* Scores the union of A and B (merge.h): ok and cost = max(d_in, bound of d_out). */
static void score(const group *A, const group *B, double tau, int by_volume, pair *out) {
    out->ok = 0;
    out->cost = INFINITY;
    acd_hull H;
    if (!joint_hull(A, B, &H)) return;
    size_t start = 0;
    double din = depth_in_hull(A, &H, 0.0, tau, &start);
    if (din <= tau) din = depth_in_hull(B, &H, din, tau, &start);
    double dout = INFINITY, *key = NULL, *ub = NULL;
    size_t nf = H.ntriangles;
    double hvol = H.volume;
    if (din <= tau) {
        key = malloc((nf ? nf : 1) * 9 * sizeof *key);
        ub = malloc((nf ? nf : 1) * sizeof *ub);
        if (key && ub) dout = hull_facets_ub(A, B, &H, tau, 1, key, ub);
    }
    acd_hull_free(&H);
    if (!(din <= tau) || !(dout <= tau) || !sort_facets(key, ub, nf)) {
        free(key);
        free(ub);
        return;
    }
    out->ok = 1;
    out->bound = fmax(din, dout);
    out->cost = by_volume ? hvol - A->hvol - B->hvol : out->bound;
    out->ft = key;
    out->fub = ub;
    out->nft = nf;
}

static int add_adj(group *g, uint32_t x) {
    for (size_t i = 0; i < g->nadj; i++)
        if (g->adj[i] == x) return 1;
    uint32_t *na = realloc(g->adj, (g->nadj + 1) * sizeof *na);
    if (!na) return 0;
    g->adj = na;
    size_t i = g->nadj++;
    while (i > 0 && g->adj[i - 1] > x) {
        g->adj[i] = g->adj[i - 1];
        i--;
    }
    g->adj[i] = x;
    return 1;
}

static void remove_adj(group *g, uint32_t x) {
    size_t j = 0;
    for (size_t i = 0; i < g->nadj; i++)
        if (g->adj[i] != x) g->adj[j++] = g->adj[i];
    g->nadj = j;
}

typedef struct vpos {
    double p[3];
    uint32_t part;
} vpos;

static int cmp_vpos(const void *x, const void *y) {
    const vpos *a = x, *b = y;
    for (int k = 0; k < 3; k++)
        if (a->p[k] != b->p[k]) return a->p[k] < b->p[k] ? -1 : 1;
    return (a->part > b->part) - (a->part < b->part);
}

typedef struct shared {
    uint32_t a, b, pos; /* parts a < b share the position of entry pos */
} shared;

static int cmp_shared(const void *x, const void *y) {
    const shared *a = x, *b = y;
    if (a->a != b->a) return a->a < b->a ? -1 : 1;
    if (a->b != b->b) return a->b < b->b ? -1 : 1;
    return (a->pos > b->pos) - (a->pos < b->pos);
}

/* Adjacent part pairs (three non-collinear shared vertex positions) as adjacency lists. */
static acd_status adjacency(const acd_mesh *parts, size_t nparts, group *G, double tol, acd_error *err) {
    size_t nv = 0;
    for (size_t i = 0; i < nparts; i++) nv += parts[i].nvertices;
    vpos *vp = malloc((nv ? nv : 1) * sizeof *vp);
    if (!vp) return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for %zu vertices", nv);
    size_t k = 0;
    for (size_t i = 0; i < nparts; i++)
        for (size_t v = 0; v < parts[i].nvertices; v++) {
            memcpy(vp[k].p, parts[i].vertices + 3 * v, sizeof(double[3]));
            vp[k++].part = (uint32_t)i;
        }
    qsort(vp, nv, sizeof *vp, cmp_vpos);
    size_t ns = 0, caps = 0;
    shared *sh = NULL;
    for (size_t i = 0; i < nv;) {
        size_t j = i;
        while (j < nv && !memcmp(vp[j].p, vp[i].p, sizeof(double[3]))) j++;
        for (size_t x = i; x < j; x++)
            for (size_t y = x + 1; y < j; y++) {
                if (vp[x].part == vp[y].part) continue;
                if (ns == caps) {
                    caps = caps ? 2 * caps : 1024;
                    shared *n2 = realloc(sh, caps * sizeof *n2);
                    if (!n2) {
                        free(sh);
                        free(vp);
                        return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for shared vertices");
                    }
                    sh = n2;
                }
                sh[ns++] = (shared){vp[x].part, vp[y].part, (uint32_t)i};
            }
        i = j;
    }
    if (ns) qsort(sh, ns, sizeof *sh, cmp_shared);
    acd_status st = ACD_OK;
    for (size_t i = 0; i < ns && st == ACD_OK;) {
        size_t j = i;
        while (j < ns && sh[j].a == sh[i].a && sh[j].b == sh[i].b) j++;
        /* three positions spanning a triangle of height > tol */
        const double *p0 = vp[sh[i].pos].p, *p1 = NULL;
        int found = 0;
        for (size_t x = i + 1; x < j && !found; x++) {
            const double *q = vp[sh[x].pos].p;
            if (!p1) {
                if (len3(p0, q) > tol) p1 = q;
                continue;
            }
            double u[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, w[3] = {q[0] - p0[0], q[1] - p0[1], q[2] - p0[2]};
            double c[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
            if (sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) > tol * sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]))
                found = 1;
        }
        if (found && (!add_adj(&G[sh[i].a], sh[i].b) || !add_adj(&G[sh[i].b], sh[i].a)))
            st = acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for adjacency");
        i = j;
    }
    free(sh);
    free(vp);
    return st;
}

/* Scores pairs [p0, p1) (independently: any thread count gives the same scores). */
static void score_pairs(group *G, pair *P, size_t p0, size_t p1, double tau, int by_volume, int threads) {
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && p1 - p0 > 1)
#endif
    for (long i = (long)p0; i < (long)p1; i++) score(&G[P[i].a], &G[P[i].b], tau, by_volume, &P[i]);
    (void)threads;
}

static acd_status group_init_hull(group *g, const double *pts, size_t n, double tau, acd_error *err) {
    acd_hull h;
    acd_status st = acd_hull_compute(pts, n, &h, err);
    if (st != ACD_OK) return st;
    if (h.dim == 3 && !set_facets(g, g, NULL, &h, tau)) {
        acd_hull_free(&h);
        return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for a hull's facets");
    }
    g->hv = h.vertices;
    g->nhv = h.nvertices;
    g->hvol = h.dim == 3 ? h.volume : 0;
    h.vertices = NULL;
    acd_hull_free(&h);
    return ACD_OK;
}

/* G[c] = G[a] u G[b]. */
static acd_status join(group *G, pair *pr, uint32_t c, acd_error *err) {
    uint32_t a = pr->a, b = pr->b;
    double bound = pr->bound;
    group *A = &G[a], *B = &G[b], *C = &G[c];
    memset(C, 0, sizeof *C);
    acd_hull H;
    if (!joint_hull(A, B, &H)) return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for a joined hull");
    /* the facet table the pair's score made (the same hull) */
    C->ft = pr->ft;
    C->fub = pr->fub;
    C->nft = pr->nft;
    pr->ft = pr->fub = NULL;
    C->hv = H.vertices;
    C->nhv = H.nvertices;
    C->hvol = H.volume;
    H.vertices = NULL;
    acd_hull_free(&H);
    C->nsv = A->nsv + B->nsv;
    C->sv = malloc((C->nsv ? C->nsv : 1) * 3 * sizeof(double));
    C->nmembers = A->nmembers + B->nmembers;
    C->members = malloc(C->nmembers * sizeof *C->members);
    if (!C->sv || !C->members) return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory joining parts");
    memcpy(C->sv, A->sv, 3 * A->nsv * sizeof(double));
    memcpy(C->sv + 3 * A->nsv, B->sv, 3 * B->nsv * sizeof(double));
    memcpy(C->members, A->members, A->nmembers * sizeof *C->members);
    memcpy(C->members + A->nmembers, B->members, B->nmembers * sizeof *C->members);
    C->pbvh = A->pbvh;
    for (int s = 0; s < 2; s++) {
        group *S = s ? B : A;
        for (size_t i = 0; i < S->nadj; i++) {
            uint32_t x = S->adj[i];
            if (x == a || x == b) continue;
            remove_adj(&G[x], a);
            remove_adj(&G[x], b);
            if (!add_adj(&G[x], c) || !add_adj(C, x)) return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for adjacency");
        }
    }
    C->bound = bound;
    C->alive = 1;
    /* the joined groups' data are no longer needed */
    uint32_t *ma = A->members, *mb = B->members;
    A->members = B->members = NULL;
    group_free(A);
    group_free(B);
    free(ma);
    free(mb);
    return ACD_OK;
}

static acd_status push_pair(pair **P, size_t *np, size_t *cap, uint32_t a, uint32_t b, acd_error *err) {
    if (*np == *cap) {
        size_t nc = *cap ? 2 * *cap : 256;
        pair *n2 = realloc(*P, nc * sizeof *n2);
        if (!n2) return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for pairs");
        *P = n2;
        *cap = nc;
    }
    (*P)[(*np)++] = (pair){a < b ? a : b, a < b ? b : a, 0, INFINITY, INFINITY, NULL, NULL, 0};
    return ACD_OK;
}

acd_status acd3_merge_adjacent(const acd_mesh *input, const acd_mesh *parts, size_t nparts, double tau, double tol,
                               const acd3_merge_opts *opts, int threads, acd3_merge_result *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    const int by_volume = opts && opts->by_volume;
    const size_t stop_at = opts ? opts->stop_at : 0;
    if (threads < 1) threads = 1;
    if (!(tau > 0) || nparts < 2 || (stop_at && nparts <= stop_at)) { /* tau 0: only a convex union could be joined; not searched */
        out->group_of = malloc((nparts ? nparts : 1) * sizeof *out->group_of);
        out->group_size = malloc((nparts ? nparts : 1) * sizeof *out->group_size);
        out->bound = calloc(nparts ? nparts : 1, sizeof *out->bound);
        if (!out->group_of || !out->group_size || !out->bound) {
            acd3_merge_result_free(out);
            return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for %zu parts", nparts);
        }
        for (size_t i = 0; i < nparts; i++) {
            out->group_of[i] = (uint32_t)i;
            out->group_size[i] = 1;
        }
        out->ngroups = nparts;
        return ACD_OK;
    }
    size_t ng = 0, capg = 2 * nparts + 1;
    group *G = calloc(capg, sizeof *G);
    pair *P = NULL;
    size_t np = 0, capp = 0;
    acd_bvh in_bvh;
    memset(&in_bvh, 0, sizeof in_bvh);
    acd_bvh *pbvh = calloc(nparts, sizeof *pbvh);
    out->group_of = malloc((nparts ? nparts : 1) * sizeof *out->group_of);
    if (!G || !out->group_of || !pbvh) {
        free(G);
        free(pbvh);
        acd3_merge_result_free(out);
        return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for %zu parts", nparts);
    }
    acd_status st = acd_bvh_build(&in_bvh, input->vertices, input->nvertices, input->triangles, input->ntriangles, err);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < input->nvertices; v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], input->vertices[3 * v + k]);
            hi[k] = fmax(hi[k], input->vertices[3 * v + k]);
        }
    double on_tol = MERGE_ON_SURFACE_REL * len3(lo, hi);
    /* one group per part (independently: in parallel) */
    ng = nparts;
    acd_status *gst = calloc(nparts ? nparts : 1, sizeof *gst);
    acd_error *gerr = calloc(nparts ? nparts : 1, sizeof *gerr);
    if (st == ACD_OK && (!gst || !gerr)) st = acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for %zu parts", nparts);
    if (st == ACD_OK) {
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nparts > 1)
#endif
        for (long li = 0; li < (long)nparts; li++) {
            size_t i = (size_t)li;
            group *g = &G[i];
            g->alive = 1;
            g->nmembers = 1;
            g->members = malloc(sizeof *g->members);
            g->sv = malloc((parts[i].nvertices ? parts[i].nvertices : 1) * 3 * sizeof(double));
            if (!g->members || !g->sv) {
                gst[i] = acd_fail(&gerr[i], ACD_ERR_NOMEM, "merge: out of memory for part %zu", i);
                continue;
            }
            g->members[0] = (uint32_t)i;
            for (size_t v = 0; v < parts[i].nvertices; v++) {
                acd_bvh_closest_result q;
                const double *p = parts[i].vertices + 3 * v;
                if (acd_bvh_closest(&in_bvh, p, on_tol * on_tol, &q)) memcpy(g->sv + 3 * g->nsv++, p, sizeof(double[3]));
            }
            g->pbvh = pbvh;
            acd_status s2 = acd_bvh_build(&pbvh[i], parts[i].vertices, parts[i].nvertices, parts[i].triangles,
                                          parts[i].ntriangles, &gerr[i]);
            if (s2 == ACD_OK) s2 = group_init_hull(g, parts[i].vertices, parts[i].nvertices, tau, &gerr[i]);
            gst[i] = s2;
        }
        for (size_t i = 0; i < nparts; i++)
            if (gst[i] != ACD_OK) {
                st = gst[i];
                if (err) *err = gerr[i];
                break;
            }
    }
    free(gst);
    free(gerr);
    acd_bvh_free(&in_bvh);
    if (st == ACD_OK) st = adjacency(parts, nparts, G, tol, err);
    for (size_t i = 0; i < nparts && st == ACD_OK; i++)
        for (size_t k = 0; k < G[i].nadj && st == ACD_OK; k++)
            if (G[i].adj[k] > i) st = push_pair(&P, &np, &capp, (uint32_t)i, G[i].adj[k], err);
    if (st == ACD_OK) score_pairs(G, P, 0, np, tau, by_volume, threads);
    /* greedy: the cheapest joinable pair of live groups, ties by the lower ids */
    size_t nlive = nparts;
    while (st == ACD_OK && nlive > stop_at) {
        size_t best = SIZE_MAX, w = 0;
        for (size_t i = 0; i < np; i++) {
            if (!G[P[i].a].alive || !G[P[i].b].alive) {
                pair_free(&P[i]);
                continue;
            }
            P[w++] = P[i];
            if (!P[w - 1].ok) continue;
            if (best == SIZE_MAX || P[w - 1].cost < P[best].cost) best = w - 1;
        }
        np = w;
        if (best == SIZE_MAX) break;
        uint32_t c = (uint32_t)ng++;
        st = join(G, &P[best], c, err);
        if (st != ACD_OK) break;
        out->merges++;
        nlive--;
        size_t p0 = np;
        for (size_t k = 0; k < G[c].nadj && st == ACD_OK; k++) st = push_pair(&P, &np, &capp, G[c].adj[k], c, err);
        if (st == ACD_OK) score_pairs(G, P, p0, np, tau, by_volume, threads);
    }
    if (st == ACD_OK) {
        /* groups numbered by their lowest part */
        uint32_t *num = malloc(ng * sizeof *num);
        out->group_size = calloc(nparts ? nparts : 1, sizeof *out->group_size);
        out->bound = calloc(nparts ? nparts : 1, sizeof *out->bound);
        uint32_t *owner = malloc((nparts ? nparts : 1) * sizeof *owner);
        if (!num || !out->group_size || !out->bound || !owner) {
            st = acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory");
        } else {
            for (size_t g = 0; g < ng; g++) {
                num[g] = UINT32_MAX;
                if (G[g].alive)
                    for (size_t m = 0; m < G[g].nmembers; m++) owner[G[g].members[m]] = (uint32_t)g;
            }
            for (size_t i = 0; i < nparts; i++) {
                uint32_t g = owner[i];
                if (num[g] == UINT32_MAX) {
                    num[g] = (uint32_t)out->ngroups++;
                    out->bound[num[g]] = G[g].nmembers > 1 ? G[g].bound : 0.0;
                }
                out->group_of[i] = num[g];
                out->group_size[num[g]]++;
            }
        }
        free(num);
        free(owner);
    }
    for (size_t g = 0; g < ng; g++) group_free(&G[g]);
    for (size_t i = 0; i < nparts; i++) acd_bvh_free(&pbvh[i]);
    free(pbvh);
    for (size_t i = 0; i < np; i++) pair_free(&P[i]);
    free(G);
    free(P);
    if (st != ACD_OK) acd3_merge_result_free(out);
    return st;
}

double acd3_merge_hull_reach(const acd_bvh *part, const acd_hull *H, double tau) {
    if (H->dim != 3) return INFINITY;
    size_t nf = H->ntriangles;
    double *key = malloc((nf ? nf : 1) * 9 * sizeof *key), *ub = malloc((nf ? nf : 1) * sizeof *ub);
    double worst = INFINITY;
    if (key && ub) {
        uint32_t member = 0;
        group g;
        memset(&g, 0, sizeof g);
        g.pbvh = part;
        g.members = &member;
        g.nmembers = 1;
        worst = hull_facets_ub(&g, NULL, H, tau, 1, key, ub);
    }
    free(key);
    free(ub);
    return worst;
}
