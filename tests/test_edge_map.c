/* geom3/edge_map: the map's keys sorted, repeated half-edges in triangle order, the twins and
 * finds agreeing with a brute-force reference, on dense and sparse vertex ids (the radix sort's
 * packed key a * (maxid + 1) + b takes 2 to 5 digit passes), a vertex of high degree, a keep
 * mask, no half-edge at all; acd_edge_map_check_closed and its one-at-a-time conditions on a
 * tetrahedron, one with a triangle missing, one flipped, one repeating a vertex, and
 * acd_edge_map_closed (build and check in one) agreeing with them, and the twins by half-edge it
 * keeps; acd_edge_map_sort of the same entries agreeing with the build, at sizes on both sides of
 * the insertion sort's and the binary-searched twins' limits, with dense and sparse ids. */
#include "testutil.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"
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
    /* the same entries in triangle order, sorted by acd_edge_map_sort: the same map */
    acd_edge_map s;
    s.n = n, s.twin = NULL;
    s.key = malloc((n ? n : 1) * sizeof *s.key);
    s.half = malloc((n ? n : 1) * sizeof *s.half);
    assert_non_null(s.key);
    assert_non_null(s.half);
    for (size_t t = 0, k = 0; t < nt; t++)
        for (int i = 0; keep[t] && i < 3; i++, k++) {
            s.key[k] = ((uint64_t)tri[3 * t + i] << 32) | tri[3 * t + (i + 1) % 3];
            s.half[k] = (uint32_t)(3 * t + (size_t)i);
        }
    assert_int_equal(acd_edge_map_sort(&s, &err), ACD_OK);
    assert_memory_equal(s.key, m.key, n * sizeof *m.key);
    assert_memory_equal(s.half, m.half, n * sizeof *m.half);
    acd_edge_map_free(&s);
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

/* sizes around the limits: 48 keys (insertion sort), 1024 entries (twins by binary search); ids
 * dense (below twice the entries: the sort's and the twins' vertex buckets) and sparse (radix) */
static void test_size_limits(void **state) {
    (void)state;
    size_t nts[] = {1, 5, 16, 17, 40, 341, 342, 700};
    for (size_t i = 0; i < sizeof nts / sizeof *nts; i++) {
        check(10 + i, nts[i], (uint32_t)(nts[i] / 2 + 3), 1, 0, 0);
        check(20 + i, nts[i], (uint32_t)(nts[i] / 3 + 3), 7, 0, 1);
    }
    /* over 1024 entries with sparse ids: the twins by the radix sort (dense: by the transpose) */
    check(31, 700, 300, 100003, 0, 0);
    check(32, 700, 300, 100003, 0, 1);
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

/* check_closed on the nt triangles tri, against the conditions one at a time; returns its status
 * (its report in *err) */
static acd_status closed_status(const uint32_t *tri, size_t nt, acd_error *err) {
    acd_edge_map m;
    assert_int_equal(acd_edge_map_build(tri, nt, NULL, &m, err), ACD_OK);
    uint32_t *tw = NULL;
    assert_int_equal(acd_edge_map_twins(&m, &tw, err), ACD_OK);
    int ok = 1;
    for (size_t i = 0; i < m.n; i++) ok &= acd_edge_map_entry_closed(&m, tw, i);
    for (size_t t = 0; t < nt; t++) ok &= acd_edge_map_triangle_proper(tri + 3 * t);
    acd_error_clear(err);
    acd_status st = acd_edge_map_check_closed(&m, tri, nt, err);
    assert_int_equal(st == ACD_OK, ok);
    /* acd_edge_map_closed: the same answer; when closed, the same map kept (or none asked for) */
    acd_edge_map k;
    acd_error e2;
    assert_int_equal(acd_edge_map_closed(tri, nt, &k, &e2), st);
    assert_int_equal(acd_edge_map_closed(tri, nt, NULL, NULL), st);
    if (st == ACD_OK) {
        assert_int_equal(k.n, m.n);
        assert_memory_equal(k.key, m.key, m.n * sizeof *m.key);
        assert_memory_equal(k.half, m.half, m.n * sizeof *m.half);
        /* its twins by half-edge: the opposite half-edge, an involution */
        assert_non_null(k.twin);
        assert_int_equal(k.n, 3 * nt);
        for (size_t h = 0; h < 3 * nt; h++) {
            uint32_t o = k.twin[h];
            assert_true(o < 3 * nt && o / 3 != h / 3);
            assert_int_equal(k.twin[o], h);
            assert_int_equal(tri[o], tri[3 * (h / 3) + (h % 3 + 1) % 3]);
            assert_int_equal(tri[3 * (o / 3) + (o % 3 + 1) % 3], tri[h]);
        }
        acd_edge_map_free(&k);
    } else {
        assert_string_equal(e2.message, err->message);
    }
    free(tw);
    acd_edge_map_free(&m);
    return st;
}

static void test_check_closed(void **state) {
    (void)state;
    acd_error err;
    uint32_t tet[12] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    assert_int_equal(closed_status(tet, 4, &err), ACD_OK);
    /* a triangle missing: its edges' opposites have none */
    assert_int_equal(closed_status(tet, 3, &err), ACD_ERR_NON_MANIFOLD);
    assert_non_null(strstr(err.message, "no opposite edge"));
    /* the last triangle flipped: its half-edges repeat the others' */
    uint32_t flip[12] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 2, 3};
    assert_int_equal(closed_status(flip, 4, &err), ACD_ERR_NON_MANIFOLD);
    assert_non_null(strstr(err.message, "same direction"));
    /* a triangle repeating a vertex (its half-edges paired: only that condition fails) */
    uint32_t rep[15] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2, 4, 4, 5};
    assert_int_equal(closed_status(rep, 5, &err), ACD_ERR_NON_MANIFOLD);
    assert_non_null(strstr(err.message, "repeats a vertex"));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dense_ids),
        cmocka_unit_test(test_sparse_ids),
        cmocka_unit_test(test_high_degree),
        cmocka_unit_test(test_size_limits),
        cmocka_unit_test(test_empty),
        cmocka_unit_test(test_check_closed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
