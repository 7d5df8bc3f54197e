// ctest: LABELS slow TIMEOUT 1800
/* Many handles (spec acd3d.md §6): turbine (genus 11) and cheese (genus 133) finish in both
 * modes with every part within tau (or joined by the merge pass, whose bound is tau), each
 * part's genus reported between 0 and the input's; turbine also the same for 1 and 2 threads. */
#include "testutil.h"

#include <stdio.h>

#include "acd/acd3d.h"

static void run(const acd_mesh *m, acd3d_mode mode, long input_genus, int both_threads, const char *name) {
    acd3d_params p = acd3d_default_params();
    p.mode = mode;
    p.tau = 0.05;
    p.threads = 1;
    acd3d_result r1, r2;
    acd_error err;
    assert_int_equal(acd3d_decompose(m, &p, &r1, &err), ACD_OK);
    long gsum = 0;
    for (size_t i = 0; i < r1.nparts; i++) {
        const acd3d_part *q = &r1.parts[i];
        acd3d_leaf_reason why = r1.nodes[q->node].leaf_reason;
        assert_true(why == ACD3D_LEAF_TAU || why == ACD3D_LEAF_FLAT || why == ACD3D_LEAF_JOINED);
        assert_true(q->concavity <= r1.tau * (1 + 1e-12));
        assert_true(q->genus >= 0 && q->genus <= input_genus);
        gsum += q->genus;
    }
    if (mode == ACD3D_SURFACE) assert_true(gsum <= input_genus);
    if (both_threads) {
        p.threads = 2;
        assert_int_equal(acd3d_decompose(m, &p, &r2, &err), ACD_OK);
        assert_int_equal(r1.nparts, r2.nparts);
        for (size_t i = 0; i < r1.nparts; i++) {
            assert_int_equal(r1.parts[i].mesh.ntriangles, r2.parts[i].mesh.ntriangles);
            assert_int_equal(r1.parts[i].genus, r2.parts[i].genus);
            assert_true(r1.parts[i].concavity == r2.parts[i].concavity);
        }
        acd3d_result_free(&r2);
    }
    print_message("%s %s tau 0.05: %zu parts, genus summed over parts %ld (input %ld), %.1f s\n", name,
                  mode == ACD3D_SOLID ? "solid" : "surface", r1.nparts, gsum, input_genus, r1.seconds);
    acd3d_result_free(&r1);
}

static void test_many_handles(void **state) {
    (void)state;
    const char *names[] = {"turbine", "cheese"};
    const long genus[] = {11, 133};
    int ran = 0;
    for (int i = 0; i < 2; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s.off", ACD_MESH_DATA, names[i]);
        acd_mesh m;
        acd_error err;
        if (acd_mesh_read(path, &m, &err) != ACD_OK) continue;
        ran++;
        run(&m, ACD3D_SOLID, genus[i], i == 0, names[i]);
        run(&m, ACD3D_SURFACE, genus[i], i == 0, names[i]);
        acd_mesh_free(&m);
    }
    if (!ran) TU_SKIP("no turbine/cheese in %s (run scripts/fetch-data.sh)", ACD_MESH_DATA);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_many_handles),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
