/* Tests of Hertel-Mehlhorn (acd2/exact_hm through include/acd/exact2d.h): partitions of random
 * polygons with holes and of the data polygons (convex pieces of input vertices, areas adding up,
 * no overlap), the piece/diagonal count identity, HM within 4 times MCD, determinism. */
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/exact2d.h"
#include "core/rng.h"
#include "poly2_support.h"

static size_t hm_check(const acd_polygon *p, size_t *mcd_out) {
    acd_exact2d_result r, r2;
    acd_error err;
    acd_status st = acd_exact2d_decompose(p, ACD_EXACT2D_HM, &r, &err);
    if (st != ACD_OK) print_message("HM failed: %s\n", err.message);
    assert_int_equal(st, ACD_OK);
    assert_true(p2_check_partition(p, &r));
    size_t h = p->nrings - 1, n = acd_polygon_num_points(p);
    /* cutting a polygon with h holes along d diagonals into k pieces: k = d - h + 1 */
    assert_int_equal(r.npieces + h, r.ndiagonals + 1);
    assert_true(r.npieces <= n + 2 * h - 2);
    assert_int_equal(r.input_holes, h);
    assert_int_equal(acd_exact2d_decompose(p, ACD_EXACT2D_HM, &r2, &err), ACD_OK);
    assert_int_equal(r2.npieces, r.npieces);
    for (size_t i = 0; i < r.npieces; i++)
        assert_memory_equal(r.pieces[i].index, r2.pieces[i].index, r.pieces[i].npoints * sizeof(size_t));
    if (mcd_out && h == 0) {
        acd_exact2d_result m;
        assert_int_equal(acd_exact2d_decompose(p, ACD_EXACT2D_MCD, &m, &err), ACD_OK);
        assert_true(m.npieces <= r.npieces);
        assert_true(r.npieces <= 4 * m.npieces);
        *mcd_out = m.npieces;
        acd_exact2d_result_free(&m);
    }
    size_t k = r.npieces;
    acd_exact2d_result_free(&r);
    acd_exact2d_result_free(&r2);
    return k;
}

static void test_random_with_holes(void **state) {
    (void)state;
    acd_rng g;
    acd_rng_seed(&g, 99);
    for (int it = 0; it < 200; it++) {
        acd_polygon p;
        size_t n = 3 + (size_t)acd_rng_below(&g, it < 100 ? 20 : 200);
        size_t h = it % 3 == 0 ? 0 : (size_t)acd_rng_below(&g, 12);
        assert_true(p2_random_polygon(&g, &p, n, h, 10, 1));
        size_t mcd = 0;
        hm_check(&p, &mcd);
        acd_polygon_free(&p);
    }
}

/* A square with a square hole: 4 convex pieces are necessary; HM finds at least that. */
static void test_square_ring(void **state) {
    (void)state;
    acd_vec2 o[] = {{0, 0}, {3, 0}, {3, 3}, {0, 3}}, h[] = {{1, 1}, {1, 2}, {2, 2}, {2, 1}};
    const acd_vec2 *rings[] = {o, h};
    size_t sz[] = {4, 4};
    acd_polygon p;
    assert_int_equal(acd_polygon_from_rings(&p, rings, sz, 2, NULL), ACD_OK);
    size_t k = hm_check(&p, NULL);
    assert_true(k >= 4 && k <= 8);
    acd_polygon_free(&p);
    /* a convex polygon stays one piece */
    acd_vec2 hex[] = {{2, 0}, {1, 2}, {-1, 2}, {-2, 0}, {-1, -2}, {1, -2}};
    const acd_vec2 *r1[] = {hex};
    size_t s1[] = {6};
    assert_int_equal(acd_polygon_from_rings(&p, r1, s1, 1, NULL), ACD_OK);
    assert_int_equal(hm_check(&p, NULL), 1);
    acd_polygon_free(&p);
}

static void test_data_polygons(void **state) {
    (void)state;
    const char *files[] = {"BarbedThing", "batlogo", "bird", "dragon", "hole1", "hole2", "hole3", "hole4", "hole5",
                           "nazca_nazca_monkey", "nazca_nazca_heron", "nazca_nazca_monkey_2", "star_star6",
                           "star_star5_noise", "taiwan", "texas", "torus1", "torus2", "wierd2", "wierd2_n"};
    char path[1024], rel[256];
    int tested = 0;
    for (size_t f = 0; f < sizeof files / sizeof *files; f++) {
        snprintf(rel, sizeof rel, "polygons-lien/%s.poly", files[f]);
        if (!tu_shared_data(path, sizeof path, rel)) continue;
        acd_polygon polys[4];
        int np = p2_read_poly(path, polys, 4);
        assert_true(np >= 1);
        for (int i = 0; i < np; i++) {
            int small = acd_polygon_num_points(&polys[i]) <= 1500;
            size_t mcd = 0, k = hm_check(&polys[i], small ? &mcd : NULL);
            print_message("%s: HM %zu pieces%s", files[f], k, small && mcd ? "" : "\n");
            if (small && mcd) print_message(", MCD %zu\n", mcd);
            acd_polygon_free(&polys[i]);
            tested++;
        }
    }
    if (!tested) TU_SKIP("Lien's polygons not found under shared/data");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_square_ring),
        cmocka_unit_test(test_random_with_holes),
        cmocka_unit_test(test_data_polygons),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
