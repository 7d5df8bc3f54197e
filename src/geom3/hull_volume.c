/* geom3/hull_volume: the volume of a point set's convex hull, fast; see hull_volume.h. */
#include "geom3/hull_volume.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "acd/hull.h"

/* qhull's volume (acd_hull_volume: acd_hull_compute's volume, the same bits unless that hull was
 * rebuilt, include/acd/hull.h; without the hull). */
static double hull_volume_pts(const double *pts, size_t n) {
    double v;
    return acd_hull_volume(pts, n, &v, NULL) == ACD_OK ? v : -1;
}

/* A point within this fraction of the coordinates' scale of a facet's plane counts as inside it; a
 * set this thin (relative to the same scale) has no volume. */
#define HULL_VOLUME_EPS 1e-10
#define HULL_VOLUME_FLAT 1e-8
/* Coordinates (their largest magnitude) above this, or an extent below its inverse, go to qhull
 * (acd_hull_compute normalises them): the planes' cross products square the coordinates' squares,
 * which overflow past about 1e77 (fuzz_hull_volume: points at 2e84 gave volume 0 for 1.09e248). */
#define HULL_VOLUME_RANGE 1e60
/* A set farther from the origin than this many times its extent is moved to its box's centre
 * first: the tolerances are relative to the coordinates' magnitude (their roundoff), so far from
 * the origin a thin set came out flat (fuzz_hull_volume: points at 1.04e-42 spread over 4e-49, volume
 * 0 for 2.7e-150; a scan in UTM coordinates, 5e6 m off, would lose parts thinner than 5% of a metre).
 * Nearer sets keep their bits. */
#define HULL_VOLUME_OFFSET 1e4
/* A sweep (acd_hull_volume_sweep) stops at a new facet whose angle at its apex is below this sine, and
 * at one that folds over its horizon facet by more than this many times the tolerance (hv_expand). */
#define HULL_VOLUME_SLIVER 1e-6
#define HULL_VOLUME_FOLD 1e3
/* Distance from a horizon edge's line (in tolerances) below which a new facet (a sweep's or the
 * per-set hull's) is checked for a fold: twice D / HULL_VOLUME_FOLD (a margin for the rounding), D
 * (the extent's diagonal) at most 1.8e10 tolerances. */
#define HULL_VOLUME_NARROW 4e7
/* A sweep starts its hull only from a prefix whose scale (its largest coordinate or extent) is at
 * least this fraction of the extent of all the points the sweep may add: the tolerance is the
 * prefix's (HULL_VOLUME_EPS of its scale), and the facets later points make carry the rounding of
 * their own scale. fuzz_hull_volume: six points within 6e-25 of the origin, then four at 0.9; the
 * tolerance of the first six (6e-35) made the hull lose a corner and half its volume (4.0e-6 for
 * qhull's 8.0e-6). A prefix this small is skipped (its queries left to acd_hull_volume_fast, which
 * scales by the whole set) and the hull starts at the next query. */
#define HULL_VOLUME_PREFIX_REL 1e-3
/* ... and only from a prefix whose hull is at least this many tolerances thick (its volume at least
 * HULL_VOLUME_THICK_START x eps x the square of its extent): points added to a slab of a few hundred
 * tolerances meet facets tilted by their rounding. fuzz_hull_volume (CI, 2026-11-26): ten points near
 * 1e-42, the first five within 8e-8 of their scale of a plane (800 tolerances); the hulls of the next
 * prefixes came out 4e-6 and 8e-5 below qhull's, a query over them 2.3 times the harness's slack. A
 * thinner prefix is skipped as a small one is. */
#define HULL_VOLUME_THICK_START 1e4

/* The facets of acd_hull_volume_fast's hull (the workspace's array): what the searches read, 64
 * bytes (one cache line; the array is aligned to it). */
struct acd_hv_facet {
    double n[3], d;  /* unit outward normal, n.x = d on the plane */
    int v[3], nb[3]; /* nb[k]: across edge (v[k], v[k+1]) */
    int vis, mark;   /* the visible search's stamps (acd_hull_volume_ws.iter): visible, tested and not */
};
typedef struct acd_hv_facet hv_facet;
/* A facet's outside set (a list through acd_hull_volume_ws.next), its farthest point and how far
 * (the workspace's array beside the facets'). */
struct acd_hv_out {
    double fard;
    int head, far;
};
typedef struct acd_hv_out hv_out;
#define HV_FACET_ALIGN 64
_Static_assert(sizeof(hv_facet) == HV_FACET_ALIGN, "a facet fills one cache line");

void acd_hull_volume_ws_free(acd_hull_volume_ws *w) {
    free(w->f), free(w->o), free(w->alive), free(w->next), free(w->start), free(w->end), free(w->stack);
    free(w->pend), free(w->hor), free(w->horf), free(w->horu), free(w->newf), free(w->visl), free(w->pl), free(w->near);
    memset(w, 0, sizeof *w);
}

static int hv_reserve_points(acd_hull_volume_ws *w, size_t n) {
    if (n <= w->pcap) return 1;
    size_t c = 2 * n;
    int *a = realloc(w->next, c * sizeof *a), *b = a ? realloc(w->start, c * sizeof *b) : NULL;
    if (a) w->next = a;
    if (b) w->start = b;
    int *e = b ? realloc(w->end, c * sizeof *e) : NULL;
    if (e) w->end = e;
    if (!a || !b || !e) return 0;
    w->pcap = c;
    return 1;
}

/* *a holds at least need ints (grown to twice that); 0 when out of memory. */
static int hv_grow_int(int **a, size_t *cap, size_t need) {
    if (need <= *cap) return 1;
    int *b = realloc(*a, 2 * need * sizeof *b);
    if (!b) return 0;
    *a = b, *cap = 2 * need;
    return 1;
}

/* Room for need horizon edges: their vertex pairs, facets (all and each once), new facets and the
 * planes of the new and horizon facets. */
static int hv_grow_horizon(acd_hull_volume_ws *w, size_t need) {
    size_t c = 2 * need;
    int *a = realloc(w->hor, 2 * c * sizeof *a);
    if (a) w->hor = a;
    int *b = a ? realloc(w->horf, c * sizeof *b) : NULL;
    if (b) w->horf = b;
    int *u = b ? realloc(w->horu, c * sizeof *u) : NULL;
    if (u) w->horu = u;
    int *nf = u ? realloc(w->newf, c * sizeof *nf) : NULL;
    if (nf) w->newf = nf;
    double *pl = nf ? realloc(w->pl, (2 * 4 * c + 8) * sizeof *pl) : NULL;
    if (pl) w->pl = pl;
    if (!pl) return 0;
    w->hcap = c;
    return 1;
}

/* Room for k more facets (hv_reserve_facets' slow path); 0 when out of memory. */
static int hv_grow_facets(acd_hull_volume_ws *w, size_t k) {
    size_t nc = w->fcap ? 2 * w->fcap : 256;
    while (nc < w->nf + k) nc *= 2;
    hv_facet *f = aligned_alloc(HV_FACET_ALIGN, nc * sizeof *f);
    if (!f) return 0;
    if (w->nf) memcpy(f, w->f, w->nf * sizeof *f);
    free(w->f);
    w->f = f;
    hv_out *o = realloc(w->o, nc * sizeof *o);
    if (!o) return 0;
    w->o = o;
    int *st = realloc(w->stack, nc * sizeof *st);
    if (!st) return 0;
    w->stack = st;
    unsigned char *al = realloc(w->alive, nc);
    if (!al) return 0;
    w->alive = al, w->fcap = nc;
    return 1;
}

/* Room for k more facets; 0 when out of memory. */
static inline int hv_reserve_facets(acd_hull_volume_ws *w, size_t k) {
    return w->nf + k <= w->fcap || hv_grow_facets(w, k);
}

/* F's plane: its cross product n (not 0 unless degenerate, its squared length l2 as computed here)
 * made unit, through the point A. */
static inline void hv_set_plane(hv_facet *F, const double n[3], double l2, const double *A) {
    double l = sqrt(l2), u[3] = {n[0], n[1], n[2]};
    if (l > 0) u[0] /= l, u[1] /= l, u[2] /= l;
    memcpy(F->n, u, sizeof u);
    F->d = u[0] * A[0] + u[1] * A[1] + u[2] * A[2];
}

/* Facet (a, b, c) of the points p (its neighbours left to the caller). Its index, -1 when out of
 * memory. */
static int hv_new_facet(acd_hull_volume_ws *w, const double *p, int a, int b, int c) {
    if (!hv_reserve_facets(w, 1)) return -1;
    hv_facet *F = &w->f[w->nf];
    F->v[0] = a, F->v[1] = b, F->v[2] = c;
    const double *A = p + 3 * a, *B = p + 3 * b, *C = p + 3 * c;
    double e1[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]}, e2[3] = {C[0] - A[0], C[1] - A[1], C[2] - A[2]};
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    hv_set_plane(F, n, n[0] * n[0] + n[1] * n[1] + n[2] * n[2], A);
    F->mark = 0, F->vis = 0;
    hv_out *O = &w->o[w->nf];
    O->head = -1, O->far = -1, O->fard = 0;
    w->alive[w->nf] = 1;
    return (int)w->nf++;
}

static inline double hv_dist(const hv_facet *F, const double *q) {
    return F->n[0] * q[0] + F->n[1] * q[1] + F->n[2] * q[2] - F->d;
}

/* Point i into the outside set of the first of the nc facets cand it is above by more than eps: 1;
 * 0 when none (*mx: the most it is above one of them, *fm: that one). */
static int hv_assign(acd_hull_volume_ws *w, const double *p, int i, const int *cand, int nc, double eps, double *mx,
                     int *fm) {
    double m = -INFINITY;
    int b = -1;
    for (int k = 0; k < nc; k++) {
        double dd = hv_dist(&w->f[cand[k]], p + 3 * i);
        if (dd > eps) {
            hv_out *O = &w->o[cand[k]];
            w->next[i] = O->head;
            O->head = i;
            if (dd > O->fard) O->fard = dd, O->far = i;
            return 1;
        }
        if (dd > m) m = dd, b = cand[k];
    }
    *mx = m, *fm = b;
    return 0;
}

/* A sweep's point near the hull is kept (hv_near_retest) unless a walk of at most this many facets
 * from the facet it is farthest above finds one whose triangle its projection lies in, within the
 * tolerance of its plane: then the point is within the tolerance of the hull, and of every hull after. */
#define HULL_VOLUME_NEAR_WALK 16

/* A sweep's point i taken as inside though above facet f (by at most eps): onto w->near unless it is
 * within eps of the hull (HULL_VOLUME_NEAR_WALK; beyond an edge whose facets meet at a small angle the
 * walk crosses that edge back and forth). 0 when out of memory. */
static int hv_near_add(acd_hull_volume_ws *w, const double *p, int i, int f, double eps) {
    const double *x = p + 3 * (size_t)i;
    for (int step = 0; step < HULL_VOLUME_NEAR_WALK; step++) {
        const hv_facet *F = &w->f[f];
        int out = -1;
        for (int k = 0; k < 3 && out < 0; k++) {
            const double *A = p + 3 * F->v[k], *B = p + 3 * F->v[(k + 1) % 3];
            double e[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]}, r[3] = {x[0] - A[0], x[1] - A[1], x[2] - A[2]};
            double c[3] = {e[1] * r[2] - e[2] * r[1], e[2] * r[0] - e[0] * r[2], e[0] * r[1] - e[1] * r[0]};
            if (F->n[0] * c[0] + F->n[1] * c[1] + F->n[2] * c[2] < 0) out = k;
        }
        if (out < 0) {
            if (fabs(hv_dist(F, x)) <= eps) return 1;
            break;
        }
        f = F->nb[out];
    }
    if (!hv_grow_int(&w->near, &w->nearcap, w->nnear + 1)) return 0;
    w->near[w->nnear++] = i;
    return 1;
}

/* The facets visible from point q (index pi) connected to facet fi or (if not -1) fj, into
 * w->visl (*nv of them), and the horizon (the edges of visible facets whose neighbour is not visible,
 * in the order of w->visl and their edges: a facet tested is visible or not for good when its
 * neighbour is taken) into w->hor / w->horf, each edge's index in w->start (by its first vertex) and
 * w->end (by its second; hv_cone resets both); *bad: 1 when a vertex starts or ends two edges (the
 * horizon is not one simple cycle). *added (if not NULL): less the tetrahedra of q and each visible
 * facet (in the order of w->visl), over 6: the volume the cone from q adds. The horizon's size, -1
 * when out of memory. */
static long hv_visible(acd_hull_volume_ws *w, const double *p, const double *q, int fi, int fj, double eps, size_t *nv_out,
                       int *bad_out, double *added) {
    int iter = ++w->iter, both = -1; /* the and of every start[a] and end[b] met: negative while all are -1 */
    size_t nv = 0, ns = 0, nh = 0;
    int *visl = w->visl, *stack = w->stack, *start = w->start, *end = w->end;
    hv_facet *f = w->f;
    double s = 0;
#ifdef __SSE2__
    const __m128d q01 = _mm_loadu_pd(q), q12 = _mm_loadu_pd(q + 1);
#endif
    f[fi].vis = iter;
    stack[ns++] = fi;
    if (fj >= 0 && fj != fi) f[fj].vis = iter, stack[ns++] = fj;
    while (ns > 0) {
        int g = stack[--ns];
        visl[nv++] = g;
        const hv_facet *G = &f[g];
        if (added) {
            const double *A = p + 3 * G->v[0], *B = p + 3 * G->v[1], *C = p + 3 * G->v[2];
#ifdef __SSE2__
            /* the same operations two at a time: (b1 c2 - b2 c1, b2 c0 - b0 c2), b0 c1 - b1 c0, then
             * (a0 X + a1 Y) + a2 Z */
            __m128d b01 = _mm_sub_pd(_mm_loadu_pd(B), q01), b12 = _mm_sub_pd(_mm_loadu_pd(B + 1), q12);
            __m128d c01 = _mm_sub_pd(_mm_loadu_pd(C), q01), c12 = _mm_sub_pd(_mm_loadu_pd(C + 1), q12);
            __m128d xy = _mm_sub_pd(_mm_mul_pd(b12, _mm_shuffle_pd(c12, c01, 1)), _mm_mul_pd(_mm_shuffle_pd(b12, b01, 1), c12));
            __m128d zz = _mm_mul_pd(b01, _mm_shuffle_pd(c01, c01, 1)); /* (b0 c1, b1 c0) */
            __m128d m = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(A), q01), xy);
            double z = _mm_cvtsd_f64(zz) - _mm_cvtsd_f64(_mm_unpackhi_pd(zz, zz));
            s -= (_mm_cvtsd_f64(m) + _mm_cvtsd_f64(_mm_unpackhi_pd(m, m))) + (A[2] - q[2]) * z;
#else
            double a[3] = {A[0] - q[0], A[1] - q[1], A[2] - q[2]}, b[3] = {B[0] - q[0], B[1] - q[1], B[2] - q[2]},
                   c[3] = {C[0] - q[0], C[1] - q[1], C[2] - q[2]};
            s -= a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
#endif
        }
        for (int k = 0; k < 3; k++) {
            int h = G->nb[k];
            hv_facet *H = &f[h];
            if (H->vis == iter) continue;
            if (H->mark != iter) {
                if (hv_dist(H, q) > eps) {
                    H->vis = iter;
                    stack[ns++] = h;
                    continue;
                }
                H->mark = iter; /* checked, not visible */
            }
            if (nh + 1 > w->hcap && !hv_grow_horizon(w, nh + 1)) {
                for (size_t j = 0; j < nh; j++) start[w->hor[2 * j]] = end[w->hor[2 * j + 1]] = -1;
                return -1;
            }
            int a = G->v[k], b = G->v[k == 2 ? 0 : k + 1];
            both &= start[a] & end[b];
            start[a] = end[b] = (int)nh;
            w->hor[2 * nh] = a, w->hor[2 * nh + 1] = b, w->horf[nh] = h;
            nh++;
        }
    }
    if (added) *added += s / 6;
    *nv_out = nv, *bad_out = both >= 0;
    return (long)nh;
}

/* Plane j of the planes packed in pairs for hv_first_above (n[0] of both, n[1], n[2], d). */
static inline void hv_pack(double *pl, size_t j, const double n[3], double d) {
    double *b = pl + 8 * (j >> 1) + (j & 1);
    b[0] = n[0], b[2] = n[1], b[4] = n[2], b[6] = d;
}

/* The cone of new facets from point pi over the nh horizon edges in w->hor / w->horf (hv_visible,
 * which found them a simple cycle unless bad; w->start / w->end reset here); undo (if not NULL)
 * records each horizon facet's neighbour changed (facet, edge, old value). The horizon edges pi is
 * within HULL_VOLUME_NARROW x eps of the line of into w->horu (w->nnarrow of them: hv_expand's fold
 * check, in a sweep and in the per-set hull alike). *inward: 1 when the initial simplex's centroid is above a new facet.
 * Returns nh (the new facets are the last nh, in w->newf too), -1 when out of memory, -2 when the
 * horizon is not one simple cycle or (in a sweep) a new facet is a sliver (nothing changed then).
 * The planes first (hv_new_facet's arithmetic, two facets at a time where SSE2 is there: the same
 * bits), into the facets' room before they are made, and packed into w->pl (hv_pack, an odd nh
 * padded by a plane no point is above) for hv_expand. */
static long hv_cone(acd_hull_volume_ws *w, const double *p, int pi, size_t nh, int bad, double eps, int **undo,
                    size_t *nundo, size_t *undocap, int *inward) {
    int *hor = w->hor, *horf = w->horf, *newf = w->newf, *start = w->start, *end = w->end;
    if (bad || nh < 3) goto refused;
    if (undo && *nundo + 3 * nh > *undocap) {
        size_t c = 2 * (*nundo + 3 * nh);
        int *u = realloc(*undo, c * sizeof *u);
        if (u) *undo = u, *undocap = c;
    }
    if ((undo && *nundo + 3 * nh > *undocap) || !hv_reserve_facets(w, nh)) {
        for (size_t k = 0; k < nh; k++) start[hor[2 * k]] = end[hor[2 * k + 1]] = -1;
        return -1;
    }
    /* a sweep refuses a sliver (pi nearly on the line of a horizon edge: its plane would be noise) */
    int sweep = w->sweep, in = 0, *horu = w->horu;
    double narrow = HULL_VOLUME_NARROW * eps * (HULL_VOLUME_NARROW * eps);
    const double *C = p + 3 * pi, *cen = w->cen;
    hv_facet *F0 = w->f + w->nf;
    size_t nn = 0, k = 0;
#ifdef __SSE2__
    {
        const __m128d cx = _mm_set1_pd(C[0]), cy = _mm_set1_pd(C[1]), cz = _mm_set1_pd(C[2]), z = _mm_setzero_pd();
        const __m128d ox = _mm_set1_pd(cen[0]), oy = _mm_set1_pd(cen[1]), oz = _mm_set1_pd(cen[2]);
        const __m128d ss = _mm_set1_pd(HULL_VOLUME_SLIVER * HULL_VOLUME_SLIVER), nw = _mm_set1_pd(narrow);
        for (; k + 1 < nh; k += 2) {
            const double *A0 = p + 3 * hor[2 * k], *B0 = p + 3 * hor[2 * k + 1], *A1 = p + 3 * hor[2 * k + 2],
                         *B1 = p + 3 * hor[2 * k + 3];
            __m128d ax = _mm_loadh_pd(_mm_load_sd(A0), A1), ay = _mm_loadh_pd(_mm_load_sd(A0 + 1), A1 + 1),
                    az = _mm_loadh_pd(_mm_load_sd(A0 + 2), A1 + 2);
            __m128d bx = _mm_loadh_pd(_mm_load_sd(B0), B1), by = _mm_loadh_pd(_mm_load_sd(B0 + 1), B1 + 1),
                    bz = _mm_loadh_pd(_mm_load_sd(B0 + 2), B1 + 2);
            __m128d e1x = _mm_sub_pd(bx, ax), e1y = _mm_sub_pd(by, ay), e1z = _mm_sub_pd(bz, az);
            __m128d e2x = _mm_sub_pd(cx, ax), e2y = _mm_sub_pd(cy, ay), e2z = _mm_sub_pd(cz, az);
            __m128d nx = _mm_sub_pd(_mm_mul_pd(e1y, e2z), _mm_mul_pd(e1z, e2y));
            __m128d ny = _mm_sub_pd(_mm_mul_pd(e1z, e2x), _mm_mul_pd(e1x, e2z));
            __m128d nz = _mm_sub_pd(_mm_mul_pd(e1x, e2y), _mm_mul_pd(e1y, e2x));
            __m128d l2 = _mm_add_pd(_mm_add_pd(_mm_mul_pd(nx, nx), _mm_mul_pd(ny, ny)), _mm_mul_pd(nz, nz));
            {
                __m128d a2 = _mm_add_pd(_mm_add_pd(_mm_mul_pd(e1x, e1x), _mm_mul_pd(e1y, e1y)), _mm_mul_pd(e1z, e1z));
                if (sweep) {
                    __m128d b2 = _mm_add_pd(_mm_add_pd(_mm_mul_pd(e2x, e2x), _mm_mul_pd(e2y, e2y)), _mm_mul_pd(e2z, e2z));
                    if (_mm_movemask_pd(_mm_cmpgt_pd(l2, _mm_mul_pd(_mm_mul_pd(ss, a2), b2))) != 3) bad = 1;
                }
                int na = _mm_movemask_pd(_mm_cmplt_pd(l2, _mm_mul_pd(nw, a2)));
                if (na & 1) horu[nn++] = (int)k;
                if (na & 2) horu[nn++] = (int)k + 1;
            }
            __m128d l = _mm_sqrt_pd(l2), ok = _mm_cmpgt_pd(l, z);
            nx = _mm_or_pd(_mm_and_pd(ok, _mm_div_pd(nx, l)), _mm_andnot_pd(ok, nx));
            ny = _mm_or_pd(_mm_and_pd(ok, _mm_div_pd(ny, l)), _mm_andnot_pd(ok, ny));
            nz = _mm_or_pd(_mm_and_pd(ok, _mm_div_pd(nz, l)), _mm_andnot_pd(ok, nz));
            __m128d d = _mm_add_pd(_mm_add_pd(_mm_mul_pd(nx, ax), _mm_mul_pd(ny, ay)), _mm_mul_pd(nz, az));
            __m128d dc = _mm_sub_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(nx, ox), _mm_mul_pd(ny, oy)), _mm_mul_pd(nz, oz)), d);
            in |= _mm_movemask_pd(_mm_cmpgt_pd(dc, z));
            double *b = w->pl + 4 * k;
            _mm_storeu_pd(b, nx), _mm_storeu_pd(b + 2, ny), _mm_storeu_pd(b + 4, nz), _mm_storeu_pd(b + 6, d);
            _mm_store_pd(F0[k].n, _mm_unpacklo_pd(nx, ny));
            _mm_store_pd(F0[k].n + 2, _mm_unpacklo_pd(nz, d));
            _mm_store_pd(F0[k + 1].n, _mm_unpackhi_pd(nx, ny));
            _mm_store_pd(F0[k + 1].n + 2, _mm_unpackhi_pd(nz, d));
        }
    }
#endif
    for (; k < nh; k++) {
        const double *A = p + 3 * hor[2 * k], *B = p + 3 * hor[2 * k + 1];
        double e1[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]}, e2[3] = {C[0] - A[0], C[1] - A[1], C[2] - A[2]};
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double l2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        double a2 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
        if (sweep) {
            double b2 = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
            if (!(l2 > HULL_VOLUME_SLIVER * HULL_VOLUME_SLIVER * a2 * b2)) bad = 1;
        }
        if (l2 < narrow * a2) horu[nn++] = (int)k; /* distance from the line: sqrt(l2 / a2) */
        hv_set_plane(&F0[k], n, l2, A);
        in |= hv_dist(&F0[k], cen) > 0;
        hv_pack(w->pl, k, F0[k].n, F0[k].d);
    }
    if (nh & 1) {
        const double zero[3] = {0, 0, 0};
        hv_pack(w->pl, nh, zero, INFINITY); /* the pair's second plane: below every point */
    }
    w->nnarrow = nn;
    if (bad) goto refused;
    int nf0 = (int)w->nf;
    for (k = 0; k < nh; k++) {
        int a = hor[2 * k], b = hor[2 * k + 1], h = horf[k], nk = nf0 + (int)k;
        hv_facet *F = &F0[k];
        F->v[0] = a, F->v[1] = b, F->v[2] = pi;
        /* (on a simple cycle start[b] and end[a] are read once each, by this edge: reset here) */
        F->nb[0] = h, F->nb[1] = nf0 + start[b], F->nb[2] = nf0 + end[a];
        start[b] = end[a] = -1;
        F->mark = 0, F->vis = 0;
        hv_out *O = &w->o[nk];
        O->head = -1, O->far = -1, O->fard = 0;
        w->alive[nk] = 1;
        newf[k] = nk;
        hv_facet *H = &w->f[h];
        /* its edge (b, a): the one from b (a facet's vertices are distinct) if it goes to a (without
         * branches to mispredict) */
        int e = (H->v[1] == b) | (H->v[2] == b) << 1;
        if (H->v[e] == b && H->v[e == 2 ? 0 : e + 1] == a) {
            if (undo) {
                int *u = *undo + *nundo;
                u[0] = h, u[1] = e, u[2] = H->nb[e];
                *nundo += 3;
            }
            H->nb[e] = nk;
        }
    }
    w->nf += nh;
    *inward = in != 0;
    return (long)nh;
refused:
    for (k = 0; k < nh; k++) start[hor[2 * k]] = end[hor[2 * k + 1]] = -1;
    return -2;
}

/* The Quickhull loop from the pending facets w->pend[0..top): each step adds the farthest point of
 * a facet's outside set; *added (if not NULL) accumulates the volume each step adds. 0, -1 when out
 * of memory, -2 when a horizon is not one simple cycle. */
/* The sweep's steps find the facets visible from a point by a climb over the facets from a start
 * (to the neighbour the point is farther above, while there is one); a climb ending on a facet the
 * point is at most this many times the tolerance above may have stopped on a nearly coplanar
 * facet away from the rest of the visible region: every facet is then searched. */
#define HULL_VOLUME_CLIMB_SURE 1e4

/* A facet visible from q (farther than eps above its plane), the one q is farthest above of those
 * met: a climb from facet start (if alive) then, when it ends on a facet q is barely above, the
 * farthest of every facet; -1 when q is inside (*dmax, if not NULL: how far q is above the facet
 * returned, or when inside the most it is above a facet, *fmax: that facet). */
static int hv_find_visible(const acd_hull_volume_ws *w, const double *q, int start, double eps, double *dmax, int *fmax) {
    int cur = -1;
    double dc = -INFINITY;
    if (start >= 0 && (size_t)start < w->nf && w->alive[start]) {
        cur = start;
        dc = hv_dist(&w->f[cur], q);
        /* (the facet the climb came from is never the next step: q is above it by less, so it is not
         * skipped, which spares a branch) */
        for (size_t steps = 0; steps < w->nf; steps++) {
            const int *nb = w->f[cur].nb;
            int h0 = nb[0], h1 = nb[1], h2 = nb[2], bn = -1;
            double d0 = hv_dist(&w->f[h0], q), d1 = hv_dist(&w->f[h1], q), d2 = hv_dist(&w->f[h2], q), bd = dc;
            bn = d0 > bd ? h0 : bn, bd = d0 > bd ? d0 : bd;
            bn = d1 > bd ? h1 : bn, bd = d1 > bd ? d1 : bd;
            bn = d2 > bd ? h2 : bn, bd = d2 > bd ? d2 : bd;
            if (bn < 0) break;
            cur = bn, dc = bd;
        }
        if (dc > HULL_VOLUME_CLIMB_SURE * eps) {
            if (dmax) *dmax = dc;
            return cur;
        }
    }
    for (size_t t = 0; t < w->nf; t++) { /* (a removed facet's plane is still there: no branch on alive) */
        double dd = hv_dist(&w->f[t], q);
        int b = w->alive[t] && dd > dc;
        dc = b ? dd : dc, cur = b ? (int)t : cur;
    }
    if (dmax) *dmax = dc, *fmax = cur;
    return dc > eps ? cur : -1;
}

/* The distance of x above plane k packed in pl (hv_pack). */
static inline double hv_packed_dist(const double *pl, size_t k, const double *x) {
    const double *b = pl + 8 * (k >> 1) + (k & 1);
    return b[0] * x[0] + b[2] * x[1] + b[4] * x[2] - b[6];
}

/* The first of the nt planes packed in pl (hv_pack; an odd nt padded by a plane no point is above) that
 * x is above by more than eps, *dd: by how much; nt when none, *pos then set to 1 if x is above one
 * of them (by more than 0). Each distance is n[0] x[0] + n[1] x[1] + n[2] x[2] - d in that order,
 * two planes at a time where SSE2 is there (the same bits). */
static inline size_t hv_first_above(const double *pl, size_t nt, const double *x, double eps, double *dd, int *pos) {
    size_t j = 0;
#ifdef __SSE2__
    __m128d x0 = _mm_set1_pd(x[0]), x1 = _mm_set1_pd(x[1]), x2 = _mm_set1_pd(x[2]), e = _mm_set1_pd(eps);
    __m128d z = _mm_setzero_pd(), any = z;
    for (; j < nt; j += 2) {
        const double *b = pl + 4 * j;
        __m128d t = _mm_add_pd(_mm_mul_pd(_mm_loadu_pd(b), x0), _mm_mul_pd(_mm_loadu_pd(b + 2), x1));
        t = _mm_sub_pd(_mm_add_pd(t, _mm_mul_pd(_mm_loadu_pd(b + 4), x2)), _mm_loadu_pd(b + 6));
        int a = _mm_movemask_pd(_mm_cmpgt_pd(t, e));
        if (a) {
            double two[2];
            _mm_storeu_pd(two, t);
            *dd = two[!(a & 1)];
            return j + !(a & 1);
        }
        any = _mm_or_pd(any, _mm_cmpgt_pd(t, z));
    }
    if (_mm_movemask_pd(any)) *pos = 1;
#else
    for (; j < nt; j++) {
        double t = hv_packed_dist(pl, j, x);
        if (t > eps) {
            *dd = t;
            return j;
        }
        if (t > 0) *pos = 1;
    }
#endif
    return nt;
}

/* What a step changed in the facets before it (to be undone): neighbours (facet, edge, old
 * value), facets removed. */
typedef struct hv_undo {
    int *nb, *killed;
    size_t nnb, nbcap, nk, kcap;
} hv_undo;

static int hv_expand(acd_hull_volume_ws *w, const double *p, double eps, size_t top, double *added, hv_undo *u) {
    while (top > 0) {
        int fi = w->pend[--top];
        if (!w->alive[fi] || w->o[fi].head < 0) continue;
        int pi = w->o[fi].far;
        const double *q = p + 3 * pi;
        if (!hv_grow_int(&w->visl, &w->vcap, w->nf)) return -1;
        /* a sweep's step with q barely above fi also searches from the facet q is farthest above
         * (hv_find_visible): fi may be joined to the rest of the visible region only through facets
         * within eps (two cones from q then, the facets between within eps of q) */
        int fj = added && !(w->o[fi].fard > HULL_VOLUME_CLIMB_SURE * eps) ? hv_find_visible(w, q, fi, eps, NULL, NULL) : -1;
        size_t nv;
        int bad, inward = 0;
        long r = hv_visible(w, p, q, fi, fj, eps, &nv, &bad, added);
        if (r < 0) return -1;
        r = u ? hv_cone(w, p, pi, (size_t)r, bad, eps, &u->nb, &u->nnb, &u->nbcap, &inward)
              : hv_cone(w, p, pi, (size_t)r, bad, eps, NULL, NULL, NULL, &inward);
        if (r < 0) return (int)r;
        if (u && u->nk + nv > u->kcap) {
            size_t c = 2 * (u->nk + nv);
            int *k2 = realloc(u->killed, c * sizeof *k2);
            if (!k2) return -1;
            u->killed = k2, u->kcap = c;
        }
        size_t nh = (size_t)r;
        int iter = w->iter, *horf = w->horf, *newf = w->newf, *visl = w->visl;
        /* a new facet with the initial simplex's centroid above it faces inward (hv_cone): the visible
         * region was inconsistent (fuzz_hull_volume: a sweep's corner then counted 1.74 of volume
         * that lay inside, +15%); numerically ambiguous */
        if (inward) return -2;
        /* a new facet (a sweep's, or the per-set hull's since fuzz_hull_volume's fold_per_set: there
         * point 1, 3.9e-7 of the extent off the line of its horizon edge, made a facet 1.4e-4 below the
         * horizon facet's third vertex, and a later point was never tested against it, the volume
         * 2.8e-5 below qhull's; acd_hull_volume_fast then leaves the set to qhull) must not fold over
         * its horizon facet (that facet's third vertex above it
         * by more than HULL_VOLUME_FOLD x eps): q within eps of the horizon facet's plane and nearly on
         * the line of their edge tilts the new plane by up to eps over q's distance from that line, the
         * hull is no longer convex there, and a later point above the horizon facet is never tested
         * against it (fuzz_hull_volume, sweep_thin_prefix2: q 1.5e-11 of the extent above the horizon
         * facet's plane, 1.2e-9 off the edge's line; the new plane tilted 0.01 rad, the horizon facet's
         * third vertex 1.1e-2 of the extent above it; the next prefix's hull missed a point 9e-5 of the
         * extent above the horizon facet, its volume 1.6e-5 below qhull's). Numerically ambiguous: the
         * query is declined, a prefix's hull built again from scratch. The vertex (within the extent D
         * of the edge's line) is above the new plane by at most about D eps / d, d q's distance from
         * that line, so only the edges with d under HULL_VOLUME_NARROW eps (twice D / HULL_VOLUME_FOLD)
         * are checked (hv_cone's, in w->horu). Smaller folds are left: on fandisk's budget run 131 of
         * its 137 folds beyond eps were within 100 eps (each refusal costs a rebuild). */
        for (size_t j = 0; j < w->nnarrow; j++) {
            int k = w->horu[j];
            const hv_facet *H = &w->f[horf[k]];
            if (hv_dist(&w->f[newf[k]], p + 3 * (H->v[0] + H->v[1] + H->v[2] - w->hor[2 * k] - w->hor[2 * k + 1])) >
                HULL_VOLUME_FOLD * eps)
                return -2;
        }
        w->lastf = newf[0];
        /* the visible facets' outside points to the first new facet they are above (their planes
         * packed by hv_cone); not above a new facet, a point may still be above a horizon facet: then
         * the first of those, each once in their first order (their planes packed when first needed) */
        const double zero[3] = {0, 0, 0};
        double *pl = w->pl, *ph = pl + 4 * (nh + (nh & 1));
        int *horu = w->horu;
        size_t nu = 0;
        int hpacked = 0;
        for (size_t k = 0; k < nv; k++) {
            w->alive[visl[k]] = 0;
            if (u) u->killed[u->nk++] = visl[k];
            for (int i = w->o[visl[k]].head; i >= 0;) {
                int nx = w->next[i];
                if (i != pi) {
                    const double *x = p + 3 * i;
                    double dd = 0;
                    int pos = 0, to = -1;
                    size_t j = hv_first_above(pl, nh, x, eps, &dd, &pos);
                    if (j < nh)
                        to = newf[j];
                    else {
                        if (!hpacked) {
                            for (size_t t = 0; t < nh; t++) {
                                int h = horf[t];
                                if (w->f[h].vis == -iter) continue;
                                w->f[h].vis = -iter;
                                hv_pack(ph, nu, w->f[h].n, w->f[h].d);
                                horu[nu++] = h;
                            }
                            if (nu & 1) hv_pack(ph, nu, zero, INFINITY);
                            hpacked = 1;
                        }
                        j = hv_first_above(ph, nu, x, eps, &dd, &pos);
                        if (j < nu)
                            to = horu[j];
                        else if (w->sweep && pos) { /* near the hull: the first facet x is farthest above */
                            double mx = 0;
                            int bf = -1;
                            for (size_t t = 0; t < nh; t++) {
                                double d = hv_packed_dist(pl, t, x);
                                if (d > mx) mx = d, bf = newf[t];
                            }
                            for (size_t t = 0; t < nu; t++) {
                                double d = hv_packed_dist(ph, t, x);
                                if (d > mx) mx = d, bf = horu[t];
                            }
                            if (bf >= 0 && !hv_near_add(w, p, i, bf, eps)) return -1;
                        }
                    }
                    if (to >= 0) {
                        hv_out *O = &w->o[to];
                        w->next[i] = O->head;
                        O->head = i;
                        if (dd > O->fard) O->fard = dd, O->far = i;
                    }
                }
                i = nx;
            }
            w->o[visl[k]].head = -1;
        }
        if (top + 2 * nh > w->pendcap && !hv_grow_int(&w->pend, &w->pendcap, top + 2 * nh)) return -1;
        const hv_out *on = w->o + newf[0]; /* (the new facets are newf[0] + k) */
        for (size_t k = 0; k < nh; k++) { /* (without branches to mispredict) */
            w->pend[top] = newf[k], top += on[k].head >= 0;
            w->pend[top] = horf[k], top += w->o[horf[k]].head >= 0;
        }
    }
    return 0;
}

/* The initial simplex of the first n points of p (built in w, the other points assigned to its
 * facets' outside sets, the facets with points pushed on w->pend: *top of them) and the tolerance
 * in *eps_out, the set's extent (its largest side) in *ext_out unless NULL. 1; 0 for a flat set or
 * fewer than 4 points; -1 when out of memory; -2 for qhull (HULL_VOLUME_RANGE) or on trouble; -4 when
 * the set is to be centred first (HULL_VOLUME_OFFSET). */
static int hv_simplex(const double *p, size_t n, acd_hull_volume_ws *w, double *eps_out, double *ext_out,
                      size_t *top_out) {
    if (n < 4) return 0;
    if (!hv_reserve_points(w, n) || !hv_grow_int(&w->pend, &w->pendcap, 64) || (w->hcap < 64 && !hv_grow_horizon(w, 64)))
        return -1;
    w->nf = 0;
    /* the initial simplex: the extreme pair along the axes, then farthest from its line, then from
     * their plane */
    int ex[6];
    for (int k = 0; k < 3; k++) ex[2 * k] = ex[2 * k + 1] = 0;
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) lo[k] = hi[k] = p[k];
    for (size_t i = 1; i < n; i++)
        for (int k = 0; k < 3; k++) {
            if (p[3 * i + k] < lo[k]) lo[k] = p[3 * i + k], ex[2 * k] = (int)i;
            if (p[3 * i + k] > hi[k]) hi[k] = p[3 * i + k], ex[2 * k + 1] = (int)i;
        }
    double ext = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    if (!(ext > 0)) return 0;
    double scale = fmax(fmax(fabs(lo[0]), fabs(hi[0])), fmax(fmax(fabs(lo[1]), fabs(hi[1])), fmax(fabs(lo[2]), fabs(hi[2]))));
    if (!(scale <= HULL_VOLUME_RANGE) || !(ext >= 1.0 / HULL_VOLUME_RANGE)) return -2; /* to qhull */
    if (scale > HULL_VOLUME_OFFSET * ext) return -4;                                       /* centre it */
    double eps = HULL_VOLUME_EPS * fmax(scale, ext);
    *eps_out = eps;
    if (ext_out) *ext_out = ext;
    int i0 = ex[0], i1 = ex[1];
    double best = -1;
    for (int a = 0; a < 6; a++)
        for (int b = a + 1; b < 6; b++) {
            const double *A = p + 3 * ex[a], *B = p + 3 * ex[b];
            double dd = (A[0] - B[0]) * (A[0] - B[0]) + (A[1] - B[1]) * (A[1] - B[1]) + (A[2] - B[2]) * (A[2] - B[2]);
            if (dd > best) best = dd, i0 = ex[a], i1 = ex[b];
        }
    const double *P0 = p + 3 * i0, *P1 = p + 3 * i1;
    double u[3] = {P1[0] - P0[0], P1[1] - P0[1], P1[2] - P0[2]};
    int i2 = -1;
    best = 0;
    for (size_t i = 0; i < n; i++) {
        const double *q = p + 3 * i;
        double r[3] = {q[0] - P0[0], q[1] - P0[1], q[2] - P0[2]};
        double c[3] = {u[1] * r[2] - u[2] * r[1], u[2] * r[0] - u[0] * r[2], u[0] * r[1] - u[1] * r[0]};
        double dd = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
        if (dd > best) best = dd, i2 = (int)i;
    }
    if (i2 < 0) return 0;
    const double *P2 = p + 3 * i2;
    double v2[3] = {P2[0] - P0[0], P2[1] - P0[1], P2[2] - P0[2]};
    double nn[3] = {u[1] * v2[2] - u[2] * v2[1], u[2] * v2[0] - u[0] * v2[2], u[0] * v2[1] - u[1] * v2[0]};
    double nl = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
    if (!(nl > 0)) return 0;
    int i3 = -1;
    best = 0;
    /* the first point of largest |distance| (the quotient by nl, computed only where the numerator
     * grows: the division is monotone, so a smaller numerator cannot give a larger quotient) */
    double bestnum = 0;
    for (size_t i = 0; i < n; i++) {
        const double *q = p + 3 * i;
        double num = fabs(nn[0] * (q[0] - P0[0]) + nn[1] * (q[1] - P0[1]) + nn[2] * (q[2] - P0[2]));
        if (!(num > bestnum)) continue;
        bestnum = num;
        double dd = num / nl;
        if (dd > best) best = dd, i3 = (int)i;
    }
    if (i3 < 0 || !(best > HULL_VOLUME_FLAT * fmax(scale, ext))) return 0; /* flat: qhull's dim < 3 gives 0 too */
    int tri[4][3] = {{i0, i1, i2}, {i0, i1, i3}, {i0, i2, i3}, {i1, i2, i3}};
    double cen0[3];
    for (int k = 0; k < 3; k++) cen0[k] = (p[3 * i0 + k] + p[3 * i1 + k] + p[3 * i2 + k] + p[3 * i3 + k]) / 4;
    memcpy(w->cen, cen0, sizeof cen0);
    for (int t = 0; t < 4; t++) {
        if (hv_new_facet(w, p, tri[t][0], tri[t][1], tri[t][2]) < 0) return -1;
        if (hv_dist(&w->f[t], cen0) > 0) { /* inward: reversed */
            w->nf--;
            if (hv_new_facet(w, p, tri[t][0], tri[t][2], tri[t][1]) < 0) return -1;
        }
    }
    double cen[3];
    for (int k = 0; k < 3; k++) cen[k] = (p[3 * i0 + k] + p[3 * i1 + k] + p[3 * i2 + k] + p[3 * i3 + k]) / 4;
    for (int t = 0; t < 4; t++)
        if (hv_dist(&w->f[t], cen) > 0) return -2; /* not outward: should not happen */
    /* neighbours of the simplex: by matching edges */
    for (int a = 0; a < 4; a++)
        for (int k = 0; k < 3; k++) {
            int x = w->f[a].v[k], y = w->f[a].v[(k + 1) % 3];
            w->f[a].nb[k] = -1;
            for (int b = 0; b < 4; b++)
                for (int m = 0; m < 3 && b != a; m++)
                    if (w->f[b].v[m] == y && w->f[b].v[(m + 1) % 3] == x) w->f[a].nb[k] = b;
            if (w->f[a].nb[k] < 0) return -2;
        }
    int all[4] = {0, 1, 2, 3};
    for (size_t i = 0; i < n; i++) {
        w->start[i] = w->end[i] = -1;
        if ((int)i == i0 || (int)i == i1 || (int)i == i2 || (int)i == i3) continue;
        double mx;
        int fm;
        if (!hv_assign(w, p, (int)i, all, 4, eps, &mx, &fm) && w->sweep && mx > 0 && !hv_near_add(w, p, (int)i, fm, eps))
            return -1;
    }
    size_t top = 0;
    for (int t = 0; t < 4; t++)
        if (w->o[t].head >= 0) w->pend[top++] = t;
    *top_out = top;
    return 1;
}

/* The first n points of p less the centre of their bounding box, into q. */
static void hv_centred(const double *p, size_t n, double *q, double c[3]) {
    double lo[3] = {p[0], p[1], p[2]}, hi[3] = {p[0], p[1], p[2]};
    for (size_t i = 1; i < n; i++)
        for (int k = 0; k < 3; k++) lo[k] = fmin(lo[k], p[3 * i + k]), hi[k] = fmax(hi[k], p[3 * i + k]);
    for (int k = 0; k < 3; k++) c[k] = lo[k] + 0.5 * (hi[k] - lo[k]);
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) q[3 * i + k] = p[3 * i + k] - c[k];
}

/* The volume of the hull in w (its alive facets, points p): tetrahedra from the initial simplex's
 * centroid (w->cen, inside the hull). */
static double hv_hull_volume(const acd_hull_volume_ws *w, const double *p) {
    const double *cen = w->cen;
    double s = 0;
    for (size_t t = 0; t < w->nf; t++) {
        const hv_facet *F = &w->f[t];
        if (!w->alive[t]) continue;
        const double *A = p + 3 * F->v[0], *B = p + 3 * F->v[1], *C = p + 3 * F->v[2];
        double a[3] = {A[0] - cen[0], A[1] - cen[1], A[2] - cen[2]}, b[3] = {B[0] - cen[0], B[1] - cen[1], B[2] - cen[2]},
               c[3] = {C[0] - cen[0], C[1] - cen[1], C[2] - cen[2]};
        s += a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return s / 6;
}

/* The Quickhull from the initial simplex (its outside sets in w, top facets pending) and the volume. */
static double hv_finish(acd_hull_volume_ws *w, const double *p, double eps, size_t top) {
    int r = hv_expand(w, p, eps, top, NULL, NULL);
    return r < 0 ? r : hv_hull_volume(w, p);
}

static double hull_volume_qh(const double *p, size_t n, acd_hull_volume_ws *w) {
    double eps;
    size_t top;
    int r = hv_simplex(p, n, w, &eps, NULL, &top);
    if (r == -4) { /* far from the origin: the same set about its centre */
        double *q = malloc(3 * n * sizeof *q), c[3];
        if (!q) return -1;
        hv_centred(p, n, q, c);
        r = hv_simplex(q, n, w, &eps, NULL, &top);
        double v = r == 1 ? hv_finish(w, q, eps, top) : r == -4 ? -2 : r;
        free(q);
        return v;
    }
    if (r <= 0) return r;
    return hv_finish(w, p, eps, top);
}


double acd_hull_volume_fast(const double *pts, size_t n, acd_hull_volume_ws *w, int *fallback) {
    double v = hull_volume_qh(pts, n, w);
    if (fallback) *fallback = v == -2;
    return v == -2 ? hull_volume_pts(pts, n) : v;
}

int acd_hull_volume_vertices(const double *pts, size_t n, acd_hull_volume_ws *w, unsigned char *flag, size_t *nflag) {
    double v = hull_volume_qh(pts, n, w);
    if (v == -1) return -1;
    if (!(v > 0)) return 0; /* flat, fewer than 4 points, or left to qhull */
    for (size_t i = 0; i < n; i++) flag[i] = 0;
    size_t k = 0;
    for (size_t t = 0; t < w->nf; t++)
        if (w->alive[t])
            for (int j = 0; j < 3; j++) {
                unsigned char *x = &flag[w->f[t].v[j]];
                k += !*x;
                *x = 1;
            }
    *nflag = k;
    return 1;
}

/* a before b: (u, v, index) in lexicographic order */
static int hv_uv_less(const double *a, const double *b) {
    return a[0] < b[0] || (a[0] == b[0] && (a[1] < b[1] || (a[1] == b[1] && a[2] < b[2])));
}

/* The n triples of uv sorted (hv_uv_less): a merge sort through tmp (room for as many), the runs
 * of 8 by insertion first. */
static void hv_uv_sort(double *uv, double *tmp, size_t n) {
    for (size_t a = 0; a < n; a += 8) {
        size_t b = a + 8 < n ? a + 8 : n;
        for (size_t i = a + 1; i < b; i++) {
            double x[3] = {uv[3 * i], uv[3 * i + 1], uv[3 * i + 2]};
            size_t j = i;
            for (; j > a && hv_uv_less(x, uv + 3 * (j - 1)); j--) memcpy(uv + 3 * j, uv + 3 * (j - 1), sizeof x);
            memcpy(uv + 3 * j, x, sizeof x);
        }
    }
    double *src = uv, *dst = tmp;
    for (size_t w = 8; w < n; w *= 2) {
        for (size_t a = 0; a < n; a += 2 * w) {
            size_t m = a + w < n ? a + w : n, b = a + 2 * w < n ? a + 2 * w : n, i = a, j = m, k = a;
            while (i < m && j < b) {
                const double *x = hv_uv_less(src + 3 * j, src + 3 * i) ? src + 3 * j++ : src + 3 * i++;
                memcpy(dst + 3 * k++, x, sizeof(double[3]));
            }
            memcpy(dst + 3 * k, src + 3 * i, (m - i) * sizeof(double[3])), k += m - i;
            memcpy(dst + 3 * k, src + 3 * j, (b - j) * sizeof(double[3]));
        }
        double *t = src;
        src = dst, dst = t;
    }
    if (src != uv) memcpy(uv, src, n * sizeof(double[3]));
}

/* The corners of the planar hull of the nx points x (on a plane of normal dir) into out (their
 * indices in x, each at most once: at most nx); how many. uv: room for 6 * nx doubles, out for
 * 2 * nx + 2 ints (the chains before duplicates are dropped). */
static size_t hv_corners(const double *x, size_t nx, const double dir[3], double *uv, int *out) {
    double u[3];
    int k0 = fabs(dir[0]) < fabs(dir[1]) ? (fabs(dir[0]) < fabs(dir[2]) ? 0 : 2) : (fabs(dir[1]) < fabs(dir[2]) ? 1 : 2);
    double e[3] = {0, 0, 0};
    e[k0] = 1;
    u[0] = dir[1] * e[2] - dir[2] * e[1], u[1] = dir[2] * e[0] - dir[0] * e[2], u[2] = dir[0] * e[1] - dir[1] * e[0];
    double v[3] = {dir[1] * u[2] - dir[2] * u[1], dir[2] * u[0] - dir[0] * u[2], dir[0] * u[1] - dir[1] * u[0]};
    for (size_t i = 0; i < nx; i++) {
        const double *q = x + 3 * i;
        uv[3 * i] = u[0] * q[0] + u[1] * q[1] + u[2] * q[2];
        uv[3 * i + 1] = v[0] * q[0] + v[1] * q[1] + v[2] * q[2];
        uv[3 * i + 2] = (double)i;
    }
    hv_uv_sort(uv, uv + 3 * nx, nx);
    /* Andrew's monotone chain, strict turns only */
    size_t m = 0;
    int *h = out;
#define HV_CROSS(o, a, b) ((uv[3 * (a)] - uv[3 * (o)]) * (uv[3 * (b) + 1] - uv[3 * (o) + 1]) - (uv[3 * (a) + 1] - uv[3 * (o) + 1]) * (uv[3 * (b)] - uv[3 * (o)]))
    for (size_t i = 0; i < nx; i++) {
        while (m >= 2 && HV_CROSS(h[m - 2], h[m - 1], (int)i) <= 0) m--;
        h[m++] = (int)i;
    }
    for (size_t i = nx - 1, t = m + 1; i-- > 0;) {
        while (m >= t && HV_CROSS(h[m - 2], h[m - 1], (int)i) <= 0) m--;
        h[m++] = (int)i;
    }
#undef HV_CROSS
    if (m > 1) m--; /* the first point again */
    /* to indices in x, each once: the turns are rounded, so on a nearly collinear set a point can end
     * on both chains (anchor.off's budget run: 29 corners of 27 points, which overran the caller's
     * room for nx); a point taken has its index slot set to -1 */
    size_t k = 0;
    for (size_t i = 0; i < m; i++) {
        double *s = uv + 3 * h[i] + 2;
        if (*s < 0) continue;
        h[k++] = (int)*s;
        *s = -1;
    }
    return k;
}

/* Point i into the outside set of facet f (which it sees, dd above its plane: hv_dist), f onto the
 * pending stack (of top entries) if its set was empty, f's farthest point updated. 0 when the stack
 * cannot grow. */
static int hv_push_outside(acd_hull_volume_ws *w, int i, int f, double dd, size_t *top) {
    hv_out *O = &w->o[f];
    if (O->head < 0) {
        if (*top + 1 > w->pendcap && !hv_grow_int(&w->pend, &w->pendcap, *top + 1)) return 0;
        w->pend[(*top)++] = f;
    }
    w->next[i] = O->head;
    O->head = i;
    if (dd > O->fard) O->fard = dd, O->far = i;
    return 1;
}

/* The sweep's points near the hull (w->near: above a facet, by at most eps, when they were found
 * inside or dropped from a removed facet's outside set) that are above an alive facet made since
 * facet f0 by more than eps, into the outside set of the one they are farthest above (pending, *top
 * entries). Outside the queries (stamp NULL) they leave the list; in query q the first np entries (the
 * prefix's) stay, stamped q (not taken twice), the others (the query's) leave it. How many; -1 when
 * out of memory.
 *
 * Why: a point within eps of every facet it is above is taken as inside, but near an edge whose
 * facets meet at a small angle b (a hull nearly flat, as a prefix can be) it can lie up to about
 * 2 eps / b beyond the hull; a later point whose cone replaces one of those facets can leave it
 * outside by far more (fuzz_hull_volume: a prefix 1.6e-8 of its extent thick, a point 6.5e-3 of the
 * extent beyond its rim found inside; the hull of the next prefix missed it, the query's volume 0.3%
 * below qhull's). The per-set Quickhull does not keep them: its hull contains the initial simplex of
 * the whole set, so such an edge is as thin as the set and what it misses is of order eps x extent^2. */
static long hv_near_retest(acd_hull_volume_ws *w, const double *P, double eps, size_t f0, size_t np, int *stamp, int q,
                           size_t *top) {
    size_t keep = 0;
    long pushed = 0;
    for (size_t k = 0; k < w->nnear; k++) {
        int i = w->near[k], pre = stamp && k < np;
        if (pre && stamp[i] == q) {
            w->near[keep++] = i;
            continue;
        }
        const double *x = P + 3 * (size_t)i;
        int bf = -1;
        double bd = eps;
        for (size_t t = f0; t < w->nf; t++)
            if (w->alive[t]) {
                double dd = hv_dist(&w->f[t], x);
                if (dd > bd) bd = dd, bf = (int)t;
            }
        if (bf >= 0 && !hv_push_outside(w, i, bf, bd, top)) return -1;
        pushed += bf >= 0;
        if (bf < 0 || pre) w->near[keep++] = i;
        if (bf >= 0 && pre) stamp[i] = q;
    }
    w->nnear = keep;
    return pushed;
}

/* The sweep's hull of the first n points of P from scratch (Quickhull, then its points near the hull
 * tested again: hv_near_retest), its volume in *V and tolerance in *eps: 1; 0 when flat, numerically
 * ambiguous, too small for the sweep (its scale under HULL_VOLUME_PREFIX_REL of `whole`, the
 * extent of every point the sweep may add) or too thin (HULL_VOLUME_THICK_START); -1 when out of
 * memory. */
static int hv_chain_start(acd_hull_volume_ws *w, const double *P, size_t n, double whole, double *eps, double *V) {
    size_t top = 0;
    w->nnear = 0;
    double ext; /* the prefix's extent */
    int r = hv_simplex(P, n, w, eps, &ext, &top);
    if (r != 1) return r == -1 || r == -4 ? r : 0;
    /* (hv_simplex's tolerance is HULL_VOLUME_EPS times the prefix's scale) */
    if (!(*eps >= HULL_VOLUME_EPS * HULL_VOLUME_PREFIX_REL * whole)) return 0;
    w->lastf = 0;
    for (;;) {
        r = hv_expand(w, P, *eps, top, NULL, NULL);
        if (r < 0) return r == -1 ? -1 : 0;
        top = 0;
        long k = hv_near_retest(w, P, *eps, 0, 0, NULL, 0, &top);
        if (k < 0) return -1;
        if (k == 0) break;
    }
    *V = hv_hull_volume(w, P);
    if (!(*V >= HULL_VOLUME_THICK_START * *eps * ext * ext)) return 0; /* too thin to grow from */
    return 1;
}

int acd_hull_volume_sweep(const double *pts, size_t n, const double dir[3], const size_t *cnt, const double *xs,
                          const size_t *xb, const size_t *xe, int nq, double *vol, acd_hull_volume_ws *w) {
    return acd_hull_volume_sweep_some(pts, n, dir, cnt, xs, xb, xe, nq, NULL, vol, w);
}

int acd_hull_volume_sweep_some(const double *pts, size_t n, const double dir[3], const size_t *cnt, const double *xs,
                               const size_t *xb, const size_t *xe, int nq, const unsigned char *need, double *vol,
                               acd_hull_volume_ws *w) {
    int qend = nq; /* after the last query asked for, the sweep stops */
    if (need)
        while (qend > 0 && !need[qend - 1]) qend--;
    for (int q = 0; q < nq; q++) vol[q] = need && !need[q] ? -4 : -3;
    size_t maxx = 0;
    double big = 0; /* the largest coordinate of every point the sweep may add: beyond the range, none
                     * is computed here (hv_simplex checks only the first prefix) */
    for (size_t i = 0; i < 3 * n; i++) { /* as fmax (a NaN skipped), without its call */
        double a = fabs(pts[i]);
        big = a > big ? a : big;
    }
    for (int q = 0; q < nq; q++) {
        if (xe[q] - xb[q] > maxx) maxx = xe[q] - xb[q];
        for (size_t i = 3 * xb[q]; i < 3 * xe[q]; i++) {
            double a = fabs(xs[i]);
            big = a > big ? a : big;
        }
    }
    if (!(big <= HULL_VOLUME_RANGE)) return 0;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, whole = 0;
    /* as fmin and fmax (a NaN skipped; lo and hi never NaN), without their calls: a zero's sign cannot
     * change `whole` (a difference of zeros is only taken when hi > lo) */
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            double x = pts[3 * i + k];
            lo[k] = x < lo[k] ? x : lo[k], hi[k] = x > hi[k] ? x : hi[k];
        }
    for (int q = 0; q < nq; q++)
        for (size_t i = xb[q]; i < xe[q]; i++)
            for (int k = 0; k < 3; k++) {
                double x = xs[3 * i + k];
                lo[k] = x < lo[k] ? x : lo[k], hi[k] = x > hi[k] ? x : hi[k];
            }
    for (int k = 0; k < 3; k++) whole = hi[k] > lo[k] ? fmax(whole, hi[k] - lo[k]) : whole;
    double *P = malloc(3 * (n + maxx + 1) * sizeof *P), *uv = malloc(6 * (maxx + 1) * sizeof *uv);
    int *corner = malloc((2 * maxx + 2) * sizeof *corner), *stamp = malloc((n + maxx + 1) * sizeof *stamp);
    hv_undo U;
    memset(&U, 0, sizeof U);
    int st = 0;
    w->nf = 0; /* (room for the facets of a hull of all the points at once: fewer copies as it grows) */
    if (!P || !uv || !corner || !stamp || !hv_reserve_points(w, n + maxx + 1) || !hv_grow_int(&w->pend, &w->pendcap, 64) ||
        !hv_reserve_facets(w, 4 * (n + maxx) + 256) ||
        (w->hcap < 64 && !hv_grow_horizon(w, 64))) {
        st = -1;
        goto out;
    }
    memcpy(P, pts, 3 * n * sizeof *P);
    w->sweep = 1;
    w->nnear = 0;
    for (size_t i = 0; i < n + maxx + 1; i++) w->start[i] = w->end[i] = -1, stamp[i] = -1;
    /* the first query whose prefix has a volume: the hull of it by the Quickhull above */
    int q0 = 0, centred = 0;
    double eps = 0, V = 0, c[3] = {0, 0, 0};
    size_t top = 0;
    for (; q0 < qend; q0++) {
        if (cnt[q0] < 4) continue;
        int r = hv_chain_start(w, P, cnt[q0], whole, &eps, &V);
        if (r == -1) {
            st = -1;
            goto out;
        }
        if (r == -4 && !centred) { /* far from the origin: every point about the box's centre, again */
            centred = 1;
            hv_centred(pts, n, P, c);
            q0--;
            continue;
        }
        if (r == 1) break;
    }
    if (q0 == qend) goto out;
    int last = w->lastf;
    for (int q = q0; q < qend; q++) {
        if (q > q0) { /* the points up to this query's prefix: outside sets, then the Quickhull loop, then
                       * the points near the hull above a facet made since (hv_near_retest), again */
            top = 0;
            size_t fm = w->nf;
            for (size_t i = cnt[q - 1]; i < cnt[q]; i++) {
                double dm;
                int fm, f = hv_find_visible(w, P + 3 * i, last, eps, &dm, &fm);
                if (f < 0) {
                    if (dm > 0 && !hv_near_add(w, P, (int)i, fm, eps)) {
                        st = -1;
                        goto out;
                    }
                    continue;
                }
                if (!hv_push_outside(w, (int)i, f, dm, &top)) {
                    st = -1;
                    goto out;
                }
                last = f;
            }
            for (;;) {
                if (top > 0) {
                    int r = hv_expand(w, P, eps, top, &V, NULL);
                    if (r == -1) {
                        st = -1;
                        goto out;
                    }
                    if (r == -2) { /* the hull of this prefix again from scratch, then on */
                        r = hv_chain_start(w, P, cnt[q], whole, &eps, &V);
                        if (r == -1) st = -1;
                        if (r != 1) goto out;
                        last = w->lastf;
                        break;
                    }
                    last = w->lastf;
                }
                size_t f1 = w->nf;
                top = 0;
                long k = hv_near_retest(w, P, eps, fm, 0, NULL, 0, &top);
                if (k < 0) {
                    st = -1;
                    goto out;
                }
                if (k == 0) break;
                fm = f1;
            }
        }
        if (need && !need[q]) continue; /* (its corners would be undone: the hull is as if it had run) */
        /* the query: the corners of its extra points' planar hull added, the volume, then undone */
        size_t nx = xe[q] - xb[q];
        if (nx == 0) {
            vol[q] = V;
            continue;
        }
        size_t nc = nx >= 3 ? hv_corners(xs + 3 * xb[q], nx, dir, uv, corner) : 0;
        if (nx < 3) {
            for (size_t j = 0; j < nx; j++) corner[j] = (int)j;
            nc = nx;
        }
        size_t nf0 = w->nf, np = w->nnear;
        int start = last;
        U.nnb = U.nk = 0;
        double Vx = 0;
        top = 0;
        for (size_t j = 0; j < nc; j++) { /* outside sets, then the Quickhull loop (farthest first) */
            int pi = (int)(n + j);
            for (int k = 0; k < 3; k++) P[3 * pi + k] = xs[3 * (xb[q] + (size_t)corner[j]) + k] - c[k];
            double dm;
            int fm, f = hv_find_visible(w, P + 3 * pi, start, eps, &dm, &fm);
            if (f < 0) {
                if (dm > 0 && !hv_near_add(w, P, pi, fm, eps)) {
                    st = -1;
                    goto out;
                }
                continue;
            }
            start = f; /* the next corner is the polygon's next: near this one */
            if (!hv_push_outside(w, pi, f, dm, &top)) {
                st = -1;
                goto out;
            }
        }
        int r = hv_expand(w, P, eps, top, &Vx, &U);
        for (size_t fm = nf0; r == 0;) { /* the points near the hull above a facet the query made */
            size_t f1 = w->nf;
            top = 0;
            long k = hv_near_retest(w, P, eps, fm, np, stamp, q, &top);
            if (k <= 0) {
                r = (int)k;
                break;
            }
            r = hv_expand(w, P, eps, top, &Vx, &U);
            fm = f1;
        }
        if (r == -1) {
            st = -1;
            goto out;
        }
        if (r == 0) vol[q] = V + Vx;
        for (size_t k = 0; k < U.nk; k++) {
            hv_out *O = &w->o[U.killed[k]];
            w->alive[U.killed[k]] = 1, O->head = -1, O->far = -1, O->fard = 0;
        }
        for (size_t k = U.nnb; k >= 3; k -= 3) w->f[U.nb[k - 3]].nb[U.nb[k - 2]] = U.nb[k - 1];
        if (r == -2) /* stopped midway: outside sets left on the facets made before */
            for (size_t t = 0; t < nf0; t++) w->o[t].head = -1, w->o[t].far = -1, w->o[t].fard = 0;
        w->nf = nf0;
        w->nnear = np;
    }
out:
    w->sweep = 0;
    free(P), free(uv), free(corner), free(stamp), free(U.nb), free(U.killed);
    return st;
}
