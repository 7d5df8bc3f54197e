/* corise/edgesort: (lo, hi, face) records sorted by radix or qsort (edgesort.h). */
#include "corise/edgesort.h"

#include <stdlib.h>
#include <string.h>

int acd_corise_ef_cmp(const void *x, const void *y) {
    const acd_corise_ef *p = x, *q = y;
    if (p->lo != q->lo) return p->lo < q->lo ? -1 : 1;
    if (p->hi != q->hi) return p->hi < q->hi ? -1 : 1;
    return (p->face > q->face) - (p->face < q->face);
}

static uint32_t digit(const acd_corise_ef *r, int pass) {
    /* passes from the least significant: face low, face high, hi low, hi high, lo low, lo high */
    uint32_t v = pass < 2 ? r->face : pass < 4 ? r->hi : r->lo;
    return (pass & 1) ? v >> 16 : v & 0xffffu;
}

int acd_corise_ef_sort(acd_corise_ef *e, size_t n) {
    if (n < ACD_CORISE_EDGESORT_RADIX_MIN) {
        qsort(e, n, sizeof *e, acd_corise_ef_cmp);
        return 1;
    }
    acd_corise_ef *tmp = malloc(n * sizeof *tmp);
    size_t *count = malloc(65537 * sizeof *count);
    if (!tmp || !count) {
        free(tmp);
        free(count);
        return 0;
    }
    /* records made in facet order (every caller's): faces non-decreasing along the array, so a
       stable sort by (lo, hi) alone leaves the ties in face order, the order the full key gives;
       the two face passes are skipped (a third of the sort) */
    int pass0 = 2;
    for (size_t i = 1; i < n && pass0; i++)
        if (e[i].face < e[i - 1].face) pass0 = 0;
    acd_corise_ef *src = e, *dst = tmp;
    for (int pass = pass0; pass < 6; pass++) {
        memset(count, 0, 65537 * sizeof *count);
        for (size_t i = 0; i < n; i++) count[digit(&src[i], pass) + 1]++;
        if (count[digit(&src[0], pass) + 1] == n) continue; /* one value: the order stands */
        for (size_t d = 0; d < 65536; d++) count[d + 1] += count[d];
        for (size_t i = 0; i < n; i++) dst[count[digit(&src[i], pass)]++] = src[i]; /* stable */
        acd_corise_ef *t = src;
        src = dst;
        dst = t;
    }
    if (src != e) memcpy(e, src, n * sizeof *e);
    free(tmp);
    free(count);
    return 1;
}
