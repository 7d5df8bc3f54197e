/* geom3/sphere: minimum enclosing sphere by Welzl's randomized algorithm (Welzl 1991) with the
 * move-to-front heuristic (Gaertner 1999), on a shuffle with a fixed seed so results are
 * deterministic. Used to normalise models to radius 1 as in Lien's experiments (D Table 4, P Table 1).
 * Points are normalised (bounding-box centre, longest side) first; degenerate support sets
 * (collinear or coplanar within ACD_TOL_REL_DIST) fall back to a smaller support, and the final
 * radius is the farthest distance from the centre, so enclosure always holds. */
#include "geom3/sphere.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/rng.h"
#include "core/tolerance.h"
#include "geom3/vec3.h"

#define SPHERE_SHUFFLE_SEED 0x5748454c5aull
/* a point is outside a trial ball when farther than radius + this (normalised units) */
#define SPHERE_SLACK ACD_TOL_REL_WELD

typedef struct ball {
    double c[3];
    double r; /* < 0: empty */
} ball;

typedef struct mtf_ctx {
    const double *w; /* normalised points */
    uint32_t *next, *prev;
    uint32_t head;
} mtf_ctx;

#define NIL UINT32_MAX

static ball ball_diameter(const double *a, const double *b) {
    ball B;
    for (int k = 0; k < 3; k++) B.c[k] = 0.5 * (a[k] + b[k]);
    B.r = 0.5 * acd_dist3(a, b);
    return B;
}

/* Grows B to contain the support points exactly (floating point). */
static void ball_cover(ball *B, const double *const *s, int k) {
    for (int i = 0; i < k; i++) {
        double d = acd_dist3(B->c, s[i]);
        if (d > B->r) B->r = d;
    }
}

/* Ball of the farthest pair among the support points, grown to cover them all. */
static ball ball_fallback(const double *const *s, int k) {
    int bi = 0, bj = 1;
    double bd = -1;
    for (int i = 0; i < k; i++)
        for (int j = i + 1; j < k; j++) {
            double d = acd_dist3(s[i], s[j]);
            if (d > bd) bd = d, bi = i, bj = j;
        }
    ball B = ball_diameter(s[bi], s[bj]);
    ball_cover(&B, s, k);
    return B;
}

/* Smallest ball with the k <= 4 support points on its boundary. */
static ball ball_support(const double *const *s, int k) {
    ball B;
    if (k == 0) {
        B.c[0] = B.c[1] = B.c[2] = 0;
        B.r = -1;
        return B;
    }
    if (k == 1) {
        memcpy(B.c, s[0], sizeof B.c);
        B.r = 0;
        return B;
    }
    if (k == 2) return ball_diameter(s[0], s[1]);
    double u[3], v[3];
    for (int i = 0; i < 3; i++) {
        u[i] = s[1][i] - s[0][i];
        v[i] = s[2][i] - s[0][i];
    }
    double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2], vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    double tol = ACD_TOL_REL_DIST;
    if (k == 3) {
        if (nn <= tol * tol * uu * vv) return ball_fallback(s, 3);
        /* circumcentre: s0 + (|u|^2 (v x n) + |v|^2 (n x u)) / (2 |n|^2) */
        double vxn[3] = {v[1] * n[2] - v[2] * n[1], v[2] * n[0] - v[0] * n[2], v[0] * n[1] - v[1] * n[0]};
        double nxu[3] = {n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
        for (int i = 0; i < 3; i++) B.c[i] = s[0][i] + (uu * vxn[i] + vv * nxu[i]) / (2 * nn);
        B.r = 0;
        ball_cover(&B, s, 3);
        return B;
    }
    /* k == 4: solve 2 [u; v; t] x = [|u|^2; |v|^2; |t|^2] by Cramer's rule */
    double t[3];
    for (int i = 0; i < 3; i++) t[i] = s[3][i] - s[0][i];
    double tt = t[0] * t[0] + t[1] * t[1] + t[2] * t[2];
    double det = 2 * (t[0] * n[0] + t[1] * n[1] + t[2] * n[2]); /* 2 t . (u x v) */
    if (fabs(det) <= 2 * tol * sqrt(uu * vv * tt)) { /* coplanar support: best of the triples */
        ball best;
        best.r = -1;
        for (int skip = 0; skip < 4; skip++) {
            const double *q[3];
            int m = 0;
            for (int i = 0; i < 4; i++)
                if (i != skip) q[m++] = s[i];
            ball C = ball_support(q, 3);
            if (acd_dist3(C.c, s[skip]) <= C.r + SPHERE_SLACK && (best.r < 0 || C.r < best.r)) best = C;
        }
        if (best.r < 0) best = ball_fallback(s, 4);
        ball_cover(&best, s, 4);
        return best;
    }
    double uxv[3] = {n[0], n[1], n[2]};
    double vxt[3] = {v[1] * t[2] - v[2] * t[1], v[2] * t[0] - v[0] * t[2], v[0] * t[1] - v[1] * t[0]};
    double txu[3] = {t[1] * u[2] - t[2] * u[1], t[2] * u[0] - t[0] * u[2], t[0] * u[1] - t[1] * u[0]};
    /* x = (|u|^2 (v x t) + |v|^2 (t x u) + |t|^2 (u x v)) / (2 u . (v x t)) */
    double den = 2 * (u[0] * vxt[0] + u[1] * vxt[1] + u[2] * vxt[2]);
    for (int i = 0; i < 3; i++) B.c[i] = s[0][i] + (uu * vxt[i] + vv * txu[i] + tt * uxv[i]) / den;
    B.r = 0;
    ball_cover(&B, s, 4);
    return B;
}

static void move_to_front(mtf_ctx *x, uint32_t i) {
    if (x->head == i) return;
    uint32_t p = x->prev[i], q = x->next[i];
    if (p != NIL) x->next[p] = q;
    if (q != NIL) x->prev[q] = p;
    x->prev[i] = NIL;
    x->next[i] = x->head;
    x->prev[x->head] = i;
    x->head = i;
}

/* Smallest ball of the list prefix before node end with the k support points on the boundary. */
static ball mtf_ball(mtf_ctx *x, uint32_t end, const double **s, int k) {
    ball B = ball_support(s, k);
    if (k == 4) return B;
    uint32_t i = x->head;
    while (i != end && i != NIL) {
        uint32_t nx = x->next[i];
        const double *p = x->w + 3 * (size_t)i;
        if (B.r < 0 || acd_dist3(B.c, p) > B.r + SPHERE_SLACK) {
            s[k] = p;
            B = mtf_ball(x, i, s, k + 1);
            move_to_front(x, i);
        }
        i = nx;
    }
    return B;
}

acd_status acd_min_sphere(const double *points, size_t n, acd_sphere *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    if (n == 0) return acd_fail(err, ACD_ERR_DEGENERATE, "minimum sphere: no points");
    if (n >= UINT32_MAX) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "minimum sphere: %zu points too many", n);
    double lo[3], hi[3];
    for (size_t i = 0; i < n; i++) {
        const double *p = points + 3 * i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "minimum sphere: point %zu has a non-finite coordinate (%g, %g, %g)",
                            i, p[0], p[1], p[2]);
        for (int k = 0; k < 3; k++) {
            if (i == 0 || p[k] < lo[k]) lo[k] = p[k];
            if (i == 0 || p[k] > hi[k]) hi[k] = p[k];
        }
    }
    double c0[3], sc = 0;
    for (int k = 0; k < 3; k++) {
        double side = hi[k] - lo[k];
        if (!isfinite(side))
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "minimum sphere: coordinate range along axis %d overflows", k);
        if (side > sc) sc = side;
        c0[k] = lo[k] + 0.5 * side;
    }
    if (sc == 0) {
        memcpy(out->center, points, sizeof out->center);
        out->radius = 0;
        return ACD_OK;
    }
    double *w = malloc(3 * n * sizeof *w);
    mtf_ctx x = {w, malloc(n * sizeof(uint32_t)), malloc(n * sizeof(uint32_t)), 0};
    uint32_t *perm = malloc(n * sizeof *perm);
    if (!w || !x.next || !x.prev || !perm) {
        free(w);
        free(x.next);
        free(x.prev);
        free(perm);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for the minimum sphere of %zu points", n);
    }
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) w[3 * i + k] = (points[3 * i + k] - c0[k]) / sc;
    acd_rng rng;
    acd_rng_seed(&rng, SPHERE_SHUFFLE_SEED);
    for (size_t i = 0; i < n; i++) perm[i] = (uint32_t)i;
    for (size_t i = n - 1; i > 0; i--) { /* Fisher-Yates */
        size_t j = (size_t)acd_rng_below(&rng, i + 1);
        uint32_t t = perm[i];
        perm[i] = perm[j];
        perm[j] = t;
    }
    x.head = perm[0];
    for (size_t i = 0; i < n; i++) {
        x.prev[perm[i]] = i > 0 ? perm[i - 1] : NIL;
        x.next[perm[i]] = i + 1 < n ? perm[i + 1] : NIL;
    }
    const double *s[4];
    ball B = mtf_ball(&x, NIL, s, 0);
    /* back to input coordinates; the radius is the farthest point, so enclosure holds exactly */
    for (int k = 0; k < 3; k++) out->center[k] = c0[k] + B.c[k] * sc;
    double r = 0;
    for (size_t i = 0; i < n; i++) {
        const double *p = points + 3 * i;
        double d[3] = {(p[0] - out->center[0]) / sc, (p[1] - out->center[1]) / sc, (p[2] - out->center[2]) / sc};
        double di = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (di > r) r = di;
    }
    out->radius = r * sc;
    free(w);
    free(x.next);
    free(x.prev);
    free(perm);
    return ACD_OK;
}
