/* eval/verify3d (include/acd/verify3d.h): the independent check of a 3D decomposition that
 * `acd 3d --verify` runs, called on library results.
 *  1. a U-shaped block (voxels) decomposed in solid mode, and with --budget and --trim-coverage:
 *     acd3d_verify passes; then each check is made to fail by corrupting a copy of the result:
 *     a part vertex moved out of its hull, a part left out (volumes no longer add up), a tau leaf's
 *     concavity above tau, a budget part's bound above the merge tolerance; the message names the
 *     part and the figures, the same for 1 and 2 threads;
 *  2. surface mode: the patches tile the surface; a face dropped from a patch fails;
 *  3. NULL arguments are refused (ACD_ERR_INVALID_ARGUMENT). */
// ctest: TIMEOUT 300
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd/mesh.h"
#include "acd/verify3d.h"
#include "shapes.h"

/* A U: a 4 x 2 x 3 block of voxels with a 2 x 2 x 2 notch from the top. */
static void u_block(acd_mesh *m) {
    enum { NX = 4, NY = 2, NZ = 3 };
    unsigned char occ[NX * NY * NZ];
    for (int z = 0; z < NZ; z++)
        for (int y = 0; y < NY; y++)
            for (int x = 0; x < NX; x++) occ[(z * NY + y) * NX + x] = !(z >= 1 && x >= 1 && x <= 2);
    memset(m, 0, sizeof *m);
    assert_int_equal(mg_voxels(m, occ, NX, NY, NZ), 1);
}

static void decompose(const acd_mesh *m, const acd3d_params *p, acd3d_result *r) {
    acd_error err;
    acd_status st = acd3d_decompose(m, p, r, &err);
    if (st != ACD_OK) fail_msg("acd3d_decompose: %s", err.message);
    assert_true(r->nparts >= 2);
}

/* acd3d_verify on r with params p at 1 and 2 threads: the same status and message; returns the
 * status, the message in msg. */
static acd_status verify_both(const acd_mesh *m, const acd3d_params *p, const acd3d_result *r, char msg[512]) {
    acd3d_params q = *p;
    acd_error e1, e2;
    memset(&e1, 0, sizeof e1);
    memset(&e2, 0, sizeof e2);
    q.threads = 1;
    acd_status s1 = acd3d_verify(m, &q, r, NULL, &e1);
    q.threads = 2;
    acd_status s2 = acd3d_verify(m, &q, r, NULL, &e2);
    assert_int_equal(s1, s2);
    if (s1 != ACD_OK) assert_string_equal(e1.message, e2.message);
    snprintf(msg, 512, "%s", s1 == ACD_OK ? "" : e1.message);
    return s1;
}

static void expect_fail(const acd_mesh *m, const acd3d_params *p, const acd3d_result *r, const char *what) {
    char msg[512];
    acd_status st = verify_both(m, p, r, msg);
    if (st != ACD_ERR_VERIFY) fail_msg("expected a failure naming '%s', got status %d (%s)", what, (int)st, msg);
    if (!strstr(msg, what)) fail_msg("expected '%s' in: %s", what, msg);
}

/* The part of largest volume. */
static size_t largest(const acd3d_result *r) {
    size_t b = 0;
    for (size_t i = 1; i < r->nparts; i++)
        if (r->parts[i].volume > r->parts[b].volume) b = i;
    return b;
}

static void test_solid(void **state) {
    (void)state;
    acd_mesh m;
    u_block(&m);
    acd3d_params p = acd3d_default_params();
    p.tau = 0.01;
    p.merge = 0;
    acd3d_result r;
    decompose(&m, &p, &r);
    char msg[512];
    acd3d_verify_report rep = {1, 1};
    acd_error err;
    if (acd3d_verify(&m, &p, &r, &rep, &err) != ACD_OK) fail_msg("a clean result fails: %s", err.message);
    assert_true(rep.outside == 0 && rep.nbound == 0);

    /* a vertex of the largest part pushed out of its hull: along +x beyond the hull's box */
    size_t b = largest(&r);
    acd_mesh *pm = &r.parts[b].mesh;
    size_t far = 0;
    for (size_t v = 1; v < pm->nvertices; v++)
        if (pm->vertices[3 * v] > pm->vertices[3 * far]) far = v;
    double keep = pm->vertices[3 * far];
    pm->vertices[3 * far] = keep + 0.05;
    expect_fail(&m, &p, &r, "sticks out of its hull");
    pm->vertices[3 * far] = keep;
    assert_int_equal(verify_both(&m, &p, &r, msg), ACD_OK);

    /* one part left out: the volumes no longer add up to the input's */
    r.nparts--;
    expect_fail(&m, &p, &r, "part volumes add up to");
    r.nparts++;

    /* a tau leaf above tau */
    size_t t = r.nparts;
    for (size_t i = 0; i < r.nparts && t == r.nparts; i++)
        if (r.nodes[r.parts[i].node].leaf_reason == ACD3D_LEAF_TAU) t = i;
    assert_true(t < r.nparts);
    double c = r.parts[t].concavity;
    r.parts[t].concavity = 2 * r.tau + 1e-3;
    expect_fail(&m, &p, &r, "exceeds tau");
    r.parts[t].concavity = c;
    assert_int_equal(verify_both(&m, &p, &r, msg), ACD_OK);
    acd3d_result_free(&r);

    /* a part budget with trimmed hulls: passes, with the outside volume reported */
    acd3d_params bp = acd3d_budget_params(6);
    bp.trim_coverage = 0.0008;
    decompose(&m, &bp, &r);
    if (acd3d_verify(&m, &bp, &r, &rep, &err) != ACD_OK) fail_msg("the budget result fails: %s", err.message);
    assert_true(rep.outside >= 0 && rep.outside <= 0.0008 * r.input_volume * (1 + 1e-6));
    /* a budget part whose bound is above the merge tolerance */
    t = r.nparts;
    for (size_t i = 0; i < r.nparts && t == r.nparts; i++) {
        acd3d_leaf_reason lr = r.nodes[r.parts[i].node].leaf_reason;
        if (lr == ACD3D_LEAF_BUDGET || lr == ACD3D_LEAF_JOINED) t = i;
    }
    assert_true(t < r.nparts);
    c = r.parts[t].concavity;
    r.parts[t].concavity = 2 * r.merge_tau + 1e-3;
    expect_fail(&m, &bp, &r, "exceeds the merge tolerance");
    r.parts[t].concavity = c;
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}

static void test_surface(void **state) {
    (void)state;
    acd_mesh m;
    u_block(&m);
    acd3d_params p = acd3d_default_params();
    p.mode = ACD3D_SURFACE;
    p.tau = 0.01;
    acd3d_result r;
    decompose(&m, &p, &r);
    char msg[512];
    if (verify_both(&m, &p, &r, msg) != ACD_OK) fail_msg("a clean surface result fails: %s", msg);
    /* a face dropped from the largest patch: the parts no longer hold the input's faces */
    size_t b = 0;
    for (size_t i = 1; i < r.nparts; i++)
        if (r.parts[i].mesh.ntriangles > r.parts[b].mesh.ntriangles) b = i;
    r.parts[b].mesh.ntriangles--;
    expect_fail(&m, &p, &r, "the parts hold");
    r.parts[b].mesh.ntriangles++;
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}

static void test_null(void **state) {
    (void)state;
    acd_mesh m;
    u_block(&m);
    acd3d_params p = acd3d_default_params();
    acd3d_result r;
    memset(&r, 0, sizeof r);
    acd_error err;
    assert_int_equal(acd3d_verify(NULL, &p, &r, NULL, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_int_equal(acd3d_verify(&m, NULL, &r, NULL, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_int_equal(acd3d_verify(&m, &p, NULL, NULL, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err.message, "result"));
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_solid),
        cmocka_unit_test(test_surface),
        cmocka_unit_test(test_null),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
