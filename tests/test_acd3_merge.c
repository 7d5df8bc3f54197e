/* Tests of the merge pass's choice by volume (acd3/merge with acd3_merge_opts.by_volume): the pair
 * whose joint hull adds the least volume first, among the joinable ones — its d_out is bounded only
 * when it comes up (lazily), so a cheaper pair refused by d_out must give way to the next. Two
 * voxel slabs (thickness 1: every vertex lies on the joint hulls' top or bottom facet, d_in = 0):
 * an L of bars (3 cells and 2) whose hull adds 2 but reaches 1 out of the L (the middle of its
 * diagonal facet), and a step of two bars of 10 cells offset by 3 whose hull adds 3 and reaches
 * 0.75 out (3/4 of the way along each slanted facet). With tau 0.9 only the step may be joined. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "acd3/merge.h"
#include "shapes.h"

enum { NX = 14, NY = 12 };

static void cells(acd_mesh *m, const int (*xy)[2], int n) {
    unsigned char occ[NX * NY];
    memset(occ, 0, sizeof occ);
    for (int i = 0; i < n; i++) occ[xy[i][1] * NX + xy[i][0]] = 1;
    assert_true(mg_voxels(m, occ, NX, NY, 1));
}

/* Cells x0..x1 (inclusive) of row y. */
static int row(int (*xy)[2], int x0, int x1, int y) {
    int n = 0;
    for (int x = x0; x <= x1; x++) xy[n][0] = x, xy[n][1] = y, n++;
    return n;
}

static void test_volume_order_skips_refused(void **state) {
    (void)state;
    int xy[64][2], n = 0;
    acd_mesh parts[4], in;
    /* L: A = row 0, x 0..2; B = column 0, y 1..2 */
    n = row(xy, 0, 2, 0);
    cells(&parts[0], (const int(*)[2])xy, n);
    xy[0][0] = 0, xy[0][1] = 1, xy[1][0] = 0, xy[1][1] = 2;
    cells(&parts[1], (const int(*)[2])xy, 2);
    /* step: C = row 8, x 0..9; D = row 9, x 3..12 */
    n = row(xy, 0, 9, 8);
    cells(&parts[2], (const int(*)[2])xy, n);
    n = row(xy, 3, 12, 9);
    cells(&parts[3], (const int(*)[2])xy, n);
    /* the input: all of them */
    n = row(xy, 0, 2, 0);
    xy[n][0] = 0, xy[n][1] = 1, n++;
    xy[n][0] = 0, xy[n][1] = 2, n++;
    n += row(xy + n, 0, 9, 8);
    n += row(xy + n, 3, 12, 9);
    cells(&in, (const int(*)[2])xy, n);
    const double tau = 0.9, tol = 1e-9;
    acd_error err;
    /* the costs: the L's joint hull adds 2, the step's 3 */
    acd3_merge_opts mo = {1, 3, 0};
    acd3_merge_result r[2];
    const int threads[2] = {1, 2};
    for (int t = 0; t < 2; t++) {
        assert_int_equal(acd3_merge_adjacent(&in, parts, 4, tau, tol, &mo, threads[t], &r[t], &err), ACD_OK);
        assert_int_equal(r[t].ngroups, 3);
        assert_int_equal(r[t].merges, 1);
        assert_true(r[t].group_of[0] != r[t].group_of[1]); /* the L: refused (reaches 1 > tau) */
        assert_int_equal(r[t].group_of[2], r[t].group_of[3]); /* the step joined */
        double b = r[t].bound[r[t].group_of[2]];
        assert_true(b >= 0.75 - 1e-9 && b <= tau); /* an upper bound of the step's reach */
    }
    assert_memory_equal(r[0].group_of, r[1].group_of, 4 * sizeof *r[0].group_of);
    /* without a stop: still only the step (the L is never joinable) */
    mo.stop_at = 0;
    acd3_merge_result all;
    assert_int_equal(acd3_merge_adjacent(&in, parts, 4, tau, tol, &mo, 1, &all, &err), ACD_OK);
    assert_int_equal(all.ngroups, 3);
    assert_true(all.group_of[0] != all.group_of[1]);
    /* with a tolerance above the L's reach both are joined, the L first (cheaper) */
    mo.stop_at = 3;
    acd3_merge_result wide;
    assert_int_equal(acd3_merge_adjacent(&in, parts, 4, 1.5, tol, &mo, 1, &wide, &err), ACD_OK);
    assert_int_equal(wide.ngroups, 3);
    assert_int_equal(wide.group_of[0], wide.group_of[1]);
    assert_true(wide.group_of[2] != wide.group_of[3]);
    acd3_merge_result_free(&wide);
    acd3_merge_result_free(&all);
    for (int t = 0; t < 2; t++) acd3_merge_result_free(&r[t]);
    for (int k = 0; k < 4; k++) acd_mesh_free(&parts[k]);
    acd_mesh_free(&in);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_volume_order_skips_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
