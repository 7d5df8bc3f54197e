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

static void test_sorted_order(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 7);
    enum { N = 2000 };
    acd_minheap_item *ref = malloc(N * sizeof *ref);
    assert_non_null(ref);
    acd_minheap h = {0};
    for (size_t i = 0; i < N; i++) {
        /* few distinct keys: the id decides most ties */
        ref[i].key = (double)acd_rng_below(&r, 17);
        ref[i].id = (uint32_t)acd_rng_below(&r, 1000);
        ref[i].tie = 0; /* what acd_minheap_push gives */
        assert_true(acd_minheap_push(&h, ref[i].key, ref[i].id));
    }
    qsort(ref, N, sizeof *ref, cmp_item);
    for (size_t i = 0; i < N; i++) {
        acd_minheap_item it = acd_minheap_pop(&h);
        assert_true(it.key == ref[i].key && it.id == ref[i].id);
    }
    assert_int_equal(h.n, 0);
    acd_minheap_free(&h);
    free(ref);
}

static void test_tie_order(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 11);
    enum { N = 3000 };
    acd_minheap_item *ref = malloc(N * sizeof *ref);
    assert_non_null(ref);
    acd_minheap h = {0};
    for (size_t i = 0; i < N; i++) {
        /* few distinct keys and ids: the tie decides many orders; ids near 2^32 and ties above
         * 2^31 check that the two are compared as unsigned and the id first */
        ref[i].key = (double)acd_rng_below(&r, 5);
        ref[i].id = UINT32_MAX - (uint32_t)acd_rng_below(&r, 7);
        ref[i].tie = (uint32_t)acd_rng_below(&r, 50) * 0x5000000u;
        assert_true(acd_minheap_push_item(&h, ref[i]));
    }
    qsort(ref, N, sizeof *ref, cmp_item);
    for (size_t i = 0; i + 1 < N; i++) assert_int_equal(acd_minheap_less(ref[i + 1], ref[i]), 0);
    for (size_t i = 0; i < N; i++) {
        acd_minheap_item it = acd_minheap_pop(&h);
        assert_true(it.key == ref[i].key && it.id == ref[i].id && it.tie == ref[i].tie);
    }
    assert_int_equal(h.n, 0);
    acd_minheap_free(&h);
    free(ref);
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
