/* Property tests of the 2D decomposition (spec ../shared/spec/acd2d.md §12): for the small
 * polygons of the shared data folder and for random star-shaped polygons with 0, 1 and 2 holes,
 * every measure and tau in {0, 0.01, 0.1, 0.5, 1, 5, 10, 20, 40}: the independent verifier
 * accepts the partition and the tau bound (and rejects it against a stricter bound), the
 * component count is at most notches + 1 without holes, reported concavities match the
 * recomputed ones, SP/H1 never increase concavity along the tree, results are deterministic
 * (checks in tests/support/props2d.h). The large models are in test_acd2d_properties_slow.c. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>

#include "core/rng.h"
#include "props2d.h"

/* Files with at most ~500 vertices. */
static const char *const small_models[] = {
    "simple1.poly", "star_star1.poly", "hole1.poly", "simple2.poly", "batlogo.poly", "BarbedThing.poly",
    "hole2.poly", "star_star2.poly", "star_star2_noise.poly", "egg.poly", "simple3.poly", "hole4.poly",
    "dragon.poly", "torus2.poly", "torus1.poly", "wierd1.poly", "dsb.poly", "simple4.poly", "texas.poly",
    "star_star3.poly", "star_star3_noise.poly", "taiwan.poly", "bird.poly", "simple8.poly", "simple7.poly",
    "hole5.poly", "hole3.poly", "simple5.poly",
};

static void test_small_models(void **state) {
    (void)state;
    p2d_stats st = {0};
    st.survey = getenv("ACD_P2D_SURVEY") != NULL;
    size_t found = 0;
    for (size_t i = 0; i < sizeof small_models / sizeof small_models[0]; i++) {
        char rel[256];
        snprintf(rel, sizeof rel, "polygons-lien/%s", small_models[i]);
        found += (size_t)p2d_sweep_file(rel, 1, &st);
    }
    print_message("    %zu files, %zu runs checked (%zu components), %zu runs unsupported by acd2d, %zu refused\n", found,
                  st.runs, st.components, st.unsupported, st.refused);
    if (!found) TU_SKIP("no shared polygon data");
    print_message("    %zu known-defect failures, %zu failures\n", st.known, st.failed);
    assert_int_equal(st.failed, 0);
    assert_true(st.runs > 0);
    assert_int_equal(st.refused, 0);
}

/* A star-shaped polygon around (cx, cy): n vertices at angles i*2pi/n jittered by less than
 * half a step (gaps < pi/2 for n >= 8) and radii in [r0, r1]; orientation sign: +1 CCW. */
static void star(acd_rng *rng, acd_vec2 *out, size_t n, double cx, double cy, double r0, double r1, int sign) {
    for (size_t i = 0; i < n; i++) {
        double a = (i + 0.45 * (acd_rng_uniform(rng) - 0.5)) * 2 * 3.14159265358979323846 / (double)n;
        double r = r0 + (r1 - r0) * acd_rng_uniform(rng);
        size_t k = sign > 0 ? i : n - 1 - i;
        out[k] = (acd_vec2){cx + r * cos(a), cy + r * sin(a)};
    }
}

static void test_random_stars(void **state) {
    (void)state;
    static const size_t sizes[] = {8, 16, 40, 120};
    p2d_stats st = {0};
    st.survey = getenv("ACD_P2D_SURVEY") != NULL;
    acd_rng rng;
    acd_rng_seed(&rng, 20061201);
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++)
        for (int holes = 0; holes <= 2; holes++)
            for (int rep = 0; rep < 3; rep++) {
                size_t n = sizes[s], hn = 6 + n / 10;
                acd_vec2 outer[120], h1[32], h2[32];
                /* outer radii in [30, 100]: its edges stay > 30 cos(pi/4) > 21 from the centre */
                star(&rng, outer, n, 0, 0, 30, 100, +1);
                const acd_vec2 *rings[3] = {outer, h1, h2};
                size_t rs[3] = {n, hn, hn};
                if (holes == 1) star(&rng, h1, hn, 0, 0, 5, 15, -1);
                if (holes == 2) {
                    star(&rng, h1, hn, -9, 0, 2, 7, -1);
                    star(&rng, h2, hn, 9, 0, 2, 7, -1);
                }
                acd_polygon p;
                acd_error err;
                assert_int_equal(acd_polygon_from_rings(&p, rings, rs, 1 + (size_t)holes, &err), ACD_OK);
                if (acd_polygon_validate(&p, 0, &err) != ACD_OK) fail_msg("random star invalid: %s", err.message);
                char name[64];
                snprintf(name, sizeof name, "star n=%zu holes=%d #%d", n, holes, rep);
                for (int m = 0; m < 4; m++)
                    for (size_t t = 0; t < P2D_NTAUS; t++) p2d_check(&p, name, (acd2d_measure)m, p2d_taus[t], t == 0, &st);
                acd_polygon_free(&p);
            }
    print_message("    %zu runs checked (%zu components), %zu runs unsupported by acd2d, %zu refused\n", st.runs,
                  st.components, st.unsupported, st.refused);
    print_message("    %zu known-defect failures, %zu failures\n", st.known, st.failed);
    assert_int_equal(st.failed, 0);
    assert_true(st.runs > 0);
    /* a valid polygon with holes is always decomposed (the refusal of "star n=120 holes=1 #1",
     * tests/data/2d/star120-hole-refused.poly, is fixed: test_acd2d_holes.c) */
    assert_int_equal(st.refused, 0);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_small_models),
        cmocka_unit_test(test_random_stars),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
