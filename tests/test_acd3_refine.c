/* Tests of the merge pass's refinement (acd3/merge with acd3_merge_opts.refine; docs/acd3d.md "Hull
 * tightness"): at a fixed part count it cuts a group by a volume plane and joins the cheapest pair, or
 * cuts the union of an adjacent pair anew, when that lowers the sum of the hulls' volumes. On a
 * voxel shape whose best partition is known: the part count is kept, the hull volume falls to the
 * known optimum, the groups tile the input (volumes add up), every group is within tau, the pieces
 * name the atoms they were cut from, no refinement gives the greedy result unchanged, and the output
 * is the same for 1, 2 and 4 threads. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "acd3/merge.h"
#include "geom3/plane_cut.h"
#include "shapes.h"

enum { NX = 7, NY = 2, NZ = 1 };

/* Voxels of a 7 x 2 x 1 grid: the cells (x, y) listed in xs/ys. */
static void voxels(acd_mesh *m, const int *xs, const int *ys, int n) {
    unsigned char occ[NX * NY * NZ];
    memset(occ, 0, sizeof occ);
    for (int i = 0; i < n; i++) occ[ys[i] * NX + xs[i]] = 1;
    assert_true(mg_voxels(m, occ, NX, NY, NZ));
}

/* The atom k of r (an input part below nparts, else a piece). */
static const acd_mesh *atom(const acd_mesh *parts, size_t nparts, const acd3_merge_result *r, size_t k) {
    return k < nparts ? &parts[k] : &r->new_parts[k - nparts];
}

/* Sum over r's groups of the volume of the hull of its atoms. */
static double hull_sum(const acd_mesh *parts, size_t nparts, const acd3_merge_result *r) {
    size_t na = nparts + r->nnew;
    double s = 0;
    for (size_t g = 0; g < r->ngroups; g++) {
        size_t nv = 0;
        for (size_t k = 0; k < na; k++)
            if (r->group_of[k] == g) nv += atom(parts, nparts, r, k)->nvertices;
        double *pts = malloc(3 * nv * sizeof *pts);
        assert_non_null(pts);
        size_t w = 0;
        for (size_t k = 0; k < na; k++)
            if (r->group_of[k] == g) {
                const acd_mesh *m = atom(parts, nparts, r, k);
                memcpy(pts + 3 * w, m->vertices, 3 * m->nvertices * sizeof *pts);
                w += m->nvertices;
            }
        acd_hull h;
        assert_int_equal(acd_hull_compute(pts, nv, &h, NULL), ACD_OK);
        s += h.volume;
        acd_hull_free(&h);
        free(pts);
    }
    return s;
}

/* An inverted T (a bar of 5 cells, one cell on its middle) and two cells continuing the bar; input =
 * their union. Three groups kept: the best is the T cut at its bar's top (hulls 5 + 1) with the two
 * cells joined (hull 2): 8, against 8 + 1 + 1 = 10 without the refinement (the T's hull is 8). */
static void test_trade_on_voxels(void **state) {
    (void)state;
    const int tx[] = {0, 1, 2, 3, 4, 2}, ty[] = {0, 0, 0, 0, 0, 1};
    const int bx[] = {5}, by[] = {0}, cx[] = {6}, cy[] = {0};
    const int ix[] = {0, 1, 2, 3, 4, 5, 6, 2}, iy[] = {0, 0, 0, 0, 0, 0, 0, 1};
    acd_mesh in, parts[3];
    voxels(&in, ix, iy, 8);
    voxels(&parts[0], tx, ty, 6);
    voxels(&parts[1], bx, by, 1);
    voxels(&parts[2], cx, cy, 1);
    const double tau = 0.25, tol = 1e-9, vin = mg_volume(&in);
    acd3_merge_opts mo = {1, 3, 0};
    acd3_merge_result plain, ref[3];
    acd_error err;
    assert_int_equal(acd3_merge_adjacent(&in, parts, 3, tau, tol, &mo, 1, &plain, &err), ACD_OK);
    /* no refinement: nothing joined (already at 3), no piece */
    assert_int_equal(plain.ngroups, 3);
    assert_int_equal(plain.nnew, 0);
    assert_true(fabs(hull_sum(parts, 3, &plain) - 10) <= 1e-9);
    mo.refine = 5;
    const int threads[3] = {1, 2, 4};
    for (int t = 0; t < 3; t++)
        assert_int_equal(acd3_merge_adjacent(&in, parts, 3, tau, tol, &mo, threads[t], &ref[t], &err), ACD_OK);
    acd3_merge_result *r = &ref[0];
    assert_int_equal(r->ngroups, 3);
    assert_true(r->trades >= 1);
    assert_true(r->nnew >= 2);
    print_message("refined: %zu steps, %zu pieces, hull volume %.9g\n", r->trades, r->nnew, hull_sum(parts, 3, r));
    /* near the optimum 8 (the volume plane is searched at sampled offsets: within 0.1 of it) */
    assert_true(hull_sum(parts, 3, r) >= 8 - 1e-9 && hull_sum(parts, 3, r) <= 8.1);
    /* the groups tile the input: the atoms not cut add up to its volume; every group within tau */
    size_t na = 3 + r->nnew;
    double sum = 0;
    for (size_t k = 0; k < na; k++) {
        const acd_mesh *m = atom(parts, 3, r, k);
        if (k >= 3) {
            assert_true(r->new_parent[k - 3] < k);
            assert_true(fabs(mg_volume(m) - r->new_volume[k - 3]) <= 1e-12 * vin);
            /* a piece lies on one side of its parent's cut plane */
            const double *pl = r->new_plane[k - 3];
            double lo = INFINITY, hi = -INFINITY;
            for (size_t v = 0; v < m->nvertices; v++) {
                double s = pl[0] * m->vertices[3 * v] + pl[1] * m->vertices[3 * v + 1] + pl[2] * m->vertices[3 * v + 2] + pl[3];
                lo = fmin(lo, s), hi = fmax(hi, s);
            }
            assert_true(lo >= -1e-9 || hi <= 1e-9);
        }
        if (r->group_of[k] == UINT32_MAX) continue;
        assert_true(r->group_of[k] < r->ngroups);
        sum += mg_volume(m);
    }
    assert_true(fabs(sum - vin) <= 1e-9 * vin);
    for (size_t g = 0; g < r->ngroups; g++) assert_true(r->bound[g] <= tau);
    /* the same for any thread count */
    for (int t = 1; t < 3; t++) {
        assert_int_equal(ref[t].nnew, r->nnew);
        assert_int_equal(ref[t].ngroups, r->ngroups);
        assert_memory_equal(ref[t].group_of, r->group_of, na * sizeof *r->group_of);
        for (size_t k = 0; k < r->nnew; k++) {
            assert_int_equal(ref[t].new_parts[k].nvertices, r->new_parts[k].nvertices);
            assert_memory_equal(ref[t].new_parts[k].vertices, r->new_parts[k].vertices,
                                3 * r->new_parts[k].nvertices * sizeof(double));
        }
    }
    acd3_merge_result_free(&plain);
    for (int t = 0; t < 3; t++) acd3_merge_result_free(&ref[t]);
    for (int k = 0; k < 3; k++) acd_mesh_free(&parts[k]);
    acd_mesh_free(&in);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_trade_on_voxels),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
