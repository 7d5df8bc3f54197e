/* Tests of the minimum convex decomposition (Keil-Snoeyink, acd2/exact_mcd through
 * include/acd/exact2d.h): optimality against brute force (all sets of non-crossing diagonals) on
 * small random polygons, the dissertation's MCD counts (monkey 340, heron 263), partition checks,
 * refusal of holes, determinism. */
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/exact2d.h"
#include "core/rng.h"
#include "exact2d_brute.h"
#include "poly2_support.h"

static acd_polygon ring_polygon(const acd_vec2 *v, size_t n) {
    const acd_vec2 *rings[] = {v};
    size_t sz[] = {n};
    acd_polygon p;
    assert_int_equal(acd_polygon_from_rings(&p, rings, sz, 1, NULL), ACD_OK);
    return p;
}

static size_t mcd_count(const acd_vec2 *v, size_t n) {
    acd_polygon p = ring_polygon(v, n);
    acd_exact2d_result r;
    acd_error err;
    acd_status st = acd_exact2d_decompose(&p, ACD_EXACT2D_MCD, &r, &err);
    if (st != ACD_OK) print_message("MCD failed: %s\n", err.message);
    assert_int_equal(st, ACD_OK);
    assert_true(p2_check_partition(&p, &r));
    assert_int_equal(r.ndiagonals, r.npieces - 1);
    size_t k = r.npieces;
    acd_exact2d_result_free(&r);
    acd_polygon_free(&p);
    return k;
}

/* General position: MCD equals the brute-force minimum exactly. */
static void test_brute_force_general(void **state) {
    (void)state;
    acd_rng g;
    acd_rng_seed(&g, 2024);
    int tested = 0;
    for (int it = 0; it < 400; it++) {
        int n = 4 + (int)acd_rng_below(&g, 6); /* 4..9 */
        acd_vec2 v[BR_MAXN];
        p2_random_star(&g, v, (size_t)n, 0, 0, 0.15, 1.0);
        if (!br_is_simple(v, n)) continue;
        int bm = br_mcd(v, n);
        size_t m = mcd_count(v, (size_t)n);
        if ((int)m != bm) print_message("iteration %d: MCD %zu, brute force %d\n", it, m, bm);
        assert_int_equal((int)m, bm);
        tested++;
    }
    assert_true(tested > 300);
}

/* Integer grids: many collinear vertices (180-degree piece vertices, diagonals along edges, cuts
 * through chains of collinear vertices): MCD equals the brute-force minimum too. */
static void test_brute_force_collinear(void **state) {
    (void)state;
    acd_rng g;
    acd_rng_seed(&g, 77);
    int tested = 0, above = 0;
    for (int it = 0; it < 1200; it++) {
        int n = 4 + (int)acd_rng_below(&g, 7); /* 4..10 */
        acd_vec2 v[BR_MAXN];
        p2_random_star(&g, v, (size_t)n, 0, 0, 0.2, 1.0);
        double s = it % 2 ? 3 : 5;
        for (int i = 0; i < n; i++) {
            v[i].x = round(v[i].x * s);
            v[i].y = round(v[i].y * s);
        }
        if (!br_is_simple(v, n)) continue;
        int bm = br_mcd(v, n);
        size_t m = mcd_count(v, (size_t)n);
        if ((int)m != bm) {
            print_message("iteration %d: MCD %zu, brute force %d:", it, m, bm);
            for (int i = 0; i < n; i++) print_message(" (%g, %g)", v[i].x, v[i].y);
            print_message("\n");
            above++;
        }
        tested++;
    }
    assert_true(tested > 300);
    assert_int_equal(above, 0);
}

static void test_simple_cases(void **state) {
    (void)state;
    acd_vec2 tri[] = {{0, 0}, {1, 0}, {0, 1}};
    assert_int_equal(mcd_count(tri, 3), 1);
    acd_vec2 sq_cw[] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    assert_int_equal(mcd_count(sq_cw, 4), 1);
    /* an L: one notch, two pieces; clockwise too */
    acd_vec2 l[] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
    assert_int_equal(mcd_count(l, 6), 2);
    acd_vec2 lcw[6];
    for (int i = 0; i < 6; i++) lcw[i] = l[5 - i];
    assert_int_equal(mcd_count(lcw, 6), 2);
    /* comb with 4 teeth: the base must be cut between the teeth, 5 pieces */
    acd_vec2 comb[] = {{0, 0}, {7, 0}, {7, 3}, {6, 3}, {6, 1}, {5, 1}, {5, 3}, {4, 3},
                       {4, 1}, {3, 1}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
    assert_int_equal(mcd_count(comb, 16), 5);
    /* a square with collinear points on its edges: still one piece */
    acd_vec2 sq[] = {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
    assert_int_equal(mcd_count(sq, 8), 1);
}

static void test_holes_refused(void **state) {
    (void)state;
    acd_vec2 o[] = {{0, 0}, {4, 0}, {4, 4}, {0, 4}}, h[] = {{1, 1}, {1, 2}, {2, 2}, {2, 1}};
    const acd_vec2 *rings[] = {o, h};
    size_t sz[] = {4, 4};
    acd_polygon p;
    assert_int_equal(acd_polygon_from_rings(&p, rings, sz, 2, NULL), ACD_OK);
    acd_exact2d_result r;
    acd_error err;
    assert_int_equal(acd_exact2d_decompose(&p, ACD_EXACT2D_MCD, &r, &err), ACD_ERR_UNSUPPORTED);
    assert_non_null(strstr(err.message, "hole"));
    assert_int_equal(r.npieces, 0);
    acd_polygon_free(&p);
}

/* Found by fuzz_exact2d (corpus exact2d/ub-null-option-offset): an invalid ring that revisits
 * (0, 0) three times made the DP offset its still NULL option array (undefined behaviour under
 * UBSan, "applying zero offset to null pointer"). It must merely return, either way. */
static void test_invalid_ring_no_ub(void **state) {
    (void)state;
    acd_vec2 v[] = {{0, 0}, {2, -6}, {0, 0}, {6, -111}, {0, 0}, {4, 0}, {10, -111}, {0, 9}, {-1, 20}, {-8, 10}, {0, 5}};
    acd_polygon p = ring_polygon(v, sizeof v / sizeof v[0]);
    acd_exact2d_result r;
    acd_error err;
    if (acd_exact2d_decompose(&p, ACD_EXACT2D_MCD, &r, &err) == ACD_OK) acd_exact2d_result_free(&r);
    else assert_true(err.message[0] != '\0');
    acd_polygon_free(&p);
}

/* The dissertation's MCD sizes (Fig. 13: monkey 340; Fig. 27: heron 263) and texas (38, back-derived
 * from Table 3, spec §7.4). */
static void test_dissertation_counts(void **state) {
    (void)state;
    const char *files[] = {"nazca_nazca_monkey", "nazca_nazca_heron", "texas"};
    const size_t expect[] = {340, 263, 38};
    char path[1024], rel[256];
    int tested = 0;
    for (int f = 0; f < 3; f++) {
        snprintf(rel, sizeof rel, "polygons-lien/%s.poly", files[f]);
        if (!tu_shared_data(path, sizeof path, rel)) continue;
        acd_polygon polys[4];
        int np = p2_read_poly(path, polys, 4);
        assert_int_equal(np, 1);
        acd_exact2d_result r, r2;
        acd_error err;
        assert_int_equal(acd_exact2d_decompose(&polys[0], ACD_EXACT2D_MCD, &r, &err), ACD_OK);
        print_message("%s: %zu vertices, %zu notches, MCD %zu pieces in %.3f s\n", files[f], r.input_vertices,
                      r.input_notches, r.npieces, r.seconds);
        assert_int_equal(r.npieces, expect[f]);
        assert_true(p2_check_partition(&polys[0], &r));
        assert_int_equal(acd_exact2d_verify(&polys[0], &r, &err), ACD_OK);
        /* determinism */
        assert_int_equal(acd_exact2d_decompose(&polys[0], ACD_EXACT2D_MCD, &r2, &err), ACD_OK);
        assert_int_equal(r2.npieces, r.npieces);
        for (size_t i = 0; i < r.npieces; i++) {
            assert_int_equal(r.pieces[i].npoints, r2.pieces[i].npoints);
            assert_memory_equal(r.pieces[i].index, r2.pieces[i].index, r.pieces[i].npoints * sizeof(size_t));
        }
        /* a corrupted result does not verify */
        if (r.pieces[0].npoints >= 4) {
            acd_vec2 t = r.pieces[0].points[1];
            r.pieces[0].points[1] = r.pieces[0].points[2];
            r.pieces[0].points[2] = t;
            size_t ti = r.pieces[0].index[1];
            r.pieces[0].index[1] = r.pieces[0].index[2];
            r.pieces[0].index[2] = ti;
            assert_int_equal(acd_exact2d_verify(&polys[0], &r, &err), ACD_ERR_VERIFY);
        }
        r.pieces[0].index[0] = 999999999;
        assert_int_equal(acd_exact2d_verify(&polys[0], &r, &err), ACD_ERR_VERIFY);
        acd_exact2d_result_free(&r);
        acd_exact2d_result_free(&r2);
        acd_polygon_free(&polys[0]);
        tested++;
    }
    if (!tested) TU_SKIP("Lien's polygons not found under shared/data");
}

/* Every hole-free data polygon decomposes and verifies (the large stars are left to the bench). */
static void test_data_polygons(void **state) {
    (void)state;
    const char *files[] = {"BarbedThing", "batlogo", "bird", "dragon", "dsb", "egg", "simple1", "simple2",
                           "simple3", "simple4", "simple5", "simple7", "simple8", "star_star1", "star_star2",
                           "star_star3", "star_star2_noise", "star_star3_noise", "star_star4", "taiwan",
                           "wierd1", "wierd2", "wierd2_n"};
    char path[1024], rel[256];
    int tested = 0;
    for (size_t f = 0; f < sizeof files / sizeof *files; f++) {
        snprintf(rel, sizeof rel, "polygons-lien/%s.poly", files[f]);
        if (!tu_shared_data(path, sizeof path, rel)) continue;
        acd_polygon polys[4];
        int np = p2_read_poly(path, polys, 4);
        assert_true(np >= 1);
        for (int i = 0; i < np; i++) {
            acd_exact2d_result r, h;
            acd_error err;
            acd_status st = acd_exact2d_decompose(&polys[i], ACD_EXACT2D_MCD, &r, &err);
            if (st != ACD_OK) print_message("%s: %s\n", files[f], err.message);
            assert_int_equal(st, ACD_OK);
            if (!p2_check_partition(&polys[i], &r)) print_message("in %s (MCD)\n", files[f]);
            assert_true(p2_check_partition(&polys[i], &r));
            assert_int_equal(acd_exact2d_decompose(&polys[i], ACD_EXACT2D_HM, &h, &err), ACD_OK);
            assert_true(h.npieces >= r.npieces);
            assert_true(h.npieces <= 4 * r.npieces);
            /* Hertel-Mehlhorn keeps at most two essential diagonals per notch */
            assert_true(h.npieces <= 2 * h.input_notches + 1);
            acd_exact2d_result_free(&r);
            acd_exact2d_result_free(&h);
            acd_polygon_free(&polys[i]);
            tested++;
        }
    }
    if (!tested) TU_SKIP("Lien's polygons not found under shared/data");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_simple_cases),        cmocka_unit_test(test_brute_force_general),
        cmocka_unit_test(test_brute_force_collinear), cmocka_unit_test(test_holes_refused),
        cmocka_unit_test(test_dissertation_counts), cmocka_unit_test(test_data_polygons),
        cmocka_unit_test(test_invalid_ring_no_ub),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
