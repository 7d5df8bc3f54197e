/* Tests of geom2/triangulate: ear clipping with hole bridging.
 * Properties checked on every polygon: n + 2h - 2 triangles, indices in range, every triangle
 * counterclockwise (non-degenerate unless the input has collinear vertices), areas add up to the
 * polygon's area (1e-9 relative), every triangle's centroid strictly inside the polygon (exact
 * even-odd test), determinism. */
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/polygon.h"
#include "core/predicates.h"
#include "core/rng.h"
#include "geom2/triangulate.h"
#include "poly2_support.h"

/* Triangulates and checks; returns the number of degenerate triangles. */
static size_t check_triangulation(const acd_polygon *p, int expect_nondegenerate) {
    size_t *t = NULL, nt = 0, ndeg = 99;
    acd_error err;
    acd_status st = acd_triangulate_polygon(p, &t, &nt, &ndeg, &err);
    if (st != ACD_OK) print_message("triangulation failed: %s\n", err.message);
    assert_int_equal(st, ACD_OK);
    size_t n = acd_polygon_num_points(p), h = p->nrings - 1;
    assert_int_equal(nt, n + 2 * h - 2);
    double area = p2_region_area(p->points, p->ring_start, p->nrings), sum = 0, sumabs = 0;
    size_t deg = 0, stride = nt / 1500 + 1; /* centroid checks are O(n) each: sample big inputs */
    for (size_t i = 0; i < nt; i++) {
        for (int k = 0; k < 3; k++) assert_true(t[3 * i + k] < n);
        const double *a = V2(&p->points[t[3 * i]]), *b = V2(&p->points[t[3 * i + 1]]), *c = V2(&p->points[t[3 * i + 2]]);
        int o = acd_orient2d_sign(a, b, c);
        assert_true(o >= 0);
        if (o == 0) deg++;
        double ar = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
        sum += ar;
        sumabs += fabs(ar);
        if (o > 0 && ar > 1e-12 * area && i % stride == 0) {
            double q[2] = {(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3};
            if (!p2_point_inside(p->points, p->ring_start, p->nrings, q))
                print_message("triangle %zu (%zu %zu %zu) centroid (%g, %g) outside\n", i, t[3 * i], t[3 * i + 1],
                              t[3 * i + 2], q[0], q[1]);
            assert_true(p2_point_inside(p->points, p->ring_start, p->nrings, q));
        }
    }
    assert_int_equal(deg, ndeg);
    if (expect_nondegenerate) assert_int_equal(deg, 0);
    if (fabs(sum - area) > 1e-9 * fabs(area) || fabs(sumabs - area) > 1e-9 * fabs(area))
        print_message("area %.17g, triangles %.17g\n", area, sum);
    assert_true(fabs(sum - area) <= 1e-9 * fabs(area));
    assert_true(fabs(sumabs - area) <= 1e-9 * fabs(area));
    /* determinism */
    size_t *t2 = NULL, nt2 = 0;
    assert_int_equal(acd_triangulate_polygon(p, &t2, &nt2, NULL, NULL), ACD_OK);
    assert_int_equal(nt2, nt);
    assert_memory_equal(t, t2, 3 * nt * sizeof *t);
    free(t);
    free(t2);
    return deg;
}

static acd_polygon make(const acd_vec2 *const *rings, const size_t *sizes, size_t nrings) {
    acd_polygon p;
    assert_int_equal(acd_polygon_from_rings(&p, rings, sizes, nrings, NULL), ACD_OK);
    return p;
}

static void test_simple_shapes(void **state) {
    (void)state;
    acd_vec2 tri[] = {{0, 0}, {1, 0}, {0, 1}};
    acd_vec2 sq_cw[] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    acd_vec2 comb[] = {{0, 0}, {10, 0}, {10, 5}, {9, 5}, {9, 1}, {8, 1}, {8, 5}, {7, 5}, {7, 1}, {6, 1},
                       {6, 5}, {5, 5}, {5, 1}, {4, 1}, {4, 5}, {3, 5}, {3, 1}, {2, 1}, {2, 5}, {0, 5}};
    const acd_vec2 *r1[] = {tri}, *r2[] = {sq_cw}, *r3[] = {comb};
    size_t s1[] = {3}, s2[] = {4}, s3[] = {20};
    acd_polygon p = make(r1, s1, 1);
    check_triangulation(&p, 1);
    acd_polygon_free(&p);
    p = make(r2, s2, 1);
    check_triangulation(&p, 1);
    acd_polygon_free(&p);
    p = make(r3, s3, 1);
    check_triangulation(&p, 1);
    acd_polygon_free(&p);
}

/* Collinear vertices on the edges: degenerate triangles are allowed only where forced. */
static void test_collinear(void **state) {
    (void)state;
    acd_vec2 sq[] = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 1}, {3, 2}, {3, 3}, {2, 3}, {1, 3}, {0, 3}, {0, 2}, {0, 1}};
    const acd_vec2 *r[] = {sq};
    size_t s[] = {12};
    acd_polygon p = make(r, s, 1);
    check_triangulation(&p, 1);
    acd_polygon_free(&p);
    /* a triangle with many points on one edge: a fan from the apex, no degenerate triangle */
    acd_vec2 fan[12];
    for (int i = 0; i < 11; i++) fan[i] = (acd_vec2){i, 0};
    fan[11] = (acd_vec2){5, 7};
    const acd_vec2 *rf[] = {fan};
    size_t sf[] = {12};
    p = make(rf, sf, 1);
    check_triangulation(&p, 1);
    acd_polygon_free(&p);
}

/* Holes whose bridges meet vertices exactly: a grid of square holes (rightmost vertices aligned
 * in columns and rows, rays through vertices), and a hole level with outer vertices. */
static void test_hole_grid(void **state) {
    (void)state;
    enum { K = 6 };
    acd_vec2 outer[] = {{0, 0}, {2 * K + 1, 0}, {2 * K + 1, 2 * K + 1}, {0, 2 * K + 1}};
    acd_vec2 holes[K * K][4];
    const acd_vec2 *rings[1 + K * K];
    size_t sizes[1 + K * K];
    rings[0] = outer;
    sizes[0] = 4;
    for (int i = 0; i < K; i++)
        for (int j = 0; j < K; j++) {
            acd_vec2 *h = holes[i * K + j];
            double x = 1 + 2 * i, y = 1 + 2 * j;
            h[0] = (acd_vec2){x, y};
            h[1] = (acd_vec2){x, y + 1};
            h[2] = (acd_vec2){x + 1, y + 1};
            h[3] = (acd_vec2){x + 1, y};
            rings[1 + i * K + j] = h;
            sizes[1 + i * K + j] = 4;
        }
    acd_polygon p = make(rings, sizes, 1 + K * K);
    check_triangulation(&p, 1);
    acd_polygon_free(&p);
    /* diamond holes whose rightmost vertices lie on the rays of others */
    acd_vec2 o2[] = {{0, 0}, {10, 0}, {10, 2}, {10, 4}, {0, 4}};
    acd_vec2 d1[] = {{2, 2}, {3, 3}, {4, 2}, {3, 1}}, d2[] = {{5, 2}, {6, 3}, {7, 2}, {6, 1}};
    const acd_vec2 *r2[] = {o2, d1, d2};
    size_t s2[] = {5, 4, 4};
    p = make(r2, s2, 3);
    check_triangulation(&p, 1);
    acd_polygon_free(&p);
}

static void test_random_with_holes(void **state) {
    (void)state;
    acd_rng g;
    acd_rng_seed(&g, 12345);
    for (int it = 0; it < 300; it++) {
        acd_polygon p;
        size_t n = 3 + (size_t)acd_rng_below(&g, it < 200 ? 30 : 400);
        size_t h = (size_t)acd_rng_below(&g, it < 200 ? 5 : 40);
        assert_true(p2_random_polygon(&g, &p, n, h, it < 200 ? 8 : 30, 1));
        check_triangulation(&p, 0);
        acd_polygon_free(&p);
    }
}

static void test_lien_data(void **state) {
    (void)state;
    const char *files[] = {"BarbedThing", "batlogo", "bird", "dragon", "dsb", "egg", "hole1", "hole2", "hole3",
                           "hole4", "hole5", "nazca_nazca_heron", "nazca_nazca_monkey", "nazca_nazca_monkey_2",
                           "simple1", "simple2", "simple3", "simple4", "simple5", "simple7", "simple8",
                           "star_star1", "star_star3_noise", "star_star5_noise", "star_star6", "taiwan", "texas",
                           "torus1", "torus2", "wierd1", "wierd2", "wierd2_n"};
    char path[1024], rel[256];
    int tested = 0;
    for (size_t f = 0; f < sizeof files / sizeof *files; f++) {
        snprintf(rel, sizeof rel, "polygons-lien/%s.poly", files[f]);
        if (!tu_shared_data(path, sizeof path, rel)) continue;
        acd_polygon polys[16];
        int np = p2_read_poly(path, polys, 16);
        if (np < 0) {
            print_message("could not parse %s\n", path);
            fail();
        }
        for (int i = 0; i < np; i++) {
            size_t deg = check_triangulation(&polys[i], 0);
            if (deg) print_message("%s polygon %d: %zu zero-area triangles (collinear vertices)\n", files[f], i, deg);
            acd_polygon_free(&polys[i]);
            tested++;
        }
    }
    if (!tested) TU_SKIP("no polygons under shared/data/polygons-lien");
}

static void test_errors(void **state) {
    (void)state;
    acd_vec2 two[] = {{0, 0}, {1, 1}}, nan_pts[] = {{0, 0}, {1, 0}, {NAN, 1}};
    const acd_vec2 *r1[] = {two}, *r2[] = {nan_pts};
    size_t s1[] = {2}, s2[] = {3};
    acd_polygon p = make(r1, s1, 1);
    size_t *t, nt;
    acd_error err;
    assert_int_equal(acd_triangulate_polygon(&p, &t, &nt, NULL, &err), ACD_ERR_DEGENERATE);
    assert_null(t);
    acd_polygon_free(&p);
    p = make(r2, s2, 1);
    assert_int_equal(acd_triangulate_polygon(&p, &t, &nt, NULL, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "vertex 2"));
    acd_polygon_free(&p);
    /* a hole outside the outer ring: refused without best effort, triangles with it */
    acd_vec2 o[] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, hole[] = {{3, 0}, {3, 1}, {4, 1}, {4, 0}};
    const acd_vec2 *r3[] = {o, hole};
    size_t s3[] = {4, 4};
    p = make(r3, s3, 2);
    acd_status st = acd_triangulate_polygon(&p, &t, &nt, NULL, &err);
    if (st == ACD_OK) free(t);
    else assert_int_equal(st, ACD_ERR_INVALID_INPUT);
    size_t forced = 0;
    assert_int_equal(acd_triangulate_rings(p.points, p.ring_start, p.nrings, ACD_TRI_BEST_EFFORT, &t, &nt, NULL,
                                           &forced, &err),
                     ACD_OK);
    assert_int_equal(nt, 8 + 2 - 2);
    free(t);
    acd_polygon_free(&p);
    /* a bow tie (self-crossing): terminates either way */
    acd_vec2 bow[] = {{0, 0}, {2, 2}, {2, 0}, {0, 2}};
    const acd_vec2 *r4[] = {bow};
    size_t s4[] = {4};
    p = make(r4, s4, 1);
    assert_int_equal(acd_triangulate_rings(p.points, p.ring_start, p.nrings, ACD_TRI_BEST_EFFORT, &t, &nt, NULL,
                                           &forced, &err),
                     ACD_OK);
    assert_int_equal(nt, 2);
    free(t);
    st = acd_triangulate_polygon(&p, &t, &nt, NULL, &err);
    if (st == ACD_OK) free(t);
    acd_polygon_free(&p);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_simple_shapes),     cmocka_unit_test(test_collinear),
        cmocka_unit_test(test_hole_grid),         cmocka_unit_test(test_random_with_holes),
        cmocka_unit_test(test_lien_data),         cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
