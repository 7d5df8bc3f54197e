/* Tests of the WKT reader (geom2/wkt): POLYGON, MULTIPOLYGON, GEOMETRYCOLLECTION, EMPTY,
 * Z/M/ZM tags, SRID prefix, several geometries, and errors with line numbers. */
#include "testutil.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "acd/polygon.h"

static acd_status parse(acd_polygon_set *s, const char *text, acd_error *err) {
    return acd_polygon_set_parse(s, text, SIZE_MAX, ACD_POLY_FORMAT_AUTO, "t.wkt", NULL, err);
}

static void test_polygons(void **state) {
    (void)state;
    acd_polygon_set s;
    acd_error err;
    assert_int_equal(parse(&s, "POLYGON ((0 0, 10 0, 10 10, 0 10, 0 0), (2 2, 2 4, 4 4, 4 2, 2 2))", &err), ACD_OK);
    assert_int_equal(s.count, 1);
    assert_int_equal(s.polygons[0].nrings, 2);
    assert_true(acd_polygon_area(&s.polygons[0]) == 96.0);
    assert_int_equal(acd_polygon_validate(&s.polygons[0], 0, &err), ACD_OK);
    acd_polygon_set_free(&s);

    assert_int_equal(parse(&s,
                           "SRID=4326;multipolygon(((0 0,1 0,1 1,0 0)),EMPTY,((5 5,6 5,6 6)))\n"
                           "POLYGON EMPTY;\n"
                           "GEOMETRYCOLLECTION (POINT (1 2), LINESTRING (0 0, 1 1), POLYGON Z ((0 0 1, 0 -1 1, -1 0 1)),"
                           " GEOMETRYCOLLECTION EMPTY)\n"
                           "POLYGONZM ((0 0 1 2, 2 0 1 2, 2 2 1 2))\n"
                           "POLYGON M ((0 0 7, 3 0 7, 3 3 7))\n"
                           "POLYGON ((0 0 9, 4 0 9, 4 4 9))\n"
                           "POLYGON ((1.5e1 -2.5E-1, +16 0, 15 1))",
                           &err),
                     ACD_OK);
    assert_int_equal(s.count, 7);
    assert_true(s.polygons[1].points[0].x == 5);
    assert_true(s.polygons[2].points[1].x == -1 && s.polygons[2].points[1].y == 0); /* reversed to CCW */
    assert_true(s.polygons[6].points[0].x == 15 && s.polygons[6].points[0].y == -0.25);
    for (size_t i = 0; i < s.count; i++) assert_int_equal(acd_polygon_validate(&s.polygons[i], i, &err), ACD_OK);
    acd_polygon_set_free(&s);
}

static void test_errors(void **state) {
    (void)state;
    static const struct {
        const char *text;
        acd_status st;
        const char *needle1, *needle2;
    } bad[] = {
        {"POLYGON ((0 0, 1 0, 1 1)", ACD_ERR_PARSE, "t.wkt:1:", "after a ring"},
        {"POLYGON ((0 0, 1 0, 1))", ACD_ERR_PARSE, "t.wkt:1:", "expected the y coordinate"},
        {"POLYGON\n((0 0, 1 0, nan 1))", ACD_ERR_PARSE, "t.wkt:2:", "expected a point"},
        {"POLYGON ((0 0, 1 0, 1e400 1))", ACD_ERR_PARSE, "t.wkt:1:", "out of the range"},
        {"POLYGON Z ((0 0, 1 0, 1 1))", ACD_ERR_PARSE, "2 coordinates here; expected 3", ""},
        {"POLYGON ((0 0 0 0, 1 0 0 0, 1 1 0 0))", ACD_ERR_PARSE, "4 coordinates", ""},
        {"POLYGON ZM ((0 0 1 2 3, 1 0 1 2 3, 1 1 1 2 3))", ACD_ERR_PARSE, "after a point", ""},
        {"POLYGONX ((0 0, 1 0, 1 1))", ACD_ERR_PARSE, "unknown WKT geometry type 'POLYGONX'", ""},
        {"POLYGON (0 0, 1 0, 1 1)", ACD_ERR_PARSE, "expected '(' to open a ring", ""},
        {"POLYGON ((0 0, 1 0, 1 1)) garbage", ACD_ERR_PARSE, "unknown WKT geometry type 'GARBAGE'", ""},
        {"POLYGON EMPTY", ACD_ERR_DEGENERATE, "no polygon", ""},
        {"POINT (1 2)", ACD_ERR_DEGENERATE, "no polygon", ""},
        {"LINESTRING (1 2", ACD_ERR_PARSE, "unbalanced", ""},
        {"MULTIPOLYGON ((0 0, 1 0, 1 1))", ACD_ERR_PARSE, "expected '(' to open a ring", ""},
        {"POLYGON ((0 0, 1 0, 1 1),)", ACD_ERR_PARSE, "expected '(' to open a ring", ""},
    };
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        acd_polygon_set s;
        acd_error err;
        acd_status st = parse(&s, bad[k].text, &err);
        if (st != bad[k].st || !strstr(err.message, bad[k].needle1) || !strstr(err.message, bad[k].needle2))
            fail_msg("case %zu: status %d, message '%s'", k, (int)st, st == ACD_OK ? "" : err.message);
        assert_null(s.polygons);
    }
    /* deep collections are refused */
    char deep[4096] = "";
    for (int i = 0; i < 100; i++) strcat(deep, "GEOMETRYCOLLECTION(");
    acd_polygon_set s;
    acd_error err;
    assert_int_equal(parse(&s, deep, &err), ACD_ERR_PARSE);
    assert_non_null(strstr(err.message, "too deep"));
}

/* WKT writer: exact round trip of one polygon (POLYGON) and of several (MULTIPOLYGON). */
static void test_round_trip(void **state) {
    (void)state;
    acd_polygon_set s, t;
    acd_error err;
    assert_int_equal(parse(&s, "MULTIPOLYGON (((0 0, 10 0, 10 10, 0 10, 0 0), (2 2, 2 4, 4 4, 4 2, 2 2)), "
                               "((20 0, 21 0, 20 1)))",
                           &err),
                     ACD_OK);
    s.polygons[1].points[1].x = 1.0 / 3.0 + 20;
    for (int single = 0; single < 2; single++) {
        acd_polygon_set one = {s.polygons, single ? 1 : s.count};
        char *text;
        size_t len;
        assert_int_equal(acd_polygon_set_to_wkt_text(&one, &text, &len, &err), ACD_OK);
        assert_non_null(strstr(text, single ? "POLYGON ((" : "MULTIPOLYGON ((("));
        assert_int_equal(parse(&t, text, &err), ACD_OK);
        assert_int_equal(t.count, one.count);
        for (size_t i = 0; i < t.count; i++) {
            assert_int_equal(t.polygons[i].nrings, one.polygons[i].nrings);
            assert_memory_equal(t.polygons[i].points, one.polygons[i].points,
                                acd_polygon_num_points(&one.polygons[i]) * sizeof(acd_vec2));
        }
        acd_polygon_set_free(&t);
        free(text);
    }
    acd_polygon_set_free(&s);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_polygons),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_round_trip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
