/* Tests of export/export3d: everything written by acd_export_all is read back: the OBJ has one
 * group per hull with the exact coordinates, per-hull and per-part files exist and match, the JSON
 * summary adds up, URDF and MJCF reference one mesh per hull; hull simplification keeps the budget
 * and encloses; bad options are refused. */
#include "testutil.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "acd/export.h"
#include "core/tolerance.h"
#include "meshgen.h"

static size_t count(const char *s, const char *needle) {
    size_t c = 0;
    for (const char *p = strstr(s, needle); p; p = strstr(p + 1, needle)) c++;
    return c;
}

static void rm_rf(const char *dir) {
    char cmd[512];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0) print_message("could not remove %s\n", dir);
}

static void make_halves(acd_hull h[2], tm_mesh b[2]) {
    double lo0[3] = {0.1, 0, 0}, hi0[3] = {0.5, 1.0 / 3.0, 1}, lo1[3] = {0.5, 0, 0}, hi1[3] = {0.9, 1.0 / 3.0, 1};
    b[0] = tm_box(lo0, hi0);
    b[1] = tm_box(lo1, hi1);
    for (int i = 0; i < 2; i++) assert_int_equal(acd_hull_compute(b[i].v, b[i].nv, &h[i], NULL), ACD_OK);
}

static void test_export_all_round_trip(void **state) {
    (void)state;
    char dir[] = "/tmp/acd_export_XXXXXX";
    assert_non_null(mkdtemp(dir));
    acd_hull h[2];
    tm_mesh b[2];
    make_halves(h, b);
    acd_mesh_part pa[2] = {{"left", {b[0].v, b[0].nv, b[0].t, b[0].nt}}, {"right", {b[1].v, b[1].nv, b[1].t, b[1].nt}}};
    acd_mesh_parts parts = {pa, 2};
    acd_export_options o = acd_export_default_options();
    o.name = "box_robot";
    acd_error err;
    char out[512], path[700];
    snprintf(out, sizeof out, "%s/out", dir);
    assert_int_equal(acd_export_all(out, &parts, h, 2, NULL, &o, &err), ACD_OK);

    /* one OBJ, two groups, exact coordinates */
    snprintf(path, sizeof path, "%s/decomposition.obj", out);
    acd_mesh_parts back;
    assert_int_equal(acd_mesh_read_parts(path, &back, &err), ACD_OK);
    assert_int_equal(back.count, 2);
    assert_string_equal(back.parts[0].name, "hull_000");
    assert_string_equal(back.parts[1].name, "hull_001");
    for (int i = 0; i < 2; i++) {
        assert_int_equal(back.parts[i].mesh.ntriangles, h[i].ntriangles);
        assert_int_equal(back.parts[i].mesh.nvertices, h[i].nvertices);
        /* every hull vertex comes back bit for bit (the reader orders vertices by first use) */
        for (size_t v = 0; v < h[i].nvertices; v++) {
            int found = 0;
            for (size_t w = 0; w < back.parts[i].mesh.nvertices && !found; w++)
                found = memcmp(back.parts[i].mesh.vertices + 3 * w, h[i].vertices + 3 * v, 3 * sizeof(double)) == 0;
            assert_true(found);
        }
    }
    acd_mesh_parts_free(&back);

    /* one file per hull and per part */
    for (int i = 0; i < 2; i++) {
        acd_mesh m;
        snprintf(path, sizeof path, "%s/hulls/hull_%03d.obj", out, i);
        assert_int_equal(acd_mesh_read(path, &m, &err), ACD_OK);
        assert_int_equal(m.nvertices, h[i].nvertices);
        acd_mesh_free(&m);
        snprintf(path, sizeof path, "%s/parts/part_%03d.obj", out, i);
        assert_int_equal(acd_mesh_read(path, &m, &err), ACD_OK);
        assert_int_equal(m.ntriangles, 12);
        acd_mesh_free(&m);
    }

    /* summary */
    snprintf(path, sizeof path, "%s/summary.json", out);
    char *js = tu_read_file(path, NULL);
    assert_non_null(js);
    cJSON *root = cJSON_Parse(js);
    assert_non_null(root);
    assert_int_equal((int)cJSON_GetObjectItem(root, "hulls")->valuedouble, 2);
    double vs = cJSON_GetObjectItem(root, "hull_volume_sum")->valuedouble;
    assert_true(fabs(vs - (h[0].volume + h[1].volume)) < 1e-15);
    cJSON *list = cJSON_GetObjectItem(root, "hull_list");
    assert_int_equal(cJSON_GetArraySize(list), 2);
    assert_string_equal(cJSON_GetObjectItem(cJSON_GetArrayItem(list, 1), "part")->valuestring, "right");
    cJSON_Delete(root);
    free(js);

    /* URDF and MJCF */
    snprintf(path, sizeof path, "%s/box_robot.urdf", out);
    char *urdf = tu_read_file(path, NULL);
    assert_non_null(urdf);
    assert_int_equal(count(urdf, "<collision"), 2);
    assert_int_equal(count(urdf, "filename=\"hulls/hull_001.obj\""), 1);
    assert_non_null(strstr(urdf, "<robot name=\"box_robot\">"));
    free(urdf);
    snprintf(path, sizeof path, "%s/box_robot.xml", out);
    char *mj = tu_read_file(path, NULL);
    assert_non_null(mj);
    assert_int_equal(count(mj, "<mesh name="), 2);
    assert_int_equal(count(mj, "<geom "), 2);
    assert_non_null(strstr(mj, "file=\"hulls/hull_000.obj\""));
    free(mj);

    for (int i = 0; i < 2; i++) {
        acd_hull_free(&h[i]);
        tm_free(&b[i]);
    }
    rm_rf(dir);
}

static void test_simplified_export(void **state) {
    (void)state;
    char dir[] = "/tmp/acd_export_XXXXXX";
    assert_non_null(mkdtemp(dir));
    tm_mesh t = tm_torus(1.0, 0.3, 48, 16);
    acd_hull h;
    assert_int_equal(acd_hull_compute(t.v, t.nv, &h, NULL), ACD_OK);
    assert_true(h.nvertices > 16);
    acd_export_options o = acd_export_default_options();
    o.max_hull_vertices = 16;
    o.mesh_ext = "stl";
    acd_error err;
    assert_int_equal(acd_export_all(dir, NULL, &h, 1, NULL, &o, &err), ACD_OK);
    char path[600];
    snprintf(path, sizeof path, "%s/decomposition.obj", dir);
    acd_mesh m;
    assert_int_equal(acd_mesh_read(path, &m, &err), ACD_OK);
    assert_true(m.nvertices <= 16);
    acd_hull s;
    assert_int_equal(acd_hull_compute(m.vertices, m.nvertices, &s, NULL), ACD_OK);
    acd_scale sc = acd_scale_of_points(t.v, t.nv, 3);
    for (size_t i = 0; i < t.nv; i++) assert_true(acd_hull_plane_distance(&s, t.v + 3 * i) <= 2 * sc.dist);
    acd_hull_free(&s);
    acd_mesh_free(&m);
    snprintf(path, sizeof path, "%s/hulls/hull_000.stl", dir);
    assert_int_equal(access(path, R_OK), 0);
    acd_hull_free(&h);
    tm_free(&t);
    rm_rf(dir);
}

static void test_bad_options(void **state) {
    (void)state;
    acd_hull h[2];
    tm_mesh b[2];
    make_halves(h, b);
    acd_export_options o = acd_export_default_options();
    acd_error err;
    o.mesh_ext = "xyz";
    assert_int_equal(acd_export_all("/tmp/acd_never_made", NULL, h, 2, NULL, &o, &err), ACD_ERR_INVALID_ARGUMENT);
    o = acd_export_default_options();
    o.name = "my robot";
    assert_int_equal(acd_export_urdf("/tmp/acd_never.urdf", "", 2, &o, &err), ACD_ERR_INVALID_ARGUMENT);
    o = acd_export_default_options();
    o.max_hull_vertices = 3;
    assert_int_equal(acd_export_all("/tmp/acd_never_made", NULL, h, 2, NULL, &o, &err), ACD_ERR_INVALID_ARGUMENT);
    o = acd_export_default_options();
    assert_int_equal(acd_export_hulls_obj("/nonexistent-dir/x.obj", h, 2, &o, &err), ACD_ERR_IO);
    assert_int_equal(acd_export_urdf("/tmp/acd_never.urdf", "a\"b", 2, &o, &err), ACD_ERR_INVALID_ARGUMENT);
    for (int i = 0; i < 2; i++) {
        acd_hull_free(&h[i]);
        tm_free(&b[i]);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_export_all_round_trip),
        cmocka_unit_test(test_simplified_export),
        cmocka_unit_test(test_bad_options),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
