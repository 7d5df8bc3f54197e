/* Tests of eval/eval3d (acd eval) on decompositions with known answers: a mesh decomposed into
 * itself, a cube split in two (the shared face is not boundary), hulls that miss half the cube,
 * an L-shaped prism under its single convex hull, an open mesh, determinism, bad input. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/eval.h"
#include "acd/hull.h"
#include "eval/eval3d.h"
#include "meshgen.h"

static acd_mesh as_mesh(const tm_mesh *m) {
    acd_mesh a = {m->v, m->nv, m->t, m->nt};
    return a;
}

static acd_hull box_hull(double x0, double x1, double y0, double y1, double z0, double z1) {
    double lo[3] = {x0, y0, z0}, hi[3] = {x1, y1, z1};
    tm_mesh b = tm_box(lo, hi);
    acd_hull h;
    assert_int_equal(acd_hull_compute(b.v, b.nv, &h, NULL), ACD_OK);
    assert_int_equal(h.dim, 3);
    tm_free(&b);
    return h;
}

static acd_eval_params small_params(void) {
    acd_eval_params p = acd_eval_default_params();
    p.samples = 64000; /* 40^3: the unit cube's grid splits at x = 0.5 exactly */
    p.surface_samples = 20000;
    return p;
}

static void test_cube_is_its_own_decomposition(void **state) {
    (void)state;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    tm_mesh cube = tm_box(lo, hi);
    acd_mesh m = as_mesh(&cube);
    acd_hull h = box_hull(0, 1, 0, 1, 0, 1);
    acd_eval_params p = small_params();
    acd_eval_report r;
    acd_error err;
    assert_int_equal(acd_eval_hulls(&m, &h, 1, &p, &r, &err), ACD_OK);
    assert_int_equal(r.parts, 1);
    assert_int_equal(r.hull_vertices, 8);
    assert_true(r.mesh_closed);
    assert_true(fabs(r.mesh_volume - 1) < 1e-14);
    assert_true(fabs(r.hull_volume_sum - 1) < 1e-12);
    assert_true(r.union_volume == 1.0);
    assert_true(r.iou == 1.0 && r.coverage == 1.0 && r.excess == 0.0);
    assert_true(r.mesh_to_hulls_max < 1e-12 && r.hulls_to_mesh_max < 1e-12);
    assert_true(r.concavity_max < 1e-12);
    assert_int_equal(r.samples, 64000);
    assert_int_equal(r.inexact_distances, 0);
    assert_true(fabs(r.diagonal - sqrt(3.0)) < 1e-15);
    acd_hull_free(&h);
    tm_free(&cube);
}

/* A vertex no face uses is not on the surface: a cube with a stray vertex far outside scores as
 * the cube (before, the stray vertex was a mesh sample 2.6 diagonals from the hull). */
static void test_unused_vertex_is_not_surface(void **state) {
    (void)state;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    tm_mesh cube = tm_box(lo, hi);
    double *v = malloc(3 * (cube.nv + 1) * sizeof *v);
    assert_non_null(v);
    memcpy(v, cube.v, 3 * cube.nv * sizeof *v);
    v[3 * cube.nv] = v[3 * cube.nv + 1] = v[3 * cube.nv + 2] = 5;
    acd_mesh m = {v, cube.nv + 1, cube.t, cube.nt};
    acd_hull h = box_hull(0, 1, 0, 1, 0, 1);
    acd_eval_params p = small_params();
    acd_eval_report r;
    acd_error err;
    assert_int_equal(acd_eval_hulls(&m, &h, 1, &p, &r, &err), ACD_OK);
    assert_true(r.iou == 1.0 && r.coverage == 1.0);
    assert_true(r.mesh_to_hulls_max < 1e-12 && r.hulls_to_mesh_max < 1e-12);
    assert_true(r.concavity_max < 1e-12);
    acd_hull_free(&h);
    free(v);
    tm_free(&cube);
}

static void test_cube_split_in_two(void **state) {
    (void)state;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    tm_mesh cube = tm_box(lo, hi);
    acd_mesh m = as_mesh(&cube);
    acd_hull h[2] = {box_hull(0, 0.5, 0, 1, 0, 1), box_hull(0.5, 1, 0, 1, 0, 1)};
    acd_eval_params p = small_params();
    acd_eval_report r;
    assert_int_equal(acd_eval_hulls(&m, h, 2, &p, &r, NULL), ACD_OK);
    assert_int_equal(r.parts, 2);
    assert_int_equal(r.hull_vertices, 16);
    assert_true(fabs(r.hull_volume_sum - 1) < 1e-12);
    assert_true(r.iou == 1.0 && r.coverage == 1.0 && r.excess == 0.0);
    /* the shared face x = 0.5 is inside the union: no distance from it */
    assert_true(r.hulls_to_mesh_max < 1e-12);
    assert_true(r.mesh_to_hulls_max < 1e-12);
    /* a quarter of the hulls' area (the two copies of the shared face, 2 of 8) is not boundary */
    assert_true(fabs((double)r.boundary_samples / (double)r.surface_samples - 0.75) < 0.01);
    acd_hull_free(&h[0]);
    acd_hull_free(&h[1]);
    tm_free(&cube);
}

static void test_hull_misses_half_the_cube(void **state) {
    (void)state;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    tm_mesh cube = tm_box(lo, hi);
    acd_mesh m = as_mesh(&cube);
    acd_hull h = box_hull(0, 0.5, 0, 1, 0, 1);
    acd_eval_params p = small_params();
    acd_eval_report r;
    assert_int_equal(acd_eval_hulls(&m, &h, 1, &p, &r, NULL), ACD_OK);
    double s3 = sqrt(3.0);
    assert_true(r.coverage == 0.5);
    assert_true(r.iou == 0.5);
    assert_true(r.excess == 0.0);
    assert_true(fabs(r.union_volume - 0.5) < 1e-12);
    /* the face x = 1 is 0.5 from the half box (exact: those points are outside the union) */
    assert_true(fabs(r.mesh_to_hulls_max - 0.5 / s3) < 1e-12);
    /* mean over the cube's surface: x - 0.5 on four half faces, 0.5 on x = 1: (4 * 0.5 * 0.25 + 0.5) / 6 */
    assert_true(fabs(r.mesh_to_hulls_mean - (1.0 / 6.0) / s3) < 2e-3);
    /* the cut face x = 0.5: max 0.5 at its centre, mean 1/6 over a quarter of the boundary */
    assert_true(fabs(r.hulls_to_mesh_max - 0.5 / s3) < 0.01);
    assert_true(r.hulls_to_mesh_max <= 0.5 / s3 + 1e-12);
    assert_true(fabs(r.hulls_to_mesh_mean - (1.0 / 24.0) / s3) < 2e-3);
    assert_true(r.concavity_max == r.mesh_to_hulls_max);
    acd_hull_free(&h);
    tm_free(&cube);
}

static void test_l_prism_under_one_hull(void **state) {
    (void)state;
    double poly[12] = {0, 0, 2, 0, 2, 1, 1, 1, 1, 2, 0, 2};
    tm_mesh l = tm_prism(poly, 6, 3, 0, 1);
    acd_mesh m = as_mesh(&l);
    acd_hull h;
    assert_int_equal(acd_hull_compute(l.v, l.nv, &h, NULL), ACD_OK);
    acd_eval_params p = acd_eval_default_params();
    p.samples = 200000;
    p.surface_samples = 50000;
    acd_eval_report r;
    assert_int_equal(acd_eval_hulls(&m, &h, 1, &p, &r, NULL), ACD_OK);
    assert_true(fabs(r.mesh_volume - 3.0) < 1e-13);
    assert_true(fabs(r.hull_volume_sum - 3.5) < 1e-12);
    assert_true(r.coverage == 1.0);
    assert_true(fabs(r.excess - 0.5 / 3.0) < 2e-3);
    assert_true(fabs(r.iou - 3.0 / 3.5) < 2e-3);
    assert_true(fabs(r.union_volume - 3.5) < 5e-3);
    /* the notch edge (1, 1, z) is 1/sqrt(2) from the hull facet x + y = 3 and min(z, 1 - z) from
     * the caps: 0.5 at its middle (every distance exact: one hull) */
    assert_true(fabs(r.mesh_to_hulls_max - 0.5 / 3.0) < 0.005);
    assert_true(r.mesh_to_hulls_max <= 0.5 / 3.0 + 1e-12);
    /* the facet's midline is 0.5 from the notch walls */
    assert_true(fabs(r.hulls_to_mesh_max - 0.5 / 3.0) < 0.01);
    assert_int_equal(r.inexact_distances, 0);
    acd_hull_free(&h);
    tm_free(&l);
}

static void test_overlapping_hulls_inside_distance(void **state) {
    (void)state;
    /* the L covered by two overlapping boxes: [0,2]x[0,1] and [0,1]x[0,2]; mesh points in the
     * overlap square are inside the union; the notch corner (1,1) is on the boundary */
    double poly[12] = {0, 0, 2, 0, 2, 1, 1, 1, 1, 2, 0, 2};
    tm_mesh l = tm_prism(poly, 6, 3, 0, 1);
    acd_mesh m = as_mesh(&l);
    acd_hull h[2] = {box_hull(0, 2, 0, 1, 0, 1), box_hull(0, 1, 0, 2, 0, 1)};
    acd_eval_params p = small_params();
    acd_eval_report r;
    assert_int_equal(acd_eval_hulls(&m, h, 2, &p, &r, NULL), ACD_OK);
    assert_true(fabs(r.iou - 1.0) < 1e-12 && r.excess == 0.0);
    assert_true(fabs(r.hull_volume_sum - 4.0) < 1e-12);
    assert_true(r.mesh_to_hulls_max < 1e-9);
    assert_true(r.hulls_to_mesh_max < 1e-9);
    acd_hull_free(&h[0]);
    acd_hull_free(&h[1]);
    tm_free(&l);
}

static void test_open_mesh_and_determinism(void **state) {
    (void)state;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    tm_mesh cube = tm_box(lo, hi);
    memmove(cube.t + 6, cube.t + 12, 24 * sizeof(uint32_t)); /* drop the top face */
    cube.nt = 10;
    acd_mesh m = as_mesh(&cube);
    acd_hull h = box_hull(0, 1, 0, 1, 0, 1);
    acd_eval_params p = small_params();
    p.samples = 8000;
    acd_eval_report r1, r2;
    assert_int_equal(acd_eval_hulls(&m, &h, 1, &p, &r1, NULL), ACD_OK);
    assert_false(r1.mesh_closed);
    assert_true(r1.coverage == 1.0 && r1.iou == 1.0);
    assert_int_equal(acd_eval_hulls(&m, &h, 1, &p, &r2, NULL), ACD_OK);
    r1.seconds = r2.seconds = 0;
    assert_memory_equal(&r1, &r2, sizeof r1);
    p.seed = 2;
    assert_int_equal(acd_eval_hulls(&m, &h, 1, &p, &r2, NULL), ACD_OK);
    assert_true(r2.seed == 2);
    acd_hull_free(&h);
    tm_free(&cube);
}

static void test_json_and_errors(void **state) {
    (void)state;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    tm_mesh cube = tm_box(lo, hi);
    acd_mesh m = as_mesh(&cube);
    acd_hull h = box_hull(0, 1, 0, 1, 0, 1);
    acd_eval_params p = small_params();
    acd_eval_report r;
    acd_error err;
    assert_int_equal(acd_eval_hulls(&m, &h, 1, &p, &r, &err), ACD_OK);
    char *js;
    assert_int_equal(acd_eval_report_json(&r, &js, &err), ACD_OK);
    const char *keys[] = {"\"parts\"", "\"hull_vertices\"", "\"mesh_volume\"", "\"hull_volume_sum\"", "\"union_volume\"",
                          "\"iou\"", "\"coverage\"", "\"excess\"", "\"distance\"", "\"mesh_to_hulls_max\"",
                          "\"mesh_to_hulls_mean\"", "\"hulls_to_mesh_max\"", "\"hulls_to_mesh_mean\"",
                          "\"concavity_max\"", "\"samples\"", "\"seed\"", "\"seconds\""};
    for (size_t i = 0; i < sizeof keys / sizeof *keys; i++) assert_non_null(strstr(js, keys[i]));
    free(js);
    /* uninitialised parameters, no triangles, bad index, only flat hulls */
    acd_eval_params bad;
    memset(&bad, 0, sizeof bad);
    assert_int_equal(acd_eval_hulls(&m, &h, 1, &bad, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    acd_mesh empty = {cube.v, cube.nv, cube.t, 0};
    assert_int_equal(acd_eval_hulls(&empty, &h, 1, &p, &r, &err), ACD_ERR_DEGENERATE);
    cube.t[5] = 99;
    assert_int_equal(acd_eval_hulls(&m, &h, 1, &p, &r, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "triangle 1"));
    cube.t[5] = 1;
    double flat[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    acd_hull fh;
    assert_int_equal(acd_hull_compute(flat, 4, &fh, NULL), ACD_OK);
    assert_int_equal(acd_eval_hulls(&m, &fh, 1, &p, &r, &err), ACD_ERR_DEGENERATE);
    acd_hull_free(&fh);
    /* coordinates beyond ACD_COORD_MAX, in the mesh or a hull: refused, not "the mesh encloses no
     * volume (no sample of 1 fell inside)" */
    double big[12] = {0, 0, 0, 1e300, 0, 0, 0, 1e300, 0, 0, 0, 1e300};
    acd_hull bh;
    assert_int_equal(acd_hull_compute(big, 4, &bh, NULL), ACD_OK);
    assert_int_equal(acd_eval_hulls(&m, &bh, 1, &p, &r, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "hull of part 0"));
    assert_non_null(strstr(err.message, "magnitude"));
    acd_hull_free(&bh);
    double keep = cube.v[3];
    cube.v[3] = -1e300;
    assert_int_equal(acd_eval_hulls(&m, &h, 1, &p, &r, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "magnitude"));
    cube.v[3] = keep;
    acd_hull_free(&h);
    tm_free(&cube);
}

static void test_eval_parts_computes_hulls(void **state) {
    (void)state;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    tm_mesh cube = tm_box(lo, hi);
    acd_mesh m = as_mesh(&cube);
    /* the cube's own vertices as one part, plus a flat part */
    double fv[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t ft[3] = {0, 1, 2};
    acd_mesh_part parts[2] = {{"whole", {cube.v, cube.nv, cube.t, cube.nt}}, {"flat", {fv, 3, ft, 1}}};
    acd_mesh_parts ps = {parts, 2};
    acd_eval_params p = small_params();
    acd_eval_report r;
    assert_int_equal(acd_eval_parts(&m, &ps, &p, &r, NULL), ACD_OK);
    assert_int_equal(r.parts, 2);
    assert_int_equal(r.degenerate_parts, 1);
    assert_int_equal(r.hull_vertices, 11);
    assert_true(r.iou == 1.0);
    tm_free(&cube);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cube_is_its_own_decomposition),
        cmocka_unit_test(test_unused_vertex_is_not_surface),
        cmocka_unit_test(test_cube_split_in_two),
        cmocka_unit_test(test_hull_misses_half_the_cube),
        cmocka_unit_test(test_l_prism_under_one_hull),
        cmocka_unit_test(test_overlapping_hulls_inside_distance),
        cmocka_unit_test(test_open_mesh_and_determinism),
        cmocka_unit_test(test_json_and_errors),
        cmocka_unit_test(test_eval_parts_computes_hulls),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
