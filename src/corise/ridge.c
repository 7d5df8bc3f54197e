/* corise/ridge: greedy convex-ridge clustering, CoRiSe §4.1, Eq. 2; spec corise.md §2.4. */
#include "corise/ridge.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/union_find.h"

size_t acd_corise_hull_index(const acd_corise_bridges *b, uint32_t v) {
    size_t lo = 0, hi = b->nhull;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (b->hull_vertex[mid] < v)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < b->nhull && b->hull_vertex[lo] == v ? lo : SIZE_MAX;
}

void acd_corise_ridges_free(acd_corise_ridges *r) {
    if (!r) return;
    free(r->ridge_of);
    memset(r, 0, sizeof *r);
}

typedef struct low_item {
    double length;
    size_t bridge;
} low_item;

static int cmp_low(const void *x, const void *y) {
    const low_item *p = x, *q = y;
    if (p->length != q->length) return p->length < q->length ? -1 : 1;
    return (p->bridge > q->bridge) - (p->bridge < q->bridge);
}

acd_status acd_corise_ridges_compute(const acd_corise_bridges *b, double tau, acd_corise_ridges *out, acd_error *err) {
    if (!b || !out) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "corise: NULL argument");
    memset(out, 0, sizeof *out);
    if (!isfinite(tau) || tau < 0) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "corise: tau %g must be finite, >= 0", tau);
    size_t nh = b->nhull, nb = b->nbridges;
    size_t *parent = malloc((nh ? nh : 1) * sizeof *parent);
    size_t *ends = malloc((2 * nb + 1) * sizeof *ends); /* hull indices of each bridge's ends */
    low_item *low = malloc((nb ? nb : 1) * sizeof *low);
    size_t *high = malloc((nb ? nb : 1) * sizeof *high);
    out->ridge_of = malloc((nh ? nh : 1) * sizeof *out->ridge_of);
    if (!parent || !ends || !low || !high || !out->ridge_of) {
        free(parent);
        free(ends);
        free(low);
        free(high);
        acd_corise_ridges_free(out);
        return acd_fail(err, ACD_ERR_NOMEM, "corise: out of memory clustering %zu hull vertices", nh);
    }
    for (size_t i = 0; i < nh; i++) parent[i] = i;
    size_t nlow = 0, nhigh = 0;
    acd_status st = ACD_OK;
    for (size_t i = 0; i < nb; i++) {
        const acd_corise_bridge *br = &b->bridge[i];
        ends[2 * i] = acd_corise_hull_index(b, br->a);
        ends[2 * i + 1] = acd_corise_hull_index(b, br->b);
        if (ends[2 * i] == SIZE_MAX || ends[2 * i + 1] == SIZE_MAX) {
            st = acd_fail(err, ACD_ERR_INTERNAL, "corise: bridge (%u, %u) ends off the hull", br->a, br->b);
            goto done;
        }
        if (!isfinite(br->length)) continue; /* no valley: neither low nor high */
        if (br->concavity > tau)
            high[nhigh++] = i;
        else
            low[nlow++] = (low_item){br->length, i};
    }
    qsort(low, nlow, sizeof *low, cmp_low);
    for (size_t k = 0; k < nlow; k++) {
        size_t i = low[k].bridge;
        size_t cu = acd_uf_find_z(parent, ends[2 * i]), cw = acd_uf_find_z(parent, ends[2 * i + 1]);
        if (cu == cw) continue;
        int blocked = 0;
        for (size_t h = 0; h < nhigh && !blocked; h++) {
            size_t x = acd_uf_find_z(parent, ends[2 * high[h]]), y = acd_uf_find_z(parent, ends[2 * high[h] + 1]);
            blocked = (x == cu && y == cw) || (x == cw && y == cu);
        }
        if (blocked) continue;
        if (cu < cw)
            parent[cw] = cu;
        else
            parent[cu] = cw;
    }
    /* number the clusters by their smallest member */
    size_t nr = 0;
    for (size_t v = 0; v < nh; v++) out->ridge_of[v] = UINT32_MAX;
    for (size_t v = 0; v < nh; v++) {
        size_t r = acd_uf_find_z(parent, v);
        if (out->ridge_of[r] == UINT32_MAX) out->ridge_of[r] = (uint32_t)nr++;
        out->ridge_of[v] = out->ridge_of[r];
    }
    out->nridges = nr;
    out->nhull = nh;
done:
    free(parent);
    free(ends);
    free(low);
    free(high);
    if (st != ACD_OK) acd_corise_ridges_free(out);
    return st;
}
