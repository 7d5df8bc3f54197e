/* Large-graph test of corise/maxflow: a 1000 x 1000 image-segmentation grid (1M nodes, 2M
 * n-links) solved by Boykov-Kolmogorov and by the reference Dinic: equal flow, identical minimal
 * source set, and a time bound that catches accidental quadratic behaviour. */
// ctest: LABELS slow TIMEOUT 600
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "core/rng.h"
#include "corise/maxflow.h"
#include "maxflow_ref.h"

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Integer data terms from a smooth two-region "image" plus noise; Potts n-links of weight 3. */
static void big_grid(ref_graph *r, size_t w, size_t h) {
    acd_rng rng;
    acd_rng_seed(&rng, 1000000);
    ref_init(r, w * h);
    for (size_t y = 0; y < h; y++)
        for (size_t x = 0; x < w; x++) {
            size_t i = y * w + x;
            double u = (double)x / (double)w - 0.5, v = (double)y / (double)h - 0.5;
            double base = 0.5 + 0.4 * sin(12.0 * u) * cos(9.0 * v);
            double fg = base + 0.3 * (acd_rng_uniform(&rng) - 0.5);
            r->cs[i] = floor(20 * fg > 0 ? 20 * fg : 0);
            r->ct[i] = floor(20 * (1 - fg) > 0 ? 20 * (1 - fg) : 0);
            if (x + 1 < w) ref_add_edge(r, i, i + 1, 3, 3);
            if (y + 1 < h) ref_add_edge(r, i, i + w, 3, 3);
        }
}

static void test_million_nodes(void **state) {
    (void)state;
    ref_graph r;
    big_grid(&r, 1000, 1000);
    acd_error err;
    acd_maxflow *g = NULL;
    assert_int_equal(acd_maxflow_create(&g, r.n, r.ne, &err), ACD_OK);
    assert_int_equal(acd_maxflow_add_nodes(g, r.n, NULL, &err), ACD_OK);
    for (size_t i = 0; i < r.n; i++) assert_int_equal(acd_maxflow_add_tweights(g, i, r.cs[i], r.ct[i], &err), ACD_OK);
    for (size_t k = 0; k < r.ne; k++)
        assert_int_equal(acd_maxflow_add_edge(g, r.e[k].i, r.e[k].j, r.e[k].cap, r.e[k].rev, &err), ACD_OK);
    double t0 = now(), flow = -1;
    assert_int_equal(acd_maxflow_solve(g, &flow, &err), ACD_OK);
    double t_bk = now() - t0;

    unsigned char *side = malloc(r.n), *ref_side = malloc(r.n);
    assert_non_null(side);
    assert_non_null(ref_side);
    size_t nsrc = 0;
    for (size_t i = 0; i < r.n; i++) {
        side[i] = (unsigned char)acd_maxflow_is_source(g, i);
        nsrc += side[i];
    }
    t0 = now();
    double ref = ref_maxflow(&r, ref_side);
    double t_ref = now() - t0;
    print_message("1M-node grid: BK %.3f s, Dinic %.3f s, flow %.17g, %zu nodes on the source side\n", t_bk, t_ref,
                  flow, nsrc);
    assert_true(flow == ref);
    assert_true(ref_cut_capacity(&r, side) == flow);
    assert_memory_equal(side, ref_side, r.n);
    assert_true(nsrc > r.n / 10 && nsrc < r.n - r.n / 10);
    /* generous bound (2 shared cores, sanitizers off in this test): BK is near-linear here */
    assert_true(t_bk < 30.0);
    free(side);
    free(ref_side);
    acd_maxflow_free(g);
    ref_free(&r);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_million_nodes)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
