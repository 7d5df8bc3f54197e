/* Progress and cancellation of acd3d_decompose (issue 4 item 7: "progress on stderr for runs over a
 * second; cancellable through the API") in every stage of a run: the tree, the part budget
 * (acd3/budget), the solid merge pass with its refinement (acd3/merge) and surface mode's merge pass
 * (acd3/surface_merge). On a bumpy sphere with
 * the budget pipeline: each stage reports (fractions in [0, 1] and not decreasing within a stage,
 * or -1), a callback that returns non-zero in a stage makes the call return ACD_ERR_CANCELLED with a
 * message and no result (the ASan build checks nothing leaks), and a callback that never cancels
 * leaves the output bit for bit as without one. */
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "shapes.h"

typedef struct seen {
    const char *cancel_prefix; /* cancel at the first stage starting with it (NULL: never) */
    int tree, budget, join, refine, surface, other;
    double last_fraction;
    char last_stage[64];
} seen;

static int starts(const char *s, const char *p) { return !strncmp(s, p, strlen(p)); }

static int on_progress(void *user, double fraction, const char *stage) {
    seen *S = user;
    assert_true(fraction == -1.0 || (fraction >= 0 && fraction <= 1));
    if (!strcmp(stage, S->last_stage) && fraction >= 0 && S->last_fraction >= 0)
        assert_true(fraction >= S->last_fraction); /* not decreasing within a stage */
    S->last_fraction = fraction;
    snprintf(S->last_stage, sizeof S->last_stage, "%s", stage);
    if (starts(stage, "measuring")) S->tree++;
    else if (starts(stage, "budget")) S->budget++;
    else if (starts(stage, "merge: joining surface")) S->surface++;
    else if (starts(stage, "merge: joining")) S->join++;
    else if (starts(stage, "merge: refining")) S->refine++;
    else S->other++;
    return S->cancel_prefix && starts(stage, S->cancel_prefix);
}

/* Counts as on_progress does, and cancels at the second call. */
static int cancel_second(void *user, double fraction, const char *stage) {
    seen *S = user;
    on_progress(user, fraction, stage);
    return S->tree + S->budget + S->join + S->refine + S->surface + S->other >= 2;
}

/* The budget pipeline (docs/acd3d.md "Excess-driven budget") at 8 parts, refined. */
static acd3d_params budget_params(void) {
    acd3d_params p = acd3d_default_params();
    p.tau = 10;
    p.budget_parts = 8;
    p.cut_choice = ACD3D_CHOICE_VOLUME;
    p.merge_order = ACD3D_MERGE_VOLUME;
    p.merge_parts = 6;
    p.merge_refine = 4;
    p.merge_tau = 0.3;
    p.threads = 2;
    return p;
}

static void test_stages_reported(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 48, 32, mg_bumpy_r, NULL));
    acd3d_params p = budget_params();
    seen S = {.last_fraction = -1};
    p.progress = on_progress;
    p.progress_user = &S;
    acd3d_result r, q;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    print_message("tree %d, budget %d, join %d, refine %d, other %d; %zu parts\n", S.tree, S.budget, S.join,
                  S.refine, S.other, r.nparts);
    assert_true(S.tree >= 1);
    assert_true(S.budget >= 8 - 1); /* one report per cut at least */
    assert_true(S.join >= 1);       /* 8 parts joined down to 6 */
    assert_true(S.refine >= 1);
    /* without a callback: the same output */
    p.progress = NULL;
    assert_int_equal(acd3d_decompose(&m, &p, &q, &err), ACD_OK);
    assert_int_equal(q.nparts, r.nparts);
    for (size_t i = 0; i < q.nparts; i++) {
        assert_true(q.parts[i].hull_volume == r.parts[i].hull_volume);
        assert_int_equal(q.parts[i].hull.nvertices, r.parts[i].hull.nvertices);
        assert_memory_equal(q.parts[i].hull.vertices, r.parts[i].hull.vertices,
                            3 * q.parts[i].hull.nvertices * sizeof(double));
    }
    acd3d_result_free(&r);
    acd3d_result_free(&q);
    acd_mesh_free(&m);
}

/* Cancelled in each stage: ACD_ERR_CANCELLED, a message, and no later stage reached. */
static void test_cancel_in_each_stage(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 48, 32, mg_bumpy_r, NULL));
    const char *stages[] = {"measuring", "budget", "merge: joining", "merge: refining"};
    for (size_t k = 0; k < sizeof stages / sizeof *stages; k++) {
        acd3d_params p = budget_params();
        seen S = {.cancel_prefix = stages[k], .last_fraction = -1};
        p.progress = on_progress;
        p.progress_user = &S;
        acd3d_result r;
        acd_error err = {0};
        assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_CANCELLED);
        assert_non_null(strstr(err.message, "cancelled"));
        print_message("cancel at '%s': %s\n", stages[k], err.message);
        if (k < 3) assert_int_equal(S.refine, 0);
        if (k < 2) assert_int_equal(S.join, 0);
        if (k < 1) assert_int_equal(S.budget, 0);
    }
    acd_mesh_free(&m);
}

/* The tree polls the callback within a batch of nodes too (between candidate cuts, before each cut
 * try: the root's batch is most of a large mesh's run), not only once per batch: with one thread
 * every split node calls it at least three times (before its try, before claiming its first
 * candidate, once more when its candidates are done), so a run makes more calls than it has nodes
 * (one call per batch, at most one per tree level, would be far fewer). Cancelled at the second
 * call (inside the root's batch): ACD_ERR_CANCELLED, and no call after it. */
static void test_cancel_within_batch(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 48, 32, mg_bumpy_r, NULL));
    acd3d_params p = acd3d_default_params();
    p.threads = 1;
    seen S = {.last_fraction = -1};
    p.progress = on_progress;
    p.progress_user = &S;
    acd3d_result r;
    acd_error err = {0};
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    print_message("%d tree calls, %zu nodes, %zu parts\n", S.tree, r.nnodes, r.nparts);
    assert_true(r.nnodes >= 3);
    assert_true((size_t)S.tree > r.nnodes);
    acd3d_result_free(&r);
    seen C = {.cancel_prefix = NULL, .last_fraction = -1};
    p.progress = cancel_second;
    p.progress_user = &C;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_CANCELLED);
    assert_non_null(strstr(err.message, "cancelled"));
    assert_int_equal(C.tree, 2);
    assert_int_equal(C.other + C.budget + C.join + C.refine, 0);
    acd_mesh_free(&m);
}

/* Surface mode's merge pass (acd3/surface_merge): reported, and cancelled there. */
static void test_surface_merge(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 32, 20, mg_bumpy_r, NULL));
    acd3d_params p = acd3d_default_params();
    p.mode = ACD3D_SURFACE;
    p.tau = 0.05;
    p.threads = 2;
    seen S = {.last_fraction = -1};
    p.progress = on_progress;
    p.progress_user = &S;
    acd3d_result r;
    acd_error err = {0};
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    print_message("surface: tree %d, surface merge %d, other %d; %zu parts\n", S.tree, S.surface, S.other, r.nparts);
    assert_true(S.surface >= 1);
    assert_int_equal(S.budget + S.join + S.refine, 0);
    acd3d_result_free(&r);
    seen C = {.cancel_prefix = "merge: joining surface", .last_fraction = -1};
    p.progress_user = &C;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_CANCELLED);
    assert_non_null(strstr(err.message, "cancelled"));
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stages_reported),
        cmocka_unit_test(test_cancel_in_each_stage),
        cmocka_unit_test(test_cancel_within_batch),
        cmocka_unit_test(test_surface_merge),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
