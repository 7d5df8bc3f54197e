/* Stress tests of acd2d on degenerate inputs: integer skylines (many collinear vertices, equal
 * coordinates, axis-parallel cuts), square holes on a grid (holes aligned with each other and
 * with notches), every measure, both cut modes, exact and default notch tests. Every run must
 * succeed and give simple counterclockwise pieces whose areas add up and whose concavity is
 * within tau. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>

#include "acd/acd2d.h"
#include "acd2d_check.h"
#include "core/rng.h"

/* two-sided skyline over x = 0..w: top heights in [1, 6], bottom depths in [-6, -1] */
static acd_polygon skyline(acd_rng *rng, int w, int holes) {
    acd_vec2 *p = malloc((size_t)(4 * w + 8) * sizeof *p);
    int *top = malloc((size_t)w * sizeof *top), *bot = malloc((size_t)w * sizeof *bot);
    assert_non_null(p);
    for (int i = 0; i < w; i++) {
        top[i] = 1 + (int)acd_rng_below(rng, 6);
        bot[i] = -1 - (int)acd_rng_below(rng, 6);
    }
    size_t n = 0;
    for (int i = 0; i < w; i++) { /* bottom, left to right */
        p[n++] = (acd_vec2){i, bot[i]};
        p[n++] = (acd_vec2){i + 1, bot[i]};
    }
    for (int i = w - 1; i >= 0; i--) { /* top, right to left */
        p[n++] = (acd_vec2){i + 1, top[i]};
        p[n++] = (acd_vec2){i, top[i]};
    }
    /* drop consecutive duplicates (equal heights make repeated points) */
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (k == 0 || p[i].x != p[k - 1].x || p[i].y != p[k - 1].y) p[k++] = p[i];
    while (k > 1 && p[k - 1].x == p[0].x && p[k - 1].y == p[0].y) k--;
    acd_vec2 *rings_store[64];
    const acd_vec2 *rings[64];
    size_t sizes[64], nr = 0;
    rings[nr] = p;
    sizes[nr++] = k;
    for (int i = 0; i < w && nr < 60; i++) {
        if (!holes || acd_rng_below(rng, 3) != 0) continue;
        /* a square hole in column i, at y in [0.25, 0.75] (always inside: top >= 1, bottom <= -1) */
        acd_vec2 *h = malloc(4 * sizeof *h);
        double s = acd_rng_below(rng, 2) ? 0.25 : 0.5;
        h[0] = (acd_vec2){i + 0.25, 0.25};
        h[1] = (acd_vec2){i + 0.25, 0.25 + s};
        h[2] = (acd_vec2){i + 0.75, 0.25 + s};
        h[3] = (acd_vec2){i + 0.75, 0.25};
        rings_store[nr] = h;
        rings[nr] = h;
        sizes[nr++] = 4;
    }
    acd_polygon poly;
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(&poly, rings, sizes, nr, &err), ACD_OK);
    for (size_t r = 1; r < nr; r++) free(rings_store[r]);
    free(p);
    free(top);
    free(bot);
    return poly;
}

static void run_all(const acd_polygon *poly, const char *what) {
    double area = acd_polygon_area(poly);
    const double taus[] = {0, 0.3, 2, 50};
    for (int m = 0; m < 4; m++)
        for (int cut = 0; cut < 2; cut++)
            for (int tol = 0; tol < 2; tol++)
                for (int t = 0; t < 4; t++) {
                    acd2d_params prm = acd2d_default_params();
                    prm.measure = (acd2d_measure)m;
                    prm.cut = (acd2d_cut)cut;
                    prm.notch_tolerance = tol ? 1e-5 : 0;
                    prm.tau = taus[t];
                    acd2d_result res;
                    acd_error err;
                    acd_status st = acd2d_decompose(poly, &prm, &res, &err);
                    if (st != ACD_OK)
                        print_message("%s m%d cut%d tol%d tau %g: %s\n", what, m, cut, tol, taus[t], err.message);
                    assert_int_equal(st, ACD_OK);
                    if (ck_result(&res, &prm, area, 1)) {
                        print_message("%s m%d cut%d tol%d tau %g failed\n", what, m, cut, tol, taus[t]);
                        fail();
                    }
                    acd2d_result_free(&res);
                }
}

static void test_skylines(void **state) {
    (void)state;
    acd_rng rng;
    acd_rng_seed(&rng, 2024);
    for (int i = 0; i < 12; i++) {
        acd_polygon p = skyline(&rng, 3 + i, 0);
        run_all(&p, "skyline");
        acd_polygon_free(&p);
    }
}

static void test_skylines_with_holes(void **state) {
    (void)state;
    acd_rng rng;
    acd_rng_seed(&rng, 77);
    for (int i = 0; i < 12; i++) {
        acd_polygon p = skyline(&rng, 3 + i, 1);
        run_all(&p, "skyline+holes");
        acd_polygon_free(&p);
    }
}

/* far from the origin and rotated: coordinates are no longer integers, rounding everywhere */
static void test_rotated_far(void **state) {
    (void)state;
    acd_rng rng;
    acd_rng_seed(&rng, 5);
    for (int i = 0; i < 8; i++) {
        acd_polygon p = skyline(&rng, 4 + i, 1);
        double a = 0.3 + 0.1 * i, c = cos(a), s = sin(a);
        size_t np = acd_polygon_num_points(&p);
        for (size_t k = 0; k < np; k++) {
            double x = p.points[k].x, y = p.points[k].y;
            p.points[k].x = 1e6 + c * x - s * y;
            p.points[k].y = -3e5 + s * x + c * y;
        }
        run_all(&p, "rotated");
        acd_polygon_free(&p);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_skylines), cmocka_unit_test(test_skylines_with_holes),
                                       cmocka_unit_test(test_rotated_far)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
