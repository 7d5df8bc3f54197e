/* Tests of geom3/bvh: every query against brute force over random triangle soups and a grid
 * mesh, determinism of the build, bad input rejected with a message. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "geom3/bvh.h"

typedef struct soup {
    double *v;
    uint32_t *t;
    size_t nv, nt;
} soup;

/* n random small triangles in the unit cube (plus a few long thin ones and degenerate ones). */
static soup make_soup(size_t n, uint64_t seed) {
    soup s;
    s.nv = 3 * n;
    s.nt = n;
    s.v = malloc(s.nv * 3 * sizeof(double));
    s.t = malloc(s.nt * 3 * sizeof(uint32_t));
    assert_non_null(s.v);
    assert_non_null(s.t);
    acd_rng r;
    acd_rng_seed(&r, seed);
    for (size_t i = 0; i < n; i++) {
        double c[3];
        for (int k = 0; k < 3; k++) c[k] = acd_rng_uniform(&r);
        double size = (i % 17 == 0) ? 0.5 : 0.05;
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) s.v[9 * i + 3 * j + k] = c[k] + size * (acd_rng_uniform(&r) - 0.5);
        if (i % 23 == 0) memcpy(&s.v[9 * i + 6], &s.v[9 * i + 3], 3 * sizeof(double)); /* degenerate */
        for (int j = 0; j < 3; j++) s.t[3 * i + j] = (uint32_t)(3 * i + j);
    }
    return s;
}

static void free_soup(soup *s) {
    free(s->v);
    free(s->t);
}

static void test_closest_matches_brute_force(void **state) {
    (void)state;
    soup s = make_soup(2000, 7);
    acd_bvh b;
    acd_error err;
    assert_int_equal(acd_bvh_build(&b, s.v, s.nv, s.t, s.nt, &err), ACD_OK);
    acd_rng r;
    acd_rng_seed(&r, 11);
    for (int q = 0; q < 300; q++) {
        double p[3];
        for (int k = 0; k < 3; k++) p[k] = 1.6 * acd_rng_uniform(&r) - 0.3;
        double best = INFINITY;
        for (size_t t = 0; t < s.nt; t++) {
            double c[3];
            double d = acd_closest_point_triangle(p, &s.v[9 * t], &s.v[9 * t + 3], &s.v[9 * t + 6], c);
            if (d < best) best = d;
        }
        acd_bvh_closest_result res;
        assert_int_equal(acd_bvh_closest(&b, p, INFINITY, &res), 1);
        assert_true(res.dist2 == best);
        /* the reported point is on the reported triangle at that distance */
        double c[3];
        uint32_t t = res.triangle;
        double d = acd_closest_point_triangle(p, &s.v[9 * t], &s.v[9 * t + 3], &s.v[9 * t + 6], c);
        assert_true(d == res.dist2);
        /* a limit below the distance finds nothing */
        if (best > 0) assert_int_equal(acd_bvh_closest(&b, p, best * 0.5, &res), 0);
    }
    acd_bvh_free(&b);
    free_soup(&s);
}

static void test_closest_point_triangle_regions(void **state) {
    (void)state;
    double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0}, q[3];
    double p1[3] = {0.2, 0.2, 3};
    assert_true(fabs(acd_closest_point_triangle(p1, a, b, c, q) - 9.0) < 1e-14);
    assert_true(fabs(q[0] - 0.2) < 1e-15 && fabs(q[1] - 0.2) < 1e-15 && q[2] == 0);
    double p2[3] = {-1, -1, 0};
    assert_true(acd_closest_point_triangle(p2, a, b, c, q) == 2.0);
    double p3[3] = {1, 1, 0}; /* beyond edge bc: closest (0.5, 0.5, 0) */
    assert_true(fabs(acd_closest_point_triangle(p3, a, b, c, q) - 0.5) < 1e-15);
    assert_true(fabs(q[0] - 0.5) < 1e-15 && fabs(q[1] - 0.5) < 1e-15);
    /* degenerate triangle: a segment */
    double d2[3] = {2, 0, 0}, p4[3] = {1, 1, 0};
    assert_true(fabs(acd_closest_point_triangle(p4, a, b, d2, q) - 1.0) < 1e-15);
    /* all three the same point */
    assert_true(acd_closest_point_triangle(p4, a, a, a, q) == 2.0);
}

static void test_raycast_matches_brute_force(void **state) {
    (void)state;
    soup s = make_soup(1500, 3);
    acd_bvh b;
    assert_int_equal(acd_bvh_build(&b, s.v, s.nv, s.t, s.nt, NULL), ACD_OK);
    /* brute force through a one-triangle tree per triangle */
    acd_rng r;
    acd_rng_seed(&r, 5);
    int hits = 0;
    for (int q = 0; q < 200; q++) {
        double o[3], d[3];
        for (int k = 0; k < 3; k++) {
            o[k] = acd_rng_uniform(&r);
            d[k] = acd_rng_uniform(&r) - 0.5;
        }
        if (q % 10 == 0) d[0] = d[1] = 0; /* axis-parallel ray */
        double tbest = INFINITY;
        for (size_t t = 0; t < s.nt; t++) {
            acd_bvh one;
            assert_int_equal(acd_bvh_build(&one, s.v, s.nv, s.t + 3 * t, 1, NULL), ACD_OK);
            double tt;
            uint32_t tri;
            if (acd_bvh_raycast(&one, o, d, INFINITY, &tt, &tri) && tt < tbest) tbest = tt;
            acd_bvh_free(&one);
        }
        double tt = INFINITY;
        uint32_t tri;
        int hit = acd_bvh_raycast(&b, o, d, INFINITY, &tt, &tri);
        assert_int_equal(hit, tbest < INFINITY);
        if (hit) {
            hits++;
            assert_true(tt == tbest);
        }
    }
    assert_true(hits > 50);
    acd_bvh_free(&b);
    free_soup(&s);
}

typedef struct count_ctx {
    unsigned char *seen;
    size_t n;
} count_ctx;

static int mark_tri(void *user, uint32_t t) {
    count_ctx *c = user;
    c->seen[t]++;
    c->n++;
    return 0;
}

static void tri_bounds(const soup *s, size_t t, double lo[3], double hi[3]) {
    for (int k = 0; k < 3; k++) {
        lo[k] = hi[k] = s->v[9 * t + k];
        for (int j = 1; j < 3; j++) {
            lo[k] = fmin(lo[k], s->v[9 * t + 3 * j + k]);
            hi[k] = fmax(hi[k], s->v[9 * t + 3 * j + k]);
        }
    }
}

static void test_box_and_line_queries(void **state) {
    (void)state;
    soup s = make_soup(1000, 9);
    acd_bvh b;
    assert_int_equal(acd_bvh_build(&b, s.v, s.nv, s.t, s.nt, NULL), ACD_OK);
    count_ctx c = {calloc(s.nt, 1), 0};
    assert_non_null(c.seen);
    acd_rng r;
    acd_rng_seed(&r, 13);
    for (int q = 0; q < 50; q++) {
        double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++) {
            lo[k] = acd_rng_uniform(&r);
            hi[k] = lo[k] + 0.2 * acd_rng_uniform(&r);
        }
        memset(c.seen, 0, s.nt);
        c.n = 0;
        acd_bvh_query_box(&b, lo, hi, mark_tri, &c);
        for (size_t t = 0; t < s.nt; t++) {
            double tl[3], th[3];
            tri_bounds(&s, t, tl, th);
            int meets = 1;
            for (int k = 0; k < 3; k++)
                if (tl[k] > hi[k] || lo[k] > th[k]) meets = 0;
            assert_int_equal(c.seen[t], meets);
        }
        /* the line through lo parallel to axis q % 3, forward */
        int axis = q % 3;
        memset(c.seen, 0, s.nt);
        acd_bvh_query_axis_line(&b, lo, axis, 1, mark_tri, &c);
        for (size_t t = 0; t < s.nt; t++) {
            double tl[3], th[3];
            tri_bounds(&s, t, tl, th);
            int meets = th[axis] >= lo[axis];
            for (int k = 0; k < 3; k++)
                if (k != axis && (lo[k] < tl[k] || lo[k] > th[k])) meets = 0;
            assert_int_equal(c.seen[t], meets);
        }
        /* the halfspace n.x > off: exactly the triangles whose box reaches beyond, among them every
         * triangle with a vertex beyond */
        double n[3], off = 0.5 * acd_rng_uniform(&r);
        for (int k = 0; k < 3; k++) n[k] = 2 * acd_rng_uniform(&r) - 1;
        memset(c.seen, 0, s.nt);
        acd_bvh_query_halfspace(&b, n, off, mark_tri, &c);
        for (size_t t = 0; t < s.nt; t++) {
            double tl[3], th[3], top = 0, vmax = -INFINITY;
            tri_bounds(&s, t, tl, th);
            for (int k = 0; k < 3; k++) top += n[k] * (n[k] >= 0 ? th[k] : tl[k]);
            for (int j = 0; j < 3; j++)
                vmax = fmax(vmax, n[0] * s.v[9 * t + 3 * j] + n[1] * s.v[9 * t + 3 * j + 1] + n[2] * s.v[9 * t + 3 * j + 2]);
            assert_int_equal(c.seen[t], top > off);
            if (vmax > off) assert_int_equal(c.seen[t], 1);
        }
    }
    free(c.seen);
    acd_bvh_free(&b);
    free_soup(&s);
}

static void test_overlap_pairs_match_brute_force(void **state) {
    (void)state;
    soup s = make_soup(800, 21);
    acd_bvh b;
    assert_int_equal(acd_bvh_build(&b, s.v, s.nv, s.t, s.nt, NULL), ACD_OK);
    for (int m = 0; m < 2; m++) {
        double margin = m ? 0.01 : 0.0;
        uint32_t *pairs;
        size_t np;
        assert_int_equal(acd_bvh_collect_pairs(&b, margin, &pairs, &np, NULL), ACD_OK);
        size_t expect = 0, k = 0;
        for (size_t i = 0; i < s.nt; i++) {
            double l1[3], h1[3];
            tri_bounds(&s, i, l1, h1);
            for (size_t j = i + 1; j < s.nt; j++) {
                double l2[3], h2[3];
                tri_bounds(&s, j, l2, h2);
                int meets = 1;
                for (int a = 0; a < 3; a++)
                    if (l1[a] - margin > h2[a] + margin || l2[a] - margin > h1[a] + margin) meets = 0;
                if (!meets) continue;
                expect++;
                /* the sorted list holds exactly these pairs, in order, each once */
                assert_true(k < np);
                assert_int_equal(pairs[2 * k], i);
                assert_int_equal(pairs[2 * k + 1], j);
                k++;
            }
        }
        assert_int_equal(np, expect);
        assert_true(expect > 100);
        free(pairs);
    }
    acd_bvh_free(&b);
    free_soup(&s);
}

static void test_build_deterministic_and_valid(void **state) {
    (void)state;
    soup s = make_soup(3000, 1);
    acd_bvh a, b;
    assert_int_equal(acd_bvh_build(&a, s.v, s.nv, s.t, s.nt, NULL), ACD_OK);
    assert_int_equal(acd_bvh_build(&b, s.v, s.nv, s.t, s.nt, NULL), ACD_OK);
    assert_int_equal(a.nnodes, b.nnodes);
    assert_memory_equal(a.nodes, b.nodes, a.nnodes * sizeof *a.nodes);
    assert_memory_equal(a.order, b.order, s.nt * sizeof *a.order);
    /* every triangle in exactly one leaf; children after parents; boxes nest */
    unsigned char *seen = calloc(s.nt, 1);
    assert_non_null(seen);
    for (size_t i = 0; i < a.nnodes; i++) {
        const acd_bvh_node *n = &a.nodes[i];
        if (n->count) {
            assert_true(n->count <= ACD_BVH_LEAF_MAX);
            for (uint32_t j = 0; j < n->count; j++) seen[a.order[n->first + j]]++;
        } else {
            assert_true(n->first > i && n->first + 1 < a.nnodes);
            for (int c = 0; c < 2; c++)
                for (int k = 0; k < 3; k++) {
                    assert_true(a.nodes[n->first + c].lo[k] >= n->lo[k]);
                    assert_true(a.nodes[n->first + c].hi[k] <= n->hi[k]);
                }
        }
    }
    for (size_t t = 0; t < s.nt; t++) assert_int_equal(seen[t], 1);
    free(seen);
    /* every box is tight: a leaf's the bounds of its triangles' vertices, an inner node's the union of
     * its children's (bit for bit: the boxes gathered while partitioning are range_bounds') */
    for (size_t i = a.nnodes; i-- > 0;) {
        const acd_bvh_node *n = &a.nodes[i];
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        if (n->count) {
            for (uint32_t j = 0; j < n->count; j++)
                for (int c = 0; c < 3; c++)
                    for (int k = 0; k < 3; k++) {
                        double x = s.v[3 * s.t[3 * a.order[n->first + j] + c] + k];
                        lo[k] = fmin(lo[k], x);
                        hi[k] = fmax(hi[k], x);
                    }
        } else {
            for (int c = 0; c < 2; c++)
                for (int k = 0; k < 3; k++) {
                    lo[k] = fmin(lo[k], a.nodes[n->first + c].lo[k]);
                    hi[k] = fmax(hi[k], a.nodes[n->first + c].hi[k]);
                }
        }
        assert_memory_equal(lo, n->lo, sizeof lo);
        assert_memory_equal(hi, n->hi, sizeof hi);
    }
    acd_bvh_free(&a);
    acd_bvh_free(&b);
    free_soup(&s);
}

/* acd_bvh_build_threads gives acd_bvh_build's tree bit for bit (its subtrees built by parallel tasks,
 * numbered as the sequential build numbers them), at any thread count, also when called inside a
 * parallel region: random soups (one subtree level of tasks; several), and a soup with thousands of
 * coincident triangles and exponentially spaced ones (the median and the index-order splits). */
static void assert_same_tree(const acd_bvh *a, const acd_bvh *b) {
    assert_int_equal(a->nnodes, b->nnodes);
    assert_memory_equal(a->nodes, b->nodes, a->nnodes * sizeof *a->nodes);
    assert_memory_equal(a->order, b->order, a->ntriangles * sizeof *a->order);
    assert_memory_equal(a->boxes, b->boxes, a->ntriangles * 6 * sizeof *a->boxes);
}

static void test_build_threads_same_tree(void **state) {
    (void)state;
    soup s[3] = {make_soup(6000, 7), make_soup(60000, 8), {0}};
    size_t n = 12000;
    s[2].nv = 3 * n, s[2].nt = n;
    s[2].v = malloc(3 * n * 3 * sizeof(double));
    s[2].t = malloc(3 * n * sizeof(uint32_t));
    assert_non_null(s[2].v);
    assert_non_null(s[2].t);
    for (size_t i = 0; i < n; i++) {
        double x = i < n / 2 ? 0.0 : ldexp(1.0, -(int)(i - n / 2) / 4);
        double tri[9] = {x, 0, 0, x + 1e-3, 0, 0, x, 1e-3, 0};
        memcpy(s[2].v + 9 * i, tri, sizeof tri);
        for (int k = 0; k < 3; k++) s[2].t[3 * i + k] = (uint32_t)(3 * i + k);
    }
    for (int m = 0; m < 3; m++) {
        acd_bvh a;
        assert_int_equal(acd_bvh_build(&a, s[m].v, s[m].nv, s[m].t, s[m].nt, NULL), ACD_OK);
        for (int threads = 1; threads <= 4; threads++) {
            acd_bvh b;
            assert_int_equal(acd_bvh_build_threads(&b, s[m].v, s[m].nv, s[m].t, s[m].nt, threads, NULL), ACD_OK);
            assert_same_tree(&a, &b);
            acd_bvh_free(&b);
        }
        acd_bvh c[2];
        acd_status st[2];
#ifdef _OPENMP
#pragma omp parallel for num_threads(2)
#endif
        for (int k = 0; k < 2; k++) st[k] = acd_bvh_build_threads(&c[k], s[m].v, s[m].nv, s[m].t, s[m].nt, 2, NULL);
        for (int k = 0; k < 2; k++) {
            assert_int_equal(st[k], ACD_OK);
            assert_same_tree(&a, &c[k]);
            acd_bvh_free(&c[k]);
        }
        acd_bvh_free(&a);
        free_soup(&s[m]);
    }
}

static void test_coincident_and_skewed_input(void **state) {
    (void)state;
    /* 500 copies of one triangle, then triangles at exponentially spaced positions */
    size_t n = 1000;
    double *v = malloc(3 * n * 3 * sizeof(double));
    uint32_t *t = malloc(3 * n * sizeof(uint32_t));
    assert_non_null(v);
    assert_non_null(t);
    for (size_t i = 0; i < n; i++) {
        double x = i < 500 ? 0.0 : ldexp(1.0, -(int)(i - 500) / 2);
        double tri[9] = {x, 0, 0, x + 1e-3, 0, 0, x, 1e-3, 0};
        memcpy(v + 9 * i, tri, sizeof tri);
        for (int k = 0; k < 3; k++) t[3 * i + k] = (uint32_t)(3 * i + k);
    }
    acd_bvh b;
    assert_int_equal(acd_bvh_build(&b, v, 3 * n, t, n, NULL), ACD_OK);
    double p[3] = {0.3, 0.3, 0.3};
    acd_bvh_closest_result res;
    assert_int_equal(acd_bvh_closest(&b, p, INFINITY, &res), 1);
    double best = INFINITY;
    for (size_t i = 0; i < n; i++) {
        double q[3];
        double d = acd_closest_point_triangle(p, v + 9 * i, v + 9 * i + 3, v + 9 * i + 6, q);
        if (d < best) best = d;
    }
    assert_true(res.dist2 == best);
    acd_bvh_free(&b);
    free(v);
    free(t);
}

static void test_bad_input(void **state) {
    (void)state;
    double v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t t[3] = {0, 1, 3};
    acd_bvh b;
    acd_error err;
    assert_int_equal(acd_bvh_build(&b, v, 3, t, 1, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "triangle 0"));
    assert_null(b.nodes);
    v[4] = NAN;
    t[2] = 2;
    assert_int_equal(acd_bvh_build(&b, v, 3, t, 1, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "non-finite"));
    /* empty mesh: an empty tree that finds nothing */
    assert_int_equal(acd_bvh_build(&b, v, 3, t, 0, &err), ACD_OK);
    double p[3] = {0, 0, 0};
    acd_bvh_closest_result res;
    assert_int_equal(acd_bvh_closest(&b, p, INFINITY, &res), 0);
    acd_bvh_free(&b);
}

/* Subnormal extents (found by fuzzing): a flat grid whose z coordinates differ by subnormal
 * amounts gives node boxes with a subnormal z extent; building must not convert NaN/inf to int
 * (UBSan) and queries must still work. */
static void test_subnormal_extent(void **state) {
    (void)state;
    enum { N = 9 };
    double v[3 * N * N];
    uint32_t t[6 * (N - 1) * (N - 1)];
    for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++) {
            double *p = v + 3 * (y * N + x);
            p[0] = x, p[1] = y, p[2] = ((x + y) % 3) * 1e-320;
        }
    size_t nt = 0;
    for (int y = 0; y + 1 < N; y++)
        for (int x = 0; x + 1 < N; x++) {
            uint32_t a = (uint32_t)(y * N + x), b = a + 1, c = a + N + 1, d = a + N;
            t[3 * nt] = a, t[3 * nt + 1] = b, t[3 * nt + 2] = c, nt++;
            t[3 * nt] = a, t[3 * nt + 1] = c, t[3 * nt + 2] = d, nt++;
        }
    acd_bvh bvh;
    acd_error err;
    assert_int_equal(acd_bvh_build(&bvh, v, N * N, t, nt, &err), ACD_OK);
    acd_bvh_closest_result r;
    double p[3] = {3.25, 4.5, 2};
    assert_true(acd_bvh_closest(&bvh, p, INFINITY, &r));
    assert_true(fabs(r.dist2 - 4.0) < 1e-12);
    acd_bvh_free(&bvh);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_subnormal_extent),
        cmocka_unit_test(test_closest_point_triangle_regions),
        cmocka_unit_test(test_closest_matches_brute_force),
        cmocka_unit_test(test_raycast_matches_brute_force),
        cmocka_unit_test(test_box_and_line_queries),
        cmocka_unit_test(test_overlap_pairs_match_brute_force),
        cmocka_unit_test(test_build_deterministic_and_valid),
        cmocka_unit_test(test_build_threads_same_tree),
        cmocka_unit_test(test_coincident_and_skewed_input),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
