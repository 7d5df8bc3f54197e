/* geom2/hull2d: Andrew's monotone chain (IPL 9(5), 1979) with exact orientation tests. */
#include "geom2/hull2d.h"

#include <stdlib.h>

#include "core/predicates.h"

static int turn(const acd_vec2 *pts, size_t a, size_t b, size_t c) {
    const double A[2] = {pts[a].x, pts[a].y}, B[2] = {pts[b].x, pts[b].y}, C[2] = {pts[c].x, pts[c].y};
    return acd_orient2d_sign(A, B, C);
}

static int less_xy(const acd_vec2 *pts, size_t a, size_t b) {
    if (pts[a].x != pts[b].x) return pts[a].x < pts[b].x;
    if (pts[a].y != pts[b].y) return pts[a].y < pts[b].y;
    return a < b;
}

/* Bottom-up merge sort of indices (stable, no global state, no qsort context needed). */
static void sort_indices(const acd_vec2 *pts, size_t *idx, size_t *tmp, size_t n) {
    for (size_t w = 1; w < n; w *= 2) {
        for (size_t lo = 0; lo < n; lo += 2 * w) {
            size_t mid = lo + w < n ? lo + w : n, hi = lo + 2 * w < n ? lo + 2 * w : n;
            size_t i = lo, j = mid, k = lo;
            while (i < mid && j < hi) tmp[k++] = less_xy(pts, idx[j], idx[i]) ? idx[j++] : idx[i++];
            while (i < mid) tmp[k++] = idx[i++];
            while (j < hi) tmp[k++] = idx[j++];
        }
        for (size_t k = 0; k < n; k++) idx[k] = tmp[k];
    }
}

size_t acd_hull2d_indices(const acd_vec2 *pts, size_t n, size_t *out, size_t *scratch) {
    if (n == 0) return 0;
    /* out doubles as the sorted index list, scratch as merge buffer; then build into scratch */
    for (size_t i = 0; i < n; i++) out[i] = i;
    sort_indices(pts, out, scratch, n);
    /* dedupe equal points (keep the first: the smallest index, by the stable order) */
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        if (m > 0 && pts[out[i]].x == pts[out[m - 1]].x && pts[out[i]].y == pts[out[m - 1]].y) continue;
        out[m++] = out[i];
    }
    if (m < 3) {
        for (size_t i = 0; i < m; i++) scratch[i] = out[i];
        for (size_t i = 0; i < m; i++) out[i] = scratch[i];
        return m;
    }
    size_t k = 0;
    size_t *h = scratch; /* up to 2m entries are never needed: lower + upper <= m + 1 */
    for (size_t i = 0; i < m; i++) {
        while (k >= 2 && turn(pts, h[k - 2], h[k - 1], out[i]) <= 0) k--;
        h[k++] = out[i];
    }
    size_t lower = k + 1;
    for (size_t i = m - 1; i-- > 0;) {
        while (k >= lower && turn(pts, h[k - 2], h[k - 1], out[i]) <= 0) k--;
        h[k++] = out[i];
    }
    k--; /* the first point is repeated at the end */
    for (size_t i = 0; i < k; i++) out[i] = h[i];
    return k;
}
