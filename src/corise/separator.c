/* corise/separator: valley separators by residual concavity, CoRiSe §4.2 Eq. 3, §4.3, §5.1;
 * spec corise.md §2.5. */
#include "corise/separator.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "corise/valley.h"

static acd_status piece(const double *V, const uint32_t *chain, size_t s, size_t t, double *c, acd_error *err) {
    return acd_corise_chain_concavity(V, chain + s, t - s + 1, NULL, c, NULL, NULL, err);
}

/* better candidate m over best: smaller value, then larger original concavity, then smaller m */
static int better(double val, double corig, size_t m, double bval, double bcorig, size_t bm) {
    if (val != bval) return val < bval;
    if (corig != bcorig) return corig > bcorig;
    return m < bm;
}

/* argmin over lo < m < hi of max(C(V[lo..m]), C(V[m..hi])); lo + 1 < hi required. */
static acd_status best_split(const double *V, const uint32_t *chain, size_t lo, size_t hi, const double *corig,
                             size_t *arg, double *value, acd_error *err) {
    size_t bm = SIZE_MAX;
    double bv = INFINITY;
    for (size_t m = lo + 1; m < hi; m++) {
        double p, s;
        acd_status st = piece(V, chain, lo, m, &p, err);
        if (st == ACD_OK) st = piece(V, chain, m, hi, &s, err);
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
    double *corig = malloc(n * sizeof *corig), *P = malloc(n * sizeof *P), *S = malloc(n * sizeof *S);
    acd_status st = ACD_OK;
    if (!corig || !P || !S) {
        st = acd_fail(err, ACD_ERR_NOMEM, "corise: out of memory splitting a valley of %zu vertices", n);
        goto done;
    }
    if ((st = acd_corise_chain_concavity(vertices, chain, n, corig, NULL, NULL, NULL, err)) != ACD_OK) goto done;
    size_t argrc = SIZE_MAX, argmax = SIZE_MAX;
    double minrc = INFINITY;
    for (size_t m = 1; m + 1 < n; m++)
        if (argmax == SIZE_MAX || corig[m] > corig[argmax]) argmax = m;
    /* shortcut, same result: when the deepest vertex already leaves both pieces shallow, min RC <= tau
       (V-shaped) and the separator is that vertex, so the other RC values are not needed */
    {
        double ps, ss;
        if ((st = piece(vertices, chain, 0, argmax, &ps, err)) != ACD_OK) goto done;
        if ((st = piece(vertices, chain, argmax, n - 1, &ss, err)) != ACD_OK) goto done;
        double rcs = ps > ss ? ps : ss;
        if (rcs <= tau) {
            out->ushaped = 0;
            out->first = out->second = argmax;
            out->residual = rcs;
            goto done;
        }
    }
    argmax = SIZE_MAX;
    for (size_t m = 1; m + 1 < n; m++) {
        if ((st = piece(vertices, chain, 0, m, &P[m], err)) != ACD_OK) goto done;
        if ((st = piece(vertices, chain, m, n - 1, &S[m], err)) != ACD_OK) goto done;
        double rc = P[m] > S[m] ? P[m] : S[m];
        if (argrc == SIZE_MAX || better(rc, corig[m], m, minrc, corig[argrc], argrc)) argrc = m, minrc = rc;
        if (argmax == SIZE_MAX || corig[m] > corig[argmax]) argmax = m;
    }
    if (minrc <= tau) { /* V-shaped */
        size_t s = argmax;
        double rcs = P[s] > S[s] ? P[s] : S[s];
        if (rcs > tau) s = argrc, rcs = minrc;
        out->ushaped = 0;
        out->first = out->second = s;
        out->residual = rcs;
        goto done;
    }
    size_t i = 0, j = SIZE_MAX;
    for (size_t m = 1; m + 1 < n; m++) {
        if (P[m] <= tau) i = m;
        if (S[m] <= tau && j == SIZE_MAX) j = m;
    }
    if (i == 0 || j == SIZE_MAX || i >= j) { /* degenerate: one separator at argmin RC */
        out->ushaped = 0;
        out->first = out->second = argrc;
        out->residual = minrc;
        goto done;
    }
    size_t k = i, g = j;
    double vk = P[i], vg = S[j];
    if (i > 1 && (st = best_split(vertices, chain, 0, i, corig, &k, &vk, err)) != ACD_OK) goto done;
    if (j + 2 < n && (st = best_split(vertices, chain, j, n - 1, corig, &g, &vg, err)) != ACD_OK) goto done;
    double pk, sg;
    if ((st = piece(vertices, chain, 0, k, &pk, err)) != ACD_OK) goto done;
    if ((st = piece(vertices, chain, g, n - 1, &sg, err)) != ACD_OK) goto done;
    out->ushaped = 1;
    out->first = k;
    out->second = g;
    out->residual = pk > sg ? pk : sg;
done:
    free(corig);
    free(P);
    free(S);
    return st;
}
