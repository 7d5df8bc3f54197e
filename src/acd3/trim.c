/* acd3/trim: hulls trimmed within a coverage budget (see trim.h). */
#include "acd3/trim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "acd3/poll.h"
#include "acd3/trim_beyond.h"
#include "core/error.h"
#include "geom3/bvh.h"
#include "geom3/vec3.h"
#include "mesh/selfintersect.h"

/* The depths a facet's plane is moved inward by, as fractions of the cube root of the part's
 * initial hull volume (increasing). */
static const double ACD3_TRIM_DEPTHS[ACD3_TRIM_NDEPTHS] = {0.001, 0.002, 0.005, 0.01, 0.02, 0.04};
#define NDEPTHS ((size_t)ACD3_TRIM_NDEPTHS)
/* Distinct hulls cut per round (their next cuts searched in parallel); fixed, so the result does not
 * depend on the thread count. */
#define ACD3_TRIM_BATCH 4
/* A cut removing no part volume is scored as removing this fraction of min_gain (finite ratios). */
#define ACD3_TRIM_LOSS_FLOOR 1e-6
/* An internal wall (is_wall): a part triangle with its corners within this fraction of the depth
 * unit of a facet plane and its centroid farther than that from the input's surface. */
#define ACD3_TRIM_WALL_REL 1e-6

/* A candidate plane of a hull: a facet plane of the initial hull or a plane a cut was made by, and
 * its caps at the depths: the hull volume beyond (gain, for the current hull) and the part volume
 * beyond (loss: the part never changes, so computed once). */
typedef struct trim_plane {
    double n[3], off0;               /* n.x = off0: the facet's plane (n unit, outward) */
    double gain[NDEPTHS], loss[NDEPTHS];
    double base;                     /* the part volume beyond n.x = off0 already charged (a cut's own
                                        plane: that cut's loss; a facet plane: 0) */
    double chg[NDEPTHS];             /* fmax(loss - base, 0): the part volume a cut at the depth charges */
    double den[NDEPTHS];             /* with the losses: fmax(chg, the loss floor), choose's denominators */
    int have_loss;
    int facet;                       /* a facet plane of the initial hull */
    int cut_id;                      /* not a facet plane: the cut it is the plane of (trim_hull.cutpl) */
    int wall_known, wall;            /* whether it holds an internal wall of the part (is_wall: then not
                                        cut), once asked */
    int dirty;                       /* gains measured before the last cuts: upper bounds */
    int best_ok;                     /* best_k, best_r hold the plane's best cap for its gains and a room
                                        no smaller than the current one (choose) */
    int best_k;                      /* -1: no cap fits */
    double best_r;
    double top;                      /* the largest n.x of the part's vertices (with the losses) */
    size_t lim;                      /* the caps at depths >= lim are refused: each would leave some of
                                        the part farther than maxdist from the hull (far_check) */
} trim_plane;

/* A convex polytope as outward triangles (a hull cut by planes: its triangles clipped, the section
 * fanned); vertices may repeat a position where a cut passed through a vertex. */
typedef struct trim_poly {
    double *v;        /* 3 * nv */
    size_t nv;
    uint32_t *t;      /* 3 * nt */
    size_t nt;
    double *pl;       /* 4 * nt: the plane each triangle lies in, n.x + d = 0, n outward unit */
} trim_poly;

static void poly_free(trim_poly *P) {
    free(P->v);
    free(P->t);
    free(P->pl);
    memset(P, 0, sizeof *P);
}

typedef struct trim_hull {
    trim_poly h;      /* the current hull */
    double *vdot;     /* h.nv once cut: its vertices' n.x in plane_measure (NULL: computed per triangle) */
    acd3_trim_tree tree; /* the part's triangles (from its BVH) */
    const acd_bvh *bvh;  /* the part's BVH: the caller's (acd3_trim_trees) or own_bvh */
    const acd_mesh *part; /* the part (its triangles: is_wall) */
    const acd_bvh *input_bvh; /* the input's tree (is_wall), or NULL: no input, walls not looked for */
    acd_bvh own_bvh;
    double unit;      /* depth unit: cube root of the initial hull volume */
    double loss_floor; /* a cut's loss is scored as at least this (ACD3_TRIM_LOSS_FLOOR x min_gain) */
    double centre[3]; /* of the initial hull's bounding box (apexes of the cones) */
    int active;       /* a solid hull that may still be cut */
    trim_plane *pl;   /* candidate planes */
    size_t npl, cappl;
    double *corner;   /* 3 * ncorner: the corners of the last cut's removed cap (the vertices at or
                         beyond the plane and the crossings) */
    size_t ncorner, cornercap;
    int cut;          /* cut at least once */
    int crossing;     /* the part intersects itself: not trimmed */
    size_t nt_limit;  /* more triangles than this after a cut: the polytope re-hulled */
    int stale;        /* the best cut to choose again (the hull was cut) */
    int have;         /* best cut found */
    double plane[3], off, gain, loss, full, ratio, depth; /* the best cut: loss its charge's bound, full the
                                                             part volume beyond its plane */
    size_t bj, bk;    /* the best cut's plane and depth */
    double reach;     /* how far the part reaches beyond the best cut's plane (>= 0) */
    double *cutpl;    /* 4 per cut made (n, off), in order: charge_cut's clips */
    size_t ncut, cutcap;
    double *capc;     /* 3 per corner: the corners of each cut's removed cap, cut c's from capoff[c] to
                         capoff[c + 1] (charge_cut) */
    size_t ncapc, capccap, *capoff;
    double *rel;      /* charge_cut's scratch: the planes of the cuts that matter (4 per) */
    double charge;    /* the last cut's charge (charge_cut: exact, at most loss) */
    unsigned char *tkind; /* per part triangle (wall_check, allocated at the first check): 0 not known,
                             1 an internal wall (off the input's surface), 2 on the surface */
    double maxdist;   /* a cut may leave no vertex of the part farther than this from the hull */
    unsigned char *outside; /* per part vertex (far_check, allocated at the first check): outside the hull */
    double *closest;  /* 3 per part vertex: an outside vertex's closest point of the hull */
    uint32_t *pend;   /* far_check's scratch: the vertices measured, their closest points in pendq */
    double *pendq;
    size_t refused;   /* cuts refused by far_check */
} trim_hull;

/* T's polytope replaced by hull h (3D), its arrays taken over (h's set to NULL: acd_hull_free then
 * frees the rest). */
static void hull_take(trim_hull *T, acd_hull *h) {
    poly_free(&T->h);
    T->h.v = h->vertices, T->h.nv = h->nvertices;
    T->h.t = h->triangles, T->h.nt = h->ntriangles;
    T->h.pl = h->planes;
    h->vertices = NULL, h->triangles = NULL, h->planes = NULL;
}

static void apex_on(const double centre[3], const double n[3], double off, double o[3]) {
    double s = acd_dot3(n, centre) - off; /* n unit */
    for (int k = 0; k < 3; k++) o[k] = centre[k] - s * n[k];
}

static void plane_levels(const trim_hull *T, const trim_plane *P, acd3_trim_levels *L) {
    for (size_t k = 0; k < NDEPTHS; k++) {
        double apex[3];
        L->off[k] = P->off0 - ACD3_TRIM_DEPTHS[k] * T->unit;
        apex_on(T->centre, P->n, L->off[k], apex);
        L->ax[k] = apex[0], L->ay[k] = apex[1], L->az[k] = apex[2];
    }
}

/* The triangles of a hull with their neighbours, for plane_measure's search from a facet. */
typedef struct trim_adj {
    const uint32_t *nbr; /* 3 * nt: the triangle across each edge */
    uint32_t *mark;      /* nt: the stamp of the last search that reached the triangle */
    uint32_t *stack;     /* nt */
    uint32_t stamp;
} trim_adj;

/* P's gains for the current hull, and its losses when not known and some gain reaches min_gain.
 * With adj (the hull's neighbours) only the triangles reached from triangle `seed` (which lies in
 * P's plane) through triangles beyond the deepest plane are visited: the hull's surface beyond a
 * plane is one disk, and the triangles meeting it are connected through their edges. */
static void plane_measure(trim_hull *T, trim_plane *P, double min_gain, trim_adj *adj, uint32_t seed) {
    acd3_trim_levels L;
    plane_levels(T, P, &L);
    double gain[NDEPTHS] = {0}; /* (summed here: not through P, which the compiler cannot keep apart) */
    const trim_poly *h = &T->h;
    const double deepest = L.off[NDEPTHS - 1];
    if (adj) {
        uint32_t sp = 0;
        adj->stamp++;
        adj->mark[seed] = adj->stamp;
        adj->stack[sp++] = seed;
        while (sp > 0) {
            uint32_t t = adj->stack[--sp];
            const uint32_t *tr = h->t + 3 * (size_t)t;
            const double *const p[3] = {h->v + 3 * (size_t)tr[0], h->v + 3 * (size_t)tr[1], h->v + 3 * (size_t)tr[2]};
            const double d[3] = {acd_dot3(P->n, p[0]), acd_dot3(P->n, p[1]), acd_dot3(P->n, p[2])};
            if (!(acd3_trim_top(d) > deepest)) continue;
            acd3_trim_tri_beyond(p, d, &L, 0, gain);
            for (int e = 0; e < 3; e++) {
                uint32_t g = adj->nbr[3 * (size_t)t + e];
                if (g < h->nt && adj->mark[g] != adj->stamp) {
                    adj->mark[g] = adj->stamp;
                    adj->stack[sp++] = g;
                }
            }
        }
    } else if (T->vdot) { /* every triangle, a cut hull's vertex dots computed once (in T->vdot) */
        double *vd = T->vdot;
        for (size_t v = 0; v < h->nv; v++) vd[v] = acd_dot3(P->n, h->v + 3 * v);
        for (size_t t = 0; t < h->nt; t++) {
            const uint32_t *tr = h->t + 3 * t;
            const double d[3] = {vd[tr[0]], vd[tr[1]], vd[tr[2]]};
            if (!(acd3_trim_top(d) > deepest)) continue;
            const double *const p[3] = {h->v + 3 * (size_t)tr[0], h->v + 3 * (size_t)tr[1], h->v + 3 * (size_t)tr[2]};
            acd3_trim_tri_beyond(p, d, &L, 0, gain);
        }
    } else { /* every triangle (T->vdot not allocated: out of memory) */
        for (size_t t = 0; t < h->nt; t++) {
            const uint32_t *tr = h->t + 3 * t;
            const double *const p[3] = {h->v + 3 * (size_t)tr[0], h->v + 3 * (size_t)tr[1], h->v + 3 * (size_t)tr[2]};
            const double d[3] = {acd_dot3(P->n, p[0]), acd_dot3(P->n, p[1]), acd_dot3(P->n, p[2])};
            if (acd3_trim_top(d) > deepest) acd3_trim_tri_beyond(p, d, &L, 0, gain);
        }
    }
    memcpy(P->gain, gain, sizeof gain);
    P->best_ok = 0;
    if (P->have_loss || !(P->gain[NDEPTHS - 1] >= min_gain)) return; /* the deepest cap holds the others */
    memset(P->loss, 0, sizeof P->loss);
    /* only the depths whose cap can be cut: gains only fall, so a cap under min_gain stays under */
    size_t k_lo = 0;
    while (!(P->gain[k_lo] >= min_gain)) k_lo++;
    double top;
    acd3_trim_tree_beyond(&T->tree, P->n, &L, k_lo, P->loss, &top);
    /* a vertex x of the part beyond a level lies at least n.x - off from the hull cut there (the
     * rest of the hull is on the other side of the plane): the depths where the part's top vertex is
     * farther than maxdist are refused without a cut (the levels deepen: so are all deeper ones) */
    while (P->lim > 0 && top - L.off[P->lim - 1] > T->maxdist) P->lim--;
    P->top = top;
    for (size_t k = 0; k < NDEPTHS; k++) {
        P->loss[k] = fmax(P->loss[k], 0.0);
        P->chg[k] = fmax(P->loss[k] - P->base, 0.0);
        P->den[k] = fmax(P->chg[k], T->loss_floor); /* (once: the losses never change) */
    }
    P->have_loss = 1;
}

static int add_plane(trim_hull *T, const double n[3], double off0) {
    if (T->npl == T->cappl) {
        size_t nc = T->cappl ? 2 * T->cappl : 64;
        trim_plane *np = realloc(T->pl, nc * sizeof *np);
        if (!np) return 0;
        T->pl = np;
        T->cappl = nc;
    }
    trim_plane *P = &T->pl[T->npl++];
    memset(P, 0, sizeof *P);
    memcpy(P->n, n, sizeof P->n);
    P->off0 = off0;
    P->lim = NDEPTHS;
    return 1;
}

/* Whether facet plane P of T holds a triangle of T's part that is not on the input's surface: an
 * internal wall (a face a cut made, or a section of a join) lying on the hull's boundary. The hull's
 * facet there spans the wall and air beside it, so its caps can pass the ratio test, and cutting one
 * takes the part's layer along the wall out of every hull (the neighbour lies across the wall): the
 * union's boundary then runs through the solid, far from its surface (fandisk with min_gain 6e-6:
 * concavity_max 0.0116 -> 0.025; docs/results/3d-armadillo.md). A triangle of the input's surface,
 * clipped or not, lies on it. A triangle in the plane: its corners within ACD3_TRIM_WALL_REL x the
 * depth unit of it (the part's triangles near it from its tree); off the surface: its centroid
 * farther than that from the input's triangles. */
typedef struct wall_query {
    const acd_mesh *m;
    const acd_bvh *input;
    const double *n;
    double off, tol;
    int wall;
} wall_query;

static int wall_tri(void *user, uint32_t t) {
    wall_query *q = user;
    const double *p[3];
    for (int k = 0; k < 3; k++) {
        p[k] = q->m->vertices + 3 * (size_t)q->m->triangles[3 * (size_t)t + k];
        if (!(fabs(acd_dot3(q->n, p[k]) - q->off) <= q->tol)) return 0; /* not in the plane */
    }
    double g[3];
    for (int k = 0; k < 3; k++) g[k] = (p[0][k] + p[1][k] + p[2][k]) / 3;
    acd_bvh_closest_result r;
    q->wall = acd_bvh_closest(q->input, g, q->tol * q->tol, &r) == 0; /* no input point within tol */
    return q->wall;
}

static int is_wall(const trim_hull *T, const trim_plane *P) {
    wall_query q = {T->part, T->input_bvh, P->n, P->off0, ACD3_TRIM_WALL_REL * T->unit, 0};
    acd_bvh_query_halfspace(T->bvh, P->n, P->off0 - q.tol, wall_tri, &q);
    return q.wall;
}

/* The best cut of hull T among its planes' caps (largest gain / charge) charging at most `room` of
 * part volume. A cap's charge here is its loss less the plane's base, an upper bound of what the cut
 * is then charged (charge_cut, exact): the part volume beyond the plane's
 * own level (off0), which is beyond each of its depths, was charged already when off0 is the plane
 * of a cut made on this hull (after_cut); 0 for a facet plane, which the part does not cross. The
 * cuts made along one normal thus charge, summed, the part volume beyond the deepest: each region
 * outside the trimmed hull is charged at least once (the guarantee, docs/acd3d.md). */
static void choose(trim_hull *T, double room, double min_gain, double ratio_floor) {
    T->have = 0;
    if (!T->active) return;
    /* lazily: a plane whose caps met a removed cap keeps its old gains, upper bounds (gains only
     * fall); when the best is such a plane its gains are measured again on the hull and the search
     * repeated, so the choice is the best of the exact ratios */
    for (;;) {
        size_t bj = SIZE_MAX, bk = 0;
        T->have = 0;
        for (size_t j = 0; j < T->npl; j++) {
            trim_plane *P = &T->pl[j];
            if (!P->have_loss || P->wall) continue;
            /* the plane's best cap (the first of largest ratio), kept while its gains stand and it fits
             * the room: the room only shrinks, and the best of fewer caps is the same while it is among
             * them; the first plane of largest best ratio is then the scan's first cap of largest ratio */
            if (!P->best_ok || (P->best_k >= 0 && !(P->chg[P->best_k] <= room))) {
                P->best_k = -1;
                for (size_t k = 0; k < P->lim; k++) {
                    if (!(P->gain[k] >= min_gain) || !(P->chg[k] <= room)) continue;
                    double r = P->gain[k] / P->den[k];
                    if (!(r > ratio_floor) || (P->best_k >= 0 && !(r > P->best_r))) continue;
                    P->best_k = (int)k;
                    P->best_r = r;
                }
                P->best_ok = 1;
            }
            if (P->best_k < 0 || (T->have && !(P->best_r > T->ratio))) continue;
            T->have = 1;
            bj = j, bk = (size_t)P->best_k;
            T->ratio = P->best_r;
        }
        if (!T->have) return;
        trim_plane *B = &T->pl[bj];
        if (B->facet && !B->wall_known && T->input_bvh) { /* asked of the planes that would be cut only */
            B->wall_known = 1;
            B->wall = is_wall(T, B);
            if (B->wall) continue;
        }
        if (!T->pl[bj].dirty) {
            const trim_plane *P = &T->pl[bj];
            memcpy(T->plane, P->n, sizeof T->plane);
            T->off = P->off0 - ACD3_TRIM_DEPTHS[bk] * T->unit;
            T->gain = P->gain[bk];
            T->loss = P->chg[bk];
            T->full = P->loss[bk];
            T->depth = ACD3_TRIM_DEPTHS[bk] * T->unit;
            T->bj = bj, T->bk = bk;
            T->reach = fmax(P->top - T->off, 0.0);
            return;
        }
        T->pl[bj].dirty = 0;
        plane_measure(T, &T->pl[bj], min_gain, NULL, 0); /* (its losses are kept) */
    }
}

/* The part volume the cut just made (T->plane, T->off) removed from the hull, exactly: the part
 * beyond the plane and inside every earlier cut (acd3_trim_tree_charge), in T->charge; at most
 * T->loss (the loss less the plane's base, an upper bound of it that counts a region beyond two
 * cuts' planes twice: on the armadillo the charges summed 6% over the volume outside), which stands
 * when the clipping gives up. Only the earlier cuts whose removed caps reach beyond the plane matter:
 * a point of the part beyond the plane and outside the hull lies in the cap of the first cut that
 * removed it, and beyond that cut's plane. None: the charge is the loss (a facet plane's, the part
 * beyond it); only the cut whose plane this is, deeper: the loss less the base (the part between the
 * two parallel planes), both exact. The cut's plane and cap's corners are then recorded for the next
 * cuts. 0 out of memory. */
static int charge_cut(trim_hull *T) {
    if (!T->capoff) {
        T->capoff = malloc(sizeof *T->capoff);
        if (!T->capoff) return 0;
        T->capoff[0] = 0;
    }
    if (T->ncut == T->cutcap) {
        const size_t nc = T->cutcap ? 2 * T->cutcap : 16;
        double *np = realloc(T->cutpl, 4 * nc * sizeof *np), *nr = np ? realloc(T->rel, 4 * nc * sizeof *nr) : NULL;
        if (np) T->cutpl = np;
        if (nr) T->rel = nr;
        size_t *no = nr ? realloc(T->capoff, (nc + 1) * sizeof *no) : NULL;
        if (!no) return 0;
        T->capoff = no, T->cutcap = nc;
    }
    if (T->ncapc + T->ncorner > T->capccap) {
        size_t nc = T->capccap ? 2 * T->capccap : 256;
        while (nc < T->ncapc + T->ncorner) nc *= 2;
        double *np = realloc(T->capc, 3 * nc * sizeof *np);
        if (!np) return 0;
        T->capc = np, T->capccap = nc;
    }
    const trim_plane *B = &T->pl[T->bj];
    const size_t own = B->facet ? SIZE_MAX : (size_t)B->cut_id;
    size_t nrel = 0, nother = 0;
    for (size_t c = 0; c < T->ncut; c++) {
        int meets = 0;
        for (size_t v = T->capoff[c]; v < T->capoff[c + 1] && !meets; v++)
            meets = acd_dot3(T->plane, T->capc + 3 * v) > T->off;
        if (!meets) continue;
        memcpy(T->rel + 4 * nrel++, T->cutpl + 4 * c, 4 * sizeof *T->rel);
        nother += c != own;
    }
    T->charge = T->loss;
    if (nother > 0) {
        /* the apex: the centroid of the section (the cap's corners on the plane, its crossings), on
         * the plane and inside the hull, so inside every earlier cut: a triangle's cone from it then
         * needs clipping only where the triangle's part beyond the plane is not (most are) */
        double apex[3] = {0, 0, 0}, m = 0;
        const double tol = ACD3_TRIM_WALL_REL * T->unit;
        for (size_t v = 0; v < T->ncorner; v++) {
            const double *x = T->corner + 3 * v;
            if (!(fabs(acd_dot3(T->plane, x) - T->off) <= tol)) continue;
            for (int k = 0; k < 3; k++) apex[k] += x[k];
            m++;
        }
        if (m > 0) {
            for (int k = 0; k < 3; k++) apex[k] /= m;
            apex_on(apex, T->plane, T->off, apex);
        } else
            apex_on(T->centre, T->plane, T->off, apex);
        const double ex = acd3_trim_tree_charge(&T->tree, T->plane, T->off, apex, T->rel, nrel);
        if (ex == ex) T->charge = fmin(fmax(ex, 0.0), T->loss);
    }
    double *c = T->cutpl + 4 * T->ncut;
    memcpy(c, T->plane, 3 * sizeof *c);
    c[3] = T->off;
    memcpy(T->capc + 3 * T->ncapc, T->corner, 3 * T->ncorner * sizeof *T->capc);
    T->ncapc += T->ncorner;
    T->capoff[++T->ncut] = T->ncapc;
    return 1;
}

static int after_cut(trim_hull *T, double min_gain) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < T->ncorner; v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], T->corner[3 * v + k]);
            hi[k] = fmax(hi[k], T->corner[3 * v + k]);
        }
    for (size_t j = 0; j < T->npl; j++) {
        trim_plane *P = &T->pl[j];
        double deepest = P->off0 - ACD3_TRIM_DEPTHS[NDEPTHS - 1] * T->unit;
        if (!(acd_box_max_dot(P->n, lo, hi) > deepest)) continue; /* the cap's box is below: so is the cap */
        int meets = 0;
        for (size_t v = 0; v < T->ncorner && !meets; v++) meets = acd_dot3(P->n, T->corner + 3 * v) > deepest;
        if (meets) P->dirty = 1; /* its caps lost what they held of the removed cap: measured when needed */
    }
    if (!add_plane(T, T->plane, T->off)) return 0;
    T->pl[T->npl - 1].base = T->full;
    T->pl[T->npl - 1].cut_id = (int)T->ncut - 1; /* (charge_cut has recorded the cut) */
    plane_measure(T, &T->pl[T->npl - 1], min_gain, NULL, 0);
    return 1;
}

typedef struct facet_key {
    double pl[4];
    uint32_t t;
} facet_key;

static int facet_cmp(const void *a, const void *b) {
    const facet_key *x = a, *y = b;
    int c = memcmp(x->pl, y->pl, sizeof x->pl);
    return c ? c : (x->t > y->t) - (x->t < y->t);
}

/* Facets measured between two polls of init_planes (a large part's planes took 0.48 CPU-s at 832k
 * faces). */
#define TRIM_PLANES_POLL 16

/* The hull's facet planes as candidates, measured (a facet split into triangles once: its
 * triangles carry the same plane; searched from its triangle of lowest index). nbr: the hull's
 * neighbours (acd_hull.neighbors). poll (may be NULL): asked every TRIM_PLANES_POLL facets; a stop
 * leaves the planes measured so far (1: the caller sees the stop). */
static int init_planes(trim_hull *T, double min_gain, const uint32_t *nbr, acd3_poll *poll) {
    const trim_poly *h = &T->h;
    facet_key *keys = malloc(h->nt * sizeof *keys);
    uint32_t *mark = calloc(h->nt, sizeof *mark), *stack = malloc(h->nt * sizeof *stack);
    int ok = keys && mark && stack;
    for (size_t f = 0; ok && f < h->nt; f++) {
        memcpy(keys[f].pl, h->pl + 4 * f, sizeof keys[f].pl);
        keys[f].t = (uint32_t)f;
    }
    if (ok) qsort(keys, h->nt, sizeof *keys, facet_cmp);
    trim_adj adj = {nbr, mark, stack, 0};
    for (size_t f = 0; f < h->nt && ok; f++) {
        const double *pl = keys[f].pl;
        if (f > 0 && !memcmp(keys[f - 1].pl, pl, sizeof keys[f].pl)) continue;
        if (f % TRIM_PLANES_POLL == TRIM_PLANES_POLL - 1 && acd3_poll_stop(poll)) break;
        ok = add_plane(T, pl, -pl[3]);
        if (ok) T->pl[T->npl - 1].facet = 1;
        if (ok) plane_measure(T, &T->pl[T->npl - 1], min_gain, &adj, keys[f].t);
    }
    free(keys), free(mark), free(stack);
    return ok;
}

typedef struct sect_pt {
    double ang;
    uint32_t v;
} sect_pt;

static int sect_cmp(const void *a, const void *b) {
    const sect_pt *x = a, *y = b;
    return x->ang < y->ang ? -1 : x->ang > y->ang ? 1 : (x->v > y->v) - (x->v < y->v);
}

/* The squared distance from x to the convex polytope P (0 inside), its closest point in q: the
 * nearest of the triangles whose planes x lies beyond (the closest point of the boundary lies on
 * a facet that x is beyond: x minus it is in the point's normal cone, a combination of the normals
 * of the facets there with weights >= 0, so it has a positive dot with one of them); a triangle
 * whose plane is already as far as the best is skipped. */
static double poly_dist2(const trim_poly *P, const double x[3], double q[3]) {
    double best = INFINITY;
    for (size_t t = 0; t < P->nt; t++) {
        const double *pl = P->pl + 4 * t;
        const double s = acd_dot3(pl, x) + pl[3];
        if (!(s > 0) || !(s * s < best)) continue;
        const uint32_t *tr = P->t + 3 * t;
        double c[3];
        const double d2 = acd_closest_point_triangle(x, P->v + 3 * (size_t)tr[0], P->v + 3 * (size_t)tr[1],
                                                     P->v + 3 * (size_t)tr[2], c);
        if (d2 < best) best = d2, memcpy(q, c, sizeof c);
    }
    if (best == INFINITY) best = 0, memcpy(q, x, 3 * sizeof(double)); /* beyond none: inside */
    return best;
}

/* Whether cutting T's hull by n.x = off into P leaves every vertex of the part within T->maxdist of
 * P (the thin-feature bound, docs/acd3d.md "Trimmed hulls"). The part's surface is its triangles,
 * and the distance to a convex set is convex, so on a triangle it is largest at a corner: the
 * vertices bound the whole surface. Measured: the vertices beyond the plane, and those outside the
 * hull already whose closest point of it lies beyond the plane (the others keep their distance: P
 * lies in the hull and holds that point). 1 within (the closest points then recorded), 0 not, -1
 * out of memory. */
static int far_check(trim_hull *T, const trim_poly *P, const double n[3], double off) {
    if (T->maxdist == INFINITY) return 1;
    const acd_mesh *m = T->part;
    const size_t nv = m->nvertices;
    if (!T->outside) {
        T->outside = calloc(nv ? nv : 1, 1);
        T->closest = malloc(3 * (nv ? nv : 1) * sizeof *T->closest);
        T->pend = malloc((nv ? nv : 1) * sizeof *T->pend);
        T->pendq = malloc(3 * (nv ? nv : 1) * sizeof *T->pendq);
        if (!T->outside || !T->closest || !T->pend || !T->pendq) {
            free(T->outside), free(T->closest), free(T->pend), free(T->pendq);
            T->outside = NULL, T->closest = NULL, T->pend = NULL, T->pendq = NULL;
            return -1;
        }
    }
    const double lim2 = T->maxdist * T->maxdist;
    size_t np = 0;
    for (size_t v = 0; v < nv; v++) {
        const double *x = m->vertices + 3 * v;
        if (!(acd_dot3(n, x) > off) && !(T->outside[v] && acd_dot3(n, T->closest + 3 * v) > off)) continue;
        double *q = T->pendq + 3 * np;
        if (!(poly_dist2(P, x, q) <= lim2)) return 0;
        T->pend[np++] = (uint32_t)v;
    }
    for (size_t i = 0; i < np; i++) {
        const uint32_t v = T->pend[i];
        memcpy(T->closest + 3 * (size_t)v, T->pendq + 3 * i, 3 * sizeof(double));
        T->outside[v] = 1; /* (a vertex measured inside keeps itself as its closest point: harmless) */
    }
    return 1;
}

/* Whether the part's internal walls beyond the plane n.x = off lie within T->maxdist - T->reach of
 * the input's surface (the bound on the union's new boundary, docs/acd3d.md "Trimmed hulls"). A cut
 * exposes the section of the part on its plane: from a point y of it, the part is left along n
 * within reach (the part's vertices reach no farther beyond the plane), at a point z of its surface
 * beyond the plane: the input's surface (y then within reach of it), or an internal wall, whose
 * neighbour part lies beyond and is not covered by this hull: y is then within reach + dist(z,
 * surface). The walls beyond the plane are their triangles (those off the input's surface: the
 * centroid farther than ACD3_TRIM_WALL_REL x the depth unit from it) clipped to the side beyond,
 * sampled on a grid of spacing at most h = maxdist / 8 (every point within h of a sample: the
 * distance moves by at most the step), each sample within maxdist - reach - h of the input's
 * triangles. A cap that slices a wedge along a wall (text_on_cube: a slab 0.49 thick along a cut
 * face, the union's boundary then 16 units inside the solid) is refused. 1 within, 0 not, -1 out of
 * memory. */
typedef struct wall_check_q {
    trim_hull *T;
    const double *n;
    double off, h, lim2;
    int fail;
} wall_check_q;

static int wall_sample(const wall_check_q *q, const double a[3], const double b[3], const double c[3]) {
    double e = 0;
    for (int k = 0; k < 3; k++) {
        const double *u = k == 0 ? a : k == 1 ? b : a, *w = k == 0 ? b : c;
        const double d[3] = {w[0] - u[0], w[1] - u[1], w[2] - u[2]};
        e = fmax(e, sqrt(acd_dot3(d, d)));
    }
    const double mm = ceil(e / q->h);
    const int m = mm < 1 ? 1 : mm > 4096 ? 4096 : (int)mm;
    for (int i = 0; i <= m; i++)
        for (int j = 0; i + j <= m; j++) {
            double p[3];
            for (int k = 0; k < 3; k++) p[k] = a[k] + (b[k] - a[k]) * i / m + (c[k] - a[k]) * j / m;
            acd_bvh_closest_result r;
            if (!acd_bvh_closest(q->T->input_bvh, p, q->lim2, &r)) return 0;
        }
    return 1;
}

static int wall_check_tri(void *user, uint32_t t) {
    wall_check_q *q = user;
    trim_hull *T = q->T;
    const acd_mesh *m = T->part;
    const double *p[3];
    double s[3];
    int nb = 0;
    for (int k = 0; k < 3; k++) {
        p[k] = m->vertices + 3 * (size_t)m->triangles[3 * (size_t)t + k];
        s[k] = acd_dot3(q->n, p[k]) - q->off;
        nb += s[k] > 0;
    }
    if (nb == 0) return 0;
    if (!T->tkind[t]) {
        double g[3];
        for (int k = 0; k < 3; k++) g[k] = (p[0][k] + p[1][k] + p[2][k]) / 3;
        const double tol = ACD3_TRIM_WALL_REL * T->unit;
        acd_bvh_closest_result r;
        T->tkind[t] = acd_bvh_closest(T->input_bvh, g, tol * tol, &r) ? 2 : 1;
    }
    if (T->tkind[t] == 2) return 0;
    if (!(q->lim2 > 0)) return q->fail = 1; /* no room: no wall may reach beyond */
    double poly[4][3]; /* the triangle's part beyond the plane */
    int np = 0;
    for (int k = 0; k < 3; k++) {
        const int k1 = k == 2 ? 0 : k + 1;
        if (s[k] > 0) memcpy(poly[np++], p[k], sizeof poly[0]);
        if ((s[k] > 0) != (s[k1] > 0) && s[k] != s[k1]) {
            const double x = s[k] / (s[k] - s[k1]);
            for (int c = 0; c < 3; c++) poly[np][c] = p[k][c] + x * (p[k1][c] - p[k][c]);
            np++;
        }
    }
    for (int i = 1; i + 1 < np; i++)
        if (!wall_sample(q, poly[0], poly[i], poly[i + 1])) return q->fail = 1;
    if (np == 1 && !wall_sample(q, poly[0], poly[0], poly[0])) return q->fail = 1;
    return 0;
}

static int wall_check(trim_hull *T, const double n[3], double off) {
    if (!T->input_bvh || T->maxdist == INFINITY) return 1;
    if (!T->tkind) {
        T->tkind = calloc(T->part->ntriangles ? T->part->ntriangles : 1, 1);
        if (!T->tkind) return -1;
    }
    const double h = T->maxdist / 8, lim = T->maxdist - T->reach - h;
    wall_check_q q = {T, n, off, h, lim > 0 ? lim * lim : 0, 0};
    acd_bvh_query_halfspace(T->bvh, n, off, wall_check_tri, &q);
    return !q.fail;
}

/* The hull cut by the plane n.x = off (T->plane, T->off), by clipping its triangles: those below
 * kept, those crossing clipped (the crossing of an edge computed once, from its lower vertex
 * index), the section (the crossings and the vertices on the plane, in convex position) fanned in
 * angular order; the removed cap's corners kept in T->corner.
 * 1 done, 0 refused (more than max_vertices, or nothing removed), 2 refused by far_check (the hull
 * kept; the cap's depth and the deeper ones of its plane then refused: the hull only shrinks, so
 * the distances only grow), -1 out of memory. */
static int cut_hull(trim_hull *T, size_t max_vertices) {
    const trim_poly *h = &T->h;
    const double *n = T->plane;
    size_t nv = h->nv, nt = h->nt;
    double *s = malloc(nv * sizeof *s);
    uint32_t *map = malloc(nv * sizeof *map);
    /* crossings: per crossing edge, the new vertex of that edge (found through the edge's twin by a
     * search over the vertex's triangles would cost more: an edge key table, sized once the triangles
     * crossing the plane are counted) */
    size_t ekcap = 1;
    uint64_t *ekey = NULL;
    uint32_t *eval = NULL;
    trim_poly out = {0};
    size_t vcap = nv + 3 * nt + 8, tcap = 5 * nt + 16;
    out.v = malloc(3 * vcap * sizeof *out.v);
    out.t = malloc(3 * tcap * sizeof *out.t);
    out.pl = malloc(4 * tcap * sizeof *out.pl);
    sect_pt *sec = malloc(vcap * sizeof *sec);
    if (T->cornercap < vcap) {
        double *nc = realloc(T->corner, 3 * vcap * sizeof *nc);
        if (nc) {
            T->corner = nc;
            T->cornercap = vcap;
        }
    }
    int ret = -1;
    if (!s || !map || !out.v || !out.t || !out.pl || !sec || T->cornercap < vcap) goto done;
    size_t nbeyond = 0;
    T->ncorner = 0;
    for (size_t v = 0; v < nv; v++) {
        s[v] = acd_dot3(n, h->v + 3 * v) - T->off;
        map[v] = UINT32_MAX;
        nbeyond += s[v] > 0;
        if (s[v] >= 0) memcpy(T->corner + 3 * T->ncorner++, h->v + 3 * v, 3 * sizeof(double));
    }
    ret = 0;
    if (nbeyond == 0) goto done;
    size_t ncross = 0; /* triangles with corners on both sides: two crossing edges each */
    for (size_t t = 0; t < nt; t++) {
        const uint32_t *tr = h->t + 3 * t;
        ncross += (s[tr[0]] > 0 || s[tr[1]] > 0 || s[tr[2]] > 0) && (s[tr[0]] < 0 || s[tr[1]] < 0 || s[tr[2]] < 0);
    }
    while (ekcap < 4 * ncross + 16) ekcap <<= 1;
    ekey = malloc(ekcap * sizeof *ekey);
    eval = malloc(ekcap * sizeof *eval);
    ret = -1;
    if (!ekey || !eval) goto done;
    ret = 0;
    memset(ekey, 0xff, ekcap * sizeof *ekey);
    size_t nsec = 0;
#define ADD_V(p) (memcpy(out.v + 3 * out.nv, (p), 3 * sizeof(double)), (uint32_t)out.nv++)
    for (size_t t = 0; t < nt; t++) {
        const uint32_t *tr = h->t + 3 * t;
        int nb = (s[tr[0]] > 0) + (s[tr[1]] > 0) + (s[tr[2]] > 0);
        if (nb == 3) continue; /* beyond: removed */
        uint32_t below[4];
        int nbl = 0;
        for (int k = 0; k < 3; k++) {
            uint32_t a = tr[k], b = tr[k == 2 ? 0 : k + 1];
            if (!(s[a] > 0)) { /* at or below: kept (on the plane: also a corner of the section and of the cap) */
                if (map[a] == UINT32_MAX) {
                    map[a] = ADD_V(h->v + 3 * (size_t)a);
                    if (s[a] == 0) sec[nsec++].v = map[a];
                }
                below[nbl++] = map[a];
            }
            if ((s[a] < 0 && s[b] > 0) || (s[a] > 0 && s[b] < 0)) { /* a crossing edge */
                uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
                uint64_t key = (uint64_t)lo << 32 | hi;
                size_t slot = (size_t)((key * 0x9E3779B97F4A7C15ull) >> 20) & (ekcap - 1);
                while (ekey[slot] != UINT64_MAX && ekey[slot] != key) slot = (slot + 1) & (ekcap - 1);
                if (ekey[slot] != key) {
                    double x = s[lo] / (s[lo] - s[hi]), p[3];
                    for (int q = 0; q < 3; q++) p[q] = h->v[3 * (size_t)lo + q] + x * (h->v[3 * (size_t)hi + q] - h->v[3 * (size_t)lo + q]);
                    ekey[slot] = key;
                    eval[slot] = ADD_V(p);
                    sec[nsec++].v = eval[slot];
                    memcpy(T->corner + 3 * T->ncorner++, p, sizeof p);
                }
                below[nbl++] = eval[slot];
            }
        }
        for (int k = 1; k + 1 < nbl; k++) { /* the part below, fanned, in the triangle's plane */
            uint32_t *o = out.t + 3 * out.nt;
            o[0] = below[0], o[1] = below[k], o[2] = below[k + 1];
            memcpy(out.pl + 4 * out.nt, h->pl + 4 * t, 4 * sizeof(double));
            out.nt++;
        }
    }
#undef ADD_V
    if (nsec >= 3) { /* the section, counterclockwise seen from the side beyond (outward for the kept part) */
        double c[3] = {0, 0, 0}, u[3], w[3];
        for (size_t i = 0; i < nsec; i++)
            for (int q = 0; q < 3; q++) c[q] += out.v[3 * (size_t)sec[i].v + q] / (double)nsec;
        int ax = fabs(n[0]) < fabs(n[1]) ? (fabs(n[0]) < fabs(n[2]) ? 0 : 2) : (fabs(n[1]) < fabs(n[2]) ? 1 : 2);
        double e[3] = {0, 0, 0};
        e[ax] = 1;
        double un = 0;
        u[0] = n[1] * e[2] - n[2] * e[1], u[1] = n[2] * e[0] - n[0] * e[2], u[2] = n[0] * e[1] - n[1] * e[0];
        un = sqrt(acd_dot3(u, u));
        for (int q = 0; q < 3; q++) u[q] /= un;
        w[0] = n[1] * u[2] - n[2] * u[1], w[1] = n[2] * u[0] - n[0] * u[2], w[2] = n[0] * u[1] - n[1] * u[0];
        for (size_t i = 0; i < nsec; i++) {
            const double *p = out.v + 3 * (size_t)sec[i].v;
            double d[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
            sec[i].ang = atan2(acd_dot3(d, w), acd_dot3(d, u));
        }
        qsort(sec, nsec, sizeof *sec, sect_cmp);
        const double pl[4] = {n[0], n[1], n[2], -T->off};
        for (size_t i = 1; i + 1 < nsec; i++) {
            uint32_t *o = out.t + 3 * out.nt;
            o[0] = sec[0].v, o[1] = sec[i].v, o[2] = sec[i + 1].v;
            memcpy(out.pl + 4 * out.nt, pl, sizeof pl);
            out.nt++;
        }
    }
    if (out.nt < 4 || (max_vertices >= 4 && out.nv > max_vertices)) goto done; /* refused */
    int near = wall_check(T, n, T->off);
    if (near == 1) near = far_check(T, &out, n, T->off);
    if (near <= 0) {
        if (near == 0) {
            trim_plane *B = &T->pl[T->bj];
            B->lim = T->bk;
            B->best_ok = 0;
            T->refused++;
            ret = 2;
        } else
            ret = -1;
        goto done;
    }
    poly_free(&T->h);
    T->h = out;
    /* the polytope's triangles pile up where cuts cross earlier sections (a section is fanned over
     * all its crossings, collinear ones too, and the next section crosses every fan edge: on fandisk,
     * with the cuts deepened along their planes, 14x the triangles visited by plane_measure): past
     * twice its size at the last hull, its hull again (qhull: the same solid, the same vertices up to
     * those inside its faces) */
    if (T->h.nt > T->nt_limit) {
        acd_hull nh;
        acd_error e;
        if (acd_hull_compute(T->h.v, T->h.nv, &nh, &e) == ACD_OK) {
            if (nh.dim == 3) hull_take(T, &nh);
            acd_hull_free(&nh);
        } /* (else, out of memory too, the polytope is kept: its triangles hold the same solid) */
        T->nt_limit = 2 * T->h.nt + 64;
    }
    free(T->vdot); /* (NULL on failure: plane_measure then does without) */
    T->vdot = malloc(T->h.nv * sizeof *T->vdot);
    memset(&out, 0, sizeof out);
    T->cut = 1;
    ret = 1;
done:
    poly_free(&out);
    free(s), free(map), free(ekey), free(eval), free(sec);
    return ret;
}

typedef struct part_order {
    double cost;
    size_t i;
} part_order;

static int part_order_cmp(const void *a, const void *b) {
    const part_order *x = a, *y = b;
    return x->cost > y->cost ? -1 : x->cost < y->cost ? 1 : (x->i > y->i) - (x->i < y->i);
}

acd_status acd3_trim_hulls(acd3d_part *parts, size_t nparts, double input_volume, double budget, double min_gain,
                           size_t max_vertices, const acd_mesh *input, const acd3_trim_trees *trees, int threads,
                           acd_progress_fn progress, void *progress_user, acd3_trim_stats *stats, acd_error *err) {
    /* the run's own measure of how far a part's surface may lie from its hull: the joined parts of a
     * merged run are within the merge tolerance, a split part within tau */
    double maxdist = 0;
    for (size_t i = 0; i < nparts; i++)
        if (parts[i].volume > 0 && parts[i].concavity > maxdist) maxdist = parts[i].concavity;
    return acd3_trim_hulls_within(parts, nparts, input_volume, budget, min_gain, max_vertices, maxdist, input, trees,
                                  threads, progress, progress_user, stats, err);
}

acd_status acd3_trim_hulls_within(acd3d_part *parts, size_t nparts, double input_volume, double budget,
                                  double min_gain, size_t max_vertices, double max_distance, const acd_mesh *input,
                                  const acd3_trim_trees *trees, int threads, acd_progress_fn progress,
                                  void *progress_user, acd3_trim_stats *stats, acd_error *err) {
    memset(stats, 0, sizeof *stats);
    for (size_t i = 0; i < nparts; i++) parts[i].trimmed_volume = 0;
    if (!(budget > 0) || nparts == 0 || !(input_volume > 0)) return ACD_OK;
    trim_hull *T = calloc(nparts, sizeof *T);
    acd_status *pst = calloc(nparts, sizeof *pst);
    if (!T || !pst) {
        free(T);
        free(pst);
        return acd_fail(err, ACD_ERR_NOMEM, "trim: out of memory");
    }
    double hull_sum = 0;
    for (size_t i = 0; i < nparts; i++) hull_sum += parts[i].hull_volume;
    /* a cut raises IoU = |M n U| / |M u U| when the hull volume it removes over the part volume it
     * removes exceeds 1 + |M u U| / |M n U|; the hulls' sum over the input's volume bounds that */
    const double ratio_floor = 1.0 + hull_sum / input_volume;
    const double loss_floor = ACD3_TRIM_LOSS_FLOOR * min_gain;
    /* the distance bound (far_check, wall_check): a thin feature (a fin, embossed letters) is not cut
     * off whole for its small volume, nor a slab along a cut face (docs/acd3d.md "Trimmed hulls") */
    const double maxdist = max_distance >= 0 ? max_distance : 0; /* (NaN: 0) */
    stats->max_distance = maxdist;
    for (size_t i = 0; i < nparts; i++) T[i].maxdist = maxdist;
    int input_crossings = 0;
    acd_status input_st = ACD_OK;
    /* the input's tree (its self-crossing test, then the walls': is_wall): the caller's, else built
     * once in task -1 for both */
    acd_bvh own_input;
    memset(&own_input, 0, sizeof own_input);
    const acd_bvh *input_bvh = NULL;
    /* the parts' planes, and (task -1) the input's self-intersections; the parts largest first (a
     * part's planes cost about its hull's size times its own: the largest last would run alone) */
    part_order *order = malloc(nparts * sizeof *order);
    if (order) {
        for (size_t i = 0; i < nparts; i++) {
            order[i].cost = (double)parts[i].hull.nvertices * (double)parts[i].mesh.ntriangles;
            order[i].i = i;
        }
        qsort(order, nparts, sizeof *order, part_order_cmp);
    }
    /* the set-up polled before and after the tasks, before each task, between a part's steps (hull,
     * tree, planes) and within its planes (init_planes), by the calling thread (the others skip
     * their tasks once it says stop): 3.3 CPU-s without a call at 832k faces before the first
     * "trim" call. A stop leaves T as far as it got (freed below). */
    acd3_poll poll_obj, *poll = NULL;
    if (progress) {
        poll_obj = acd3_poll_make(progress, progress_user, "trim: preparing");
        poll = &poll_obj;
    }
    acd3_poll_stop(poll); /* (once stopped, the tasks below are skipped) */
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1)
#endif
    for (long c = -1; c < (long)nparts; c++) {
        acd_error e;
        const long j = c < 0 || !order ? c : (long)order[c].i;
        if (acd3_poll_stop(poll)) continue;
        if (j < 0) {
            if (!input) continue;
            input_bvh = trees ? trees->input : NULL;
            if (!acd_bvh_is_over(input_bvh, input->vertices, input->nvertices, input->triangles, input->ntriangles)) {
                input_st = acd_bvh_build(&own_input, input->vertices, input->nvertices, input->triangles,
                                         input->ntriangles, &e);
                input_bvh = input_st == ACD_OK ? &own_input : NULL;
                if (input_st == ACD_OK && acd3_poll_stop(poll)) continue;
            }
            if (input_st == ACD_OK)
                input_st = acd_mesh_self_intersects_bvh(input, input_bvh, &input_crossings, &e);
            continue;
        }
        trim_hull *H = &T[j];
        const acd3d_part *p = &parts[j];
        if (!(p->volume > 0) || p->hull.nvertices < 4) continue;
        acd_hull h0;
        pst[j] = acd_hull_compute(p->hull.vertices, p->hull.nvertices, &h0, &e);
        if (pst[j] != ACD_OK) continue;
        if (acd3_poll_stop(poll)) {
            acd_hull_free(&h0);
            continue;
        }
        if (h0.dim != 3) {
            acd_hull_free(&h0);
            continue;
        }
        H->unit = cbrt(h0.volume);
        H->loss_floor = loss_floor;
        hull_take(H, &h0); /* (H->h empty: T is calloc'd) */
        /* the part's tree: the caller's, else built (kept for the self-crossing test) */
        const acd_bvh *given = trees && trees->parts ? trees->parts[j] : NULL;
        if (acd_bvh_is_over(given, p->mesh.vertices, p->mesh.nvertices, p->mesh.triangles, p->mesh.ntriangles)) {
            H->bvh = given;
        } else {
            pst[j] = acd_bvh_build(&H->own_bvh, p->mesh.vertices, p->mesh.nvertices, p->mesh.triangles,
                                   p->mesh.ntriangles, &e);
            if (pst[j] != ACD_OK) {
                acd_hull_free(&h0);
                continue;
            }
            H->bvh = &H->own_bvh;
            if (acd3_poll_stop(poll)) {
                acd_hull_free(&h0);
                continue;
            }
        }
        if (!acd3_trim_tree_build(&H->tree, H->bvh)) {
            pst[j] = ACD_ERR_NOMEM;
            acd_hull_free(&h0);
            continue;
        }
        if (acd3_poll_stop(poll)) {
            acd_hull_free(&h0);
            continue;
        }
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (size_t v = 0; v < H->h.nv; v++)
            for (int k = 0; k < 3; k++) {
                double x = H->h.v[3 * v + k];
                lo[k] = fmin(lo[k], x);
                hi[k] = fmax(hi[k], x);
            }
        for (int k = 0; k < 3; k++) H->centre[k] = lo[k] + 0.5 * (hi[k] - lo[k]);
        H->active = 1;
        H->stale = 1;
        H->nt_limit = 2 * H->h.nt + 64;
        if (!init_planes(H, min_gain, h0.neighbors, poll)) pst[j] = ACD_ERR_NOMEM;
        acd_hull_free(&h0);
    }
    free(order);
    /* an input that crosses itself: its parts that cross themselves are left whole */
    if (!acd3_poll_stop(poll) && input_st == ACD_OK && input_crossings) {
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nparts > 1)
#endif
        for (long j = 0; j < (long)nparts; j++) {
            if (!T[j].active || acd3_poll_stop(poll)) continue;
            int crossings = 0;
            acd_error e;
            pst[j] = acd_mesh_self_intersects_bvh(&parts[j].mesh, T[j].bvh, &crossings, &e);
            if (pst[j] != ACD_OK || crossings) T[j].active = 0;
            T[j].crossing = pst[j] == ACD_OK && crossings;
        }
    }
    for (size_t j = 0; j < nparts; j++) {
        T[j].part = &parts[j].mesh;
        T[j].input_bvh = input_st == ACD_OK ? input_bvh : NULL;
    }
    acd_status st = acd3_poll_stopped(poll) ? acd_fail(err, ACD_ERR_CANCELLED, "cancelled (trim: preparing)")
                    : input_st == ACD_OK ? ACD_OK
                                         : acd_fail(err, input_st, "trim: out of memory");
    for (size_t i = 0; i < nparts && st == ACD_OK; i++) {
        if (pst[i] == ACD_ERR_NOMEM) st = acd_fail(err, ACD_ERR_NOMEM, "trim: out of memory");
        stats->skipped += T[i].crossing;
    }
    double spent = 0;
    size_t batch[ACD3_TRIM_BATCH], *pick = st == ACD_OK ? malloc(nparts * sizeof *pick) : NULL;
    if (st == ACD_OK && !pick) st = acd_fail(err, ACD_ERR_NOMEM, "trim: out of memory");
    while (st == ACD_OK) {
        if (progress && progress(progress_user, fmin(1.0, spent / budget), "trim")) {
            st = acd_fail(err, ACD_ERR_CANCELLED, "cancelled while trimming the hulls after %zu cuts", stats->cuts);
            break;
        }
        const double room = budget - spent;
        /* a hull's best cut stands while the hull is not cut and the cut fits the room (the room only
         * shrinks: the best of fewer candidates, the same when it is still among them) */
        size_t nch = 0;
        for (size_t j = 0; j < nparts; j++)
            if (T[j].stale || (T[j].have && !(T[j].loss <= room))) pick[nch++] = j;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nch > 1)
#endif
        for (long c = 0; c < (long)nch; c++) { /* each touches its own hull */
            choose(&T[pick[c]], room, min_gain, ratio_floor);
            T[pick[c]].stale = 0;
        }
        /* the round: up to ACD3_TRIM_BATCH hulls of best ratio (ties: lower index), in that order,
         * while their cuts fit the budget */
        int nb = 0;
        for (size_t i = 0; i < nparts; i++) {
            if (!T[i].have) continue;
            int at = nb < ACD3_TRIM_BATCH ? nb++ : ACD3_TRIM_BATCH;
            while (at > 0 && T[batch[at - 1]].ratio < T[i].ratio) {
                if (at < ACD3_TRIM_BATCH) batch[at] = batch[at - 1];
                at--;
            }
            if (at < ACD3_TRIM_BATCH) batch[at] = i;
        }
        if (nb == 0) break;
        int take = 0;
        double planned = 0;
        for (int b = 0; b < nb; b++) {
            trim_hull *H = &T[batch[b]];
            if (planned + H->loss > room) break; /* the next round chooses within the room left */
            planned += H->loss;
            take = b + 1;
        }
        if (take == 0) break; /* (cannot happen: the best cut of the first hull fits the room) */
        int res[ACD3_TRIM_BATCH];
        /* the round's hulls in parallel (each task touches its own hull). Measured 2026-11-26: the
         * armadillo's trimmed run 1.92 -> 1.85 s wall on 2 idle cores. With libgomp's spinning wait
         * (OMP_WAIT_POLICY unset) and both cores busy with other processes, the region's waits cost
         * more than they saved (camel's trimmed run 2.4 -> 2.6-2.8 s; a first try on a busier machine:
         * 0.28 s on one thread, 1.8 s on two); with the passive wait the CLI sets (cli/main.c) the
         * same as sequential rounds there (fandisk 1.10 s both) */
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && take > 1)
#endif
        for (int b = 0; b < take; b++) {
            res[b] = cut_hull(&T[batch[b]], max_vertices);
            if (res[b] == 1 && (!charge_cut(&T[batch[b]]) || !after_cut(&T[batch[b]], min_gain))) res[b] = -1;
            T[batch[b]].stale = 1;
        }
        for (int b = 0; b < take; b++) {
            trim_hull *H = &T[batch[b]];
            size_t i = batch[b];
            if (res[b] < 0) {
                st = acd_fail(err, ACD_ERR_NOMEM, "trim: out of memory");
                break;
            }
            if (res[b] == 0) { /* refused: this hull is left as it is */
                H->active = 0;
                continue;
            }
            if (res[b] == 2) continue; /* too far (far_check): its next best cut chosen next round */
            spent += H->charge;
            parts[i].trimmed_volume += H->charge;
            stats->cuts++;
            stats->removed_hull += H->gain;
            stats->removed_part += H->charge;
            if (H->depth > stats->max_depth) stats->max_depth = H->depth;
        }
    }
    free(pick);
    /* the trimmed hulls out: the hull of each cut polytope's vertices (facets merged as qhull does) */
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nparts > 1 && st == ACD_OK)
#endif
    for (long j = 0; j < (long)nparts; j++) {
        trim_hull *H = &T[j];
        pst[j] = ACD_OK;
        if (st != ACD_OK || !H->cut) continue;
        acd_hull nh;
        acd_error e;
        pst[j] = acd_hull_compute(H->h.v, H->h.nv, &nh, &e);
        if (pst[j] != ACD_OK) continue;
        acd_mesh *m = &parts[j].hull;
        acd_mesh_free(m);
        m->vertices = nh.vertices, m->nvertices = nh.nvertices;
        m->triangles = nh.triangles, m->ntriangles = nh.ntriangles;
        parts[j].hull_volume = nh.volume;
        nh.vertices = NULL, nh.triangles = NULL;
        acd_hull_free(&nh);
    }
    for (size_t i = 0; i < nparts && st == ACD_OK; i++)
        if (pst[i] != ACD_OK) st = acd_fail(err, pst[i], "trim: a trimmed hull could not be computed");
    for (size_t i = 0; i < nparts; i++) {
        stats->refused_far += T[i].refused;
        poly_free(&T[i].h);
        free(T[i].vdot);
        acd3_trim_tree_free(&T[i].tree);
        acd_bvh_free(&T[i].own_bvh);
        free(T[i].pl);
        free(T[i].corner);
        free(T[i].cutpl), free(T[i].capc), free(T[i].capoff), free(T[i].rel);
        free(T[i].outside), free(T[i].closest), free(T[i].pend), free(T[i].pendq), free(T[i].tkind);
    }
    acd_bvh_free(&own_input);
    free(T);
    free(pst);
    return st;
}
