/* corise/separator: valley separators by residual concavity, CoRiSe §4.2 Eq. 3, §4.3, §5.1;
 * spec corise.md §2.5. */
#include "corise/separator.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "corise/valley.h"

/* Concavities of the chain's pieces, computed once each: P[m] = C(V[0..m]), S[m] = C(V[m..n-1])
 * (NAN until computed), and for every piece a cheap certified lower bound
 * (acd_corise_chain_bound) that lets candidates be skipped without changing any result: a piece
 * whose bound, less its slack, is above the value to beat cannot win or tie, and a piece whose
 * bound is exact needs no shortest path. */
typedef struct pieces {
    const double *V;
    const uint32_t *chain;
    size_t n;
    double *P, *S;   /* exact values (NAN: not yet) */
    double *lP, *lS; /* certified lower bounds of P and S */
} pieces;

static acd_status piece(const double *V, const uint32_t *chain, size_t s, size_t t, double *c, acd_error *err) {
    return acd_corise_chain_concavity(V, chain + s, t - s + 1, NULL, c, NULL, NULL, err);
}

/* lower bound of C(V[s..t]) that the exact value is certainly not below; *exact when it is it */
static double piece_bound(const double *V, const uint32_t *chain, size_t s, size_t t, int *exact) {
    double b;
    acd_corise_chain_bound(V, chain + s, t - s + 1, &b, exact);
    return *exact ? b : b * (1 - ACD_CORISE_CHAIN_BOUND_REL);
}

static acd_status get_P(pieces *w, size_t m, double *out, acd_error *err) {
    if (isnan(w->P[m])) {
        acd_status st = piece(w->V, w->chain, 0, m, &w->P[m], err);
        if (st != ACD_OK) return st;
    }
    *out = w->P[m];
    return ACD_OK;
}

static acd_status get_S(pieces *w, size_t m, double *out, acd_error *err) {
    if (isnan(w->S[m])) {
        acd_status st = piece(w->V, w->chain, m, w->n - 1, &w->S[m], err);
        if (st != ACD_OK) return st;
    }
    *out = w->S[m];
    return ACD_OK;
}

/* better candidate m over best: smaller value, then larger original concavity, then smaller m */
static int better(double val, double corig, size_t m, double bval, double bcorig, size_t bm) {
    if (val != bval) return val < bval;
    if (corig != bcorig) return corig > bcorig;
    return m < bm;
}

typedef struct cand {
    double lb;
    size_t m;
} cand;

static int cmp_cand(const void *x, const void *y) {
    const cand *p = x, *q = y;
    if (p->lb != q->lb) return p->lb < q->lb ? -1 : 1;
    return (p->m > q->m) - (p->m < q->m);
}

/* argmin over lo < m < hi of max(C(V[lo..m]), C(V[m..hi])) (better() order); lo + 1 < hi
 * required. The pieces starting at 0 and ending at n - 1 are P and S. Candidates are visited by
 * increasing lower bound and the rest skipped once the bound passes the best value: the same
 * argmin and value as evaluating every candidate, since better() is a total order and a skipped
 * candidate's value is strictly larger than the best. cand: scratch of n entries. */
static acd_status best_split(pieces *w, size_t lo, size_t hi, const double *corig, cand *cd, size_t *arg,
                             double *value, acd_error *err) {
    const double *V = w->V;
    const uint32_t *chain = w->chain;
    size_t nc = 0;
    for (size_t m = lo + 1; m < hi; m++) {
        int e1, e2;
        double b1 = lo == 0 ? w->lP[m] : piece_bound(V, chain, lo, m, &e1);
        double b2 = hi == w->n - 1 ? w->lS[m] : piece_bound(V, chain, m, hi, &e2);
        cd[nc++] = (cand){b1 > b2 ? b1 : b2, m};
    }
    qsort(cd, nc, sizeof *cd, cmp_cand);
    size_t bm = SIZE_MAX;
    double bv = INFINITY;
    for (size_t i = 0; i < nc; i++) {
        size_t m = cd[i].m;
        if (bm != SIZE_MAX && cd[i].lb > bv) break; /* every later candidate is worse */
        double p, s;
        acd_status st = lo == 0 ? get_P(w, m, &p, err) : piece(V, chain, lo, m, &p, err);
        if (st != ACD_OK) return st;
        if (bm != SIZE_MAX && p > bv) continue;
        st = hi == w->n - 1 ? get_S(w, m, &s, err) : piece(V, chain, m, hi, &s, err);
        if (st != ACD_OK) return st;
        double v = p > s ? p : s;
        if (bm == SIZE_MAX || better(v, corig[m], m, bv, corig[bm], bm)) bm = m, bv = v;
    }
    *arg = bm;
    *value = bv;
    return ACD_OK;
}

acd_status acd_corise_valley_split(const double *vertices, const uint32_t *chain, size_t n, double tau,
                                   acd_corise_split *out, acd_error *err) {
    if (!vertices || !chain || !out) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "corise: NULL argument");
    memset(out, 0, sizeof *out);
    if (n < 3) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "corise: a valley of %zu vertices cannot be split", n);
    double *corig = malloc(n * sizeof *corig), *buf = malloc(4 * n * sizeof *buf);
    cand *cd = malloc(n * sizeof *cd);
    pieces w = {vertices, chain, n, NULL, NULL, NULL, NULL};
    acd_status st = ACD_OK;
    if (!corig || !buf || !cd) {
        st = acd_fail(err, ACD_ERR_NOMEM, "corise: out of memory splitting a valley of %zu vertices", n);
        goto done;
    }
    w.P = buf;
    w.S = buf + n;
    w.lP = buf + 2 * n;
    w.lS = buf + 3 * n;
    for (size_t m = 0; m < n; m++) w.P[m] = w.S[m] = NAN;
    if ((st = acd_corise_chain_concavity(vertices, chain, n, corig, NULL, NULL, NULL, err)) != ACD_OK) goto done;
    size_t argmax = SIZE_MAX;
    for (size_t m = 1; m + 1 < n; m++)
        if (argmax == SIZE_MAX || corig[m] > corig[argmax]) argmax = m;
    /* shortcut, same result: when the deepest vertex already leaves both pieces shallow, min RC <= tau
       (V-shaped) and the separator is that vertex, so the other RC values are not needed */
    {
        double ps, ss;
        if ((st = get_P(&w, argmax, &ps, err)) != ACD_OK) goto done;
        if ((st = get_S(&w, argmax, &ss, err)) != ACD_OK) goto done;
        double rcs = ps > ss ? ps : ss;
        if (rcs <= tau) {
            out->ushaped = 0;
            out->first = out->second = argmax;
            out->residual = rcs;
            goto done;
        }
        /* else RC(argmax) > tau: a V-shaped valley takes argmin RC below */
    }
    for (size_t m = 1; m + 1 < n; m++) {
        int e;
        w.lP[m] = piece_bound(vertices, chain, 0, m, &e);
        if (e && isnan(w.P[m])) w.P[m] = w.lP[m];
        w.lS[m] = piece_bound(vertices, chain, m, n - 1, &e);
        if (e && isnan(w.S[m])) w.S[m] = w.lS[m];
    }
    /* argmin RC over 0 < m < n - 1 (RC(m) = max(P(m), S(m))) */
    size_t argrc;
    double minrc;
    if ((st = best_split(&w, 0, n - 1, corig, cd, &argrc, &minrc, err)) != ACD_OK) goto done;
    if (minrc <= tau) { /* V-shaped: the deepest vertex's RC is above tau, so the separator is argmin RC */
        out->ushaped = 0;
        out->first = out->second = argrc;
        out->residual = minrc;
        goto done;
    }
    /* U-shaped: i = the largest m with P(m) <= tau, j = the smallest m with S(m) <= tau */
    size_t i = 0, j = SIZE_MAX;
    for (size_t m = n - 2; m >= 1 && i == 0; m--) {
        if (w.lP[m] > tau) continue;
        double v;
        if ((st = get_P(&w, m, &v, err)) != ACD_OK) goto done;
        if (v <= tau) i = m;
    }
    for (size_t m = 1; m + 1 < n && j == SIZE_MAX; m++) {
        if (w.lS[m] > tau) continue;
        double v;
        if ((st = get_S(&w, m, &v, err)) != ACD_OK) goto done;
        if (v <= tau) j = m;
    }
    if (i == 0 || j == SIZE_MAX || i >= j) { /* degenerate: one separator at argmin RC */
        out->ushaped = 0;
        out->first = out->second = argrc;
        out->residual = minrc;
        goto done;
    }
    size_t k = i, g = j;
    double vk, vg;
    if (i > 1 && (st = best_split(&w, 0, i, corig, cd, &k, &vk, err)) != ACD_OK) goto done;
    if (j + 2 < n && (st = best_split(&w, j, n - 1, corig, cd, &g, &vg, err)) != ACD_OK) goto done;
    double pk, sg;
    if ((st = get_P(&w, k, &pk, err)) != ACD_OK) goto done;
    if ((st = get_S(&w, g, &sg, err)) != ACD_OK) goto done;
    out->ushaped = 1;
    out->first = k;
    out->second = g;
    out->residual = pk > sg ? pk : sg;
done:
    free(corig);
    free(buf);
    free(cd);
    return st;
}
