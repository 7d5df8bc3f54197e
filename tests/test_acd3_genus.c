/* Tests of arbitrary genus in 3D ACD (spec acd3d.md §6): the genus of every part is reported
 * (acd3/topology: Euler characteristic with boundary loops), surfaces with handles are cut open
 * along loops that do not separate them, and genus > 0 inputs finish in both modes with every
 * part within tau, the same for any number of threads. */
#include "testutil.h"

#include <math.h>
#include <stdio.h>

#include "acd/acd3d.h"
#include "acd3/topology.h"
#include "shapes.h"

static double sphere_r(double th, double ph, void *u) { (void)th, (void)ph, (void)u; return 1.0; }

static void topo(const acd_mesh *m, acd3_topology *t) {
    acd_error err;
    assert_int_equal(acd3_topology_of(m, t, &err), ACD_OK);
}

static void test_topology_of_known_surfaces(void **state) {
    (void)state;
    acd_mesh m;
    acd3_topology t;
    assert_true(mg_radial(&m, 24, 12, sphere_r, NULL));
    topo(&m, &t);
    assert_true(t.genus == 0 && t.boundary_loops == 0 && t.euler == 2 && t.components == 1);
    m.ntriangles -= 24; /* the ring at the south pole: a disk with one opening */
    topo(&m, &t);
    assert_true(t.genus == 0 && t.boundary_loops == 1 && t.euler == 1);
    acd_mesh_free(&m);
    assert_true(mg_torus(&m, 24, 12, 1.0, 0.3));
    topo(&m, &t);
    assert_true(t.genus == 1 && t.boundary_loops == 0 && t.euler == 0);
    /* the torus cut open across its tube (faces of one ring of the u direction removed): an
     * annulus, genus 0 with two openings */
    size_t keep = 0;
    for (size_t f = 0; f < m.ntriangles; f++) {
        uint32_t *q = m.triangles + 3 * f;
        int ring0 = 0;
        for (int k = 0; k < 3; k++) ring0 |= q[k] / 12 == 0; /* vertex i * nv + j: i == 0 */
        if (ring0) continue;
        for (int k = 0; k < 3; k++) m.triangles[3 * keep + k] = q[k];
        keep++;
    }
    m.ntriangles = keep;
    topo(&m, &t);
    assert_true(t.genus == 0 && t.boundary_loops == 2);
    acd_mesh_free(&m);
}

/* Every part within tau (none stuck), genus between 0 and the input's, the parts' genus summed
 * at most the input's; the same result for 1 and 2 threads. */
static void check_genus_run(const acd_mesh *m, acd3d_mode mode, double tau, long input_genus, const char *name) {
    acd3d_params p = acd3d_default_params();
    p.mode = mode;
    p.tau = tau;
    p.threads = 1;
    acd3d_result r1, r2;
    acd_error err;
    assert_int_equal(acd3d_decompose(m, &p, &r1, &err), ACD_OK);
    p.threads = 2;
    assert_int_equal(acd3d_decompose(m, &p, &r2, &err), ACD_OK);
    long gsum = 0, gmax = 0;
    for (size_t i = 0; i < r1.nparts; i++) {
        const acd3d_part *q = &r1.parts[i];
        acd3d_leaf_reason why = r1.nodes[q->node].leaf_reason;
        assert_true(why == ACD3D_LEAF_TAU || why == ACD3D_LEAF_FLAT || why == ACD3D_LEAF_JOINED);
        assert_true(q->concavity <= r1.tau * (1 + 1e-12));
        assert_true(q->genus >= 0 && q->genus <= input_genus);
        if (mode == ACD3D_SOLID) assert_int_equal(q->boundary_loops, 0);
        gsum += q->genus;
        if (q->genus > gmax) gmax = q->genus;
    }
    if (mode == ACD3D_SURFACE) assert_true(gsum <= input_genus); /* cutting a surface never adds handles */
    assert_int_equal(r1.nparts, r2.nparts);
    for (size_t i = 0; i < r1.nparts; i++) {
        assert_int_equal(r1.parts[i].mesh.ntriangles, r2.parts[i].mesh.ntriangles);
        assert_int_equal(r1.parts[i].genus, r2.parts[i].genus);
        assert_true(r1.parts[i].concavity == r2.parts[i].concavity);
    }
    print_message("%s %s tau %g: %zu parts, %ld with handles summed (max %ld), input genus %ld\n", name,
                  mode == ACD3D_SOLID ? "solid" : "surface", tau, r1.nparts, gsum, gmax, input_genus);
    acd3d_result_free(&r1);
    acd3d_result_free(&r2);
}

static void test_torus_both_modes(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_torus(&m, 32, 16, 1.0, 0.35));
    check_genus_run(&m, ACD3D_SOLID, 0.1, 1, "torus");
    check_genus_run(&m, ACD3D_SURFACE, 0.1, 1, "torus");
    /* a torus decomposed within tau 0.1 cannot stay one ring: its hull's hole would be bridged */
    acd3d_params p = acd3d_default_params();
    p.mode = ACD3D_SURFACE;
    p.tau = 0.1;
    acd3d_result r;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    for (size_t i = 0; i < r.nparts; i++) assert_int_equal(r.parts[i].genus, 0);
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}

static int load(const char *name, acd_mesh *m) {
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.off", ACD_MESH_DATA, name);
    acd_error err;
    return acd_mesh_read(path, m, &err) == ACD_OK;
}

static void test_real_meshes_with_handles(void **state) {
    (void)state;
    const char *names[] = {"elephant", "knot1"};
    const long genus[] = {3, 1};
    int ran = 0;
    for (int i = 0; i < 2; i++) {
        acd_mesh m;
        if (!load(names[i], &m)) continue;
        ran++;
        check_genus_run(&m, ACD3D_SOLID, 0.1, genus[i], names[i]);
        check_genus_run(&m, ACD3D_SURFACE, 0.1, genus[i], names[i]);
        acd_mesh_free(&m);
    }
    if (!ran) TU_SKIP("no elephant/knot1 in %s (run scripts/fetch-data.sh)", ACD_MESH_DATA);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_topology_of_known_surfaces),
        cmocka_unit_test(test_torus_both_modes),
        cmocka_unit_test(test_real_meshes_with_handles),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
