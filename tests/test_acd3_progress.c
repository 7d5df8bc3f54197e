/* Progress and cancellation of acd3d_decompose (issue 4 item 7: "progress on stderr for runs over a
 * second; cancellable through the API") in every stage of a run: the tree, the part budget
 * (acd3/budget), the solid merge pass with its refinement (acd3/merge) and surface mode's merge pass
 * (acd3/surface_merge). On a bumpy sphere with
 * the budget pipeline: each stage reports (fractions in [0, 1] and not decreasing within a stage,
 * or -1), a callback that returns non-zero in a stage makes the call return ACD_ERR_CANCELLED with a
 * message and no result (the ASan build checks nothing leaks), and a callback that never cancels
 * leaves the output bit for bit as without one. The tree's callback is also called within a node's
 * work (acd3/poll): the measure (acd3/measure), the global cut's graph (acd3/pocket_cut) and the
 * checks of the input, so a large root part does not keep it silent. */
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd3d_check.h"
#include "acd3/measure.h"
#include "acd3/pocket_cut.h"
#include "acd3/poll.h"
#include "shapes.h"

typedef struct seen {
    const char *cancel_prefix; /* cancel at the first stage starting with it (NULL: never) */
    int check, tree, budget, join, refine, surface, other;
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
    if (starts(stage, "checking the input")) S->check++;
    else if (starts(stage, "measuring")) S->tree++;
    else if (starts(stage, "budget")) S->budget++;
    else if (starts(stage, "merge: joining surface")) S->surface++;
    else if (starts(stage, "merge: joining")) S->join++;
    else if (starts(stage, "merge: refining")) S->refine++;
    else S->other++;
    return S->cancel_prefix && starts(stage, S->cancel_prefix);
}

/* Counts as on_progress does, and cancels at the second call of the tree. */
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
    ck3_same_hulls(&q, &r);
    acd3d_result_free(&r);
    acd3d_result_free(&q);
    acd_mesh_free(&m);
}

/* Cancelled in each stage: ACD_ERR_CANCELLED, a message, and no later stage reached. */
static void test_cancel_in_each_stage(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 48, 32, mg_bumpy_r, NULL));
    const char *stages[] = {"measuring", "budget", "merge: preparing", "merge: joining", "merge: refining"};
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
        if (k < 4) assert_int_equal(S.refine, 0);
        if (k < 3) assert_int_equal(S.join, 0);
        if (k < 1) assert_int_equal(S.budget, 0);
    }
    acd_mesh_free(&m);
}

/* The stage of every call (static strings of the library), and a stop at call stop_at (1-based; 0:
 * never) or at the first call of stage stop_stage (NULL: never). */
#define LOG_CALLS 16384
typedef struct call_log {
    const char *stage[LOG_CALLS];
    int n, stop_at, after_stop;
    const char *stop_stage;
    int stop_stage_nth, stage_seen; /* stop at the stop_stage_nth call of stop_stage (0: the first) */
    int stopped;
} call_log;

static int log_call(void *user, double fraction, const char *stage) {
    (void)fraction;
    call_log *l = user;
    if (l->stopped) l->after_stop++;
    if (l->n < LOG_CALLS) l->stage[l->n] = stage;
    l->n++;
    if (l->stop_stage && !strcmp(stage, l->stop_stage)) l->stage_seen++;
    if ((l->stop_at && l->n == l->stop_at) ||
        (l->stop_stage && !strcmp(stage, l->stop_stage) && l->stage_seen >= l->stop_stage_nth))
        l->stopped = 1;
    return l->stopped;
}

static int log_count(const call_log *l, const char *stage) {
    int c = 0;
    for (int i = 0; i < l->n && i < LOG_CALLS; i++) c += !strcmp(l->stage[i], stage);
    return c;
}

/* The merge pass's set-up calls the callback within its steps, not only between them: before each
 * part's tree and hull ("merge: preparing the parts' hulls", from the calling thread: 2.3 CPU-s
 * without a call at 832k faces before, with the input's tree: "merge: preparing the input's tree"
 * before it) and between chunks of MERGE_SCORE_POLL_PAIRS pairs of the first scoring ("merge:
 * scoring adjacent pairs", 0.5 CPU-s). On the bumpy sphere, default
 * parameters (88 parts joined down to 48): with 1 thread a stop at the first, second, middle and
 * last call of each of those stages returns ACD_ERR_CANCELLED at once (no call after it), with 2
 * threads at the first call; a callback that never stops leaves the parts as without one. */
static void test_cancel_in_merge_setup(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 48, 32, mg_bumpy_r, NULL));
    acd3d_params p = acd3d_default_params();
    p.threads = 1;
    static call_log all;
    memset(&all, 0, sizeof all);
    p.progress = log_call;
    p.progress_user = &all;
    acd3d_result r, q;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_true(all.n < LOG_CALLS);
    const char *within[] = {"merge: preparing the parts' hulls", "merge: scoring adjacent pairs",
                            "merge: preparing the input's tree"};
    for (int k = 0; k < 3; k++) print_message("%s: %d calls\n", within[k], log_count(&all, within[k]));
    print_message("%d calls, %zu parts\n", all.n, r.nparts);
    assert_true(log_count(&all, within[0]) >= 8);
    assert_true(log_count(&all, within[1]) >= 2);
    assert_int_equal(log_count(&all, within[2]), 1);
    p.progress = NULL;
    assert_int_equal(acd3d_decompose(&m, &p, &q, &err), ACD_OK);
    ck3_same_hulls(&q, &r);
    acd3d_result_free(&q);
    acd3d_result_free(&r);
    static call_log c;
    for (int k = 0; k < 3; k++) {
        int first = 0, last = 0; /* 1-based call numbers; the stage's calls are consecutive */
        for (int i = 1; i <= all.n; i++)
            if (!strcmp(all.stage[i - 1], within[k])) {
                if (!first) first = i;
                last = i;
            }
        assert_int_equal(last - first + 1, log_count(&all, within[k]));
        const int at[4] = {first, first + 1, (first + last) / 2, last};
        for (int j = 0; j < 4 && at[j] <= last; j++) {
            memset(&c, 0, sizeof c);
            c.stop_at = at[j];
            p.progress = log_call;
            p.progress_user = &c;
            assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_CANCELLED);
            assert_int_equal(c.n, at[j]);
            assert_string_equal(c.stage[at[j] - 1], within[k]);
            assert_non_null(strstr(err.message, "cancelled"));
            assert_non_null(strstr(err.message, within[k])); /* the stage it stopped in */
        }
    }
    p.threads = 2;
    for (int k = 0; k < 3; k++) {
        memset(&c, 0, sizeof c);
        c.stop_stage = within[k];
        p.progress_user = &c;
        assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_CANCELLED);
        assert_int_equal(c.after_stop, 0);
        assert_string_equal(c.stage[c.n - 1], within[k]);
    }
    acd_mesh_free(&m);
}

/* The trim's set-up (acd3/trim: each part's hull, tree and planes, the input's self-crossing test)
 * calls the callback before each task and between a part's steps ("trim: preparing", from the
 * calling thread: 3.3 CPU-s without a call at 832k faces before the first "trim" call). On the bumpy
 * sphere, the budget pipeline with trim_coverage 0.005: with 1 and 2 threads a stop at the stage's
 * first and middle (2 threads: second) call returns ACD_ERR_CANCELLED at once (no call after it) naming the stage (the
 * ASan build checks everything is freed); a callback that never stops leaves the trimmed hulls as
 * without one. */
static void test_cancel_in_trim_setup(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 48, 32, mg_bumpy_r, NULL));
    const char *stage = "trim: preparing";
    for (int threads = 1; threads <= 2; threads++) {
        acd3d_params p = budget_params();
        p.trim_coverage = 0.005;
        p.threads = threads;
        static call_log all, c;
        memset(&all, 0, sizeof all);
        p.progress = log_call;
        p.progress_user = &all;
        acd3d_result r, q;
        acd_error err;
        assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
        assert_true(all.n < LOG_CALLS);
        assert_true(r.trim_cuts > 0);
        int first = 0, last = 0; /* 1-based call numbers; the stage's calls are consecutive */
        for (int i = 1; i <= all.n; i++)
            if (!strcmp(all.stage[i - 1], stage)) {
                if (!first) first = i;
                last = i;
            }
        print_message("%d threads: %s: %d calls (%d to %d of %d), %zu trim cuts\n", threads, stage,
                      log_count(&all, stage), first, last, all.n, r.trim_cuts);
        assert_true(log_count(&all, stage) >= 8);
        assert_int_equal(last - first + 1, log_count(&all, stage));
        assert_string_equal(all.stage[last], "trim"); /* the set-up's calls come right before the trim's */
        p.progress = NULL;
        assert_int_equal(acd3d_decompose(&m, &p, &q, &err), ACD_OK);
        ck3_same_hulls(&q, &r);
        acd3d_result_free(&q);
        acd3d_result_free(&r);
        /* the stage's first call, and its middle one (2 threads: its second; the calling thread's
         * share of the tasks varies, the calls before and after them do not) */
        const int nth[2] = {1, threads == 1 ? (last - first) / 2 + 1 : 2};
        for (int k = 0; k < 2; k++) {
            memset(&c, 0, sizeof c);
            c.stop_stage = stage;
            c.stop_stage_nth = nth[k];
            p.progress = log_call;
            p.progress_user = &c;
            assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_CANCELLED);
            if (threads == 1) assert_int_equal(c.n, first + nth[k] - 1);
            assert_int_equal(c.stage_seen, nth[k]);
            assert_int_equal(c.after_stop, 0);
            assert_string_equal(c.stage[c.n - 1], stage);
            assert_non_null(strstr(err.message, "cancelled"));
            assert_non_null(strstr(err.message, stage));
        }
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
    assert_true(C.check >= 1); /* the checks of the input call it too */
    acd_mesh_free(&m);
}

/* A bumpy sphere of 25,600 triangles whose root part is a leaf (tau above its concavity): the tree
 * does nothing but the root's measure after the batch's first call. The measure calls the callback
 * (between its phases and every few projected hull edges): a callback that cancels at the tree's
 * second call (inside the measure) gets ACD_ERR_CANCELLED (without the poll in the measure there is
 * no second call: the run ends ACD_OK); not cancelled, the output is the same as without a
 * callback. With two threads too (the calling thread takes the root: it is the one that calls). */
static void test_cancel_in_root_measure(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 160, 80, mg_bumpy_r, NULL));
    for (int threads = 1; threads <= 2; threads++) {
        acd3d_params p = acd3d_default_params();
        p.tau = 10; /* the root is within tau */
        p.threads = threads;
        seen S = {.last_fraction = -1};
        p.progress = on_progress;
        p.progress_user = &S;
        acd3d_result r, q;
        acd_error err = {0};
        assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
        print_message("%d thread(s): %d checks, %d tree calls (1 before the root's measure), %zu parts\n", threads,
                      S.check, S.tree, r.nparts);
        assert_int_equal(r.nparts, 1);
        assert_true(S.tree >= 5);
        p.progress = NULL;
        assert_int_equal(acd3d_decompose(&m, &p, &q, &err), ACD_OK);
        assert_int_equal(q.parts[0].hull.nvertices, r.parts[0].hull.nvertices);
        assert_memory_equal(q.parts[0].hull.vertices, r.parts[0].hull.vertices,
                            3 * q.parts[0].hull.nvertices * sizeof(double));
        assert_true(q.parts[0].concavity == r.parts[0].concavity);
        acd3d_result_free(&r);
        acd3d_result_free(&q);
        seen C = {.last_fraction = -1};
        p.progress = cancel_second;
        p.progress_user = &C;
        assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_CANCELLED);
        assert_non_null(strstr(err.message, "cancelled"));
        assert_int_equal(C.tree, 2);
    }
    acd_mesh_free(&m);
}

/* acd3_measure_compute_hull and acd3_cut_graph_build with a poll: the same measure and cut graph as
 * without one when it never says stop; cancelled at every call in turn, ACD_ERR_CANCELLED and
 * nothing kept (each exit frees what it made: the ASan build checks). Fails without the polls (no
 * poll argument; in the tree, no call within the measure). */
static void test_measure_and_cut_graph_polls(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 80, 48, mg_bumpy_r, NULL));
    acd_edge_graph g;
    acd_error err = {0};
    assert_int_equal(acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &g, &err), ACD_OK);
    const double eps = 0.01, tol = 1e-9;
    acd3_measure ref, ms;
    assert_int_equal(acd3_measure_compute(&m, &g, eps, tol, &ref, &err), ACD_OK);
    tu_counter c = {0, 0};
    acd3_poll poll = acd3_poll_make(tu_count_calls, &c, "measuring and cutting");
    assert_int_equal(acd3_measure_compute_hull(&m, &g, NULL, eps, tol, &poll, &ms, &err), ACD_OK);
    const int ncalls = c.calls;
    print_message("measure: %d calls (%zu projected hull edges)\n", ncalls, ms.nprojected);
    assert_true(ncalls >= 5);
    assert_true(ms.concavity == ref.concavity);
    assert_int_equal(ms.witness, ref.witness);
    assert_memory_equal(ms.vconc, ref.vconc, m.nvertices * sizeof *ms.vconc);
    acd3_measure_free(&ms);
    /* every exit: the first calls (after the hull, the patches, the open surfaces' rule), a few
     * within the projection, the last two (after the pockets' flood and the handle cuts) */
    for (int k = 1; k <= ncalls; k = k < 4 || k >= ncalls - 2 ? k + 1 : k + ncalls / 4 > ncalls - 2 ? ncalls - 1 : k + ncalls / 4) {
        c = (tu_counter){0, k};
        poll = acd3_poll_make(tu_count_calls, &c, "measuring and cutting");
        assert_int_equal(acd3_measure_compute_hull(&m, &g, NULL, eps, tol, &poll, &ms, &err), ACD_ERR_CANCELLED);
        assert_int_equal(c.calls, k);
        assert_null(ms.vconc);
    }
    /* the cut graph: polled per knot source */
    const acd3_gc_opts o = {2 * eps, 0.2 * eps, ACD3D_WEIGHT_RATIO, 0, 0};
    acd3_cut_graph cg0, cg;
    assert_int_equal(acd3_cut_graph_build(&m, &g, &ref, &o, NULL, &cg0, &err), ACD_OK);
    c = (tu_counter){0, 0};
    poll = acd3_poll_make(tu_count_calls, &c, "measuring and cutting");
    assert_int_equal(acd3_cut_graph_build(&m, &g, &ref, &o, &poll, &cg, &err), ACD_OK);
    const int ncg = c.calls;
    print_message("cut graph: %d calls, %zu cuts\n", ncg, cg.ncuts);
    assert_true(ncg >= 1);
    assert_int_equal(cg.ncuts, cg0.ncuts);
    acd3_cut_graph_free(&cg);
    acd3_cut_graph_free(&cg0);
    /* (cancelled at the first calls, then at a few spread over the rest: the calls are many) */
    for (int k = 1; k <= ncg; k = k < 4 ? k + 1 : k + ncg / 5 + 1) {
        c = (tu_counter){0, k};
        poll = acd3_poll_make(tu_count_calls, &c, "measuring and cutting");
        assert_int_equal(acd3_cut_graph_build(&m, &g, &ref, &o, &poll, &cg, &err), ACD_ERR_CANCELLED);
        assert_int_equal(c.calls, k);
    }
    acd3_measure_free(&ref);
    acd_edge_graph_free(&g);
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
        cmocka_unit_test(test_cancel_in_merge_setup),
        cmocka_unit_test(test_cancel_in_trim_setup),
        cmocka_unit_test(test_cancel_within_batch),
        cmocka_unit_test(test_cancel_in_root_measure),
        cmocka_unit_test(test_measure_and_cut_graph_polls),
        cmocka_unit_test(test_surface_merge),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
