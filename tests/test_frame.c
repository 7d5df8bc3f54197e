/* Tests of geom3/frame (the local frame for input far from the origin) and of the public volume
 * functions on meshes far from the origin: acd_mesh_volume_beyond, acd_hull_volume_outside and its
 * bound, the volumes of acd_segment, acd_mesh_validate and acd_eval_hulls. The meshes are moved exactly
 * (tests/far_mesh.h), so a far call must give what the near call gives, to the rounding of what
 * the model coordinates themselves carry (a plane's offset there). */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/eval.h"
#include "acd/hull.h"
#include "acd/mesh.h"
#include "acd/segment.h"
#include "core/rng.h"
#include "far_mesh.h"
#include "geom3/frame.h"
#include "shapes.h"

static const double RATIOS[3] = {1e4, 1e6, 1e8};
static const double DIR[3] = {1.0, -0.5, 0.25};

/* x - c is exact: its rounding error (TwoSum) is zero */
static int sub_exact(double x, double c) {
    double s = x - c, bb = s - x;
    return (x - (s - bb)) + (-c - bb) == 0;
}

/* The rule (frame.h) on random boxes from near the origin to 1e12 extents away: an axis is moved
 * exactly when its centre is beyond 16 P, by a multiple of P within P/2 of the centre, and every
 * coordinate's local value is exact and within P of 0. */
static void test_rule(void **state) {
    (void)state;
    acd_rng rng;
    acd_rng_seed(&rng, 7);
    enum { N = 50 };
    double pts[3 * N];
    size_t moved = 0, kept = 0;
    for (int trial = 0; trial < 2000; trial++) {
        double E = ldexp(1.0 + acd_rng_uniform(&rng), (int)acd_rng_below(&rng, 40) - 20);
        double m[3];
        for (int k = 0; k < 3; k++)
            m[k] = (acd_rng_uniform(&rng) - 0.5) * E * pow(10.0, 13.0 * acd_rng_uniform(&rng));
        for (int i = 0; i < N; i++)
            for (int k = 0; k < 3; k++) pts[3 * i + k] = m[k] + (acd_rng_uniform(&rng) - 0.5) * E;
        acd_frame f;
        acd_geom3_frame_of(pts, N, &f);
        double lo[3], hi[3];
        for (int k = 0; k < 3; k++) {
            lo[k] = hi[k] = pts[k];
            for (int i = 1; i < N; i++) lo[k] = fmin(lo[k], pts[3 * i + k]), hi[k] = fmax(hi[k], pts[3 * i + k]);
        }
        double ext = fmax(fmax(hi[0] - lo[0], hi[1] - lo[1]), hi[2] - lo[2]);
        assert_true(f.extent == ext);
        int ex;
        (void)frexp(ext, &ex);
        double P = ldexp(1.0, ex);
        int any = 0;
        for (int k = 0; k < 3; k++) {
            double ctr = lo[k] + 0.5 * (hi[k] - lo[k]);
            if (f.c[k] == 0) {
                assert_true(fabs(ctr) <= ACD_FRAME_NEAR * P);
                kept++;
                continue;
            }
            any = 1;
            moved++;
            assert_true(fabs(ctr) > ACD_FRAME_NEAR * P);
            assert_true(fmod(f.c[k], P) == 0);
            assert_true(fabs(f.c[k] - ctr) <= 0.5 * P);
            for (int i = 0; i < N; i++) {
                assert_true(sub_exact(pts[3 * i + k], f.c[k]));
                assert_true(fabs(pts[3 * i + k] - f.c[k]) <= P);
            }
        }
        assert_int_equal(f.moved, any);
        /* to local and back: the points themselves */
        double q[3 * N];
        memcpy(q, pts, sizeof q);
        acd_geom3_frame_to_local(&f, q, N);
        acd_geom3_frame_to_model(&f, q, N);
        assert_memory_equal(q, pts, sizeof q);
    }
    assert_true(moved > 500 && kept > 500);
    /* a box like the data meshes' (the farthest, ChineseDragon: centre 8.7 extents along z): kept */
    double dragon[6] = {-56, -56, 926, 56, 56, 1039};
    acd_frame f;
    acd_geom3_frame_of(dragon, 2, &f);
    assert_false(f.moved);
}

/* A cube of side 1e-3 at 1e12 (8 spacings a side: far.off of the defect) is refused naming a vertex
 * and the ratio; a unit cube 1e9 away (4.5e6 steps) passes. */
static void test_resolution(void **state) {
    (void)state;
    double c[24];
    for (int i = 0; i < 8; i++)
        for (int k = 0; k < 3; k++) c[3 * i + k] = 1e12 + ((i >> k) & 1) * 1e-3;
    acd_frame f;
    acd_geom3_frame_of(c, 8, &f);
    acd_error err;
    acd_error_clear(&err);
    assert_int_equal(acd_geom3_frame_check(&f, c, "test", &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "vertex"));
    assert_non_null(strstr(err.message, "steps"));
    for (int i = 0; i < 8; i++)
        for (int k = 0; k < 3; k++) c[3 * i + k] = 1e9 + ((i >> k) & 1);
    acd_geom3_frame_of(c, 8, &f);
    assert_true(f.moved);
    assert_int_equal(acd_geom3_frame_check(&f, c, "test", &err), ACD_OK);
}

static void bumpy(acd_mesh *m) {
    assert_true(mg_radial(m, 24, 12, mg_bumpy_r, NULL));
    far_quantize(m, -20);
}

/* acd_mesh_volume_beyond: a plane z = 1/4 moved with the mesh (its offset exact) gives the near
 * volume (1e-12 relative: on today's code the clipped points took the far coordinates' spacing, an
 * error ~ulp(D) x area); a tilted plane, whose far offset is rounded, within 2 ulp(D) x the
 * section's area (at most the mesh's area). */
static void test_volume_beyond(void **state) {
    (void)state;
    acd_mesh near;
    bumpy(&near);
    const double E = far_extent(&near);
    double area;
    const double o[3] = {0, 0, 0};
    (void)far_volume_about(&near, o, &area);
    const double pz[4] = {0, 0, 1, -0.25}, pt[4] = {0.6, 0, 0.8, -0.1};
    const double vz = acd_mesh_volume_beyond(&near, pz), vt = acd_mesh_volume_beyond(&near, pt);
    assert_true(vz > 0.1 && vt > 0.1);
    for (int r = 0; r < 3; r++) {
        acd_mesh far;
        acd_error err;
        assert_int_equal(acd_mesh_copy(&far, &near, &err), ACD_OK);
        double D[3];
        far_offset(E, RATIOS[r], DIR, D);
        far_translate_exact(&far, D);
        double fz[4] = {0, 0, 1, -0.25 - D[2]};
        assert_true(fz[3] + D[2] == -0.25);
        double wz = acd_mesh_volume_beyond(&far, fz);
        assert_true(fabs(wz - vz) <= 1e-12 * vz);
        double ft[4] = {0.6, 0, 0.8, -0.1 - (0.6 * D[0] + 0.8 * D[2])};
        double wt = acd_mesh_volume_beyond(&far, ft);
        double u = far_spacing(far.vertices, far.nvertices);
        assert_true(fabs(wt - vt) <= 1e-12 * vt + 2 * u * area);
        acd_mesh_free(&far);
    }
    acd_mesh_free(&near);
}

/* acd_hull_volume_outside and its bound: the bumpy sphere outside the hull of a cube of side 1.5,
 * near and moved exactly with the cube, whose planes are exact in model coordinates too (axis
 * normals, offsets -(0.75 + D): checked): the far volumes are the near ones to 1e-12 relative (on
 * today's code 1e-9 off at 1e8 extents, the cuts' points at the model coordinates' spacing). */
static void test_hull_outside(void **state) {
    (void)state;
    acd_mesh near;
    bumpy(&near);
    const double E = far_extent(&near);
    double cube[24];
    for (int i = 0; i < 8; i++)
        for (int k = 0; k < 3; k++) cube[3 * i + k] = ((i >> k) & 1) ? 0.75 : -0.75;
    acd_hull h0;
    acd_error err;
    assert_int_equal(acd_hull_compute(cube, 8, &h0, &err), ACD_OK);
    double v0, b0 = acd_hull_volume_outside_bound(&h0, &near, 1e-9, 1);
    assert_int_equal(acd_hull_volume_outside(&h0, &near, 1e-9, 1, &v0, &err), ACD_OK);
    assert_true(v0 > 0.5 && b0 >= v0 * (1 - 1e-9));
    for (int r = 0; r < 3; r++) {
        acd_mesh far;
        assert_int_equal(acd_mesh_copy(&far, &near, &err), ACD_OK);
        double D[3], fc[24];
        far_offset(E, RATIOS[r], DIR, D);
        far_translate_exact(&far, D);
        for (int i = 0; i < 8; i++)
            for (int k = 0; k < 3; k++) fc[3 * i + k] = cube[3 * i + k] + D[k];
        acd_hull h1;
        assert_int_equal(acd_hull_compute(fc, 8, &h1, &err), ACD_OK);
        for (size_t t = 0; t < h1.ntriangles; t++) { /* the planes exact: n an axis, n.D + d = -0.75 */
            const double *q = h1.planes + 4 * t;
            assert_true(fabs(q[0]) + fabs(q[1]) + fabs(q[2]) == 1 && (q[0] == 0) + (q[1] == 0) + (q[2] == 0) == 2);
            assert_true(q[0] * D[0] + q[1] * D[1] + q[2] * D[2] + q[3] == -0.75);
        }
        const double u = far_spacing(far.vertices, far.nvertices);
        double v1, b1 = acd_hull_volume_outside_bound(&h1, &far, 1e-9 + 4 * u, 1);
        assert_int_equal(acd_hull_volume_outside(&h1, &far, 1e-9 + 4 * u, 1, &v1, &err), ACD_OK);
        assert_true(fabs(v1 - v0) <= 1e-12 * v0);
        assert_true(fabs(b1 - b0) <= 1e-12 * b0);
        acd_hull_free(&h1);
        acd_mesh_free(&far);
    }
    acd_hull_free(&h0);
    acd_mesh_free(&near);
}

/* The input's volume as acd_segment, acd_mesh_validate and acd_eval_hulls report it: far as near, 1e-12
 * relative (acd_segment summed about the origin: fandisk 1e6 extents away gave 1.3e-4 of it). */
static void test_mesh_volumes(void **state) {
    (void)state;
    acd_mesh near;
    bumpy(&near);
    const double E = far_extent(&near);
    acd_error err;
    acd_segment_params sp = acd_segment_default_params();
    acd_segment_result s0;
    assert_int_equal(acd_segment(&near, &sp, &s0, &err), ACD_OK);
    acd_mesh_report r0;
    assert_int_equal(acd_mesh_validate(&near, 0, &r0, &err), ACD_OK);
    const double v0 = s0.mesh_volume;
    assert_true(v0 > 1 && fabs(r0.volume - v0) <= 1e-12 * v0);
    acd_hull hn;
    assert_int_equal(acd_hull_compute(near.vertices, near.nvertices, &hn, &err), ACD_OK);
    acd_eval_params ep = acd_eval_default_params();
    ep.samples = 1000;
    acd_eval_report e0;
    assert_int_equal(acd_eval_hulls(&near, &hn, 1, &ep, &e0, &err), ACD_OK);
    assert_true(fabs(e0.mesh_volume - v0) <= 1e-12 * v0);
    for (int r = 0; r < 3; r++) {
        acd_mesh far;
        assert_int_equal(acd_mesh_copy(&far, &near, &err), ACD_OK);
        double D[3];
        far_offset(E, RATIOS[r], DIR, D);
        far_translate_exact(&far, D);
        acd_segment_result s1;
        assert_int_equal(acd_segment(&far, &sp, &s1, &err), ACD_OK);
        assert_true(fabs(s1.mesh_volume - v0) <= 1e-12 * v0);
        /* the hulls are the input's own points: their volumes as near */
        assert_true(fabs(s1.hull_volume / s1.mesh_volume - s0.hull_volume / v0) <= 1e-6);
        acd_mesh_report r1;
        assert_int_equal(acd_mesh_validate(&far, 0, &r1, &err), ACD_OK);
        assert_true(fabs(r1.volume - v0) <= 1e-12 * v0);
        acd_hull hf;
        assert_int_equal(acd_hull_compute(far.vertices, far.nvertices, &hf, &err), ACD_OK);
        assert_true(fabs(hf.volume - hn.volume) <= 1e-9 * hn.volume);
        acd_eval_report e1;
        assert_int_equal(acd_eval_hulls(&far, &hf, 1, &ep, &e1, &err), ACD_OK);
        assert_true(fabs(e1.mesh_volume - v0) <= 1e-12 * v0);
        acd_hull_free(&hf);
        acd_mesh_report_free(&r1);
        acd_segment_result_free(&s1);
        acd_mesh_free(&far);
    }
    acd_hull_free(&hn);
    acd_mesh_report_free(&r0);
    acd_segment_result_free(&s0);
    acd_mesh_free(&near);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rule),
        cmocka_unit_test(test_resolution),
        cmocka_unit_test(test_volume_beyond),
        cmocka_unit_test(test_hull_outside),
        cmocka_unit_test(test_mesh_volumes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
