/* geom3/hull_volume: the volume of a point set's convex hull, fast; see hull_volume.h. */
#include "geom3/hull_volume.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"

/* qhull's volume (acd_hull_volume: acd_hull_compute's volume, the same bits, without the hull). */
static double hull_volume_pts(const double *pts, size_t n) {
    double v;
    return acd_hull_volume(pts, n, &v, NULL) == ACD_OK ? v : -1;
}

/* A point within this fraction of the coordinates' scale of a facet's plane counts as inside it; a
 * set this thin (relative to the same scale) has no volume. */
#define HULL_VOLUME_EPS 1e-10
#define HULL_VOLUME_FLAT 1e-8

/* The facets of acd_hull_volume_fast's hull (the workspace's array). */
struct acd_hv_facet {
    double n[3], d;  /* unit outward normal, n.x = d on the plane */
    double fard;
    int head, far;   /* outside set (a list through acd_hull_volume_ws.next) and its farthest point */
    int v[3], nb[3]; /* nb[k]: across edge (v[k], v[k+1]) */
    int alive, mark;
};
typedef struct acd_hv_facet hv_facet;

void acd_hull_volume_ws_free(acd_hull_volume_ws *w) {
    free(w->f), free(w->next), free(w->start), free(w->end), free(w->stack), free(w->vis);
    free(w->pend), free(w->hor), free(w->horf), free(w->horu), free(w->newf), free(w->visl), free(w->pl);
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
    double *pl = nf ? realloc(w->pl, 2 * 4 * c * sizeof *pl) : NULL;
    if (pl) w->pl = pl;
    if (!pl) return 0;
    w->hcap = c;
    return 1;
}

static int hv_new_facet(acd_hull_volume_ws *w, const double *p, int a, int b, int c) {
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

static int hv_assign(acd_hull_volume_ws *w, const double *p, int i, const int *cand, int nc, double eps) {
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

static double hull_volume_qh(const double *p, size_t n, acd_hull_volume_ws *w) {
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
    double eps = HULL_VOLUME_EPS * fmax(scale, ext);
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
        hv_assign(w, p, (int)i, all, 4, eps);
    }
    int iter = 0;
    /* the pending facets: a stack of indices (a facet may be pushed when made) */
    size_t top = 0;
    for (int t = 0; t < 4; t++)
        if (w->f[t].head >= 0) w->pend[top++] = t;
    double vol = -1;
    while (top > 0) {
        int fi = w->pend[--top];
        if (!w->f[fi].alive || w->f[fi].head < 0) continue;
        int pi = w->f[fi].far;
        const double *q = p + 3 * pi;
        iter++;
        /* the visible facets from pi (connected through edges) */
        size_t nv = 0, ns = 0;
        if (!hv_grow_int(&w->visl, &w->vcap, w->nf)) return -1;
        int *visl = w->visl;
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
                if (nh + 1 > w->hcap && !hv_grow_horizon(w, nh + 1)) return -1;
                w->hor[2 * nh] = G->v[e], w->hor[2 * nh + 1] = G->v[(e + 1) % 3], w->horf[nh] = h;
                nh++;
            }
        }
        int *hor = w->hor, *horf = w->horf, *newf = w->newf;
        /* a simple cycle: every vertex starts one horizon edge and ends one */
        int bad = 0;
        for (size_t k = 0; k < nh; k++) {
            if (w->start[hor[2 * k]] >= 0 || w->end[hor[2 * k + 1]] >= 0) bad = 1;
            w->start[hor[2 * k]] = (int)k;
            w->end[hor[2 * k + 1]] = (int)k;
        }
        if (bad || nh < 3) {
            for (size_t k = 0; k < nh; k++) w->start[hor[2 * k]] = w->end[hor[2 * k + 1]] = -1;
            return -2;
        }
        for (size_t k = 0; k < nh; k++) {
            int nfi = hv_new_facet(w, p, hor[2 * k], hor[2 * k + 1], pi);
            if (nfi < 0) return -1;
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
        /* the new facets' planes packed, then the horizon facets' (each once, in their first order:
         * the same first match as testing them all in order) */
        double *pl = w->pl;
        for (size_t k = 0; k < nh; k++) {
            const hv_facet *F = &w->f[newf[k]];
            pl[4 * k] = F->n[0], pl[4 * k + 1] = F->n[1], pl[4 * k + 2] = F->n[2], pl[4 * k + 3] = F->d;
        }
        int *horu = w->horu;
        size_t nu = 0;
        for (size_t k = 0; k < nh; k++) {
            int h = horf[k];
            if (w->vis[h] == -iter) continue;
            w->vis[h] = -iter;
            const hv_facet *F = &w->f[h];
            double *r = pl + 4 * (nh + nu);
            r[0] = F->n[0], r[1] = F->n[1], r[2] = F->n[2], r[3] = F->d;
            horu[nu++] = h;
        }
        /* the visible facets' outside points to the new facets; not above a new facet, a point may
         * still be above a horizon facet */
        for (size_t k = 0; k < nv; k++) {
            hv_facet *G = &w->f[visl[k]];
            G->alive = 0;
            for (int i = G->head; i >= 0;) {
                int nx = w->next[i];
                if (i != pi) {
                    const double *x = p + 3 * i;
                    size_t j = 0, nt = nh + nu;
                    double dd = 0;
                    for (; j < nt; j++) {
                        const double *r = pl + 4 * j;
                        dd = r[0] * x[0] + r[1] * x[1] + r[2] * x[2] - r[3];
                        if (dd > eps) break;
                    }
                    if (j < nt) {
                        hv_facet *F = &w->f[j < nh ? newf[j] : horu[j - nh]];
                        w->next[i] = F->head;
                        F->head = i;
                        if (dd > F->fard) F->fard = dd, F->far = i;
                    }
                }
                i = nx;
            }
            G->head = -1;
        }
        if (top + 2 * nh > w->pendcap && !hv_grow_int(&w->pend, &w->pendcap, top + 2 * nh)) return -1;
        for (size_t k = 0; k < nh; k++) {
            if (w->f[newf[k]].head >= 0) w->pend[top++] = newf[k];
            if (w->f[horf[k]].head >= 0) w->pend[top++] = horf[k];
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
    return vol;
}

double acd_hull_volume_fast(const double *pts, size_t n, acd_hull_volume_ws *w, int *fallback) {
    double v = hull_volume_qh(pts, n, w);
    if (fallback) *fallback = v == -2;
    return v == -2 ? hull_volume_pts(pts, n) : v;
}
