/* Tests of geom3/hull_simplify: the result has at most N vertices and encloses every input point
 * (sphere and torus point sets, several budgets); small hulls come back unchanged; bad budgets and
 * flat input are refused. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>

#include "core/rng.h"
#include "core/tolerance.h"
#include "geom3/hull_simplify.h"
#include "meshgen.h"

static void check_encloses(const double *pts, size_t n, size_t budget) {
    acd_hull full, s;
    assert_int_equal(acd_hull_compute(pts, n, &full, NULL), ACD_OK);
    acd_error err;
    acd_status st = acd_hull_simplify(pts, n, budget, &s, &err);
    if (st != ACD_OK) print_message("budget %zu: %s\n", budget, err.message);
    assert_int_equal(st, ACD_OK);
    assert_int_equal(s.dim, 3);
    assert_true(s.nvertices <= budget);
    acd_scale sc = acd_scale_of_points(pts, n, 3);
    for (size_t i = 0; i < n; i++) assert_true(acd_hull_plane_distance(&s, pts + 3 * i) <= sc.dist);
    assert_true(s.volume >= full.volume * (1 - 1e-12));
    if (full.nvertices <= budget) assert_int_equal(s.nvertices, full.nvertices);
    acd_hull_free(&full);
    acd_hull_free(&s);
}

static void test_sphere_points(void **state) {
    (void)state;
    size_t n = 2000;
    double *p = malloc(3 * n * sizeof(double));
    assert_non_null(p);
    acd_rng r;
    acd_rng_seed(&r, 4);
    for (size_t i = 0; i < n; i++) {
        double z = 2 * acd_rng_uniform(&r) - 1, a = 6.283185307179586 * acd_rng_uniform(&r), s = sqrt(1 - z * z);
        p[3 * i] = 3 * s * cos(a) + 10;
        p[3 * i + 1] = s * sin(a);
        p[3 * i + 2] = 0.5 * z;
    }
    size_t budgets[] = {4, 5, 8, 16, 32, 64, 5000};
    for (size_t b = 0; b < sizeof budgets / sizeof *budgets; b++) check_encloses(p, n, budgets[b]);
    free(p);
}

static void test_torus_and_box(void **state) {
    (void)state;
    tm_mesh t = tm_torus(1.0, 0.3, 40, 16);
    check_encloses(t.v, t.nv, 12);
    check_encloses(t.v, t.nv, 24);
    tm_free(&t);
    double lo[3] = {0, 0, 0}, hi[3] = {2, 1, 1e-3};
    tm_mesh b = tm_box(lo, hi);
    check_encloses(b.v, b.nv, 8);
    check_encloses(b.v, b.nv, 6);
    check_encloses(b.v, b.nv, 4);
    tm_free(&b);
}

static void test_refusals(void **state) {
    (void)state;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    tm_mesh b = tm_box(lo, hi);
    acd_hull s;
    acd_error err;
    assert_int_equal(acd_hull_simplify(b.v, b.nv, 3, &s, &err), ACD_ERR_INVALID_ARGUMENT);
    /* a flat octagon cannot be cut to 4 vertices here */
    double oct[24];
    for (int i = 0; i < 8; i++) {
        oct[3 * i] = cos(i * 0.785398);
        oct[3 * i + 1] = sin(i * 0.785398);
        oct[3 * i + 2] = 0;
    }
    assert_int_equal(acd_hull_simplify(oct, 8, 4, &s, &err), ACD_ERR_UNSUPPORTED);
    assert_int_equal(acd_hull_simplify(oct, 8, 8, &s, &err), ACD_OK);
    assert_int_equal(s.dim, 2);
    acd_hull_free(&s);
    tm_free(&b);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sphere_points),
        cmocka_unit_test(test_torus_and_box),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
