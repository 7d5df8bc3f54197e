/* Tests of the mesh report: exact counts on small meshes with known topology (cube, tori,
 * Moebius strip, pinched and fin configurations, defects), exact self-intersection decisions,
 * and the known values of the fetched CGAL meshes (skipped when data/meshes is absent). */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/mesh.h"

#define PI 3.14159265358979323846

static const double cube_v[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
static const uint32_t cube_t[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                       {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};

typedef struct builder {
    double v[4096 * 3];
    uint32_t t[8192 * 3];
    size_t nv, nt;
} builder;

static void add_cube(builder *b, double dx, double dy, double dz, double s) {
    uint32_t base = (uint32_t)b->nv;
    for (int i = 0; i < 8; i++) {
        b->v[3 * b->nv] = dx + s * cube_v[i][0];
        b->v[3 * b->nv + 1] = dy + s * cube_v[i][1];
        b->v[3 * b->nv + 2] = dz + s * cube_v[i][2];
        b->nv++;
    }
    for (int i = 0; i < 12; i++) {
        for (int k = 0; k < 3; k++) b->t[3 * b->nt + (size_t)k] = base + cube_t[i][k];
        b->nt++;
    }
}

/* Torus with n x m quads (outward), centre (cx, 0, 0), radii R and r. */
static void add_torus(builder *b, double cx, int n, int m, double R, double r) {
    uint32_t base = (uint32_t)b->nv;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < m; j++) {
            double u = 2 * PI * i / n, w = 2 * PI * j / m;
            b->v[3 * b->nv] = cx + (R + r * cos(w)) * cos(u);
            b->v[3 * b->nv + 1] = (R + r * cos(w)) * sin(u);
            b->v[3 * b->nv + 2] = r * sin(w);
            b->nv++;
        }
    for (int i = 0; i < n; i++)
        for (int j = 0; j < m; j++) {
            uint32_t a = base + (uint32_t)(i * m + j), bb = base + (uint32_t)(((i + 1) % n) * m + j),
                     c = base + (uint32_t)(((i + 1) % n) * m + (j + 1) % m), d = base + (uint32_t)(i * m + (j + 1) % m);
            uint32_t t1[3] = {a, bb, c}, t2[3] = {a, c, d};
            memcpy(b->t + 3 * b->nt++, t1, sizeof t1);
            memcpy(b->t + 3 * b->nt++, t2, sizeof t2);
        }
}

static void report_of(builder *b, acd_mesh_report *r) {
    acd_mesh m = {b->v, b->nv, b->t, b->nt};
    acd_error err;
    acd_status s = acd_mesh_validate(&m, 1, r, &err);
    if (s != ACD_OK) fail_msg("%s", err.message);
}

static builder *new_builder(void) {
    builder *b = calloc(1, sizeof *b);
    assert_non_null(b);
    return b;
}

static void test_cube(void **state) {
    (void)state;
    builder *b = new_builder();
    add_cube(b, 0, 0, 0, 1);
    acd_mesh_report r;
    report_of(b, &r);
    assert_int_equal(r.vertices, 8);
    assert_int_equal(r.faces, 12);
    assert_int_equal(r.edges, 18);
    assert_int_equal(r.boundary_edges, 0);
    assert_int_equal(r.nonmanifold_edges, 0);
    assert_int_equal(r.nonmanifold_vertices, 0);
    assert_int_equal(r.components, 1);
    assert_int_equal(r.genus, 0);
    assert_true(r.closed && r.oriented && r.orientable);
    assert_int_equal(r.inward_components, 0);
    assert_true(fabs(r.volume - 1) < 1e-15 && fabs(r.area - 6) < 1e-14);
    assert_int_equal(r.self_intersections, 0);
    assert_int_equal(r.degenerate_faces, 0);
    assert_int_equal(r.duplicate_faces, 0);
    acd_mesh_report_free(&r);
    /* inside out */
    for (size_t t = 0; t < b->nt; t++) {
        uint32_t x = b->t[3 * t + 1];
        b->t[3 * t + 1] = b->t[3 * t + 2];
        b->t[3 * t + 2] = x;
    }
    report_of(b, &r);
    assert_true(r.oriented && r.closed);
    assert_int_equal(r.inward_components, 1);
    assert_true(fabs(r.volume + 1) < 1e-15);
    acd_mesh_report_free(&r);
    /* one face flipped: 3 conflicting edges, still orientable */
    uint32_t x = b->t[1];
    b->t[1] = b->t[2];
    b->t[2] = x;
    report_of(b, &r);
    assert_false(r.oriented);
    assert_true(r.orientable);
    assert_int_equal(r.orientation_conflicts, 3);
    assert_int_equal(r.genus, 0);
    acd_mesh_report_free(&r);
    /* two faces removed: open with 4 boundary edges, no closed component */
    b->nt = 10;
    report_of(b, &r);
    assert_false(r.closed);
    assert_int_equal(r.boundary_edges, 4);
    assert_int_equal(r.closed_components, 0);
    assert_int_equal(r.genus, 0);
    acd_mesh_report_free(&r);
    free(b);
}

static void test_tori_and_components(void **state) {
    (void)state;
    builder *b = new_builder();
    add_torus(b, 0, 16, 8, 2, 0.5);
    acd_mesh_report r;
    report_of(b, &r);
    assert_int_equal(r.genus, 1);
    assert_true(r.closed && r.oriented);
    assert_int_equal(r.inward_components, 0);
    assert_int_equal(r.self_intersections, 0);
    assert_true(r.volume > 0);
    acd_mesh_report_free(&r);
    add_torus(b, 10, 12, 6, 2, 0.7);
    add_cube(b, 20, 0, 0, 1);
    report_of(b, &r);
    assert_int_equal(r.components, 3);
    assert_int_equal(r.closed_components, 3);
    assert_int_equal(r.genus, 2);
    assert_int_equal(r.component[0].genus, 1);
    assert_int_equal(r.component[2].genus, 0);
    assert_true(fabs(r.component[2].volume - 1) < 1e-12);
    acd_mesh_report_free(&r);
    free(b);
}

static void test_moebius(void **state) {
    (void)state;
    builder *b = new_builder();
    int n = 20;
    for (int i = 0; i < n; i++) {
        double u = 2 * PI * i / n;
        for (int s = -1; s <= 1; s += 2) {
            double w = 0.3 * s;
            b->v[3 * b->nv] = (1 + w * cos(u / 2)) * cos(u);
            b->v[3 * b->nv + 1] = (1 + w * cos(u / 2)) * sin(u);
            b->v[3 * b->nv + 2] = w * sin(u / 2);
            b->nv++;
        }
    }
    for (int i = 0; i < n; i++) {
        uint32_t a = (uint32_t)(2 * i), c = (uint32_t)(2 * i + 1);
        uint32_t a2 = (uint32_t)(2 * ((i + 1) % n)), c2 = (uint32_t)(2 * ((i + 1) % n) + 1);
        if (i == n - 1) { /* the half twist: the strip's sides swap */
            uint32_t x = a2;
            a2 = c2;
            c2 = x;
        }
        uint32_t t1[3] = {a, a2, c2}, t2[3] = {a, c2, c};
        memcpy(b->t + 3 * b->nt++, t1, sizeof t1);
        memcpy(b->t + 3 * b->nt++, t2, sizeof t2);
    }
    acd_mesh_report r;
    report_of(b, &r);
    assert_false(r.orientable);
    assert_false(r.oriented);
    assert_false(r.closed);
    assert_int_equal(r.components, 1);
    assert_int_equal(r.boundary_edges, 2 * (size_t)n); /* one boundary curve of 2n edges */
    assert_int_equal(r.component[0].genus, -1);
    assert_int_equal(r.self_intersections, 0);
    acd_mesh_report_free(&r);
    free(b);
}

static void test_nonmanifold(void **state) {
    (void)state;
    builder *b = new_builder();
    /* two cubes sharing one vertex (a pinch): cube 2 reuses vertex 6 of cube 1 as its corner 0 */
    add_cube(b, 0, 0, 0, 1);
    add_cube(b, 1, 1, 1, 1);
    for (size_t i = 0; i < 3 * b->nt; i++)
        if (b->t[i] == 8) b->t[i] = 6;
    acd_mesh_report r;
    report_of(b, &r);
    assert_int_equal(r.nonmanifold_vertices, 1);
    assert_int_equal(r.nonmanifold_edges, 0);
    assert_int_equal(r.components, 2); /* edge-connected components */
    assert_int_equal(r.genus, 0);
    assert_int_equal(r.unused_vertices, 1);
    assert_true(r.closed);
    assert_int_equal(r.self_intersections, 0);
    acd_mesh_report_free(&r);
    /* three triangles on one edge (a fin): one non-manifold edge */
    builder *f = new_builder();
    static const double fv[5][3] = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {-1, 0.5, 0}, {-1, -0.5, 0}};
    static const uint32_t ft[3][3] = {{0, 1, 2}, {1, 0, 3}, {1, 0, 4}};
    memcpy(f->v, fv, sizeof fv);
    memcpy(f->t, ft, sizeof ft);
    f->nv = 5;
    f->nt = 3;
    report_of(f, &r);
    assert_int_equal(r.nonmanifold_edges, 1);
    assert_int_equal(r.boundary_edges, 6);
    assert_int_equal(r.nonmanifold_vertices, 2);
    assert_false(r.closed);
    assert_int_equal(r.self_intersections, 0);
    acd_mesh_report_free(&r);
    free(f);
    free(b);
}

static void test_degenerate_and_duplicate(void **state) {
    (void)state;
    builder *b = new_builder();
    add_cube(b, 0, 0, 0, 1);
    /* a face repeating an index, a zero-area face on collinear points, a duplicate (flipped) */
    b->v[3 * 8] = 0.5;
    b->v[3 * 8 + 1] = 0;
    b->v[3 * 8 + 2] = 0; /* vertex 8 on edge 0-1 */
    b->nv = 9;
    uint32_t extra[3][3] = {{0, 0, 1}, {0, 8, 1}, {0, 1, 2}};
    memcpy(b->t + 3 * b->nt, extra, sizeof extra);
    b->nt += 3;
    acd_mesh_report r;
    report_of(b, &r);
    assert_int_equal(r.degenerate_faces, 2);
    assert_int_equal(r.duplicate_faces, 1);
    /* the duplicate shares its 3 vertices with the face it repeats (counted as a duplicate, not an
     * intersection) and meets the other bottom face only along the diagonal; zero-area faces are
     * skipped */
    assert_int_equal(r.self_intersections, 0);
    assert_int_equal(r.components, 1);
    acd_mesh_report_free(&r);
    free(b);
}

static void test_self_intersections_exact(void **state) {
    (void)state;
    acd_error err;
    size_t n;
    /* two interpenetrating cubes */
    builder *b = new_builder();
    add_cube(b, 0, 0, 0, 1);
    add_cube(b, 0.5, 0.5, 0.5, 1);
    acd_mesh m = {b->v, b->nv, b->t, b->nt};
    assert_int_equal(acd_mesh_self_intersections(&m, &n, NULL, 0, &err), ACD_OK);
    assert_true(n > 0);
    /* separate cubes touching along a face (distinct vertices): touching counts */
    b->nv = b->nt = 0;
    add_cube(b, 0, 0, 0, 1);
    add_cube(b, 1, 0, 0, 1);
    m = (acd_mesh){b->v, b->nv, b->t, b->nt};
    assert_int_equal(acd_mesh_self_intersections(&m, &n, NULL, 0, &err), ACD_OK);
    assert_true(n > 0);
    /* separated by one ulp: no intersection (exact decision) */
    b->nv = b->nt = 0;
    add_cube(b, 0, 0, 0, 1);
    add_cube(b, nextafter(1.0, 2.0), 0, 0, 1);
    m = (acd_mesh){b->v, b->nv, b->t, b->nt};
    assert_int_equal(acd_mesh_self_intersections(&m, &n, NULL, 0, &err), ACD_OK);
    assert_int_equal(n, 0);
    /* an unwelded cube (every face with its own vertices): adjacency by coordinates, no intersection */
    b->nv = b->nt = 0;
    for (int t = 0; t < 12; t++)
        for (int k = 0; k < 3; k++) {
            memcpy(b->v + 3 * b->nv, cube_v[cube_t[t][k]], 3 * sizeof(double));
            b->t[3 * b->nt + (size_t)k] = (uint32_t)b->nv++;
            if (k == 2) b->nt++;
        }
    m = (acd_mesh){b->v, b->nv, b->t, b->nt};
    assert_int_equal(acd_mesh_self_intersections(&m, &n, NULL, 0, &err), ACD_OK);
    assert_int_equal(n, 0);
    /* shared edge: coplanar fold-over intersects, a proper hinge does not */
    static const double hv[4][3] = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.3, 0.5, 0}};
    uint32_t ht[2][3] = {{0, 1, 2}, {1, 0, 3}};
    m = (acd_mesh){(double *)hv, 4, &ht[0][0], 2};
    assert_int_equal(acd_mesh_self_intersections(&m, &n, NULL, 0, &err), ACD_OK);
    assert_int_equal(n, 1);
    double hv2[4][3] = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.3, -0.5, 0}};
    m.vertices = &hv2[0][0];
    assert_int_equal(acd_mesh_self_intersections(&m, &n, NULL, 0, &err), ACD_OK);
    assert_int_equal(n, 0);
    hv2[3][1] = 0.5;
    hv2[3][2] = 1e-300; /* just off the plane: no longer coplanar, touches only along the edge */
    assert_int_equal(acd_mesh_self_intersections(&m, &n, NULL, 0, &err), ACD_OK);
    assert_int_equal(n, 0);
    /* shared vertex: the second triangle pierces the first; or only touches at the vertex */
    double sv[5][3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 0.5, -1}, {1, 0.5, 1}};
    uint32_t st[2][3] = {{0, 1, 2}, {0, 3, 4}};
    m = (acd_mesh){&sv[0][0], 5, &st[0][0], 2};
    uint32_t pair[2];
    assert_int_equal(acd_mesh_self_intersections(&m, &n, pair, 1, &err), ACD_OK);
    assert_int_equal(n, 1);
    assert_int_equal(pair[0], 0);
    assert_int_equal(pair[1], 1);
    sv[3][0] = sv[4][0] = -1; /* now on the other side of vertex 0: meets only at the vertex */
    assert_int_equal(acd_mesh_self_intersections(&m, &n, NULL, 0, &err), ACD_OK);
    assert_int_equal(n, 0);
    /* shared vertex, coplanar, the second inside the first's angle */
    double cv[5][3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 0.2, 0}, {0.2, 1, 0}};
    m = (acd_mesh){&cv[0][0], 5, &st[0][0], 2};
    assert_int_equal(acd_mesh_self_intersections(&m, &n, NULL, 0, &err), ACD_OK);
    assert_int_equal(n, 1);
    free(b);
}

typedef struct known {
    const char *file;
    long genus;
    int closed;
    size_t boundary_edges;
} known;

static void test_known_meshes(void **state) {
    (void)state;
    static const known ks[] = {
        {"elephant.off", 3, 1, 0},       {"eight.off", 2, 1, 0},        {"cheese.off", 133, 1, 0},
        {"mushroom.off", 0, 0, 64},      {"3torus.off", 3, 1, 0},       {"double-torus-example.off", 2, 1, 0},
        {"torus_quad.off", 1, 1, 0},     {"armadillo.off", 0, 1, 0},    {"cube.off", 0, 1, 0},
        {"open_cube.off", 0, 0, 4},
    };
    int found = 0;
    for (size_t i = 0; i < sizeof ks / sizeof ks[0]; i++) {
        char path[1024];
        if (!tu_mesh_data(path, sizeof path, ks[i].file)) continue;
        found++;
        acd_mesh m;
        acd_error err;
        if (acd_mesh_read(path, &m, &err) != ACD_OK) fail_msg("%s", err.message);
        acd_mesh_report r;
        if (acd_mesh_validate(&m, 0, &r, &err) != ACD_OK) fail_msg("%s", err.message);
        print_message("%s: %zu vertices, %zu faces, genus %ld, %zu boundary edges, %zu components\n", ks[i].file,
                      r.vertices, r.faces, r.genus, r.boundary_edges, r.components);
        assert_int_equal(r.closed, ks[i].closed);
        assert_int_equal(r.boundary_edges, ks[i].boundary_edges);
        if (ks[i].closed) assert_int_equal(r.genus, ks[i].genus);
        acd_mesh_report_free(&r);
        acd_mesh_free(&m);
    }
    if (!found) TU_SKIP("no fetched meshes in %s (run scripts/fetch-data.sh)", ACD_MESH_DATA);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cube),
        cmocka_unit_test(test_tori_and_components),
        cmocka_unit_test(test_moebius),
        cmocka_unit_test(test_nonmanifold),
        cmocka_unit_test(test_degenerate_and_duplicate),
        cmocka_unit_test(test_self_intersections_exact),
        cmocka_unit_test(test_known_meshes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
