/* core/minheap: pops come out sorted by (key, id) (and by tie after those, items pushed with
 * acd_minheap_push_item), whatever the push order, across growth and interleaved pushes and pops. */
#include "testutil.h"

#include <stdlib.h>

#include "core/minheap.h"
#include "core/rng.h"

static int cmp_item(const void *a, const void *b) {
    const acd_minheap_item *x = a, *y = b;
    if (x->key != y->key) return x->key < y->key ? -1 : 1;
    if (x->id != y->id) return (x->id > y->id) - (x->id < y->id);
    return (x->tie > y->tie) - (x->tie < y->tie);
}

/* n items of keys below nkeys, ids id0 + below nids, ties tie_step x below nties (tie_step 0: pushed
 * by acd_minheap_push, tie 0), pushed in random order: they pop sorted, and acd_minheap_less
 * agrees with that order */
static void check_sorted(uint64_t seed, size_t n, uint64_t nkeys, uint32_t id0, uint64_t nids, uint32_t tie_step,
                         uint64_t nties) {
    acd_rng r;
    acd_rng_seed(&r, seed);
    acd_minheap_item *ref = malloc(n * sizeof *ref);
    assert_non_null(ref);
    acd_minheap h = {0};
    for (size_t i = 0; i < n; i++) {
        ref[i].key = (double)acd_rng_below(&r, nkeys);
        ref[i].id = id0 + (uint32_t)acd_rng_below(&r, nids);
        ref[i].tie = tie_step ? tie_step * (uint32_t)acd_rng_below(&r, nties) : 0;
        assert_true(tie_step ? acd_minheap_push_item(&h, ref[i]) : acd_minheap_push(&h, ref[i].key, ref[i].id));
    }
    qsort(ref, n, sizeof *ref, cmp_item);
    for (size_t i = 0; i + 1 < n; i++) assert_int_equal(acd_minheap_less(ref[i + 1], ref[i]), 0);
    for (size_t i = 0; i < n; i++) {
        acd_minheap_item it = acd_minheap_pop(&h);
        assert_true(it.key == ref[i].key && it.id == ref[i].id && it.tie == ref[i].tie);
    }
    assert_int_equal(h.n, 0);
    acd_minheap_free(&h);
    free(ref);
}

static void test_sorted_order(void **state) {
    (void)state;
    /* few distinct keys: the id decides most ties */
    check_sorted(7, 2000, 17, 0, 1000, 0, 1);
}

static void test_tie_order(void **state) {
    (void)state;
    /* few distinct keys and ids: the tie decides many orders; ids near 2^32 and ties above 2^31
     * check that the two are compared as unsigned and the id first */
    check_sorted(11, 3000, 5, UINT32_MAX - 6, 7, 0x5000000u, 50);
}

static void test_interleaved(void **state) {
    (void)state;
    acd_minheap h = {0};
    assert_true(acd_minheap_push(&h, 3.0, 1));
    assert_true(acd_minheap_push(&h, 1.0, 9));
    assert_true(acd_minheap_push(&h, 1.0, 2));
    acd_minheap_item a = acd_minheap_pop(&h);
    assert_true(a.key == 1.0 && a.id == 2);
    assert_true(acd_minheap_push(&h, 0.5, 4));
    assert_true(acd_minheap_pop(&h).id == 4);
    assert_true(acd_minheap_pop(&h).id == 9);
    assert_true(acd_minheap_pop(&h).id == 1);
    assert_int_equal(h.n, 0);
    acd_minheap_free(&h);
    assert_null(h.a);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sorted_order),
        cmocka_unit_test(test_tie_order),
        cmocka_unit_test(test_interleaved),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
