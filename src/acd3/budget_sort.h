/* acd3/budget_sort: the budget pass's sorts (acd3/budget: the sampled vertices along a direction,
 * a section's crossings in its plane's frame): stable merge sorts inlined per element type, and a
 * bucket pass before them that gives the same order (tests/test_acd3_budget_sort.c checks both
 * against a reference sort). Header only: each includer gets its own static inline copies. */
#ifndef ACD_ACD3_BUDGET_SORT_H
#define ACD_ACD3_BUDGET_SORT_H

#include <math.h>
#include <stddef.h>
#include <string.h>

/* A stable merge sort of TYPE arrays by LESS, inlined rather than qsort's callback: NAME(a, n, tmp)
 * sorts a[0..n) through tmp (room for n): runs of 8 by insertion, then bottom-up merges (an element
 * of the right run goes first only when LESS than the left's). Stable: the arrays sorted here hold
 * their input positions (i = 0, 1, ...), so LESS need not compare them: the result is the order
 * by key, then position, which any sort by a strict total order gives. */
#define BUDGET_MERGE_SORT(NAME, TYPE, LESS)                                                                    \
    static inline void NAME(TYPE *a, size_t n, TYPE *tmp) {                                                          \
        for (size_t r = 0; r < n; r += 8) {                                                                   \
            size_t e = r + 8 < n ? r + 8 : n;                                                                 \
            for (size_t i = r + 1; i < e; i++) {                                                              \
                TYPE x = a[i];                                                                                \
                size_t j = i;                                                                                 \
                for (; j > r && LESS(&x, &a[j - 1]); j--) a[j] = a[j - 1];                                    \
                a[j] = x;                                                                                     \
            }                                                                                                 \
        }                                                                                                     \
        TYPE *src = a, *dst = tmp;                                                                            \
        for (size_t w = 8; w < n; w *= 2) {                                                                   \
            for (size_t r = 0; r < n; r += 2 * w) {                                                           \
                size_t m = r + w < n ? r + w : n, e = r + 2 * w < n ? r + 2 * w : n, i = r, j = m, k = r;     \
                while (i < m && j < e) { /* without a branch on the data */                               \
                    int t_ = LESS(&src[j], &src[i]);                                                          \
                    const TYPE *s_ = t_ ? &src[j] : &src[i];                                                  \
                    dst[k++] = *s_;                                                                           \
                    j += (size_t)t_, i += (size_t)!t_;                                                        \
                }                                                                                             \
                while (i < m) dst[k++] = src[i++];                                                            \
                while (j < e) dst[k++] = src[j++];                                                            \
            }                                                                                                 \
            TYPE *t = src;                                                                                    \
            src = dst, dst = t;                                                                               \
        }                                                                                                     \
        if (src != a) memcpy(a, src, n * sizeof *a);                                                          \
    }

/* The sampled vertices' order along a direction (by projection, then index). */
typedef struct keyed {
    double key;
    size_t i;
} keyed;
static inline int keyed_less(const keyed *x, const keyed *y) { return x->key < y->key; } /* then i: the sort is stable */
BUDGET_MERGE_SORT(keyed_sort, keyed, keyed_less)

/* A crossing in the plane's own frame, for the section's hull. */
typedef struct xpt {
    double u, v;
    size_t i;
} xpt;
static inline int xpt_less(const xpt *a, const xpt *b) { /* by u, then v, then i (the sort is stable) */
    return (a->u < b->u) | ((a->u == b->u) & (a->v < b->v));
}

/* (qsort's callbacks were 4.5% of a bunny00 budget run) */
BUDGET_MERGE_SORT(xpt_sort, xpt, xpt_less)

/* A bucket pass before those merge sorts: NAME(a, n, tmp, cnt) sorts a[0..n) (its elements in input
 * order, as above) through tmp (room for n) and cnt (room for n + 1) into the order SORT gives. The
 * elements go, in order, to n buckets by (KEY - min) * n / (max - min), truncated (a non-decreasing
 * function of KEY: equal keys share a bucket, a larger key never goes to an earlier one); each
 * bucket is then sorted by SORT. Both steps are stable, so the result is the stable sort by LESS,
 * SORT's own, whenever LESS orders by KEY first and is a strict weak order (no NaN: VALID); else,
 * and for few elements or a range that does not divide, SORT alone. About 3x cheaper than the merge
 * sort on the sample (1000 projections) and the sections' points. */
#define BUDGET_BUCKET_SORT(NAME, TYPE, KEY, VALID, SORT)                                                        \
    static inline void NAME(TYPE *a, size_t n, TYPE *tmp, size_t *cnt) {                                             \
        double lo = INFINITY, hi = -INFINITY;                                                                 \
        int ok = n >= 32;                                                                                     \
        for (size_t k = 0; ok && k < n; k++) {                                                                \
            double x = KEY(&a[k]);                                                                            \
            if (!VALID(&a[k])) ok = 0;                                                                        \
            if (x < lo) lo = x;                                                                               \
            if (x > hi) hi = x;                                                                               \
        }                                                                                                     \
        double nb = (double)n, sc = ok && hi > lo ? nb / (hi - lo) : 0;                                       \
        if (!(sc > 0 && sc < INFINITY)) {                                                                     \
            SORT(a, n, tmp);                                                                                  \
            return;                                                                                           \
        }                                                                                                     \
        memset(cnt, 0, (n + 1) * sizeof *cnt);                                                                \
        for (size_t k = 0; k < n; k++) {                                                                      \
            double t = (KEY(&a[k]) - lo) * sc;                                                                \
            cnt[(t < nb ? (size_t)t : n - 1) + 1]++;                                                          \
        }                                                                                                     \
        for (size_t b = 1; b <= n; b++) cnt[b] += cnt[b - 1]; /* cnt[b]: where bucket b starts */            \
        for (size_t k = 0; k < n; k++) {                                                                      \
            double t = (KEY(&a[k]) - lo) * sc;                                                                \
            tmp[cnt[t < nb ? (size_t)t : n - 1]++] = a[k];                                                    \
        }                                                                                                     \
        /* now cnt[b]: where bucket b ends */                                                                 \
        for (size_t b = 0, s = 0; b < n; s = cnt[b++])                                                        \
            if (cnt[b] - s > 1) SORT(tmp + s, cnt[b] - s, a + s);                                             \
        memcpy(a, tmp, n * sizeof *a);                                                                        \
    }

static inline double keyed_key(const keyed *x) { return x->key; }
static inline int keyed_valid(const keyed *x) { return x->key == x->key; }
BUDGET_BUCKET_SORT(keyed_bucket_sort, keyed, keyed_key, keyed_valid, keyed_sort)
static inline double xpt_key(const xpt *x) { return x->u; }
static inline int xpt_valid(const xpt *x) { return x->u == x->u && x->v == x->v; }
BUDGET_BUCKET_SORT(xpt_bucket_sort, xpt, xpt_key, xpt_valid, xpt_sort)

#endif
