/* Tests of corise/ridge (greedy convex-ridge clustering, Eq. 2) and corise/separator (residual
 * concavity, V- and U-shaped valleys): hand-made bridge sets with known ridges, the Eq. 2
 * properties on random bridge sets, hand-worked valley splits, and the trench box end to end. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "corise/ridge.h"
#include "corise/separator.h"
#include "corise/valley.h"
#include "corise_meshes.h"

/* A bridge set over hull vertices 0..nh-1 (mesh ids = hull indices) with given lengths and
 * concavities; no valley paths (the clustering does not read them). */
static void fake_bridges(acd_corise_bridges *b, size_t nh, const uint32_t (*ab)[2], const double *len,
                         const double *conc, size_t nb) {
    memset(b, 0, sizeof *b);
    b->nhull = nh;
    b->hull_vertex = malloc(nh * sizeof *b->hull_vertex);
    for (size_t i = 0; i < nh; i++) b->hull_vertex[i] = (uint32_t)i;
    b->nbridges = nb;
    b->bridge = calloc(nb, sizeof *b->bridge);
    for (size_t i = 0; i < nb; i++) {
        b->bridge[i].a = ab[i][0];
        b->bridge[i].b = ab[i][1];
        b->bridge[i].length = len[i];
        b->bridge[i].concavity = conc[i];
    }
}

static void test_ridges_by_hand(void **state) {
    (void)state;
    /* two triangles {0,1,2}, {3,4,5} of low bridges, joined by a low bridge (2,3) but also by
     * high bridges (0,5) and (1,4): (2,3), collapsed after the triangles, is rejected -> two ridges */
    const uint32_t ab[][2] = {{0, 1}, {1, 2}, {0, 2}, {3, 4}, {4, 5}, {3, 5}, {2, 3}, {0, 5}, {1, 4}};
    double len[] = {1, 1, 1.5, 1, 1, 1.5, 2, 3, 3};
    double conc[] = {0, 0.05, 0.1, 0, 0.05, 0.1, 0.1, 0.9, 0.5};
    acd_corise_bridges b;
    fake_bridges(&b, 6, ab, len, conc, 9);
    acd_corise_ridges r;
    acd_error err;
    assert_int_equal(acd_corise_ridges_compute(&b, 0.2, &r, &err), ACD_OK);
    assert_int_equal(r.nridges, 2);
    uint32_t want[] = {0, 0, 0, 1, 1, 1};
    assert_memory_equal(r.ridge_of, want, sizeof want);
    acd_corise_ridges_free(&r);
    /* tau above every concavity: everything shallow, one ridge */
    assert_int_equal(acd_corise_ridges_compute(&b, 1.0, &r, &err), ACD_OK);
    assert_int_equal(r.nridges, 1);
    acd_corise_ridges_free(&r);
    /* tau = 0: only the zero-concavity bridges (0,1), (3,4) are low */
    assert_int_equal(acd_corise_ridges_compute(&b, 0.0, &r, &err), ACD_OK);
    assert_int_equal(r.nridges, 4);
    uint32_t want0[] = {0, 0, 1, 2, 2, 3};
    assert_memory_equal(r.ridge_of, want0, sizeof want0);
    acd_corise_ridges_free(&r);
    assert_int_equal(acd_corise_ridges_compute(&b, NAN, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    acd_corise_bridges_free(&b);

    /* order matters: path 0-1-2 with a high bridge 0-2; the shorter low bridge merges first */
    const uint32_t ab2[][2] = {{0, 1}, {1, 2}, {0, 2}};
    double len2[] = {1, 2, 2.5}, conc2[] = {0, 0, 1};
    fake_bridges(&b, 3, ab2, len2, conc2, 3);
    assert_int_equal(acd_corise_ridges_compute(&b, 0.5, &r, &err), ACD_OK);
    uint32_t w1[] = {0, 0, 1};
    assert_memory_equal(r.ridge_of, w1, sizeof w1);
    acd_corise_ridges_free(&r);
    b.bridge[0].length = 3; /* now 1-2 is shorter */
    assert_int_equal(acd_corise_ridges_compute(&b, 0.5, &r, &err), ACD_OK);
    uint32_t w2[] = {0, 1, 1};
    assert_memory_equal(r.ridge_of, w2, sizeof w2);
    acd_corise_ridges_free(&r);
    /* an unreachable bridge (no valley) is ignored */
    b.bridge[1].length = INFINITY;
    assert_int_equal(acd_corise_ridges_compute(&b, 0.5, &r, &err), ACD_OK);
    uint32_t w3[] = {0, 0, 1};
    assert_memory_equal(r.ridge_of, w3, sizeof w3);
    acd_corise_ridges_free(&r);
    acd_corise_bridges_free(&b);
}

/* Eq. 2 on random complete bridge sets: no high bridge inside a ridge; every low bridge between
 * two ridges is matched by a high bridge between the same two ridges (the greedy merge was
 * maximal). */
static void test_ridges_random_properties(void **state) {
    (void)state;
    acd_rng rng;
    acd_rng_seed(&rng, 2016);
    for (int t = 0; t < 200; t++) {
        size_t nh = 2 + (size_t)acd_rng_below(&rng, 12), nb = 0;
        uint32_t(*ab)[2] = malloc(nh * nh * sizeof *ab);
        double *len = malloc(nh * nh * sizeof *len), *conc = malloc(nh * nh * sizeof *conc);
        for (uint32_t i = 0; i < nh; i++)
            for (uint32_t j = i + 1; j < nh; j++)
                if (acd_rng_uniform(&rng) < 0.6) {
                    ab[nb][0] = i;
                    ab[nb][1] = j;
                    len[nb] = (double)(1 + acd_rng_below(&rng, 5)); /* ties on purpose */
                    conc[nb] = acd_rng_uniform(&rng);
                    nb++;
                }
        acd_corise_bridges b;
        fake_bridges(&b, nh, (const uint32_t(*)[2])ab, len, conc, nb);
        double tau = acd_rng_uniform(&rng);
        acd_corise_ridges r;
        acd_error err;
        assert_int_equal(acd_corise_ridges_compute(&b, tau, &r, &err), ACD_OK);
        assert_true(r.nridges >= 1 && r.nridges <= nh);
        for (size_t i = 0; i < nb; i++) {
            uint32_t ra = r.ridge_of[ab[i][0]], rb = r.ridge_of[ab[i][1]];
            if (conc[i] > tau) assert_true(ra != rb);
            if (conc[i] <= tau && ra != rb) {
                int matched = 0;
                for (size_t k = 0; k < nb; k++) {
                    uint32_t x = r.ridge_of[ab[k][0]], y = r.ridge_of[ab[k][1]];
                    if (conc[k] > tau && ((x == ra && y == rb) || (x == rb && y == ra))) matched = 1;
                }
                assert_true(matched);
            }
        }
        /* numbering by smallest member: ridge ids appear in increasing order of first occurrence */
        uint32_t next = 0;
        for (size_t v = 0; v < nh; v++) {
            assert_true(r.ridge_of[v] <= next);
            if (r.ridge_of[v] == next) next++;
        }
        assert_int_equal(next, r.nridges);
        acd_corise_ridges_free(&r);
        acd_corise_bridges_free(&b);
        free(ab);
        free(len);
        free(conc);
    }
}

/* V-shaped valley: straight arms (0,0)->(2,-2)->(4,0) sampled every unit in x, in the plane z = 0.
 * Splitting at the bottom (index 2) leaves two straight pieces: RC = 0. */
static void test_split_v(void **state) {
    (void)state;
    double v[] = {0, 0, 0, 1, -1, 0, 2, -2, 0, 3, -1, 0, 4, 0, 0};
    uint32_t chain[] = {0, 1, 2, 3, 4};
    acd_corise_split s;
    acd_error err;
    assert_int_equal(acd_corise_valley_split(v, chain, 5, 0.5, &s, &err), ACD_OK);
    assert_int_equal(s.ushaped, 0);
    assert_int_equal(s.first, 2);
    assert_int_equal(s.second, 2);
    assert_true(s.residual <= 1e-15);
    assert_int_equal(acd_corise_valley_split(v, chain, 2, 0.5, &s, &err), ACD_ERR_INVALID_ARGUMENT);
}

/* U-shaped valley: (0,0) (0,-1) (0,-2) (1,-2) (2,-2) (3,-2) (3,-1) (3,0), tau = 0.5. Every single
 * split leaves a piece with concavity >= 6/sqrt(13) = 1.66 (e.g. split at (0,-2): the corner (3,-2)
 * against the new bridge (0,-2)-(3,0)). Prefixes: P(1) = P(2) = 0, P(3) = 2/sqrt(5) > 0.5 -> i = 2;
 * by symmetry j = 5. The prefix V[0..2] is split best at k = 1 (the only choice), the suffix at
 * g = 6. The bottom V[1..6] is left fuzzy. */
static void test_split_u(void **state) {
    (void)state;
    double v[] = {0, 0, 0, 0, -1, 0, 0, -2, 0, 1, -2, 0, 2, -2, 0, 3, -2, 0, 3, -1, 0, 3, 0, 0};
    uint32_t chain[] = {0, 1, 2, 3, 4, 5, 6, 7};
    acd_corise_split s;
    acd_error err;
    assert_int_equal(acd_corise_valley_split(v, chain, 8, 0.5, &s, &err), ACD_OK);
    assert_int_equal(s.ushaped, 1);
    assert_int_equal(s.first, 1);
    assert_int_equal(s.second, 6);
    assert_true(s.residual <= 1e-15);
    /* with tau = 2 it is V-shaped: the deepest vertex against the original bridge is (0,-2) or
     * (3,-2) (both at 2; ties: smaller index) and RC there = 6/sqrt(13) <= 2 */
    assert_int_equal(acd_corise_valley_split(v, chain, 8, 2.0, &s, &err), ACD_OK);
    assert_int_equal(s.ushaped, 0);
    assert_int_equal(s.first, 2);
    assert_true(fabs(s.residual - 6 / sqrt(13.0)) < 1e-12);
}

/* The separator evaluated exhaustively, as specified (every RC(m), every candidate of the U
 * splits), with the same tie-breaks: the reference the pruned acd_corise_valley_split must match
 * bit for bit. */
static double ref_piece(const double *V, const uint32_t *chain, size_t s, size_t t) {
    double c;
    acd_error err;
    assert_int_equal(acd_corise_chain_concavity(V, chain + s, t - s + 1, NULL, &c, NULL, NULL, &err), ACD_OK);
    return c;
}

static int ref_better(double val, double corig, size_t m, double bval, double bcorig, size_t bm) {
    if (val != bval) return val < bval;
    if (corig != bcorig) return corig > bcorig;
    return m < bm;
}

static void ref_best(const double *V, const uint32_t *chain, size_t lo, size_t hi, const double *corig, size_t *arg) {
    size_t bm = SIZE_MAX;
    double bv = INFINITY;
    for (size_t m = lo + 1; m < hi; m++) {
        double p = ref_piece(V, chain, lo, m), q = ref_piece(V, chain, m, hi), v = p > q ? p : q;
        if (bm == SIZE_MAX || ref_better(v, corig[m], m, bv, corig[bm], bm)) bm = m, bv = v;
    }
    *arg = bm;
}

static acd_corise_split ref_split(const double *V, const uint32_t *chain, size_t n, double tau) {
    acd_corise_split out = {0, 0, 0, 0};
    double *corig = malloc(n * sizeof *corig), *P = malloc(n * sizeof *P), *S = malloc(n * sizeof *S);
    acd_error err;
    assert_int_equal(acd_corise_chain_concavity(V, chain, n, corig, NULL, NULL, NULL, &err), ACD_OK);
    size_t argrc = SIZE_MAX, argmax = SIZE_MAX;
    double minrc = INFINITY;
    for (size_t m = 1; m + 1 < n; m++) {
        P[m] = ref_piece(V, chain, 0, m);
        S[m] = ref_piece(V, chain, m, n - 1);
        double rc = P[m] > S[m] ? P[m] : S[m];
        if (argrc == SIZE_MAX || ref_better(rc, corig[m], m, minrc, corig[argrc], argrc)) argrc = m, minrc = rc;
        if (argmax == SIZE_MAX || corig[m] > corig[argmax]) argmax = m;
    }
    double rcmax = P[argmax] > S[argmax] ? P[argmax] : S[argmax];
    size_t i = 0, j = SIZE_MAX;
    for (size_t m = 1; m + 1 < n; m++) {
        if (P[m] <= tau) i = m;
        if (S[m] <= tau && j == SIZE_MAX) j = m;
    }
    if (rcmax <= tau) {
        out.first = out.second = argmax;
        out.residual = rcmax;
    } else if (minrc <= tau || i == 0 || j == SIZE_MAX || i >= j) {
        out.first = out.second = argrc;
        out.residual = minrc;
    } else {
        size_t k = i, g = j;
        if (i > 1) ref_best(V, chain, 0, i, corig, &k);
        if (j + 2 < n) ref_best(V, chain, j, n - 1, corig, &g);
        double pk = ref_piece(V, chain, 0, k), sg = ref_piece(V, chain, g, n - 1);
        out.ushaped = 1;
        out.first = k;
        out.second = g;
        out.residual = pk > sg ? pk : sg;
    }
    free(corig);
    free(P);
    free(S);
    return out;
}

/* Random valleys (a dip with noise, overhangs and zig-zags, so that pieces are monotone, simple
 * non-monotone (shortest paths) and self-intersecting): the split equals the exhaustive reference
 * for several tau (V, U and degenerate cases), and the cheap bound of every piece is certified:
 * exact when it says so, else at most the concavity (with its slack). */
static void test_split_matches_exhaustive(void **state) {
    (void)state;
    acd_rng rng;
    acd_rng_seed(&rng, 4242);
    size_t kinds[4] = {0, 0, 0, 0}, ushaped = 0, vshaped = 0;
    for (int trial = 0; trial < 300; trial++) {
        size_t n = 3 + (size_t)(acd_rng_uniform(&rng) * 40);
        double *V = malloc(3 * n * sizeof *V);
        uint32_t *chain = malloc(n * sizeof *chain);
        double depth = 0.2 + 2 * acd_rng_uniform(&rng), noise = 0.5 * acd_rng_uniform(&rng),
               back = acd_rng_uniform(&rng) < 0.5 ? 0.6 * acd_rng_uniform(&rng) : 0;
        for (size_t t = 0; t < n; t++) {
            double x = (double)t / (double)(n - 1);
            double flat = acd_rng_uniform(&rng) < 0.5 ? 0.3 : 0; /* U-like bottoms */
            double dip = depth * fmin(1.0, sin(3.14159265358979 * x) + flat);
            V[3 * t] = 4 * x + noise * (acd_rng_uniform(&rng) - 0.5) - back * sin(6.28318530717959 * x);
            V[3 * t + 1] = -dip + noise * (acd_rng_uniform(&rng) - 0.5);
            V[3 * t + 2] = 0.3 * noise * (acd_rng_uniform(&rng) - 0.5);
            chain[t] = (uint32_t)(n - 1 - t); /* not in vertex order */
        }
        /* chain[t] indexes V reversed: reverse the coordinates to keep the shape */
        for (size_t t = 0; t < n / 2; t++)
            for (int k = 0; k < 3; k++) {
                double tmp = V[3 * t + k];
                V[3 * t + k] = V[3 * (n - 1 - t) + k];
                V[3 * (n - 1 - t) + k] = tmp;
            }
        for (size_t s = 0; s + 2 < n; s += 3)
            for (size_t e = s + 2; e < n; e += 2) {
                double b, c;
                int exact;
                acd_corise_conc_kind kind;
                acd_error err;
                acd_corise_chain_bound(V, chain + s, e - s + 1, &b, &exact);
                assert_int_equal(acd_corise_chain_concavity(V, chain + s, e - s + 1, NULL, &c, NULL, &kind, &err), ACD_OK);
                kinds[kind]++;
                if (exact) {
                    assert_true(kind == ACD_CORISE_CONC_MONOTONE || kind == ACD_CORISE_CONC_TRIVIAL);
                    assert_true(c == b);
                } else {
                    assert_true(c >= b * (1 - ACD_CORISE_CHAIN_BOUND_REL));
                    if (kind == ACD_CORISE_CONC_FALLBACK) assert_true(c == b);
                }
            }
        double taus[4] = {0.05, 0.2 * depth, 0.5 * depth, 2 * depth};
        for (int k = 0; k < 4; k++) {
            acd_corise_split s, r = ref_split(V, chain, n, taus[k]);
            acd_error err;
            assert_int_equal(acd_corise_valley_split(V, chain, n, taus[k], &s, &err), ACD_OK);
            assert_int_equal(s.ushaped, r.ushaped);
            assert_int_equal(s.first, r.first);
            assert_int_equal(s.second, r.second);
            assert_true(s.residual == r.residual);
            if (s.ushaped) ushaped++;
            else vshaped++;
        }
        free(V);
        free(chain);
    }
    print_message("pieces: %zu trivial, %zu monotone, %zu shortest path, %zu fallback; splits: %zu V, %zu U\n", kinds[0],
                  kinds[1], kinds[2], kinds[3], vshaped, ushaped);
    assert_true(kinds[ACD_CORISE_CONC_SP] > 100 && kinds[ACD_CORISE_CONC_MONOTONE] > 100);
    assert_true(ushaped > 20 && vshaped > 20);
}

typedef struct trench {
    double h, depth, xc, halfwidth;
} trench;

static double trench_top(double x, double y, const void *u) {
    (void)y;
    const trench *t = u;
    double d = fabs(x - t->xc) / t->halfwidth;
    return t->h - (d < 1 ? t->depth * (1 - d) : 0);
}

/* The 2 x 1 x 1 box with a trench at x = 1: at tau = 0.3 the corners at x = 0 and at x = 2 form
 * two ridges (the top bridges over the trench are high); every deep valley splits with both ends'
 * pieces shallow. */
static void test_trench_box_ridges(void **state) {
    (void)state;
    trench tr = {1.0, 0.6, 1.0, 0.25};
    acd_mesh m;
    cm_heightfield_box(&m, 16, 8, 8, 2.0, 1.0, trench_top, &tr);
    acd_edge_graph g;
    acd_corise_bridges b;
    acd_corise_ridges r;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &g, &err), ACD_OK);
    assert_int_equal(acd_corise_bridges_compute(&m, &g, &b, &err), ACD_OK);
    assert_int_equal(acd_corise_ridges_compute(&b, 0.3, &r, &err), ACD_OK);
    assert_int_equal(r.nridges, 2);
    for (size_t i = 0; i < b.nhull; i++) {
        double x = m.vertices[3 * b.hull_vertex[i]];
        assert_int_equal(r.ridge_of[i], x < 1.0 ? 0 : 1);
    }
    size_t deep = 0;
    for (size_t i = 0; i < b.nbridges; i++) {
        const acd_corise_bridge *br = &b.bridge[i];
        if (br->concavity <= 0.3) continue;
        deep++;
        acd_corise_split s;
        assert_int_equal(acd_corise_valley_split(m.vertices, b.path + br->first, br->count, 0.3, &s, &err), ACD_OK);
        assert_true(s.first > 0 && s.second < br->count - 1 && s.first <= s.second);
        double c0, c1;
        assert_int_equal(acd_corise_chain_concavity(m.vertices, b.path + br->first, s.first + 1, NULL, &c0, NULL, NULL,
                                                    &err),
                         ACD_OK);
        assert_int_equal(acd_corise_chain_concavity(m.vertices, b.path + br->first + s.second, br->count - s.second, NULL,
                                                    &c1, NULL, NULL, &err),
                         ACD_OK);
        assert_true(c0 <= 0.3 && c1 <= 0.3);
        /* the deepest vertex is at the separator (V) or in the fuzzy bottom between them (U) */
        assert_true(s.first <= br->deepest && br->deepest <= s.second);
        /* the trench bottom line x = 1 lies between the separators */
        double x0 = m.vertices[3 * b.path[br->first + s.first]], x1 = m.vertices[3 * b.path[br->first + s.second]];
        assert_true((x0 - 1.0) * (x1 - 1.0) <= 1e-12);
    }
    assert_true(deep >= 3);
    acd_corise_ridges_free(&r);
    acd_corise_bridges_free(&b);
    acd_edge_graph_free(&g);
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ridges_by_hand), cmocka_unit_test(test_ridges_random_properties),
        cmocka_unit_test(test_split_v),        cmocka_unit_test(test_split_u),
        cmocka_unit_test(test_split_matches_exhaustive),
        cmocka_unit_test(test_trench_box_ridges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
