/* Tests of the budget pipeline's settings (acd3d_budget_params, acd3d_params.merge_tau_diag;
 * docs/acd3d.md "Excess-driven budget"): the preset holds the documented values and leaves the rest
 * at the defaults (parts 0: the defaults); merge_tau_diag gives the merge tolerance merge_tau_diag x
 * the bounding-box diagonal, reported in result.merge_tau_relative, and the run is bit for bit the
 * one with merge_tau set to that relative value (in tau's units whether tau is relative or
 * absolute); merge_tau > 0 takes precedence; the preset's run on a bumpy star equals the run with
 * every field written out (the CLI's long form); bad values and the combinations the budget
 * excludes are refused. (The budget pass itself: tests/test_acd3_budget.c; the CLI's short form:
 * tests/cli/3d_budget.sh.) */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "shapes.h"

/* A sphere with bumps (hull excess everywhere), not centred on the origin, longer along x: the
 * diagonal and the radius are not in a simple ratio. */
static void bumpy(acd_mesh *m) {
    assert_true(mg_radial(m, 32, 24, mg_bumpy_r, NULL));
    for (size_t i = 0; i < m->nvertices; i++) {
        m->vertices[3 * i] = 1.5 * m->vertices[3 * i] + 3;
        m->vertices[3 * i + 2] -= 2;
    }
}

/* The bounding-box diagonal, computed as the library's scale does (core/tolerance). */
static double diagonal(const acd_mesh *m) {
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) lo[k] = hi[k] = m->vertices[k];
    for (size_t i = 0; i < m->nvertices; i++)
        for (int k = 0; k < 3; k++) {
            double v = m->vertices[3 * i + k];
            if (v < lo[k]) lo[k] = v;
            if (v > hi[k]) hi[k] = v;
        }
    double d2 = 0;
    for (int k = 0; k < 3; k++) d2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    return sqrt(d2);
}

/* Two results alike, bit for bit in their hulls. */
static void assert_same_hulls(const acd3d_result *a, const acd3d_result *b) {
    assert_true(a->merge_tau == b->merge_tau);
    assert_true(a->tau == b->tau);
    assert_int_equal(a->nparts, b->nparts);
    assert_int_equal(a->nnodes, b->nnodes);
    for (size_t i = 0; i < a->nparts; i++) {
        assert_int_equal(a->parts[i].hull.nvertices, b->parts[i].hull.nvertices);
        assert_int_equal(a->parts[i].hull.ntriangles, b->parts[i].hull.ntriangles);
        assert_memory_equal(a->parts[i].hull.vertices, b->parts[i].hull.vertices,
                            3 * a->parts[i].hull.nvertices * sizeof(double));
        assert_memory_equal(a->parts[i].hull.triangles, b->parts[i].hull.triangles,
                            3 * a->parts[i].hull.ntriangles * sizeof(uint32_t));
        assert_true(a->parts[i].concavity == b->parts[i].concavity);
    }
}

static void test_preset(void **state) {
    (void)state;
    const acd3d_params d = acd3d_default_params();
    acd3d_params p = acd3d_budget_params(40);
    assert_int_equal(p.cookie, ACD3D_PARAMS_COOKIE);
    assert_int_equal(p.budget_parts, 40);
    assert_int_equal(p.merge_parts, 40);
    assert_int_equal(p.merge_refine, ACD3D_BUDGET_MERGE_REFINE);
    assert_int_equal(p.merge_refine, 40);
    assert_true(p.tau == ACD3D_BUDGET_TAU && p.tau == 10.0);
    assert_int_equal(p.tau_absolute, 0);
    assert_true(p.merge_tau == 0);
    assert_true(p.merge_tau_diag == ACD3D_BUDGET_MERGE_TAU_DIAG && p.merge_tau_diag == 0.0195);
    assert_int_equal(p.cut_choice, ACD3D_CHOICE_VOLUME);
    assert_int_equal(p.merge_order, ACD3D_MERGE_VOLUME);
    /* the rest as the defaults */
    assert_int_equal(p.mode, ACD3D_SOLID);
    assert_int_equal(p.merge, 1);
    assert_int_equal(p.max_hulls, 0);
    assert_int_equal(p.max_hull_vertices, 0);
    assert_true(p.eps_ratio == d.eps_ratio && p.delta_ratio == d.delta_ratio);
    assert_int_equal(p.weight, d.weight);
    assert_int_equal(p.resolver, d.resolver);
    assert_int_equal(p.max_depth, d.max_depth);
    assert_int_equal(p.stop, d.stop);
    assert_int_equal(p.region_cuts, d.region_cuts);
    assert_int_equal(p.surface_cut, d.surface_cut);
    assert_int_equal(p.threads, d.threads);
    assert_null(p.progress);
    /* the defaults: no merge_tau_diag, no budget */
    assert_true(d.merge_tau_diag == 0);
    assert_int_equal(d.budget_parts, 0);
    p = acd3d_budget_params(0);
    assert_int_equal(p.budget_parts, 0);
    assert_int_equal(p.merge_parts, 0);
    assert_int_equal(p.merge_refine, 0);
    assert_true(p.tau == d.tau && p.merge_tau_diag == 0);
    assert_int_equal(p.cut_choice, d.cut_choice);
    assert_int_equal(p.merge_order, d.merge_order);
}

static void test_merge_tau_diag(void **state) {
    (void)state;
    acd_mesh m;
    bumpy(&m);
    const double diag = diagonal(&m), f = 0.06;
    acd_error err;
    acd3d_result a, b, c;
    acd3d_params p = acd3d_default_params();
    p.threads = 2;
    p.tau = 0.05;
    p.merge_tau_diag = f;
    assert_int_equal(acd3d_decompose(&m, &p, &a, &err), ACD_OK);
    print_message("diagonal %.17g, radius %.17g, merge tau %.17g (relative %.17g), %zu parts\n", diag, a.scale,
                  a.merge_tau, a.merge_tau_relative, a.nparts);
    assert_true(a.merge_tau_relative == f * diag / a.scale);
    assert_true(a.merge_tau == a.merge_tau_relative * a.scale);
    assert_true(fabs(a.merge_tau - f * diag) <= 1e-14 * a.merge_tau);
    assert_true(a.merge_tau > 1.5 * a.tau); /* not tau's fallback: 0.06 diagonal is 0.12+ radius */
    for (size_t i = 0; i < a.nparts; i++)
        if (a.nodes[a.parts[i].node].leaf_reason == ACD3D_LEAF_JOINED)
            assert_true(a.parts[i].concavity <= a.merge_tau * (1 + 1e-12));
    /* the same run as merge_tau = the relative value */
    p.merge_tau_diag = 0;
    p.merge_tau = a.merge_tau_relative;
    assert_int_equal(acd3d_decompose(&m, &p, &b, &err), ACD_OK);
    assert_true(b.merge_tau_relative == a.merge_tau_relative);
    assert_same_hulls(&a, &b);
    acd3d_result_free(&b);
    /* merge_tau_diag does not depend on tau's units: tau absolute, the same merge tolerance */
    p.merge_tau = 0;
    p.merge_tau_diag = f;
    p.tau_absolute = 1;
    p.tau = a.tau;
    assert_int_equal(acd3d_decompose(&m, &p, &b, &err), ACD_OK);
    assert_true(b.merge_tau == a.merge_tau);
    assert_true(b.merge_tau_relative == a.merge_tau_relative);
    acd3d_result_free(&b);
    p.tau_absolute = 0;
    p.tau = 0.05;
    /* merge_tau > 0 takes precedence */
    p.merge_tau = 0.07;
    assert_int_equal(acd3d_decompose(&m, &p, &c, &err), ACD_OK);
    assert_true(c.merge_tau == 0.07 * c.scale);
    assert_true(c.merge_tau_relative == 0.07);
    acd3d_result_free(&c);
    /* neither: tau */
    p.merge_tau = 0;
    p.merge_tau_diag = 0;
    assert_int_equal(acd3d_decompose(&m, &p, &c, &err), ACD_OK);
    assert_true(c.merge_tau == c.tau);
    assert_true(c.merge_tau_relative == 0.05);
    acd3d_result_free(&c);
    acd3d_result_free(&a);
    acd_mesh_free(&m);
}

/* The preset's run is the run with every setting written out (the CLI's long form with the merge
 * tolerance in tau's units), and not the default's. */
static void test_preset_equals_long_form(void **state) {
    (void)state;
    acd_mesh m;
    bumpy(&m);
    enum { N = 5 };
    acd_error err;
    acd3d_result s, l, d;
    acd3d_params p = acd3d_budget_params(N);
    p.threads = 2;
    assert_int_equal(acd3d_decompose(&m, &p, &s, &err), ACD_OK);
    print_message("budget %d: %zu parts, merge tau %.17g (relative %.17g)\n", N, s.nparts, s.merge_tau,
                  s.merge_tau_relative);
    assert_true(s.nparts >= N); /* every part within 0.0195 of the diagonal: beyond the budget on these bumps */
    assert_true(s.merge_tau_relative == ACD3D_BUDGET_MERGE_TAU_DIAG * diagonal(&m) / s.scale);
    size_t budget_nodes = 0;
    for (size_t n = 0; n < s.nnodes; n++) budget_nodes += s.nodes[n].leaf_reason == ACD3D_LEAF_BUDGET;
    assert_true(budget_nodes >= N);
    acd3d_params q = acd3d_default_params();
    q.threads = 2;
    q.tau = 10;
    q.budget_parts = N;
    q.merge_tau = s.merge_tau_relative;
    q.cut_choice = ACD3D_CHOICE_VOLUME;
    q.merge_order = ACD3D_MERGE_VOLUME;
    q.merge_parts = N;
    q.merge_refine = 40;
    assert_int_equal(acd3d_decompose(&m, &q, &l, &err), ACD_OK);
    assert_same_hulls(&s, &l);
    /* the defaults with only budget_parts set (what the CLI's --budget alone ran before) differ */
    q = acd3d_default_params();
    q.threads = 2;
    q.budget_parts = N;
    assert_int_equal(acd3d_decompose(&m, &q, &d, &err), ACD_OK);
    assert_true(d.tau != s.tau && d.merge_tau != s.merge_tau);
    acd3d_result_free(&s);
    acd3d_result_free(&l);
    acd3d_result_free(&d);
    acd_mesh_free(&m);
}

static void test_refused(void **state) {
    (void)state;
    acd_mesh m;
    bumpy(&m);
    acd_error err;
    acd3d_result r;
    const double bad[] = {-0.01, NAN, INFINITY};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        acd3d_params p = acd3d_default_params();
        p.merge_tau_diag = bad[i];
        assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_INVALID_ARGUMENT);
        assert_non_null(strstr(err.message, "merge_tau_diag"));
    }
    acd3d_params p = acd3d_budget_params(8);
    p.max_hulls = 4;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err.message, "exclude each other"));
    p = acd3d_budget_params(8);
    p.mode = ACD3D_SURFACE;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err.message, "solid mode only"));
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_preset),
        cmocka_unit_test(test_merge_tau_diag),
        cmocka_unit_test(test_preset_equals_long_form),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
