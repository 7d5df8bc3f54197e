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
#include "core/u32vec.h"
#include "core/union_find.h"
#include "acd3/poll.h"
#include "acd3/volume_plane.h"
#include "geom3/bvh.h"
#include "geom3/plane_cut.h"
#include "geom3/volume.h"
#include "geom3/vec3.h"

/* Closest-point queries allowed when scoring one pair; a pair needing more is refused. */
#define MERGE_MAX_QUERIES 100000
/* Closest-point queries after which a facet's bound switches from the closest point to its
 * triangle (facet_ub; at most 363 on the target meshes at their settings, so their bounds are the
 * point bound's). */
#define MERGE_FACET_POINT_QUERIES 1000
/* Hull pieces are not subdivided below this fraction of tau: such a piece (its centroid within
 * tau of the part but its bound above tau) refuses the pair. */
#define MERGE_MIN_RADIUS_REL 1e-3
/* A vertex is on the input surface when within this fraction of the input's bounding-box
 * diagonal of it (cut vertices are interpolated on input edges: off by rounding only). */
#define MERGE_ON_SURFACE_REL 1e-9
/* A pair refused for a surface vertex deeper than tau in its joint hull refuses the pairs of the
 * joined group too (the depth of a point inside a convex set only grows with the set), when the depth
 * found exceeded tau by this fraction of the input's bounding-box diagonal (far above the rounding of
 * the hulls' planes and of the hull vertices kept). */
#define MERGE_DEPTH_SLACK_REL 1e-9

/* Without a stop (acd3_merge_opts.stop_at 0), a pair whose joint hull adds more than this fraction of
 * the input's volume to the two hulls is refused (merge.h, "the added volume"): such a join costs
 * about as much IoU, for one part fewer. The largest join on the six target meshes at their default
 * settings adds 0.011 (fandisk); GEB's that undid the tree's split 0.156, animation's 0.276. */
#define MERGE_MAX_ADDED_REL 0.02

/* The atoms the groups are made of: the input parts, then the pieces the refinement cuts. */
typedef struct atoms {
    size_t n, cap;
    acd_mesh *mesh; /* shallow copies of the input parts (i < nparts), owned pieces beyond */
    acd_bvh *bvh;
    unsigned char *bvh_kept; /* the caller's tree (acd3_merge_kept.bvh), read only: not freed */
    double *vol;
    double **sv; /* its vertices on the input surface */
    size_t *nsv;
    uint32_t **adj; /* adjacent atoms, increasing */
    size_t *nadj;
    uint32_t *owner; /* its live group; UINT32_MAX once cut */
    uint32_t *parent; /* pieces: the atom cut */
    double (*plane)[4]; /* pieces: the parent's cut plane */
    double max_added;   /* a pair whose joint hull adds more volume is refused (merge.h; INFINITY: none) */
} atoms;

typedef struct group {
    int alive;
    double *hv; /* hull vertices */
    size_t nhv;
    double *sv; /* vertices on the input surface */
    size_t nsv;
    const atoms *at; /* the atoms (shared), indexed by members[] */
    uint32_t *adj; /* adjacent live groups, increasing */
    size_t nadj;
    uint32_t *members;
    size_t nmembers;
    double bound;
    double hvol; /* its hull's volume (0 when flat) */
    double *ft;  /* its hull's facets: 9 coordinates each, corners in canonical order, sorted */
    double *fub; /* per facet: an upper bound of the distance from its points to the group (> tau: not bounded) */
    size_t nft;
    double vol;      /* the members' volume */
    int est;         /* refinement: 0 its volume plane not searched yet, 1 searched, 2 its cut refused, 3 searched
                        but its saving not measured (est_ub bounds it) */
    double est_gain; /* the hull volume its volume plane saves (the plane found on a sample, its saving on every vertex) */
    double est_ub;   /* est 3: an upper bound of est_gain (from the sample's score) */
    acd3_plane_candidate est_plane;
} group;

typedef struct pair {
    uint32_t a, b; /* a < b */
    int ok;
    double cost;  /* the order: the bound, or (by_volume) the hull volume the join adds */
    double bound; /* max(d_in, bound of d_out) */
    double *ft, *fub; /* ok: the joined hull's facet table (as group.ft, fub), for the join */
    size_t nft;
    double *hv; /* ok: the joined hull's vertices and volume, for the join */
    size_t nhv;
    double hvol;
    double din_lo; /* refused by d_in: a lower bound of d_in (> tau), else 0 */
    int pend;      /* by_volume: d_in within tau, d_out not bounded yet (finish_pair); H kept */
    acd_hull H;
    double din;
    int est;          /* refinement: as group.est, for the cut of the pair's union */
    double est_gain;  /* the hull volume that cut saves against the pair's two hulls (as group.est_gain) */
    double est_ub;    /* as group.est_ub */
    acd3_plane_candidate est_plane;
} pair;

static void pair_free(pair *p) {
    if (p->pend) acd_hull_free(&p->H);
    p->pend = 0;
    free(p->ft);
    free(p->fub);
    free(p->hv);
    p->ft = p->fub = p->hv = NULL;
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
    for (size_t k = 0; k < r->nnew; k++) acd_mesh_free(&r->new_parts[k]);
    free(r->new_parts);
    free(r->new_parent);
    free(r->new_plane);
    free(r->new_volume);
    acd_bvh_free(&r->input_bvh);
    for (size_t i = 0; i < r->npart_bvh; i++) acd_bvh_free(&r->part_bvh[i]);
    free(r->part_bvh);
    memset(r, 0, sizeof *r);
}

/* Distance from p to the members' triangles, if below lim (else lim or more); q: the closest point
 * found and tri the corners of its triangle (untouched when none within lim). */
static double dist_group(const group *g, const double p[3], double lim, double q[3], double tri[9]) {
    double d = INFINITY;
    for (size_t m = 0; m < g->nmembers; m++) {
        acd_bvh_closest_result r;
        double l = d < lim ? d : lim;
        const acd_bvh *bvh = &g->at->bvh[g->members[m]];
        if (acd_bvh_closest(bvh, p, l * l, &r) && sqrt(r.dist2) < d) {
            d = sqrt(r.dist2);
            memcpy(q, r.point, sizeof r.point);
            for (int k = 0; k < 3; k++)
                memcpy(tri + 3 * k, bvh->vertices + 3 * (size_t)bvh->triangles[3 * (size_t)r.triangle + k],
                       sizeof(double[3]));
        }
    }
    return d;
}

static double dist_groups(const group *A, const group *B, const double p[3], double lim, double q[3], double tri[9]) {
    double d = dist_group(A, p, lim, q, tri);
    if (B) {
        double e = dist_group(B, p, d < lim ? d : lim, q, tri);
        if (e < d) d = e;
    }
    return d;
}

/* Moves hull H's vertices to *hv, *nhv (a group's or a pair's record) and frees the rest of H. */
static void take_hull_vertices(acd_hull *H, double **hv, size_t *nhv) {
    *hv = H->vertices;
    *nhv = H->nvertices;
    H->vertices = NULL;
    acd_hull_free(H);
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
    return fmax(acd_dist3(tri, q), fmax(acd_dist3(tri + 3, q), acd_dist3(tri + 6, q)));
}

/* Largest distance from the corners of piece to the triangle t. */
static double max_corner_dist_tri(const double piece[9], const double t[9]) {
    double q[3], m = 0;
    for (int k = 0; k < 3; k++) m = fmax(m, acd_closest_point_triangle(piece + 3 * k, t, t + 3, t + 6, q));
    return sqrt(m); /* (squared distances) */
}

/* An upper bound of the distance from the points of triangle tri to A u B (B may be NULL). For a
 * point q of A u B, every point of a triangle is within max_k |v_k - q| of q (|x - q| is convex,
 * its maximum on the triangle is at a corner). The triangle is subdivided (midpoints, 4 children)
 * until every piece has such a point within tau of all its corners: first the point its parent
 * found (no query), else the closest point q of A u B to its centroid g. Since
 * max_k |v_k - q| <= dist(g) + r (r: the piece's circumradius), this bound is never looser than
 * the Lipschitz one. A facet that takes more than MERGE_FACET_POINT_QUERIES queries so (the point
 * bound needs pieces of radius about sqrt(tau^2 - d^2) where the distance d nears tau: thousands
 * of queries on a large facet at a small tau) bounds its remaining pieces by the triangle T of
 * A u B that q lies on: max_k dist(v_k, T), as convex and never above max_k |v_k - q|, and flat
 * where the part is (a piece parallel to T needs no subdivision). Returns INFINITY when a
 * centroid is farther than tau, the query budget runs out or pieces get too small. Stack items:
 * the piece's corners (9), the parent's point (3; NaN for none) and its triangle (9). */
#define MERGE_WARM_SLACK_REL 1e-9
#define MERGE_ITEM 21
static double facet_ub(const group *A, const group *B, const double tri0[9], double tau, size_t *queries,
                       double **stackp, size_t *capp) {
    double *stack = *stackp;
    size_t n = 1, cap = *capp, q0 = *queries;
    memcpy(stack, tri0, 9 * sizeof *stack);
    for (int k = 9; k < MERGE_ITEM; k++) stack[k] = NAN;
    double ub = 0, prev_d = INFINITY, prev_g[3] = {0, 0, 0};
    while (n) {
        double it[MERGE_ITEM];
        memcpy(it, stack + MERGE_ITEM * (--n), sizeof it);
        const double *tri = it, *pq = it + 9, *pt = it + 12;
        int has_pq = !isnan(pq[0]), by_tri = *queries - q0 > MERGE_FACET_POINT_QUERIES;
        if (has_pq) {
            double b = by_tri ? max_corner_dist_tri(tri, pt) : max_corner_dist(tri, pq);
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
        double lim = fmin(tau, (prev_d + acd_dist3(g, prev_g)) * (1 + 1e-9) + MERGE_WARM_SLACK_REL * tau);
        double q[3], t[9], pg[3], dq = INFINITY;
        if (has_pq) { /* the parent's point, or (by_tri) its triangle's point closest to g */
            if (by_tri) dq = sqrt(acd_closest_point_triangle(g, pt, pt + 3, pt + 6, pg));
            else dq = acd_dist3(g, pq), memcpy(pg, pq, sizeof pg);
            lim = fmin(lim, dq * (1 + 1e-9) + MERGE_WARM_SLACK_REL * tau);
        }
        double d = dist_groups(A, B, g, lim, q, t);
        if (!(d <= dq) && has_pq) { /* nothing nearer than the parent's point was found */
            d = dq;
            memcpy(q, pg, sizeof q);
            memcpy(t, pt, sizeof t);
        }
        if (!(d <= tau)) return INFINITY;
        prev_d = d;
        memcpy(prev_g, g, sizeof prev_g);
        double b = by_tri ? max_corner_dist_tri(tri, t) : max_corner_dist(tri, q);
        if (b <= tau) {
            if (b > ub) ub = b;
            continue;
        }
        double r = fmax(acd_dist3(g, tri), fmax(acd_dist3(g, tri + 3), acd_dist3(g, tri + 6)));
        if (r < MERGE_MIN_RADIUS_REL * tau) return INFINITY;
        if (n + 4 > cap) {
            double *ns = realloc(stack, 2 * cap * MERGE_ITEM * sizeof *ns);
            if (!ns) return INFINITY;
            stack = *stackp = ns;
            cap = *capp = 2 * cap;
        }
        double sub[4][9];
        acd_tri_split4(tri, sub);
        for (int s = 0; s < 4; s++) {
            memcpy(stack + MERGE_ITEM * n, sub[s], sizeof sub[s]);
            memcpy(stack + MERGE_ITEM * n + 9, q, sizeof q);
            memcpy(stack + MERGE_ITEM * n + 12, t, sizeof t);
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

/* The facet table of H, the hull of A u B (B may be NULL): *worst = hull_facets_ub's largest bound,
 * and the table (H->ntriangles facets, sorted by key) in *ft, *fub — with stop_early only when
 * *worst <= tau, else *ft = *fub = NULL. Returns 0 out of memory (nothing kept). */
static int facet_table(const group *A, const group *B, const acd_hull *H, double tau, int stop_early, double *worst,
                       double **ft, double **fub) {
    size_t nf = H->ntriangles;
    double *key = malloc((nf ? nf : 1) * 9 * sizeof *key), *ub = malloc((nf ? nf : 1) * sizeof *ub);
    *ft = *fub = NULL;
    if (!key || !ub) {
        free(key), free(ub);
        return 0;
    }
    *worst = hull_facets_ub(A, B, H, tau, stop_early, key, ub);
    if (stop_early && !(*worst <= tau)) {
        free(key), free(ub);
        return 1;
    }
    if (!sort_facets(key, ub, nf)) {
        free(key), free(ub);
        return 0;
    }
    *ft = key;
    *fub = ub;
    return 1;
}

/* The pair's d_out bounded on its hull H (score's second half): ok when within tau. */
static void score_dout(const group *A, const group *B, double tau, int by_volume, acd_hull *H, double din, pair *out) {
    double dout = INFINITY, *key = NULL, *ub = NULL;
    if (!facet_table(A, B, H, tau, 1, &dout, &key, &ub)) dout = INFINITY;
    if (!(dout <= tau)) {
        free(key);
        free(ub);
        acd_hull_free(H);
        out->ok = 0;
        out->cost = INFINITY;
        return;
    }
    out->hvol = H->volume;
    out->nft = H->ntriangles;
    take_hull_vertices(H, &out->hv, &out->nhv);
    out->ok = 1;
    out->bound = fmax(din, dout);
    out->cost = by_volume ? out->hvol - A->hvol - B->hvol : out->bound;
    out->ft = key;
    out->fub = ub;
}

/* Scores the union of A and B (merge.h): ok and cost = max(d_in, bound of d_out). A pair whose
 * din_lo is above din_refuse (inherited, join_best) is refused without a hull, one whose joint hull
 * adds more than at->max_added to the two hulls' volume after d_in (not inherited: a larger group can
 * add less; checked after d_in so that a depth above tau is still found and inherited). By volume, the cost
 * (the hull volume the join adds) does not depend on d_out: a pair within tau by d_in is left
 * pending (its hull kept), its d_out bounded when it comes up as the cheapest (finish_pair): the
 * same choices, without the facet bounds of the pairs never chosen. */
static void score(const group *A, const group *B, double tau, double din_refuse, int by_volume, pair *out) {
    out->ok = 0;
    out->cost = INFINITY;
    if (out->din_lo > din_refuse) return;
    acd_hull H;
    if (!joint_hull(A, B, &H)) return;
    size_t start = 0;
    double din = depth_in_hull(A, &H, 0.0, tau, &start);
    if (din <= tau) din = depth_in_hull(B, &H, din, tau, &start);
    if (!(din <= tau) || H.volume - A->hvol - B->hvol > A->at->max_added) {
        if (!(din <= tau)) out->din_lo = din; /* (inherited by the joined groups' pairs: join_best) */
        acd_hull_free(&H);
        return;
    }
    if (by_volume) {
        out->pend = 1;
        out->H = H;
        out->din = din;
        out->cost = H.volume - A->hvol - B->hvol;
        return;
    }
    score_dout(A, B, tau, by_volume, &H, din, out);
}

/* A pending pair's d_out (score): ok or refused. */
static void finish_pair(const group *G, pair *p, double tau) {
    if (!p->pend) return;
    p->pend = 0;
    acd_hull H = p->H;
    memset(&p->H, 0, sizeof p->H);
    score_dout(&G[p->a], &G[p->b], tau, 1, &H, p->din, p);
}

static int adj_add(uint32_t **adj, size_t *n, uint32_t x) {
    for (size_t i = 0; i < *n; i++)
        if ((*adj)[i] == x) return 1;
    uint32_t *na = realloc(*adj, (*n + 1) * sizeof *na);
    if (!na) return 0;
    *adj = na;
    size_t i = (*n)++;
    while (i > 0 && na[i - 1] > x) {
        na[i] = na[i - 1];
        i--;
    }
    na[i] = x;
    return 1;
}

static int add_adj(group *g, uint32_t x) {
    return adj_add(&g->adj, &g->nadj, x);
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

/* Adjacent pairs (three non-collinear shared vertex positions) among the meshes M[sel[k]] (sel
 * NULL: M[k]), k < n: *pairs gets the local indices a < b of each pair, pairs in increasing order. */
static acd_status adjacent_pairs(const acd_mesh *M, const uint32_t *sel, size_t n, double tol, uint32_t **pairs,
                                 size_t *npairs, acd_error *err) {
    *pairs = NULL;
    *npairs = 0;
    size_t nv = 0;
    for (size_t i = 0; i < n; i++) nv += M[sel ? sel[i] : i].nvertices;
    vpos *vp = malloc((nv ? nv : 1) * sizeof *vp);
    if (!vp) return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for %zu vertices", nv);
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        const acd_mesh *m = &M[sel ? sel[i] : i];
        for (size_t v = 0; v < m->nvertices; v++) {
            memcpy(vp[k].p, m->vertices + 3 * v, sizeof(double[3]));
            vp[k++].part = (uint32_t)i;
        }
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
    size_t capp = 0;
    for (size_t i = 0; i < ns && st == ACD_OK;) {
        size_t j = i;
        while (j < ns && sh[j].a == sh[i].a && sh[j].b == sh[i].b) j++;
        /* three positions spanning a triangle of height > tol */
        const double *p0 = vp[sh[i].pos].p, *p1 = NULL;
        int found = 0;
        for (size_t x = i + 1; x < j && !found; x++) {
            const double *q = vp[sh[x].pos].p;
            if (!p1) {
                if (acd_dist3(p0, q) > tol) p1 = q;
                continue;
            }
            double u[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, w[3] = {q[0] - p0[0], q[1] - p0[1], q[2] - p0[2]};
            double c[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
            if (sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) > tol * sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]))
                found = 1;
        }
        if (found) {
            if (*npairs == capp) {
                capp = capp ? 2 * capp : 256;
                uint32_t *np2 = realloc(*pairs, 2 * capp * sizeof *np2);
                if (!np2) {
                    st = acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for adjacency");
                    break;
                }
                *pairs = np2;
            }
            (*pairs)[2 * *npairs] = sh[i].a;
            (*pairs)[2 * *npairs + 1] = sh[i].b;
            (*npairs)++;
        }
        i = j;
    }
    free(sh);
    free(vp);
    if (st != ACD_OK) {
        free(*pairs);
        *pairs = NULL;
        *npairs = 0;
    }
    return st;
}

/* Scores pairs [p0, p1) (independently: any thread count gives the same scores); din_refuse: as
 * score's. */
static void score_pairs(group *G, pair *P, size_t p0, size_t p1, double tau, double din_refuse, int by_volume,
                        int threads) {
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && p1 - p0 > 1)
#endif
    for (long i = (long)p0; i < (long)p1; i++) score(&G[P[i].a], &G[P[i].b], tau, din_refuse, by_volume, &P[i]);
    (void)threads;
}

/* Whether kept can stand for the hull of the n points pts: each of its vertices is the input point
 * its source names, bit for bit (a hull computed from another point set, or the same points in
 * another order, fails this unless its vertices happen to sit at the same indices; the caller
 * promises the rest: kept is acd_hull_compute of exactly these points, in this order). */
int acd3_kept_hull_matches(const acd_hull *kept, const double *pts, size_t n) {
    if (kept->dim < 0 || (kept->nvertices && (!kept->vertices || !kept->source))) return 0;
    for (size_t v = 0; v < kept->nvertices; v++) {
        uint32_t s = kept->source[v];
        if (s >= n || memcmp(kept->vertices + 3 * v, pts + 3 * (size_t)s, 3 * sizeof *pts) != 0) return 0;
    }
    return 1;
}

/* Whether table can stand for the facet table of H at tau (the caller promises it was made for H over
 * the group's tree: acd3_merge_kept). */
static int kept_table_fits(const acd3_facet_table *table, const acd_hull *H, double tau) {
    return table && table->key && table->ub && H->dim == 3 && table->n == H->ntriangles && table->tau == tau;
}

/* The group's hull data from the hull of its part's n points pts: kept when given (and matching,
 * acd3_kept_hull_matches; read only), else computed (the same qhull run gives the same bits); its
 * facet table copied from table when given for the kept hull (kept_table_fits; the bounds
 * facet_table computes, as every facet of an accepted table is bounded), else computed. */
static acd_status group_init_hull(group *g, const double *pts, size_t n, const acd_hull *kept,
                                  const acd3_facet_table *table, double tau, acd_error *err) {
    acd_hull h;
    const acd_hull *H = &h;
    if (kept && acd3_kept_hull_matches(kept, pts, n)) {
        H = kept;
    } else {
        acd_status st = acd_hull_compute(pts, n, &h, err);
        if (st != ACD_OK) return st;
    }
    double worst;
    if (H == kept && kept_table_fits(table, H, tau)) {
        size_t nf = table->n;
        g->ft = malloc((nf ? nf : 1) * 9 * sizeof *g->ft);
        g->fub = malloc((nf ? nf : 1) * sizeof *g->fub);
        if (!g->ft || !g->fub) return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for a hull's facets");
        memcpy(g->ft, table->key, nf * 9 * sizeof *g->ft);
        memcpy(g->fub, table->ub, nf * sizeof *g->fub);
    } else if (H->dim == 3 && !facet_table(g, NULL, H, tau, 0, &worst, &g->ft, &g->fub)) {
        if (H == &h) acd_hull_free(&h);
        return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for a hull's facets");
    }
    if (H->dim == 3) g->nft = H->ntriangles;
    g->hvol = H->dim == 3 ? H->volume : 0;
    if (H == &h) {
        take_hull_vertices(&h, &g->hv, &g->nhv);
        return ACD_OK;
    }
    g->hv = malloc((H->nvertices ? H->nvertices : 1) * 3 * sizeof *g->hv);
    if (!g->hv) return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for a hull's vertices");
    memcpy(g->hv, H->vertices, 3 * H->nvertices * sizeof *g->hv);
    g->nhv = H->nvertices;
    return ACD_OK;
}

/* G[c] = G[a] u G[b]. */
static acd_status join(group *G, pair *pr, uint32_t c, acd_error *err) {
    uint32_t a = pr->a, b = pr->b;
    double bound = pr->bound;
    group *A = &G[a], *B = &G[b], *C = &G[c];
    memset(C, 0, sizeof *C);
    if (!pr->hv) return acd_fail(err, ACD_ERR_INTERNAL, "merge: a joined pair without its hull");
    /* the hull and facet table the pair's score made */
    C->ft = pr->ft;
    C->fub = pr->fub;
    C->nft = pr->nft;
    C->hv = pr->hv;
    C->nhv = pr->nhv;
    C->hvol = pr->hvol;
    pr->ft = pr->fub = pr->hv = NULL;
    C->nsv = A->nsv + B->nsv;
    C->sv = malloc((C->nsv ? C->nsv : 1) * 3 * sizeof(double));
    C->nmembers = A->nmembers + B->nmembers;
    C->members = malloc(C->nmembers * sizeof *C->members);
    if (!C->sv || !C->members) return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory joining parts");
    memcpy(C->sv, A->sv, 3 * A->nsv * sizeof(double));
    memcpy(C->sv + 3 * A->nsv, B->sv, 3 * B->nsv * sizeof(double));
    memcpy(C->members, A->members, A->nmembers * sizeof *C->members);
    memcpy(C->members + A->nmembers, B->members, B->nmembers * sizeof *C->members);
    C->at = A->at;
    C->vol = A->vol + B->vol;
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
    pair *p = &(*P)[(*np)++];
    memset(p, 0, sizeof *p);
    p->a = a < b ? a : b;
    p->b = a < b ? b : a;
    p->cost = p->bound = INFINITY;
    return ACD_OK;
}

/* Refinement (merge.h, docs/acd3d.md "Hull tightness"). A step must save at least this fraction of
 * the input's volume (hull volume saved by the cut minus hull volume added by the join). */
#define MERGE_REFINE_MIN_GAIN_REL 2e-5
/* Cuts refused (a side beyond tau, or not saving enough) allowed per step allowed, over the pass. */
#define MERGE_REFINE_FAILS_PER_STEP 2
/* The volume planes of the estimates are scored on at most this many vertices (acd3/volume_plane). */
#define MERGE_REFINE_SCORED 300
/* Moves estimated at a time (in parallel), largest upper bound first; a constant, so that the
 * moves estimated do not depend on the thread count. */
#define MERGE_REFINE_BATCH 8
/* A pair's union is re-cut across its first principal axes only (the groups lie along the first). */
#define MERGE_REFINE_PAIR_AXES 1
/* A plane's score on the sample bounds its sides' hull volumes on every vertex from below (the
 * sample's vertices are among those, its crossings on the same edges: its hulls lie inside theirs),
 * up to the own Quickhull's error and the plane's offset rounded once more; this fraction of the
 * score is allowed for them. Over the 1609 estimates of the 12 refining runs of /work/ident.sh the
 * sides less the score were within 1.2e-15 of the score in 194 (a small group: the sample is every
 * vertex and edge; as low as -1.2e-15), at least 1.2e-4 of it in the other 1415. */
#define MERGE_REFINE_SAMPLE_SLACK 1e-3

static int atoms_reserve(atoms *at, size_t n) {
    if (n <= at->cap) return 1;
    size_t nc = at->cap ? 2 * at->cap : 16;
    while (nc < n) nc *= 2;
#define ATOMS_GROW(f)                                        \
    do {                                                     \
        void *p_ = realloc(at->f, nc * sizeof *at->f);       \
        if (!p_) return 0;                                   \
        at->f = p_;                                          \
        memset(at->f + at->cap, 0, (nc - at->cap) * sizeof *at->f); \
    } while (0)
    ATOMS_GROW(mesh);
    ATOMS_GROW(bvh);
    ATOMS_GROW(bvh_kept);
    ATOMS_GROW(vol);
    ATOMS_GROW(sv);
    ATOMS_GROW(nsv);
    ATOMS_GROW(adj);
    ATOMS_GROW(nadj);
    ATOMS_GROW(owner);
    ATOMS_GROW(parent);
    ATOMS_GROW(plane);
#undef ATOMS_GROW
    at->cap = nc;
    return 1;
}

/* Frees atom i's data (its mesh too when owned: i >= nparts). */
static void atom_clear(atoms *at, size_t i, size_t nparts) {
    if (at->bvh_kept[i]) memset(&at->bvh[i], 0, sizeof at->bvh[i]);
    else acd_bvh_free(&at->bvh[i]);
    at->bvh_kept[i] = 0;
    free(at->sv[i]);
    free(at->adj[i]);
    at->sv[i] = NULL;
    at->adj[i] = NULL;
    at->nsv[i] = at->nadj[i] = 0;
    if (i >= nparts) acd_mesh_free(&at->mesh[i]);
}

static void atoms_free(atoms *at, size_t nparts) {
    for (size_t i = 0; i < at->n; i++) atom_clear(at, i, nparts);
    free(at->mesh);
    free(at->bvh);
    free(at->bvh_kept);
    free(at->vol);
    free(at->sv);
    free(at->nsv);
    free(at->adj);
    free(at->nadj);
    free(at->owner);
    free(at->parent);
    free(at->plane);
    memset(at, 0, sizeof *at);
}

/* The input for the test of a vertex on its surface: its tree, and its used vertices by their
 * coordinates (an open-addressing table of vertex ids, UINT32_MAX empty) with the triangles around each
 * (inc[inc_off[v] .. inc_off[v + 1]]). */
typedef struct in_surface {
    acd_bvh bvh;
    const acd_mesh *m;
    uint32_t *slot;
    size_t mask;
    uint32_t *inc_off, *inc;
} in_surface;

static void in_surface_free(in_surface *S) {
    acd_bvh_free(&S->bvh);
    free(S->slot);
    free(S->inc_off);
    free(S->inc);
    memset(S, 0, sizeof *S);
}

static size_t point_hash(const double p[3]) {
    uint64_t h = 0x9e3779b97f4a7c15u;
    for (int k = 0; k < 3; k++) {
        uint64_t x;
        memcpy(&x, p + k, sizeof x);
        h = (h ^ x) * 0xff51afd7ed558ccdu;
        h ^= h >> 32;
    }
    return (size_t)h;
}

/* The table and the triangles around each vertex (the tree is built apart); 0 out of memory (the
 * test then uses the tree alone). */
static int in_surface_index(in_surface *S, const acd_mesh *m) {
    size_t nv = m->nvertices, nt = m->ntriangles, cap = 16;
    S->m = m;
    while (cap < 2 * nv) cap *= 2;
    S->slot = malloc(cap * sizeof *S->slot);
    S->inc_off = calloc(nv + 1, sizeof *S->inc_off);
    S->inc = malloc((nt ? 3 * nt : 1) * sizeof *S->inc);
    uint32_t *cur = malloc((nv ? nv : 1) * sizeof *cur);
    if (!S->slot || !S->inc_off || !S->inc || !cur || nt >= UINT32_MAX / 3) {
        free(S->slot), free(S->inc_off), free(S->inc), free(cur);
        S->slot = S->inc_off = S->inc = NULL;
        return 0;
    }
    S->mask = cap - 1;
    for (size_t k = 0; k < 3 * nt; k++) S->inc_off[m->triangles[k] + 1]++;
    for (size_t v = 0; v < nv; v++) S->inc_off[v + 1] += S->inc_off[v];
    memcpy(cur, S->inc_off, nv * sizeof *cur);
    for (size_t t = 0; t < nt; t++)
        for (int c = 0; c < 3; c++) S->inc[cur[m->triangles[3 * t + c]]++] = (uint32_t)t;
    free(cur);
    for (size_t k = 0; k < cap; k++) S->slot[k] = UINT32_MAX;
    for (size_t v = 0; v < nv; v++) {
        if (S->inc_off[v + 1] == S->inc_off[v]) continue; /* unused: not a point of the surface */
        const double *p = m->vertices + 3 * v;
        size_t h = point_hash(p) & S->mask;
        while (S->slot[h] != UINT32_MAX && memcmp(m->vertices + 3 * (size_t)S->slot[h], p, sizeof(double[3])) != 0)
            h = (h + 1) & S->mask;
        if (S->slot[h] == UINT32_MAX) S->slot[h] = (uint32_t)v; /* the first of equal points */
    }
    return 1;
}

/* Whether p is within on_tol of the input (acd_bvh_closest on its tree finds a point within on_tol).
 * A point that is an input vertex (bit for bit) is first tried against the triangles around that
 * vertex: one of them within on_tol is a triangle the tree's search finds within on_tol too (its box
 * holds p: never pruned), so the answer is the tree's; otherwise the tree answers. */
static int on_input(const in_surface *S, const double p[3], double on_tol) {
    if (S->slot) {
        size_t h = point_hash(p) & S->mask;
        while (S->slot[h] != UINT32_MAX) {
            const double *v = S->m->vertices + 3 * (size_t)S->slot[h];
            if (memcmp(v, p, sizeof(double[3])) == 0) {
                uint32_t u = S->slot[h];
                for (uint32_t k = S->inc_off[u]; k < S->inc_off[u + 1]; k++) {
                    const uint32_t *tr = S->m->triangles + 3 * (size_t)S->inc[k];
                    double q[3];
                    if (acd_closest_point_triangle(p, S->m->vertices + 3 * (size_t)tr[0], S->m->vertices + 3 * (size_t)tr[1],
                                                   S->m->vertices + 3 * (size_t)tr[2], q) <= on_tol * on_tol)
                        return 1;
                }
                break;
            }
            h = (h + 1) & S->mask;
        }
    }
    acd_bvh_closest_result q;
    return acd_bvh_closest(&S->bvh, p, on_tol * on_tol, &q);
}

/* Atom i's surface vertices (within on_tol of the input). */
static acd_status atom_surface(atoms *at, size_t i, const in_surface *in, double on_tol, acd_error *err) {
    const acd_mesh *m = &at->mesh[i];
    at->sv[i] = malloc((m->nvertices ? m->nvertices : 1) * 3 * sizeof(double));
    if (!at->sv[i]) return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for part %zu", i);
    for (size_t v = 0; v < m->nvertices; v++) {
        const double *p = m->vertices + 3 * v;
        if (on_input(in, p, on_tol)) memcpy(at->sv[i] + 3 * at->nsv[i]++, p, sizeof(double[3]));
    }
    return ACD_OK;
}

/* Atom i's surface vertices and tree. */
static acd_status atom_init(atoms *at, size_t i, const in_surface *in_bvh, double on_tol, acd_error *err) {
    const acd_mesh *m = &at->mesh[i];
    acd_status st = atom_surface(at, i, in_bvh, on_tol, err);
    if (st != ACD_OK) return st;
    return acd_bvh_build(&at->bvh[i], m->vertices, m->nvertices, m->triangles, m->ntriangles, err);
}

/* The group's volume plane (searched on a sample: acd3_volume_planes_scored) and the hull volume it
 * saves against g->hvol (the hulls of its two sides over every vertex, by geom3/hull_volume's own
 * Quickhull since c536875: within 1e-9 of qhull's; it only ranks the moves, whose gain is then
 * measured with qhull's hulls). The saving is measured only when the sample's bound, g->hvol less
 * the sample's score (MERGE_REFINE_SAMPLE_SLACK), less c0 exceeds bv: else est 3 keeps the plane and
 * that bound (est_ub), and a later call (the best gain bv having dropped below it) measures it. */
static void estimate(group *g, int naxes, double c0, double bv) {
    const atoms *at = g->at;
    const int searched = g->est == 3;
    g->est = 1;
    g->est_gain = -INFINITY;
    size_t nv = 0, nt = 0;
    for (size_t k = 0; k < g->nmembers; k++) {
        nv += at->mesh[g->members[k]].nvertices;
        nt += at->mesh[g->members[k]].ntriangles;
    }
    acd_mesh m;
    memset(&m, 0, sizeof m);
    m.vertices = malloc((nv ? nv : 1) * 3 * sizeof(double));
    m.triangles = malloc((nt ? nt : 1) * 3 * sizeof(uint32_t));
    if (m.vertices && m.triangles && nv < UINT32_MAX) {
        for (size_t k = 0; k < g->nmembers; k++) {
            const acd_mesh *s = &at->mesh[g->members[k]];
            memcpy(m.vertices + 3 * m.nvertices, s->vertices, 3 * s->nvertices * sizeof(double));
            for (size_t t = 0; t < 3 * s->ntriangles; t++) m.triangles[3 * m.ntriangles + t] = s->triangles[t] + (uint32_t)m.nvertices;
            m.nvertices += s->nvertices;
            m.ntriangles += s->ntriangles;
        }
        /* the plane searched on a sample, its saving measured on every vertex (the sides' hulls) */
        double sc = 0;
        int found = searched || acd3_volume_planes_scored(&m, 1, MERGE_REFINE_SCORED, naxes, &g->est_plane, &sc, NULL) == 1;
        double ub = g->hvol - sc * (1 - MERGE_REFINE_SAMPLE_SLACK);
        if (found && !searched && !(ub - c0 > bv)) {
            g->est = 3;
            g->est_ub = ub;
        } else if (found) {
            double ex = acd3_volume_plane_sides(&m, g->est_plane.normal, g->est_plane.point);
            if (ex >= 0) g->est_gain = g->hvol - ex;
        }
    }
    acd_mesh_free(&m);
}

static int pair_union(const group *A, const group *B, group *U);

/* What estimate(g, naxes) costs, roughly (measured on the armadillo's budget run: about linear in
 * the vertices, the plane search once per axis and the sides' hulls once; est 3: the sides only):
 * for the order of a batch. */
static double estimate_work(const group *g, int naxes, int est) {
    size_t nv = 0;
    for (size_t k = 0; k < g->nmembers; k++) nv += g->at->mesh[g->members[k]].nvertices;
    return (double)nv * (est == 3 ? 1 : naxes + 1);
}

/* The volume plane of the union of the pair's groups and the hull volume it saves against theirs. */
static void estimate_pair(const group *G, pair *p, double bv) {
    group U;
    int est = p->est;
    p->est = 1;
    p->est_gain = -INFINITY;
    if (!pair_union(&G[p->a], &G[p->b], &U)) return;
    U.est = est;
    U.est_plane = p->est_plane;
    estimate(&U, MERGE_REFINE_PAIR_AXES, 0, bv);
    p->est = U.est;
    p->est_gain = U.est_gain;
    p->est_ub = U.est_ub;
    p->est_plane = U.est_plane;
    free(U.members);
}

/* S = the group of the atoms mem[0..n): hull, surface vertices, facet bounds. Returns 1 when its
 * bound is within tau, 0 when not (or flat; S freed), -1 out of memory (S freed). */
static int side_group(group *S, const atoms *at, const uint32_t *mem, size_t n, double tau) {
    memset(S, 0, sizeof *S);
    S->at = at;
    size_t nv = 0, nsv = 0;
    for (size_t i = 0; i < n; i++) {
        nv += at->mesh[mem[i]].nvertices;
        nsv += at->nsv[mem[i]];
    }
    double *pts = malloc((nv ? nv : 1) * 3 * sizeof *pts);
    S->members = malloc((n ? n : 1) * sizeof *S->members);
    S->sv = malloc((nsv ? nsv : 1) * 3 * sizeof(double));
    if (!pts || !S->members || !S->sv) {
        free(pts);
        group_free(S);
        return -1;
    }
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        const acd_mesh *m = &at->mesh[mem[i]];
        memcpy(pts + 3 * k, m->vertices, 3 * m->nvertices * sizeof *pts);
        k += m->nvertices;
        memcpy(S->sv + 3 * S->nsv, at->sv[mem[i]], 3 * at->nsv[mem[i]] * sizeof(double));
        S->nsv += at->nsv[mem[i]];
        S->members[i] = mem[i];
        S->vol += at->vol[mem[i]];
    }
    S->nmembers = n;
    acd_hull H;
    acd_status hs = acd_hull_compute(pts, nv, &H, NULL);
    free(pts);
    if (hs != ACD_OK || H.dim != 3) {
        if (hs == ACD_OK) acd_hull_free(&H);
        group_free(S);
        return hs == ACD_ERR_NOMEM ? -1 : 0;
    }
    size_t start = 0;
    double din = depth_in_hull(S, &H, 0.0, tau, &start), dout = INFINITY;
    int ret = 0;
    if (din <= tau) ret = facet_table(S, NULL, &H, tau, 1, &dout, &S->ft, &S->fub) ? dout <= tau : -1;
    if (ret != 1) {
        acd_hull_free(&H);
        group_free(S);
        return ret;
    }
    S->nft = H.ntriangles;
    S->bound = fmax(din, dout);
    S->hvol = H.volume;
    take_hull_vertices(&H, &S->hv, &S->nhv);
    S->alive = 1;
    return 1;
}

/* The connected components of the atoms mem[0..n) through adjacency (adjacent_pairs: three
 * non-collinear shared vertex positions, as the greedy joins ask of two groups), appended to *out
 * (each component's atoms in mem's order, the components in the order of their first atom in mem),
 * their ends in out's order appended to *ends. A side of a refinement cut is made one group per
 * component: one group holding pieces that do not touch would be one part whose hull spans the gap
 * between them (issue 4; the greedy joins keep groups connected, only a cut's side can break it).
 * Returns 0, or -1 out of memory (err set). */
static int side_components(const atoms *at, const uint32_t *mem, size_t n, double tol, acd_u32vec *out,
                           acd_u32vec *ends, acd_error *err) {
    uint32_t *pr = NULL, *uf = malloc((n ? n : 1) * sizeof *uf);
    size_t npr = 0;
    if (!uf) return -1;
    if (n > 1 && adjacent_pairs(at->mesh, mem, n, tol, &pr, &npr, err) != ACD_OK) {
        free(uf);
        return -1;
    }
    for (size_t i = 0; i < n; i++) uf[i] = (uint32_t)i;
    for (size_t k = 0; k < npr; k++) acd_uf_union(uf, pr[2 * k], pr[2 * k + 1]);
    free(pr);
    int ok = 1;
    /* a root is its component's first atom (acd_uf_union: the smaller root wins) */
    for (size_t i = 0; i < n && ok; i++) {
        if (acd_uf_find(uf, (uint32_t)i) != i) continue;
        for (size_t j = i; j < n && ok; j++)
            if (acd_uf_find(uf, (uint32_t)j) == i) ok = acd_u32vec_push(out, mem[j]);
        if (ok) ok = acd_u32vec_push(ends, (uint32_t)out->n);
    }
    free(uf);
    if (!ok) acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory cutting a part");
    return ok ? 0 : -1;
}

/* One member of the group try_cut cuts: the side it lies on (0: +, 1: -) when it does not cross the
 * plane, else (-1) its cut and the statuses of the cut and of the pieces' closedness check. */
typedef struct cut_member {
    int side;
    acd_status cs, es;
    acd_cut_result cr;
} cut_member;

/* Cuts group X by its volume plane: its members crossing the plane are cut (the pieces appended to
 * the atoms, owner unset), each side's connected components made groups, in *Sp (*nsp of them, >= 2;
 * allocated). Returns 1 (every component within tau; *gain: X's hull volume minus theirs), 0 refused
 * (the atoms as before), or -(status). The members' cuts, the pieces' surface vertices and trees,
 * and the components' groups are made in parallel (threads); the result is the sequential one: the
 * members in order, the first failure deciding. */
static int try_cut(const group *X, atoms *at, size_t nparts, const in_surface *in_bvh, double on_tol, double diag,
                   double tol, double tau, int threads, group **Sp, size_t *nsp, double *gain, acd_error *err) {
    *Sp = NULL;
    *nsp = 0;
    acd_cut_plane cp;
    if (acd_cut_plane_from_normal(X->est_plane.point, X->est_plane.normal, diag, &cp, NULL) != ACD_OK) return 0;
    double d = -(cp.normal[0] * cp.a[0] + cp.normal[1] * cp.a[1] + cp.normal[2] * cp.a[2]);
    const size_t n0 = at->n, nm = X->nmembers;
    acd_u32vec mem[2] = {{0}, {0}};
    cut_member *cm = calloc(nm ? nm : 1, sizeof *cm);
    if (!cm) {
        acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory cutting a part");
        return -(int)ACD_ERR_NOMEM;
    }
    /* the members' sides and the crossing members' cuts, independently */
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nm > 1)
#endif
    for (long k = 0; k < (long)nm; k++) {
        cut_member *c = &cm[k];
        const acd_mesh *M = &at->mesh[X->members[k]];
        int pos = 0, neg = 0;
        for (size_t v = 0; v < M->nvertices && !(pos && neg); v++) {
            int sd = acd_cut_plane_side(&cp, M->vertices + 3 * v);
            pos |= sd > 0;
            neg |= sd < 0;
        }
        if (!pos || !neg) {
            c->side = neg ? 1 : 0;
            continue;
        }
        c->side = -1;
        acd_error ce;
        c->cs = acd_plane_cut_flags(M, &cp, ACD_PLANE_CUT_DROP_SPECKS, &c->cr, &ce);
        /* every piece must be closed and consistently oriented, as decompose.c asks of its cuts: on
         * a part whose distinct vertices share a point (an input pinched at a vertex) the cut may
         * leave a piece with an edge used twice in one direction; such a cut is refused */
        if (c->cs == ACD_OK) c->es = acd_cut_result_check_closed(&c->cr);
    }
    /* the pieces become atoms, in member order, up to the first member whose cut failed (kstop; its
     * verdict fail) */
    int fail = 1;
    size_t kstop = nm;
    for (size_t k = 0; k < nm && fail == 1; k++) {
        cut_member *c = &cm[k];
        if (c->side >= 0) continue;
        if (c->cs != ACD_OK) fail = c->cs == ACD_ERR_NOMEM ? -(int)ACD_ERR_NOMEM : 0;
        else if (c->es != ACD_OK) fail = c->es == ACD_ERR_NOMEM ? -(int)ACD_ERR_NOMEM : 0;
        else if (!atoms_reserve(at, at->n + c->cr.npieces)) fail = -(int)ACD_ERR_NOMEM;
        if (fail != 1) {
            kstop = k;
            break;
        }
        for (size_t p = 0; p < c->cr.npieces; p++) {
            size_t i = at->n++;
            at->mesh[i] = c->cr.pieces[p].mesh;
            memset(&c->cr.pieces[p].mesh, 0, sizeof c->cr.pieces[p].mesh);
            at->owner[i] = UINT32_MAX;
            at->parent[i] = X->members[k];
            memcpy(at->plane[i], cp.normal, sizeof(double[3]));
            at->plane[i][3] = d;
        }
    }
    /* the pieces' volumes, surface vertices and trees, independently */
    const size_t npc = at->n - n0;
    acd_status *ist = calloc(npc ? npc : 1, sizeof *ist);
    acd_error *ierr = calloc(npc ? npc : 1, sizeof *ierr);
    int ret = ist && ierr ? 1 : -(int)ACD_ERR_NOMEM;
    if (ret == 1) {
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && npc > 1)
#endif
        for (long j = 0; j < (long)npc; j++) {
            size_t i = n0 + (size_t)j;
            at->vol[i] = acd_geom3_signed_volume(&at->mesh[i]);
            ist[j] = atom_init(at, i, in_bvh, on_tol, &ierr[j]);
        }
    }
    /* the sides' members in order; the first failure decides, as in a sequential pass */
    size_t j = 0;
    for (size_t k = 0; k < kstop && ret == 1; k++) {
        cut_member *c = &cm[k];
        if (c->side >= 0) {
            if (!acd_u32vec_push(&mem[c->side], X->members[k])) ret = -(int)ACD_ERR_NOMEM;
            continue;
        }
        for (size_t p = 0; p < c->cr.npieces && ret == 1; p++, j++) {
            if (ist[j] != ACD_OK) {
                if (err) *err = ierr[j];
                ret = ist[j] == ACD_ERR_NOMEM ? -(int)ACD_ERR_NOMEM : 0;
            } else if (!acd_u32vec_push(&mem[c->cr.pieces[p].side > 0 ? 0 : 1], (uint32_t)(n0 + j))) {
                ret = -(int)ACD_ERR_NOMEM;
            }
        }
    }
    if (ret == 1) ret = fail;
    free(ist);
    free(ierr);
    for (size_t k = 0; k < nm; k++)
        if (cm[k].side < 0 && cm[k].cs == ACD_OK) acd_cut_result_free(&cm[k].cr);
    free(cm);
    if (ret == 1 && (!mem[0].n || !mem[1].n)) ret = 0;
    /* each side's connected components (side_components), the + side's first: one group each */
    acd_u32vec cm_all = {0}, cend = {0};
    for (int s = 0; s < 2 && ret == 1; s++)
        if (side_components(at, mem[s].a, mem[s].n, tol, &cm_all, &cend, err) < 0) ret = -(int)ACD_ERR_NOMEM;
    const size_t ns = cend.n;
    group *S = ret == 1 ? calloc(ns, sizeof *S) : NULL;
    int *rs = ret == 1 ? calloc(ns, sizeof *rs) : NULL;
    if (ret == 1 && (!S || !rs)) ret = -(int)ACD_ERR_NOMEM;
    if (ret == 1) {
        /* every component at once; the first refused (in order) decides */
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && ns > 1)
#endif
        for (long c = 0; c < (long)ns; c++) {
            size_t c0 = c ? cend.a[c - 1] : 0;
            rs[c] = side_group(&S[c], at, cm_all.a + c0, cend.a[c] - c0, tau);
        }
        for (size_t c = 0; c < ns && ret == 1; c++)
            if (rs[c] != 1) ret = rs[c] < 0 ? -(int)ACD_ERR_NOMEM : 0;
        for (size_t c = 0; c < ns && ret != 1; c++)
            if (rs[c] == 1) group_free(&S[c]);
    }
    if (ret == 1) {
        double g = X->hvol;
        for (size_t c = 0; c < ns; c++) g -= S[c].hvol;
        *gain = g;
        *Sp = S;
        *nsp = ns;
    } else {
        free(S);
    }
    free(rs);
    free(cm_all.a);
    free(cend.a);
    if (ret != 1) {
        for (size_t i = n0; i < at->n; i++) atom_clear(at, i, nparts);
        at->n = n0;
    }
    if (ret < 0) acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory cutting a part");
    free(mem[0].a);
    free(mem[1].a);
    return ret;
}

static int grow_groups(group **G, size_t *capg, size_t need) {
    if (need <= *capg) return 1;
    size_t nc = 2 * *capg;
    if (nc < need) nc = need;
    group *n2 = realloc(*G, nc * sizeof *n2);
    if (!n2) return 0;
    memset(n2 + *capg, 0, (nc - *capg) * sizeof *n2);
    *G = n2;
    *capg = nc;
    return 1;
}

static int pair_before(const pair *P, size_t i, size_t j) {
    return P[i].cost < P[j].cost || (P[i].cost == P[j].cost && i < j);
}

/* The cheapest joinable pair involving neither group x nor y (ties: the earlier), SIZE_MAX if none.
 * Pending pairs (score) are finished cheapest first until the cheapest is joinable: when the
 * cheapest is pending, it and the next pending ones cheaper than the cheapest joinable (at most
 * MERGE_FINISH_BATCH: a constant, the same work for any thread count) in parallel. */
#define MERGE_FINISH_BATCH 4
static size_t cheapest_ok(const group *G, pair *P, size_t np, uint32_t x, uint32_t y, double tau, int threads) {
    for (;;) {
        size_t best = SIZE_MAX, bok = SIZE_MAX, pend[MERGE_FINISH_BATCH];
        int npend = 0;
        for (size_t i = 0; i < np; i++) {
            if (!P[i].ok && !P[i].pend) continue;
            if (P[i].a == x || P[i].b == x || P[i].a == y || P[i].b == y) continue;
            if (best == SIZE_MAX || pair_before(P, i, best)) best = i;
            if (P[i].ok && (bok == SIZE_MAX || pair_before(P, i, bok))) bok = i;
        }
        if (best == SIZE_MAX || P[best].ok) return best;
        /* the cheapest pending pairs before bok, in order (insertion into a short sorted list) */
        for (size_t i = 0; i < np; i++) {
            if (!P[i].pend || (bok != SIZE_MAX && !pair_before(P, i, bok))) continue;
            if (P[i].a == x || P[i].b == x || P[i].a == y || P[i].b == y) continue;
            int k = npend < MERGE_FINISH_BATCH ? npend++ : MERGE_FINISH_BATCH;
            if (k == MERGE_FINISH_BATCH && !pair_before(P, i, pend[k - 1])) continue;
            if (k == MERGE_FINISH_BATCH) k--;
            while (k > 0 && pair_before(P, i, pend[k - 1])) {
                pend[k] = pend[k - 1];
                k--;
            }
            pend[k] = i;
        }
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && npend > 1)
#endif
        for (int k = 0; k < npend; k++) finish_pair(G, &P[pend[k]], tau);
        (void)threads;
    }
}

/* Drops the pairs of dead groups; returns the cheapest joinable pair (ties: the earlier), SIZE_MAX if
 * none. */
static size_t best_pair(const group *G, pair *P, size_t *np, double tau, int threads) {
    size_t w = 0;
    for (size_t i = 0; i < *np; i++) {
        if (!G[P[i].a].alive || !G[P[i].b].alive) {
            pair_free(&P[i]);
            continue;
        }
        P[w++] = P[i];
    }
    *np = w;
    return cheapest_ok(G, P, w, UINT32_MAX, UINT32_MAX, tau, threads);
}

/* Joins pair best into a new group, its pairs with its neighbours pushed and scored. A neighbour x
 * whose pair with one of the joined groups was refused by a depth above din_refuse is refused with
 * the new group too, without a hull (MERGE_DEPTH_SLACK_REL): score would find that depth or more. */
static acd_status join_best(group **G, size_t *ng, size_t *capg, atoms *at, pair **P, size_t *np, size_t *capp,
                            size_t best, double tau, double din_refuse, int by_volume, int threads, acd_error *err) {
    if (!grow_groups(G, capg, *ng + 1)) return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for groups");
    uint32_t c = (uint32_t)(*ng)++;
    uint32_t a = (*P)[best].a, b = (*P)[best].b;
    acd_status st = join(*G, &(*P)[best], c, err);
    if (st != ACD_OK) return st;
    group *C = &(*G)[c];
    for (size_t k = 0; k < C->nmembers; k++) at->owner[C->members[k]] = c;
    size_t p0 = *np;
    for (size_t k = 0; k < C->nadj && st == ACD_OK; k++) st = push_pair(P, np, capp, C->adj[k], c, err);
    if (st != ACD_OK) return st;
    /* the joined groups' pairs are still in P (best_pair drops them next) */
    for (size_t i = 0; i < p0; i++) {
        pair *q = &(*P)[i];
        if (!(q->din_lo > din_refuse)) continue;
        uint32_t x;
        if (q->a == a || q->a == b) x = q->b;
        else if (q->b == a || q->b == b) x = q->a;
        else continue;
        for (size_t j = p0; j < *np; j++) {
            pair *r = &(*P)[j];
            if (r->a == x && r->din_lo < q->din_lo) r->din_lo = q->din_lo; /* r->b == c > x */
        }
    }
    score_pairs(*G, *P, p0, *np, tau, din_refuse, by_volume, threads);
    return st;
}

static int cmp_u32(const void *x, const void *y) {
    uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return (a > b) - (a < b);
}

/* Makes the cut of the group(s) x (and y, unless UINT32_MAX: a pair cut as one; try_cut: pieces
 * from n0 on, the sides' components S[0..ns)) real: the components become groups (S's records moved
 * there), the pieces get their adjacency, x and y die; the new groups' pairs are pushed and scored. */
static acd_status commit_cut(group **Gp, size_t *ng, size_t *capg, uint32_t x, uint32_t y, atoms *at, size_t n0,
                             group *S, size_t ns, double tol, pair **P, size_t *np, size_t *capp, double tau, int by_volume,
                             int threads, acd_error *err) {
    if (!grow_groups(Gp, capg, *ng + ns)) {
        for (size_t j = 0; j < ns; j++) group_free(&S[j]); /* not moved into G: the caller frees only S */
        return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for groups");
    }
    group *G = *Gp;
    const uint32_t s0 = (uint32_t)*ng; /* the new groups: s0 .. s0 + ns - 1 */
    uint32_t dy[2] = {x, y};
    const int ndy = y == UINT32_MAX ? 1 : 2;
    *ng += ns;
    for (size_t j = 0; j < ns; j++) {
        G[s0 + j] = S[j];
        for (size_t k = 0; k < G[s0 + j].nmembers; k++) at->owner[G[s0 + j].members[k]] = s0 + (uint32_t)j;
    }
    /* the atoms whose adjacency may change: the pieces, the cut groups' members and their neighbours */
    acd_u32vec sel = {0};
    int ok = 1;
    for (int e = 0; e < ndy; e++)
        for (size_t k = 0; k < G[dy[e]].nmembers; k++)
            if (at->owner[G[dy[e]].members[k]] == dy[e]) at->owner[G[dy[e]].members[k]] = UINT32_MAX; /* cut */
    for (size_t i = n0; i < at->n && ok; i++) ok = acd_u32vec_push(&sel, (uint32_t)i);
    for (int e = 0; e < ndy; e++)
        for (size_t k = 0; k < G[dy[e]].nmembers && ok; k++) {
            uint32_t a = G[dy[e]].members[k];
            if (at->owner[a] != UINT32_MAX) ok = acd_u32vec_push(&sel, a);
            for (size_t j = 0; j < at->nadj[a] && ok; j++)
                if (at->owner[at->adj[a][j]] != UINT32_MAX) ok = acd_u32vec_push(&sel, at->adj[a][j]);
        }
    if (!ok) {
        free(sel.a);
        return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for adjacency");
    }
    qsort(sel.a, sel.n, sizeof *sel.a, cmp_u32);
    size_t w = 0;
    for (size_t i = 0; i < sel.n; i++)
        if (!w || sel.a[w - 1] != sel.a[i]) sel.a[w++] = sel.a[i];
    sel.n = w;
    uint32_t *pr;
    size_t npr;
    acd_status st = adjacent_pairs(at->mesh, sel.a, sel.n, tol, &pr, &npr, err);
    for (size_t k = 0; k < npr && st == ACD_OK; k++) {
        uint32_t a = sel.a[pr[2 * k]], b = sel.a[pr[2 * k + 1]];
        if (a < n0 && b < n0) continue;
        if (at->owner[a] == UINT32_MAX || at->owner[b] == UINT32_MAX) continue;
        if (!adj_add(&at->adj[a], &at->nadj[a], b) || !adj_add(&at->adj[b], &at->nadj[b], a))
            st = acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for adjacency");
    }
    free(pr);
    free(sel.a);
    /* group adjacency */
    for (int e = 0; e < ndy; e++)
        for (size_t k = 0; k < G[dy[e]].nadj; k++) remove_adj(&G[G[dy[e]].adj[k]], dy[e]);
    for (size_t j = 0; j < ns && st == ACD_OK; j++)
        for (size_t k = 0; k < G[s0 + j].nmembers && st == ACD_OK; k++) {
            const uint32_t sj = s0 + (uint32_t)j, a = G[sj].members[k];
            for (size_t i = 0; i < at->nadj[a] && st == ACD_OK; i++) {
                uint32_t o = at->owner[at->adj[a][i]];
                if (o == UINT32_MAX || o == sj) continue;
                if (!add_adj(&G[sj], o) || !add_adj(&G[o], sj))
                    st = acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for adjacency");
            }
        }
    for (int e = 0; e < ndy; e++) group_free(&G[dy[e]]);
    size_t p0 = *np;
    /* each pair once: a pair of two new groups from the earlier one's list */
    for (size_t j = 0; j < ns && st == ACD_OK; j++) {
        const uint32_t sj = s0 + (uint32_t)j;
        for (size_t k = 0; k < G[sj].nadj && st == ACD_OK; k++)
            if (!(G[sj].adj[k] >= s0 && G[sj].adj[k] < sj)) st = push_pair(P, np, capp, G[sj].adj[k], sj, err);
    }
    if (st == ACD_OK) score_pairs(G, *P, p0, *np, tau, INFINITY, by_volume, threads);
    return st;
}

/* The union of groups a and b as a group for estimate and try_cut (members and hull volume: the sum
 * of theirs); 0 out of memory. */
static int pair_union(const group *A, const group *B, group *U) {
    memset(U, 0, sizeof *U);
    U->at = A->at;
    U->nmembers = A->nmembers + B->nmembers;
    U->members = malloc(U->nmembers * sizeof *U->members);
    if (!U->members) return 0;
    memcpy(U->members, A->members, A->nmembers * sizeof *U->members);
    memcpy(U->members + A->nmembers, B->members, B->nmembers * sizeof *U->members);
    U->hvol = A->hvol + B->hvol;
    U->vol = A->vol + B->vol;
    return 1;
}

/* The cheapest joinable pair (i1, INFINITY without one) and, for each of its two groups, the cheapest
 * joinable pair without it: what a trade of a group joins after its cut. */
typedef struct cheapest_join {
    size_t i1;
    double c0ab[2];
} cheapest_join;

static void cheapest_join_init(cheapest_join *cj, const group *G, pair *P, size_t np, double tau, int threads) {
    cj->i1 = cheapest_ok(G, P, np, UINT32_MAX, UINT32_MAX, tau, threads);
    cj->c0ab[0] = cj->c0ab[1] = INFINITY;
    for (int s = 0; s < 2 && cj->i1 != SIZE_MAX; s++) {
        size_t i = cheapest_ok(G, P, np, s ? P[cj->i1].b : P[cj->i1].a, UINT32_MAX, tau, threads);
        if (i != SIZE_MAX) cj->c0ab[s] = P[i].cost;
    }
}

/* The cost of the cheapest joinable pair not involving group g. */
static double cheapest_join_without(const cheapest_join *cj, const pair *P, uint32_t g) {
    if (cj->i1 == SIZE_MAX) return INFINITY;
    return g == P[cj->i1].a ? cj->c0ab[0] : g == P[cj->i1].b ? cj->c0ab[1] : P[cj->i1].cost;
}

/* A move to estimate (the refinement's lazy estimates): a group's cut or (pair) a pair's re-cut,
 * with an upper bound of what it can save. */
typedef struct refine_cand {
    double ub;
    uint32_t i;
    int pair;
} refine_cand;

static int cmp_refine_cand(const void *x, const void *y) {
    const refine_cand *a = x, *b = y;
    if (a->ub != b->ub) return a->ub > b->ub ? -1 : 1;
    if (a->pair != b->pair) return a->pair - b->pair;
    return (a->i > b->i) - (a->i < b->i);
}

static int grow_cands(refine_cand **c, size_t *cap) {
    size_t nc = *cap ? 2 * *cap : 64;
    refine_cand *n2 = realloc(*c, nc * sizeof *n2);
    if (!n2) return 0;
    *c = n2;
    *cap = nc;
    return 1;
}

acd_status acd3_merge_adjacent(const acd_mesh *input, const acd_mesh *parts, size_t nparts, double tau, double tol,
                               const acd3_merge_opts *opts, int threads, acd3_merge_result *out, acd_error *err) {
    return acd3_merge_adjacent_hulls(input, parts, NULL, nparts, tau, tol, opts, threads, out, err);
}

/* Pairs scored between two calls of the callback in the set-up's scoring (all at once without a
 * callback; each pair's score is its own, so the chunks change nothing but the calls): all the
 * pairs took 0.5 CPU-s without a call at 832k faces. */
#define MERGE_SCORE_POLL_PAIRS 16

/* The merge's error when the caller's callback says stop in stage (the set-up's poll, merge_progress). */
static acd_status setup_cancelled(acd_error *err, const char *stage) {
    return acd_fail(err, ACD_ERR_CANCELLED, "cancelled (%s)", stage);
}

/* The caller's progress callback (opts may be NULL), between steps: ACD_ERR_CANCELLED when it asks. */
static acd_status merge_progress(const acd3_merge_opts *opts, double fraction, const char *stage, acd_error *err) {
    if (opts && opts->progress && opts->progress(opts->progress_user, fraction, stage))
        return setup_cancelled(err, stage);
    return ACD_OK;
}

acd_status acd3_merge_adjacent_hulls(const acd_mesh *input, const acd_mesh *parts, const acd_hull *const *hulls,
                                     size_t nparts, double tau, double tol, const acd3_merge_opts *opts, int threads,
                                     acd3_merge_result *out, acd_error *err) {
    if (!hulls) return acd3_merge_adjacent_kept(input, parts, NULL, nparts, tau, tol, opts, threads, out, err);
    acd3_merge_kept *kept = calloc(nparts ? nparts : 1, sizeof *kept);
    if (!kept) {
        memset(out, 0, sizeof *out);
        return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for %zu parts", nparts);
    }
    for (size_t i = 0; i < nparts; i++) kept[i].hull = hulls[i];
    acd_status st = acd3_merge_adjacent_kept(input, parts, kept, nparts, tau, tol, opts, threads, out, err);
    free(kept);
    return st;
}

/* Whether bvh can stand for part m's tree: built over m's own arrays (the caller promises the rest). */
static int kept_bvh_fits(const acd_bvh *bvh, const acd_mesh *m) {
    return bvh && bvh->vertices == m->vertices && bvh->triangles == m->triangles && bvh->nvertices == m->nvertices &&
           bvh->ntriangles == m->ntriangles && (bvh->nnodes > 0) == (m->ntriangles > 0);
}

acd_status acd3_merge_adjacent_kept(const acd_mesh *input, const acd_mesh *parts, const acd3_merge_kept *kept,
                                    size_t nparts, double tau, double tol, const acd3_merge_opts *opts, int threads,
                                    acd3_merge_result *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    const int by_volume = opts && opts->by_volume;
    const size_t stop_at = opts ? opts->stop_at : 0;
    const size_t refine = stop_at && opts ? opts->refine : 0;
    if (threads < 1) threads = 1;
    if (!(tau > 0) || nparts < 2 || (stop_at && nparts <= stop_at && !refine)) { /* tau 0: only a convex union could be joined; not searched */
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
    in_surface in_bvh;
    memset(&in_bvh, 0, sizeof in_bvh);
    atoms at;
    memset(&at, 0, sizeof at);
    if (!G || !atoms_reserve(&at, nparts)) {
        free(G);
        atoms_free(&at, nparts);
        return acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for %zu parts", nparts);
    }
    at.n = nparts;
    acd_status st = ACD_OK;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < input->nvertices; v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], input->vertices[3 * v + k]);
            hi[k] = fmax(hi[k], input->vertices[3 * v + k]);
        }
    const double diag = acd_dist3(lo, hi), on_tol = MERGE_ON_SURFACE_REL * diag;
    double in_vol = 0;
    /* the input's tree (its subtrees in parallel: with the parts' trees, hulls and facet tables kept,
     * as after the budget pass, the tree was most of the set-up, built by one thread while the other
     * had nothing to do); then one group per part (independently: in parallel): the parts' trees and
     * hulls, then the parts' surface vertices (they need the input's tree) */
    ng = nparts;
    acd_status *gst = calloc(nparts + 1, sizeof *gst);
    acd_error *gerr = calloc(nparts + 1, sizeof *gerr);
    if (!gst || !gerr) st = acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for %zu parts", nparts);
    if (st == ACD_OK) {
        /* polled before the input's tree, after it and before each part's tree and hull, by the calling
         * thread (the others skip their parts once it says stop): 2.3 CPU-s without a call at 832k */
        acd3_poll poll_obj, *poll = NULL;
        if (opts && opts->progress) {
            poll_obj = acd3_poll_make(opts->progress, opts->progress_user, "merge: preparing the input's tree");
            poll = &poll_obj;
        }
        gst[nparts] = acd3_poll_stop(poll) ? setup_cancelled(&gerr[nparts], "merge: preparing the input's tree")
                                           : acd_bvh_build_threads(&in_bvh.bvh, input->vertices, input->nvertices,
                                                                   input->triangles, input->ntriangles, threads,
                                                                   &gerr[nparts]);
        if (gst[nparts] == ACD_OK) { /* (a stop before the tree leaves its stage for the parts' messages) */
            acd3_poll_set_stage(poll, "merge: preparing the parts' hulls");
            if (acd3_poll_stop(poll)) gst[nparts] = setup_cancelled(&gerr[nparts], poll->stage);
        }
        if (gst[nparts] == ACD_OK) in_surface_index(&in_bvh, input); /* (none: the tree alone) */
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nparts > 1)
#endif
        for (long li = 1; li <= (long)nparts; li++) {
            size_t i = (size_t)li - 1;
            group *g = &G[i];
            at.mesh[i] = parts[i];
            at.owner[i] = (uint32_t)i;
            at.parent[i] = UINT32_MAX;
            if (acd3_poll_stop(poll)) { /* the group left empty (freed as one) */
                gst[i] = setup_cancelled(&gerr[i], poll->stage);
                continue;
            }
            at.vol[i] = acd_geom3_signed_volume(&parts[i]);
            g->alive = 1;
            g->at = &at;
            g->vol = at.vol[i];
            g->nmembers = 1;
            g->members = malloc(sizeof *g->members);
            const acd3_merge_kept *kp = kept ? &kept[i] : NULL;
            acd_status s2 = ACD_OK;
            int own_bvh = kp && kept_bvh_fits(kp->bvh, &parts[i]);
            if (own_bvh) {
                at.bvh[i] = *kp->bvh; /* read only (not freed: bvh_kept) */
                at.bvh_kept[i] = 1;
            } else {
                s2 = acd_bvh_build(&at.bvh[i], parts[i].vertices, parts[i].nvertices, parts[i].triangles,
                                   parts[i].ntriangles, &gerr[i]);
            }
            if (s2 == ACD_OK && !g->members) s2 = acd_fail(&gerr[i], ACD_ERR_NOMEM, "merge: out of memory for part %zu", i);
            if (s2 == ACD_OK) {
                g->members[0] = (uint32_t)i;
                s2 = group_init_hull(g, parts[i].vertices, parts[i].nvertices, kp ? kp->hull : NULL,
                                     own_bvh ? kp->table : NULL, tau, &gerr[i]);
            }
            gst[i] = s2;
        }
        for (size_t i = 0; i <= nparts; i++)
            if (gst[i] != ACD_OK) {
                st = gst[i];
                if (err) *err = gerr[i];
                break;
            }
    }
    /* the set-up's steps tell the callback too (each a pass over every part: seconds on a large mesh) */
    if (st == ACD_OK) st = merge_progress(opts, -1.0, "merge: preparing the parts' surfaces", err);
    if (st == ACD_OK) {
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nparts > 1)
#endif
        for (long li = 0; li < (long)nparts; li++) {
            size_t i = (size_t)li;
            group *g = &G[i];
            acd_status s2 = atom_surface(&at, i, &in_bvh, on_tol, &gerr[i]);
            if (s2 == ACD_OK) {
                g->nsv = at.nsv[i];
                g->sv = malloc((g->nsv ? g->nsv : 1) * 3 * sizeof(double));
                if (g->sv) memcpy(g->sv, at.sv[i], 3 * g->nsv * sizeof(double));
                else s2 = acd_fail(&gerr[i], ACD_ERR_NOMEM, "merge: out of memory for part %zu", i);
            }
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
    for (size_t i = 0; i < nparts; i++) in_vol += at.vol[i];
    if (st == ACD_OK) st = merge_progress(opts, -1.0, "merge: preparing the adjacent pairs", err);
    if (st == ACD_OK) {
        uint32_t *pr;
        size_t npr;
        st = adjacent_pairs(parts, NULL, nparts, tol, &pr, &npr, err);
        for (size_t k = 0; k < npr && st == ACD_OK; k++) {
            uint32_t a = pr[2 * k], b = pr[2 * k + 1];
            if (!add_adj(&G[a], b) || !add_adj(&G[b], a) || !adj_add(&at.adj[a], &at.nadj[a], b) ||
                !adj_add(&at.adj[b], &at.nadj[b], a))
                st = acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory for adjacency");
        }
        free(pr);
    }
    for (size_t i = 0; i < nparts && st == ACD_OK; i++)
        for (size_t k = 0; k < G[i].nadj && st == ACD_OK; k++)
            if (G[i].adj[k] > i) st = push_pair(&P, &np, &capp, (uint32_t)i, G[i].adj[k], err);
    const double din_refuse = tau + MERGE_DEPTH_SLACK_REL * diag;
    at.max_added = stop_at ? INFINITY : (opts && opts->max_added > 0 ? opts->max_added : MERGE_MAX_ADDED_REL) * in_vol;
    if (st == ACD_OK) st = merge_progress(opts, -1.0, "merge: scoring adjacent pairs", err);
    const size_t chunk = opts && opts->progress ? MERGE_SCORE_POLL_PAIRS : np;
    for (size_t p0 = 0; st == ACD_OK && p0 < np; p0 += chunk) {
        if (p0 > 0) st = merge_progress(opts, -1.0, "merge: scoring adjacent pairs", err);
        if (st == ACD_OK) score_pairs(G, P, p0, np - p0 > chunk ? p0 + chunk : np, tau, din_refuse, by_volume, threads);
    }
    /* greedy: the cheapest joinable pair of live groups, ties by the lower ids */
    size_t nlive = nparts;
    while (st == ACD_OK && nlive > stop_at) {
        st = merge_progress(opts, stop_at ? (double)(nparts - nlive) / (double)(nparts - stop_at) : -1.0,
                            "merge: joining", err);
        if (st != ACD_OK) break;
        size_t best = best_pair(G, P, &np, tau, threads);
        if (best == SIZE_MAX) break;
        st = join_best(&G, &ng, &capg, &at, &P, &np, &capp, best, tau, din_refuse, by_volume, threads, err);
        if (st != ACD_OK) break;
        out->merges++;
        nlive--;
    }
    /* refinement: the move of largest estimated gain, made when its actual gain is positive: a trade
     * (a group cut by its volume plane, the cheapest other pair joined) or a re-cut (the union of an
     * adjacent pair cut anew by its volume plane) */
    size_t fails = 0, capc = 0;
    refine_cand *cands = NULL;
    const double min_gain = MERGE_REFINE_MIN_GAIN_REL * in_vol;
    while (st == ACD_OK && out->trades < refine && fails <= MERGE_REFINE_FAILS_PER_STEP * refine) {
        st = merge_progress(opts, (double)out->trades / (double)refine, "merge: refining", err);
        if (st != ACD_OK) break;
        best_pair(G, P, &np, tau, threads);
        cheapest_join cj;
        cheapest_join_init(&cj, G, P, np, tau, threads);
        /* estimates made lazily, largest upper bound first, until no unestimated move can beat the
         * best estimated one: a cut saves at most the excess of the hull over the volume (the sides'
         * hulls hold the sides), a trade that less the join; a move whose plane is searched but whose
         * saving is not measured (est 3: its sample's bound did not exceed bv) by its sample's bound */
        for (;;) {
            double bv = min_gain;
            for (size_t g = 0; g < ng; g++)
                if (G[g].alive && G[g].est == 1) bv = fmax(bv, G[g].est_gain - cheapest_join_without(&cj, P, (uint32_t)g));
            for (size_t i = 0; i < np; i++)
                if (P[i].est == 1) bv = fmax(bv, P[i].est_gain);
            size_t nc = 0;
            for (size_t g = 0; g < ng && st == ACD_OK; g++) {
                double c0 = cheapest_join_without(&cj, P, (uint32_t)g);
                double ub = G[g].est == 3 ? G[g].est_ub - c0 : G[g].hvol - G[g].vol - c0;
                if (G[g].alive && (G[g].est == 0 || G[g].est == 3) && ub > bv) {
                    if (nc == capc && !grow_cands(&cands, &capc)) st = acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory");
                    else cands[nc++] = (refine_cand){ub, (uint32_t)g, 0};
                }
            }
            for (size_t i = 0; i < np && st == ACD_OK; i++) {
                const group *A = &G[P[i].a], *B = &G[P[i].b];
                double ub = P[i].est == 3 ? P[i].est_ub : A->hvol + B->hvol - A->vol - B->vol;
                if ((P[i].est == 0 || P[i].est == 3) && ub > bv) {
                    if (nc == capc && !grow_cands(&cands, &capc)) st = acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory");
                    else cands[nc++] = (refine_cand){ub, (uint32_t)i, 1};
                }
            }
            if (st != ACD_OK || !nc) break;
            qsort(cands, nc, sizeof *cands, cmp_refine_cand);
            if (nc > MERGE_REFINE_BATCH) nc = MERGE_REFINE_BATCH;
            /* the batch run longest first (each estimate writes only its own record: any order gives
             * the same estimates; longest first leaves the threads the least idle at its end) */
            size_t run[MERGE_REFINE_BATCH];
            double work[MERGE_REFINE_BATCH];
            for (size_t k = 0; k < nc; k++) {
                run[k] = k;
                const refine_cand *c = &cands[k];
                work[k] = c->pair ? estimate_work(&G[P[c->i].a], MERGE_REFINE_PAIR_AXES, P[c->i].est) +
                                        estimate_work(&G[P[c->i].b], MERGE_REFINE_PAIR_AXES, P[c->i].est)
                                  : estimate_work(&G[c->i], 3, G[c->i].est);
            }
            for (size_t k = 1; k < nc; k++)
                for (size_t m = k; m > 0 && work[run[m]] > work[run[m - 1]]; m--) {
                    size_t x = run[m];
                    run[m] = run[m - 1];
                    run[m - 1] = x;
                }
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nc > 1)
#endif
            for (long k = 0; k < (long)nc; k++) {
                const refine_cand *c = &cands[run[k]];
                if (!c->pair) estimate(&G[c->i], 3, cheapest_join_without(&cj, P, c->i), bv);
                else estimate_pair(G, &P[c->i], bv);
            }
        }
        if (st != ACD_OK) break;
        /* the best move: a trade of group x (its gain less the cheapest join surviving it), or a
         * re-cut of pair q */
        size_t x = SIZE_MAX, q = SIZE_MAX;
        double bestv = min_gain, c0x = INFINITY;
        for (size_t g = 0; g < ng; g++) {
            if (!G[g].alive || G[g].est != 1) continue;
            double c0 = cheapest_join_without(&cj, P, (uint32_t)g);
            if (G[g].est_gain - c0 > bestv) bestv = G[g].est_gain - c0, x = g, c0x = c0;
        }
        for (size_t i = 0; i < np; i++)
            if (P[i].est == 1 && P[i].est_gain > bestv) bestv = P[i].est_gain, q = i, x = SIZE_MAX;
        if (x == SIZE_MAX && q == SIZE_MAX) break;
        group *S = NULL, U;
        size_t ns = 0;
        double gain = 0;
        size_t n0 = at.n;
        int r;
        if (q != SIZE_MAX) {
            if (!pair_union(&G[P[q].a], &G[P[q].b], &U)) {
                st = acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory");
                break;
            }
            U.est_plane = P[q].est_plane;
            r = try_cut(&U, &at, nparts, &in_bvh, on_tol, diag, tol, tau, threads, &S, &ns, &gain, err);
            free(U.members);
        } else {
            r = try_cut(&G[x], &at, nparts, &in_bvh, on_tol, diag, tol, tau, threads, &S, &ns, &gain, err);
            gain -= c0x;
        }
        if (r < 0) {
            st = (acd_status)(-r);
            break;
        }
        if (r == 1 && !(gain > min_gain)) {
            for (size_t j = 0; j < ns; j++) group_free(&S[j]);
            free(S);
            S = NULL;
            for (size_t i = n0; i < at.n; i++) atom_clear(&at, i, nparts);
            at.n = n0;
            r = 0;
        }
        if (r == 0) {
            if (q != SIZE_MAX) P[q].est = 2;
            else G[x].est = 2;
            fails++;
            continue;
        }
        if (q != SIZE_MAX) st = commit_cut(&G, &ng, &capg, P[q].a, P[q].b, &at, n0, S, ns, tol, &P, &np, &capp, tau,
                                           by_volume, threads, err);
        else st = commit_cut(&G, &ng, &capg, (uint32_t)x, UINT32_MAX, &at, n0, S, ns, tol, &P, &np, &capp, tau,
                             by_volume, threads, err);
        free(S);
        /* the count back: a trade joins the cheapest pair, and a side of several components (ns > 2)
         * costs one more join per extra component, the cheapest joinable pairs then (none: the count
         * stays above; their added hull volume is not in the step's gain) */
        const size_t need = ns - (q != SIZE_MAX ? 2 : 1);
        for (size_t e = 0; e < need && st == ACD_OK; e++) {
            size_t best = best_pair(G, P, &np, tau, threads);
            if (best == SIZE_MAX) {
                if (e == 0 && q == SIZE_MAX) /* cannot happen: the pair of cost c0x is still there */
                    st = acd_fail(err, ACD_ERR_INTERNAL, "merge: no join after a refinement cut");
                break;
            }
            st = join_best(&G, &ng, &capg, &at, &P, &np, &capp, best, tau, din_refuse, by_volume, threads, err);
        }
        out->trades++;
    }
    free(cands);
    if (st == ACD_OK) {
        /* groups numbered by their lowest atom; the cut atoms in none */
        size_t na = at.n;
        uint32_t *num = malloc((ng ? ng : 1) * sizeof *num);
        out->group_of = realloc(out->group_of, (na ? na : 1) * sizeof *out->group_of);
        out->group_size = calloc(na ? na : 1, sizeof *out->group_size);
        out->bound = calloc(na ? na : 1, sizeof *out->bound);
        out->nnew = na - nparts;
        size_t nn = out->nnew ? out->nnew : 1;
        out->new_parts = calloc(nn, sizeof *out->new_parts);
        out->new_parent = malloc(nn * sizeof *out->new_parent);
        out->new_plane = malloc(nn * sizeof *out->new_plane);
        out->new_volume = malloc(nn * sizeof *out->new_volume);
        if (!num || !out->group_of || !out->group_size || !out->bound || !out->new_parts || !out->new_parent ||
            !out->new_plane || !out->new_volume) {
            st = acd_fail(err, ACD_ERR_NOMEM, "merge: out of memory");
        } else {
            for (size_t g = 0; g < ng; g++) num[g] = UINT32_MAX;
            for (size_t i = 0; i < na; i++) {
                uint32_t g = at.owner[i];
                if (g == UINT32_MAX) {
                    out->group_of[i] = UINT32_MAX;
                    continue;
                }
                if (num[g] == UINT32_MAX) {
                    num[g] = (uint32_t)out->ngroups++;
                    int pieces = 0;
                    for (size_t m = 0; m < G[g].nmembers; m++) pieces |= G[g].members[m] >= nparts;
                    out->bound[num[g]] = G[g].nmembers > 1 || pieces ? G[g].bound : 0.0;
                }
                out->group_of[i] = num[g];
                out->group_size[num[g]]++;
            }
            for (size_t k = 0; k < out->nnew; k++) {
                size_t i = nparts + k;
                out->new_parts[k] = at.mesh[i];
                memset(&at.mesh[i], 0, sizeof at.mesh[i]);
                out->new_parent[k] = at.parent[i];
                memcpy(out->new_plane[k], at.plane[i], sizeof(double[4]));
                out->new_volume[k] = at.vol[i];
            }
        }
        free(num);
    }
    if (st == ACD_OK && opts && opts->keep_trees) { /* the trees handed over (acd3/trim uses them) */
        out->part_bvh = calloc(nparts, sizeof *out->part_bvh);
        if (out->part_bvh) { /* (none: the caller builds them again) */
            out->npart_bvh = nparts;
            for (size_t i = 0; i < nparts; i++)
                if (!at.bvh_kept[i] && at.owner[i] != UINT32_MAX && out->group_size[out->group_of[i]] == 1) {
                    out->part_bvh[i] = at.bvh[i];
                    memset(&at.bvh[i], 0, sizeof at.bvh[i]);
                }
        }
        out->input_bvh = in_bvh.bvh;
        memset(&in_bvh.bvh, 0, sizeof in_bvh.bvh);
    }
    for (size_t g = 0; g < ng; g++) group_free(&G[g]);
    atoms_free(&at, nparts);
    in_surface_free(&in_bvh);
    for (size_t i = 0; i < np; i++) pair_free(&P[i]);
    free(G);
    free(P);
    if (st != ACD_OK) acd3_merge_result_free(out);
    return st;
}

void acd3_facet_table_free(acd3_facet_table *t) {
    if (!t) return;
    free(t->key);
    free(t->ub);
    memset(t, 0, sizeof *t);
}

double acd3_merge_hull_reach(const acd_bvh *part, const acd_hull *H, double tau) {
    return acd3_merge_hull_reach_table(part, H, tau, NULL);
}

double acd3_merge_hull_reach_table(const acd_bvh *part, const acd_hull *H, double tau, acd3_facet_table *table) {
    if (table) memset(table, 0, sizeof *table);
    if (H->dim != 3) return INFINITY;
    size_t nf = H->ntriangles;
    double *key = malloc((nf ? nf : 1) * 9 * sizeof *key), *ub = malloc((nf ? nf : 1) * sizeof *ub);
    double worst = INFINITY;
    if (key && ub) {
        uint32_t member = 0;
        atoms at;
        memset(&at, 0, sizeof at);
        at.bvh = (acd_bvh *)part; /* read only */
        group g;
        memset(&g, 0, sizeof g);
        g.at = &at;
        g.members = &member;
        g.nmembers = 1;
        worst = hull_facets_ub(&g, NULL, H, tau, 1, key, ub);
        /* every facet bounded (none above tau): the table group_init_hull's facet_table makes, the
         * same bounds in the same order, then sorted */
        if (table && worst <= tau && sort_facets(key, ub, nf)) {
            table->key = key;
            table->ub = ub;
            table->n = nf;
            table->tau = tau;
            return worst;
        }
    }
    free(key);
    free(ub);
    return worst;
}
