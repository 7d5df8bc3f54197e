/* Tests of geom3/hull: the qhull wrapper checked against brute force (every triple of points whose
 * plane has all points on one side) on random points, and on degenerate sets: 0-3 points,
 * duplicates, collinear, coplanar, huge and tiny coordinates, NaN. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "core/predicates.h"
#include "core/rng.h"
#include "geom3/bvh.h"
#include "hull_winding.h"

static double extent_of(const double *p, size_t n) {
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            if (i == 0 || p[3 * i + k] < lo[k]) lo[k] = p[3 * i + k];
            if (i == 0 || p[3 * i + k] > hi[k]) hi[k] = p[3 * i + k];
        }
    double d = 0;
    for (int k = 0; k < 3; k++) d += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    return sqrt(d);
}

/* Structural checks valid for every dim 3 hull: vertices are input points, closed 2-manifold with
 * consistent neighbours, every input point inside every facet plane within tol, Euler. */
static void check_solid_hull(const acd_hull *h, const double *pts, size_t n) {
    assert_int_equal(h->dim, 3);
    double tol = 1e-10 * extent_of(pts, n);
    for (size_t v = 0; v < h->nvertices; v++) {
        assert_true(h->source[v] < n);
        assert_memory_equal(h->vertices + 3 * v, pts + 3 * h->source[v], 3 * sizeof(double));
    }
    assert_int_equal(h->ntriangles, 2 * h->nvertices - 4); /* Euler for a triangulated sphere */
    for (size_t t = 0; t < h->ntriangles; t++) {
        const uint32_t *tri = h->triangles + 3 * t;
        for (int e = 0; e < 3; e++) {
            uint32_t a = tri[e], b = tri[(e + 1) % 3];
            assert_true(a < h->nvertices);
            uint32_t u = h->neighbors[3 * t + e];
            assert_true(u < h->ntriangles);
            const uint32_t *ot = h->triangles + 3 * u;
            int found = 0;
            for (int f = 0; f < 3; f++)
                if (ot[f] == b && ot[(f + 1) % 3] == a) {
                    found = 1;
                    assert_int_equal(h->neighbors[3 * u + f], t);
                }
            assert_true(found);
        }
        const double *pl = h->planes + 4 * t;
        assert_true(fabs(pl[0] * pl[0] + pl[1] * pl[1] + pl[2] * pl[2] - 1) < 1e-12);
        for (size_t i = 0; i < n; i++) {
            double v = pl[0] * pts[3 * i] + pl[1] * pts[3 * i + 1] + pl[2] * pts[3 * i + 2] + pl[3];
            if (v > tol) print_message("point %zu is %g outside facet %zu (tol %g)\n", i, v, t, tol);
            assert_true(v <= tol);
        }
        /* vertices lie on the plane */
        for (int k = 0; k < 3; k++) {
            const double *q = h->vertices + 3 * tri[k];
            assert_true(fabs(pl[0] * q[0] + pl[1] * q[1] + pl[2] * q[2] + pl[3]) <= tol);
        }
    }
}

/* Brute force for points in general position: facets are the triples with all points on one side. */
static void brute_hull(const double *p, size_t n, size_t *nfacets, double *volume, int *is_vertex) {
    double o[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) o[k] += p[3 * i + k] / (double)n;
    size_t nf = 0;
    double vol = 0;
    for (size_t i = 0; i < n; i++) is_vertex[i] = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++)
            for (size_t k = j + 1; k < n; k++) {
                int pos = 0, neg = 0;
                for (size_t m = 0; m < n && !(pos && neg); m++) {
                    if (m == i || m == j || m == k) continue;
                    int s = acd_orient3d_sign(p + 3 * i, p + 3 * j, p + 3 * k, p + 3 * m);
                    pos += s > 0;
                    neg += s < 0;
                }
                if (pos && neg) continue;
                nf++;
                is_vertex[i] = is_vertex[j] = is_vertex[k] = 1;
                double a[3], b[3], c[3];
                for (int q = 0; q < 3; q++) {
                    a[q] = p[3 * i + q] - o[q];
                    b[q] = p[3 * j + q] - o[q];
                    c[q] = p[3 * k + q] - o[q];
                }
                double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                             a[2] * (b[0] * c[1] - b[1] * c[0]);
                vol += fabs(det) / 6.0;
            }
    *nfacets = nf;
    *volume = vol;
}

static void test_random_vs_brute_force(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 11);
    for (int trial = 0; trial < 40; trial++) {
        size_t n = 4 + (size_t)acd_rng_below(&r, 50);
        double *p = malloc(3 * n * sizeof *p);
        int *isv = malloc(n * sizeof *isv);
        assert_non_null(p);
        assert_non_null(isv);
        int sphere = trial % 3 == 0;
        for (size_t i = 0; i < n; i++) {
            for (int k = 0; k < 3; k++) p[3 * i + k] = 2 * acd_rng_uniform(&r) - 1;
            if (sphere) { /* many points on the hull */
                double l = sqrt(p[3 * i] * p[3 * i] + p[3 * i + 1] * p[3 * i + 1] + p[3 * i + 2] * p[3 * i + 2]);
                for (int k = 0; k < 3; k++) p[3 * i + k] /= l;
            }
        }
        acd_hull h;
        acd_error err;
        assert_int_equal(acd_hull_compute(p, n, &h, &err), ACD_OK);
        check_solid_hull(&h, p, n);
        size_t nf;
        double vol;
        brute_hull(p, n, &nf, &vol, isv);
        assert_int_equal(h.ntriangles, nf);
        assert_true(fabs(h.volume - vol) <= 1e-12 * vol);
        size_t nv = 0;
        for (size_t i = 0; i < n; i++) nv += (size_t)isv[i];
        assert_int_equal(h.nvertices, nv);
        for (size_t v = 0; v < h.nvertices; v++) assert_true(isv[h.source[v]]);
        /* triangles outward: every point on the inner side, decided exactly */
        for (size_t t = 0; t < h.ntriangles; t++) {
            const uint32_t *tri = h.triangles + 3 * t;
            for (size_t i = 0; i < n; i++)
                assert_true(acd_orient3d_sign(h.vertices + 3 * tri[0], h.vertices + 3 * tri[1], h.vertices + 3 * tri[2],
                                              p + 3 * i) >= 0);
        }
        acd_hull_free(&h);
        free(p);
        free(isv);
    }
}

static void test_large_random_cloud(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 12);
    size_t n = 20000;
    double *p = malloc(3 * n * sizeof *p);
    assert_non_null(p);
    for (size_t i = 0; i < 3 * n; i++) p[i] = acd_rng_uniform(&r);
    acd_hull h, h2;
    acd_error err;
    assert_int_equal(acd_hull_compute(p, n, &h, &err), ACD_OK);
    check_solid_hull(&h, p, n);
    assert_true(h.volume > 0.95 && h.volume <= 1.0);
    /* determinism */
    assert_int_equal(acd_hull_compute(p, n, &h2, &err), ACD_OK);
    assert_int_equal(h.ntriangles, h2.ntriangles);
    assert_memory_equal(h.triangles, h2.triangles, 3 * h.ntriangles * sizeof(uint32_t));
    assert_memory_equal(h.planes, h2.planes, 4 * h.ntriangles * sizeof(double));
    acd_hull_free(&h);
    acd_hull_free(&h2);
    free(p);
}

/* A unit cube's corners, plus points on its faces and edges, interior points and duplicates. */
static size_t cube_cloud(double *p, acd_rng *r, double scale, double off) {
    size_t n = 0;
    for (int c = 0; c < 8; c++) {
        p[3 * n] = c & 1;
        p[3 * n + 1] = (c >> 1) & 1;
        p[3 * n + 2] = (c >> 2) & 1;
        n++;
    }
    for (int i = 0; i < 60; i++) { /* on faces (exactly coplanar with facets) */
        int ax = i % 3;
        for (int k = 0; k < 3; k++) p[3 * n + k] = acd_rng_uniform(r);
        p[3 * n + ax] = (i / 3) % 2;
        n++;
    }
    for (int i = 0; i < 12; i++) { /* on edges */
        for (int k = 0; k < 3; k++) p[3 * n + k] = (i >> k) & 1;
        p[3 * n + i % 3] = 0.25 + 0.5 * acd_rng_uniform(r);
        n++;
    }
    for (int i = 0; i < 30; i++, n++)
        for (int k = 0; k < 3; k++) p[3 * n + k] = 0.1 + 0.8 * acd_rng_uniform(r);
    for (int i = 0; i < 8; i++, n++) memcpy(p + 3 * n, p + 3 * (size_t)i, 3 * sizeof(double)); /* duplicates */
    for (size_t i = 0; i < 3 * n; i++) p[i] = p[i] * scale + off;
    return n;
}

static void test_cube_with_coplanar_and_duplicates(void **state) {
    (void)state;
    double scales[][2] = {{1, 0}, {1e100, 3e100}, {1e-100, -7e-100}, {1e6, 1e9}};
    for (size_t s = 0; s < sizeof scales / sizeof scales[0]; s++) {
        acd_rng r;
        acd_rng_seed(&r, 13);
        double p[3 * 200];
        size_t n = cube_cloud(p, &r, scales[s][0], scales[s][1]);
        acd_hull h;
        acd_error err;
        assert_int_equal(acd_hull_compute(p, n, &h, &err), ACD_OK);
        check_solid_hull(&h, p, n);
        double sc = scales[s][0];
        assert_int_equal(h.nvertices, 8);
        if (!(fabs(h.volume / (sc * sc * sc) - 1) < 1e-9)) print_message("scale %g: volume %.17g nv %zu\n", sc, h.volume / (sc * sc * sc), h.nvertices);
        assert_true(fabs(h.volume / (sc * sc * sc) - 1) < 1e-9);
        assert_true(fabs(h.area / (sc * sc) - 6) < 1e-9);
        /* distances: centre inside by half a side, a point outside by 2 sides */
        double c[3] = {0.5 * sc + scales[s][1], 0.5 * sc + scales[s][1], 0.5 * sc + scales[s][1]};
        assert_true(fabs(acd_hull_plane_distance(&h, c) / sc + 0.5) < 1e-9);
        c[0] = 3 * sc + scales[s][1];
        assert_true(fabs(acd_hull_plane_distance(&h, c) / sc - 2) < 1e-9);
        acd_hull_free(&h);
    }
}

static void test_few_points(void **state) {
    (void)state;
    acd_hull h;
    acd_error err;
    assert_int_equal(acd_hull_compute(NULL, 0, &h, &err), ACD_OK);
    assert_int_equal(h.dim, -1);
    assert_int_equal(h.nvertices, 0);
    assert_true(isinf(acd_hull_plane_distance(&h, (double[3]){0, 0, 0})));
    acd_hull_free(&h);

    double one[3] = {1, 2, 3};
    assert_int_equal(acd_hull_compute(one, 1, &h, &err), ACD_OK);
    assert_int_equal(h.dim, 0);
    assert_int_equal(h.nvertices, 1);
    assert_int_equal(h.ntriangles, 0);
    assert_true(fabs(acd_hull_plane_distance(&h, (double[3]){1, 2, 5}) - 2) < 1e-15);
    acd_hull_free(&h);

    double same[9] = {1, 2, 3, 1, 2, 3, 1, 2, 3};
    assert_int_equal(acd_hull_compute(same, 3, &h, &err), ACD_OK);
    assert_int_equal(h.dim, 0);
    assert_int_equal(h.nvertices, 1);
    acd_hull_free(&h);

    double two[6] = {0, 0, 0, 1, 1, 1};
    assert_int_equal(acd_hull_compute(two, 2, &h, &err), ACD_OK);
    assert_int_equal(h.dim, 1);
    assert_int_equal(h.nvertices, 2);
    assert_int_equal(h.source[0], 0);
    assert_int_equal(h.source[1], 1);
    assert_true(fabs(acd_hull_plane_distance(&h, (double[3]){2, 2, 2}) - sqrt(3)) < 1e-15);
    acd_hull_free(&h);

    double three[9] = {0, 0, 0, 2, 0, 0, 0, 3, 1};
    assert_int_equal(acd_hull_compute(three, 3, &h, &err), ACD_OK);
    assert_int_equal(h.dim, 2);
    assert_int_equal(h.nvertices, 3);
    assert_int_equal(h.ntriangles, 1);
    assert_true(fabs(h.area - 0.5 * 2 * sqrt(10)) < 1e-14);
    assert_true(h.volume == 0);
    for (int e = 0; e < 3; e++) assert_int_equal(h.neighbors[e], ACD_HULL_NO_NEIGHBOR);
    assert_true(fabs(acd_hull_plane_distance(&h, (double[3]){0.5, 0.3, 0.1})) < 1e-15);
    acd_hull_free(&h);

    double tet[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    assert_int_equal(acd_hull_compute(tet, 4, &h, &err), ACD_OK);
    check_solid_hull(&h, tet, 4);
    assert_true(fabs(h.volume - 1.0 / 6) < 1e-15);
    acd_hull_free(&h);
}

static void test_collinear(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 14);
    double p[3 * 50];
    size_t imin = 0, imax = 0;
    double tmin = 2, tmax = -1;
    for (size_t i = 0; i < 50; i++) {
        double t = acd_rng_uniform(&r);
        if (i == 7) t = tmin < 2 ? tmin : t; /* a duplicate of an earlier extreme */
        p[3 * i] = 1 + 0.3 * t;
        p[3 * i + 1] = -2 + 0.7 * t;
        p[3 * i + 2] = 5 - 0.1 * t;
        if (t < tmin) tmin = t, imin = i;
        if (t > tmax) tmax = t, imax = i;
    }
    acd_hull h;
    acd_error err;
    assert_int_equal(acd_hull_compute(p, 50, &h, &err), ACD_OK);
    assert_int_equal(h.dim, 1);
    assert_int_equal(h.nvertices, 2);
    uint32_t a = h.source[0], b = h.source[1];
    assert_true((a == imin && b == imax) || (a == imax && b == imin));
    acd_hull_free(&h);
}

static void test_coplanar(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 15);
    for (int trial = 0; trial < 10; trial++) {
        size_t n = 3 + (size_t)acd_rng_below(&r, 60);
        double U[3] = {1, 2, -0.5}, V[3] = {-0.3, 0.4, 2}, O[3] = {10, -20, 3};
        double scale = trial % 2 ? 1e-120 : 1e120;
        double *uv = malloc(2 * n * sizeof *uv), *p = malloc(3 * n * sizeof *p);
        assert_non_null(uv);
        assert_non_null(p);
        for (size_t i = 0; i < n; i++) {
            uv[2 * i] = acd_rng_uniform(&r);
            uv[2 * i + 1] = acd_rng_uniform(&r);
            if (i > 0 && i % 5 == 0) memcpy(uv + 2 * i, uv, 2 * sizeof(double)); /* duplicates */
            for (int k = 0; k < 3; k++) p[3 * i + k] = (O[k] + uv[2 * i] * U[k] + uv[2 * i + 1] * V[k]) * scale;
        }
        /* brute force 2D hull area in (u, v) */
        double area2 = 0;
        for (size_t i = 0; i < n; i++)
            for (size_t j = 0; j < n; j++) {
                if ((i > 0 && i % 5 == 0) || (j > 0 && j % 5 == 0)) continue; /* copies of point 0 */
                if (uv[2 * i] == uv[2 * j] && uv[2 * i + 1] == uv[2 * j + 1]) continue;
                int ok = 1;
                for (size_t k = 0; k < n && ok; k++)
                    if (acd_orient2d(uv + 2 * i, uv + 2 * j, uv + 2 * k) < 0) ok = 0;
                if (ok) area2 += uv[2 * i] * uv[2 * j + 1] - uv[2 * j] * uv[2 * i + 1];
            }
        double cr[3] = {U[1] * V[2] - U[2] * V[1], U[2] * V[0] - U[0] * V[2], U[0] * V[1] - U[1] * V[0]};
        double expect = 0.5 * area2 * sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]) * scale * scale;
        acd_hull h;
        acd_error err;
        assert_int_equal(acd_hull_compute(p, n, &h, &err), ACD_OK);
        if (n == 3 && expect == 0) {
            acd_hull_free(&h);
            free(uv);
            free(p);
            continue;
        }
        assert_int_equal(h.dim, 2);
        assert_int_equal(h.ntriangles, h.nvertices - 2);
        if (!(fabs(h.area - expect) <= 1e-9 * expect)) print_message("n %zu area %.17g expect %.17g\n", n, h.area, expect);
        assert_true(fabs(h.area - expect) <= 1e-9 * expect);
        double tol = 1e-10 * extent_of(p, n);
        for (size_t i = 0; i < n; i++) assert_true(acd_hull_plane_distance(&h, p + 3 * i) <= tol);
        for (size_t v = 0; v < h.nvertices; v++)
            assert_memory_equal(h.vertices + 3 * v, p + 3 * h.source[v], 3 * sizeof(double));
        acd_hull_free(&h);
        free(uv);
        free(p);
    }
    /* a square: 4 coplanar points */
    double sq[12] = {0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
    acd_hull h;
    assert_int_equal(acd_hull_compute(sq, 4, &h, NULL), ACD_OK);
    assert_int_equal(h.dim, 2);
    assert_int_equal(h.nvertices, 4);
    assert_true(fabs(h.area - 1) < 1e-15);
    assert_true(fabs(acd_hull_plane_distance(&h, (double[3]){0.5, 0.5, 3}) - 2) < 1e-15);
    assert_true(fabs(acd_hull_plane_distance(&h, (double[3]){2, 0.5, 1}) - 1) < 1e-15);
    acd_hull_free(&h);
}

static void test_nearly_flat(void **state) {
    (void)state;
    /* a slab much thinner than the dimension tolerance is planar; a thin but real one is solid */
    acd_rng r;
    acd_rng_seed(&r, 16);
    double p[3 * 100];
    for (int thick = 0; thick < 2; thick++) {
        double eps = thick ? 1e-6 : 1e-14;
        for (int i = 0; i < 100; i++) {
            p[3 * i] = acd_rng_uniform(&r);
            p[3 * i + 1] = acd_rng_uniform(&r);
            p[3 * i + 2] = eps * acd_rng_uniform(&r);
        }
        acd_hull h;
        acd_error err;
        assert_int_equal(acd_hull_compute(p, 100, &h, &err), ACD_OK);
        assert_int_equal(h.dim, thick ? 3 : 2);
        if (thick) check_solid_hull(&h, p, 100);
        acd_hull_free(&h);
    }
}

static void test_edges(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 17);
    double p[3 * 40];
    for (int i = 0; i < 120; i++) p[i] = acd_rng_uniform(&r);
    acd_hull h;
    acd_hull_edge *e;
    size_t ne;
    assert_int_equal(acd_hull_compute(p, 40, &h, NULL), ACD_OK);
    assert_int_equal(acd_hull_edges(&h, &e, &ne, NULL), ACD_OK);
    assert_int_equal(ne, 3 * h.ntriangles / 2); /* closed: every edge in two triangles */
    for (size_t i = 0; i < ne; i++) {
        assert_true(e[i].v[0] < e[i].v[1]);
        if (i > 0) assert_true(e[i - 1].v[0] < e[i].v[0] || (e[i - 1].v[0] == e[i].v[0] && e[i - 1].v[1] < e[i].v[1]));
        int fl = 0, fr = 0;
        for (int k = 0; k < 3; k++) {
            const uint32_t *L = h.triangles + 3 * e[i].left, *R = h.triangles + 3 * e[i].right;
            if (L[k] == e[i].v[0] && L[(k + 1) % 3] == e[i].v[1]) fl = 1;
            if (R[k] == e[i].v[1] && R[(k + 1) % 3] == e[i].v[0]) fr = 1;
        }
        assert_true(fl && fr);
    }
    free(e);
    acd_hull_free(&h);
    /* planar: a square's 4 boundary edges have one side only, its diagonal both */
    double sq[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    assert_int_equal(acd_hull_compute(sq, 4, &h, NULL), ACD_OK);
    assert_int_equal(acd_hull_edges(&h, &e, &ne, NULL), ACD_OK);
    assert_int_equal(ne, 5);
    size_t inner = 0;
    for (size_t i = 0; i < ne; i++) {
        int missing = (e[i].left == ACD_HULL_NO_NEIGHBOR) + (e[i].right == ACD_HULL_NO_NEIGHBOR);
        assert_true(missing <= 1);
        inner += missing == 0;
    }
    assert_int_equal(inner, 1);
    free(e);
    acd_hull_free(&h);
    double seg[6] = {0, 0, 0, 1, 2, 3};
    assert_int_equal(acd_hull_compute(seg, 2, &h, NULL), ACD_OK);
    assert_int_equal(acd_hull_edges(&h, &e, &ne, NULL), ACD_OK);
    assert_int_equal(ne, 1);
    free(e);
    acd_hull_free(&h);
}

static void test_nan_rejected(void **state) {
    (void)state;
    double p[12] = {0, 0, 0, 1, 0, 0, 0, NAN, 0, 0, 0, 1};
    acd_hull h;
    acd_error err;
    assert_int_equal(acd_hull_compute(p, 4, &h, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "point 2"));
    p[7] = INFINITY;
    assert_int_equal(acd_hull_compute(p, 4, &h, &err), ACD_ERR_INVALID_INPUT);
    acd_hull_free(&h);
    double big[6] = {-1.5e308, 0, 0, 1.5e308, 0, 0};
    assert_int_equal(acd_hull_compute(big, 2, &h, &err), ACD_ERR_INVALID_INPUT);
    acd_hull_free(&h);
}

/* acd_hull_volume: the volume of acd_hull_compute's hull, to the bit, without the hull: random
 * clouds (spheres: every point on the hull), the cube with coplanar points and duplicates (merged
 * facets), a nearly flat slab, and lower-dimensional sets (0). */
static void test_volume_only(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 21);
    for (int trial = 0; trial < 60; trial++) {
        size_t n = trial < 6 ? (size_t)trial : 4 + (size_t)acd_rng_below(&r, 400);
        double *p = malloc(3 * (n > 200 ? n : 200) * sizeof *p); /* (cube_cloud: 118 points) */
        assert_non_null(p);
        int kind = trial % 4;
        if (kind == 3 && n >= 4) {
            n = cube_cloud(p, &r, 1e3, 7.5);
        } else {
            for (size_t i = 0; i < n; i++) {
                for (int k = 0; k < 3; k++) p[3 * i + k] = 2 * acd_rng_uniform(&r) - 1;
                if (kind == 0) { /* on a sphere */
                    double l = sqrt(p[3 * i] * p[3 * i] + p[3 * i + 1] * p[3 * i + 1] + p[3 * i + 2] * p[3 * i + 2]);
                    for (int k = 0; k < 3; k++) p[3 * i + k] /= l;
                }
                if (kind == 1) p[3 * i + 2] *= 1e-9; /* a slab: dim 3 or 2 */
                if (kind == 2 && trial % 8 == 2) p[3 * i + 2] = 0.25; /* coplanar: dim 2 */
            }
        }
        acd_hull h;
        acd_error err;
        double v = -1;
        assert_int_equal(acd_hull_compute(p, n, &h, &err), ACD_OK);
        assert_int_equal(acd_hull_volume(p, n, &v, &err), ACD_OK);
        double expect = h.dim == 3 ? h.volume : 0;
        assert_memory_equal(&v, &expect, sizeof v);
        if (n >= 4 && kind == 0) assert_true(v > 0);
        acd_hull_free(&h);
        free(p);
    }
    double q[3] = {0, 0, NAN}, v;
    acd_error err;
    assert_int_equal(acd_hull_volume(q, 1, &v, &err), ACD_ERR_INVALID_INPUT);
}

/* Every input point inside every facet plane, within ACD_TOL_REL_DIST of the diagonal. */
static void assert_encloses(const acd_hull *h, const double *pts, size_t n) {
    double tol = 1e-10 * extent_of(pts, n), worst = -INFINITY;
    for (size_t t = 0; t < h->ntriangles; t++) {
        const double *pl = h->planes + 4 * t;
        for (size_t i = 0; i < n; i++) {
            double v = pl[0] * pts[3 * i] + pl[1] * pts[3 * i + 1] + pl[2] * pts[3 * i + 2] + pl[3];
            if (v > worst) worst = v;
        }
    }
    if (worst > tol) print_message("a point is %g outside a facet plane (tol %g)\n", worst, tol);
    assert_true(worst <= tol);
}


/* fuzz_hull's six points (docs/results/fuzz.md "Hull misses a point"): A, B, C, D, E, F. */
static const double ill_six[18] = {0, 0, -9.585035187470353,
                                   -9.586051653338757, -9.586051653338757, -9.586052776444209,
                                   -9.586051653338757, -9.586051653338757, -9.586051653338757,
                                   -9.586051653338757, -9.586051653242881, -9.586051653338757,
                                   0, -2.184312143644803e-08, 0,
                                   0, 7.55684574833281e-12, 7.556001431015457e-12};

/* The six points base and n - 6 random convex combinations of them (seed 3), the six at slots
 * 37 + 61 k: points checked through several levels of hull_enclose's tree. Owned by the caller. */
static double *six_and_combinations(const double *base, size_t n) {
    double *q = malloc(3 * n * sizeof *q);
    assert_non_null(q);
    acd_rng r;
    acd_rng_seed(&r, 3);
    for (size_t i = 0; i < n; i++) {
        double wsum = 0, wt[6];
        for (int k = 0; k < 6; k++) wsum += wt[k] = acd_rng_uniform(&r) * acd_rng_uniform(&r);
        for (int c = 0; c < 3; c++) {
            q[3 * i + c] = 0;
            for (int k = 0; k < 6; k++) q[3 * i + c] += wt[k] / wsum * base[3 * k + c];
        }
    }
    for (int k = 0; k < 6; k++) memcpy(q + 3 * (size_t)(37 + 61 * k), base + 3 * k, 3 * sizeof(double));
    return q;
}

/* fuzz_hull's six points (docs/results/fuzz.md): C and D 1e-10 apart make the plane of facet
 * (C, D, A) ill-conditioned, and qhull took B as coplanar with it while B lies 1.1e-6 (1.2e-7 of the
 * extent) outside it. Every plane encloses every point (the hull is rebuilt since 2026-11-26:
 * test_triangles_enclose_ill_conditioned). Also scaled (1e-90, 1e90) and moved, and as
 * acd_hull_volume sees it. */
static void test_enclosure_ill_conditioned(void **state) {
    (void)state;
    const double *base = ill_six;
    const double scales[4] = {1, 1e-90, 1e90, 1}, shifts[4] = {0, 0, 0, 3.5};
    for (int c = 0; c < 4; c++) {
        double p[18];
        for (int i = 0; i < 18; i++) p[i] = base[i] * scales[c] + shifts[c];
        acd_hull h;
        acd_error err;
        assert_int_equal(acd_hull_compute(p, 6, &h, &err), ACD_OK);
        assert_int_equal(h.dim, 3);
        assert_int_equal(h.ntriangles, 2 * h.nvertices - 4);
        assert_encloses(&h, p, 6);
        /* each plane still supports its triangle: no vertex outside, one on it or below it by at
         * most the lift (B's distance, 1.2e-7 of the extent) */
        for (size_t t = 0; t < h.ntriangles; t++) {
            const double *pl = h.planes + 4 * t;
            for (int k = 0; k < 3; k++) {
                const double *q = h.vertices + 3 * h.triangles[3 * t + k];
                double v = pl[0] * q[0] + pl[1] * q[1] + pl[2] * q[2] + pl[3];
                assert_true(v <= 1e-10 * extent_of(p, 6) && v >= -2e-7 * extent_of(p, 6));
            }
        }
        /* acd_hull_volume is qhull's hull's (B left out), below the rebuilt hull's by at most B's
         * distance x the area */
        double v = -1;
        assert_int_equal(acd_hull_volume(p, 6, &v, &err), ACD_OK);
        assert_true(v > 0 && fabs(v - h.volume) <= 2e-7 * extent_of(p, 6) * h.area);
        acd_hull_free(&h);
    }
    /* with 400 convex combinations of the six (the points checked through several levels of
     * hull_enclose's tree), in shuffled order: still every point inside every plane */
    enum { NP = 406 };
    double *q = six_and_combinations(base, NP);
    acd_hull h;
    acd_error err;
    assert_int_equal(acd_hull_compute(q, NP, &h, &err), ACD_OK);
    assert_int_equal(h.dim, 3);
    assert_encloses(&h, q, NP);
    acd_hull_free(&h);
    free(q);
}

/* The hull as a mesh (what the OBJ holds) encloses every input point: vertices are input points,
 * closed and consistently oriented (each edge's neighbour runs it backwards and points back), Euler
 * characteristic 2, volume > 0; each triangle's plane (h->planes) is a plane of the triangle (its
 * three vertices within tol of it) with every point below it within tol (convex within the
 * tolerance); and, without the planes, every point is within tol of the triangles or inside them
 * (winding number 1: the solid angles of the triangles seen from it sum to 4 pi, Van Oosterom and
 * Strackee's formula, in coordinates normalised by the extent). tol = 1e-10 x the extent. */
static void assert_mesh_encloses(const acd_hull *h, const double *pts, size_t n) {
    assert_int_equal(h->dim, 3);
    assert_true(h->volume > 0);
    double ext = extent_of(pts, n), tol = 1e-10 * ext;
    for (size_t v = 0; v < h->nvertices; v++) {
        assert_true(h->source[v] < n);
        assert_memory_equal(h->vertices + 3 * v, pts + 3 * h->source[v], 3 * sizeof(double));
    }
    assert_int_equal(2 * h->nvertices, h->ntriangles + 4); /* V - E + F = 2 with E = 3F/2 */
    for (size_t t = 0; t < h->ntriangles; t++) {
        const uint32_t *tri = h->triangles + 3 * t;
        assert_true(tri[0] != tri[1] && tri[1] != tri[2] && tri[2] != tri[0]);
        for (int e = 0; e < 3; e++) {
            uint32_t u = h->neighbors[3 * t + e];
            assert_true(u < h->ntriangles);
            int found = 0;
            for (int f = 0; f < 3; f++)
                if (h->triangles[3 * u + f] == tri[(e + 1) % 3] && h->triangles[3 * u + (f + 1) % 3] == tri[e] &&
                    h->neighbors[3 * u + f] == t)
                    found = 1;
            assert_true(found);
        }
        const double *pl = h->planes + 4 * t;
        assert_true(fabs(pl[0] * pl[0] + pl[1] * pl[1] + pl[2] * pl[2] - 1) < 1e-12);
        for (int k = 0; k < 3; k++) {
            const double *q = h->vertices + 3 * tri[k];
            double v = pl[0] * q[0] + pl[1] * q[1] + pl[2] * q[2] + pl[3];
            double rnd = 8 * 2.220446049250313e-16 * (fabs(pl[0] * q[0]) + fabs(pl[1] * q[1]) + fabs(pl[2] * q[2]) + fabs(pl[3]));
            if (fabs(v) > tol + rnd) print_message("vertex %u is %g off the plane of triangle %zu (tol %g)\n", tri[k], v, t, tol);
            assert_true(fabs(v) <= tol + rnd); /* (up to the rounding of n.q + d in these coordinates) */
        }
        for (size_t i = 0; i < n; i++) {
            double v = pl[0] * pts[3 * i] + pl[1] * pts[3 * i + 1] + pl[2] * pts[3 * i + 2] + pl[3];
            if (v > tol) print_message("point %zu is %g above the plane of triangle %zu (tol %g)\n", i, v, t, tol);
            assert_true(v <= tol);
        }
    }
    double lo[3], hi[3], cen[3];
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            if (i == 0 || pts[3 * i + k] < lo[k]) lo[k] = pts[3 * i + k];
            if (i == 0 || pts[3 * i + k] > hi[k]) hi[k] = pts[3 * i + k];
        }
    for (int k = 0; k < 3; k++) cen[k] = 0.5 * (lo[k] + hi[k]);
    for (size_t i = 0; i < n; i++) {
        double near, wn = hull_winding(h, pts + 3 * i, cen, ext, &near);
        if (near <= 1e-10) continue; /* on the surface within tol */
        if (fabs(wn - 1) > 0.25)
            print_message("point %zu (%g from the triangles) has winding number %g\n", i, near * ext, wn);
        assert_true(fabs(wn - 1) <= 0.25);
    }
}

/* The volume of the convex hull of points in general position on their hull (no four coplanar on a
 * face): the facets are the triples with every point on one side (exact signs), each adding its
 * tetrahedron to point 0 by the adaptive orient3d (accurate to its own magnitude, as a flat hull
 * needs). */
static double exact_volume(const double *p, size_t n) {
    double vol = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++)
            for (size_t k = j + 1; k < n; k++) {
                int pos = 0, neg = 0;
                for (size_t m = 0; m < n; m++) {
                    int sg = acd_orient3d_sign(p + 3 * i, p + 3 * j, p + 3 * k, p + 3 * m);
                    pos += sg > 0;
                    neg += sg < 0;
                }
                if (!(pos && neg)) vol += fabs(acd_orient3d(p + 3 * i, p + 3 * j, p + 3 * k, p)) / 6;
            }
    return vol;
}

/* fuzz_hull's six points again, now for the triangles (the mesh written to OBJ; qhull's miss B by
 * 1.1e-6): the mesh closed, convex within the tolerance and enclosing every point
 * (assert_mesh_encloses), the volume within tol x area of the exact hull's (brute force), and
 * acd_hull_volume (qhull's hull, not rebuilt: B left out) below it by at most B's distance x area. At several scales and offsets,
 * in all 720 orders at scale 1, and with the 400 convex combinations of test_enclosure_ill_conditioned. */
static void test_triangles_enclose_ill_conditioned(void **state) {
    (void)state;
    const double *base = ill_six;
    const double scales[7] = {1, 1e-3, 1e5, 1e-90, 1e90, 1, 1e-30}, shifts[7] = {0, 0, 0, 0, 0, 3.5, -7e-30};
    for (int c = 0; c < 7; c++) {
        double p[18];
        for (int i = 0; i < 18; i++) p[i] = base[i] * scales[c] + shifts[c];
        acd_hull h;
        acd_error err;
        assert_int_equal(acd_hull_compute(p, 6, &h, &err), ACD_OK);
        assert_mesh_encloses(&h, p, 6);
        assert_encloses(&h, p, 6);
        /* the exact hull's volume, within tol x the area (the hull is computed on coordinates
         * normalised by the extent: their rounding moves this flat hull's volume by 6e-9 of it) */
        double exact = exact_volume(p, 6);
        if (!(fabs(h.volume - exact) <= 1e-10 * extent_of(p, 6) * h.area))
            print_message("case %d: volume %.17g, exact %.17g\n", c, h.volume, exact);
        assert_true(fabs(h.volume - exact) <= 1e-10 * extent_of(p, 6) * h.area);
        double v = -1;
        assert_int_equal(acd_hull_volume(p, 6, &v, &err), ACD_OK);
        assert_true(v > 0 && fabs(v - h.volume) <= 2e-7 * extent_of(p, 6) * h.area);
        acd_hull_free(&h);
    }
    int perm[6] = {0, 1, 2, 3, 4, 5}, cnt[6] = {0};
    for (int k = 0; k < 720;) { /* every order (Heap's algorithm) */
        double p[18];
        for (int i = 0; i < 6; i++) memcpy(p + 3 * i, base + 3 * perm[i], 3 * sizeof(double));
        acd_hull h;
        acd_error err;
        assert_int_equal(acd_hull_compute(p, 6, &h, &err), ACD_OK);
        assert_mesh_encloses(&h, p, 6);
        assert_encloses(&h, p, 6);
        double v = -1;
        assert_int_equal(acd_hull_volume(p, 6, &v, &err), ACD_OK);
        assert_true(v > 0 && fabs(v - h.volume) <= 2e-7 * extent_of(p, 6) * h.area);
        acd_hull_free(&h);
        k++;
        int i = 1;
        while (i < 6 && cnt[i] >= i) cnt[i++] = 0;
        if (i == 6) break;
        int j = i % 2 ? cnt[i] : 0, x = perm[i];
        perm[i] = perm[j];
        perm[j] = x;
        cnt[i]++;
    }
    enum { NP = 406 };
    double *q = six_and_combinations(base, NP);
    acd_hull h;
    acd_error err;
    assert_int_equal(acd_hull_compute(q, NP, &h, &err), ACD_OK);
    assert_mesh_encloses(&h, q, NP);
    assert_encloses(&h, q, NP);
    double v = -1;
    assert_int_equal(acd_hull_volume(q, NP, &v, &err), ACD_OK);
    assert_true(v > 0 && fabs(v - h.volume) <= 2e-7 * extent_of(q, NP) * h.area);
    acd_hull_free(&h);
    free(q);
}

/* The hull of the n points p: every point inside every plane and inside the mesh of its triangles. */
static void hull_of_encloses(const double *p, size_t n) {
    acd_hull h;
    acd_error err;
    assert_int_equal(acd_hull_compute(p, n, &h, &err), ACD_OK);
    assert_mesh_encloses(&h, p, n);
    assert_encloses(&h, p, n);
    acd_hull_free(&h);
}

/* fuzz_hull's 17 points at 1e40 with tiny ones mixed in (docs/results/geom3.md): qhull lost the
 * point of greatest y, 1.2e-9 of the extent above its well-conditioned facet of normal (0, 1, 0),
 * which hull_enclose trusted; an extreme point outside a plane now makes every facet checked (and
 * here the hull rebuilt). Fails on the old code (the point above a plane by 1.2e-9). */
static void test_lost_extreme_point(void **state) {
    (void)state;
    static const double p[51] = {
        0x1.4b286a3b969c8p-1022, -0x1.0a06edc98c07bp-269, -0x1.a73ca4edabfc5p-978,
        -0x1.7d1f8e1f2bf32p+125, 0x1.8484848c7c7c7p+133, -0x1.7c7d1f8e14848p+125,
        0x1.848484848c7c7p+133, 0x1.8484848484848p+133, 0x1.8484848074848p+133,
        0x1.8484848484848p+133, 0x0.0000ba2e8bc48p-1022, 0x0.0000000000100p-1022,
        0x1.8484848484800p+133, 0x1.8484848484848p+133, 0x1.8484848484848p+133,
        0x1.848483f484848p+133, 0x1.8484848484848p+133, 0x1.8484848484848p+133,
        0x1.8484848484848p+133, 0x1.8484848484848p+133, 0x1.8484848484848p+133,
        0x1.8482f48484848p+133, -0x1.8484848484848p+117, 0x1.7c7c7c7c7c7c7p-83,
        0x1.a3a3a3a3a3ac7p-92, -0x1.7c7c73a3a3a3ap+125, -0x1.7c7c7c7c7c764p+125,
        -0x1.7c7c7c7c7c7c7p+125, -0x1.7c7c7c7c7c7c7p+125, -0x1.7c7c7c7c7c7c7p+125,
        0x1.84848c7c7c7c7p+133, 0x1.8074848484848p+133, 0x1.8484848484848p+133,
        0x0.0000148484848p-1022, 0x1.8484800000000p+133, 0x1.8484848484848p+133,
        0x1.8484848484848p+133, 0x1.f484848484848p+132, 0x1.8484848484848p+133,
        0x1.8484848484848p+133, 0x1.8484848484848p+133, 0x1.8484848484848p+133,
        0x1.8484848484848p+133, 0x1.8484848484848p-267, 0x1.8484848484848p+133,
        -0x1.7c7c7c7c74848p+125, 0x1.a3a3ac73ac7c7p-92, -0x1.a3a3a3a3a3a3ap+116,
        -0x1.7c7c764c7c7c7p+125, -0x1.7c7c7c7c7c7c7p+125, -0x1.7c7c7c7c7c7c7p+125,
    };
    hull_of_encloses(p, 17);
}

/* fuzz_hull's 17 points spanning 1e45 to 1e-314 (docs/results/geom3.md): qhull flipped a facet and
 * merged a concave-coplanar ridge on the way, and left point 8 1.35e-9 of the extent above two
 * well-shaped triangles of a merged facet (normal agreeing with their own), which hull_enclose
 * trusted; the point is extreme in none of hull_extremes_outside's 14 directions. A hull qhull
 * repaired that way now has every facet checked. Fails on the old code (the point above a plane by
 * 1.35e-9 of the extent). */
static void test_lost_point_repaired(void **state) {
    (void)state;
    static const double p[51] = {
        0x1.4b286a3b969c8p-686, -0x1.ac7bedc000000p+116, 0x0.00000c7c7c7c7p-1022,
        0.0, -0x1.7a26e00000000p+125, 0x0.00002c7c7c7c7p-1022,
        -0x1.7c1c700000000p+125, -0x1.7c7c7c7c70700p+125, -0x1.7c7c7ffc7c7c7p+125,
        0x1.a3a3a3a3a3ac7p-92, -0x1.7c7c7c7c7c7c7p+125, -0x1.7c7c7c7c7c7c7p+125,
        0x1.d2dc7c7c7c7c7p-301, -0x1.7c72d2d2d2d2dp+125, 0x1.9494949c7c7c7p+149,
        0x1.9494949494949p+149, 0x1.7c7c749496349p-947, -0x1.0000007000000p+113,
        -0x1.316249809d396p-11, -0x1.78526249424b6p+125, 0x1.7c7c7c0d0c71bp-83,
        -0x1.73a3a3a3a3a3ap+125, -0x1.7c7c7c7c7c7c7p+125, 0x0.00bc7c7c7c7c7p-1022,
        0x1.d2d0000000c00p-301, -0x1.7c7c5c72d2d2dp+125, 0x1.94949494949c7p+149,
        0x1.9494949494949p+149, 0x1.4c7f5c7c74949p-975, -0x1.7c7006907feffp+125,
        -0x1.7c7c787c7c7c7p+109, 0x1.a3a3ac7c3c7c7p-92, 0x1.a3a3a3a3a3a3ap-92,
        -0x1.7c7c7c7e728c7p+125, 0x0.1c70018c7c7c7p-1022, -0x1.7c7c7c7c71600p+125,
        -0x1.7c73ac7c7c7c7p+125, -0x1.7c7c7c7c7c7c7p+125, -0x1.7c7c7c7c7c7c7p+125,
        -0x1.7c7c7c7c7c7c7p+125, 0x1.d2d2d2d2d2d2dp-301, 0x1.9c7c7c7c7c7c7p+149,
        0x1.9494949494949p+149, -0x1.9494949494949p+117, 0x1.0000404c7f5c7p-911,
        -0x1.7c7c7c7c70069p+125, 0x1.7c7c7c7c7c787p-1011, 0.0,
        -0x1.7c7c7c7c70000p+125, -0x1.7c7c7c73ac7c7p+125, -0x1.3c7c7c7c7c7d7p-917,
    };
    hull_of_encloses(p, 17);
}

/* fuzz_hull (CI at ad28b14): 17 points spanning 1e45 to 1e-314 whose qhull hull left point 4 1.3e-9
 * of the extent above a trusted facet, with neither a repaired non-convexity nor an extreme point
 * outside to flag it; the hull is thin (volume about 4e-8 of the diagonal cubed), and hull_enclose
 * now trusts no facet of a thin hull. */
static void test_lost_point_thin(void **state) {
    (void)state;
    static const double p[51] = {
        0x1.4b286a3b969c8p-686, -0x1.ac7bedc000000p+116, 0x0.00000c7c7c7c7p-1022,
        0.0, -0x1.7a26e00000000p+125, 0x0.00002c7c7c7c7p-1022,
        -0x1.7c1c700000000p+125, -0x1.7c7c7c7c70700p+125, -0x1.7c7c7ffc7c7c7p+125,
        0x1.a3a3a3a3a3ac7p-92, -0x1.7c7c7c7c7c7c7p+125, -0x1.7c7c7c7c7c7c7p+125,
        0x1.d2dc7c7c7c7c7p-301, -0x1.7c72d2d2d2d2dp+125, 0x1.9494949c7c7c7p+149,
        0x1.9494949494949p-1019, 0.0, -0x1.7c7a26e000000p+125,
        0x0.0000002c7c7c7p-1022, 0x1.7c7c1c7000000p-1011, -0x1.7c7c7c7c7c707p+125,
        -0x1.7c7c7c7ffc7c7p+125, -0x1.73a3a3a3a3a3ap+125, 0x0.00bc7c7c7c7c7p-1022,
        0x1.d2d0000000c00p-301, -0x1.7c7c5c72d2d2dp+125, 0x1.94949494949c7p+149,
        0x1.9494949494949p+149, 0x1.4c7f5c7c74949p-975, -0x1.7c7006907feffp+125,
        -0x1.7c7c787c7c7c7p+109, 0x1.a3a3ac7c3c7c7p-92, 0x1.a3a3a3a3a3a3ap-92,
        -0x1.7c7c7c7e728c7p+125, 0x0.1c70018c7c7c7p-1022, -0x1.7c7c7c7c71600p+125,
        -0x1.7c73ac7c7c7c7p+125, -0x1.7c7c7c7c7cfc7p+125, -0x1.7c7c7c7c74139p+125,
        -0x1.7c7c7c7c7c7c7p+125, 0x1.d2d2d2d2d2d2dp-301, 0x1.9c7c741c7c7c7p+149,
        0x1.9494949494949p+149, -0x1.9494949494949p+117, 0x1.0000404c7f5c7p-911,
        -0x1.7c7c7c7c70069p+125, 0x1.7c7c7c7c7c787p-1011, 0.0,
        -0x1.7c7c7c7c70000p+125, -0x1.7c7c7c73ac7c7p+125, -0x1.3c7c7c7c7c7d7p-917,
    };
    hull_of_encloses(p, 17);
}

/* fuzz_hull (2026-11-26, fuzzrun; corpus hull/lost_point_small_facet): nine points spanning 1e45 to
 * 1e-311. qhull's facet (8, 5, 2) is a small well-shaped triangle (edges 5.5e-8, 5.5e-8, 7.8e-8 of
 * the extent, least altitude 3.9e-8) at normalised coordinates near 0.5, and point 3 is 1.34e-9 of
 * the extent above its plane. hull_enclose trusted the facet: the trust test counted the cross
 * product's rounding (eps x L / h: 4.4e-16) but not the vertices' own (their normalised coordinates
 * carry eps x |w|, and qhull decided on them), which tilts so small a triangle by up to about
 * eps |w| / h, 3e-9 here. The hull is neither thin (6.5e-7 of the diagonal cubed), repaired, nor
 * has an extreme point outside. (The unminimised input, 34 points, had a sliver of altitude 4.9e-11
 * and two points 1.35e-9 out.) Fails on the old code (point 3 1.34e-9 outside). */
static void test_lost_point_small_facet(void **state) {
    (void)state;
    static const double p[27] = {
        0x1.84848a3b969c8p+133, 0x1.8484848484848p+133, 0x1.8484848484848p+133,
        0x1.8484848484848p-267, 0x1.8484848484848p+133, -0x1.7c7c7c7c74848p+125,
        -0x1.7c7c7c7c7c7c7p+125, -0x1.7c7c7c7c7c7c7p+125, 0x1.d2dc7c7c7c7c7p-301,
        -0x1.7c72d2d2d2d2dp+125, 0x1.9494949c7c7c7p+149, 0x1.9494949494949p+149,
        0x1.7c7c749496349p-947, -0x1.0000007000000p+113, 0x1.316000c09d396p+149,
        -0x1.7c7c7c7c74949p+125, -0x1.7c7c7c7c7c7c7p+125, -0x1.7c7c7c7c7c7c7p+125,
        0x1.d2d2d2d2d2d2dp-301, 0x1.9c7c7c7c7c7c7p+149, 0x1.9494949494959p+149,
        0x1.7c7c7c7c74949p-1011, 0x0.00f0000010000p-1022, -0x1.7c7c7c7c71300p+125,
        -0x1.7c7c7c73ac7c7p+125, 0x1.286a3c7c7c7c7p-692, -0x1.7bedc00c77b00p-19,
    };
    hull_of_encloses(p, 9);
}

/* Many ill-conditioned facets at once: points on a sphere, a third of them with a twin 1e-11 to
 * 1e-7 away in a random direction (slivers of every conditioning, on both sides of hull_enclose's
 * trust test), shuffled in: every point inside every plane. (qhull's planes already pass this
 * without any check; test_enclosure_ill_conditioned is the case that needs the lift.) */
static void test_enclosure_twins(void **state) {
    (void)state;
    enum { NB = 3000, NT = 1000 };
    double *p = malloc(3 * (NB + NT) * sizeof *p);
    assert_non_null(p);
    acd_rng r;
    acd_rng_seed(&r, 11);
    const double golden = 2.399963229728653; /* pi (3 - sqrt 5) */
    for (size_t i = 0; i < NB; i++) {
        double z = 1 - (2.0 * (double)i + 1) / NB, rho = sqrt(1 - z * z), a = golden * (double)i;
        p[3 * i] = 7.0 * rho * cos(a) + 2.0;
        p[3 * i + 1] = 7.0 * rho * sin(a) - 1.0;
        p[3 * i + 2] = 7.0 * z;
    }
    for (size_t j = 0; j < NT; j++) {
        const double *q = p + 3 * (3 * j);
        double *t = p + 3 * (NB + j), dir[3], len = 0;
        for (int c = 0; c < 3; c++) {
            dir[c] = 2 * acd_rng_uniform(&r) - 1;
            len += dir[c] * dir[c];
        }
        double gap = 1e-11 * pow(1e4, acd_rng_uniform(&r)) / sqrt(len);
        for (int c = 0; c < 3; c++) t[c] = q[c] + gap * dir[c];
    }
    for (size_t i = NB + NT - 1; i > 0; i--) { /* shuffle */
        size_t k = (size_t)(acd_rng_uniform(&r) * (double)(i + 1));
        if (k > i) k = i;
        for (int c = 0; c < 3; c++) {
            double x = p[3 * i + c];
            p[3 * i + c] = p[3 * k + c];
            p[3 * k + c] = x;
        }
    }
    acd_hull h;
    acd_error err;
    assert_int_equal(acd_hull_compute(p, NB + NT, &h, &err), ACD_OK);
    assert_int_equal(h.dim, 3);
    assert_encloses(&h, p, NB + NT);
    acd_hull_free(&h);
    free(p);
}

/* acd_hull_take moves the arrays out and leaves an empty hull that acd_hull_free (and a second
 * take) handle. */
static void test_take(void **state) {
    (void)state;
    const double p[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    acd_hull h, e;
    assert_int_equal(acd_hull_compute(p, 4, &h, NULL), ACD_OK);
    const double *verts = h.vertices;
    double vol = h.volume;
    acd_hull t = acd_hull_take(&h);
    assert_ptr_equal(t.vertices, verts);
    assert_int_equal(t.dim, 3);
    assert_true(t.volume == vol && t.ntriangles == 4);
    assert_int_equal(h.dim, -1);
    assert_null(h.vertices);
    assert_int_equal(h.ntriangles, 0);
    e = acd_hull_take(&h);
    assert_int_equal(e.dim, -1);
    acd_hull_free(&h);
    acd_hull_free(&t);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_vs_brute_force),
        cmocka_unit_test(test_large_random_cloud),
        cmocka_unit_test(test_cube_with_coplanar_and_duplicates),
        cmocka_unit_test(test_few_points),
        cmocka_unit_test(test_collinear),
        cmocka_unit_test(test_coplanar),
        cmocka_unit_test(test_nearly_flat),
        cmocka_unit_test(test_edges),
        cmocka_unit_test(test_nan_rejected),
        cmocka_unit_test(test_volume_only),
        cmocka_unit_test(test_enclosure_ill_conditioned),
        cmocka_unit_test(test_triangles_enclose_ill_conditioned),
        cmocka_unit_test(test_lost_extreme_point),
        cmocka_unit_test(test_lost_point_repaired),
        cmocka_unit_test(test_lost_point_thin),
        cmocka_unit_test(test_lost_point_small_facet),
        cmocka_unit_test(test_enclosure_twins),
        cmocka_unit_test(test_take),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
