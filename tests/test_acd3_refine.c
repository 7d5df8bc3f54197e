/* Tests of the merge pass's refinement (acd3/merge, acd3d_params.merge_refine; docs/acd3d.md "Hull
 * tightness"): at a fixed part count it cuts a part by a volume plane and joins the cheapest pair
 * when that lowers the hulls' volume. The parts still tile the input (volumes add up), every part
 * made or changed by it is a joined record within the merge tolerance whose hull reaches out by no
 * more than its bound, the pieces sit in the tree under the parts they were cut from, the hulls'
 * volume is not higher than without it, and the output is the same for 1, 2 and 4 threads. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd/hull.h"
#include "geom3/bvh.h"
#include "shapes.h"
#include "acd3d_check.h"

/* How far the part's hull reaches out of the part: the largest distance from a hull vertex or
 * facet centroid to the part's surface (a lower bound of the Hausdorff distance from the hull). */
static double hull_reach(const acd3d_part *pt) {
    acd_bvh b;
    acd_error err;
    assert_int_equal(acd_bvh_build(&b, pt->mesh.vertices, pt->mesh.nvertices, pt->mesh.triangles,
                                   pt->mesh.ntriangles, &err), ACD_OK);
    double worst = 0;
    const acd_mesh *h = &pt->hull;
    for (size_t t = 0; t < h->ntriangles; t++)
        for (int k = 0; k < 4; k++) {
            double p[3];
            for (int d = 0; d < 3; d++) {
                if (k < 3) p[d] = h->vertices[3 * (size_t)h->triangles[3 * t + k] + d];
                else p[d] = (h->vertices[3 * (size_t)h->triangles[3 * t] + d] + h->vertices[3 * (size_t)h->triangles[3 * t + 1] + d] +
                             h->vertices[3 * (size_t)h->triangles[3 * t + 2] + d]) / 3.0;
            }
            acd_bvh_closest_result q;
            if (acd_bvh_closest(&b, p, INFINITY, &q) && sqrt(q.dist2) > worst) worst = sqrt(q.dist2);
        }
    acd_bvh_free(&b);
    return worst;
}

static double hull_sum(const acd3d_result *r) {
    double s = 0;
    for (size_t i = 0; i < r->nparts; i++) s += r->parts[i].hull_volume;
    return s;
}

/* The refinement's invariants on r (input volume vin); returns how many pieces it made. */
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
        /* a joined record: within the merge tolerance, its hull within its bound of it, its members'
         * volumes adding up to its own */
        assert_true(pt->concavity <= r->merge_tau * (1 + 1e-12));
        assert_true(hull_reach(pt) <= pt->concavity * (1 + 1e-9) + 1e-12);
        double mv = 0;
        for (size_t n = 0; n < r->nnodes; n++)
            if (r->nodes[n].merged_into == pt->node) mv += r->nodes[n].volume;
        assert_true(fabs(mv - nd->volume) <= 1e-9 * vin);
    }
    assert_true(fabs(sum - vin) <= 1e-9 * vin);
    /* the pieces: children of the node cut, that node no longer a part, each piece in a joined
     * record unless cut again */
    size_t pieces = 0;
    for (size_t n = 0; n < r->nnodes; n++) {
        const acd3d_node *nd = &r->nodes[n];
        if (nd->leaf_reason != ACD3D_LEAF_REFINED && !(nd->first_child >= 0 && r->nodes[nd->first_child].leaf_reason == ACD3D_LEAF_REFINED))
            continue;
        if (nd->leaf_reason == ACD3D_LEAF_REFINED) {
            pieces++;
            assert_true(nd->parent >= 0);
            const acd3d_node *pa = &r->nodes[nd->parent];
            assert_true((int)n >= pa->first_child && (int)n < pa->first_child + pa->nchildren);
            assert_int_equal(pa->part, -1);
            if (nd->first_child < 0) assert_true(nd->merged_into >= 0);
        }
        if (nd->first_child >= 0) { /* cut: its children's volumes add up to its own */
            double cv = 0;
            for (int k = 0; k < nd->nchildren; k++) cv += r->nodes[nd->first_child + k].volume;
            assert_true(fabs(cv - nd->volume) <= 1e-9 * vin);
            assert_int_equal(nd->part, -1);
        }
    }
    return pieces;
}

static void run_shape(const acd_mesh *m, double tau, double merge_tau, size_t parts) {
    acd3d_params p = acd3d_default_params();
    p.tau = tau;
    p.merge_tau = merge_tau;
    p.cut_choice = ACD3D_CHOICE_VOLUME;
    p.merge_order = ACD3D_MERGE_VOLUME;
    p.merge_parts = parts;
    p.threads = 1;
    acd3d_result plain, ref[3];
    acd_error err;
    assert_int_equal(acd3d_decompose(m, &p, &plain, &err), ACD_OK);
    p.merge_refine = 20;
    const int threads[3] = {1, 2, 4};
    for (int k = 0; k < 3; k++) {
        p.threads = threads[k];
        assert_int_equal(acd3d_decompose(m, &p, &ref[k], &err), ACD_OK);
    }
    double vin = mg_volume(m);
    size_t pieces = check_refined(&ref[0], vin);
    print_message("refine: %zu parts, %zu pieces, hull volume %.6g -> %.6g (input %.6g)\n", ref[0].nparts, pieces,
                  hull_sum(&plain), hull_sum(&ref[0]), vin);
    assert_true(pieces > 0);
    assert_int_equal(ref[0].nparts, plain.nparts);
    assert_true(hull_sum(&ref[0]) < hull_sum(&plain));
    for (int k = 1; k < 3; k++) {
        ck3_same_parts(&ref[0], &ref[k]);
        assert_int_equal(ref[k].nnodes, ref[0].nnodes);
    }
    acd3d_result_free(&plain);
    for (int k = 0; k < 3; k++) acd3d_result_free(&ref[k]);
}

/* A bumpy, elongated blob (like a scanned limb): radius 1 + 0.15 sin(4 theta) cos(3 phi), stretched. */
static double bumpy_r(double th, double ph, void *u) {
    (void)u;
    return 1.0 + 0.15 * sin(4 * th) * cos(3 * ph) + 0.6 * fabs(cos(th));
}

static void test_bumpy(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 48, 32, bumpy_r, NULL));
    run_shape(&m, 0.03, 0.06, 10);
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bumpy),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
