// ctest: LABELS slow TIMEOUT 900
/* Property tests of the 2D decomposition on the large models of the shared data folder (the
 * Nazca monkey and heron at every resolution, the maze, star4..star6): every measure and tau in
 * {0, 0.01, 0.1, 0.5, 1, 5, 10, 20, 40}, checked as in test_acd2d_properties.c
 * (tests/support/props2d.h). Labelled slow: skipped in the ASan run. */
#include "testutil.h"

#include <stdlib.h>

#include "props2d.h"

static const char *const large_models[] = {
    "star_star4.poly", "star_star4_noise.poly", "wierd2.poly", "wierd2_n.poly",
    "nazca_nazca_heron_oldversion.poly", "nazca_nazca_heron_original.poly", "nazca_nazca_heron.poly",
    "nazca_nazca_monkey_oldversion.poly", "nazca_nazca_monkey_original.poly", "nazca_nazca_monkey.poly",
    "star_star5.poly", "star_star5_noise.poly", "nazca_nazca_monkey1.5.poly", "nazca_nazca_nosize_monkey1.5.poly",
    "nazca_nazca_monkey_original_2.poly", "nazca_nazca_monkey_2.poly", "star_star6.poly",
};

static void test_large_models(void **state) {
    (void)state;
    p2d_stats st = {0};
    st.survey = getenv("ACD_P2D_SURVEY") != NULL;
    size_t found = 0;
    for (size_t i = 0; i < sizeof large_models / sizeof large_models[0]; i++) {
        char rel[256];
        snprintf(rel, sizeof rel, "polygons-lien/%s", large_models[i]);
        found += (size_t)p2d_sweep_file(rel, 0, &st);
        print_message("    %s: %zu runs so far\n", large_models[i], st.runs);
    }
    print_message("    %zu files, %zu runs checked (%zu components), %zu runs unsupported by acd2d, %zu refused\n", found,
                  st.runs, st.components, st.unsupported, st.refused);
    if (!found) TU_SKIP("no shared polygon data");
    print_message("    %zu known-defect failures, %zu failures\n", st.known, st.failed);
    assert_int_equal(st.failed, 0);
    assert_true(st.runs > 0);
    assert_int_equal(st.refused, 0);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_large_models)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
