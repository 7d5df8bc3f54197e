/* The real 2D polygons fetched by scripts/fetch-data.sh into data/2d (docs/data.md): CGAL's
 * Straight_skeleton_2 samples (converted by scripts/cgal_pwh_to_poly.py) and DejaVu Sans glyphs
 * with holes (scripts/ttf_glyph_to_poly.py) read, validate with the expected vertex and hole
 * counts, and decompose exactly (Hertel-Mehlhorn; MCD without holes, MCD <= HM) and by ACD at
 * tau = 0, every result passing its verifier. Skips with a message when data/2d is absent. */
#include "testutil.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "acd/acd2d.h"
#include "acd/exact2d.h"
#include "acd/polygon.h"
#include "acd/verify2d.h"

static const struct {
    const char *file;
    size_t vertices, holes;
} FILES[] = {
    {"cgal/straight_skeleton_sample_1.poly", 1766, 20}, {"cgal/straight_skeleton_sample_2.poly", 1024, 11},
    {"cgal/straight_skeleton_sample_3.poly", 993, 0},   {"cgal/straight_skeleton_sample_4.poly", 639, 2},
    {"glyphs/dejavu-sans-B.poly", 77, 2},               {"glyphs/dejavu-sans-8.poly", 136, 2},
    {"glyphs/dejavu-sans-at.poly", 177, 1},             {"glyphs/dejavu-sans-g.poly", 97, 1},
};

static void test_real_polygons(void **state) {
    (void)state;
    size_t done = 0;
    for (size_t k = 0; k < sizeof FILES / sizeof FILES[0]; k++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/data/2d/%s", ACD_SOURCE_DIR, FILES[k].file);
        if (access(path, R_OK) != 0) continue;
        acd_polygon_set s;
        acd_error err;
        if (acd_polygon_set_read_file(&s, path, ACD_POLY_FORMAT_AUTO, NULL, &err) != ACD_OK)
            fail_msg("%s: %s", FILES[k].file, err.message);
        assert_int_equal(s.count, 1);
        const acd_polygon *p = &s.polygons[0];
        if (acd_polygon_validate(p, 0, &err) != ACD_OK) fail_msg("%s: %s", FILES[k].file, err.message);
        assert_int_equal(acd_polygon_num_points(p), FILES[k].vertices);
        assert_int_equal(p->nrings - 1, FILES[k].holes);
        acd_exact2d_result hm, mcd;
        if (acd_exact2d_decompose(p, ACD_EXACT2D_HM, &hm, &err) != ACD_OK) fail_msg("%s HM: %s", FILES[k].file, err.message);
        assert_int_equal(acd_exact2d_verify(p, &hm, &err), ACD_OK);
        if (FILES[k].holes == 0) {
            if (acd_exact2d_decompose(p, ACD_EXACT2D_MCD, &mcd, &err) != ACD_OK)
                fail_msg("%s MCD: %s", FILES[k].file, err.message);
            assert_int_equal(acd_exact2d_verify(p, &mcd, &err), ACD_OK);
            assert_true(mcd.npieces <= hm.npieces && hm.npieces <= 4 * mcd.npieces);
            acd_exact2d_result_free(&mcd);
        } else {
            assert_int_equal(acd_exact2d_decompose(p, ACD_EXACT2D_MCD, &mcd, &err), ACD_ERR_UNSUPPORTED);
        }
        acd2d_params prm = acd2d_default_params();
        acd2d_result res;
        if (acd2d_decompose(p, &prm, &res, &err) != ACD_OK) fail_msg("%s ACD: %s", FILES[k].file, err.message);
        acd_verify2d_report rep;
        if (acd_verify2d_result(p, &res, &prm, 0, &rep, &err) != ACD_OK) fail_msg("%s ACD verify: %s", FILES[k].file, err.message);
        /* at tau = 0 the components are convex: at least one per hole plus one */
        assert_true(res.ncomponents >= FILES[k].holes + 1);
        acd2d_result_free(&res);
        acd_exact2d_result_free(&hm);
        acd_polygon_set_free(&s);
        done++;
    }
    if (!done) TU_SKIP("data/2d not fetched (scripts/fetch-data.sh)");
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_real_polygons)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
