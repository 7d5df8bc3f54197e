/* geom3/edge_map: the map's keys sorted, repeated half-edges in triangle order, the twins and
 * finds agreeing with a brute-force reference, on dense and sparse vertex ids (the radix sort's
 * packed key a * (maxid + 1) + b takes 2 to 5 digit passes), a vertex of high degree, a keep
 * mask, no half-edge at all. */
#include "testutil.h"

#include <stdlib.h>

#include "core/rng.h"
#include "geom3/edge_map.h"

typedef struct rec {
    uint64_t key;
    uint32_t half;
} rec;

static int cmp_rec(const void *a, const void *b) {
    const rec *x = a, *y = b;
    if (x->key != y->key) return x->key < y->key ? -1 : 1;
    return x->half < y->half ? -1 : x->half > y->half;
}

/* nt random triangles over vertex ids below nid (every id times stride); with hub, vertex 0 in
 * every triangle. Every triangle kept unless drop, then every third one is left out. */
static void check(uint64_t seed, size_t nt, uint32_t nid, uint32_t stride, int hub, int drop) {
    acd_rng rng;
    acd_rng_seed(&rng, seed);
    uint32_t *tri = malloc(3 * nt * sizeof *tri);
    uint8_t *keep = malloc(nt);
    rec *ref = malloc(3 * nt * sizeof *ref);
    assert_non_null(tri);
    assert_non_null(keep);
    assert_non_null(ref);
    size_t n = 0;
    for (size_t t = 0; t < nt; t++) {
        for (int k = 0; k < 3; k++) tri[3 * t + k] = stride * (uint32_t)acd_rng_below(&rng, nid);
        if (hub) tri[3 * t] = 0;
        keep[t] = !drop || t % 3 != 0;
        if (!keep[t]) continue;
        for (int k = 0; k < 3; k++) {
            ref[n].key = ((uint64_t)tri[3 * t + k] << 32) | tri[3 * t + (k + 1) % 3];
            ref[n++].half = (uint32_t)(3 * t + (size_t)k);
        }
    }
    qsort(ref, n, sizeof *ref, cmp_rec);
    acd_edge_map m;
    acd_error err;
    assert_int_equal(acd_edge_map_build(tri, nt, drop ? keep : NULL, &m, &err), ACD_OK);
    assert_int_equal(m.n, n);
    for (size_t i = 0; i < n; i++) {
        assert_true(m.key[i] == ref[i].key);
        assert_int_equal(m.half[i], ref[i].half);
    }
    uint32_t *tw;
    assert_int_equal(acd_edge_map_twins(&m, &tw, &err), ACD_OK);
    for (size_t i = 0; i < n; i++) {
        uint32_t a = (uint32_t)(m.key[i] >> 32), b = (uint32_t)m.key[i];
        /* the first of the reversed key's entries, by brute force */
        uint32_t want = ACD_EDGE_NONE;
        uint64_t rk = ((uint64_t)b << 32) | a;
        for (size_t j = 0; j < n && want == ACD_EDGE_NONE; j++)
            if (ref[j].key == rk) want = ref[j].half;
        assert_int_equal(tw[i], want);
        assert_int_equal(acd_edge_map_find(&m, b, a), want);
    }
    free(tw);
    acd_edge_map_free(&m);
    free(tri);
    free(keep);
    free(ref);
}

static void test_dense_ids(void **state) {
    (void)state;
    for (uint64_t s = 1; s <= 4; s++) check(s, 400, 60, 1, 0, (int)(s & 1)); /* repeated half-edges too */
}

static void test_sparse_ids(void **state) {
    (void)state;
    for (uint64_t s = 1; s <= 4; s++) check(s, 300, 50, 100003, 0, (int)(s & 1)); /* ids up to 5e6 */
}

static void test_high_degree(void **state) {
    (void)state;
    for (uint64_t s = 1; s <= 4; s++) check(s, 500, 200, 1, 1, (int)(s & 1)); /* vertex 0 in every triangle */
}

static void test_empty(void **state) {
    (void)state;
    acd_edge_map m;
    acd_error err;
    uint32_t tri[3] = {0, 1, 2};
    uint8_t keep = 0;
    assert_int_equal(acd_edge_map_build(tri, 1, &keep, &m, &err), ACD_OK);
    assert_int_equal(m.n, 0);
    assert_int_equal(acd_edge_map_find(&m, 0, 1), ACD_EDGE_NONE);
    acd_edge_map_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dense_ids),
        cmocka_unit_test(test_sparse_ids),
        cmocka_unit_test(test_high_degree),
        cmocka_unit_test(test_empty),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
