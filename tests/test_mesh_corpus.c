/* Robustness of the readers on real files fetched by scripts/fetch-data.sh: every CGAL mesh and
 * every assimp test model is either read (and then validated) or refused with a message naming
 * the file; known results of the assimp models (malformed-file cases included) are checked.
 * Skips when data/meshes is absent. */
#include "testutil.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/mesh.h"

static int is_mesh_name(const char *n) {
    size_t l = strlen(n);
    static const char *const ext[] = {".obj", ".off", ".ply", ".stl", ".OBJ", ".OFF", ".PLY", ".STL"};
    for (size_t i = 0; i < sizeof ext / sizeof ext[0]; i++)
        if (l > 4 && !strcmp(n + l - 4, ext[i])) return 1;
    return 0;
}

/* Reads and validates every mesh of dir; returns the number of files seen. */
static int sweep(const char *dir, int *failed_reads) {
    DIR *d = opendir(dir);
    if (!d) return 0;
    int n = 0;
    struct dirent *e;
    char **names = NULL;
    size_t count = 0;
    while ((e = readdir(d)) != NULL) {
        if (!is_mesh_name(e->d_name)) continue;
        names = realloc(names, (count + 1) * sizeof *names);
        assert_non_null(names);
        names[count] = strdup(e->d_name);
        assert_non_null(names[count]);
        count++;
    }
    closedir(d);
    for (size_t i = 0; i < count; i++) {
        char path[2048];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        acd_mesh m;
        acd_error err;
        acd_status s = acd_mesh_read(path, &m, &err);
        n++;
        if (s != ACD_OK) {
            (*failed_reads)++;
            if (strncmp(err.message, path, strlen(path)) != 0) fail_msg("%s: message does not name the file: %s", path, err.message);
        } else {
            acd_mesh_report r;
            if (acd_mesh_validate(&m, 0, &r, &err) != ACD_OK) fail_msg("%s: validate: %s", path, err.message);
            assert_int_equal(r.faces, m.ntriangles);
            acd_mesh_report_free(&r);
            acd_mesh_free(&m);
        }
        free(names[i]);
    }
    free(names);
    return n;
}

static void test_sweep_cgal(void **state) {
    (void)state;
    int failed = 0, n = sweep(ACD_MESH_DATA, &failed);
    if (!n) TU_SKIP("no fetched meshes in %s (run scripts/fetch-data.sh)", ACD_MESH_DATA);
    print_message("%d meshes, %d refused\n", n, failed);
    assert_int_equal(failed, 0); /* every CGAL mesh and the npm bunny read */
}

typedef struct expect {
    const char *file;
    int ok;
    size_t vertices, faces;
    int closed;
    const char *message; /* for ok == 0: part of the error message */
} expect;

static void test_assimp_models(void **state) {
    (void)state;
    char probe[2048];
    if (!tu_mesh_data(probe, sizeof probe, "assimp/OBJ/box.obj"))
        TU_SKIP("no assimp test models in %s/assimp (run scripts/fetch-data.sh)", ACD_MESH_DATA);
    static const expect ex[] = {
        {"OBJ/box.obj", 1, 8, 12, 1, NULL},
        {"OBJ/box_UTF16BE.obj", 1, 8, 12, 1, NULL},
        {"OBJ/box_without_lineending.obj", 1, 8, 12, 1, NULL},
        {"OBJ/cube_with_vertexcolors.obj", 1, 8, 12, 1, NULL},
        {"OBJ/point_cloud.obj", 1, 3, 0, 0, NULL},
        {"OBJ/number_formats.obj", 0, 0, 0, 0, "number_formats.obj:11: vertex needs 3 numbers"},
        {"OFF/Cube.off", 1, 8, 12, 1, NULL},
        {"OFF/invalid.off", 0, 0, 0, 0, "invalid.off:6: face 0 has 0 vertices"},
        {"PLY/cube.ply", 1, 8, 12, 1, NULL},
        {"PLY/cube_binary.ply", 1, 8, 12, 1, NULL},
        {"PLY/pond.0.ply", 0, 0, 0, 0, "byte offset"},
        {"STL/Spider_ascii.stl", 1, 722, 1368, 0, NULL},
        {"STL/Spider_binary.stl", 1, 722, 1368, 0, NULL},
        {"STL/triangle_with_two_solids.stl", 1, 6, 2, 0, NULL},
        {"STL/triangle_with_empty_solid.stl", 1, 3, 1, 0, NULL},
        {"invalid/OutOfMemory.off", 0, 0, 0, 0, "exceed what the file can hold"},
        {"invalid/empty.obj", 0, 0, 0, 0, "empty file"},
        {"invalid/empty.off", 0, 0, 0, 0, "empty file"},
        {"invalid/empty.ply", 0, 0, 0, 0, "empty file"},
        {"invalid/malformed.obj", 0, 0, 0, 0, "malformed.obj:28: vertex index 0"},
        {"invalid/malformed2.obj", 0, 0, 0, 0, "face with 0 vertices"},
    };
    for (size_t i = 0; i < sizeof ex / sizeof ex[0]; i++) {
        char rel[256], path[2048];
        snprintf(rel, sizeof rel, "assimp/%s", ex[i].file);
        if (!tu_mesh_data(path, sizeof path, rel)) fail_msg("%s missing", rel);
        acd_mesh m;
        acd_error err;
        acd_status s = acd_mesh_read(path, &m, &err);
        if (!ex[i].ok) {
            if (s == ACD_OK) fail_msg("%s: read, expected an error", ex[i].file);
            if (!strstr(err.message, ex[i].message)) fail_msg("%s: message '%s'", ex[i].file, err.message);
            continue;
        }
        if (s != ACD_OK) fail_msg("%s: %s", ex[i].file, err.message);
        acd_mesh_report r;
        assert_int_equal(acd_mesh_validate(&m, 1, &r, &err), ACD_OK);
        if (r.vertices != ex[i].vertices || r.faces != ex[i].faces || r.closed != ex[i].closed)
            fail_msg("%s: %zu vertices, %zu faces, closed %d", ex[i].file, r.vertices, r.faces, r.closed);
        acd_mesh_report_free(&r);
        acd_mesh_free(&m);
    }
    /* and every model of the folders is read or refused with a message naming it */
    static const char *const dirs[] = {"OBJ", "OFF", "PLY", "STL", "invalid"};
    for (size_t k = 0; k < 5; k++) {
        char d[2048];
        snprintf(d, sizeof d, "%s/assimp/%s", ACD_MESH_DATA, dirs[k]);
        int failed = 0;
        assert_true(sweep(d, &failed) > 0);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sweep_cgal),
        cmocka_unit_test(test_assimp_models),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
