/* Tests of the GeoJSON reader (geom2/geojson) and writer: every container type, skipped
 * geometries, errors with JSON paths, and exact round trips. */
#include "testutil.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "acd/polygon.h"

static acd_status parse(acd_polygon_set *s, const char *text, acd_error *err) {
    return acd_polygon_set_parse(s, text, SIZE_MAX, ACD_POLY_FORMAT_AUTO, "t.json", NULL, err);
}

static const char *SQUARE = "[[0,0],[10,0],[10,10],[0,10],[0,0]]";
static const char *HOLE = "[[2,2],[2,4],[4,4],[4,2],[2,2]]";

static void test_containers(void **state) {
    (void)state;
    char text[2048];
    acd_polygon_set s;
    acd_error err;
    /* bare Polygon with a hole */
    snprintf(text, sizeof text, "{\"type\":\"Polygon\",\"coordinates\":[%s,%s]}", SQUARE, HOLE);
    assert_int_equal(parse(&s, text, &err), ACD_OK);
    assert_int_equal(s.count, 1);
    assert_int_equal(s.polygons[0].nrings, 2);
    assert_int_equal(acd_polygon_num_points(&s.polygons[0]), 8); /* closing repeats dropped */
    assert_true(acd_polygon_area(&s.polygons[0]) == 96.0);
    assert_int_equal(acd_polygon_validate(&s.polygons[0], 0, &err), ACD_OK);
    acd_polygon_set_free(&s);
    /* FeatureCollection with a MultiPolygon (island inside the hole is its own polygon), a null
     * geometry, a Point (skipped), and a GeometryCollection holding a Polygon */
    snprintf(text, sizeof text,
             "{\"type\":\"FeatureCollection\",\"features\":["
             "{\"type\":\"Feature\",\"properties\":{},\"geometry\":{\"type\":\"MultiPolygon\",\"coordinates\":"
             "[[%s,%s],[[[2.5,2.5],[3.5,2.5],[3,3.5]]]]}},"
             "{\"type\":\"Feature\",\"geometry\":null},"
             "{\"type\":\"Feature\",\"geometry\":{\"type\":\"Point\",\"coordinates\":[1,2]}},"
             "{\"type\":\"Feature\",\"geometry\":{\"type\":\"GeometryCollection\",\"geometries\":["
             "{\"type\":\"LineString\",\"coordinates\":[[0,0],[1,1]]},"
             "{\"type\":\"Polygon\",\"coordinates\":[[[20,0,5],[21,0,5],[21,1,5]]]}]}}]}",
             SQUARE, HOLE);
    assert_int_equal(parse(&s, text, &err), ACD_OK);
    assert_int_equal(s.count, 3);
    assert_int_equal(s.polygons[0].nrings, 2);
    assert_int_equal(s.polygons[1].nrings, 1);
    assert_true(s.polygons[1].points[0].x == 2.5);
    assert_true(s.polygons[2].points[1].x == 21 && s.polygons[2].points[1].y == 0); /* altitude dropped */
    for (size_t i = 0; i < s.count; i++) assert_int_equal(acd_polygon_validate(&s.polygons[i], i, &err), ACD_OK);
    acd_polygon_set_free(&s);
    /* clockwise outer is reversed by normalization */
    assert_int_equal(parse(&s, "{\"type\":\"Polygon\",\"coordinates\":[[[0,0],[0,1],[1,1],[1,0]]]}", &err), ACD_OK);
    assert_true(acd_polygon_area(&s.polygons[0]) == 1.0);
    acd_polygon_set_free(&s);
}

static void test_errors(void **state) {
    (void)state;
    static const struct {
        const char *text;
        acd_status st;
        const char *needle;
    } bad[] = {
        {"{\"type\":\"Polygon\",\"coordinates\":[[[0,0],[1,0],[1,1]]]", ACD_ERR_PARSE, "t.json:1:"},
        {"{\"type\":\"Polygon\",\"coordinates\":[[[0,0],[1,0],[1,\"a\"]]]}", ACD_ERR_PARSE, "coordinates[0][2]"},
        {"{\"type\":\"Polygon\",\"coordinates\":[[[0,0],[1,0],[1]]]}", ACD_ERR_PARSE, "coordinates[0][2]"},
        {"{\"type\":\"Polygon\",\"coordinates\":[[[0,0],[1,0],[1e999,1]]]}", ACD_ERR_PARSE, "out of the range"},
        {"{\"type\":\"Polygon\",\"coordinates\":[[]]}", ACD_ERR_PARSE, "coordinates[0]"},
        {"{\"type\":\"Polygon\"}", ACD_ERR_PARSE, "missing \"coordinates\""},
        {"{\"type\":\"Polygon\",\"coordinates\":[]}", ACD_ERR_DEGENERATE, "no polygon"},
        {"{\"type\":\"Point\",\"coordinates\":[1,2]}", ACD_ERR_DEGENERATE, "no polygon"},
        {"{\"type\":\"Circle\"}", ACD_ERR_PARSE, "unknown GeoJSON type"},
        {"{\"coordinates\":[]}", ACD_ERR_PARSE, "\"type\""},
        {"{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"geometry\":{\"type\":\"Polygon\","
         "\"coordinates\":[[[0,0],[1,0],null]]}}]}",
         ACD_ERR_PARSE, "features[0].geometry.coordinates[0][2]"},
        {"{\"type\":\"FeatureCollection\",\"features\":{}}", ACD_ERR_PARSE, "features: expected an array"},
        {"{\"type\":\"Polygon\",\"coordinates\":[[[0,0],[1,0],[0,1]]]} x", ACD_ERR_PARSE, "after the JSON value"},
        {"[1]", ACD_ERR_PARSE, "expected a GeoJSON object"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        acd_polygon_set s;
        acd_error err;
        acd_status st = parse(&s, bad[k].text, &err);
        if (st != bad[k].st || !strstr(err.message, bad[k].needle))
            fail_msg("case %zu: status %d, message '%s' (wanted %d, '%s')", k, (int)st,
                     st == ACD_OK ? "" : err.message, (int)bad[k].st, bad[k].needle);
        assert_null(s.polygons);
    }
    /* deep nesting is refused, not a stack overflow */
    size_t depth = 200;
    char *deep = malloc(depth * 64 + 64);
    assert_non_null(deep);
    char *w = deep;
    for (size_t i = 0; i < depth; i++) w += sprintf(w, "{\"type\":\"GeometryCollection\",\"geometries\":[");
    for (size_t i = 0; i < depth; i++) w += sprintf(w, "]}");
    acd_polygon_set s;
    acd_error err;
    assert_int_equal(parse(&s, deep, &err), ACD_ERR_PARSE);
    free(deep);
}

static void test_round_trip(void **state) {
    (void)state;
    char text[1024];
    snprintf(text, sizeof text,
             "{\"type\":\"MultiPolygon\",\"coordinates\":[[%s,%s],[[[20,0],[21.1,0.1],[20.3333333333333333,1]]]]}",
             SQUARE, HOLE);
    acd_polygon_set s, t, u;
    acd_error err;
    assert_int_equal(parse(&s, text, &err), ACD_OK);
    /* irrational-looking coordinates survive exactly */
    s.polygons[1].points[2].x = 0.1 + 0.2;
    s.polygons[1].points[2].y = 1.0 / 3.0;
    for (int multi = 0; multi < 2; multi++) {
        char *out;
        size_t len;
        assert_int_equal(acd_polygon_set_to_geojson_text(&s, multi, &out, &len, &err), ACD_OK);
        assert_int_equal(strlen(out), len);
        assert_int_equal(acd_polygon_set_parse(&t, out, len, ACD_POLY_FORMAT_AUTO, "rt", NULL, &err), ACD_OK);
        assert_int_equal(t.count, s.count);
        for (size_t i = 0; i < s.count; i++) {
            assert_int_equal(t.polygons[i].nrings, s.polygons[i].nrings);
            assert_int_equal(acd_polygon_num_points(&t.polygons[i]), acd_polygon_num_points(&s.polygons[i]));
            assert_memory_equal(t.polygons[i].points, s.polygons[i].points,
                                acd_polygon_num_points(&s.polygons[i]) * sizeof(acd_vec2));
        }
        acd_polygon_set_free(&t);
        free(out);
    }
    /* through a file, and via .poly */
    char path[] = "/tmp/acd_test_geojson_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    assert_int_equal(acd_polygon_set_write_geojson(&s, path, &err), ACD_OK);
    assert_int_equal(acd_polygon_set_read_file(&u, path, ACD_POLY_FORMAT_GEOJSON, NULL, &err), ACD_OK);
    assert_int_equal(u.count, 2);
    assert_memory_equal(u.polygons[1].points, s.polygons[1].points, 3 * sizeof(acd_vec2));
    acd_polygon_set_free(&u);
    remove(path);
    acd_polygon_set_free(&s);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_containers),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_round_trip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
