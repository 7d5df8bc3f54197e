/* core/minheap: pops come out sorted by (key, id) (and by tie after those, items pushed with
 * acd_minheap_push_item), whatever the push order, across growth and interleaved pushes and pops;
 * acd_minheap_pushpop gives what a push then a pop would; acd_minheap_less is the lexicographic
 * order (key, id, tie) of its definition, signed zeros and NaN included. The callers' output
 * (patches' flood, A* paths, region Dijkstra) depends on the exact order of tied items, so these
 * compare against a plain reference on many ties. */
#include "testutil.h"

#include <math.h>
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

/* the definition: by key, then id, then tie (NaN keys precede nothing and follow nothing) */
static int ref_less(acd_minheap_item a, acd_minheap_item b) {
    if (a.key < b.key) return 1;
    if (!(a.key == b.key)) return 0;
    if (a.id != b.id) return a.id < b.id;
    return a.tie < b.tie;
}

static void test_less_reference(void **state) {
    (void)state;
    const double keys[] = {-1.0, -0.0, 0.0, 1e-300, 0.5, 1.0, 2.0, INFINITY, -INFINITY, NAN};
    const uint32_t ids[] = {0, 1, 2, 0x7fffffffu, 0x80000000u, UINT32_MAX};
    size_t nk = sizeof keys / sizeof *keys, ni = sizeof ids / sizeof *ids;
    size_t checked = 0;
    for (size_t ka = 0; ka < nk; ka++)
        for (size_t kb = 0; kb < nk; kb++)
            for (size_t ia = 0; ia < ni; ia++)
                for (size_t ib = 0; ib < ni; ib++)
                    for (size_t t = 0; t < 4; t++) {
                        acd_minheap_item a = {keys[ka], ids[ia], ids[(ia + t) % ni]};
                        acd_minheap_item b = {keys[kb], ids[ib], ids[(ib + 2 * t) % ni]};
                        assert_int_equal(acd_minheap_less(a, b), ref_less(a, b));
                        checked++;
                    }
    assert_true(checked == nk * nk * ni * ni * 4);
    /* -0 and +0 are equal keys: the id decides */
    assert_true(acd_minheap_less((acd_minheap_item){0.0, 1, 0}, (acd_minheap_item){-0.0, 2, 0}));
    assert_false(acd_minheap_less((acd_minheap_item){-0.0, 2, 0}, (acd_minheap_item){0.0, 1, 0}));
}

/* The least of ref[0..n) under ref_less (the first of exact copies). */
static size_t ref_min(const acd_minheap_item *ref, size_t n) {
    size_t m = 0;
    for (size_t i = 1; i < n; i++)
        if (ref_less(ref[i], ref[m])) m = i;
    return m;
}

/* Random pushes, pops and pushpops against a plain array: every item handed back is the least
 * present (keys from few values, ids and ties from few: most comparisons are ties), sizes across
 * the growth steps. */
static void check_ops(uint64_t seed, size_t nops, uint64_t nkeys, uint64_t nids, uint64_t nties, unsigned push_pct) {
    acd_rng r;
    acd_rng_seed(&r, seed);
    acd_minheap_item *ref = malloc(nops * sizeof *ref);
    assert_non_null(ref);
    size_t n = 0, npushpop_direct = 0, npushpop_heap = 0;
    acd_minheap h = {0};
    for (size_t op = 0; op < nops; op++) {
        acd_minheap_item x = {(double)acd_rng_below(&r, nkeys) * 0.25, (uint32_t)acd_rng_below(&r, nids),
                              (uint32_t)acd_rng_below(&r, nties)};
        unsigned what = (unsigned)acd_rng_below(&r, 100);
        if (what < push_pct || n == 0) {
            if (what % 2 == 0) x.tie = 0;
            assert_true(what % 2 == 0 ? acd_minheap_push(&h, x.key, x.id) : acd_minheap_push_item(&h, x));
            ref[n++] = x;
        } else if (what < push_pct + (100 - push_pct) / 2) {
            size_t m = ref_min(ref, n);
            acd_minheap_item got = acd_minheap_pop(&h);
            assert_true(got.key == ref[m].key && got.id == ref[m].id && got.tie == ref[m].tie);
            ref[m] = ref[--n];
        } else {
            ref[n++] = x;
            size_t m = ref_min(ref, n);
            acd_minheap_item got = acd_minheap_pushpop(&h, x);
            assert_true(got.key == ref[m].key && got.id == ref[m].id && got.tie == ref[m].tie);
            if (m == n - 1) npushpop_direct++;
            else npushpop_heap++;
            ref[m] = ref[--n];
        }
        assert_int_equal(h.n, n);
    }
    while (n) {
        size_t m = ref_min(ref, n);
        acd_minheap_item got = acd_minheap_pop(&h);
        assert_true(got.key == ref[m].key && got.id == ref[m].id && got.tie == ref[m].tie);
        ref[m] = ref[--n];
    }
    assert_int_equal(h.n, 0);
    /* both ways through pushpop were taken */
    assert_true(npushpop_direct > 0 && npushpop_heap > 0);
    acd_minheap_free(&h);
    free(ref);
}

static void test_ops_reference(void **state) {
    (void)state;
    check_ops(3, 20000, 9, 6, 3, 50);      /* a small heap, nearly all ties */
    check_ops(5, 30000, 40, 200, 4, 60);   /* grows to thousands (past 256 and its doublings) */
    check_ops(9, 20000, 1000, 1000, 1, 55); /* few ties */
}

static void test_pushpop_small(void **state) {
    (void)state;
    acd_minheap h = {0};
    /* on an empty heap: x back, nothing kept */
    acd_minheap_item x = acd_minheap_pushpop(&h, (acd_minheap_item){2.0, 7, 1});
    assert_true(x.key == 2.0 && x.id == 7 && x.tie == 1 && h.n == 0);
    assert_true(acd_minheap_push(&h, 1.0, 5));
    /* x precedes the top (equal key, smaller id): x back, heap unchanged */
    x = acd_minheap_pushpop(&h, (acd_minheap_item){1.0, 4, 9});
    assert_true(x.id == 4 && h.n == 1 && h.a[0].id == 5);
    /* the top precedes x (equal key and id, tie 0 < 3): the top back, x kept */
    x = acd_minheap_pushpop(&h, (acd_minheap_item){1.0, 5, 3});
    assert_true(x.id == 5 && x.tie == 0 && h.n == 1 && h.a[0].tie == 3);
    acd_minheap_free(&h);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sorted_order),
        cmocka_unit_test(test_tie_order),
        cmocka_unit_test(test_interleaved),
        cmocka_unit_test(test_less_reference),
        cmocka_unit_test(test_ops_reference),
        cmocka_unit_test(test_pushpop_small),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
