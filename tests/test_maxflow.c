/* Tests of corise/maxflow (Boykov-Kolmogorov): against a reference Dinic max-flow on hundreds of
 * random graphs and image-like grid graphs (equal flow, identical minimal source set, cut
 * capacity = flow), plus edge cases, determinism, reuse and argument errors. */
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/rng.h"
#include "corise/maxflow.h"
#include "maxflow_ref.h"

/* Builds the BK graph from a reference graph (same call order every time). Edges are added
 * in list order; t-links are added once per node, split in two calls for odd nodes to exercise
 * accumulation. */
static acd_maxflow *build_bk(const ref_graph *r) {
    acd_maxflow *g = NULL;
    acd_error err;
    assert_int_equal(acd_maxflow_create(&g, r->n, r->ne, &err), ACD_OK);
    size_t first = 99;
    assert_int_equal(acd_maxflow_add_nodes(g, r->n, &first, &err), ACD_OK);
    assert_int_equal(first, 0);
    for (size_t i = 0; i < r->n; i++) {
        if (i % 2) {
            assert_int_equal(acd_maxflow_add_tweights(g, i, r->cs[i] / 2, 0, &err), ACD_OK);
            assert_int_equal(acd_maxflow_add_tweights(g, i, r->cs[i] - r->cs[i] / 2, r->ct[i], &err), ACD_OK);
        } else {
            assert_int_equal(acd_maxflow_add_tweights(g, i, r->cs[i], r->ct[i], &err), ACD_OK);
        }
    }
    for (size_t k = 0; k < r->ne; k++)
        assert_int_equal(acd_maxflow_add_edge(g, r->e[k].i, r->e[k].j, r->e[k].cap, r->e[k].rev, &err), ACD_OK);
    return g;
}

/* Solves r with both solvers and checks the properties. exact: integer capacities, so flows and
 * source sets must agree exactly. */
static void check_graph(const ref_graph *r, int exact, const char *what, int id) {
    unsigned char *ref_side = malloc(r->n + 1), *bk_side = malloc(r->n + 1);
    assert_non_null(ref_side);
    assert_non_null(bk_side);
    double ref_flow = ref_maxflow(r, ref_side);
    acd_maxflow *g = build_bk(r);
    double flow = -1;
    acd_error err;
    assert_int_equal(acd_maxflow_solve(g, &flow, &err), ACD_OK);
    for (size_t i = 0; i < r->n; i++) bk_side[i] = (unsigned char)acd_maxflow_is_source(g, i);
    double cut = ref_cut_capacity(r, bk_side);
    double scale = 1.0 + fabs(ref_flow);
    if (exact) {
        if (flow != ref_flow || cut != flow) {
            print_message("%s %d: BK flow %.17g, reference %.17g, cut %.17g\n", what, id, flow, ref_flow, cut);
            fail();
        }
        for (size_t i = 0; i < r->n; i++)
            if (bk_side[i] != ref_side[i]) {
                print_message("%s %d: node %zu on side %d (BK) vs %d (reference)\n", what, id, i, bk_side[i],
                              ref_side[i]);
                fail();
            }
    } else {
        if (fabs(flow - ref_flow) > 1e-9 * scale || fabs(cut - flow) > 1e-9 * scale) {
            print_message("%s %d: BK flow %.17g, reference %.17g, cut %.17g\n", what, id, flow, ref_flow, cut);
            fail();
        }
    }
    acd_maxflow_free(g);
    free(ref_side);
    free(bk_side);
}

static double rand_cap(acd_rng *rng, int integer, double zero_prob, double max) {
    if (acd_rng_uniform(rng) < zero_prob) return 0.0;
    if (integer) return (double)(1 + acd_rng_below(rng, (uint64_t)max));
    return acd_rng_uniform(rng) * max;
}

static void random_graph(ref_graph *r, acd_rng *rng, int integer) {
    size_t n = 1 + (size_t)acd_rng_below(rng, 60);
    ref_init(r, n);
    double p = acd_rng_uniform(rng) * 0.3 + 2.0 / (double)(n + 1);
    double tprob = acd_rng_uniform(rng);
    for (size_t i = 0; i < n; i++) {
        if (acd_rng_uniform(rng) < tprob) r->cs[i] = rand_cap(rng, integer, 0.3, 20);
        if (acd_rng_uniform(rng) < tprob) r->ct[i] = rand_cap(rng, integer, 0.3, 20);
    }
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++)
            if (acd_rng_uniform(rng) < p) {
                double c = rand_cap(rng, integer, 0.2, 10), rc = rand_cap(rng, integer, 0.5, 10);
                if (acd_rng_below(rng, 2))
                    ref_add_edge(r, i, j, c, rc);
                else
                    ref_add_edge(r, j, i, c, rc);
                if (acd_rng_uniform(rng) < 0.05) ref_add_edge(r, i, j, rand_cap(rng, integer, 0.2, 10), 0); /* parallel */
            }
}

static void test_random_integer(void **state) {
    (void)state;
    acd_rng rng;
    acd_rng_seed(&rng, 20260101);
    for (int t = 0; t < 400; t++) {
        ref_graph r;
        random_graph(&r, &rng, 1);
        check_graph(&r, 1, "random integer graph", t);
        ref_free(&r);
    }
}

static void test_random_fractional(void **state) {
    (void)state;
    acd_rng rng;
    acd_rng_seed(&rng, 777);
    for (int t = 0; t < 200; t++) {
        ref_graph r;
        random_graph(&r, &rng, 0);
        check_graph(&r, 0, "random fractional graph", t);
        ref_free(&r);
    }
}

/* Image-segmentation-like grid: data terms on every pixel from a noisy two-region "image",
 * Potts-like n-links to the 4 (or 8) neighbours, and a few hard (large) seeds. */
static void grid_graph(ref_graph *r, acd_rng *rng, size_t w, size_t h, int eight, int integer) {
    ref_init(r, w * h);
    double cx = (double)w * (0.3 + 0.4 * acd_rng_uniform(rng)), cy = (double)h * (0.3 + 0.4 * acd_rng_uniform(rng));
    double rad = (double)(w < h ? w : h) * (0.2 + 0.2 * acd_rng_uniform(rng));
    double lambda = integer ? (double)(1 + acd_rng_below(rng, 6)) : 0.5 + 3.0 * acd_rng_uniform(rng);
    for (size_t y = 0; y < h; y++)
        for (size_t x = 0; x < w; x++) {
            size_t i = y * w + x;
            double dx = (double)x - cx, dy = (double)y - cy;
            int inside = dx * dx + dy * dy < rad * rad;
            double noise = acd_rng_uniform(rng);
            double fg = inside ? 0.7 + 0.3 * noise : 0.6 * noise;
            if (integer) {
                r->cs[i] = floor(10 * fg);
                r->ct[i] = floor(10 * (1 - fg));
            } else {
                r->cs[i] = fg;
                r->ct[i] = 1 - fg;
            }
            if (acd_rng_uniform(rng) < 0.01) r->cs[i] += 1000; /* seeds */
            if (acd_rng_uniform(rng) < 0.01) r->ct[i] += 1000;
            if (x + 1 < w) ref_add_edge(r, i, i + 1, lambda, lambda);
            if (y + 1 < h) ref_add_edge(r, i, i + w, lambda, lambda);
            if (eight && x + 1 < w && y + 1 < h) ref_add_edge(r, i, i + w + 1, lambda / 2, lambda / 2);
            if (eight && x > 0 && y + 1 < h) ref_add_edge(r, i, i + w - 1, lambda / 2, lambda / 2);
        }
}

static void test_grids(void **state) {
    (void)state;
    acd_rng rng;
    acd_rng_seed(&rng, 4242);
    for (int t = 0; t < 120; t++) {
        size_t w = 2 + (size_t)acd_rng_below(&rng, 40), h = 2 + (size_t)acd_rng_below(&rng, 40);
        int integer = t % 2 == 0;
        ref_graph r;
        grid_graph(&r, &rng, w, h, t % 3 == 0, integer);
        check_graph(&r, integer, "grid graph", t);
        ref_free(&r);
    }
}

static void test_known_values(void **state) {
    (void)state;
    acd_error err;
    acd_maxflow *g = NULL;
    double flow = -1;
    /* empty graph */
    assert_int_equal(acd_maxflow_create(&g, 0, 0, &err), ACD_OK);
    assert_int_equal(acd_maxflow_solve(g, &flow, &err), ACD_OK);
    assert_true(flow == 0.0);
    /* classic 4-node example: s->0 (3), s->1 (2), 0->1 (1), 0->2... as nodes 0..3 */
    acd_maxflow_reset(g);
    assert_int_equal(acd_maxflow_add_nodes(g, 4, NULL, &err), ACD_OK);
    assert_int_equal(acd_maxflow_node_count(g), 4);
    assert_int_equal(acd_maxflow_add_tweights(g, 0, 3, 0, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_tweights(g, 1, 2, 0, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_tweights(g, 2, 0, 2, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_tweights(g, 3, 0, 3, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_edge(g, 0, 1, 1, 0, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_edge(g, 0, 2, 3, 0, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_edge(g, 1, 3, 2, 0, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_edge(g, 2, 3, 1, 0, &err), ACD_OK);
    assert_int_equal(acd_maxflow_solve(g, &flow, &err), ACD_OK);
    /* s->0->2->t (2), s->0->2->3->t (1), s->1->3->t (2): 5 = all source capacity */
    assert_true(flow == 5.0);
    /* every source arc saturated: the minimal source set is empty */
    for (size_t i = 0; i < 4; i++) assert_int_equal(acd_maxflow_is_source(g, i), 0);
    /* solving twice is refused */
    assert_int_equal(acd_maxflow_solve(g, &flow, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_int_equal(acd_maxflow_add_nodes(g, 1, NULL, &err), ACD_ERR_INVALID_ARGUMENT);

    /* a node tied to both terminals: min(cs, ct) flows directly */
    acd_maxflow_reset(g);
    assert_int_equal(acd_maxflow_add_nodes(g, 2, NULL, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_tweights(g, 0, 5, 3, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_tweights(g, 0, 1, 4, &err), ACD_OK); /* totals 6 and 7 */
    assert_int_equal(acd_maxflow_add_edge(g, 0, 1, 0, 0, &err), ACD_OK); /* zero-capacity edge */
    assert_int_equal(acd_maxflow_solve(g, &flow, &err), ACD_OK);
    assert_true(flow == 6.0);
    assert_int_equal(acd_maxflow_is_source(g, 0), 0);
    assert_int_equal(acd_maxflow_is_source(g, 1), 0);

    /* chain s -> 0 -> 1 -> 2 -> t with bottleneck in the middle: cut right after node 1 */
    acd_maxflow_reset(g);
    assert_int_equal(acd_maxflow_add_nodes(g, 3, NULL, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_tweights(g, 0, 10, 0, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_tweights(g, 2, 0, 10, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_edge(g, 0, 1, 7, 100, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_edge(g, 1, 2, 2.5, 100, &err), ACD_OK);
    assert_int_equal(acd_maxflow_solve(g, &flow, &err), ACD_OK);
    assert_true(flow == 2.5);
    assert_int_equal(acd_maxflow_is_source(g, 0), 1);
    assert_int_equal(acd_maxflow_is_source(g, 1), 1);
    assert_int_equal(acd_maxflow_is_source(g, 2), 0);
    assert_int_equal(acd_maxflow_is_source(g, 3), 0); /* out of range */
    acd_maxflow_free(g);
}

/* All capacities zero, or no t-links at all: flow 0, empty source set. */
static void test_zero_capacity(void **state) {
    (void)state;
    acd_error err;
    acd_maxflow *g = NULL;
    double flow = -1;
    assert_int_equal(acd_maxflow_create(&g, 0, 0, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_nodes(g, 1000, NULL, &err), ACD_OK);
    for (size_t i = 0; i + 1 < 1000; i++) assert_int_equal(acd_maxflow_add_edge(g, i, i + 1, 0, 0, &err), ACD_OK);
    for (size_t i = 0; i < 1000; i += 7) assert_int_equal(acd_maxflow_add_tweights(g, i, 0, 0, &err), ACD_OK);
    assert_int_equal(acd_maxflow_solve(g, &flow, &err), ACD_OK);
    assert_true(flow == 0.0);
    for (size_t i = 0; i < 1000; i++) assert_int_equal(acd_maxflow_is_source(g, i), 0);
    /* source links with no way to the sink: all flow 0, linked nodes and their reach on S */
    acd_maxflow_reset(g);
    assert_int_equal(acd_maxflow_add_nodes(g, 10, NULL, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_tweights(g, 3, 1, 0, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_edge(g, 3, 4, 1, 0, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_edge(g, 5, 3, 1, 0, &err), ACD_OK); /* 3 cannot reach 5 */
    assert_int_equal(acd_maxflow_solve(g, &flow, &err), ACD_OK);
    assert_true(flow == 0.0);
    for (size_t i = 0; i < 10; i++) assert_int_equal(acd_maxflow_is_source(g, i), i == 3 || i == 4);
    acd_maxflow_free(g);
}

/* The same construction twice gives bitwise-identical flow and cut; reuse after reset works. */
static void test_determinism_and_reuse(void **state) {
    (void)state;
    acd_rng rng;
    acd_rng_seed(&rng, 99);
    ref_graph r;
    grid_graph(&r, &rng, 60, 50, 1, 0);
    acd_maxflow *g1 = build_bk(&r), *g2 = build_bk(&r);
    double f1, f2;
    acd_error err;
    assert_int_equal(acd_maxflow_solve(g1, &f1, &err), ACD_OK);
    assert_int_equal(acd_maxflow_solve(g2, &f2, &err), ACD_OK);
    assert_memory_equal(&f1, &f2, sizeof f1);
    size_t nsrc = 0;
    for (size_t i = 0; i < r.n; i++) {
        assert_int_equal(acd_maxflow_is_source(g1, i), acd_maxflow_is_source(g2, i));
        nsrc += (size_t)acd_maxflow_is_source(g1, i);
    }
    assert_true(nsrc > 0 && nsrc < r.n); /* a real cut */
    /* reuse g1 for a different graph, then the first one again */
    acd_maxflow_reset(g1);
    assert_int_equal(acd_maxflow_add_nodes(g1, 2, NULL, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_tweights(g1, 0, 4, 0, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_tweights(g1, 1, 0, 4, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_edge(g1, 0, 1, 1.5, 0, &err), ACD_OK);
    double f3;
    assert_int_equal(acd_maxflow_solve(g1, &f3, &err), ACD_OK);
    assert_true(f3 == 1.5);
    acd_maxflow_free(g1);
    acd_maxflow_free(g2);
    ref_free(&r);
}

static void test_argument_errors(void **state) {
    (void)state;
    acd_error err;
    acd_maxflow *g = NULL;
    assert_int_equal(acd_maxflow_create(NULL, 0, 0, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_int_equal(acd_maxflow_create(&g, 2, 1, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_nodes(g, 2, NULL, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_tweights(g, 2, 1, 1, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err.message, "node 2"));
    assert_int_equal(acd_maxflow_add_tweights(g, 0, -1, 1, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_int_equal(acd_maxflow_add_tweights(g, 0, NAN, 1, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_int_equal(acd_maxflow_add_tweights(g, 0, 1, INFINITY, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_int_equal(acd_maxflow_add_tweights(g, 0, 1e308, 0, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_tweights(g, 0, 1e308, 0, &err), ACD_ERR_INVALID_ARGUMENT); /* overflow */
    assert_non_null(strstr(err.message, "overflows"));
    assert_int_equal(acd_maxflow_add_edge(g, 0, 0, 1, 1, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err.message, "itself"));
    assert_int_equal(acd_maxflow_add_edge(g, 0, 5, 1, 1, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_int_equal(acd_maxflow_add_edge(g, 0, 1, -0.5, 1, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_int_equal(acd_maxflow_add_edge(g, 0, 1, 1, NAN, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_int_equal(acd_maxflow_add_nodes(NULL, 1, NULL, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_int_equal(acd_maxflow_add_nodes(g, ACD_MAXFLOW_MAX_NODES, NULL, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_int_equal(acd_maxflow_is_source(g, 0), 0); /* not solved */
    acd_maxflow_free(g);
    acd_maxflow_free(NULL);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_known_values),          cmocka_unit_test(test_zero_capacity),
        cmocka_unit_test(test_random_integer),        cmocka_unit_test(test_random_fractional),
        cmocka_unit_test(test_grids),                 cmocka_unit_test(test_determinism_and_reuse),
        cmocka_unit_test(test_argument_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
