/* Tests of acd3/resolve's resolver without feature grouping (ACD3D_RESOLVER_NOTCH, spec §5.4,
 * decision A14): the candidate is the plane through the most reflex edge at the witness,
 * bisecting its dihedral angle, followed only by the axis planes; a decomposition with it (eps 0,
 * region cuts) conserves volume, keeps parts closed and meets tau; on an L the notch cut is the
 * plane x = y that separates the notch's two faces. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd3/measure.h"
#include "acd3/resolve.h"
#include "geom3/dijkstra.h"
#include "geom3/edge_map.h"
#include "shapes.h"
#include "acd3d_check.h"

/* An L of unit voxels, 6 x 4 x 1 with the corner x, y >= 2 empty (arms of lengths 6 and 4, so
 * that no principal axis of the L is along a diagonal): its reflex edge is the line x = y = 2,
 * between the faces x = 2 (normal +x) and y = 2 (normal +y). */
static void l_shape(acd_mesh *m) {
    unsigned char occ[24];
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 6; x++) occ[y * 6 + x] = !(x >= 2 && y >= 2);
    assert_true(mg_voxels(m, occ, 6, 4, 1));
}

static void test_notch_candidates(void **state) {
    (void)state;
    acd_mesh m;
    l_shape(&m);
    acd_edge_graph g;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &g, &err), ACD_OK);
    acd3_measure ms;
    assert_int_equal(acd3_measure_compute(&m, &g, 0.0, 1e-9, &ms, &err), ACD_OK);
    assert_true(ms.witness != UINT32_MAX);
    const double *w = m.vertices + 3 * (size_t)ms.witness;
    /* the deepest points of the L lie on its reflex edge */
    assert_true(fabs(w[0] - 2) < 1e-12 && fabs(w[1] - 2) < 1e-12);

    acd3_resolve_opts ro;
    memset(&ro, 0, sizeof ro);
    ro.notch = 1;
    acd3_plane_candidate c[ACD3_MAX_CANDIDATES];
    int n = acd3_cut_candidates(&m, &g, &ms, &ro, c);
    assert_true(n >= 2 && n <= 4);
    assert_string_equal(c[0].kind, "notch");
    /* a bisector of the right angle between +x and +y, through the edge */
    double s = 1 / sqrt(2.0);
    assert_true(fabs(fabs(c[0].normal[0]) - s) < 1e-12 && fabs(fabs(c[0].normal[1]) - s) < 1e-12 &&
                fabs(c[0].normal[2]) < 1e-12);
    /* the bisector of the material's 270 degrees: x = y, separating the two faces */
    assert_true(c[0].normal[0] * c[0].normal[1] < 0);
    assert_true(fabs(c[0].point[0] - 2) < 1e-12 && fabs(c[0].point[1] - 2) < 1e-12);
    for (int i = 1; i < n; i++) assert_string_equal(c[i].kind, "axis");

    /* the witness resolver proposes more kinds (valley, notch, face, centroid, axis) */
    ro.notch = 0;
    int n2 = acd3_cut_candidates(&m, &g, &ms, &ro, c);
    assert_true(n2 > n);
    int faces = 0;
    for (int i = 0; i < n2; i++) faces += !strcmp(c[i].kind, "face");
    assert_int_equal(faces, 2);

    acd3_measure_free(&ms);
    acd_edge_graph_free(&g);
    acd_mesh_free(&m);
}

static void check_parts(const acd_mesh *in, const acd3d_result *r) {
    double vin = mg_volume(in), sum = 0;
    for (size_t i = 0; i < r->nparts; i++) {
        const acd_mesh *pm = &r->parts[i].mesh;
        acd_edge_map em;
        acd_error err;
        assert_int_equal(acd_edge_map_build(pm->triangles, pm->ntriangles, NULL, &em, &err), ACD_OK);
        assert_int_equal(acd_edge_map_check_closed(&em, pm->triangles, pm->ntriangles, &err), ACD_OK);
        acd_edge_map_free(&em);
        sum += mg_volume(pm);
        assert_true(r->parts[i].concavity <= r->tau + 1e-9 * r->scale);
        assert_int_not_equal(r->nodes[r->parts[i].node].leaf_reason, ACD3D_LEAF_NO_CUT);
    }
    assert_true(fabs(sum - vin) <= 1e-9 * vin);
}

static void no_fg(acd3d_params *p) {
    p->eps_ratio = 0;
    p->resolver = ACD3D_RESOLVER_NOTCH;
    p->region_cuts = 1;
}

static void test_l_shape_notch_cut(void **state) {
    (void)state;
    acd_mesh m;
    l_shape(&m);
    acd3d_params p = acd3d_default_params();
    p.tau = 0.0;
    p.tau_absolute = 1;
    p.merge = 0;
    acd3d_result r, d;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &d, &err), ACD_OK);
    no_fg(&p);
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    check_parts(&m, &r);
    /* the root was cut by the bisector x = y through the notch edge (not an axis plane): two
     * convex parts */
    const double *pl = r.nodes[0].cut_plane, s = 1 / sqrt(2.0);
    assert_true(fabs(fabs(pl[0]) - s) < 1e-12 && fabs(fabs(pl[1]) - s) < 1e-12 && pl[0] * pl[1] < 0 &&
                fabs(pl[2]) < 1e-12 && fabs(pl[3]) < 1e-9);
    assert_int_equal(r.nparts, 2);
    assert_int_equal(d.nparts, 2);
    acd3d_result_free(&r);
    acd3d_result_free(&d);
    acd_mesh_free(&m);
}

static double waist_r(double th, double ph, void *u) {
    (void)ph;
    double k = *(double *)u, s = sin(th);
    return 1.0 - k * s * s;
}

/* A smooth part: the variant meets tau on every part, solid and surface, for 1 and 2 threads. */
static void test_waist_without_grouping(void **state) {
    (void)state;
    double k = 0.6;
    acd_mesh m;
    assert_true(mg_radial(&m, 40, 40, waist_r, &k));
    acd3d_params p = acd3d_default_params();
    p.tau = 0.03;
    no_fg(&p);
    p.threads = 1;
    acd3d_result r, r2;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_true(r.nparts >= 2);
    check_parts(&m, &r);
    p.threads = 2;
    assert_int_equal(acd3d_decompose(&m, &p, &r2, &err), ACD_OK);
    ck3_same_parts(&r, &r2);
    acd3d_result_free(&r2);
    acd3d_result_free(&r);
    p.mode = ACD3D_SURFACE;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_true(r.nparts >= 2);
    for (size_t i = 0; i < r.nparts; i++) assert_true(r.parts[i].concavity <= r.tau + 1e-9 * r.scale);
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_notch_candidates),
        cmocka_unit_test(test_l_shape_notch_cut),
        cmocka_unit_test(test_waist_without_grouping),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
