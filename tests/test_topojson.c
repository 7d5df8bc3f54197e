/* Tests of the TopoJSON reader (geom2/topojson) and of feature selection (GeoJSON too):
 * hand-made topologies with known coordinates and areas (shared and reversed arcs, quantized
 * delta-encoded arcs with a transform, holes, collections), errors naming the problem, and the
 * real npm world-atlas files when scripts/fetch-data.sh has put them in data/2d/world-atlas
 * (counts checked against an independent Python decoding; shared borders give identical rings). */
#include "testutil.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "acd/polygon.h"

static acd_status parse_sel(acd_polygon_set *s, const char *text, acd_polygon_format fmt, const char *object,
                            const char *feature, acd_error *err) {
    acd_polygon_read_options o;
    memset(&o, 0, sizeof o);
    o.format = fmt;
    o.object = object;
    o.feature = feature;
    return acd_polygon_set_parse_opts(s, text, SIZE_MAX, &o, "t.topojson", NULL, err);
}

static acd_status parse(acd_polygon_set *s, const char *text, acd_error *err) {
    return parse_sel(s, text, ACD_POLY_FORMAT_AUTO, NULL, NULL, err);
}

/* Two unit squares sharing the edge x = 1 (arc 0), the right one using it reversed. */
static const char *TWO_SQUARES =
    "{\"type\":\"Topology\",\"objects\":{\"squares\":{\"type\":\"GeometryCollection\",\"geometries\":["
    "{\"type\":\"Polygon\",\"id\":\"A\",\"properties\":{\"name\":\"left\",\"rank\":1},\"arcs\":[[0,1]]},"
    "{\"type\":\"Polygon\",\"id\":7,\"properties\":{\"name\":\"right\",\"rank\":2},\"arcs\":[[2,-1]]},"
    "{\"type\":\"Point\",\"coordinates\":[5,5]},{\"type\":null}]}},"
    "\"arcs\":[[[1,0],[1,1]],[[1,1],[0,1],[0,0],[1,0]],[[1,0],[2,0],[2,1],[1,1]]]}";

static int has_point(const acd_polygon *p, double x, double y) {
    for (size_t i = 0; i < acd_polygon_num_points(p); i++)
        if (p->points[i].x == x && p->points[i].y == y) return 1;
    return 0;
}

static void test_shared_and_reversed_arcs(void **state) {
    (void)state;
    acd_polygon_set s;
    acd_error err;
    assert_int_equal(parse(&s, TWO_SQUARES, &err), ACD_OK);
    assert_int_equal(s.count, 2);
    for (size_t i = 0; i < 2; i++) {
        assert_int_equal(s.polygons[i].nrings, 1);
        /* the shared end points are kept once and the closing repeat dropped: 4 corners */
        assert_int_equal(acd_polygon_num_points(&s.polygons[i]), 4);
        assert_true(acd_polygon_area(&s.polygons[i]) == 1.0);
        assert_int_equal(acd_polygon_validate(&s.polygons[i], i, &err), ACD_OK);
    }
    assert_true(has_point(&s.polygons[0], 0, 1) && !has_point(&s.polygons[0], 2, 0));
    assert_true(has_point(&s.polygons[1], 2, 1) && has_point(&s.polygons[1], 1, 1) && has_point(&s.polygons[1], 1, 0));
    acd_polygon_set_free(&s);
    /* forcing the format gives the same; GeoJSON forced still recognizes a Topology */
    assert_int_equal(parse_sel(&s, TWO_SQUARES, ACD_POLY_FORMAT_TOPOJSON, NULL, NULL, &err), ACD_OK);
    assert_int_equal(s.count, 2);
    acd_polygon_set_free(&s);
    assert_int_equal(parse_sel(&s, TWO_SQUARES, ACD_POLY_FORMAT_GEOJSON, NULL, NULL, &err), ACD_OK);
    assert_int_equal(s.count, 2);
    acd_polygon_set_free(&s);
}

/* A quantized square with a square hole: q in 0..4 mapped by x = 0.5 q + 10, y = 2 q + 20. */
static const char *QUANTIZED =
    "{\"type\":\"Topology\",\"transform\":{\"scale\":[0.5,2],\"translate\":[10,20]},"
    "\"objects\":{\"lake\":{\"type\":\"MultiPolygon\",\"properties\":{\"name\":\"Lake\"},"
    "\"arcs\":[[[0],[1]],[[2]]]}},"
    "\"arcs\":[[[0,0],[4,0],[0,4],[-4,0],[0,-4]],[[1,1],[0,2],[2,0],[0,-2],[-2,0]],"
    "[[10,10],[1,0],[0,1],[-1,0],[0,-1]]]}";

static void test_quantized_with_hole(void **state) {
    (void)state;
    acd_polygon_set s;
    acd_error err;
    assert_int_equal(parse(&s, QUANTIZED, &err), ACD_OK);
    assert_int_equal(s.count, 2);
    const acd_polygon *p = &s.polygons[0];
    assert_int_equal(p->nrings, 2);
    assert_int_equal(acd_polygon_num_points(p), 8);
    /* outer 2 x 8 = 16 minus the hole 1 x 4 */
    assert_true(acd_polygon_area(p) == 12.0);
    assert_true(has_point(p, 12, 28) && has_point(p, 10, 20) && has_point(p, 10.5, 22) && has_point(p, 11.5, 26));
    assert_int_equal(acd_polygon_validate(p, 0, &err), ACD_OK);
    /* the second polygon: a unit square at q = (10, 10): x 15..15.5, y 40..42 */
    assert_true(acd_polygon_area(&s.polygons[1]) == 1.0);
    assert_true(has_point(&s.polygons[1], 15, 40) && has_point(&s.polygons[1], 15.5, 42));
    acd_polygon_set_free(&s);
}

static void test_selection(void **state) {
    (void)state;
    acd_polygon_set s;
    acd_error err;
    const struct {
        const char *object, *feature;
        size_t count;
        double x; /* a vertex x only the selected polygon has (NAN: not checked) */
    } cases[] = {
        {NULL, "left", 1, 0},     {NULL, "right", 1, 2},      {NULL, "A", 1, 0},     {NULL, "7", 1, 2},
        {NULL, "id=7", 1, 2},     {NULL, "name=left", 1, 0},  {NULL, "rank=2", 1, 2}, {NULL, "2", 1, 2},
        {"squares", NULL, 2, NAN}, {"squares", "right", 1, 2},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        acd_status st = parse_sel(&s, TWO_SQUARES, ACD_POLY_FORMAT_AUTO, cases[k].object, cases[k].feature, &err);
        if (st != ACD_OK) fail_msg("case %zu: %s", k, err.message);
        assert_int_equal(s.count, cases[k].count);
        if (!isnan(cases[k].x)) assert_true(has_point(&s.polygons[0], cases[k].x, 0.0));
        acd_polygon_set_free(&s);
    }
    /* a collection selected by its own property keeps all its members */
    assert_int_equal(parse_sel(&s, QUANTIZED, ACD_POLY_FORMAT_AUTO, NULL, "Lake", &err), ACD_OK);
    assert_int_equal(s.count, 2);
    acd_polygon_set_free(&s);
    /* GeoJSON Features are selected the same way */
    const char *fc = "{\"type\":\"FeatureCollection\",\"features\":["
                     "{\"type\":\"Feature\",\"id\":1,\"properties\":{\"name\":\"a\"},\"geometry\":"
                     "{\"type\":\"Polygon\",\"coordinates\":[[[0,0],[1,0],[0,1]]]}},"
                     "{\"type\":\"Feature\",\"id\":2,\"properties\":{\"name\":\"b\"},\"geometry\":"
                     "{\"type\":\"Polygon\",\"coordinates\":[[[5,0],[6,0],[5,1]]]}}]}";
    assert_int_equal(parse_sel(&s, fc, ACD_POLY_FORMAT_AUTO, NULL, "b", &err), ACD_OK);
    assert_int_equal(s.count, 1);
    assert_true(has_point(&s.polygons[0], 6, 0));
    acd_polygon_set_free(&s);
    assert_int_equal(parse_sel(&s, fc, ACD_POLY_FORMAT_AUTO, NULL, "id=1", &err), ACD_OK);
    assert_int_equal(s.count, 1);
    assert_true(has_point(&s.polygons[0], 1, 0));
    acd_polygon_set_free(&s);
    assert_int_equal(parse_sel(&s, fc, ACD_POLY_FORMAT_AUTO, NULL, "c", &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "no Feature matches the selector 'c' (2 Features looked at"));
    assert_int_equal(parse_sel(&s, fc, ACD_POLY_FORMAT_AUTO, "countries", NULL, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err.message, "this file is GeoJSON"));
    /* .poly and WKT have no features */
    assert_int_equal(parse_sel(&s, "POLYGON ((0 0, 1 0, 0 1))", ACD_POLY_FORMAT_AUTO, NULL, "x", &err),
                     ACD_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err.message, "not to WKT"));
}

static void test_errors(void **state) {
    (void)state;
    const struct {
        const char *text, *object, *feature;
        acd_status st;
        const char *needle;
    } bad[] = {
        {"{\"type\":\"Topology\",\"objects\":{\"o\":{\"type\":\"Polygon\",\"arcs\":[[0,3]]}},"
         "\"arcs\":[[[0,0],[1,0],[0,1],[0,0]]]}",
         NULL, NULL, ACD_ERR_PARSE, "objects.o.arcs[0][1]: arc index 3 out of range (the topology has 1 arcs"},
        {"{\"type\":\"Topology\",\"objects\":{\"o\":{\"type\":\"Polygon\",\"arcs\":[[-2]]}},"
         "\"arcs\":[[[0,0],[1,0],[0,1],[0,0]]]}",
         NULL, NULL, ACD_ERR_PARSE, "objects.o.arcs[0][0]: arc index -2 out of range"},
        {"{\"type\":\"Topology\",\"objects\":{\"o\":{\"type\":\"Polygon\",\"arcs\":[[0.5]]}},\"arcs\":[[[0,0]]]}",
         NULL, NULL, ACD_ERR_PARSE, "objects.o.arcs[0][0]: expected an arc index (an integer"},
        {"{\"type\":\"Topology\",\"transform\":{\"translate\":[0,0]},\"objects\":{},\"arcs\":[]}", NULL, NULL,
         ACD_ERR_PARSE, "transform.scale: missing (a transform needs a scale)"},
        {"{\"type\":\"Topology\",\"transform\":{\"scale\":[1,1],\"translate\":[0]},\"objects\":{},\"arcs\":[]}",
         NULL, NULL, ACD_ERR_PARSE, "transform.translate: expected [tx, ty]"},
        {"{\"type\":\"Topology\",\"objects\":{}}", NULL, NULL, ACD_ERR_PARSE, "missing \"arcs\""},
        {"{\"type\":\"Topology\",\"arcs\":[]}", NULL, NULL, ACD_ERR_PARSE, "objects: missing"},
        {"{\"type\":\"Topology\",\"objects\":{},\"arcs\":[[[0,0],[1]]]}", NULL, NULL, ACD_ERR_PARSE,
         "arcs[0][1]: expected a position [x, y]"},
        {"{\"type\":\"Topology\",\"objects\":{},\"arcs\":[[]]}", NULL, NULL, ACD_ERR_PARSE,
         "arcs[0]: expected an arc (a non-empty array"},
        {"{\"type\":\"Topology\",\"objects\":{\"o\":{\"type\":\"Polygon\"}},\"arcs\":[]}", NULL, NULL,
         ACD_ERR_PARSE, "objects.o: missing \"arcs\""},
        {"{\"type\":\"Topology\",\"objects\":{\"o\":{\"type\":\"Polygon\",\"arcs\":[[]]}},\"arcs\":[]}", NULL, NULL,
         ACD_ERR_PARSE, "objects.o.arcs[0]: expected a ring"},
        {"{\"type\":\"Topology\",\"objects\":{\"o\":{\"type\":\"Circle\",\"arcs\":[]}},\"arcs\":[]}", NULL, NULL,
         ACD_ERR_PARSE, "unknown TopoJSON geometry type \"Circle\""},
        {"{\"type\":\"Topology\",\"objects\":{\"o\":{\"type\":\"GeometryCollection\",\"geometries\":[7]}},"
         "\"arcs\":[]}",
         NULL, NULL, ACD_ERR_PARSE, "objects.o.geometries[0]: expected a TopoJSON geometry object"},
        {"{\"type\":\"Topology\",\"objects\":{\"land\":{\"type\":null}},\"arcs\":[]}", NULL, NULL,
         ACD_ERR_DEGENERATE, "contains no polygon"},
        {"{\"type\":\"Topology\",\"objects\":{\"land\":{\"type\":null},\"sea\":{\"type\":null}},\"arcs\":[]}",
         "countries", NULL, ACD_ERR_INVALID_INPUT, "no object named 'countries' in objects (it has 'land', 'sea')"},
        {"{\"type\":\"Topology\",\"objects\":{\"o\":{\"type\":\"Polygon\",\"properties\":{\"name\":\"x\"},"
         "\"arcs\":[[0]]}},\"arcs\":[[[0,0],[1,0],[0,1],[0,0]]]}",
         NULL, "y", ACD_ERR_INVALID_INPUT, "no geometry matches the selector 'y' (1 geometries looked at"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        acd_polygon_set s;
        acd_error err;
        memset(&err, 0, sizeof err);
        acd_status st = parse_sel(&s, bad[k].text, ACD_POLY_FORMAT_AUTO, bad[k].object, bad[k].feature, &err);
        if (st != bad[k].st || !strstr(err.message, bad[k].needle))
            fail_msg("case %zu: got %d '%s', expected %d '%s'", k, (int)st, st == ACD_OK ? "" : err.message,
                     (int)bad[k].st, bad[k].needle);
        assert_null(s.polygons);
    }
    /* GeoJSON text with the TopoJSON format forced */
    acd_polygon_set s;
    acd_error err;
    assert_int_equal(parse_sel(&s, "{\"type\":\"Polygon\",\"coordinates\":[[[0,0],[1,0],[0,1]]]}",
                               ACD_POLY_FORMAT_TOPOJSON, NULL, NULL, &err),
                     ACD_ERR_PARSE);
    assert_non_null(strstr(err.message, "not TopoJSON"));
}

/* A ring's arc references copy the arcs: a 64 KB file (one arc of 2,700 positions referenced
 * 24,000 times) expanded to 65 million points and over 2 GB (fuzzrun3). Refused beyond 16 times
 * the arcs' positions (at least 65,536); a ring using its arc a few times is still read. */
static char *topology_with_refs(size_t npos, size_t nrefs) {
    char *text = malloc(64 + 12 * npos + 12 * nrefs + 64);
    assert_non_null(text);
    size_t len = (size_t)sprintf(text, "{\"type\":\"Topology\",\"objects\":{\"o\":{\"type\":\"Polygon\",\"arcs\":[[");
    for (size_t r = 0; r < nrefs; r++) len += (size_t)sprintf(text + len, r ? ",0" : "0");
    len += (size_t)sprintf(text + len, "]]}},\"arcs\":[[");
    for (size_t p = 0; p < npos; p++) len += (size_t)sprintf(text + len, "%s[%zu,%zu]", p ? "," : "", p % 7, (p * 3) % 11);
    sprintf(text + len, "]]}");
    return text;
}

static void test_expansion_refused(void **state) {
    (void)state;
    acd_polygon_set s;
    acd_error err;
    char *text = topology_with_refs(2700, 24000);
    assert_int_equal(parse(&s, text, &err), ACD_ERR_INVALID_INPUT);
    if (!strstr(err.message, "objects.o.arcs[0][24]: the rings' arc references expand to more than 65536 positions"))
        fail_msg("message '%s'", err.message);
    free(text);
    text = topology_with_refs(5000, 16); /* 80,000 positions: 16 times the arc's, the limit */
    assert_int_equal(parse(&s, text, &err), ACD_OK);
    assert_int_equal(s.count, 1);
    acd_polygon_set_free(&s);
    free(text);
    text = topology_with_refs(5000, 17);
    assert_int_equal(parse(&s, text, &err), ACD_ERR_INVALID_INPUT);
    free(text);
}

/* ---- the real npm world-atlas files ---- */

static const char *atlas(char *buf, size_t size, const char *file) {
    snprintf(buf, size, "%s/data/2d/world-atlas/%s", ACD_SOURCE_DIR, file);
    return access(buf, R_OK) == 0 ? buf : NULL;
}

static acd_status read_sel(acd_polygon_set *s, const char *path, const char *object, const char *feature,
                           acd_error *err) {
    acd_polygon_read_options o;
    memset(&o, 0, sizeof o);
    o.object = object;
    o.feature = feature;
    return acd_polygon_set_read_file_opts(s, path, &o, NULL, err);
}

/* Counts from an independent decoding (Python, the world-atlas 2.0.2 files): polygons, rings and
 * vertices after dropping consecutive repeats and closing repeats. */
static void test_world_atlas_counts(void **state) {
    (void)state;
    const struct {
        const char *file;
        size_t polygons, rings, points;
    } files[] = {
        {"countries-110m.json", 409, 411, 15301},
        {"countries-50m.json", 3043, 3058, 157316},
        {"land-110m.json", 125, 126, 4997},
    };
    char buf[1024];
    size_t done = 0;
    for (size_t k = 0; k < sizeof files / sizeof files[0]; k++) {
        const char *path = atlas(buf, sizeof buf, files[k].file);
        if (!path) continue;
        acd_polygon_set s;
        acd_error err;
        if (acd_polygon_set_read_file(&s, path, ACD_POLY_FORMAT_AUTO, NULL, &err) != ACD_OK)
            fail_msg("%s: %s", files[k].file, err.message);
        size_t rings = 0, points = 0;
        for (size_t i = 0; i < s.count; i++) {
            rings += s.polygons[i].nrings;
            points += acd_polygon_num_points(&s.polygons[i]);
        }
        assert_int_equal(s.count, files[k].polygons);
        assert_int_equal(rings, files[k].rings);
        assert_int_equal(points, files[k].points);
        acd_polygon_set_free(&s);
        done++;
    }
    if (!done) TU_SKIP("data/2d/world-atlas not fetched (scripts/fetch-data.sh)");
}

/* A country with an enclave: its hole is exactly the enclave's outer ring (shared arcs), and both
 * validate. 110m: South Africa / Lesotho; 50m also Italy (San Marino, Vatican). */
static void check_enclave(const char *path, const char *country, const char *enclave) {
    acd_polygon_set s, e;
    acd_error err;
    if (read_sel(&s, path, "countries", country, &err) != ACD_OK) fail_msg("%s: %s", country, err.message);
    if (read_sel(&e, path, "countries", enclave, &err) != ACD_OK) fail_msg("%s: %s", enclave, err.message);
    assert_int_equal(e.count, 1);
    const acd_polygon *hole_owner = NULL;
    size_t hole = 0;
    for (size_t i = 0; i < s.count && !hole_owner; i++)
        for (size_t r = 1; r < s.polygons[i].nrings; r++) {
            const acd_polygon *p = &s.polygons[i];
            if (acd_polygon_ring_size(p, r) != acd_polygon_num_points(&e.polygons[0])) continue;
            /* same points as a set: every enclave vertex is on this ring */
            size_t found = 0;
            for (size_t a = 0; a < acd_polygon_ring_size(p, r); a++)
                found += has_point(&e.polygons[0], acd_polygon_ring(p, r)[a].x, acd_polygon_ring(p, r)[a].y);
            if (found == acd_polygon_ring_size(p, r)) {
                hole_owner = p;
                hole = r;
                break;
            }
        }
    if (!hole_owner) fail_msg("%s: no hole equal to %s's outline", country, enclave);
    /* the hole's area (clockwise, negative) is minus the enclave's */
    double ha = 0, mag = 0; /* mag bounds the rounding of the shoelace sums */
    const acd_vec2 *h = acd_polygon_ring(hole_owner, hole);
    size_t n = acd_polygon_ring_size(hole_owner, hole);
    for (size_t a = 0; a < n; a++) {
        ha += h[a].x * h[(a + 1) % n].y - h[(a + 1) % n].x * h[a].y;
        mag += fabs(h[a].x * h[(a + 1) % n].y) + fabs(h[(a + 1) % n].x * h[a].y);
    }
    double ea = acd_polygon_area(&e.polygons[0]);
    if (!(fabs(ha / 2 + ea) <= 1e-14 * mag)) fail_msg("%s: hole area %.17g, %s area %.17g", country, ha / 2, enclave, ea);
    assert_int_equal(acd_polygon_validate(hole_owner, 0, &err), ACD_OK);
    assert_int_equal(acd_polygon_validate(&e.polygons[0], 0, &err), ACD_OK);
    acd_polygon_set_free(&s);
    acd_polygon_set_free(&e);
}

static void test_world_atlas_enclaves(void **state) {
    (void)state;
    char buf[1024];
    const char *p110 = atlas(buf, sizeof buf, "countries-110m.json");
    if (!p110) TU_SKIP("data/2d/world-atlas not fetched (scripts/fetch-data.sh)");
    check_enclave(p110, "South Africa", "Lesotho");
    char buf2[1024];
    const char *p50 = atlas(buf2, sizeof buf2, "countries-50m.json");
    if (p50) {
        check_enclave(p50, "South Africa", "Lesotho");
        check_enclave(p50, "name=Italy", "San Marino");
        check_enclave(p50, "name=Italy", "Vatican");
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shared_and_reversed_arcs), cmocka_unit_test(test_quantized_with_hole),
        cmocka_unit_test(test_selection),                cmocka_unit_test(test_errors),
        cmocka_unit_test(test_expansion_refused),        cmocka_unit_test(test_world_atlas_counts),       cmocka_unit_test(test_world_atlas_enclaves),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
