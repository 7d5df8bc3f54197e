/* acd3/budget: splitting under a part budget by hull excess; see budget.h. */
#include "acd3/budget.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "acd3/leaf_test.h"
#include "acd3/resolve.h"
#include "core/error.h"
#include "geom3/pca.h"
#include "geom3/plane_cut.h"

/* A cut leaving a piece below this fraction of the part's volume is refused (a sliver), as in the
 * decomposition's own splits. */
#define BUDGET_MIN_PIECE_FRACTION 1e-6
/* Safety net on the number of atoms (parts and pieces). */
#define BUDGET_MAX_ATOMS 20000

typedef struct atom {
    acd_mesh mesh;   /* owned for pieces, a shallow copy for input parts */
    double vol, hvol, bound;
    int ok;          /* bound <= limit (or not checked) */
    int alive;       /* a part of the current decomposition (not cut) */
    double gain;     /* hull volume its best split saves; -INFINITY: no split */
    acd_cut_result cut; /* that split's pieces (npieces >= 2), or none */
    double plane[4];
    acd_status st;
    size_t parent;   /* pieces: the atom cut */
    int evaluated;   /* gain and cut computed (lazily: only when the atom may be the next cut) */
} atom;

typedef struct budget_state {
    atom *a;
    size_t n, cap, nparts;
    double limit, extent;
    int ndir, nexact;
} budget_state;

static double hull_volume_of(const acd_mesh *m, acd_hull *keep) {
    acd_hull h;
    if (acd_hull_compute(m->vertices, m->nvertices, &h, NULL) != ACD_OK) return -1;
    double v = h.dim == 3 ? h.volume : 0;
    if (keep) *keep = h;
    else acd_hull_free(&h);
    return v;
}


/* Vertices scored at most by the plane search (every k-th beyond; every crossing of the sampled
 * triangles' edges too). */
#define BUDGET_MAX_DIRS 80
#define BUDGET_DIRS 40
#define BUDGET_EXACT 3
#define BUDGET_REFINE_DIRS 3
#define BUDGET_BATCH 4
#define BUDGET_MAX_SCORED 1000
#define BUDGET_OFFSETS 9
#define BUDGET_REFINE 3

static double hull_volume_pts(const double *pts, size_t n) {
    if (n < 4) return 0;
    acd_hull h;
    if (acd_hull_compute(pts, n, &h, NULL) != ACD_OK) return -1;
    double v = h.dim == 3 ? h.volume : 0;
    acd_hull_free(&h);
    return v;
}

/* A point within this fraction of the coordinates' scale of a facet's plane counts as inside it; a
 * set this thin (relative to the same scale) has no volume. */
#define BUDGET_HULL_EPS 1e-10
#define BUDGET_HULL_FLAT 1e-8

/* A convex hull's volume by Quickhull (Barber, Dobkin and Huhdanpaa's outside sets; our own,
 * written for the plane scores alone: no facet merging, no output but the volume, no setup per
 * call but the workspace, reused), 3-4x cheaper than a qhull run through acd_hull_compute. The
 * points of a removed facet go to the new facets or, failing those, the horizon facets (as qhull's
 * qh_findbestnew looks at both). With floating-point predicates only, a point just above a facet
 * farther away can be lost: against acd_hull_compute the volumes agree within 1e-9 relative on
 * every set knot1's run scores, within 2e-5 on fandisk's (CAD, many coplanar points), and the
 * budget output on the six target meshes is byte-identical. Returns -2 when the horizon is not
 * one simple cycle (numerically ambiguous: the caller falls back to qhull), -1 when out of
 * memory. */
typedef struct hv_facet {
    int v[3], nb[3]; /* nb[k]: across edge (v[k], v[k+1]) */
    double n[3], d;  /* unit outward normal, n.x = d on the plane */
    int head, far;   /* outside set (a list through hv_ws.next) and its farthest point */
    double fard;
    int alive, mark;
} hv_facet;

typedef struct hv_ws {
    hv_facet *f;
    size_t nf, fcap;
    int *next, *start, *end, *stack, *vis; /* per point: list link, horizon edge from / to it;
                                             per facet: search stack, visible mark */
    size_t pcap;
} hv_ws;

static void hv_ws_free(hv_ws *w) {
    free(w->f), free(w->next), free(w->start), free(w->end), free(w->stack), free(w->vis);
    memset(w, 0, sizeof *w);
}

static int hv_reserve_points(hv_ws *w, size_t n) {
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

static int hv_new_facet(hv_ws *w, const double *p, int a, int b, int c) {
    if (w->nf == w->fcap) {
        size_t nc = w->fcap ? 2 * w->fcap : 256;
        hv_facet *f = realloc(w->f, nc * sizeof *f);
        if (!f) return -1;
        w->f = f, w->fcap = nc;
        int *s = realloc(w->stack, nc * sizeof *s);
        if (!s) return -1;
        w->stack = s;
        int *v = realloc(w->vis, nc * sizeof *v);
        if (!v) return -1;
        w->vis = v;
    }
    hv_facet *F = &w->f[w->nf];
    F->v[0] = a, F->v[1] = b, F->v[2] = c;
    const double *A = p + 3 * a, *B = p + 3 * b, *C = p + 3 * c;
    double e1[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]}, e2[3] = {C[0] - A[0], C[1] - A[1], C[2] - A[2]};
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (l > 0) n[0] /= l, n[1] /= l, n[2] /= l;
    memcpy(F->n, n, sizeof n);
    F->d = n[0] * A[0] + n[1] * A[1] + n[2] * A[2];
    F->head = -1, F->far = -1, F->fard = 0, F->alive = 1, F->mark = 0;
    w->vis[w->nf] = 0;
    return (int)w->nf++;
}

static inline double hv_dist(const hv_facet *F, const double *q) {
    return F->n[0] * q[0] + F->n[1] * q[1] + F->n[2] * q[2] - F->d;
}

static int hv_assign(hv_ws *w, const double *p, int i, const int *cand, int nc, double eps) {
    for (int k = 0; k < nc; k++) {
        hv_facet *F = &w->f[cand[k]];
        double dd = hv_dist(F, p + 3 * i);
        if (dd > eps) {
            w->next[i] = F->head;
            F->head = i;
            if (dd > F->fard) F->fard = dd, F->far = i;
            return 1;
        }
    }
    return 0;
}

static double hull_volume_qh(const double *p, size_t n, hv_ws *w) {
    if (n < 4) return 0;
    if (!hv_reserve_points(w, n)) return -1;
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
    double eps = BUDGET_HULL_EPS * fmax(scale, ext);
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
    for (size_t i = 0; i < n; i++) {
        const double *q = p + 3 * i;
        double dd = (nn[0] * (q[0] - P0[0]) + nn[1] * (q[1] - P0[1]) + nn[2] * (q[2] - P0[2])) / nl;
        if (fabs(dd) > best) best = fabs(dd), i3 = (int)i;
    }
    if (i3 < 0 || !(best > BUDGET_HULL_FLAT * fmax(scale, ext))) return 0; /* flat: qhull's dim < 3 gives 0 too */
    int tri[4][3] = {{i0, i1, i2}, {i0, i1, i3}, {i0, i2, i3}, {i1, i2, i3}};
    double cen0[3];
    for (int k = 0; k < 3; k++) cen0[k] = (p[3 * i0 + k] + p[3 * i1 + k] + p[3 * i2 + k] + p[3 * i3 + k]) / 4;
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
        if ((int)i == i0 || (int)i == i1 || (int)i == i2 || (int)i == i3) continue;
        hv_assign(w, p, (int)i, all, 4, eps);
    }
    for (size_t i = 0; i < n; i++) w->start[i] = w->end[i] = -1;
    int iter = 0;
    /* the pending facets: a stack of indices (a facet may be pushed when made) */
    size_t top = 0;
    int *pend = NULL;
    size_t pcap = 0;
#define HV_PUSH(x)                                                                                                     \
    do {                                                                                                               \
        if (top == pcap) {                                                                                             \
            size_t nc_ = pcap ? 2 * pcap : 64;                                                                         \
            int *np_ = realloc(pend, nc_ * sizeof *np_);                                                               \
            if (!np_) {                                                                                                \
                free(pend);                                                                                            \
                return -1;                                                                                             \
            }                                                                                                          \
            pend = np_, pcap = nc_;                                                                                    \
        }                                                                                                              \
        pend[top++] = (x);                                                                                             \
    } while (0)
    for (int t = 0; t < 4; t++)
        if (w->f[t].head >= 0) HV_PUSH(t);
    int *hor = NULL, *horf = NULL, *visl = NULL, *newf = NULL;
    size_t hcap = 0, vcap = 0;
    double vol = -1;
    while (top > 0) {
        int fi = pend[--top];
        if (!w->f[fi].alive || w->f[fi].head < 0) continue;
        int pi = w->f[fi].far;
        const double *q = p + 3 * pi;
        iter++;
        /* the visible facets from pi (connected through edges) */
        size_t nv = 0, ns = 0;
        if (vcap < w->nf) {
            vcap = 2 * w->nf;
            int *a = realloc(visl, vcap * sizeof *a);
            if (!a) goto fail_mem;
            visl = a;
        }
        w->vis[fi] = iter;
        w->stack[ns++] = fi;
        while (ns > 0) {
            int g = w->stack[--ns];
            visl[nv++] = g;
            for (int k = 0; k < 3; k++) {
                int h = w->f[g].nb[k];
                if (w->f[h].mark == iter || w->vis[h] == iter) continue;
                if (hv_dist(&w->f[h], q) > eps) {
                    w->vis[h] = iter;
                    w->stack[ns++] = h;
                } else
                    w->f[h].mark = iter; /* checked, not visible */
            }
        }
        /* the horizon: edges of visible facets whose neighbour is not visible */
        size_t nh = 0;
        for (size_t k = 0; k < nv; k++) {
            hv_facet *G = &w->f[visl[k]];
            for (int e = 0; e < 3; e++) {
                int h = G->nb[e];
                if (w->vis[h] == iter) continue;
                if (nh + 1 > hcap) {
                    hcap = hcap ? 2 * hcap : 64;
                    int *a = realloc(hor, 2 * hcap * sizeof *a), *b = a ? realloc(horf, hcap * sizeof *b) : NULL;
                    if (a) hor = a;
                    if (b) horf = b;
                    int *c = b ? realloc(newf, hcap * sizeof *c) : NULL;
                    if (c) newf = c;
                    if (!a || !b || !c) goto fail_mem;
                }
                hor[2 * nh] = G->v[e], hor[2 * nh + 1] = G->v[(e + 1) % 3], horf[nh] = h;
                nh++;
            }
        }
        /* a simple cycle: every vertex starts one horizon edge and ends one */
        int bad = 0;
        for (size_t k = 0; k < nh; k++) {
            if (w->start[hor[2 * k]] >= 0 || w->end[hor[2 * k + 1]] >= 0) bad = 1;
            w->start[hor[2 * k]] = (int)k;
            w->end[hor[2 * k + 1]] = (int)k;
        }
        if (bad || nh < 3) {
            for (size_t k = 0; k < nh; k++) w->start[hor[2 * k]] = w->end[hor[2 * k + 1]] = -1;
            vol = -2;
            goto done;
        }
        for (size_t k = 0; k < nh; k++) {
            int nfi = hv_new_facet(w, p, hor[2 * k], hor[2 * k + 1], pi);
            if (nfi < 0) goto fail_mem;
            newf[k] = nfi;
        }
        for (size_t k = 0; k < nh; k++) {
            hv_facet *F = &w->f[newf[k]];
            int a = hor[2 * k], b = hor[2 * k + 1], h = horf[k];
            F->nb[0] = h;
            F->nb[1] = newf[w->start[b]];
            F->nb[2] = newf[w->end[a]];
            hv_facet *H = &w->f[h];
            for (int e = 0; e < 3; e++)
                if (H->v[e] == b && H->v[(e + 1) % 3] == a) H->nb[e] = newf[k];
        }
        for (size_t k = 0; k < nh; k++) w->start[hor[2 * k]] = w->end[hor[2 * k + 1]] = -1;
        /* the visible facets' outside points to the new facets */
        for (size_t k = 0; k < nv; k++) {
            hv_facet *G = &w->f[visl[k]];
            G->alive = 0;
            for (int i = G->head; i >= 0;) {
                int nx = w->next[i];
                if (i != pi) {
                    /* not above a new facet, it may still be above a horizon facet */
                    if (!hv_assign(w, p, i, newf, (int)nh, eps)) hv_assign(w, p, i, horf, (int)nh, eps);
                }
                i = nx;
            }
            G->head = -1;
        }
        for (size_t k = 0; k < nh; k++) {
            if (w->f[newf[k]].head >= 0) HV_PUSH(newf[k]);
            if (w->f[horf[k]].head >= 0) HV_PUSH(horf[k]);
        }
    }
    {
        double cen[3];
        for (int k = 0; k < 3; k++) cen[k] = (p[3 * i0 + k] + p[3 * i1 + k] + p[3 * i2 + k] + p[3 * i3 + k]) / 4;
        double s = 0;
        for (size_t t = 0; t < w->nf; t++) {
            const hv_facet *F = &w->f[t];
            if (!F->alive) continue;
            const double *A = p + 3 * F->v[0], *B = p + 3 * F->v[1], *C = p + 3 * F->v[2];
            double a[3] = {A[0] - cen[0], A[1] - cen[1], A[2] - cen[2]}, b[3] = {B[0] - cen[0], B[1] - cen[1], B[2] - cen[2]},
                   c[3] = {C[0] - cen[0], C[1] - cen[1], C[2] - cen[2]};
            s += a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
        }
        vol = s / 6;
    }
    goto done;
fail_mem:
    vol = -1;
done:
    free(pend), free(hor), free(horf), free(visl), free(newf);
    return vol;
#undef HV_PUSH
}

static double hull_volume_fast(const double *pts, size_t n, hv_ws *w) {
    double v = hull_volume_qh(pts, n, w);
    return v == -2 ? hull_volume_pts(pts, n) : v;
}

static double score_plane(const acd_mesh *m, size_t stride, size_t tstride, const double nrm[3], double c, double *bufa,
                          double *bufb, hv_ws *w) {
    size_t na = 0, nb = 0;
    for (size_t v = 0; v < m->nvertices; v += stride) {
        const double *p = m->vertices + 3 * v;
        double s = nrm[0] * p[0] + nrm[1] * p[1] + nrm[2] * p[2] - c;
        memcpy(s >= 0 ? bufa + 3 * na++ : bufb + 3 * nb++, p, sizeof(double[3]));
    }
    for (size_t t = 0; t < m->ntriangles; t += tstride)
        for (int k = 0; k < 3; k++) {
            uint32_t i = m->triangles[3 * t + k], j = m->triangles[3 * t + (k + 1) % 3];
            const double *p = m->vertices + 3 * (size_t)i, *q = m->vertices + 3 * (size_t)j;
            double sp = nrm[0] * p[0] + nrm[1] * p[1] + nrm[2] * p[2] - c;
            double sq = nrm[0] * q[0] + nrm[1] * q[1] + nrm[2] * q[2] - c;
            if ((sp >= 0) == (sq >= 0)) continue;
            double a = sp / (sp - sq), x[3];
            for (int d = 0; d < 3; d++) x[d] = p[d] + a * (q[d] - p[d]);
            memcpy(bufa + 3 * na++, x, sizeof x);
            memcpy(bufb + 3 * nb++, x, sizeof x);
        }
    double va = hull_volume_fast(bufa, na, w), vb = hull_volume_fast(bufb, nb, w);
    return va < 0 || vb < 0 ? -1 : va + vb;
}

/* The plane search of one atom: its directions (the part's principal axes, the diagonals between
 * them and a Fibonacci half-sphere in the principal frame), the sample's strides and, per
 * direction, the projection's range and the best offset found. Filled by plan_init, then each
 * direction is scored on its own (score_dir, refine_dir: parallel tasks over the batch's atoms and
 * directions, each computing exactly what the sequential search did). */
typedef struct plan {
    int nd, ok;
    double dirs[BUDGET_MAX_DIRS][3];
    double centroid[3];
    size_t stride, tstride, cap;
    double lo[BUDGET_MAX_DIRS], st[BUDGET_MAX_DIRS], bs[BUDGET_MAX_DIRS], bc[BUDGET_MAX_DIRS];
    int ord[BUDGET_MAX_DIRS];
} plan;

static void plan_init(const acd_mesh *m, int ndir, plan *P) {
    P->ok = 0;
    P->nd = 0;
    if (m->nvertices < 4) return;
    acd_pca pca;
    if (acd_pca_points(m->vertices, m->nvertices, NULL, &pca, NULL) != ACD_OK) return;
    double (*dirs)[3] = P->dirs;
    int nd = 0;
    for (int a = 0; a < 3; a++) memcpy(dirs[nd++], pca.axes[a], sizeof(double[3]));
    if (ndir > 3) {
        static const int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
        for (int q = 0; q < 3; q++)
            for (int sg = -1; sg <= 1; sg += 2) {
                for (int k = 0; k < 3; k++)
                    dirs[nd][k] = (pca.axes[pairs[q][0]][k] + sg * pca.axes[pairs[q][1]][k]) / sqrt(2.0);
                nd++;
            }
        for (int s1 = -1; s1 <= 1; s1 += 2)
            for (int s2 = -1; s2 <= 1; s2 += 2) {
                for (int k = 0; k < 3; k++)
                    dirs[nd][k] = (pca.axes[0][k] + s1 * pca.axes[1][k] + s2 * pca.axes[2][k]) / sqrt(3.0);
                nd++;
            }
    }
    if (ndir > 13) { /* more: a Fibonacci half-sphere in the principal frame */
        int extra = ndir - 13;
        if (extra > BUDGET_MAX_DIRS - 13) extra = BUDGET_MAX_DIRS - 13;
        for (int i = 0; i < extra; i++) {
            double z = 1 - (i + 0.5) / extra, r = sqrt(fmax(0, 1 - z * z)), ph = 2.399963229728653 * i;
            double l[3] = {r * cos(ph), r * sin(ph), z};
            for (int k = 0; k < 3; k++)
                dirs[nd][k] = l[0] * pca.axes[0][k] + l[1] * pca.axes[1][k] + l[2] * pca.axes[2][k];
            nd++;
        }
    }
    P->nd = nd;
    memcpy(P->centroid, pca.centroid, sizeof P->centroid);
    P->stride = (m->nvertices + BUDGET_MAX_SCORED - 1) / BUDGET_MAX_SCORED;
    P->tstride = (m->ntriangles + 2 * BUDGET_MAX_SCORED - 1) / (2 * BUDGET_MAX_SCORED);
    if (P->tstride < 1) P->tstride = 1;
    /* points one side can receive: the sampled vertices and two crossings per sampled triangle
     * (three kept for safety) */
    P->cap = (m->nvertices + P->stride - 1) / P->stride + 3 * ((m->ntriangles + P->tstride - 1) / P->tstride) + 1;
    for (int d = 0; d < nd; d++) {
        const double *ax = dirs[d];
        double lo = INFINITY, hi = -INFINITY;
        for (size_t v = 0; v < m->nvertices; v++) {
            const double *p = m->vertices + 3 * v;
            double s = ax[0] * p[0] + ax[1] * p[1] + ax[2] * p[2];
            lo = fmin(lo, s), hi = fmax(hi, s);
        }
        P->bs[d] = INFINITY, P->bc[d] = 0, P->st[d] = (hi - lo) / (BUDGET_OFFSETS + 1);
        P->lo[d] = hi > lo ? lo : NAN;
        P->ord[d] = d;
    }
    P->ok = 1;
}

static double *plan_buffers(const plan *P) { return malloc(2 * 3 * P->cap * sizeof(double)); }

/* Direction d's best of the fixed offsets (touches only P->bs[d], P->bc[d]); 0 when out of memory. */
static int score_dir(const acd_mesh *m, plan *P, int d) {
    if (!(P->lo[d] == P->lo[d])) return 1; /* flat along d */
    double *buf = plan_buffers(P);
    if (!buf) return 0;
    hv_ws hw;
    memset(&hw, 0, sizeof hw);
    for (int i = 1; i <= BUDGET_OFFSETS; i++) {
        double c = P->lo[d] + P->st[d] * i, sc = score_plane(m, P->stride, P->tstride, P->dirs[d], c, buf, buf + 3 * P->cap, &hw);
        if (sc >= 0 && sc < P->bs[d]) P->bs[d] = sc, P->bc[d] = c;
    }
    free(buf);
    hv_ws_free(&hw);
    return 1;
}

/* Direction d's offset refined around its best (touches only P->bs[d], P->bc[d]). */
static int refine_dir(const acd_mesh *m, plan *P, int d) {
    double *buf = plan_buffers(P);
    if (!buf) return 0;
    hv_ws hw;
    memset(&hw, 0, sizeof hw);
    double step = P->st[d];
    for (int r = 0; r < BUDGET_REFINE && P->bs[d] < INFINITY; r++) {
        step *= 0.5;
        double c0 = P->bc[d];
        for (int sg = -1; sg <= 1; sg += 2) {
            double c = c0 + sg * step, sc = score_plane(m, P->stride, P->tstride, P->dirs[d], c, buf, buf + 3 * P->cap, &hw);
            if (sc >= 0 && sc < P->bs[d]) P->bs[d] = sc, P->bc[d] = c;
        }
    }
    free(buf);
    hv_ws_free(&hw);
    return 1;
}

static void sort_dirs(plan *P, int lim) {
    for (int i = 1; i < lim; i++)
        for (int j = i; j > 0 && P->bs[P->ord[j]] < P->bs[P->ord[j - 1]]; j--) {
            int x = P->ord[j];
            P->ord[j] = P->ord[j - 1];
            P->ord[j - 1] = x;
        }
}

/* Up to nmax planes, best first by their sampled score, one per direction (after the refinement of
 * the best nrefine_dirs directions). */
static int plan_planes(const plan *P, int nmax, int nrefine_dirs, acd3_plane_candidate *out) {
    int lim = P->nd < nrefine_dirs ? P->nd : nrefine_dirs;
    int n = 0;
    for (int q = 0; q < lim && n < nmax; q++) {
        int d = P->ord[q];
        if (!(P->bs[d] < INFINITY)) continue;
        const double *ax = P->dirs[d];
        double cc = ax[0] * P->centroid[0] + ax[1] * P->centroid[1] + ax[2] * P->centroid[2];
        for (int k = 0; k < 3; k++) {
            out[n].normal[k] = ax[k];
            out[n].point[k] = P->centroid[k] + (P->bc[d] - cc) * ax[k];
        }
        out[n].kind = "volume";
        n++;
    }
    return n;
}

/* The atom's hull volume and bound (touches only the atom). */
static void prepare(const budget_state *S, size_t i) {
    atom *A = &S->a[i];
    A->st = ACD_OK;
    A->gain = -INFINITY;
    acd_hull H;
    memset(&H, 0, sizeof H);
    A->hvol = hull_volume_of(&A->mesh, &H);
    if (A->hvol < 0) {
        A->st = ACD_ERR_NOMEM;
        return;
    }
    A->ok = 1;
    A->bound = 0;
    {
        if (H.dim == 3) {
            int acc = 0;
            acd_error e;
            A->st = acd3_leaf_test(&A->mesh, &H, S->limit, UINT32_MAX, &acc, &A->bound, &e);
            A->ok = acc;
        }
    }
    acd_hull_free(&H);
}

/* One exact cut of an atom by a candidate plane: its pieces and the sum of their hull volumes. */
typedef struct exact_cut {
    acd_status cs;
    int good;
    double sum;
    acd_cut_plane cp;
    acd_cut_result cr;
} exact_cut;

static void exact_cut_do(const budget_state *S, const atom *A, const acd3_plane_candidate *cand, exact_cut *X) {
    memset(X, 0, sizeof *X);
    X->cs = acd_cut_plane_from_normal(cand->point, cand->normal, S->extent, &X->cp, NULL);
    if (X->cs != ACD_OK) {
        X->cs = ACD_ERR_DEGENERATE; /* skipped, as a failed cut */
        return;
    }
    acd_error ce;
    X->cs = acd_plane_cut_flags(&A->mesh, &X->cp, ACD_PLANE_CUT_DROP_SPECKS, &X->cr, &ce);
    if (X->cs != ACD_OK) return;
    double sum = 0;
    int good = X->cr.npieces >= 2;
    for (size_t p = 0; p < X->cr.npieces && good; p++) {
        double pv = acd_geom3_signed_volume(&X->cr.pieces[p].mesh);
        double hv = hull_volume_of(&X->cr.pieces[p].mesh, NULL);
        if (!(pv > BUDGET_MIN_PIECE_FRACTION * A->vol) || hv < 0) good = 0;
        sum += hv;
    }
    X->good = good;
    X->sum = sum;
}

/* The best splits of a batch of atoms (touches only those atoms): the directions of all of them
 * scored as parallel tasks, then the best directions refined, then the candidates cut exactly; every
 * choice is made in the order of the sequential search, so the result is the same for any thread
 * count. */
static void evaluate_batch(const budget_state *S, const size_t *idx, int nb, int threads) {
    (void)threads;
    plan *P = malloc((size_t)nb * sizeof *P);
    if (!P) {
        for (int j = 0; j < nb; j++) S->a[idx[j]].evaluated = 1, S->a[idx[j]].st = ACD_ERR_NOMEM;
        return;
    }
    int live = 0;
    for (int j = 0; j < nb; j++) {
        atom *A = &S->a[idx[j]];
        A->evaluated = 1;
        P[j].ok = 0, P[j].nd = 0;
        if (A->st == ACD_OK) live = 1;
    }
    if (!live) {
        free(P);
        return;
    }
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nb > 1)
#endif
    for (int j = 0; j < nb; j++)
        if (S->a[idx[j]].st == ACD_OK) plan_init(&S->a[idx[j]].mesh, S->ndir, &P[j]);
    /* tasks: (atom, direction) pairs */
    int ntask = 0, tj[BUDGET_BATCH * BUDGET_MAX_DIRS], td[BUDGET_BATCH * BUDGET_MAX_DIRS];
    for (int j = 0; j < nb; j++)
        for (int d = 0; d < (P[j].ok ? P[j].nd : 0); d++) tj[ntask] = j, td[ntask] = d, ntask++;
    int fail[BUDGET_BATCH] = {0};
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && ntask > 1)
#endif
    for (int t = 0; t < ntask; t++)
        if (!score_dir(&S->a[idx[tj[t]]].mesh, &P[tj[t]], td[t])) {
#ifdef _OPENMP
#pragma omp atomic write
#endif
            fail[tj[t]] = 1;
        }
    ntask = 0;
    for (int j = 0; j < nb; j++) {
        if (!P[j].ok) continue;
        sort_dirs(&P[j], P[j].nd);
        for (int q = 0; q < P[j].nd && q < BUDGET_REFINE_DIRS; q++) tj[ntask] = j, td[ntask] = P[j].ord[q], ntask++;
    }
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && ntask > 1)
#endif
    for (int t = 0; t < ntask; t++)
        if (!refine_dir(&S->a[idx[tj[t]]].mesh, &P[tj[t]], td[t])) {
#ifdef _OPENMP
#pragma omp atomic write
#endif
            fail[tj[t]] = 1;
        }
    acd3_plane_candidate cand[BUDGET_BATCH][BUDGET_EXACT];
    int nc[BUDGET_BATCH] = {0};
    ntask = 0;
    for (int j = 0; j < nb; j++) {
        if (!P[j].ok) continue;
        if (fail[j]) {
            S->a[idx[j]].st = ACD_ERR_NOMEM;
            continue;
        }
        int lim = P[j].nd < BUDGET_REFINE_DIRS ? P[j].nd : BUDGET_REFINE_DIRS;
        sort_dirs(&P[j], lim);
        nc[j] = plan_planes(&P[j], S->nexact, BUDGET_REFINE_DIRS, cand[j]);
        for (int k = 0; k < nc[j]; k++) tj[ntask] = j, td[ntask] = k, ntask++;
    }
    free(P);
    exact_cut X[BUDGET_BATCH][BUDGET_EXACT];
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && ntask > 1)
#endif
    for (int t = 0; t < ntask; t++) exact_cut_do(S, &S->a[idx[tj[t]]], &cand[tj[t]][td[t]], &X[tj[t]][td[t]]);
    for (int j = 0; j < nb; j++) {
        atom *A = &S->a[idx[j]];
        double best = INFINITY;
        for (int k = 0; k < nc[j]; k++) {
            exact_cut *x = &X[j][k];
            if (x->cs != ACD_OK) {
                if (x->cs == ACD_ERR_NOMEM) A->st = x->cs;
                continue;
            }
            if (x->good && x->sum < best) {
                best = x->sum;
                acd_cut_result_free(&A->cut);
                A->cut = x->cr;
                memcpy(A->plane, x->cp.normal, sizeof(double[3]));
                A->plane[3] = -(x->cp.normal[0] * x->cp.a[0] + x->cp.normal[1] * x->cp.a[1] + x->cp.normal[2] * x->cp.a[2]);
            } else
                acd_cut_result_free(&x->cr);
        }
        if (isfinite(best) && A->st == ACD_OK) A->gain = A->hvol - best;
    }
}

static void prepare_range(const budget_state *S, size_t b0, size_t b1, int threads) {
    (void)threads;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && b1 - b0 > 1)
#endif
    for (long j = (long)b0; j < (long)b1; j++) prepare(S, (size_t)j);
}

double acd3_budget_hull_volume(const double *pts, size_t n, int *fallback) {
    hv_ws w;
    memset(&w, 0, sizeof w);
    double v = hull_volume_qh(pts, n, &w);
    hv_ws_free(&w);
    if (fallback) *fallback = v == -2;
    return v == -2 ? hull_volume_pts(pts, n) : v;
}

void acd3_budget_result_free(acd3_budget_result *r) {
    if (!r) return;
    for (size_t k = 0; k < r->nnew; k++) acd_mesh_free(&r->new_parts[k]);
    free(r->new_parts);
    free(r->new_parent);
    free(r->new_plane);
    free(r->new_volume);
    free(r->new_bound);
    memset(r, 0, sizeof *r);
}

acd_status acd3_budget_split(const acd_mesh *parts, size_t nparts, size_t budget, double limit,
                             double min_gain, double extent, int threads, acd3_budget_result *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    budget_state S = {0};
    S.nparts = nparts;
    S.limit = limit;
    S.extent = extent;
    S.ndir = BUDGET_DIRS;
    S.nexact = BUDGET_EXACT;
    S.cap = 2 * nparts + 16;
    S.a = calloc(S.cap, sizeof *S.a);
    if (!S.a) return acd_fail(err, ACD_ERR_NOMEM, "budget: out of memory");
    acd_status st = ACD_OK;
    for (size_t i = 0; i < nparts; i++) {
        S.a[i].mesh = parts[i];
        S.a[i].vol = acd_geom3_signed_volume(&parts[i]);
        S.a[i].alive = 1;
    }
    S.n = nparts;
    prepare_range(&S, 0, nparts, threads);
    size_t nalive = nparts;
    for (;;) {
        for (size_t i = 0; i < S.n && st == ACD_OK; i++)
            if (S.a[i].st != ACD_OK) st = acd_fail(err, S.a[i].st, "budget: out of memory");
        if (st != ACD_OK) break;
        /* the next cut: while under the budget, the largest saving above min_gain; an atom not
         * evaluated yet may save at most its excess (hull volume less volume: each piece's hull
         * holds the piece), so those whose excess reaches the best saving found are evaluated
         * first (largest excess first, BUDGET_BATCH at a time in parallel; the choice is the same
         * as evaluating all). Then, the budget spent, a part above the limit (largest saving). */
        size_t pick = SIZE_MAX, batch[BUDGET_BATCH];
        int nb = 0;
        for (int phase = 0; phase < 2 && pick == SIZE_MAX && nb == 0; phase++) {
            if (phase == 0 && nalive >= budget) continue;
            for (size_t i = 0; i < S.n; i++) {
                const atom *A = &S.a[i];
                if (!A->alive || !A->evaluated || A->cut.npieces < 2) continue;
                if (phase == 0 ? !(A->gain > min_gain) : A->ok) continue;
                if (pick == SIZE_MAX || A->gain > S.a[pick].gain) pick = i;
            }
            double floor = pick == SIZE_MAX ? (phase == 0 ? min_gain : -INFINITY) : S.a[pick].gain;
            for (size_t i = 0; i < S.n; i++) { /* the unevaluated candidates of largest excess */
                const atom *A = &S.a[i];
                if (!A->alive || A->evaluated || (phase == 1 && A->ok)) continue;
                double ex = A->hvol - A->vol;
                if (phase == 0 && !(ex >= floor)) continue;
                int at = nb < BUDGET_BATCH ? nb++ : BUDGET_BATCH;
                while (at > 0) {
                    const atom *B = &S.a[batch[at - 1]];
                    if (B->hvol - B->vol >= ex) break;
                    if (at < BUDGET_BATCH) batch[at] = batch[at - 1];
                    at--;
                }
                if (at < BUDGET_BATCH) batch[at] = i;
            }
        }
        if (nb > 0) {
            pick = SIZE_MAX;
            evaluate_batch(&S, batch, nb, threads);
            continue;
        }
        if (pick == SIZE_MAX) break;
        size_t np = S.a[pick].cut.npieces;
        if (S.n + np > BUDGET_MAX_ATOMS) break;
        if (S.n + np > S.cap) {
            size_t nc = 2 * S.cap + np;
            atom *na = realloc(S.a, nc * sizeof *na);
            if (!na) {
                st = acd_fail(err, ACD_ERR_NOMEM, "budget: out of memory");
                break;
            }
            memset(na + S.cap, 0, (nc - S.cap) * sizeof *na);
            S.a = na;
            S.cap = nc;
        }
        atom *P = &S.a[pick];
        size_t b0 = S.n;
        for (size_t p = 0; p < np; p++) {
            atom *A = &S.a[S.n++];
            A->mesh = P->cut.pieces[p].mesh;
            memset(&P->cut.pieces[p].mesh, 0, sizeof A->mesh);
            A->vol = acd_geom3_signed_volume(&A->mesh);
            A->alive = 1;
            A->parent = pick;
        }
        acd_cut_result_free(&P->cut);
        P->alive = 0;
        nalive += np - 1;
        out->cuts++;
        prepare_range(&S, b0, S.n, threads);
    }
    /* the pieces out; the atoms' cached splits freed */
    size_t nnew = S.n - nparts;
    if (st == ACD_OK && nnew) {
        out->new_parts = calloc(nnew, sizeof *out->new_parts);
        out->new_parent = malloc(nnew * sizeof *out->new_parent);
        out->new_plane = malloc(nnew * sizeof *out->new_plane);
        out->new_volume = malloc(nnew * sizeof *out->new_volume);
        out->new_bound = malloc(nnew * sizeof *out->new_bound);
        if (!out->new_parts || !out->new_parent || !out->new_plane || !out->new_volume || !out->new_bound)
            st = acd_fail(err, ACD_ERR_NOMEM, "budget: out of memory");
    }
    if (st == ACD_OK) {
        /* parents: recorded as the cut order made them (each cut's pieces consecutive) */
        size_t k = 0;
        out->nnew = nnew;
        out->nalive = nalive;
        for (size_t i = nparts; i < S.n; i++, k++) {
            out->new_parts[k] = S.a[i].mesh;
            memset(&S.a[i].mesh, 0, sizeof S.a[i].mesh);
            out->new_volume[k] = S.a[i].vol;
            out->new_bound[k] = S.a[i].bound;
            out->new_parent[k] = (uint32_t)S.a[i].parent;
            memcpy(out->new_plane[k], S.a[S.a[i].parent].plane, sizeof out->new_plane[k]);
        }
        for (size_t i = 0; i < S.n; i++) {
            out->over += S.a[i].alive && !S.a[i].ok;
            out->hull_volume += S.a[i].alive ? S.a[i].hvol : 0;
        }
    }
    for (size_t i = 0; i < S.n; i++) {
        acd_cut_result_free(&S.a[i].cut);
        if (i >= nparts) acd_mesh_free(&S.a[i].mesh);
    }
    free(S.a);
    if (st != ACD_OK) acd3_budget_result_free(out);
    return st;
}
