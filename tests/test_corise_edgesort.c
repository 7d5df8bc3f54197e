/* Tests of corise/edgesort: the radix sort gives the array qsort gives with the full (lo, hi, face)
 * order, on random records with many repeated keys, ids past 16 bits (every digit pass used),
 * ids under 16 bits (passes skipped), sizes on both sides of the radix threshold, and an empty and
 * a one-record array; and records made in facet order (faces non-decreasing along the array, as the
 * CoRiSe loop makes them: the face passes are skipped), with faces past 16 bits. */
#include "testutil.h"

#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "corise/edgesort.h"

static void check(acd_rng *rng, size_t n, uint32_t range, int ordered) {
    acd_corise_ef *a = malloc((n ? n : 1) * sizeof *a), *b = malloc((n ? n : 1) * sizeof *b);
    assert_non_null(a);
    assert_non_null(b);
    for (size_t i = 0; i < n; i++) {
        uint32_t u = (uint32_t)(acd_rng_uniform(rng) * range), v = (uint32_t)(acd_rng_uniform(rng) * range);
        a[i] = (acd_corise_ef){u < v ? u : v, u < v ? v : u, (uint32_t)(acd_rng_uniform(rng) * range)};
        if (i && acd_rng_uniform(rng) < 0.3) a[i] = a[i - 1]; /* equal records */
        if (i && acd_rng_uniform(rng) < 0.3) a[i].lo = a[i - 1].lo, a[i].hi = a[i - 1].hi; /* equal edges */
        if (ordered) a[i].face = (uint32_t)(i / 3) * 29; /* 3 records a facet, facets in order */
    }
    memcpy(b, a, (n ? n : 1) * sizeof *a);
    assert_int_equal(acd_corise_ef_sort(a, n), 1);
    qsort(b, n, sizeof *b, acd_corise_ef_cmp);
    assert_memory_equal(a, b, (n ? n : 1) * sizeof *a);
    for (size_t i = 1; i < n; i++) assert_true(acd_corise_ef_cmp(&a[i - 1], &a[i]) <= 0);
    free(a);
    free(b);
}

static void test_radix_equals_qsort(void **state) {
    (void)state;
    acd_rng rng;
    acd_rng_seed(&rng, 1234);
    size_t sizes[] = {0, 1, 5, ACD_CORISE_EDGESORT_RADIX_MIN - 1, ACD_CORISE_EDGESORT_RADIX_MIN, 3000, 100000};
    uint32_t ranges[] = {7, 1000, 65536, 70000, 4000000000u};
    for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++)
        for (size_t j = 0; j < sizeof ranges / sizeof *ranges; j++)
            for (int ordered = 0; ordered < 2; ordered++) check(&rng, sizes[i], ranges[j], ordered);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_radix_equals_qsort)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
