/* Tests of corise/segeval (Chen et al. 2009 metrics): values worked out by hand on small
 * labellings and meshes, identical and refined segmentations, and brute-force checks of every
 * metric straight from its definition (pairs of faces for RI, region sets for Hamming and the
 * consistency errors, Floyd-Warshall for the cut discrepancy) on random labellings. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/segment.h"
#include "core/rng.h"
#include "corise/segeval.h"

#define CLOSE(x, y) assert_true(fabs((x) - (y)) <= 1e-12 * (1.0 + fabs(y)))

/* Strip of nx unit squares (y in [0,1]), two triangles per square:
 * (x,0) (x+1,0) (x+1,1) and (x,0) (x+1,1) (x,1). Vertex (x, y) has id y*(nx+1) + x. */
static void strip(acd_mesh *m, size_t nx, size_t ny) {
    size_t w = nx + 1;
    m->nvertices = w * (ny + 1);
    m->vertices = malloc(3 * m->nvertices * sizeof(double));
    for (size_t y = 0; y <= ny; y++)
        for (size_t x = 0; x <= nx; x++) {
            double *p = m->vertices + 3 * (y * w + x);
            p[0] = (double)x;
            p[1] = (double)y;
            p[2] = 0;
        }
    m->ntriangles = 2 * nx * ny;
    m->triangles = malloc(3 * m->ntriangles * sizeof(uint32_t));
    size_t t = 0;
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++) {
            uint32_t a = (uint32_t)(y * w + x), b = a + 1, c = (uint32_t)(a + w + 1), d = (uint32_t)(a + w);
            uint32_t *T = m->triangles + 3 * t;
            T[0] = a, T[1] = b, T[2] = c, T[3] = a, T[4] = c, T[5] = d;
            t += 2;
        }
}

/* The 4-square strip: A cuts at x = 2, B at x = 1 (worked in docs/segeval.md). */
static void test_strip_by_hand(void **state) {
    (void)state;
    acd_mesh m;
    strip(&m, 4, 1);
    int a[8] = {0, 0, 0, 0, 1, 1, 1, 1}, b[8] = {5, 5, 9, 9, 9, 9, 9, 9};
    acd_segeval_result r;
    acd_error err;
    assert_int_equal(acd_segeval(&m, a, b, NULL, &r, &err), ACD_OK);
    CLOSE(r.total_weight, 4.0);
    CLOSE(r.rand_index, 4.0 / 7.0);
    CLOSE(r.hamming_rm, 0.25);
    CLOSE(r.hamming_rf, 0.25);
    CLOSE(r.hamming, 0.25);
    CLOSE(r.gce, 0.25);
    CLOSE(r.lce, 0.125);
    assert_int_equal(r.nsegments_a, 2);
    assert_int_equal(r.nsegments_b, 2);
    assert_int_equal(r.ncut_a, 2);
    assert_int_equal(r.ncut_b, 2);
    assert_int_equal(r.cd_defined, 1);
    assert_int_equal(r.cd_unreachable, 0);
    CLOSE(r.dcd_ab, 1.0);
    CLOSE(r.dcd_ba, 1.0);
    double avg = (sqrt(5.0) + sqrt(17.0) + sqrt(65.0) + sqrt(101.0)) / 24.0;
    CLOSE(r.avg_radius, avg);
    CLOSE(r.cut_discrepancy, 2.0 / avg);
    CLOSE(r.cut_discrepancy_pooled, 1.0 / avg);
    /* equal areas: face weighting gives the same region values */
    acd_segeval_options o = acd_segeval_default_options();
    o.weighting = ACD_SEGEVAL_WEIGHT_FACES;
    assert_int_equal(acd_segeval(&m, a, b, &o, &r, &err), ACD_OK);
    CLOSE(r.total_weight, 8.0);
    CLOSE(r.rand_index, 4.0 / 7.0);
    CLOSE(r.gce, 0.25);
    acd_mesh_free(&m);
}

/* Six faces, unit weights: A = {0,1}{2,3}{4,5}, B = {0}{1}{2}{3,4,5}. By hand:
 * Rm = 1/6, Rf = 2/6, HD = 1/4; disagreeing pairs: (0,1), (2,3), (3,4), (3,5) -> 1 - RI = 4/15;
 * sum E(A,B) = 4 * 1/2 = 2, sum E(B,A) = 2/3 + 1/3 + 1/3 = 4/3 -> GCE = (4/3)/6 = 2/9;
 * LCE = min(1/2, 2/3)/6 = 1/12. */
static void test_counts_by_hand(void **state) {
    (void)state;
    int a[6] = {0, 0, 1, 1, 2, 2}, b[6] = {0, 1, 3, 2, 2, 2};
    acd_segeval_result r;
    acd_error err;
    assert_int_equal(acd_segeval_regions(a, b, 6, NULL, &r, &err), ACD_OK);
    CLOSE(r.hamming_rm, 1.0 / 6.0);
    CLOSE(r.hamming_rf, 1.0 / 3.0);
    CLOSE(r.hamming, 0.25);
    CLOSE(1.0 - r.rand_index, 4.0 / 15.0);
    CLOSE(r.gce, 2.0 / 9.0);
    CLOSE(r.lce, 1.0 / 12.0);
    assert_int_equal(r.cd_defined, 0);
}

/* Three faces with weights 1, 2, 3: A = {0,1}{2}, B = {0}{1,2}. By hand: pair weights 2 (A same,
 * B apart), 3 (both apart), 6 (A apart, B same) -> 1 - RI = 8/11; Rm = (5-3)/6, Rf = (3-2)/6;
 * E(A,B) = 2/3, 1/3, 0 and E(B,A) = 0, 3/5, 2/5 -> GCE = min(4/3, 12/5)/6 = 2/9, LCE = (2/3)/6. */
static void test_weights_by_hand(void **state) {
    (void)state;
    int a[3] = {0, 0, 1}, b[3] = {0, 1, 1};
    double w[3] = {1, 2, 3};
    acd_segeval_result r;
    acd_error err;
    assert_int_equal(acd_segeval_regions(a, b, 3, w, &r, &err), ACD_OK);
    CLOSE(1.0 - r.rand_index, 8.0 / 11.0);
    CLOSE(r.hamming_rm, 1.0 / 3.0);
    CLOSE(r.hamming_rf, 1.0 / 6.0);
    CLOSE(r.gce, 2.0 / 9.0);
    CLOSE(r.lce, 1.0 / 9.0);
}

static void random_labels(acd_rng *rng, int *lab, size_t n, int k) {
    for (size_t i = 0; i < n; i++) lab[i] = (int)acd_rng_below(rng, (uint64_t)k) * 37 - 50;
}

static void test_identical_and_refinement(void **state) {
    (void)state;
    acd_mesh m;
    strip(&m, 10, 6);
    size_t n = m.ntriangles;
    /* perturb the z coordinates so that areas differ */
    acd_rng rng;
    acd_rng_seed(&rng, 5);
    for (size_t v = 0; v < m.nvertices; v++) m.vertices[3 * v + 2] = 0.4 * acd_rng_uniform(&rng);
    int *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b), *c = malloc(n * sizeof *c);
    for (size_t t = 0; t < n; t++) {
        size_t sq = t / 2, x = sq % 10, y = sq / 10;
        a[t] = (int)(x / 4 + 10 * (y / 3)); /* blocks of 4 x 3 squares */
        b[t] = a[t] * 1000 - 7;             /* same partition, other names */
        c[t] = (int)(x / 2 + 10 * y);       /* refinement of a: 2 x 1 blocks */
    }
    acd_segeval_result r;
    acd_error err;
    assert_int_equal(acd_segeval(&m, a, b, NULL, &r, &err), ACD_OK);
    assert_true(r.rand_index == 1.0);
    assert_true(r.hamming == 0.0 && r.hamming_rm == 0.0 && r.hamming_rf == 0.0);
    assert_true(r.gce == 0.0 && r.lce == 0.0);
    assert_int_equal(r.cd_defined, 1);
    assert_true(r.cut_discrepancy == 0.0 && r.cut_discrepancy_pooled == 0.0);
    /* a refinement (c refines a): consistency errors 0, but the Hamming distance is not */
    assert_int_equal(acd_segeval(&m, a, c, NULL, &r, &err), ACD_OK);
    assert_true(r.gce == 0.0);
    assert_true(r.lce == 0.0);
    assert_true(r.hamming_rm == 0.0); /* every segment of c lies inside one of a */
    assert_true(r.hamming_rf > 0.1);
    assert_true(r.hamming > 0.05);
    assert_true(r.rand_index < 1.0);
    assert_true(r.cut_discrepancy > 0.0);
    assert_true(r.dcd_ab == 0.0); /* a's cuts are among c's cuts */
    free(a);
    free(b);
    free(c);
    acd_mesh_free(&m);
}

/* ---- brute force from the definitions ---------------------------------------------------- */

static void brute_regions(const int *a, const int *b, size_t n, const double *w, double *ri, double *rm, double *rf,
                          double *gce, double *lce) {
    double W = 0, agree = 0, pairs = 0;
    for (size_t i = 0; i < n; i++) W += w[i];
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++) {
            pairs += w[i] * w[j];
            if ((a[i] == a[j]) == (b[i] == b[j])) agree += w[i] * w[j];
        }
    *ri = agree / pairs;
    /* D_H(X => Y) = sum over segments R of Y of |R \ best segment of X|, where best maximises
     * the overlap (any maximiser gives the same value) */
    double d[2] = {0, 0};
    for (int dir = 0; dir < 2; dir++) {
        const int *X = dir ? b : a, *Y = dir ? a : b;
        for (size_t i = 0; i < n; i++) {
            int first = 1; /* visit each Y segment once, at its first face */
            for (size_t k = 0; k < i; k++)
                if (Y[k] == Y[i]) first = 0;
            if (!first) continue;
            double best = 0, size = 0;
            for (size_t j = 0; j < n; j++) {
                if (Y[j] != Y[i]) continue;
                size += w[j];
                double ov = 0;
                for (size_t k = 0; k < n; k++)
                    if (Y[k] == Y[i] && X[k] == X[j]) ov += w[k];
                if (ov > best) best = ov;
            }
            d[dir] += size - best;
        }
    }
    *rm = d[0] / W;
    *rf = d[1] / W;
    double s1 = 0, s2 = 0, l = 0;
    for (size_t f = 0; f < n; f++) {
        double ra = 0, rb = 0, ab = 0;
        for (size_t k = 0; k < n; k++) {
            if (a[k] == a[f]) ra += w[k];
            if (b[k] == b[f]) rb += w[k];
            if (a[k] == a[f] && b[k] == b[f]) ab += w[k];
        }
        double e1 = (ra - ab) / ra, e2 = (rb - ab) / rb;
        s1 += w[f] * e1;
        s2 += w[f] * e2;
        l += w[f] * (e1 < e2 ? e1 : e2);
    }
    *gce = (s1 < s2 ? s1 : s2) / W;
    *lce = l / W;
}

static void test_regions_brute_force(void **state) {
    (void)state;
    acd_rng rng;
    acd_rng_seed(&rng, 31337);
    for (int t = 0; t < 300; t++) {
        size_t n = 2 + (size_t)acd_rng_below(&rng, 40);
        int a[64], b[64];
        double w[64];
        random_labels(&rng, a, n, 1 + (int)acd_rng_below(&rng, 6));
        random_labels(&rng, b, n, 1 + (int)acd_rng_below(&rng, 6));
        int unit = t % 3 == 0;
        for (size_t i = 0; i < n; i++) w[i] = unit ? 1.0 : 0.1 + acd_rng_uniform(&rng);
        acd_segeval_result r, s;
        acd_error err;
        assert_int_equal(acd_segeval_regions(a, b, n, unit ? NULL : w, &r, &err), ACD_OK);
        double ri, rm, rf, gce, lce;
        brute_regions(a, b, n, w, &ri, &rm, &rf, &gce, &lce);
        CLOSE(r.rand_index, ri);
        CLOSE(r.hamming_rm, rm);
        CLOSE(r.hamming_rf, rf);
        CLOSE(r.gce, gce);
        CLOSE(r.lce, lce);
        /* symmetry: swapping A and B swaps Rm and Rf and keeps the rest */
        assert_int_equal(acd_segeval_regions(b, a, n, unit ? NULL : w, &s, &err), ACD_OK);
        CLOSE(s.rand_index, r.rand_index);
        CLOSE(s.hamming_rm, r.hamming_rf);
        CLOSE(s.hamming_rf, r.hamming_rm);
        CLOSE(s.gce, r.gce);
        CLOSE(s.lce, r.lce);
        assert_true(r.gce >= r.lce - 1e-15);
    }
}

/* Cut discrepancy against Floyd-Warshall on random labellings of a 5 x 3 grid, plus a mesh of two
 * separate strips (cut points that cannot reach the other cut are left out and counted). */
static void test_cut_discrepancy_brute_force(void **state) {
    (void)state;
    acd_mesh m;
    strip(&m, 5, 3);
    size_t nv = m.nvertices, nt = m.ntriangles;
    double *D = malloc(nv * nv * sizeof *D);
    for (size_t i = 0; i < nv * nv; i++) D[i] = INFINITY;
    for (size_t i = 0; i < nv; i++) D[i * nv + i] = 0;
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t u = m.triangles[3 * t + k], v = m.triangles[3 * t + (k + 1) % 3];
            double dx = m.vertices[3 * u] - m.vertices[3 * v], dy = m.vertices[3 * u + 1] - m.vertices[3 * v + 1];
            D[u * nv + v] = D[v * nv + u] = sqrt(dx * dx + dy * dy);
        }
    for (size_t k = 0; k < nv; k++)
        for (size_t i = 0; i < nv; i++)
            for (size_t j = 0; j < nv; j++)
                if (D[i * nv + k] + D[k * nv + j] < D[i * nv + j]) D[i * nv + j] = D[i * nv + k] + D[k * nv + j];
    acd_rng rng;
    acd_rng_seed(&rng, 8);
    int a[30], b[30];
    for (int t = 0; t < 100; t++) {
        random_labels(&rng, a, nt, 2 + (int)acd_rng_below(&rng, 3));
        random_labels(&rng, b, nt, 2 + (int)acd_rng_below(&rng, 3));
        /* cut vertices by brute force: pairs of triangles sharing two vertices, different labels */
        uint8_t ca[24] = {0}, cb[24] = {0};
        for (size_t s = 0; s < nt; s++)
            for (size_t u = s + 1; u < nt; u++) {
                uint32_t sh[3];
                int k = 0;
                for (int p = 0; p < 3; p++)
                    for (int q = 0; q < 3; q++)
                        if (m.triangles[3 * s + p] == m.triangles[3 * u + q]) sh[k++] = m.triangles[3 * s + p];
                if (k != 2) continue;
                if (a[s] != a[u]) ca[sh[0]] = ca[sh[1]] = 1;
                if (b[s] != b[u]) cb[sh[0]] = cb[sh[1]] = 1;
            }
        double sab = 0, sba = 0;
        size_t na = 0, nb = 0;
        for (size_t v = 0; v < nv; v++) {
            double best = INFINITY;
            if (ca[v]) {
                for (size_t x = 0; x < nv; x++)
                    if (cb[x] && D[v * nv + x] < best) best = D[v * nv + x];
                sab += best;
                na++;
            }
            best = INFINITY;
            if (cb[v]) {
                for (size_t x = 0; x < nv; x++)
                    if (ca[x] && D[v * nv + x] < best) best = D[v * nv + x];
                sba += best;
                nb++;
            }
        }
        acd_segeval_result r;
        acd_error err;
        assert_int_equal(acd_segeval(&m, a, b, NULL, &r, &err), ACD_OK);
        assert_int_equal(r.ncut_a, na);
        assert_int_equal(r.ncut_b, nb);
        if (na == 0 || nb == 0) {
            assert_int_equal(r.cd_defined, 0);
            continue;
        }
        assert_int_equal(r.cd_defined, 1);
        CLOSE(r.dcd_ab, sab / (double)na);
        CLOSE(r.dcd_ba, sba / (double)nb);
        CLOSE(r.cut_discrepancy, (sab / (double)na + sba / (double)nb) / r.avg_radius);
        CLOSE(r.cut_discrepancy_pooled, (sab + sba) / (double)(na + nb) / r.avg_radius);
    }
    free(D);
    acd_mesh_free(&m);

    /* two strips side by side (not connected): A cuts only the first, B cuts both */
    acd_mesh two;
    strip(&two, 2, 1); /* 6 vertices, 4 triangles */
    two.vertices = realloc(two.vertices, 12 * 3 * sizeof(double));
    two.triangles = realloc(two.triangles, 8 * 3 * sizeof(uint32_t));
    for (int v = 0; v < 6; v++) {
        memcpy(two.vertices + 3 * (6 + v), two.vertices + 3 * v, 3 * sizeof(double));
        two.vertices[3 * (6 + v) + 1] += 5;
    }
    for (int k = 0; k < 12; k++) two.triangles[12 + k] = two.triangles[k] + 6;
    two.nvertices = 12;
    two.ntriangles = 8;
    int la[8] = {0, 0, 1, 1, 2, 2, 2, 2}, lb[8] = {0, 0, 1, 1, 2, 2, 3, 3};
    acd_segeval_result r;
    acd_error err;
    assert_int_equal(acd_segeval(&two, la, lb, NULL, &r, &err), ACD_OK);
    assert_int_equal(r.ncut_a, 2);
    assert_int_equal(r.ncut_b, 4);
    assert_int_equal(r.cd_unreachable, 2); /* B's cut on the second strip cannot reach A's */
    assert_int_equal(r.cd_defined, 1);
    assert_true(r.dcd_ab == 0.0 && r.dcd_ba == 0.0);
    /* a labelling without any cut: CD undefined, region metrics still computed */
    int one[8] = {4, 4, 4, 4, 4, 4, 4, 4};
    assert_int_equal(acd_segeval(&two, one, lb, NULL, &r, &err), ACD_OK);
    assert_int_equal(r.cd_defined, 0);
    assert_true(isnan(r.cut_discrepancy));
    assert_true(r.rand_index < 1.0);
    acd_mesh_free(&two);
}

static void test_errors(void **state) {
    (void)state;
    acd_mesh m;
    strip(&m, 2, 1);
    int a[4] = {0, 0, 1, 1};
    acd_segeval_result r;
    acd_error err;
    m.triangles[7] = 99;
    assert_int_equal(acd_segeval(&m, a, a, NULL, &r, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "triangle 2"));
    m.triangles[7] = 0;
    for (size_t i = 0; i < 3 * m.nvertices; i++) m.vertices[i] = 1.0; /* zero area */
    assert_int_equal(acd_segeval(&m, a, a, NULL, &r, &err), ACD_ERR_DEGENERATE);
    acd_segeval_options o = acd_segeval_default_options();
    o.weighting = ACD_SEGEVAL_WEIGHT_FACES;
    assert_int_equal(acd_segeval(&m, a, a, &o, &r, &err), ACD_OK); /* counts still work */
    assert_true(r.rand_index == 1.0);
    assert_int_equal(r.cd_defined, 0); /* zero radius */
    m.vertices[0] = NAN;
    assert_int_equal(acd_segeval(&m, a, a, &o, &r, &err), ACD_ERR_INVALID_INPUT);
    double w[4] = {1, -1, 1, 1};
    assert_int_equal(acd_segeval_regions(a, a, 4, w, &r, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "face 1"));
    assert_int_equal(acd_segeval_regions(a, a, 0, NULL, &r, &err), ACD_ERR_DEGENERATE);
    assert_int_equal(acd_segeval_regions(NULL, a, 4, NULL, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    /* a single face: RI is 1 by convention (no pairs) */
    assert_int_equal(acd_segeval_regions(a, a + 2, 1, NULL, &r, &err), ACD_OK);
    assert_true(r.rand_index == 1.0 && r.gce == 0.0);
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_strip_by_hand),
        cmocka_unit_test(test_counts_by_hand),
        cmocka_unit_test(test_weights_by_hand),
        cmocka_unit_test(test_identical_and_refinement),
        cmocka_unit_test(test_regions_brute_force),
        cmocka_unit_test(test_cut_discrepancy_brute_force),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
