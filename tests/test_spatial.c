/* Tests of geom3/spatial: inside/outside by exact ray crossings (degenerate rays through edges
 * and vertices included), generalized winding number against brute force and on open meshes,
 * distances with known values. */
#include "testutil.h"

#include <math.h>

#include "core/rng.h"
#include "geom3/spatial.h"
#include "meshgen.h"

static void test_box_inside_outside_exact(void **state) {
    (void)state;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    tm_mesh m = tm_box(lo, hi);
    acd_spatial sp;
    assert_int_equal(acd_spatial_build(&sp, m.v, m.nv, m.t, m.nt, NULL), ACD_OK);
    assert_true(sp.closed);
    assert_int_equal(sp.boundary_edges, 0);
    acd_rng r;
    acd_rng_seed(&r, 3);
    for (int i = 0; i < 20000; i++) {
        double p[3];
        for (int k = 0; k < 3; k++) p[k] = 1.4 * acd_rng_uniform(&r) - 0.2;
        /* every third point on a line through the face diagonals or the box edges */
        if (i % 3 == 1) p[1] = p[2] = 0.5;
        if (i % 3 == 2) p[1] = p[2];
        int in = p[0] > 0 && p[0] < 1 && p[1] > 0 && p[1] < 1 && p[2] > 0 && p[2] < 1;
        int c = acd_spatial_classify(&sp, p);
        if (p[1] > 0 && p[1] < 1 && p[2] > 0 && p[2] < 1 && (p[0] == 0 || p[0] == 1))
            assert_int_equal(c, ACD_SPATIAL_ON_SURFACE);
        else
            assert_int_equal(c, in ? ACD_SPATIAL_INSIDE : ACD_SPATIAL_OUTSIDE);
        /* the winding number is exactly 1 or 0: each crossing counted once */
        assert_true(acd_spatial_winding_number(&sp, p) == (in ? 1.0 : 0.0));
    }
    /* points on the x faces, on their diagonal included, are on the surface */
    double on1[3] = {1, 0.25, 0.75}, on2[3] = {0, 0.5, 0.5}, in1[3] = {0.5, 0.5, 0.5};
    assert_int_equal(acd_spatial_classify(&sp, on1), ACD_SPATIAL_ON_SURFACE);
    assert_int_equal(acd_spatial_classify(&sp, on2), ACD_SPATIAL_ON_SURFACE);
    assert_int_equal(acd_spatial_classify(&sp, in1), ACD_SPATIAL_INSIDE);
    /* distances */
    assert_true(fabs(acd_spatial_distance(&sp, in1, NULL) - 0.5) < 1e-15);
    assert_true(fabs(acd_spatial_signed_distance(&sp, in1) + 0.5) < 1e-15);
    double out[3] = {3, 0.5, 0.5}, corner[3] = {2, 2, 2};
    assert_true(fabs(acd_spatial_signed_distance(&sp, out) - 2.0) < 1e-15);
    assert_true(fabs(acd_spatial_distance(&sp, corner, NULL) - sqrt(3.0)) < 1e-14);
    acd_spatial_free(&sp);
    tm_free(&m);
}

static void test_ray_through_vertex(void **state) {
    (void)state;
    tm_mesh m = tm_octahedron();
    acd_spatial sp;
    assert_int_equal(acd_spatial_build(&sp, m.v, m.nv, m.t, m.nt, NULL), ACD_OK);
    /* from the centre the +x ray leaves through the vertex shared by four triangles */
    double c[3] = {0, 0, 0};
    int on = 0;
    assert_int_equal(acd_spatial_ray_winding(&sp, c, &on), 1);
    assert_int_equal(on, 0);
    /* along the x axis outside: the ray passes through both x vertices */
    double o[3] = {-2, 0, 0};
    assert_int_equal(acd_spatial_ray_winding(&sp, o, &on), 0);
    /* the vertex itself is on the surface */
    double v[3] = {1, 0, 0};
    assert_int_equal(acd_spatial_classify(&sp, v), ACD_SPATIAL_ON_SURFACE);
    /* the line machinery gives the same winding numbers */
    acd_spatial_line line = {0};
    assert_int_equal(acd_spatial_line_set(&sp, 0, 0, &line, NULL), ACD_OK);
    assert_int_equal(acd_spatial_line_winding(&sp, &line, -2, NULL), 0);
    assert_int_equal(acd_spatial_line_winding(&sp, &line, 0, NULL), 1);
    assert_int_equal(acd_spatial_line_winding(&sp, &line, 0.999, NULL), 1);
    assert_int_equal(acd_spatial_line_winding(&sp, &line, 1.001, NULL), 0);
    acd_spatial_line_free(&line);
    acd_spatial_free(&sp);
    tm_free(&m);
}

static double torus_sdf(const double p[3], double R, double r) {
    double q = sqrt(p[0] * p[0] + p[1] * p[1]) - R;
    return sqrt(q * q + p[2] * p[2]) - r;
}

static double brute_gwn(const tm_mesh *m, const double q[3]) {
    double w = 0;
    for (size_t t = 0; t < m->nt; t++) {
        double a[3], b[3], c[3];
        for (int k = 0; k < 3; k++) {
            a[k] = m->v[3 * m->t[3 * t] + k] - q[k];
            b[k] = m->v[3 * m->t[3 * t + 1] + k] - q[k];
            c[k] = m->v[3 * m->t[3 * t + 2] + k] - q[k];
        }
        double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]),
               lc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                     a[2] * (b[0] * c[1] - b[1] * c[0]);
        double den = la * lb * lc + (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) * lc +
                     (a[0] * c[0] + a[1] * c[1] + a[2] * c[2]) * lb + (b[0] * c[0] + b[1] * c[1] + b[2] * c[2]) * la;
        w += 2 * atan2(det, den);
    }
    return w / (4 * 3.14159265358979323846);
}

static void test_torus_ray_and_gwn(void **state) {
    (void)state;
    tm_mesh m = tm_torus(1.0, 0.4, 64, 32);
    acd_spatial sp;
    assert_int_equal(acd_spatial_build(&sp, m.v, m.nv, m.t, m.nt, NULL), ACD_OK);
    assert_true(sp.closed);
    acd_rng r;
    acd_rng_seed(&r, 17);
    double maxerr = 0;
    int inside = 0;
    for (int i = 0; i < 3000; i++) {
        double p[3] = {3.2 * acd_rng_uniform(&r) - 1.6, 3.2 * acd_rng_uniform(&r) - 1.6, acd_rng_uniform(&r) - 0.5};
        if (i % 50 == 0) p[1] = 0; /* rays along the grid's vertex rows */
        double sdf = torus_sdf(p, 1.0, 0.4);
        int c = acd_spatial_classify(&sp, p);
        if (fabs(sdf) > 0.01) assert_int_equal(c, sdf < 0 ? ACD_SPATIAL_INSIDE : ACD_SPATIAL_OUTSIDE);
        inside += c == ACD_SPATIAL_INSIDE;
        if (i % 5 == 0) {
            double g = acd_spatial_gwn(&sp, p), e = brute_gwn(&m, p);
            double err = fabs(g - e);
            if (err > maxerr) maxerr = err;
            if (fabs(sdf) > 0.01) assert_true(fabs(g - (sdf < 0 ? 1.0 : 0.0)) < 0.02);
            /* the coarse far field used by eval3d still gives the right side */
            if (fabs(sdf) > 0.01) assert_int_equal(fabs(acd_spatial_gwn_beta(&sp, p, 2.0)) >= 0.5, sdf < 0);
        }
    }
    assert_true(inside > 200);
    assert_true(maxerr < 0.01);
    print_message("torus: max |hierarchical - exact| generalized winding number %.2e\n", maxerr);
    acd_spatial_free(&sp);
    tm_free(&m);
}

static void test_open_and_reversed_meshes(void **state) {
    (void)state;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    tm_mesh m = tm_box(lo, hi);
    /* drop the top face (the last but... triangles 2 and 3 are z = hi) */
    memmove(m.t + 6, m.t + 12, (36 - 12) * sizeof(uint32_t));
    m.nt = 10;
    acd_spatial sp;
    assert_int_equal(acd_spatial_build(&sp, m.v, m.nv, m.t, m.nt, NULL), ACD_OK);
    assert_false(sp.closed);
    assert_int_equal(sp.boundary_edges, 4);
    double c[3] = {0.5, 0.5, 0.5}, low[3] = {0.5, 0.5, 0.1}, out[3] = {0.5, 0.5, -0.5}, far[3] = {5, 5, 5};
    assert_true(fabs(acd_spatial_winding_number(&sp, c) - 5.0 / 6.0) < 1e-3);
    assert_int_equal(acd_spatial_classify(&sp, c), ACD_SPATIAL_INSIDE);
    assert_int_equal(acd_spatial_classify(&sp, low), ACD_SPATIAL_INSIDE);
    assert_int_equal(acd_spatial_classify(&sp, out), ACD_SPATIAL_OUTSIDE);
    assert_int_equal(acd_spatial_classify(&sp, far), ACD_SPATIAL_OUTSIDE);
    acd_spatial_free(&sp);
    tm_free(&m);
    /* inside-out box: winding -1 inside, still inside */
    m = tm_box(lo, hi);
    for (size_t t = 0; t < m.nt; t++) {
        uint32_t x = m.t[3 * t + 1];
        m.t[3 * t + 1] = m.t[3 * t + 2];
        m.t[3 * t + 2] = x;
    }
    assert_int_equal(acd_spatial_build(&sp, m.v, m.nv, m.t, m.nt, NULL), ACD_OK);
    assert_true(acd_spatial_winding_number(&sp, c) == -1.0);
    assert_int_equal(acd_spatial_classify(&sp, c), ACD_SPATIAL_INSIDE);
    assert_true(acd_spatial_signed_distance(&sp, c) < 0);
    acd_spatial_free(&sp);
    tm_free(&m);
}

static void test_soup_is_closed(void **state) {
    (void)state;
    /* the box with three vertices per triangle (an unwelded soup) is still closed */
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    tm_mesh m = tm_box(lo, hi);
    double *v = malloc(3 * 3 * m.nt * sizeof(double));
    uint32_t *t = malloc(3 * m.nt * sizeof(uint32_t));
    assert_non_null(v);
    assert_non_null(t);
    for (size_t i = 0; i < 3 * m.nt; i++) {
        memcpy(v + 3 * i, m.v + 3 * m.t[i], 3 * sizeof(double));
        t[i] = (uint32_t)i;
    }
    acd_spatial sp;
    assert_int_equal(acd_spatial_build(&sp, v, 3 * m.nt, t, m.nt, NULL), ACD_OK);
    assert_true(sp.closed);
    double c[3] = {0.5, 0.5, 0.5}, d[3] = {0.5, 0.5, 0.5 + 1e-9}, o[3] = {1.5, 0.5, 0.5};
    assert_int_equal(acd_spatial_classify(&sp, c), ACD_SPATIAL_INSIDE);
    assert_int_equal(acd_spatial_classify(&sp, d), ACD_SPATIAL_INSIDE);
    assert_int_equal(acd_spatial_classify(&sp, o), ACD_SPATIAL_OUTSIDE);
    acd_spatial_free(&sp);
    free(v);
    free(t);
    tm_free(&m);
}

static void test_line_matches_ray(void **state) {
    (void)state;
    tm_mesh m = tm_torus(1.0, 0.4, 24, 12);
    acd_spatial sp;
    assert_int_equal(acd_spatial_build(&sp, m.v, m.nv, m.t, m.nt, NULL), ACD_OK);
    acd_spatial_line line = {0};
    acd_rng r;
    acd_rng_seed(&r, 23);
    for (int i = 0; i < 200; i++) {
        double y = 3.2 * acd_rng_uniform(&r) - 1.6, z = acd_rng_uniform(&r) - 0.5;
        if (i % 20 == 0) y = 0, z = 0;
        assert_int_equal(acd_spatial_line_set(&sp, y, z, &line, NULL), ACD_OK);
        for (int j = 0; j < 20; j++) {
            double p[3] = {3.2 * acd_rng_uniform(&r) - 1.6, y, z};
            assert_int_equal(acd_spatial_line_winding(&sp, &line, p[0], NULL), acd_spatial_ray_winding(&sp, p, NULL));
        }
    }
    acd_spatial_line_free(&line);
    acd_spatial_free(&sp);
    tm_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_box_inside_outside_exact),
        cmocka_unit_test(test_ray_through_vertex),
        cmocka_unit_test(test_torus_ray_and_gwn),
        cmocka_unit_test(test_open_and_reversed_meshes),
        cmocka_unit_test(test_soup_is_closed),
        cmocka_unit_test(test_line_matches_ray),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
