/* acd2/pocket: bridges and pockets (Lien dissertation III.B.2, Fig. 12, Obs. B.3) and the
 * per-vertex concavity of a ring under SL, SP, H1 or H2 (IV.A.1.a-c, Algs. 2-4).
 *
 * design:
 *  1. hull of the ring's points (monotone chain, exact), listed in ring order;
 *  2. every pair of ring-consecutive hull vertices (a, b) with b != next(a) is a bridge, its
 *     pocket the chain strictly between them;
 *  3. each pocket is measured (SL, SP, or a hybrid choosing between them per pocket);
 *  4. the witness is the notch of largest concavity (spec §11 A3). */
#include "acd2/pocket.h"

#include <stdlib.h>

#include "acd2/concavity_sl.h"
#include "acd2/hybrid.h"
#include "acd2/ring.h"
#include "geom2/hull2d.h"

int acd2_work_reserve(acd2_work *w, size_t n) {
    if (n <= w->cap) return 0;
    size_t nc = w->cap ? w->cap : 16;
    while (nc < n) nc *= 2;
    size_t *h = realloc(w->hull, (nc + 1) * sizeof *h);
    if (!h) return -1;
    w->hull = h;
    size_t *s = realloc(w->scratch, (nc + 1) * sizeof *s);
    if (!s) return -1;
    w->scratch = s;
    w->cap = nc;
    return 0;
}

void acd2_work_free(acd2_work *w) {
    free(w->hull);
    free(w->scratch);
    acd2_sp_work_free(&w->sp);
    w->hull = w->scratch = NULL;
    w->cap = 0;
}

size_t acd2_ring_hull(const acd_vec2 *p, size_t n, acd2_work *w) {
    size_t nh = acd_hull2d_indices(p, n, w->hull, w->scratch);
    if (nh < 3) return nh;
    /* rotate so the smallest ring index comes first; a simple ring visits its hull vertices in
     * counterclockwise order, so the list is then increasing */
    size_t m = 0;
    for (size_t i = 1; i < nh; i++)
        if (w->hull[i] < w->hull[m]) m = i;
    for (size_t i = 0; i < nh; i++) w->scratch[i] = w->hull[(m + i) % nh];
    int sorted = 1;
    for (size_t i = 0; i < nh; i++) {
        w->hull[i] = w->scratch[i];
        if (i && w->hull[i] <= w->hull[i - 1]) sorted = 0;
    }
    if (!sorted) { /* weakly simple ring: fall back to ring order (insertion sort, rare) */
        for (size_t i = 1; i < nh; i++) {
            size_t v = w->hull[i], j = i;
            while (j > 0 && w->hull[j - 1] > v) { w->hull[j] = w->hull[j - 1]; j--; }
            w->hull[j] = v;
        }
    }
    /* pocket vertices lying on their bridge (collinear points of the hull boundary, dropped by
     * the strict hull) are hull points too: they pinch the pocket polygon, so the pocket is split
     * there (their concavity is 0 under every measure either way) */
    size_t m2 = 0;
    for (size_t h = 0; h < nh; h++) {
        size_t a = w->hull[h], b = w->hull[(h + 1) % nh];
        w->scratch[m2++] = a;
        if (acd2_next(a, n) == b) continue;
        for (size_t k = acd2_next(a, n); k != b; k = acd2_next(k, n))
            if (acd2_orient_sign(p[a], p[b], p[k]) == 0 && acd2_between(p[a], p[b], p[k], 0) &&
                !acd2_same(p[k], p[w->scratch[m2 - 1]]))
                w->scratch[m2++] = k;
    }
    for (size_t i = 0; i < m2; i++) w->hull[i] = w->scratch[i];
    return m2;
}

static double pocket_max(const double *conc, size_t n, size_t a, size_t b) {
    double m = 0;
    for (size_t k = acd2_next(a, n); k != b; k = acd2_next(k, n))
        if (conc[k] > m) m = conc[k];
    return m;
}

acd_status acd2_measure_ring(const acd_vec2 *p, const int64_t *ids, size_t n, const acd2_measure_opts *o,
                             acd2_work *w, double *conc, size_t *witness, double *value, const int64_t *cache_be,
                             const double *cache_c, int64_t *out_be) {
    *witness = SIZE_MAX;
    *value = 0;
    for (size_t k = 0; k < n; k++) conc[k] = 0;
    if (out_be)
        for (size_t k = 0; k < n; k++) out_be[k] = -1;
    if (n < 3) return ACD_OK;
    if (acd2_work_reserve(w, n)) return ACD_ERR_NOMEM;
    size_t nh = acd2_ring_hull(p, n, w);
    if (nh < 3) return ACD_OK;
    for (size_t h = 0; h < nh; h++) {
        size_t a = w->hull[h], b = w->hull[(h + 1) % nh];
        if (acd2_next(a, n) == b) continue;
        if (out_be) out_be[a] = ids[b];
        if (cache_be && cache_c && a < b && cache_be[a] == ids[b]) {
            for (size_t k = a + 1; k < b; k++) conc[k] = cache_c[k];
            continue;
        }
        acd_status st = ACD_OK;
        switch (o->measure) {
        case ACD2D_MEASURE_SL: acd2_sl_pocket(p, n, a, b, conc); break;
        case ACD2D_MEASURE_SP: st = acd2_sp_pocket(p, n, a, b, conc, &w->sp); break;
        case ACD2D_MEASURE_H1:
            if (acd2_pocket_hazard(p, n, a, b)) st = acd2_sp_pocket(p, n, a, b, conc, &w->sp);
            else acd2_sl_pocket(p, n, a, b, conc);
            break;
        case ACD2D_MEASURE_H2:
            acd2_sl_pocket(p, n, a, b, conc);
            if (pocket_max(conc, n, a, b) <= o->tau && acd2_pocket_hazard(p, n, a, b))
                st = acd2_sp_pocket(p, n, a, b, conc, &w->sp);
            break;
        }
        if (st != ACD_OK) return st;
    }
    for (size_t k = 0; k < n; k++) {
        if (conc[k] <= 0) continue;
        if (!acd2_is_notch(p[acd2_prev(k, n)], p[k], p[acd2_next(k, n)], o->notch_tol)) continue;
        if (*witness == SIZE_MAX || conc[k] > *value || (conc[k] == *value && ids[k] < ids[*witness])) {
            *witness = k;
            *value = conc[k];
        }
    }
    return ACD_OK;
}
