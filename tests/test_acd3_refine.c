/* Tests of the merge pass's refinement (acd3/merge with acd3_merge_opts.refine; docs/acd3d.md "Hull
 * tightness"): at a fixed part count it cuts a group by a volume plane and joins the cheapest pair, or
 * cuts the union of an adjacent pair anew, when that lowers the sum of the hulls' volumes. On a
 * voxel shape whose best partition is known: the part count is kept, the hull volume falls to the
 * known optimum, the groups tile the input (volumes add up), every group is within tau, the pieces
 * name the atoms they were cut from, no refinement gives the greedy result unchanged, and the output
 * is the same for 1, 2 and 4 threads. Through acd3d_decompose (merge_refine): the pieces are tree
 * nodes under the parts they were cut from, each in a joined record within the merge tolerance whose
 * hull reaches out by no more than its bound. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd/hull.h"
#include "acd3/merge.h"
#include "acd3/volume_plane.h"
#include "acd3d_check.h"
#include "merge_check.h"
#include "geom3/bvh.h"
#include "geom3/edge_map.h"
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
    acd3_merge_opts mo = {.by_volume = 1, .stop_at = 3};
    acd3_merge_result plain, ref[3];
    acd_error err;
    assert_int_equal(acd3_merge_adjacent(&in, parts, 3, tau, tol, &mo, 1, &plain, &err), ACD_OK);
    /* no refinement: nothing joined (already at 3), no piece */
    assert_int_equal(plain.ngroups, 3);
    assert_int_equal(plain.nnew, 0);
    assert_true(fabs(mck_hull_sum(parts, 3, &plain) - 10) <= 1e-9);
    mo.refine = 5;
    const int threads[3] = {1, 2, 4};
    for (int t = 0; t < 3; t++)
        assert_int_equal(acd3_merge_adjacent(&in, parts, 3, tau, tol, &mo, threads[t], &ref[t], &err), ACD_OK);
    acd3_merge_result *r = &ref[0];
    assert_int_equal(r->ngroups, 3);
    assert_true(r->trades >= 1);
    assert_true(r->nnew >= 2);
    print_message("refined: %zu steps, %zu pieces, hull volume %.9g\n", r->trades, r->nnew, mck_hull_sum(parts, 3, r));
    /* near the optimum 8 (the volume plane is searched at sampled offsets: within 0.1 of it) */
    assert_true(mck_hull_sum(parts, 3, r) >= 8 - 1e-9 && mck_hull_sum(parts, 3, r) <= 8.1);
    /* the groups tile the input: the atoms not cut add up to its volume; every group within tau */
    size_t na = 3 + r->nnew;
    double sum = 0;
    for (size_t k = 0; k < na; k++) {
        const acd_mesh *m = mck_atom(parts, 3, r, k);
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

/* How far the part's hull reaches out of the part: the largest distance from a hull vertex or facet
 * centroid to the part's surface (a lower bound of the distance the part's bound bounds). */
static double hull_reach(const acd3d_part *pt) {
    acd_bvh b;
    acd_error err;
    assert_int_equal(acd_bvh_build(&b, pt->mesh.vertices, pt->mesh.nvertices, pt->mesh.triangles, pt->mesh.ntriangles, &err),
                     ACD_OK);
    double worst = 0;
    const acd_mesh *h = &pt->hull;
    for (size_t t = 0; t < h->ntriangles; t++)
        for (int k = 0; k < 4; k++) {
            double p[3];
            for (int d = 0; d < 3; d++) {
                const double *v0 = h->vertices + 3 * (size_t)h->triangles[3 * t], *v1 = h->vertices + 3 * (size_t)h->triangles[3 * t + 1],
                             *v2 = h->vertices + 3 * (size_t)h->triangles[3 * t + 2];
                p[d] = k == 0 ? v0[d] : k == 1 ? v1[d] : k == 2 ? v2[d] : (v0[d] + v1[d] + v2[d]) / 3.0;
            }
            acd_bvh_closest_result q;
            if (acd_bvh_closest(&b, p, INFINITY, &q) && sqrt(q.dist2) > worst) worst = sqrt(q.dist2);
        }
    acd_bvh_free(&b);
    return worst;
}

/* The refinement's invariants on a decomposition r of an input of volume vin; returns how many
 * pieces it made. */
static size_t check_refined(const acd3d_result *r, double vin) {
    double sum = 0;
    for (size_t i = 0; i < r->nparts; i++) {
        const acd3d_part *pt = &r->parts[i];
        const acd3d_node *nd = &r->nodes[pt->node];
        double v = mg_volume(&pt->mesh);
        assert_true(v > 0);
        assert_true(fabs(v - pt->volume) <= 1e-9 * vin);
        sum += v;
        assert_true(pt->hull_volume >= v * (1 - 1e-9));
        if (nd->leaf_reason != ACD3D_LEAF_JOINED) continue;
        assert_true(pt->concavity <= r->merge_tau * (1 + 1e-12));
        assert_true(hull_reach(pt) <= pt->concavity * (1 + 1e-9) + 1e-12);
        double mv = 0;
        for (size_t n = 0; n < r->nnodes; n++)
            if (r->nodes[n].merged_into == pt->node) mv += r->nodes[n].volume;
        assert_true(fabs(mv - nd->volume) <= 1e-9 * vin);
    }
    assert_true(fabs(sum - vin) <= 1e-9 * vin);
    size_t pieces = 0;
    for (size_t n = 0; n < r->nnodes; n++) {
        const acd3d_node *nd = &r->nodes[n];
        if (nd->leaf_reason != ACD3D_LEAF_REFINED) continue;
        pieces++;
        /* a child of the node cut, which is no longer a part; joined unless cut again */
        assert_true(nd->parent >= 0);
        const acd3d_node *pa = &r->nodes[nd->parent];
        assert_true((int)n >= pa->first_child && (int)n < pa->first_child + pa->nchildren);
        assert_int_equal(pa->part, -1);
        assert_int_equal(pa->leaf_reason, ACD3D_LEAF_NONE);
        double cv = 0;
        for (int k = 0; k < pa->nchildren; k++) cv += r->nodes[pa->first_child + k].volume;
        assert_true(fabs(cv - pa->volume) <= 1e-9 * vin);
        if (nd->first_child < 0) assert_true(nd->merged_into >= 0);
        assert_int_equal(nd->part, -1);
    }
    return pieces;
}

/* The refinement measures a plane's saving by acd3_volume_plane_sides: the hulls of the two pieces
 * the cut gives. On the inverted T (hull 8, volume 6): the plane on top of the bar leaves a bar and a
 * cell (5 + 1: the saving a cut there makes); a plane across the bar through the middle of the top cell leaves two halves of hull 4
 * each (no saving); a plane missing the part leaves it whole (its hull). Every plane's sides hold the
 * part's volume (the bound the lazy estimates rely on). */
static void test_plane_sides(void **state) {
    (void)state;
    const int tx[] = {0, 1, 2, 3, 4, 2}, ty[] = {0, 0, 0, 0, 0, 1};
    acd_mesh t;
    voxels(&t, tx, ty, 6);
    const double up[3] = {0, 1, 0}, right[3] = {1, 0, 0};
    /* (just above the bar's top face: a vertex on the plane counts on the upper side only) */
    const double top[3] = {0, 1 + 1e-6, 0}, mid[3] = {2.5, 0, 0}, off[3] = {0, 5, 0};
    assert_true(fabs(acd3_volume_plane_sides(&t, up, top) - 6) <= 1e-5);
    assert_true(fabs(acd3_volume_plane_sides(&t, right, mid) - 8) <= 1e-9);
    assert_true(fabs(acd3_volume_plane_sides(&t, up, off) - 8) <= 1e-9);
    for (int k = 0; k < 20; k++) {
        double a = 0.3 * k, n[3] = {cos(a), sin(a) * cos(2 * a), sin(a) * sin(2 * a)}, p[3] = {0.25 * k, 0.1 * k, 0.5};
        double s = acd3_volume_plane_sides(&t, n, p);
        assert_true(s >= 6 - 1e-9 && s <= 16 + 1e-9);
    }
    acd_mesh_free(&t);
}

/* The volume plane searched on an estimate (acd3_volume_planes_scored with max_scored > 0; its
 * refinements only on the axes within 2% of the best coarse score) and in full: on the inverted T
 * both find a plane across the vertical axis between the bar and the cell, refined to within 0.2 of
 * the part's volume (6, against the part's hull 8; any plane across the bar leaves at least 7);
 * each reported score is that of its plane on every vertex (a small part is scored whole) and the
 * scores come best first. */
static void test_volume_plane_estimate(void **state) {
    (void)state;
    const int tx[] = {0, 1, 2, 3, 4, 2}, ty[] = {0, 0, 0, 0, 0, 1};
    acd_mesh t;
    voxels(&t, tx, ty, 6);
    for (int full = 0; full <= 1; full++) {
        acd3_plane_candidate c[3];
        double sc[3], whole = 0;
        int n = acd3_volume_planes_scored(&t, 3, full ? 0 : 400, 3, c, sc, &whole);
        assert_true(n >= 2);
        assert_true(fabs(whole - 8) <= 1e-9);
        for (int i = 0; i < n; i++) {
            assert_true(fabs(acd3_volume_plane_sides(&t, c[i].normal, c[i].point) - sc[i]) <= 1e-9);
            if (i > 0) assert_true(sc[i] >= sc[i - 1]);
        }
        assert_true(fabs(c[0].normal[1]) > 0.999);
        assert_true(sc[0] <= 6.2); /* the coarse offsets alone: 1/3 above the bar, 6.33 */
    }
    acd_mesh_free(&t);
}

static double bumpy_r(double th, double ph, void *u) {
    (void)u;
    return 1.0 + 0.15 * sin(4 * th) * cos(3 * ph) + 0.6 * fabs(cos(th));
}

/* A bumpy, elongated blob decomposed, merged to 5 parts and refined. */
static void test_decompose_refined(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 24, 12, bumpy_r, NULL));
    acd3d_params p = acd3d_default_params();
    p.tau = 0.05;
    p.merge_tau = 0.15;
    p.cut_choice = ACD3D_CHOICE_VOLUME;
    p.merge_order = ACD3D_MERGE_VOLUME;
    p.merge_parts = 5;
    p.threads = 1;
    acd3d_result plain, ref[3];
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &plain, &err), ACD_OK);
    p.merge_refine = 20;
    const int threads[3] = {1, 2, 4};
    for (int k = 0; k < 3; k++) {
        p.threads = threads[k];
        assert_int_equal(acd3d_decompose(&m, &p, &ref[k], &err), ACD_OK);
    }
    double vin = mg_volume(&m), hp = 0, hr = 0;
    assert_int_equal(check_refined(&plain, vin), 0);
    assert_true(check_refined(&ref[0], vin) > 0);
    assert_int_equal(ref[0].nparts, plain.nparts);
    for (size_t i = 0; i < plain.nparts; i++) hp += plain.parts[i].hull_volume;
    for (size_t i = 0; i < ref[0].nparts; i++) hr += ref[0].parts[i].hull_volume;
    assert_true(hr < hp);
    for (int k = 1; k < 3; k++) {
        ck3_same_parts(&ref[0], &ref[k]);
        assert_int_equal(ref[k].nnodes, ref[0].nnodes);
    }
    acd3d_result_free(&plain);
    for (int k = 0; k < 3; k++) acd3d_result_free(&ref[k]);
    acd_mesh_free(&m);
}

/* Found by fuzz/fuzz_acd3d_tight: a star-shaped solid pinched at the origin (seven distinct vertices
 * at the same point), cut by volume planes, merged to 7 parts at merge tau 4 x tau and refined. A
 * refinement cut of a part with coincident vertices left two pieces with an edge used twice in the
 * same direction, and the joined parts holding them were not closed. The refinement now refuses
 * such a cut (as decompose.c refuses its own): every part is closed and consistently oriented. */
static void test_refine_pinched_closed(void **state) {
    (void)state;
    static const double v[26][3] = {
        {2.2265625, 0, 3.046875}, {1.11328125, 1.93359375, 3.046875}, {-0.4453125, 0.7734375, 1.21875},
        {-0.890625, 0, 1.21875}, {-0, -0, 0}, {0, -0, 0},
        {1.4296875, 0, 0.46875}, {0.703125, 1.2421875, 0.46875}, {-0.703125, 1.2421875, 0.46875},
        {-1.4296875, 0, 0.46875}, {-0, -0, 0}, {1.171875, -2.0703125, 0.78125},
        {2.14453125, 0, -0.703125}, {0.9375, 1.65625, -0.625}, {-0.703125, 1.2421875, -0.46875},
        {-0, 0, -0}, {-0.703125, -1.2421875, -0.46875}, {0.703125, -1.2421875, -0.46875},
        {0.890625, 0, -1.21875}, {0.4453125, 0.7734375, -1.21875}, {-0.4453125, 0.7734375, -1.21875},
        {-0.890625, 0, -1.21875}, {-0.4453125, -0.7734375, -1.21875}, {0.4453125, -0.7734375, -1.21875},
        {0, 0, 1.5}, {0, 0, -0},
    };
    static const uint32_t t[48][3] = {
        {24, 0, 1}, {25, 19, 18}, {24, 1, 2}, {25, 20, 19}, {24, 2, 3}, {25, 21, 20}, {24, 3, 4}, {25, 22, 21},
        {24, 4, 5}, {25, 23, 22}, {24, 5, 0}, {25, 18, 23}, {0, 6, 7}, {0, 7, 1}, {1, 7, 8}, {1, 8, 2},
        {2, 8, 9}, {2, 9, 3}, {3, 9, 10}, {3, 10, 4}, {4, 10, 11}, {4, 11, 5}, {5, 11, 6}, {5, 6, 0},
        {6, 12, 13}, {6, 13, 7}, {7, 13, 14}, {7, 14, 8}, {8, 14, 15}, {8, 15, 9}, {9, 15, 16}, {9, 16, 10},
        {10, 16, 17}, {10, 17, 11}, {11, 17, 12}, {11, 12, 6}, {12, 18, 19}, {12, 19, 13}, {13, 19, 20}, {13, 20, 14},
        {14, 20, 21}, {14, 21, 15}, {15, 21, 22}, {15, 22, 16}, {16, 22, 23}, {16, 23, 17}, {17, 23, 18}, {17, 18, 12},
    };
    acd_mesh m = {0};
    m.nvertices = 26;
    m.ntriangles = 48;
    m.vertices = malloc(sizeof v);
    m.triangles = malloc(sizeof t);
    assert_non_null(m.vertices);
    assert_non_null(m.triangles);
    memcpy(m.vertices, v, sizeof v);
    memcpy(m.triangles, t, sizeof t);
    acd3d_params p = acd3d_default_params();
    p.tau = 0.05;
    p.merge_tau = 0.2;
    p.max_depth = 5;
    p.cut_choice = ACD3D_CHOICE_VOLUME;
    p.stop = ACD3D_STOP_HULL;
    p.merge_parts = 7;
    p.merge_refine = 2;
    p.max_hull_vertices = 10;
    p.threads = 1;
    acd3d_result r;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    double sum = 0;
    for (size_t i = 0; i < r.nparts; i++) {
        const acd_mesh *q = &r.parts[i].mesh;
        acd_edge_map em;
        assert_int_equal(acd_edge_map_build(q->triangles, q->ntriangles, NULL, &em, &err), ACD_OK);
        acd_status cs = acd_edge_map_check_closed(&em, q->triangles, q->ntriangles, &err);
        acd_edge_map_free(&em);
        if (cs != ACD_OK) fail_msg("part %zu: %s", i, err.message);
        sum += r.parts[i].volume;
    }
    assert_true(fabs(sum - r.input_volume) <= 1e-9 * r.input_volume);
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_trade_on_voxels),
        cmocka_unit_test(test_plane_sides),
        cmocka_unit_test(test_volume_plane_estimate),
        cmocka_unit_test(test_decompose_refined),
        cmocka_unit_test(test_refine_pinched_closed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
