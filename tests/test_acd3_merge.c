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
#include "core/rng.h"
#include "geom3/bvh.h"
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

/* Four parts of unit cells and their union: an L (A = row 0, x 0..2; B = column 0, y 1..2) and,
 * apart from it, a step (C = row 8, x 0..9; D = row 9, x 3..12). */
static void l_and_step(acd_mesh parts[4], acd_mesh *in) {
    int xy[64][2], n;
    n = row(xy, 0, 2, 0);
    cells(&parts[0], (const int(*)[2])xy, n);
    xy[0][0] = 0, xy[0][1] = 1, xy[1][0] = 0, xy[1][1] = 2;
    cells(&parts[1], (const int(*)[2])xy, 2);
    n = row(xy, 0, 9, 8);
    cells(&parts[2], (const int(*)[2])xy, n);
    n = row(xy, 3, 12, 9);
    cells(&parts[3], (const int(*)[2])xy, n);
    n = row(xy, 0, 2, 0);
    xy[n][0] = 0, xy[n][1] = 1, n++;
    xy[n][0] = 0, xy[n][1] = 2, n++;
    n += row(xy + n, 0, 9, 8);
    n += row(xy + n, 3, 12, 9);
    cells(in, (const int(*)[2])xy, n);
}

static void test_volume_order_skips_refused(void **state) {
    (void)state;
    acd_mesh parts[4], in;
    l_and_step(parts, &in);
    const double tau = 0.9, tol = 1e-9;
    acd_error err;
    /* the costs: the L's joint hull adds 2, the step's 3 */
    acd3_merge_opts mo = {.by_volume = 1, .stop_at = 3};
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
    /* without a stop: still only the step (the L is never joinable), with no limit on the volume a join
     * adds; by default (at most 2% of the input's volume) not even the step (3 of 25) */
    mo.stop_at = 0;
    mo.max_added = INFINITY;
    acd3_merge_result all;
    assert_int_equal(acd3_merge_adjacent(&in, parts, 4, tau, tol, &mo, 1, &all, &err), ACD_OK);
    assert_int_equal(all.ngroups, 3);
    assert_true(all.group_of[0] != all.group_of[1]);
    acd3_merge_result_free(&all);
    mo.max_added = 0;
    assert_int_equal(acd3_merge_adjacent(&in, parts, 4, tau, tol, &mo, 1, &all, &err), ACD_OK);
    assert_int_equal(all.ngroups, 4);
    mo.max_added = 0.13; /* above 3 / 25 */
    acd3_merge_result_free(&all);
    assert_int_equal(acd3_merge_adjacent(&in, parts, 4, tau, tol, &mo, 1, &all, &err), ACD_OK);
    assert_int_equal(all.ngroups, 3);
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

static void assert_same_result(const acd3_merge_result *a, const acd3_merge_result *b, size_t nparts) {
    assert_int_equal(a->ngroups, b->ngroups);
    assert_int_equal(a->merges, b->merges);
    assert_int_equal(a->nnew, b->nnew);
    assert_int_equal(a->trades, b->trades);
    size_t na = nparts + a->nnew;
    assert_memory_equal(a->group_of, b->group_of, na * sizeof *a->group_of);
    assert_memory_equal(a->group_size, b->group_size, a->ngroups * sizeof *a->group_size);
    for (size_t g = 0; g < a->ngroups; g++) assert_memory_equal(&a->bound[g], &b->bound[g], sizeof(double));
}

/* acd3_merge_adjacent_hulls with the parts' hulls given (all, some, one of them another part's:
 * not used) gives the parts and bounds of acd3_merge_adjacent, bit for bit, at 1 and 2 threads;
 * every option of the pass (bound and volume order, a stop, a tolerance joining more). */
static void test_kept_hulls_same_result(void **state) {
    (void)state;
    acd_mesh parts[4], in;
    l_and_step(parts, &in);
    acd_error err;
    acd_hull H[4];
    for (int k = 0; k < 4; k++) {
        assert_int_equal(acd_hull_compute(parts[k].vertices, parts[k].nvertices, &H[k], &err), ACD_OK);
        assert_int_equal(H[k].dim, 3);
    }
    const acd_hull *all[4] = {&H[0], &H[1], &H[2], &H[3]};
    const acd_hull *some[4] = {NULL, &H[1], &H[2], NULL};
    const acd_hull *wrong[4] = {&H[2], &H[1], &H[0], &H[3]}; /* 0 and 2 swapped: not theirs */
    const acd_hull *const *sets[3] = {all, some, wrong};
    const acd3_merge_opts opts[4] = {{.by_volume = 1, .stop_at = 3}, {.by_volume = 1, .max_added = INFINITY},
                                     {.by_volume = 0, .max_added = INFINITY}, {.stop_at = 3}};
    const double taus[2] = {0.9, 1.5}, tol = 1e-9;
    for (int o = 0; o < 4; o++)
        for (int t = 0; t < 2; t++) {
            acd3_merge_result ref;
            assert_int_equal(acd3_merge_adjacent(&in, parts, 4, taus[t], tol, &opts[o], 1, &ref, &err), ACD_OK);
            assert_true(ref.merges >= 1);
            for (int s = 0; s < 3; s++)
                for (int th = 1; th <= 2; th++) {
                    acd3_merge_result r;
                    assert_int_equal(
                        acd3_merge_adjacent_hulls(&in, parts, sets[s], 4, taus[t], tol, &opts[o], th, &r, &err),
                        ACD_OK);
                    assert_same_result(&ref, &r, 4);
                    acd3_merge_result_free(&r);
                }
            acd3_merge_result_free(&ref);
        }
    /* the hulls are read, not taken: still whole */
    for (int k = 0; k < 4; k++) {
        assert_int_equal(H[k].dim, 3);
        assert_non_null(H[k].vertices);
        acd_hull_free(&H[k]);
        acd_mesh_free(&parts[k]);
    }
    acd_mesh_free(&in);
}

/* acd3_merge_adjacent_kept with the parts' trees and facet tables given (the budget pass's leaf tests
 * hand them over): all of them, some, a tree over another part's arrays and tables made at another
 * tau (both not used) give the parts and bounds of acd3_merge_adjacent, bit for bit, at 1 and 2
 * threads. The trees and tables are read, not taken. And a table is really used: one whose bounds
 * are raised (still within tau) raises the bound of the join that reuses one of its facets (the step's
 * joint hull keeps a side facet of a part's hull). */
static void test_kept_trees_tables_same_result(void **state) {
    (void)state;
    acd_mesh parts[4], in;
    l_and_step(parts, &in);
    acd_error err;
    acd_hull H[4];
    acd_bvh B[4];
    const double taus[2] = {0.9, 1.5}, tol = 1e-9;
    acd3_facet_table T[2][4];
    for (int k = 0; k < 4; k++) {
        assert_int_equal(acd_hull_compute(parts[k].vertices, parts[k].nvertices, &H[k], &err), ACD_OK);
        assert_int_equal(acd_bvh_build(&B[k], parts[k].vertices, parts[k].nvertices, parts[k].triangles,
                                       parts[k].ntriangles, &err), ACD_OK);
        for (int t = 0; t < 2; t++) {
            double reach = acd3_merge_hull_reach_table(&B[k], &H[k], taus[t], &T[t][k]);
            assert_true(reach <= taus[t]); /* a box part: its hull's facets lie on it (bounded within tau) */
            assert_non_null(T[t][k].key);
            assert_int_equal(T[t][k].n, H[k].ntriangles);
            assert_true(T[t][k].tau == taus[t]);
            for (size_t f = 1; f < T[t][k].n; f++) /* sorted, no facet twice */
                assert_true(memcmp(T[t][k].key + 9 * (f - 1), T[t][k].key + 9 * f, 9 * sizeof(double)) != 0);
        }
    }
    const acd3_merge_opts opts[4] = {{.by_volume = 1, .stop_at = 3}, {.by_volume = 1, .max_added = INFINITY},
                                     {.by_volume = 0, .max_added = INFINITY}, {.stop_at = 3}};
    for (int o = 0; o < 4; o++)
        for (int t = 0; t < 2; t++) {
            acd3_merge_result ref;
            assert_int_equal(acd3_merge_adjacent(&in, parts, 4, taus[t], tol, &opts[o], 1, &ref, &err), ACD_OK);
            assert_true(ref.merges >= 1);
            acd3_merge_kept sets[4][4];
            memset(sets, 0, sizeof sets);
            for (int k = 0; k < 4; k++) {
                sets[0][k] = (acd3_merge_kept){&H[k], &B[k], &T[t][k]};             /* all */
                if (k == 1 || k == 2) sets[1][k] = (acd3_merge_kept){&H[k], &B[k], &T[t][k]}; /* some */
                sets[2][k] = (acd3_merge_kept){&H[k], &B[3 - k], &T[t][3 - k]}; /* others' trees: not used */
                sets[3][k] = (acd3_merge_kept){&H[k], &B[k], &T[1 - t][k]};     /* another tau: not used */
            }
            for (int s = 0; s < 4; s++)
                for (int th = 1; th <= 2; th++) {
                    acd3_merge_result r;
                    assert_int_equal(acd3_merge_adjacent_kept(&in, parts, sets[s], 4, taus[t], tol, &opts[o], th, &r, &err),
                                     ACD_OK);
                    assert_same_result(&ref, &r, 4);
                    acd3_merge_result_free(&r);
                }
            acd3_merge_result_free(&ref);
        }
    /* read, not taken: still whole (the merge used them and did not free them) */
    for (int k = 0; k < 4; k++) {
        assert_true(B[k].nnodes > 0);
        assert_ptr_equal(B[k].vertices, parts[k].vertices);
        assert_non_null(T[0][k].key);
    }
    /* used: the tables' bounds raised to 0.89 (within tau 0.9: trusted), the step joined with the
     * bound 0.89 where its own (an upper bound of its reach 0.75) is below */
    {
        const acd3_merge_opts bo = {.by_volume = 0, .max_added = INFINITY};
        acd3_merge_result ref, r;
        assert_int_equal(acd3_merge_adjacent(&in, parts, 4, 0.9, tol, &bo, 1, &ref, &err), ACD_OK);
        acd3_merge_kept raised[4];
        for (int k = 0; k < 4; k++) {
            for (size_t f = 0; f < T[0][k].n; f++) T[0][k].ub[f] = 0.89;
            raised[k] = (acd3_merge_kept){&H[k], &B[k], &T[0][k]};
        }
        assert_int_equal(acd3_merge_adjacent_kept(&in, parts, raised, 4, 0.9, tol, &bo, 1, &r, &err), ACD_OK);
        assert_int_equal(r.ngroups, ref.ngroups);
        double bref = 0, br = 0;
        for (size_t g = 0; g < ref.ngroups; g++) bref = fmax(bref, ref.bound[g]);
        for (size_t g = 0; g < r.ngroups; g++) br = fmax(br, r.bound[g]);
        assert_true(bref < 0.89);
        assert_true(br == 0.89);
        acd3_merge_result_free(&ref);
        acd3_merge_result_free(&r);
    }
    for (int k = 0; k < 4; k++) {
        for (int t = 0; t < 2; t++) acd3_facet_table_free(&T[t][k]);
        acd_bvh_free(&B[k]);
        acd_hull_free(&H[k]);
        acd_mesh_free(&parts[k]);
    }
    acd_mesh_free(&in);
}

/* Two trees are the same, bit for bit (over the same arrays). */
static void assert_same_tree(const acd_bvh *a, const acd_bvh *b) {
    assert_ptr_equal(a->vertices, b->vertices);
    assert_ptr_equal(a->triangles, b->triangles);
    assert_int_equal(a->nvertices, b->nvertices);
    assert_int_equal(a->ntriangles, b->ntriangles);
    assert_int_equal(a->nnodes, b->nnodes);
    assert_true(a->nnodes > 0);
    assert_memory_equal(a->nodes, b->nodes, a->nnodes * sizeof *a->nodes);
    assert_memory_equal(a->order, b->order, a->ntriangles * sizeof *a->order);
    assert_memory_equal(a->boxes, b->boxes, 6 * a->ntriangles * sizeof *a->boxes);
}

/* acd3_merge_opts.keep_trees (for acd3/trim): the same result, and the trees handed over are those
 * acd_bvh_build makes: the input's, and those of the parts left alone (the L's two parts: the step
 * is joined), none for the joined parts nor where the caller's tree was used; at 1 and 2 threads. */
static void test_keep_trees_handed_over(void **state) {
    (void)state;
    acd_mesh parts[4], in;
    l_and_step(parts, &in);
    acd_error err;
    const double tau = 0.9, tol = 1e-9;
    acd_bvh B[4], BI;
    for (int k = 0; k < 4; k++)
        assert_int_equal(acd_bvh_build(&B[k], parts[k].vertices, parts[k].nvertices, parts[k].triangles,
                                       parts[k].ntriangles, &err), ACD_OK);
    assert_int_equal(acd_bvh_build(&BI, in.vertices, in.nvertices, in.triangles, in.ntriangles, &err), ACD_OK);
    acd3_merge_opts mo = {.by_volume = 1, .stop_at = 3};
    acd3_merge_result ref;
    assert_int_equal(acd3_merge_adjacent(&in, parts, 4, tau, tol, &mo, 1, &ref, &err), ACD_OK);
    assert_int_equal(ref.npart_bvh, 0); /* not asked for: none */
    assert_int_equal(ref.input_bvh.nnodes, 0);
    assert_null(ref.part_bvh);
    mo.keep_trees = 1;
    for (int th = 1; th <= 2; th++) {
        acd3_merge_result r;
        assert_int_equal(acd3_merge_adjacent(&in, parts, 4, tau, tol, &mo, th, &r, &err), ACD_OK);
        assert_same_result(&ref, &r, 4);
        assert_same_tree(&r.input_bvh, &BI);
        assert_int_equal(r.npart_bvh, 4);
        for (int k = 0; k < 2; k++) assert_same_tree(&r.part_bvh[k], &B[k]);
        for (int k = 2; k < 4; k++) assert_int_equal(r.part_bvh[k].nnodes, 0); /* joined */
        acd3_merge_result_free(&r);
        /* part 0's tree given: used, not handed back */
        acd3_merge_kept kept[4];
        memset(kept, 0, sizeof kept);
        kept[0].bvh = &B[0];
        assert_int_equal(acd3_merge_adjacent_kept(&in, parts, kept, 4, tau, tol, &mo, th, &r, &err), ACD_OK);
        assert_same_result(&ref, &r, 4);
        assert_int_equal(r.part_bvh[0].nnodes, 0);
        assert_same_tree(&r.part_bvh[1], &B[1]);
        acd3_merge_result_free(&r);
        assert_true(B[0].nnodes > 0); /* (read, not taken) */
    }
    acd3_merge_result_free(&ref);
    for (int k = 0; k < 4; k++) {
        acd_bvh_free(&B[k]);
        acd_mesh_free(&parts[k]);
    }
    acd_bvh_free(&BI);
    acd_mesh_free(&in);
}

/* Distance from p to the nearest of the triangles (brute force). */
static double dist_tris(const double *v, const uint32_t *t, size_t nt, const double p[3]) {
    double best = INFINITY, q[3];
    for (size_t i = 0; i < nt; i++) {
        double d2 = acd_closest_point_triangle(p, v + 3 * t[3 * i], v + 3 * t[3 * i + 1], v + 3 * t[3 * i + 2], q);
        if (d2 < best) best = d2;
    }
    return sqrt(best);
}

/* acd3_merge_hull_reach where the distance nears tau over a whole facet: the part is a unit square
 * (two triangles) and the hull a slab over it h = 0.99 tau thick, so every point of the top facet
 * is h from the part. The closest-point bound needs pieces of radius about
 * sqrt(tau^2 - h^2) = 0.14 tau there (some 10^5 queries: the budget ran out and the bound was
 * INFINITY); the triangle the closest point lies on bounds the facet's pieces by h itself
 * (facet_ub, after MERGE_FACET_POINT_QUERIES). The bound is finite, within tau, and above the
 * distance of every sampled point of every facet. */
static void test_hull_reach_near_tau(void **state) {
    (void)state;
    const double tau = 0.01, h = 0.99 * tau;
    const double sq[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const uint32_t st[6] = {0, 1, 2, 0, 2, 3};
    double box[24];
    for (int i = 0; i < 4; i++) {
        memcpy(box + 3 * i, sq + 3 * i, 3 * sizeof(double));
        memcpy(box + 12 + 3 * i, sq + 3 * i, 3 * sizeof(double));
        box[12 + 3 * i + 2] = h;
    }
    acd_bvh bvh;
    acd_error err;
    assert_int_equal(acd_bvh_build(&bvh, sq, 4, st, 2, &err), ACD_OK);
    acd_hull H;
    assert_int_equal(acd_hull_compute(box, 8, &H, &err), ACD_OK);
    assert_int_equal(H.dim, 3);
    double reach = acd3_merge_hull_reach(&bvh, &H, tau);
    print_message("reach %.17g (h %.17g, tau %g)\n", reach, h, tau);
    assert_true(reach <= tau);
    assert_true(reach >= h * (1 - 1e-12));
    /* above the distance of sampled points of every facet */
    acd_rng r;
    acd_rng_seed(&r, 5);
    double seen = 0;
    for (size_t t = 0; t < H.ntriangles; t++)
        for (int k = 0; k < 200; k++) {
            double a = acd_rng_uniform(&r), b = acd_rng_uniform(&r);
            if (a + b > 1) a = 1 - a, b = 1 - b;
            const double *p0 = H.vertices + 3 * H.triangles[3 * t], *p1 = H.vertices + 3 * H.triangles[3 * t + 1],
                         *p2 = H.vertices + 3 * H.triangles[3 * t + 2];
            double p[3];
            for (int c = 0; c < 3; c++) p[c] = p0[c] + a * (p1[c] - p0[c]) + b * (p2[c] - p0[c]);
            double d = dist_tris(sq, st, 2, p);
            if (d > seen) seen = d;
        }
    assert_true(seen > 0.9 * h);
    assert_true(reach >= seen * (1 - 1e-12));
    /* a tau below h: refused */
    assert_true(acd3_merge_hull_reach(&bvh, &H, 0.98 * h) > 0.98 * h);
    acd_hull_free(&H);
    acd_bvh_free(&bvh);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_volume_order_skips_refused),
        cmocka_unit_test(test_hull_reach_near_tau),
        cmocka_unit_test(test_kept_hulls_same_result),
        cmocka_unit_test(test_kept_trees_tables_same_result),
        cmocka_unit_test(test_keep_trees_handed_over),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
