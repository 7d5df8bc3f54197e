/* Tests of geom2/polygon: construction, copy and area of polygons with holes. */
#include "testutil.h"

#include "acd/polygon.h"

static void test_area_with_hole(void **state) {
    (void)state;
    acd_vec2 outer[] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    acd_vec2 hole[] = {{2, 2}, {2, 4}, {4, 4}, {4, 2}}; /* clockwise */
    const acd_vec2 *rings[] = {outer, hole};
    size_t sizes[] = {4, 4};
    acd_polygon p, q;
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(&p, rings, sizes, 2, &err), ACD_OK);
    assert_int_equal(p.nrings, 2);
    assert_int_equal(acd_polygon_ring_size(&p, 1), 4);
    assert_true(acd_polygon_area(&p) == 96.0);
    assert_int_equal(acd_polygon_copy(&q, &p), ACD_OK);
    assert_true(acd_polygon_area(&q) == 96.0);
    assert_true(acd_polygon_ring(&q, 1)[2].x == 4.0);
    acd_polygon_free(&p);
    acd_polygon_free(&q);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_area_with_hole)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
