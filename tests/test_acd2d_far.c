/* acd2d far from the origin (docs/acd2d.md "Far from the origin"): the dissertation's polygons
 * translated by up to 1e10 times their extent must decompose into components that tile the
 * input as acd_verify2d checks it (cut ends shared exactly between the pieces), for every
 * measure, at tau 0 and 0.05, through the hole merges and in the hierarchy readouts; a polygon
 * whose coordinates cannot resolve its features is refused (ACD_ERR_DEGENERATE) instead of
 * decomposed into overlapping pieces. Near the origin no cut end is shared (outputs unchanged).
 *
 * Before the fix BarbedThing + 1e9 (the lead's repro) gave components 9 and 14 overlapping by
 * 3.7e-8 at a cut end rounded off an earlier cut, and --verify exited 3. */
// ctest: TIMEOUT 120
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd2d.h"
#include "acd/verify2d.h"

static int load(const char *rel, acd_polygon *out) {
    char buf[1024];
    const char *path = tu_shared_data(buf, sizeof buf, rel);
    if (!path) return 0;
    acd_polygon_set s;
    acd_error err;
    assert_int_equal(acd_polygon_set_read_file(&s, path, ACD_POLY_FORMAT_AUTO, NULL, &err), ACD_OK);
    assert_true(s.count >= 1);
    assert_int_equal(acd_polygon_copy(out, &s.polygons[0]), ACD_OK);
    acd_polygon_set_free(&s);
    return 1;
}

static double extent(const acd_polygon *p) {
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (size_t i = 0; i < acd_polygon_num_points(p); i++) {
        x0 = fmin(x0, p->points[i].x);
        x1 = fmax(x1, p->points[i].x);
        y0 = fmin(y0, p->points[i].y);
        y1 = fmax(y1, p->points[i].y);
    }
    return hypot(x1 - x0, y1 - y0);
}

/* x + d, y + d (what a user's georeferenced copy looks like) */
static void translate(acd_polygon *p, double d) {
    for (size_t i = 0; i < acd_polygon_num_points(p); i++) {
        p->points[i].x += d;
        p->points[i].y += d;
    }
}

static int count_shared(const acd2d_result *res) {
    int k = 0;
    for (size_t i = 0; i < res->nnodes; i++) k += res->nodes[i].cut_new_point == 2;
    return k;
}

/* every measure at tau 0 and 0.05 and at tau 0 with exact notches (both cut modes): verified; readouts at coarser tau verified;
 * returns the number of shared cut ends over all runs */
static int run_verified(const acd_polygon *p, const char *what) {
    int shared = 0;
    const double taus[] = {0, 0.05, 0};
    for (int m = 0; m < 4; m++)
        for (int cut = 0; cut < 2; cut++)
            for (int t = 0; t < 3; t++) {
                acd2d_params prm = acd2d_default_params();
                prm.measure = (acd2d_measure)m;
                prm.cut = (acd2d_cut)cut;
                prm.tau = taus[t];
                if (t == 2) prm.notch_tolerance = 0; /* exact notches: a shared point's kink is none */
                acd2d_result res;
                acd_error err;
                acd_status st = acd2d_decompose(p, &prm, &res, &err);
                if (st != ACD_OK) print_message("%s m%d cut%d tau %g: %s\n", what, m, cut, taus[t], err.message);
                assert_int_equal(st, ACD_OK);
                st = acd_verify2d_result(p, &res, &prm, 0, NULL, &err);
                if (st != ACD_OK) print_message("%s m%d cut%d tau %g: %s\n", what, m, cut, taus[t], err.message);
                assert_int_equal(st, ACD_OK);
                shared += count_shared(&res);
                /* hierarchy readouts: the frontier's nodes tile the input too */
                const double t2s[] = {0.05, 0.5, 2};
                for (int k = 0; k < 3 && m != ACD2D_MEASURE_H2; k++) { /* H2's readout is not a fresh run */
                    acd2d_result lod;
                    assert_int_equal(acd2d_result_at_tau(&res, t2s[k], &lod, &err), ACD_OK);
                    acd2d_params p2 = prm;
                    p2.tau = t2s[k];
                    lod.measure = res.measure;
                    st = acd_verify2d_result(p, &lod, &p2, 0, NULL, &err);
                    if (st != ACD_OK)
                        print_message("%s m%d cut%d tau %g readout %g: %s\n", what, m, cut, taus[t], t2s[k],
                                      err.message);
                    assert_int_equal(st, ACD_OK);
                    acd2d_result_free(&lod);
                }
                acd2d_result_free(&res);
            }
    return shared;
}

/* the lead's repro: BarbedThing + 1e9, and the dissertation's models at 1e8 and 1e10 extents */
static void test_translated_models(void **state) {
    (void)state;
    const char *models[] = {"polygons-lien/BarbedThing.poly", "polygons-lien/dsb.poly", "polygons-lien/bird.poly",
                            "polygons-lien/hole3.poly", "polygons-lien/torus2.poly"};
    int any = 0;
    for (size_t i = 0; i < sizeof models / sizeof *models; i++) {
        acd_polygon p;
        if (!load(models[i], &p)) continue;
        any = 1;
        /* near the origin: no cut end needs sharing, the outputs are those of before */
        assert_int_equal(run_verified(&p, models[i]), 0);
        double ext = extent(&p);
        const double offs[] = {1e9, 1e8 * ext, 1e10 * ext};
        int shared = 0;
        for (int k = 0; k < 3; k++) {
            if (k == 0 && i != 0) continue;
            acd_polygon q;
            assert_int_equal(acd_polygon_copy(&q, &p), ACD_OK);
            translate(&q, offs[k]);
            char what[160];
            snprintf(what, sizeof what, "%s + %g", models[i], offs[k]);
            shared += run_verified(&q, what);
            acd_polygon_free(&q);
        }
        /* the fix is exercised: some cut end was rounded off an earlier cut and shared */
        if (i == 0) assert_true(shared > 0);
        acd_polygon_free(&p);
    }
    if (!any) TU_SKIP("shared polygons-lien data missing");
}

/* a polygon too far out for its features: refused with the vertex and the ratio named */
static void test_refused_when_unresolved(void **state) {
    (void)state;
    /* a slanted notch 0.01 deep in a unit square: at 1e13 the spacing of doubles is 0.002 */
    const acd_vec2 ring[] = {{0, 0}, {1, 0}, {1, 1}, {0.51, 1}, {0.5, 0.99}, {0.49, 1}, {0, 1}};
    const acd_vec2 *rings[1] = {ring};
    size_t sizes[1] = {7};
    acd_polygon p;
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(&p, rings, sizes, 1, &err), ACD_OK);
    acd2d_params prm = acd2d_default_params();
    acd2d_result res;
    assert_int_equal(acd2d_decompose(&p, &prm, &res, &err), ACD_OK);
    acd2d_result_free(&res);
    translate(&p, 1e13);
    assert_int_equal(acd2d_decompose(&p, &prm, &res, &err), ACD_ERR_DEGENERATE);
    assert_non_null(strstr(err.message, "cannot resolve"));
    assert_non_null(strstr(err.message, "times the polygon's extent"));
    assert_null(res.components);
    acd_polygon_free(&p);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_translated_models),
                                       cmocka_unit_test(test_refused_when_unresolved)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
