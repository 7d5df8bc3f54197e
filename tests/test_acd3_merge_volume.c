/* Tests the merge pass's limit on the hull volume a join adds (acd3/merge, MERGE_MAX_ADDED_REL; issue
 * 4, GEB's default run): without a stop, a pair whose joint hull adds more than 2% of the input's
 * volume to the two hulls is not joined, although the joined part is within tau of its hull both ways.
 *
 * Two voxel solids in the xz plane (one cell deep in y), each split into parts as the tree would:
 *  - a U: a base row of 3 cells and two prongs 8 cells high, a slot 1 wide between them (narrower than
 *    2 tau, tau 1.5: every point of the joint hull is within 0.5 of the prongs, every surface vertex
 *    within tau of the hull's boundary); parts: left prong with the base's first two cells, right
 *    prong. The joint hull fills the slot: 8 of 19 cells added.
 *  - an L (GEB's nodes 20 and 21: a thin wall and a short stub of the floor): a wall 10 cells high
 *    and one cell of floor; the joint hull adds the wedge between them (4.5 of 11 cells), whose depth
 *    stays within tau = 1.5.
 * The old rule joined both pairs; now neither is joined, at 1, 2 and 4 threads alike, while parts
 * whose join adds no hull volume (the L's wall in two halves) are still joined, and with a stop at
 * one group (the budget pipeline) the pairs are joined as before. The whole pipeline keeps the U in
 * two parts or more. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd3/merge.h"
#include "shapes.h"

enum { NX = 3, NZ = 10 };

/* The cells (xs[i], zs[i]) of an NX x 1 x NZ grid. */
static void cells(acd_mesh *m, const int *xs, const int *zs, int n) {
    unsigned char occ[NX * NZ];
    memset(occ, 0, sizeof occ);
    for (int i = 0; i < n; i++) occ[zs[i] * NX + xs[i]] = 1; /* (z * ny + y) * nx + x, ny = 1 */
    assert_true(mg_voxels(m, occ, NX, 1, NZ));
}

/* The U (prongs 8 high) and its two parts. */
static void u_shape(acd_mesh *in, acd_mesh parts[2]) {
    int xs[19], zs[19], ax[10], az[10], bx[9], bz[9], n = 0, na = 0, nb = 0;
    for (int x = 0; x < 3; x++) {
        xs[n] = x, zs[n++] = 0;
        if (x < 2) ax[na] = x, az[na++] = 0;
        else bx[nb] = x, bz[nb++] = 0;
    }
    for (int z = 1; z <= 8; z++) {
        xs[n] = 0, zs[n++] = z, ax[na] = 0, az[na++] = z;
        xs[n] = 2, zs[n++] = z, bx[nb] = 2, bz[nb++] = z;
    }
    cells(in, xs, zs, n);
    cells(&parts[0], ax, az, na);
    cells(&parts[1], bx, bz, nb);
}

/* The L (wall 10 high, one cell of floor) and its parts: the wall's lower and upper halves, the floor
 * cell. */
static void l_shape(acd_mesh *in, acd_mesh parts[3]) {
    int xs[11], zs[11], n = 0;
    for (int z = 0; z < 10; z++) xs[n] = 0, zs[n++] = z;
    xs[n] = 1, zs[n++] = 0;
    cells(in, xs, zs, n);
    cells(&parts[0], xs, zs, 5);
    cells(&parts[1], xs + 5, zs + 5, 5);
    cells(&parts[2], xs + 10, zs + 10, 1);
}

/* The merge of parts at tau 1.5 (bound order; stop_at as given), checked the same at 2 and 4 threads. */
static void merge(const acd_mesh *in, const acd_mesh *parts, size_t n, size_t stop_at, acd3_merge_result *r) {
    acd3_merge_opts mo = {.stop_at = stop_at};
    acd_error err;
    assert_int_equal(acd3_merge_adjacent(in, parts, n, 1.5, 1e-9, &mo, 1, r, &err), ACD_OK);
    const int threads[2] = {2, 4};
    for (int t = 0; t < 2; t++) {
        acd3_merge_result o;
        assert_int_equal(acd3_merge_adjacent(in, parts, n, 1.5, 1e-9, &mo, threads[t], &o, &err), ACD_OK);
        assert_int_equal(o.ngroups, r->ngroups);
        assert_memory_equal(o.group_of, r->group_of, n * sizeof *o.group_of);
        assert_memory_equal(o.bound, r->bound, o.ngroups * sizeof *o.bound);
        acd3_merge_result_free(&o);
    }
}

static void test_slot_not_joined(void **state) {
    (void)state;
    acd_mesh in, parts[2];
    u_shape(&in, parts);
    acd3_merge_result r;
    merge(&in, parts, 2, 0, &r);
    assert_int_equal(r.ngroups, 2); /* the old rule: 1 (bound 0.5) */
    assert_int_equal(r.merges, 0);
    acd3_merge_result_free(&r);
    /* with a stop (the budget pipeline's merge) the limit is off: joined as before */
    merge(&in, parts, 2, 1, &r);
    assert_int_equal(r.ngroups, 1);
    assert_true(r.bound[0] > 0 && r.bound[0] <= 1.5);
    acd3_merge_result_free(&r);
    /* the whole pipeline: the tree splits the U (its slot 7 deep below the bridge), the merge leaves it
     * split */
    acd3d_params prm = acd3d_default_params();
    prm.tau = 0.3; /* x the radius (about 4.3): 1.3 */
    acd3d_result res;
    acd_error err;
    assert_int_equal(acd3d_decompose(&in, &prm, &res, &err), ACD_OK);
    assert_true(res.nparts >= 2);
    acd3d_result_free(&res);
    for (int k = 0; k < 2; k++) acd_mesh_free(&parts[k]);
    acd_mesh_free(&in);
}

static void test_wedge_not_joined(void **state) {
    (void)state;
    acd_mesh in, parts[3];
    l_shape(&in, parts);
    acd3_merge_result r;
    merge(&in, parts, 3, 0, &r);
    /* the wall's halves joined (no hull volume added), the floor cell not (the old rule: one group) */
    assert_int_equal(r.ngroups, 2);
    assert_int_equal(r.merges, 1);
    assert_int_equal(r.group_of[0], r.group_of[1]);
    assert_true(r.group_of[2] != r.group_of[0]);
    acd3_merge_result_free(&r);
    merge(&in, parts, 3, 1, &r);
    assert_int_equal(r.ngroups, 1);
    acd3_merge_result_free(&r);
    for (int k = 0; k < 3; k++) acd_mesh_free(&parts[k]);
    acd_mesh_free(&in);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_slot_not_joined),
        cmocka_unit_test(test_wedge_not_joined),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
