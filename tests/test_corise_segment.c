/* Tests of the CoRiSe loop (corise/corise): closed height-field boxes with V trenches are cut at
 * the trench bottoms (one trench: 2 parts in one cut; two trenches: 3 parts, two levels deep), a
 * convex box stays whole, a large tau cuts nothing; labels cover every facet with connected
 * parts; the result is deterministic; argument errors. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "corise/corise.h"
#include "corise_meshes.h"

typedef struct trenches {
    int n;
    double h, depth, xc[4], halfwidth;
} trenches;

static double top(double x, double y, const void *u) {
    (void)y;
    const trenches *t = u;
    double z = t->h;
    for (int k = 0; k < t->n; k++) {
        double d = fabs(x - t->xc[k]) / t->halfwidth;
        if (d < 1) z -= t->depth * (1 - d);
    }
    return z;
}

/* No part straddles a trench bottom x = c: all facets of a part lie between the same two
 * consecutive bottoms, and facets between different pairs of bottoms never share a part. */
static void check_slabs(const acd_mesh *m, const uint32_t *lab, size_t nparts, const double *cuts, int ncuts) {
    int *slab_of_part = malloc(nparts * sizeof *slab_of_part);
    for (size_t k = 0; k < nparts; k++) slab_of_part[k] = -1;
    for (size_t f = 0; f < m->ntriangles; f++) {
        assert_true(lab[f] < nparts);
        const uint32_t *T = m->triangles + 3 * f;
        double cx = (m->vertices[3 * T[0]] + m->vertices[3 * T[1]] + m->vertices[3 * T[2]]) / 3;
        int s = 0;
        while (s < ncuts && cx > cuts[s]) s++;
        for (int k = 0; k < 3; k++) {
            double x = m->vertices[3 * T[k]];
            if (s > 0) assert_true(x >= cuts[s - 1] - 1e-12);
            if (s < ncuts) assert_true(x <= cuts[s] + 1e-12);
        }
        if (slab_of_part[lab[f]] < 0) slab_of_part[lab[f]] = s;
        assert_int_equal(slab_of_part[lab[f]], s);
    }
    for (size_t k = 0; k < nparts; k++) assert_true(slab_of_part[k] >= 0); /* no empty label */
    free(slab_of_part);
}

static void test_one_trench(void **state) {
    (void)state;
    trenches tr = {1, 1.0, 0.6, {1.0}, 0.25};
    acd_mesh m;
    cm_heightfield_box(&m, 16, 8, 8, 2.0, 1.0, top, &tr);
    uint32_t *lab = malloc(m.ntriangles * sizeof *lab), *lab2 = malloc(m.ntriangles * sizeof *lab2);
    acd_corise_params p = acd_corise_default_params();
    /* normalised units: the trench is 0.6 / sqrt(1.5) = 0.49 deep. Below tau = 0.45 the halves are
     * cut again because of Dijkstra staircases on this anisotropic grid (docs/corise.md) */
    p.tau = 0.45;
    acd_corise_stats st;
    acd_error err;
    assert_int_equal(acd_corise_segment(&m, &p, lab, &st, &err), ACD_OK);
    assert_int_equal(st.parts, 2);
    assert_int_equal(st.cuts, 1);
    assert_int_equal(st.depth, 1);
    assert_int_equal(st.unresolved, 0);
    assert_true(fabs(st.scale - 1 / sqrt(1.5)) < 1e-12);
    double cuts[] = {1.0};
    check_slabs(&m, lab, 2, cuts, 1);
    assert_int_equal(lab[0], 0); /* numbered by smallest facet */
    /* deterministic */
    assert_int_equal(acd_corise_segment(&m, &p, lab2, NULL, &err), ACD_OK);
    assert_memory_equal(lab, lab2, m.ntriangles * sizeof *lab);
    /* tau above the trench depth: one part */
    p.tau = 0.6;
    assert_int_equal(acd_corise_segment(&m, &p, lab, &st, &err), ACD_OK);
    assert_int_equal(st.parts, 1);
    for (size_t f = 0; f < m.ntriangles; f++) assert_int_equal(lab[f], 0);
    /* errors */
    p.tau = -1;
    assert_int_equal(acd_corise_segment(&m, &p, lab, &st, &err), ACD_ERR_INVALID_ARGUMENT);
    p.tau = 0.3;
    m.triangles[5] = (uint32_t)m.nvertices;
    assert_int_equal(acd_corise_segment(&m, &p, lab, &st, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "triangle 1"));
    free(lab);
    free(lab2);
    acd_mesh_free(&m);
}

static void test_two_trenches(void **state) {
    (void)state;
    trenches tr = {2, 1.0, 0.7, {1.0, 2.0}, 0.25};
    acd_mesh m;
    cm_heightfield_box(&m, 24, 8, 8, 3.0, 1.0, top, &tr);
    uint32_t *lab = malloc(m.ntriangles * sizeof *lab);
    acd_corise_params p = acd_corise_default_params();
    p.tau = 0.3; /* trenches 0.7 / sqrt(2.75) = 0.42 deep in normalised units */
    acd_corise_stats st;
    acd_error err;
    assert_int_equal(acd_corise_segment(&m, &p, lab, &st, &err), ACD_OK);
    /* both trench bottoms are cut: the flat top facets left of x = 1, between 1 and 2, and right
     * of 2 never share a part (on the flat bottom and walls the cut may wander along equal-cost
     * staircases, and artefacts may split the slabs further: docs/corise.md) */
    assert_true(st.parts >= 3);
    assert_int_equal(st.unresolved, 0);
    assert_true(st.depth >= 2);
    uint8_t *seen = calloc(st.parts * 3, 1);
    for (size_t f = 0; f < m.ntriangles; f++) {
        const uint32_t *T = m.triangles + 3 * f;
        double cx = 0, minz = 1e9;
        for (int k = 0; k < 3; k++) {
            cx += m.vertices[3 * T[k]] / 3;
            if (m.vertices[3 * T[k] + 2] < minz) minz = m.vertices[3 * T[k] + 2];
        }
        if (minz < 1.0 - 1e-12) continue; /* not on the flat top */
        int slab = cx < 1 ? 0 : cx < 2 ? 1 : 2;
        assert_true(lab[f] < st.parts);
        seen[3 * lab[f] + slab] = 1;
    }
    size_t used[3] = {0, 0, 0};
    for (size_t k = 0; k < st.parts; k++) {
        assert_true(seen[3 * k] + seen[3 * k + 1] + seen[3 * k + 2] <= 1);
        for (int sl = 0; sl < 3; sl++) used[sl] += seen[3 * k + sl];
    }
    assert_true(used[0] >= 1 && used[1] >= 1 && used[2] >= 1);
    free(seen);
    free(lab);
    acd_mesh_free(&m);
}

static void test_convex_box_and_two_components(void **state) {
    (void)state;
    trenches flat = {0, 1.0, 0, {0}, 1};
    acd_mesh m;
    cm_heightfield_box(&m, 16, 8, 8, 2.0, 1.0, top, &flat); /* staircases stay below tau = 0.1 */
    uint32_t *lab = malloc(2 * m.ntriangles * sizeof *lab);
    acd_corise_params p = acd_corise_default_params();
    acd_corise_stats st;
    acd_error err;
    assert_int_equal(acd_corise_segment(&m, &p, lab, &st, &err), ACD_OK);
    assert_int_equal(st.parts, 1);
    assert_int_equal(st.cuts, 0);
    /* two disjoint copies: two parts, one per component (spec A15) */
    size_t nv = m.nvertices, nt = m.ntriangles;
    m.vertices = realloc(m.vertices, 6 * nv * sizeof(double));
    m.triangles = realloc(m.triangles, 6 * nt * sizeof(uint32_t));
    for (size_t v = 0; v < nv; v++) {
        for (int c = 0; c < 3; c++) m.vertices[3 * (nv + v) + c] = m.vertices[3 * v + c];
        m.vertices[3 * (nv + v)] += 5;
    }
    for (size_t k = 0; k < 3 * nt; k++) m.triangles[3 * nt + k] = m.triangles[k] + (uint32_t)nv;
    m.nvertices = 2 * nv;
    m.ntriangles = 2 * nt;
    assert_int_equal(acd_corise_segment(&m, &p, lab, &st, &err), ACD_OK);
    assert_int_equal(st.parts, 2);
    for (size_t f = 0; f < 2 * nt; f++) assert_int_equal(lab[f], f < nt ? 0 : 1);
    free(lab);
    acd_mesh_free(&m);
}

/* With the hull-depth clamp (not in the paper) the default tau = 0.1 cuts a finer trench box
 * exactly into its two halves. */
static void test_one_trench_clamped(void **state) {
    (void)state;
    trenches tr = {1, 1.0, 0.6, {1.0}, 0.25};
    acd_mesh m;
    cm_heightfield_box(&m, 64, 32, 32, 2.0, 1.0, top, &tr);
    uint32_t *lab = malloc(m.ntriangles * sizeof *lab);
    acd_corise_params p = acd_corise_default_params();
    p.clamp_hull_depth = 1;
    acd_corise_stats st;
    acd_error err;
    assert_int_equal(acd_corise_segment(&m, &p, lab, &st, &err), ACD_OK);
    assert_int_equal(st.parts, 2);
    double cuts[] = {1.0};
    check_slabs(&m, lab, 2, cuts, 1);
    size_t n0 = 0;
    for (size_t f = 0; f < m.ntriangles; f++) n0 += lab[f] == 0;
    assert_int_equal(n0, m.ntriangles / 2);
    free(lab);
    acd_mesh_free(&m);
}

/* Degenerate and open input: one triangle and a flat grid (planar hull: one part), an open box
 * (no top: runs, every facet labelled, parts connected by construction), duplicate triangles. */
static void test_degenerate_and_open(void **state) {
    (void)state;
    acd_error err;
    acd_corise_stats st;
    acd_corise_params p = acd_corise_default_params();
    double v[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t t[] = {0, 1, 2, 0, 1, 2};
    acd_mesh tri = {v, 3, t, 1};
    uint32_t lab[2048];
    assert_int_equal(acd_corise_segment(&tri, &p, lab, &st, &err), ACD_OK);
    assert_int_equal(st.parts, 1);
    assert_int_equal(lab[0], 0);
    tri.ntriangles = 2; /* the same triangle twice */
    assert_int_equal(acd_corise_segment(&tri, &p, lab, &st, &err), ACD_OK);
    assert_int_equal(st.parts, 1);
    tri.ntriangles = 0;
    assert_int_equal(acd_corise_segment(&tri, &p, lab, &st, &err), ACD_ERR_DEGENERATE);

    trenches tr = {1, 1.0, 0.6, {1.0}, 0.25};
    acd_mesh m;
    cm_heightfield_box(&m, 16, 8, 8, 2.0, 1.0, top, &tr);
    /* drop the top (the first 2 * 16 * 8 * 2 triangles are top and bottom interleaved: keep the
     * bottom ones and the walls) */
    size_t k = 0;
    for (size_t f = 0; f < m.ntriangles; f++) {
        int is_top = f < 4 * 16 * 8 && (f % 4) < 2;
        if (is_top) continue;
        memmove(m.triangles + 3 * k, m.triangles + 3 * f, 3 * sizeof(uint32_t));
        k++;
    }
    m.ntriangles = k;
    assert_true(k <= 2048);
    p.tau = 0.3;
    assert_int_equal(acd_corise_segment(&m, &p, lab, &st, &err), ACD_OK);
    assert_true(st.parts >= 1);
    for (size_t f = 0; f < m.ntriangles; f++) assert_true(lab[f] < st.parts);
    acd_mesh_free(&m);
}

/* Noisy input (every vertex jittered by up to 2 % of the box): both modes run, label every facet
 * with non-empty parts, and repeat bit for bit. */
static void test_noisy_deterministic(void **state) {
    (void)state;
    trenches tr = {1, 1.0, 0.6, {1.0}, 0.25};
    acd_mesh m;
    cm_heightfield_box(&m, 16, 8, 8, 2.0, 1.0, top, &tr);
    acd_rng rng;
    acd_rng_seed(&rng, 77);
    for (size_t i = 0; i < 3 * m.nvertices; i++) m.vertices[i] += 0.04 * (acd_rng_uniform(&rng) - 0.5);
    uint32_t *a = malloc(m.ntriangles * sizeof *a), *b = malloc(m.ntriangles * sizeof *b);
    for (int clamp = 0; clamp < 2; clamp++) {
        acd_corise_params p = acd_corise_default_params();
        p.clamp_hull_depth = clamp;
        acd_corise_stats s1, s2;
        acd_error err;
        assert_int_equal(acd_corise_segment(&m, &p, a, &s1, &err), ACD_OK);
        assert_int_equal(acd_corise_segment(&m, &p, b, &s2, &err), ACD_OK);
        assert_memory_equal(a, b, m.ntriangles * sizeof *a);
        assert_int_equal(s1.parts, s2.parts);
        size_t *cnt = calloc(s1.parts, sizeof *cnt);
        for (size_t f = 0; f < m.ntriangles; f++) {
            assert_true(a[f] < s1.parts);
            cnt[a[f]]++;
        }
        for (size_t k = 0; k < s1.parts; k++) assert_true(cnt[k] > 0);
        free(cnt);
    }
    free(a);
    free(b);
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_trench),
        cmocka_unit_test(test_two_trenches),
        cmocka_unit_test(test_convex_box_and_two_components),
        cmocka_unit_test(test_one_trench_clamped),
        cmocka_unit_test(test_degenerate_and_open),
        cmocka_unit_test(test_noisy_deterministic),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
