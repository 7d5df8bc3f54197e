/* Tests of export/json2d and export/svg2d on a hand-made decomposition: a 2x2 square cut in
 * two along x = 1. The JSON must parse back with every documented field and the exact
 * coordinates; the SVG must hold one path per input, component and hull and one line per cut. */
#include "testutil.h"

#include <cjson/cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "export/json2d.h"
#include "export/svg2d.h"

typedef struct fixture {
    acd_polygon in;
    acd_vec2 a[4], b[4], cut[1][2];
    acd2d_component comps[2];
    acd2d_node nodes[3];
    acd2d_result res;
} fixture;

static void make(fixture *f) {
    memset(f, 0, sizeof *f);
    acd_vec2 outer[] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
    const acd_vec2 *rings[] = {outer};
    size_t sizes[] = {4};
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(&f->in, rings, sizes, 1, &err), ACD_OK);
    acd_vec2 a[] = {{0, 0}, {1, 0}, {1, 2}, {0, 2}}, b[] = {{1, 0}, {2, 0}, {2, 2}, {1, 2}};
    memcpy(f->a, a, sizeof a);
    memcpy(f->b, b, sizeof b);
    f->cut[0][0] = (acd_vec2){1, 0};
    f->cut[0][1] = (acd_vec2){1, 2};
    f->comps[0] = (acd2d_component){.points = f->a, .npoints = 4, .hull = f->a, .nhull = 4, .node = 1};
    f->comps[1] = (acd2d_component){.points = f->b, .npoints = 4, .hull = f->b, .nhull = 4, .node = 2};
    f->nodes[0] = (acd2d_node){.parent = -1, .child = {1, 2}, .concavity = 0.25, .cut = {{1, 0}, {1, 2}}};
    f->nodes[1] = (acd2d_node){.parent = 0, .child = {-1, -1}, .acceptable = 1};
    f->nodes[2] = (acd2d_node){.parent = 0, .child = {-1, -1}, .acceptable = 1};
    f->res.tau = 0.5;
    f->res.measure = ACD2D_MEASURE_H2;
    f->res.input_vertices = 4;
    f->res.input_notches = 0;
    f->res.input_holes = 0;
    f->res.components = f->comps;
    f->res.ncomponents = 2;
    f->res.cuts = f->cut;
    f->res.ncuts = 1;
    f->res.nodes = f->nodes;
    f->res.nnodes = 3;
    f->res.max_concavity = 0;
    f->res.seconds = 0.125;
}

static void test_json(void **state) {
    (void)state;
    fixture f;
    make(&f);
    acd_json2d_doc d = {NULL, &f.in, &f.res, 1, 1, "ok"};
    char *s = acd_json2d_string(&d);
    assert_non_null(s);
    cJSON *j = cJSON_Parse(s);
    assert_non_null(j);
    assert_true(cJSON_GetObjectItem(j, "tau")->valuedouble == 0.5);
    assert_string_equal(cJSON_GetObjectItem(j, "measure")->valuestring, "h2");
    cJSON *in = cJSON_GetObjectItem(j, "input");
    assert_int_equal(cJSON_GetObjectItem(in, "vertices")->valueint, 4);
    assert_int_equal(cJSON_GetObjectItem(in, "notches")->valueint, 0);
    assert_int_equal(cJSON_GetObjectItem(in, "holes")->valueint, 0);
    assert_true(cJSON_GetObjectItem(in, "area")->valuedouble == 4.0);
    cJSON *comps = cJSON_GetObjectItem(j, "components");
    assert_int_equal(cJSON_GetArraySize(comps), 2);
    cJSON *c1 = cJSON_GetArrayItem(comps, 1);
    assert_int_equal(cJSON_GetArraySize(c1), 4); /* first point not repeated */
    assert_true(cJSON_GetArrayItem(cJSON_GetArrayItem(c1, 1), 0)->valuedouble == 2.0);
    assert_int_equal(cJSON_GetArraySize(cJSON_GetObjectItem(j, "hulls")), 2);
    cJSON *cuts = cJSON_GetObjectItem(j, "cuts");
    assert_int_equal(cJSON_GetArraySize(cuts), 1);
    assert_true(cJSON_GetArrayItem(cJSON_GetArrayItem(cJSON_GetArrayItem(cuts, 0), 1), 1)->valuedouble == 2.0);
    cJSON *tree = cJSON_GetArrayItem(cJSON_GetObjectItem(j, "tree"), 0);
    assert_int_equal(cJSON_GetArraySize(tree), 3);
    cJSON *root = cJSON_GetArrayItem(tree, 0);
    assert_int_equal(cJSON_GetObjectItem(root, "parent")->valueint, -1);
    assert_int_equal(cJSON_GetArraySize(cJSON_GetObjectItem(root, "children")), 2);
    assert_int_equal(cJSON_GetObjectItem(root, "component")->valueint, -1);
    assert_int_equal(cJSON_GetObjectItem(cJSON_GetArrayItem(tree, 2), "component")->valueint, 1);
    cJSON *st = cJSON_GetObjectItem(j, "stats");
    assert_int_equal(cJSON_GetObjectItem(st, "components")->valueint, 2);
    assert_true(cJSON_GetObjectItem(st, "seconds")->valuedouble == 0.125);
    assert_true(cJSON_IsNumber(cJSON_GetObjectItem(st, "max_concavity")));
    assert_true(cJSON_IsTrue(cJSON_GetObjectItem(cJSON_GetObjectItem(j, "verify"), "passed")));
    cJSON_Delete(j);
    free(s);
    /* a coordinate that needs 17 digits survives the round trip */
    f.a[0].x = 0.1 + 0.2 - 0.30000000000000004; /* 0 */
    f.b[1].x = 2.0000000000000004;
    s = acd_json2d_string(&d);
    j = cJSON_Parse(s);
    assert_true(cJSON_GetArrayItem(cJSON_GetArrayItem(cJSON_GetArrayItem(cJSON_GetObjectItem(j, "components"), 1), 1), 0)
                    ->valuedouble == 2.0000000000000004);
    cJSON_Delete(j);
    free(s);
    acd_polygon_free(&f.in);
}

static size_t count_str(const char *s, const char *w) {
    size_t n = 0;
    for (const char *p = strstr(s, w); p; p = strstr(p + 1, w)) n++;
    return n;
}

static void test_svg(void **state) {
    (void)state;
    fixture f;
    make(&f);
    char path[] = "/tmp/acd_test_svg_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    acd_svg2d_options o = acd_svg2d_default_options();
    o.title = "square <2 pieces>";
    acd_error err;
    assert_int_equal(acd_svg2d_write(path, &f.in, &f.res, 1, &o, &err), ACD_OK);
    size_t len;
    char *s = tu_read_file(path, &len);
    assert_non_null(s);
    assert_non_null(strstr(s, "<svg"));
    assert_non_null(strstr(s, "</svg>"));
    assert_non_null(strstr(s, "square &lt;2 pieces&gt;"));
    assert_int_equal(count_str(s, "<path"), 1 + 2 + 2);
    assert_int_equal(count_str(s, "<line"), 1);
    /* scaled to fit: the square spans the 800 px width minus the margins */
    assert_non_null(strstr(s, "M10.000 "));
    assert_non_null(strstr(s, "L766.000 ")); /* scale min((800-20)/2, (800-20-24)/2) */
    free(s);
    assert_int_equal(acd_svg2d_write("/nonexistent-dir/x.svg", &f.in, &f.res, 1, NULL, &err), ACD_ERR_IO);
    assert_non_null(strstr(err.message, "/nonexistent-dir/x.svg"));
    unlink(path);
    acd_polygon_free(&f.in);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_json),
        cmocka_unit_test(test_svg),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
