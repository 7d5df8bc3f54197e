/* Tests of acd3/region_cut: a plane cut restricted to one section region glues the other
 * regions back into closed pieces that conserve volume. */
#include "testutil.h"

#include <math.h>

#include "acd3/region_cut.h"
#include "geom3/edge_map.h"
#include "geom3/plane_cut.h"
#include "shapes.h"

static void check_closed(const acd_mesh *m) {
    acd_edge_map em;
    acd_error err;
    assert_int_equal(acd_edge_map_build(m->triangles, m->ntriangles, NULL, &em, &err), ACD_OK);
    assert_int_equal(acd_edge_map_check_closed(&em, m->triangles, m->ntriangles, &err), ACD_OK);
    acd_edge_map_free(&em);
}

static void test_u_shape_cut_through_one_prong(void **state) {
    (void)state;
    /* a U of voxels, 3 wide, 1 deep, 3 tall: base row full, prongs at x = 0 and x = 2 */
    unsigned char occ[9];
    for (int z = 0; z < 3; z++)
        for (int x = 0; x < 3; x++) occ[z * 3 + x] = z == 0 || x != 1;
    acd_mesh m;
    assert_true(mg_voxels(&m, occ, 3, 1, 3));
    double vol = mg_volume(&m);
    assert_true(fabs(vol - 7.0) < 1e-12);
    double p[3] = {0.5, 0.5, 1.5}, n[3] = {0, 0, 1};
    acd_cut_plane pl;
    acd_error err;
    assert_int_equal(acd_cut_plane_from_normal(p, n, 10, &pl, &err), ACD_OK);
    acd_cut_result cut;
    assert_int_equal(acd_plane_cut(&m, &pl, &cut, &err), ACD_OK);
    assert_int_equal(cut.npieces, 3); /* both prong tops come off */
    assert_int_equal(acd3_restrict_cut(&cut, p, &err), ACD_OK);
    assert_int_equal(cut.npieces, 2); /* only the prong at x = 0 is cut */
    double sum = 0, small = INFINITY;
    for (size_t i = 0; i < cut.npieces; i++) {
        check_closed(&cut.pieces[i].mesh);
        double v = mg_volume(&cut.pieces[i].mesh);
        sum += v;
        if (v < small) small = v;
    }
    assert_true(fabs(sum - vol) < 1e-12 * vol);
    assert_true(fabs(small - 1.5) < 1e-12); /* the top half of the cut prong */
    acd_cut_result_free(&cut);
    acd_mesh_free(&m);
}

static void test_single_region_unchanged(void **state) {
    (void)state;
    unsigned char occ[8] = {1, 1, 1, 1, 1, 1, 1, 1};
    acd_mesh m;
    assert_true(mg_voxels(&m, occ, 2, 2, 2));
    double p[3] = {1, 1, 1}, n[3] = {1, 0.2, 0.1};
    acd_cut_plane pl;
    acd_error err;
    assert_int_equal(acd_cut_plane_from_normal(p, n, 10, &pl, &err), ACD_OK);
    acd_cut_result cut;
    assert_int_equal(acd_plane_cut(&m, &pl, &cut, &err), ACD_OK);
    assert_int_equal(cut.npieces, 2);
    assert_int_equal(acd3_restrict_cut(&cut, p, &err), ACD_OK);
    assert_int_equal(cut.npieces, 2);
    acd_cut_result_free(&cut);
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_u_shape_cut_through_one_prong),
        cmocka_unit_test(test_single_region_unchanged),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
