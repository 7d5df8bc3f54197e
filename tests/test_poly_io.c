/* Tests of the .poly reader (geom2/poly_io) and of the 2D reading entry points: Lien's data
 * files, run-together numbers, permutations, every malformed-input error, round trips. */
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "acd/polygon.h"

static const char *const LIEN_FILES[] = {
    "BarbedThing", "batlogo", "bird", "dragon", "dsb", "egg", "hole1", "hole2", "hole3", "hole4", "hole5",
    "nazca_nazca_heron", "nazca_nazca_heron_oldversion", "nazca_nazca_heron_original", "nazca_nazca_monkey",
    "nazca_nazca_monkey1.5", "nazca_nazca_monkey_2", "nazca_nazca_monkey_oldversion",
    "nazca_nazca_monkey_original", "nazca_nazca_monkey_original_2", "nazca_nazca_nosize_monkey1.5", "simple1",
    "simple2", "simple3", "simple4", "simple5", "simple7", "simple8", "star_star1", "star_star2",
    "star_star2_noise", "star_star3", "star_star3_noise", "star_star4", "star_star4_noise", "star_star5",
    "star_star5_noise", "star_star6", "taiwan", "texas", "torus1", "torus2", "wierd1", "wierd2", "wierd2_n"};

static int read_lien(acd_polygon_set *s, const char *stem, acd_error *err) {
    char rel[256], path[1024];
    snprintf(rel, sizeof rel, "polygons-lien/%s.poly", stem);
    if (!tu_shared_data(path, sizeof path, rel)) return -1;
    return (int)acd_polygon_set_read_file(s, path, ACD_POLY_FORMAT_AUTO, NULL, err);
}

static size_t total_points(const acd_polygon_set *s) {
    size_t n = 0;
    for (size_t i = 0; i < s->count; i++) n += acd_polygon_num_points(&s->polygons[i]);
    return n;
}

static void test_all_lien_files_parse(void **state) {
    (void)state;
    int found = 0;
    for (size_t f = 0; f < sizeof LIEN_FILES / sizeof *LIEN_FILES; f++) {
        acd_polygon_set s;
        acd_error err;
        int st = read_lien(&s, LIEN_FILES[f], &err);
        if (st < 0) continue;
        found++;
        if (st != ACD_OK) fail_msg("%s: %s", LIEN_FILES[f], err.message);
        assert_true(s.count >= 1);
        for (size_t i = 0; i < s.count; i++) {
            acd_status v = acd_polygon_validate(&s.polygons[i], i, &err);
            if (v != ACD_OK) print_message("[  INFO    ] %s does not validate: %s\n", LIEN_FILES[f], err.message);
            assert_true(acd_polygon_area(&s.polygons[i]) > 0);
        }
        acd_polygon_set_free(&s);
    }
    if (!found) TU_SKIP("polygons-lien data not found");
}

static void test_lien_counts(void **state) {
    (void)state;
    static const struct {
        const char *stem;
        size_t vertices, polygons, holes;
    } expect[] = {{"nazca_nazca_monkey", 1204, 1, 0}, {"nazca_nazca_monkey_2", 9632, 1, 0},
                  {"nazca_nazca_heron", 1037, 1, 0},  {"wierd2_n", 800, 1, 0},
                  {"texas", 139, 1, 0},               {"bird", 275, 1, 0},
                  {"hole1", 10, 1, 1},                {"hole2", 0, 1, 2},
                  {"hole3", 0, 1, 3},                 {"torus1", 0, 1, 1},
                  {"simple5", 376, 1, 0}};
    int found = 0;
    for (size_t k = 0; k < sizeof expect / sizeof *expect; k++) {
        acd_polygon_set s;
        acd_error err;
        int st = read_lien(&s, expect[k].stem, &err);
        if (st < 0) continue;
        found++;
        if (st != ACD_OK) fail_msg("%s: %s", expect[k].stem, err.message);
        assert_int_equal(s.count, expect[k].polygons);
        if (expect[k].vertices) assert_int_equal(total_points(&s), expect[k].vertices);
        assert_int_equal(s.polygons[0].nrings, expect[k].holes + 1);
        assert_int_equal(acd_polygon_validate(&s.polygons[0], 0, &err), ACD_OK);
        acd_polygon_set_free(&s);
    }
    if (!found) TU_SKIP("polygons-lien data not found");
}

/* bird.poly has run-together numbers: "-6.64248.788605" is (-6.64248, .788605). */
static void test_bird_run_together(void **state) {
    (void)state;
    acd_polygon_set s;
    acd_error err;
    int st = read_lien(&s, "bird", &err);
    if (st < 0) TU_SKIP("bird.poly not found");
    assert_int_equal(st, ACD_OK);
    const acd_polygon *p = &s.polygons[0];
    int seen1 = 0, seen2 = 0, seen3 = 0;
    for (size_t i = 0; i < acd_polygon_num_points(p); i++) {
        acd_vec2 v = p->points[i];
        assert_true(fabs(v.x) < 20 && fabs(v.y) < 20);
        if (v.x == -6.64248 && v.y == .788605) seen1 = 1;
        if (v.x == -6.36951 && v.y == .242648) seen2 = 1;
        if (v.x == 7.84688 && v.y == .042924) seen3 = 1;
    }
    assert_true(seen1 && seen2 && seen3);
    acd_polygon_set_free(&s);
}

static acd_status parse(acd_polygon_set *s, const char *text, acd_polygon_fixes *fx, acd_error *err) {
    return acd_polygon_set_parse(s, text, strlen(text), ACD_POLY_FORMAT_AUTO, "t.poly", fx, err);
}

/* The vertex order line is applied; comments go anywhere; in = hole of the last out;
 * each out starts a polygon; the outer ring comes out CCW and holes CW. */
static void test_permutation_and_structure(void **state) {
    (void)state;
    const char *text = "# leading comment\n"
                       "3 # chains\n"
                       "4 out\n"
                       "0 0\n 0 10 # comment after a point\n10 10\n10 0\n"
                       "1 4 3 2\n"
                       "3 in\n2 2\n3 2\n2 3\n"
                       "3 2 1\n"
                       "3 out\n20 0 21 0\n20 1\n1 2 3\n";
    acd_polygon_set s;
    acd_error err;
    acd_polygon_fixes fx = {0};
    assert_int_equal(parse(&s, text, &fx, &err), ACD_OK);
    assert_int_equal(s.count, 2);
    const acd_polygon *p = &s.polygons[0];
    assert_int_equal(p->nrings, 2);
    /* order 1 4 3 2 = (0,0) (10,0) (10,10) (0,10): counterclockwise, kept */
    assert_true(p->points[1].x == 10 && p->points[1].y == 0);
    assert_true(p->points[2].x == 10 && p->points[2].y == 10);
    /* hole in order 3 2 1 = (2,3) (3,2) (2,2): clockwise, kept */
    const acd_vec2 *h = acd_polygon_ring(p, 1);
    assert_true(h[0].x == 2 && h[0].y == 3 && h[1].x == 3 && h[2].y == 2);
    assert_true(acd_polygon_area(p) == 100.0 - 0.5);
    assert_int_equal(fx.rings_reversed, 0);
    assert_int_equal(acd_polygon_validate(p, 0, &err), ACD_OK);
    assert_int_equal(acd_polygon_validate(&s.polygons[1], 1, &err), ACD_OK);
    acd_polygon_set_free(&s);
}

static void test_normalize_fixes(void **state) {
    (void)state;
    /* clockwise outer with a repeated vertex and a closing repeat */
    const char *text = "1\n6 out\n0 0\n0 1\n0 1\n1 1\n1 0\n0 0\n1 2 3 4 5 6\n";
    acd_polygon_set s;
    acd_error err;
    acd_polygon_fixes fx = {0};
    assert_int_equal(parse(&s, text, &fx, &err), ACD_OK);
    assert_int_equal(fx.repeated_dropped, 2);
    assert_int_equal(fx.rings_reversed, 1);
    assert_int_equal(acd_polygon_num_points(&s.polygons[0]), 4);
    assert_true(acd_polygon_area(&s.polygons[0]) == 1.0);
    assert_int_equal(acd_polygon_validate(&s.polygons[0], 0, &err), ACD_OK);
    acd_polygon_set_free(&s);
}

static void test_extra_chains_ignored(void **state) {
    (void)state;
    const char *text = "1\n3 out\n0 0 1 0 0 1\n1 2 3\n3 in\n0.1 0.1 0.2 0.1 0.1 0.2\n1 2 3\n";
    acd_polygon_set s;
    acd_error err;
    acd_polygon_fixes fx = {0};
    assert_int_equal(parse(&s, text, &fx, &err), ACD_OK);
    assert_int_equal(s.count, 1);
    assert_int_equal(s.polygons[0].nrings, 1);
    assert_int_equal(fx.chains_ignored, 1);
    acd_polygon_set_free(&s);
}

/* Every malformed input gives ACD_ERR_PARSE and a message naming the line and what was
 * expected. */
static void test_bad_inputs(void **state) {
    (void)state;
    static const struct {
        const char *text;
        const char *needle1, *needle2;
    } bad[] = {
        {"", "cannot tell the format", "empty"},
        {"@", "cannot tell the format", ""},
        {"0\n", "t.poly:1:", "0 chains"},
        {"-1\n", "t.poly:1:", "number of chains"},
        {"2\n3 out\n0 0 1 0 0 1\n1 2 3\n", "t.poly:5:", "after 1 of the 2 declared chains"},
        {"1\n3 up\n0 0 1 0 0 1\n1 2 3\n", "t.poly:2:", "'out' or 'in'"},
        {"1\n3 in\n0 0 1 0 0 1\n1 2 3\n", "t.poly:2:", "no 'out' chain precedes"},
        {"1\n0 out\n", "t.poly:2:", "0 points"},
        {"1\n3 out\n0 0 1 0 0\n", "t.poly:4:", "point 3 of 3: expected the y coordinate"},
        {"1\n3 out\n0 0 1 0 0 1\n", "t.poly:4:", "entry 1 of 3"},
        {"1\n3 out\n0 0 1 0 0 1\n1 2\n", "t.poly:5:", "entry 3 of 3"},
        {"1\n3 out\n0 0 1 0 0 1\n1 2 4\n", "t.poly:4:", "entry 3 of 3 must be an integer in 1..3"},
        {"1\n3 out\n0 0 1 0 0 1\n1 2 2\n", "t.poly:4:", "repeats point 2"},
        {"1\n3 out\n0 0 1 0 0 1\n1 2 2.5\n", "t.poly:4:", "entry 3 of 3"},
        {"1\n3 out\n0 0 nan 0 0 1\n1 2 3\n", "t.poly:3:", "point 2 of 3: expected the x coordinate"},
        {"1\n3 out\n0 0 inf 0 0 1\n1 2 3\n", "t.poly:3:", "expected the x coordinate (a decimal number) (found 'inf"},
        {"1\n3 out\n0 0 1e999 0 0 1\n1 2 3\n", "t.poly:3:", "out of the range"},
        {"1\n3 out\n0 0 0x10 0 0 1\n1 2 3\n", "t.poly:3:", "point 2 of 3"},
        {"1\n3 out\n0 0 1 0 0 1\n1 2 3\ngarbage\n", "t.poly:5:", "chain 1"},
        {"1\n1000000000000 out\n0 0\n", "t.poly:2:", "declares 1000000000000 points but only"},
        {"99999999999999999999999999\n", "t.poly:1:", "number of chains"},
        {"1\n3 out\n0 0\n1 0\n0 1\n1 2 3 # ok\n2 in\n", "t.poly:7:", "chain 1"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        acd_polygon_set s;
        acd_error err;
        acd_status st = parse(&s, bad[k].text, NULL, &err);
        if (st == ACD_OK) fail_msg("case %zu parsed", k);
        assert_int_equal(st, ACD_ERR_PARSE);
        assert_int_equal(err.status, ACD_ERR_PARSE);
        if (!strstr(err.message, bad[k].needle1) || !strstr(err.message, bad[k].needle2))
            fail_msg("case %zu: message '%s' lacks '%s' / '%s'", k, err.message, bad[k].needle1, bad[k].needle2);
        assert_null(s.polygons);
        assert_int_equal(s.count, 0);
    }
}

static void test_read_file_errors(void **state) {
    (void)state;
    acd_polygon_set s;
    acd_error err;
    assert_int_equal(acd_polygon_set_read_file(&s, "/nonexistent/x.poly", ACD_POLY_FORMAT_AUTO, NULL, &err), ACD_ERR_IO);
    assert_non_null(strstr(err.message, "/nonexistent/x.poly"));
    /* the length bounds the text: a NUL-free buffer without terminator */
    char buf[] = {'1', '\n', '3', ' ', 'o', 'u', 't', '\n', '0', ' ', '0', ' ', '1', ' ', '0', ' ', '0', ' ', '1', '\n',
                  '1', ' ', '2', ' ', '3'};
    assert_int_equal(acd_polygon_set_parse(&s, buf, sizeof buf, ACD_POLY_FORMAT_POLY, NULL, NULL, &err), ACD_OK);
    assert_int_equal(acd_polygon_num_points(&s.polygons[0]), 3);
    acd_polygon_set_free(&s);
    assert_int_equal(acd_polygon_set_parse(&s, buf, sizeof buf - 1, ACD_POLY_FORMAT_POLY, NULL, NULL, &err),
                     ACD_ERR_PARSE);
    assert_non_null(strstr(err.message, "entry 3 of 3"));
    /* a NUL byte ends the text */
    const char nul[] = "1\n3 out\n0 0 1 0 0 1\n1 2 3\n\0garbage";
    assert_int_equal(acd_polygon_set_parse(&s, nul, sizeof nul, ACD_POLY_FORMAT_AUTO, NULL, NULL, &err), ACD_OK);
    acd_polygon_set_free(&s);
}

static void assert_same_set(const acd_polygon_set *a, const acd_polygon_set *b) {
    assert_int_equal(a->count, b->count);
    for (size_t i = 0; i < a->count; i++) {
        assert_int_equal(a->polygons[i].nrings, b->polygons[i].nrings);
        assert_memory_equal(a->polygons[i].ring_start, b->polygons[i].ring_start,
                            (a->polygons[i].nrings + 1) * sizeof(size_t));
        assert_memory_equal(a->polygons[i].points, b->polygons[i].points,
                            acd_polygon_num_points(&a->polygons[i]) * sizeof(acd_vec2));
    }
}

/* Writing .poly (and GeoJSON) and reading back gives the same doubles, on every data file with
 * holes and on the biggest one. */
static void test_round_trip(void **state) {
    (void)state;
    static const char *const stems[] = {"hole3", "hole5", "torus1", "bird", "nazca_nazca_monkey_2"};
    int found = 0;
    for (size_t k = 0; k < sizeof stems / sizeof *stems; k++) {
        acd_polygon_set s, t;
        acd_error err;
        int st = read_lien(&s, stems[k], &err);
        if (st < 0) continue;
        found++;
        assert_int_equal(st, ACD_OK);
        /* make coordinates that need all 17 digits */
        s.polygons[0].points[0].x += 1.0 / 3.0;
        char *text;
        size_t len;
        assert_int_equal(acd_polygon_set_to_poly_text(&s, &text, &len, &err), ACD_OK);
        acd_polygon_fixes fx = {0};
        assert_int_equal(acd_polygon_set_parse(&t, text, len, ACD_POLY_FORMAT_AUTO, "rt", &fx, &err), ACD_OK);
        assert_int_equal(fx.repeated_dropped + fx.rings_reversed + fx.chains_ignored, 0);
        assert_same_set(&s, &t);
        acd_polygon_set_free(&t);
        free(text);
        assert_int_equal(acd_polygon_set_to_geojson_text(&s, 0, &text, &len, &err), ACD_OK);
        assert_int_equal(acd_polygon_set_parse(&t, text, len, ACD_POLY_FORMAT_AUTO, "rt", NULL, &err), ACD_OK);
        assert_same_set(&s, &t);
        acd_polygon_set_free(&t);
        free(text);
        acd_polygon_set_free(&s);
    }
    if (!found) TU_SKIP("polygons-lien data not found");
    /* several polygons with holes, through a file */
    const char *text = "4\n4 out\n0 0 10 0 10 10 0 10\n1 2 3 4\n3 in\n2 2 2 3 3 2\n1 2 3\n"
                       "3 out\n20 0 21 0 20 1\n1 2 3\n3 in\n20.1 0.1 20.1 0.2 20.2 0.1\n1 2 3\n";
    acd_polygon_set s, t;
    acd_error err;
    assert_int_equal(acd_polygon_set_parse(&s, text, strlen(text), ACD_POLY_FORMAT_POLY, "x", NULL, &err), ACD_OK);
    char path[] = "/tmp/acd_test_poly_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    assert_int_equal(acd_polygon_set_write_poly(&s, path, &err), ACD_OK);
    assert_int_equal(acd_polygon_set_read_file(&t, path, ACD_POLY_FORMAT_AUTO, NULL, &err), ACD_OK);
    assert_same_set(&s, &t);
    remove(path);
    acd_polygon_set_free(&s);
    acd_polygon_set_free(&t);
    assert_int_equal(acd_polygon_set_write_poly(&s, "/nonexistent/dir/x.poly", &err), ACD_ERR_IO);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_all_lien_files_parse),
        cmocka_unit_test(test_lien_counts),
        cmocka_unit_test(test_bird_run_together),
        cmocka_unit_test(test_permutation_and_structure),
        cmocka_unit_test(test_normalize_fixes),
        cmocka_unit_test(test_extra_chains_ignored),
        cmocka_unit_test(test_bad_inputs),
        cmocka_unit_test(test_read_file_errors),
        cmocka_unit_test(test_round_trip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
