/* Tests of the budget pass's sorts (acd3/budget_sort.h): keyed_bucket_sort and xpt_bucket_sort give
 * exactly the order of a reference stable sort (qsort by key, then input position; for the section
 * points by u, then v, then position), and so do the merge sorts they fall back to, on random keys,
 * keys with many ties, a cluster inside a huge range, signed zeros, infinities, NaN (the fallback),
 * and sizes around the bucket pass's threshold (32). A bucket function that is not monotone in the
 * key, or an unstable step, moves an element and fails. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd3/budget_sort.h"
#include "core/rng.h"

typedef struct ref {
    double u, v;
    size_t i;
} ref;

static int cmp_keyed_ref(const void *a, const void *b) {
    const ref *x = a, *y = b;
    if (x->u < y->u) return -1;
    if (y->u < x->u) return 1;
    return x->i < y->i ? -1 : x->i > y->i;
}

static int cmp_xpt_ref(const void *a, const void *b) {
    const ref *x = a, *y = b;
    if (x->u < y->u) return -1;
    if (y->u < x->u) return 1;
    if (x->v < y->v) return -1;
    if (y->v < x->v) return 1;
    return x->i < y->i ? -1 : x->i > y->i;
}

/* The kind-th key distribution. */
static double draw(acd_rng *r, int kind, size_t k, size_t n) {
    double x = acd_rng_uniform(r);
    switch (kind) {
    case 0: return 2 * x - 1;                                        /* spread */
    case 1: return (double)acd_rng_below(r, 5);                      /* five values: ties everywhere */
    case 2: return k == 0 ? -1e300 : k == 1 ? 1e300 : 1 + 1e-12 * x; /* a cluster in a huge range */
    case 3: return acd_rng_below(r, 2) ? 0.0 : -0.0;                 /* signed zeros (equal) */
    case 4: return k % 7 == 0 ? (k % 14 ? INFINITY : -INFINITY) : x; /* infinities */
    case 5: return k == n / 2 ? NAN : x;                             /* a NaN: the fallback */
    default: return ldexp(x, (int)acd_rng_below(r, 200) - 100);      /* wide exponents */
    }
}

static void test_bucket_sorts_match_reference(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 20261126);
    const size_t sizes[] = {0, 1, 2, 7, 31, 32, 33, 100, 1000, 3001};
    for (int kind = 0; kind < 7; kind++)
        for (size_t s = 0; s < sizeof sizes / sizeof *sizes; s++) {
            size_t n = sizes[s];
            keyed *a = malloc((n + 1) * sizeof *a), *b = malloc((n + 1) * sizeof *b), *t = malloc((n + 1) * sizeof *t);
            xpt *p = malloc((n + 1) * sizeof *p), *q = malloc((n + 1) * sizeof *q), *pt = malloc((n + 1) * sizeof *pt);
            ref *ra = malloc((n + 1) * sizeof *ra), *rp = malloc((n + 1) * sizeof *rp);
            size_t *cnt = malloc((n + 1) * sizeof *cnt);
            assert_true(a && b && t && p && q && pt && ra && rp && cnt);
            for (size_t k = 0; k < n; k++) {
                a[k].key = draw(&r, kind, k, n), a[k].i = k;
                p[k].u = draw(&r, kind, k, n), p[k].v = draw(&r, kind == 5 ? 0 : kind, k, n), p[k].i = k;
                ra[k] = (ref){a[k].key, 0, k};
                rp[k] = (ref){p[k].u, p[k].v, k};
            }
            memcpy(b, a, n * sizeof *a);
            memcpy(q, p, n * sizeof *p);
            keyed_bucket_sort(a, n, t, cnt);
            keyed_sort(b, n, t);
            xpt_bucket_sort(p, n, pt, cnt);
            xpt_sort(q, n, pt);
            if (kind != 5) { /* (with a NaN there is no order to compare with: only the two sorts agree) */
                qsort(ra, n, sizeof *ra, cmp_keyed_ref);
                qsort(rp, n, sizeof *rp, cmp_xpt_ref);
                for (size_t k = 0; k < n; k++) {
                    assert_int_equal(a[k].i, ra[k].i);
                    assert_int_equal(p[k].i, rp[k].i);
                }
            }
            for (size_t k = 0; k < n; k++) {
                assert_int_equal(a[k].i, b[k].i);
                assert_int_equal(p[k].i, q[k].i);
            }
            free(a), free(b), free(t), free(p), free(q), free(pt), free(ra), free(rp), free(cnt);
        }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bucket_sorts_match_reference),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
