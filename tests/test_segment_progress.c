/* Progress and cancellation of acd_segment within its steps (docs/corise.md "Progress and
 * cancellation"): the CoRiSe loop polls its callback inside a part's valley searches ("corise:
 * bridges"), its regions ("corise: regions") and its cuts' max-flows ("corise: cut"), and acd_segment
 * inside the input's preparation and the parts' hulls, so a large part does not keep it silent (12
 * CPU-s at 832k facets before). On a noisy two-bulb sphere: every such stage is polled more than
 * once; a callback that stops at a call inside one of them makes acd_segment return
 * ACD_ERR_CANCELLED at once (no call after it, no result; the ASan build checks nothing leaks), with
 * 1 and 2 threads; a callback that never stops leaves the result bit for bit as without one. The
 * steps' own functions, given a poll that stops, return ACD_ERR_CANCELLED and free what they made,
 * and give the same output bit for bit with a poll that never stops. */
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/segment.h"
#include "acd3/poll.h"
#include "corise/cut.h"
#include "corise/maxflow.h"
#include "corise/regions.h"
#include "corise/ridge.h"
#include "corise/valley.h"
#include "geom3/dijkstra.h"
#include "shapes.h"

/* r = 1 - k sin^2(theta): two bulbs along z joined by a waist of radius 1 - k */
static double waist_r(double th, double ph, void *u) {
    (void)ph;
    double k = *(double *)u, s = sin(th);
    return 1.0 - k * s * s;
}

/* The noisy two-bulb sphere of test_segment_api (many bridges of every length), 128 x 64. */
static void bulbs(acd_mesh *m) {
    double k = 0.6;
    assert_true(mg_radial(m, 128, 64, waist_r, &k));
    for (size_t v = 0; v < m->nvertices; v++)
        for (int c = 0; c < 3; c++) m->vertices[3 * v + c] *= 1 + 0.05 * sin(7.0 * (double)v + c);
}

#define MAXCALLS 20000

typedef struct rec {
    const char *stage[MAXCALLS]; /* static strings of the library */
    size_t n;
    size_t stop_at;          /* stop at call number stop_at (1-based; 0: never) */
    const char *stop_stage;  /* or at the first call of this stage (NULL: never) */
    int after_stop;          /* calls after the one that said stop */
    int stopped;
} rec;

static int on_progress(void *user, double fraction, const char *stage) {
    rec *r = user;
    assert_true(fraction >= 0 && fraction <= 1);
    if (r->stopped) r->after_stop++;
    if (r->n < MAXCALLS) r->stage[r->n] = stage;
    r->n++;
    if ((r->stop_at && r->n == r->stop_at) || (r->stop_stage && !strcmp(stage, r->stop_stage))) r->stopped = 1;
    return r->stopped;
}

static void run(const acd_mesh *m, int threads, rec *r, acd_segment_result *out, acd_status want) {
    acd_segment_params p = acd_segment_default_params();
    p.threads = threads;
    p.progress = on_progress;
    p.progress_user = r;
    acd_error err;
    acd_status st = acd_segment(m, &p, out, &err);
    assert_int_equal(st, want);
    if (want == ACD_ERR_CANCELLED) {
        assert_int_equal(r->after_stop, 0); /* returned at once: the callback was not called again */
        assert_null(out->labels);
        assert_null(out->parts);
        assert_non_null(strstr(err.message, "cancelled"));
    }
}

static size_t count_stage(const rec *r, const char *stage) {
    size_t c = 0;
    for (size_t i = 0; i < r->n && i < MAXCALLS; i++) c += !strcmp(r->stage[i], stage);
    return c;
}

/* The index (1-based call number) of the middle call of stage's first run of consecutive calls. */
static size_t middle_of_first_run(const rec *r, const char *stage) {
    size_t i = 0;
    while (i < r->n && strcmp(r->stage[i], stage)) i++;
    size_t j = i;
    while (j < r->n && !strcmp(r->stage[j], stage)) j++;
    assert_true(j > i);
    return i + (j - i) / 2 + 1;
}

static void test_cancel_within_steps(void **state) {
    (void)state;
    acd_mesh m;
    bulbs(&m);
    /* a run that is never stopped: the reference, every stage polled */
    static rec all;
    memset(&all, 0, sizeof all);
    acd_segment_result ref, r;
    run(&m, 1, &all, &ref, ACD_OK);
    assert_true(ref.nparts >= 2);
    const char *stages[] = {"segment: preparing", "corise: preparing", "corise: extracting", "corise: bridges",
                            "corise: regions",    "corise: cut",       "corise: pieces",     "segment: hulls"};
    for (size_t s = 0; s < sizeof stages / sizeof *stages; s++) {
        size_t c = count_stage(&all, stages[s]);
        print_message("%s: %zu calls\n", stages[s], c);
        assert_true(c >= 1);
    }
    print_message("%zu calls in all, %zu parts\n", all.n, ref.nparts);
    assert_true(all.n < MAXCALLS);
    /* the root's valleys, regions and cut are polled within (the root's bridges: after the hull and
       in its valley searches; its cut: in its max-flow) */
    const char *within[] = {"corise: bridges", "corise: regions", "corise: cut"};
    for (size_t s = 0; s < 3; s++) {
        size_t i = middle_of_first_run(&all, within[s]);
        assert_true(i >= 2 && !strcmp(all.stage[i - 2], within[s])); /* a call of the stage before it */
        assert_true(i < all.n && !strcmp(all.stage[i], within[s]));  /* and one after it */
        static rec c;
        memset(&c, 0, sizeof c);
        c.stop_at = i;
        run(&m, 1, &c, &r, ACD_ERR_CANCELLED);
        assert_int_equal(c.n, i);
        assert_string_equal(c.stage[i - 1], within[s]);
        /* the same with 2 threads, stopped at the stage's first call */
        memset(&c, 0, sizeof c);
        c.stop_stage = within[s];
        run(&m, 2, &c, &r, ACD_ERR_CANCELLED);
    }
    /* the preparation and the hulls */
    const char *ends[] = {"segment: preparing", "corise: extracting", "segment: hulls"};
    for (size_t s = 0; s < 3; s++) {
        static rec c;
        memset(&c, 0, sizeof c);
        c.stop_stage = ends[s];
        run(&m, 1, &c, &r, ACD_ERR_CANCELLED);
    }
    /* polled or not, the same result */
    acd_segment_params p = acd_segment_default_params();
    acd_error err;
    assert_int_equal(acd_segment(&m, &p, &r, &err), ACD_OK);
    assert_int_equal(r.nparts, ref.nparts);
    assert_memory_equal(r.labels, ref.labels, m.ntriangles * sizeof *r.labels);
    for (size_t k = 0; k < r.nparts; k++) {
        assert_int_equal(r.parts[k].hull.nvertices, ref.parts[k].hull.nvertices);
        assert_memory_equal(r.parts[k].hull.vertices, ref.parts[k].hull.vertices,
                            3 * r.parts[k].hull.nvertices * sizeof(double));
        assert_true(r.parts[k].concavity == ref.parts[k].concavity);
    }
    acd_segment_result_free(&r);
    acd_segment_result_free(&ref);
    acd_mesh_free(&m);
}

/* The input's orientation repair (acd_mesh_repair in the preparation: 0.7-0.8 CPU-s without a call
 * at 832k facets before) polls the callback, its stage "repair: orienting", in its passes over the
 * faces; a stop at any of those calls returns ACD_ERR_CANCELLED at once, with 1 and 2 threads; after
 * the repair the stage is the preparation's again. On the two bulbs with a third of the faces
 * reversed (the repair flips them back): the same labels as the bulbs as made. */
static void test_cancel_in_repair(void **state) {
    (void)state;
    acd_mesh m;
    bulbs(&m);
    for (size_t t = 0; t < m.ntriangles; t += 3) {
        uint32_t *f = m.triangles + 3 * t, x = f[1];
        f[1] = f[2], f[2] = x;
    }
    static rec all;
    memset(&all, 0, sizeof all);
    acd_segment_result ref, r;
    run(&m, 1, &all, &ref, ACD_OK);
    const char *orienting = "repair: orienting";
    size_t n = count_stage(&all, orienting);
    print_message("%zu of %zu calls in the repair\n", n, all.n);
    assert_true(n >= 3); /* the step, its half-edges, its search */
    size_t last = 0;
    for (size_t i = 1; i <= all.n && i <= MAXCALLS; i++) {
        if (strcmp(all.stage[i - 1], orienting)) continue;
        last = i;
        static rec c;
        for (int threads = 1; threads <= 2; threads++) {
            memset(&c, 0, sizeof c);
            c.stop_at = i;
            run(&m, threads, &c, &r, ACD_ERR_CANCELLED);
            assert_int_equal(c.n, i);
            assert_string_equal(c.stage[i - 1], orienting);
        }
    }
    assert_true(last < all.n);
    assert_string_equal(all.stage[last], "segment: preparing");
    /* the same parts as the bulbs oriented as made */
    acd_mesh o;
    bulbs(&o);
    acd_segment_params p = acd_segment_default_params();
    acd_error err;
    assert_int_equal(acd_segment(&o, &p, &r, &err), ACD_OK);
    assert_int_equal(r.nparts, ref.nparts);
    assert_memory_equal(r.labels, ref.labels, m.ntriangles * sizeof *r.labels);
    acd_segment_result_free(&r);
    acd_segment_result_free(&ref);
    acd_mesh_free(&o);
    acd_mesh_free(&m);
}

/* A wave of several parts at 2 threads: once the calling thread has no part left to claim, it polls
 * ("corise: wave") until the other thread has finished its part. Whether it waits at all depends on
 * which thread finishes last (timing), so the test cannot force it; it runs the two bulbs (a wave of
 * two parts) several times and checks, whenever a "corise: wave" call came, that a stop at it returns
 * ACD_ERR_CANCELLED at once (no call after it, nothing leaks under ASan), and that a callback that
 * never stops leaves the result as with 1 thread. */
static void test_wave_wait(void **state) {
    (void)state;
    acd_mesh m;
    bulbs(&m);
    static rec all;
    acd_segment_result ref, r;
    memset(&all, 0, sizeof all);
    run(&m, 1, &all, &ref, ACD_OK);
    assert_int_equal(count_stage(&all, "corise: wave"), 0); /* 1 thread: never waits */
    size_t waits = 0, stops = 0;
    for (int k = 0; k < 6; k++) {
        static rec c;
        memset(&c, 0, sizeof c);
        run(&m, 2, &c, &r, ACD_OK);
        waits += count_stage(&c, "corise: wave");
        assert_int_equal(r.nparts, ref.nparts);
        assert_memory_equal(r.labels, ref.labels, m.ntriangles * sizeof *r.labels);
        acd_segment_result_free(&r);
        memset(&c, 0, sizeof c);
        c.stop_stage = "corise: wave";
        acd_segment_params p = acd_segment_default_params();
        p.threads = 2;
        p.progress = on_progress;
        p.progress_user = &c;
        acd_error err;
        acd_status st = acd_segment(&m, &p, &r, &err);
        if (c.stopped) {
            stops++;
            assert_int_equal(st, ACD_ERR_CANCELLED);
            assert_int_equal(c.after_stop, 0);
            assert_null(r.labels);
        } else {
            assert_int_equal(st, ACD_OK);
            acd_segment_result_free(&r);
        }
    }
    print_message("2 threads: %zu \"corise: wave\" calls in 6 runs, %zu of 6 runs stopped at one\n", waits, stops);
    acd_segment_result_free(&ref);
    acd_mesh_free(&m);
}

static void test_steps_cancel(void **state) {
    (void)state;
    acd_mesh m;
    bulbs(&m);
    acd_error err;
    acd_edge_graph g;
    assert_int_equal(acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &g, &err), ACD_OK);
    /* bridges: without a poll, with one that never stops (the same bits), with one that stops */
    acd_corise_bridges b0, b1;
    tu_counter c = {0, 0};
    acd3_poll poll = acd3_poll_make(tu_count_calls, &c, "test");
    assert_int_equal(acd_corise_bridges_compute_mt(&m, &g, 1, 1, NULL, &b0, &err), ACD_OK);
    assert_int_equal(acd_corise_bridges_compute_mt(&m, &g, 1, 1, &poll, &b1, &err), ACD_OK);
    int bridge_calls = c.calls;
    print_message("bridges: %zu, polled %d times\n", b0.nbridges, bridge_calls);
    assert_true(bridge_calls >= 2); /* after the hull, and within the valley searches */
    assert_int_equal(b1.nbridges, b0.nbridges);
    assert_int_equal(b1.npath, b0.npath);
    assert_memory_equal(b1.bridge, b0.bridge, b0.nbridges * sizeof *b0.bridge);
    assert_memory_equal(b1.path, b0.path, b0.npath * sizeof *b0.path);
    acd_corise_bridges_free(&b1);
    /* 2 threads: the calling thread polls within its own share of the bridges only (fewer calls) */
    for (int stop = 1; stop <= bridge_calls; stop++)
        for (int threads = 1; threads <= (stop <= 2 ? 2 : 1); threads++) {
            c = (tu_counter){0, stop};
            poll = acd3_poll_make(tu_count_calls, &c, "test");
            assert_int_equal(acd_corise_bridges_compute_mt(&m, &g, 1, threads, &poll, &b1, &err), ACD_ERR_CANCELLED);
            assert_int_equal(c.calls, stop);
            assert_null(b1.bridge);
            assert_null(b1.path);
        }
    /* regions */
    double tau = 0.1;
    acd_corise_ridges rg;
    assert_int_equal(acd_corise_ridges_compute(&b0, tau, &rg, &err), ACD_OK);
    assert_true(rg.nridges >= 2);
    uint32_t *ml0 = malloc(m.ntriangles * sizeof *ml0), *ml1 = malloc(m.ntriangles * sizeof *ml1);
    uint32_t *part0 = malloc(m.ntriangles * sizeof *part0), *part1 = malloc(m.ntriangles * sizeof *part1);
    assert_non_null(ml0);
    assert_non_null(ml1);
    assert_non_null(part0);
    assert_non_null(part1);
    assert_int_equal(acd_corise_regions_mt(&m, &g, &b0, &rg, tau, 1, NULL, ml0, NULL, &err), ACD_OK);
    c = (tu_counter){0, 0};
    poll = acd3_poll_make(tu_count_calls, &c, "test");
    assert_int_equal(acd_corise_regions_mt(&m, &g, &b0, &rg, tau, 1, &poll, ml1, NULL, &err), ACD_OK);
    assert_memory_equal(ml1, ml0, m.ntriangles * sizeof *ml0);
    int region_calls = c.calls;
    print_message("regions: polled %d times\n", region_calls);
    assert_true(region_calls >= 2);
    for (int stop = 1; stop <= region_calls; stop++) {
        c = (tu_counter){0, stop};
        poll = acd3_poll_make(tu_count_calls, &c, "test");
        assert_int_equal(acd_corise_regions_mt(&m, &g, &b0, &rg, tau, 1, &poll, ml1, NULL, &err), ACD_ERR_CANCELLED);
        assert_int_equal(c.calls, stop);
    }
    /* the cut */
    size_t np0, np1;
    assert_int_equal(acd_corise_cut_poll(&m, &b0, &rg, ml0, NULL, NULL, part0, &np0, &err), ACD_OK);
    c = (tu_counter){0, 0};
    poll = acd3_poll_make(tu_count_calls, &c, "test");
    assert_int_equal(acd_corise_cut_poll(&m, &b0, &rg, ml0, NULL, &poll, part1, &np1, &err), ACD_OK);
    assert_int_equal(np1, np0);
    assert_memory_equal(part1, part0, m.ntriangles * sizeof *part0);
    int cut_calls = c.calls;
    print_message("cut: %zu parts, polled %d times\n", np0, cut_calls);
    assert_true(cut_calls >= 2);
    for (int stop = 1; stop <= cut_calls; stop++) {
        c = (tu_counter){0, stop};
        poll = acd3_poll_make(tu_count_calls, &c, "test");
        assert_int_equal(acd_corise_cut_poll(&m, &b0, &rg, ml0, NULL, &poll, part1, &np1, &err), ACD_ERR_CANCELLED);
        assert_int_equal(c.calls, stop);
        assert_non_null(strstr(err.message, "cancelled"));
    }
    free(ml0);
    free(ml1);
    free(part0);
    free(part1);
    acd_corise_ridges_free(&rg);
    acd_corise_bridges_free(&b0);
    acd_edge_graph_free(&g);
    acd_mesh_free(&m);
}

/* The max-flow on a grid with a long path for the flow (many growth steps): the same flow and cut
 * with a poll that never stops, ACD_ERR_CANCELLED with one that stops, within the solve. */
static void test_maxflow_poll(void **state) {
    (void)state;
    const size_t W = 120, H = 120, n = W * H;
    acd_maxflow *g[2];
    acd_error err;
    for (int k = 0; k < 2; k++) {
        assert_int_equal(acd_maxflow_create(&g[k], n, 2 * n, &err), ACD_OK);
        assert_int_equal(acd_maxflow_add_nodes(g[k], n, NULL, &err), ACD_OK);
        for (size_t y = 0; y < H; y++) {
            assert_int_equal(acd_maxflow_add_tweights(g[k], y * W, 1e9, 0, &err), ACD_OK);
            assert_int_equal(acd_maxflow_add_tweights(g[k], y * W + W - 1, 0, 1e9, &err), ACD_OK);
            for (size_t x = 0; x < W; x++) {
                double cap = 1 + (double)((x * 7 + y * 13) % 5);
                if (x + 1 < W) assert_int_equal(acd_maxflow_add_edge(g[k], y * W + x, y * W + x + 1, cap, cap, &err), ACD_OK);
                if (y + 1 < H) assert_int_equal(acd_maxflow_add_edge(g[k], y * W + x, y * W + x + W, 1, 1, &err), ACD_OK);
            }
        }
    }
    double f0, f1;
    assert_int_equal(acd_maxflow_solve(g[0], &f0, &err), ACD_OK);
    tu_counter c = {0, 0};
    acd3_poll poll = acd3_poll_make(tu_count_calls, &c, "test");
    assert_int_equal(acd_maxflow_solve_poll(g[1], &f1, &poll, &err), ACD_OK);
    print_message("max-flow: polled %d times\n", c.calls);
    assert_true(c.calls >= 2);
    assert_true(f0 == f1);
    for (size_t i = 0; i < n; i++) assert_int_equal(acd_maxflow_is_source(g[1], i), acd_maxflow_is_source(g[0], i));
    /* again, stopped at its second poll */
    acd_maxflow_free(g[1]);
    assert_int_equal(acd_maxflow_create(&g[1], 0, 0, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_nodes(g[1], n, NULL, &err), ACD_OK);
    for (size_t y = 0; y < H; y++) {
        assert_int_equal(acd_maxflow_add_tweights(g[1], y * W, 1e9, 0, &err), ACD_OK);
        assert_int_equal(acd_maxflow_add_tweights(g[1], y * W + W - 1, 0, 1e9, &err), ACD_OK);
        for (size_t x = 0; x + 1 < W; x++)
            assert_int_equal(acd_maxflow_add_edge(g[1], y * W + x, y * W + x + 1, 1, 1, &err), ACD_OK);
    }
    c = (tu_counter){0, 2};
    poll = acd3_poll_make(tu_count_calls, &c, "test");
    assert_int_equal(acd_maxflow_solve_poll(g[1], &f1, &poll, &err), ACD_ERR_CANCELLED);
    assert_int_equal(c.calls, 2);
    acd_maxflow_free(g[0]);
    acd_maxflow_free(g[1]);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cancel_within_steps),
        cmocka_unit_test(test_cancel_in_repair),
        cmocka_unit_test(test_steps_cancel),
        cmocka_unit_test(test_wave_wait),
        cmocka_unit_test(test_maxflow_poll),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
