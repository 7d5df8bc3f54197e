/* Tests of geom2/validate: acd_polygon_validate finds every kind of invalid polygon with a
 * message naming chain and vertex; the fast intersection test agrees with brute force on
 * random (often degenerate) inputs and is fast on large polygons; normalization. */
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "acd/polygon.h"
#include "core/rng.h"
#include "geom2/validate.h"

#define TV_PI 3.14159265358979323846

/* Builds a polygon from a flat list: rings separated by counts. */
static void make(acd_polygon *p, const double *xy, const size_t *sizes, size_t nrings) {
    const acd_vec2 *rings[16];
    acd_vec2 buf[256];
    size_t k = 0;
    for (size_t r = 0; r < nrings; r++) {
        rings[r] = buf + k;
        for (size_t i = 0; i < sizes[r]; i++, k++) {
            buf[k].x = xy[2 * k];
            buf[k].y = xy[2 * k + 1];
        }
    }
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(p, rings, sizes, nrings, &err), ACD_OK);
}

static void expect_invalid(const double *xy, const size_t *sizes, size_t nrings, int normalize, acd_status want,
                           const char *n1, const char *n2) {
    acd_polygon p;
    acd_error err;
    make(&p, xy, sizes, nrings);
    if (normalize) assert_int_equal(acd_polygon_normalize(&p, NULL, &err), ACD_OK);
    acd_status st = acd_polygon_validate(&p, 7, &err);
    acd_status sb = acd_polygon_validate_with(&p, 7, ACD_VALIDATE_BRUTE, NULL);
    acd_status sd = acd_polygon_validate_with(&p, 7, ACD_VALIDATE_SUBDIV, NULL);
    if (st != want) fail_msg("status %d, wanted %d: %s", (int)st, (int)want, err.message);
    assert_int_equal(sb, want);
    assert_int_equal(sd, want);
    if (!strstr(err.message, "polygon 7") || !strstr(err.message, n1) || !strstr(err.message, n2))
        fail_msg("message '%s' lacks '%s' / '%s'", err.message, n1, n2);
    acd_polygon_free(&p);
}

static void test_valid_square_with_hole(void **state) {
    (void)state;
    const double xy[] = {0, 0, 10, 0, 10, 10, 0, 10, 2, 2, 2, 4, 4, 4, 4, 2, 6, 6, 6, 8, 8, 6};
    const size_t sizes[] = {4, 4, 3};
    acd_polygon p;
    acd_error err;
    make(&p, xy, sizes, 3);
    assert_int_equal(acd_polygon_validate(&p, 0, &err), ACD_OK);
    assert_int_equal(acd_polygon_validate_with(&p, 0, ACD_VALIDATE_BRUTE, &err), ACD_OK);
    acd_polygon_free(&p);
}

static void test_invalid_cases(void **state) {
    (void)state;
    { /* bow tie */
        const double xy[] = {0, 0, 2, 2, 2, 0, 0, 2};
        const size_t sz[] = {4};
        expect_invalid(xy, sz, 1, 0, ACD_ERR_INVALID_INPUT, "self-intersects", "crosses chain 0 edge");
    }
    { /* a vertex touching a non-adjacent edge */
        const double xy[] = {0, 0, 4, 0, 4, 4, 2, 4, 2, 0.0, 1, 3};
        const size_t sz[] = {6};
        expect_invalid(xy, sz, 1, 0, ACD_ERR_INVALID_INPUT, "chain 0 vertex 4 (2, 0) touches chain 0 edge 0-1", "");
    }
    { /* collinear overlap of non-adjacent edges (plus touches) */
        const double xy[] = {0, 0, 10, 0, 10, 5, 7, 5, 7, 0, 3, 0, 3, 5, 0, 5};
        const size_t sz[] = {8};
        expect_invalid(xy, sz, 1, 0, ACD_ERR_INVALID_INPUT, "self-intersects", "chain 0");
    }
    { /* folding back (spike): adjacent edges overlap */
        const double xy[] = {0, 0, 4, 0, 4, 4, 4, 6, 4, 5, 0, 4};
        const size_t sz[] = {6};
        expect_invalid(xy, sz, 1, 0, ACD_ERR_INVALID_INPUT, "self-intersects", "chain 0");
        /* the pair test itself names the fold */
        acd_polygon p;
        acd_error err;
        make(&p, xy, sz, 1);
        assert_int_equal(acd_polygon_validate_with(&p, 7, ACD_VALIDATE_BRUTE, &err), ACD_ERR_INVALID_INPUT);
        assert_non_null(strstr(err.message, "folds back on itself at vertex 3 (4, 6)"));
        acd_polygon_free(&p);
    }
    { /* the same vertex twice (figure eight touching at a point) */
        const double xy[] = {0, 0, 2, 1, 4, 0, 4, 2, 2, 1, 0, 2};
        const size_t sz[] = {6};
        expect_invalid(xy, sz, 1, 0, ACD_ERR_INVALID_INPUT, "self-intersects", "(2, 1)");
    }
    { /* hole outside */
        const double xy[] = {0, 0, 10, 0, 10, 10, 0, 10, 12, 2, 12, 4, 14, 4, 14, 2};
        const size_t sz[] = {4, 4};
        expect_invalid(xy, sz, 2, 0, ACD_ERR_INVALID_INPUT, "hole chain 1 lies outside", "(12, 2)");
    }
    { /* a "hole" enclosing the outer boundary */
        const double xy[] = {0, 0, 10, 0, 10, 10, 0, 10, -5, -5, -5, 20, 20, 20, 20, -5};
        const size_t sz[] = {4, 4};
        expect_invalid(xy, sz, 2, 0, ACD_ERR_INVALID_INPUT, "hole chain 1 lies outside the outer boundary", "");
    }
    { /* hole touching the outer boundary at a vertex */
        const double xy[] = {0, 0, 10, 0, 10, 10, 0, 10, 0, 5, 2, 6, 2, 4};
        const size_t sz[] = {4, 3};
        expect_invalid(xy, sz, 2, 0, ACD_ERR_INVALID_INPUT, "rings meet", "chain 1 vertex 0 (0, 5) touches chain 0 edge 3-0");
    }
    { /* two holes crossing */
        const double xy[] = {0, 0, 10, 0, 10, 10, 0, 10, 2, 2, 2, 4, 4, 4, 4, 2, 3, 3, 3, 5, 5, 5, 5, 3};
        const size_t sz[] = {4, 4, 4};
        expect_invalid(xy, sz, 3, 0, ACD_ERR_INVALID_INPUT, "rings meet", "crosses chain");
    }
    { /* hole inside a hole */
        const double xy[] = {0, 0, 10, 0, 10, 10, 0, 10, 1, 1, 1, 9, 9, 9, 9, 1, 3, 3, 3, 5, 5, 5, 5, 3};
        const size_t sz[] = {4, 4, 4};
        expect_invalid(xy, sz, 3, 0, ACD_ERR_INVALID_INPUT, "hole chain 2 lies inside hole chain 1", "(3, 3)");
    }
    { /* non-finite */
        const double xy[] = {0, 0, 1, 0, NAN, 1};
        const size_t sz[] = {3};
        expect_invalid(xy, sz, 1, 0, ACD_ERR_INVALID_INPUT, "chain 0 vertex 2", "non-finite");
    }
    { /* a coordinate beyond ACD_COORD_MAX: the exact predicates would overflow (a fuzz find) */
        const double xy[] = {0, 0, 1e180, 0, 6, 99};
        const size_t sz[] = {3};
        expect_invalid(xy, sz, 1, 0, ACD_ERR_INVALID_INPUT, "chain 0 vertex 1", "beyond the supported coordinate magnitude");
    }
    { /* too few vertices after normalization */
        const double xy[] = {0, 0, 1, 0, 1, 0, 0, 0};
        const size_t sz[] = {4};
        expect_invalid(xy, sz, 1, 1, ACD_ERR_DEGENERATE, "chain 0 has 2 distinct vertices", "");
    }
    { /* zero area */
        const double xy[] = {0, 0, 1, 0, 3, 0};
        const size_t sz[] = {3};
        expect_invalid(xy, sz, 1, 0, ACD_ERR_DEGENERATE, "chain 0 has zero area", "");
    }
    { /* zero-area hole */
        const double xy[] = {0, 0, 10, 0, 10, 10, 0, 10, 2, 2, 3, 3, 4, 4};
        const size_t sz[] = {4, 3};
        expect_invalid(xy, sz, 2, 0, ACD_ERR_DEGENERATE, "chain 1 has zero area", "");
    }
    { /* clockwise outer (not normalized) */
        const double xy[] = {0, 0, 0, 1, 1, 1, 1, 0};
        const size_t sz[] = {4};
        expect_invalid(xy, sz, 1, 0, ACD_ERR_INVALID_INPUT, "chain 0 (outer boundary) is clockwise", "");
    }
    { /* repeated vertex (not normalized) */
        const double xy[] = {0, 0, 1, 0, 1, 0, 1, 1};
        const size_t sz[] = {4};
        expect_invalid(xy, sz, 1, 0, ACD_ERR_INVALID_INPUT, "chain 0 vertex 2 (1, 0) repeats vertex 1", "");
    }
}

/* Random polygons on a coarse integer grid (so touches and collinear overlaps are common):
 * a star-shaped ring around the centre, perturbed, with optional holes. The fast test must
 * agree with brute force on every one. */
static void random_polygon(acd_rng *rng, acd_polygon *p, int grid) {
    size_t n = 3 + (size_t)acd_rng_below(rng, 40);
    size_t nh = (size_t)acd_rng_below(rng, 4);
    acd_vec2 pts[256];
    const acd_vec2 *rings[8];
    size_t sizes[8];
    size_t k = 0;
    for (size_t r = 0; r <= nh; r++) {
        size_t m = r == 0 ? n : 3 + (size_t)acd_rng_below(rng, 6);
        double cx = r == 0 ? 0 : (acd_rng_uniform(rng) - 0.5) * 40;
        double cy = r == 0 ? 0 : (acd_rng_uniform(rng) - 0.5) * 40;
        double rad = r == 0 ? 50 : 2 + acd_rng_uniform(rng) * 8;
        rings[r] = pts + k;
        sizes[r] = m;
        for (size_t i = 0; i < m; i++, k++) {
            double a = 2 * TV_PI * ((double)i + 0.8 * acd_rng_uniform(rng)) / (double)m;
            double rr = rad * (0.3 + 0.7 * acd_rng_uniform(rng));
            if (r) a = -a;
            double x = cx + rr * cos(a), y = cy + rr * sin(a);
            if (acd_rng_below(rng, 12) == 0 && i > 0) { /* a wild vertex */
                x = (acd_rng_uniform(rng) - 0.5) * 100;
                y = (acd_rng_uniform(rng) - 0.5) * 100;
            }
            if (grid) {
                x = floor(x / 5) * 5;
                y = floor(y / 5) * 5;
            }
            pts[k].x = x;
            pts[k].y = y;
        }
    }
    /* exact degeneracies: a vertex moved onto another vertex or onto the midpoint of an edge
     * (midpoints of grid points are exact) */
    if (k > 3 && acd_rng_below(rng, 3) == 0) {
        size_t a = (size_t)acd_rng_below(rng, k), b = (size_t)acd_rng_below(rng, k - 1);
        if (acd_rng_below(rng, 2)) pts[a] = pts[b];
        else {
            pts[a].x = 0.5 * (pts[b].x + pts[b + 1].x);
            pts[a].y = 0.5 * (pts[b].y + pts[b + 1].y);
        }
    }
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(p, rings, sizes, nh + 1, &err), ACD_OK);
    assert_int_equal(acd_polygon_normalize(p, NULL, &err), ACD_OK);
    /* straight vertices: split every edge of some rings at its (exact) midpoint */
    if (grid && acd_rng_below(rng, 2) == 0) {
        acd_polygon q;
        const acd_vec2 *r2[8];
        size_t s2[8];
        acd_vec2 *buf = malloc(2 * acd_polygon_num_points(p) * sizeof *buf);
        assert_non_null(buf);
        size_t m = 0;
        for (size_t r = 0; r < p->nrings; r++) {
            const acd_vec2 *v = acd_polygon_ring(p, r);
            size_t n = acd_polygon_ring_size(p, r);
            r2[r] = buf + m;
            for (size_t i = 0; i < n; i++) {
                buf[m++] = v[i];
                buf[m].x = 0.5 * (v[i].x + v[(i + 1) % n].x);
                buf[m].y = 0.5 * (v[i].y + v[(i + 1) % n].y);
                m++;
            }
            s2[r] = 2 * n;
        }
        assert_int_equal(acd_polygon_from_rings(&q, r2, s2, p->nrings, &err), ACD_OK);
        free(buf);
        acd_polygon_free(p);
        *p = q;
    }
}

static void test_fast_matches_brute(void **state) {
    (void)state;
    acd_rng rng;
    acd_rng_seed(&rng, 12345);
    size_t nvalid = 0, ninvalid = 0, nnested = 0, noutside = 0;
#ifdef NDEBUG
    const int iterations = 20000;
#else
    const int iterations = 5000; /* sanitizer builds are slower */
#endif
    for (int it = 0; it < iterations; it++) {
        acd_polygon p;
        random_polygon(&rng, &p, it % 2);
        acd_error e1, e2, e3;
        acd_status a = acd_polygon_validate_with(&p, 0, ACD_VALIDATE_FAST, &e1);
        acd_status b = acd_polygon_validate_with(&p, 0, ACD_VALIDATE_BRUTE, &e2);
        acd_status d = acd_polygon_validate_with(&p, 0, ACD_VALIDATE_SUBDIV, &e3);
        if (a != b) fail_msg("iteration %d: sweep %d (%s) vs brute %d (%s)", it, (int)a, e1.message, (int)b, e2.message);
        if (d != b) fail_msg("iteration %d: subdiv %d (%s) vs brute %d (%s)", it, (int)d, e3.message, (int)b, e2.message);
        if (a == ACD_OK) nvalid++;
        else ninvalid++;
        if (a != ACD_OK && strstr(e1.message, "inside hole")) nnested++;
        if (a != ACD_OK && strstr(e1.message, "outside the outer")) noutside++;
        acd_polygon_free(&p);
    }
    print_message("[  INFO    ] %zu valid, %zu invalid random polygons (%zu nested holes, %zu holes outside)\n",
                  nvalid, ninvalid, nnested, noutside);
    assert_true(nvalid > 200 && ninvalid > 200 && noutside > 5);
}

/* Nesting: regular-polygon holes of random sizes and centres, often inside each other or
 * outside the outer ring without touching; the sweep's nesting must agree with the
 * point-in-ring tests of the other methods. */
static void test_random_nesting(void **state) {
    (void)state;
    acd_rng rng;
    acd_rng_seed(&rng, 99);
    size_t nvalid = 0, nnested = 0, noutside = 0;
    for (int it = 0; it < 4000; it++) {
        acd_vec2 pts[256];
        const acd_vec2 *rings[12];
        size_t sizes[12], k = 0;
        size_t nh = 1 + (size_t)acd_rng_below(&rng, 5);
        double prev_c[2] = {0, 0}, prev_r = 0;
        for (size_t r = 0; r <= nh; r++) {
            size_t m = r == 0 ? 24 : 3 + (size_t)acd_rng_below(&rng, 6);
            double cx = r ? (acd_rng_uniform(&rng) - 0.5) * 240 : 0, cy = r ? (acd_rng_uniform(&rng) - 0.5) * 240 : 0;
            double rad = r ? 1 + 40 * acd_rng_uniform(&rng) : 100, a0 = acd_rng_uniform(&rng);
            if (r >= 2 && acd_rng_below(&rng, 2) == 0) { /* inside the previous hole */
                cx = prev_c[0] + 0.05 * prev_r * (acd_rng_uniform(&rng) - 0.5);
                cy = prev_c[1] + 0.05 * prev_r * (acd_rng_uniform(&rng) - 0.5);
                rad = prev_r * (0.1 + 0.3 * acd_rng_uniform(&rng));
            }
            prev_c[0] = cx;
            prev_c[1] = cy;
            prev_r = rad;
            rings[r] = pts + k;
            sizes[r] = m;
            for (size_t i = 0; i < m; i++, k++) {
                double a = 2 * TV_PI * ((double)i + a0) / (double)m * (r ? -1 : 1);
                pts[k].x = cx + rad * cos(a);
                pts[k].y = cy + rad * sin(a);
            }
        }
        acd_polygon p;
        acd_error e1, e2, e3;
        assert_int_equal(acd_polygon_from_rings(&p, rings, sizes, nh + 1, &e1), ACD_OK);
        acd_status a = acd_polygon_validate_with(&p, 0, ACD_VALIDATE_FAST, &e1);
        acd_status b = acd_polygon_validate_with(&p, 0, ACD_VALIDATE_BRUTE, &e2);
        acd_status d = acd_polygon_validate_with(&p, 0, ACD_VALIDATE_SUBDIV, &e3);
        if (a != b || d != b)
            fail_msg("iteration %d: sweep %d (%s), brute %d (%s), subdiv %d", it, (int)a, e1.message, (int)b,
                     e2.message, (int)d);
        /* (with several problems the methods may name different ones first) */
        if (a != ACD_OK) {
            nnested += strstr(e1.message, "inside hole") != NULL;
            noutside += strstr(e1.message, "outside the outer") != NULL;
        } else {
            nvalid++;
        }
        acd_polygon_free(&p);
    }
    print_message("[  INFO    ] nesting: %zu valid, %zu nested holes, %zu holes outside\n", nvalid, nnested, noutside);
    assert_true(nvalid > 50 && nnested > 50 && noutside > 50);
}

/* A 100k-vertex star-shaped polygon with a few thousand holes validates quickly; one moved
 * vertex makes it invalid and is found. */
static void test_large_polygon_fast(void **state) {
    (void)state;
    const size_t n = 100000, nh = 2000, hm = 8;
    acd_vec2 *pts = malloc((n + nh * hm) * sizeof *pts);
    const acd_vec2 **rings = malloc((nh + 1) * sizeof *rings);
    size_t *sizes = malloc((nh + 1) * sizeof *sizes);
    assert_non_null(pts);
    acd_rng rng;
    acd_rng_seed(&rng, 7);
    for (size_t i = 0; i < n; i++) {
        double a = 2 * TV_PI * (double)i / (double)n;
        double r = 1000 + 0.05 * acd_rng_uniform(&rng); /* noise about the vertex spacing */
        pts[i].x = r * cos(a);
        pts[i].y = r * sin(a);
    }
    rings[0] = pts;
    sizes[0] = n;
    for (size_t h = 0; h < nh; h++) { /* small octagons on a 45 x 45 grid inside radius 800 */
        size_t gx = h % 45, gy = h / 45;
        double cx = -550 + 25.0 * (double)gx, cy = -550 + 25.0 * (double)gy;
        rings[h + 1] = pts + n + h * hm;
        sizes[h + 1] = hm;
        for (size_t i = 0; i < hm; i++) {
            double a = -2 * TV_PI * (double)i / (double)hm;
            pts[n + h * hm + i].x = cx + 5 * cos(a);
            pts[n + h * hm + i].y = cy + 5 * sin(a);
        }
    }
    acd_polygon p;
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(&p, rings, sizes, nh + 1, &err), ACD_OK);
    clock_t t0 = clock();
    acd_status st = acd_polygon_validate(&p, 0, &err);
    double secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
    if (st != ACD_OK) fail_msg("%s", err.message);
    print_message("[  INFO    ] %zu vertices, %zu holes validated in %.1f ms\n", acd_polygon_num_points(&p), nh,
                  secs * 1000);
#ifdef NDEBUG
    assert_true(secs < 1.0); /* optimized builds only; sanitizers are much slower */
#endif
    /* move one outer vertex across the ring: now it self-intersects */
    p.points[n / 2].x = 0;
    p.points[n / 2].y = 995;
    assert_int_equal(acd_polygon_validate(&p, 0, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "chain 0"));
    acd_polygon_free(&p);
    free(pts);
    free((void *)rings);
    free(sizes);
}

static void test_normalize(void **state) {
    (void)state;
    /* closing repeat, a repeated vertex, clockwise outer, counterclockwise hole */
    const double xy[] = {0, 0, 0, 10, 0, 10, 10, 10, 10, 0, 0, 0, 2, 2, 4, 2, 4, 4, 2, 4, 2, 2};
    const size_t sz[] = {6, 5};
    acd_polygon p;
    acd_error err;
    make(&p, xy, sz, 2);
    acd_polygon_fixes fx = {0};
    assert_int_equal(acd_polygon_normalize(&p, &fx, &err), ACD_OK);
    assert_int_equal(fx.repeated_dropped, 3);
    assert_int_equal(fx.rings_reversed, 2);
    assert_int_equal(acd_polygon_ring_size(&p, 0), 4);
    assert_int_equal(acd_polygon_ring_size(&p, 1), 4);
    assert_true(acd_polygon_ring(&p, 0)[0].x == 0 && acd_polygon_ring(&p, 0)[1].x == 10);
    assert_true(acd_polygon_area(&p) == 96.0);
    assert_int_equal(acd_polygon_ring_orientation(&p, 0), 1);
    assert_int_equal(acd_polygon_ring_orientation(&p, 1), -1);
    assert_int_equal(acd_polygon_validate(&p, 0, &err), ACD_OK);
    /* idempotent */
    acd_polygon_fixes fx2 = {0};
    assert_int_equal(acd_polygon_normalize(&p, &fx2, &err), ACD_OK);
    assert_int_equal(fx2.repeated_dropped + fx2.rings_reversed, 0);
    acd_polygon_free(&p);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_valid_square_with_hole), cmocka_unit_test(test_invalid_cases),
        cmocka_unit_test(test_fast_matches_brute),     cmocka_unit_test(test_random_nesting),     cmocka_unit_test(test_large_polygon_fast),
        cmocka_unit_test(test_normalize),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
