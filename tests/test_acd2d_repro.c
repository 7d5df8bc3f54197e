// ctest: LABELS slow TIMEOUT 600
/* Reproduction of the dissertation's 2D numbers (Ch. IV) and of the reference sweep of spec
 * acd2d.md §9 (authors' public code, raw units, s_c = 0.1, s_d = 1, ray cuts): component counts
 * within 10% (within 2 below 20 components), Fig. 13 / Fig. 27 counts, IV.D.3.a convexities, and
 * the partition invariants on every run. */
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "acd/acd2d.h"
#include "acd2d_check.h"

static int load(const char *rel, acd_polygon_set *set) {
    char path[1024];
    if (!tu_shared_data(path, sizeof path, rel)) return 0;
    acd_error err;
    if (acd_polygon_set_read_file(set, path, ACD_POLY_FORMAT_AUTO, NULL, &err) != ACD_OK) {
        print_message("cannot read %s: %s\n", path, err.message);
        return -1;
    }
    return 1;
}

static double convexity(const acd2d_result *r) {
    double a = 0, h = 0;
    for (size_t i = 0; i < r->ncomponents; i++) {
        a += ck_ring_area(r->components[i].points, r->components[i].npoints);
        h += ck_ring_area(r->components[i].hull, r->components[i].nhull);
    }
    return a / h;
}

static size_t run(const acd_polygon *p, acd2d_measure m, double tau, double *conv, int check) {
    acd2d_params prm = acd2d_default_params();
    prm.measure = m;
    prm.tau = tau;
    acd2d_result res;
    acd_error err;
    acd_status st = acd2d_decompose(p, &prm, &res, &err);
    if (st != ACD_OK) print_message("decompose: %s\n", err.message);
    assert_int_equal(st, ACD_OK);
    if (check) assert_int_equal(ck_result(&res, &prm, acd_polygon_area(p), 0), 0);
    if (conv) *conv = convexity(&res);
    size_t n = res.ncomponents;
    acd2d_result_free(&res);
    return n;
}

static int close_enough(size_t got, int want) {
    if (want < 20) return labs((long)got - want) <= 2;
    return fabs((double)got - want) <= 0.10 * want;
}

typedef struct row {
    const char *file;
    int measure; /* -1: all four */
    int alt;     /* second measure with the same row (SP=H1), or -1 */
    int want[9];
} row;

static const double taus[9] = {0, 0.01, 0.1, 0.5, 1, 5, 10, 20, 40};

static const row rows[] = {
    {"polygons-lien/wierd2_n.poly", ACD2D_MEASURE_SL, -1, {313, 48, 48, 38, 33, 24, 1, 1, 1}},
    {"polygons-lien/wierd2_n.poly", ACD2D_MEASURE_SP, ACD2D_MEASURE_H1, {318, 48, 46, 39, 33, 24, 20, 5, 5}},
    {"polygons-lien/wierd2_n.poly", ACD2D_MEASURE_H2, -1, {313, 48, 48, 38, 33, 24, 20, 5, 5}},
    {"polygons-lien/nazca_nazca_monkey.poly", ACD2D_MEASURE_SL, -1, {456, 423, 276, 130, 88, 36, 24, 13, 6}},
    {"polygons-lien/nazca_nazca_monkey.poly", ACD2D_MEASURE_SP, ACD2D_MEASURE_H1, {457, 426, 275, 125, 84, 37, 26, 16, 12}},
    {"polygons-lien/nazca_nazca_monkey.poly", ACD2D_MEASURE_H2, -1, {456, 423, 276, 130, 88, 36, 25, 15, 12}},
    {"polygons-lien/nazca_nazca_monkey_2.poly", ACD2D_MEASURE_SL, -1, {-1, 1265, 273, 132, 91, 36, 23, 13, 6}},
    {"polygons-lien/nazca_nazca_monkey_2.poly", ACD2D_MEASURE_SP, ACD2D_MEASURE_H1, {-1, 1275, 281, 123, 87, 39, 24, 16, 12}},
    {"polygons-lien/nazca_nazca_monkey_2.poly", ACD2D_MEASURE_H2, -1, {-1, 1265, 273, 132, 91, 37, 24, 15, 12}},
    {"polygons-lien/nazca_nazca_heron.poly", ACD2D_MEASURE_SL, ACD2D_MEASURE_H2, {375, 334, 143, 48, 35, 19, 16, 2, 1}},
    {"polygons-lien/nazca_nazca_heron.poly", ACD2D_MEASURE_SP, ACD2D_MEASURE_H1, {375, 334, 145, 46, 35, 20, 16, 2, 1}},
    {"polygons-lien/texas.poly", -1, -1, {57, 48, 29, 12, 7, 2, 1, 1, 1}},
    {"polygons-lien/bird.poly", -1, -1, {100, 92, 39, 17, 10, 3, 1, 1, 1}},
};

static void test_reference_sweep(void **state) {
    (void)state;
    int failures = 0, cells = 0;
    for (size_t r = 0; r < sizeof rows / sizeof rows[0]; r++) {
        acd_polygon_set set;
        int ok = load(rows[r].file, &set);
        if (ok == 0) TU_SKIP("%s not found", rows[r].file);
        assert_int_equal(ok, 1);
        int ms[4], nm = 0;
        if (rows[r].measure < 0) { for (int m = 0; m < 4; m++) ms[nm++] = m; }
        else {
            ms[nm++] = rows[r].measure;
            if (rows[r].alt >= 0) ms[nm++] = rows[r].alt;
        }
        for (int k = 0; k < nm; k++) {
            char line[512];
            int len = snprintf(line, sizeof line, "%-40s %s:", rows[r].file + 14, acd2d_measure_name((acd2d_measure)ms[k]));
            for (int t = 0; t < 9; t++) {
                int want = rows[r].want[t];
                size_t got = run(&set.polygons[0], (acd2d_measure)ms[k], taus[t], NULL, 1);
                int good = want < 0 || close_enough(got, want);
                cells += want >= 0;
                if (!good) failures++;
                len += snprintf(line + len, sizeof line - (size_t)len, " %zu/%d%s", got, want, good ? "" : "!");
            }
            print_message("%s\n", line);
        }
        acd_polygon_set_free(&set);
    }
    print_message("reference sweep: %d of %d cells outside the bound\n", failures, cells);
    assert_int_equal(failures, 0);
}

static void test_dissertation_numbers(void **state) {
    (void)state;
    acd_polygon_set monkey, heron, monkey2;
    int a = load("polygons-lien/nazca_nazca_monkey.poly", &monkey);
    if (a == 0) TU_SKIP("monkey not found");
    assert_int_equal(a, 1);
    assert_int_equal(load("polygons-lien/nazca_nazca_heron.poly", &heron), 1);
    assert_int_equal(load("polygons-lien/nazca_nazca_monkey_2.poly", &monkey2), 1);
    double conv;
    /* Fig. 13: monkey, tau = 0.5: 126 (IV intro: 128) components */
    size_t n = run(&monkey.polygons[0], ACD2D_MEASURE_SL, 0.5, NULL, 1);
    print_message("monkey tau 0.5 SL: %zu (126/128)\n", n);
    assert_true(n >= 120 && n <= 134);
    /* Fig. 27: heron, tau = 0.5: 49 */
    n = run(&heron.polygons[0], ACD2D_MEASURE_SL, 0.5, NULL, 1);
    print_message("heron tau 0.5 SL: %zu (49)\n", n);
    assert_true(n >= 46 && n <= 52);
    /* IV.D.3.a: convexity of 0.1-convex decompositions: monkey1 0.997, monkey2 0.995, heron1 0.98 */
    run(&monkey.polygons[0], ACD2D_MEASURE_H1, 0.1, &conv, 0);
    print_message("monkey tau 0.1 convexity %.4f (0.997)\n", conv);
    assert_true(fabs(conv - 0.997) <= 0.002);
    run(&monkey2.polygons[0], ACD2D_MEASURE_H1, 0.1, &conv, 0);
    print_message("monkey2 tau 0.1 convexity %.4f (0.995)\n", conv);
    assert_true(fabs(conv - 0.995) <= 0.002);
    run(&heron.polygons[0], ACD2D_MEASURE_H1, 0.1, &conv, 0);
    print_message("heron tau 0.1 convexity %.4f (0.98)\n", conv);
    assert_true(fabs(conv - 0.98) <= 0.005);
    /* monkey, tau = 1: convexity about 0.94 (IV.D.3.a: -0.06) */
    run(&monkey.polygons[0], ACD2D_MEASURE_H1, 1, &conv, 0);
    print_message("monkey tau 1 convexity %.4f (0.94)\n", conv);
    assert_true(fabs(conv - 0.94) <= 0.01);
    acd_polygon_set_free(&monkey);
    acd_polygon_set_free(&heron);
    acd_polygon_set_free(&monkey2);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_dissertation_numbers),
                                       cmocka_unit_test(test_reference_sweep)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
