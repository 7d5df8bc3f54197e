/* fuzz/fuzz_hull: libFuzzer target for the 3D hull and the plane cut. The input is read as points on
 * a small integer grid (3 x int8 per point, so duplicates, collinear and coplanar sets are frequent)
 * or, after a leading 'D' byte, as raw doubles. The hull's invariants are checked (vertices are input
 * points, closed manifold with consistent neighbours, every point inside every facet plane within
 * tolerance); the triangles too (the mesh written to OBJ): each facet plane passes within the
 * tolerance of its triangle's three vertices (so a plane of every triangle encloses every point).
 * With -DFUZZ_HULL_CHECK_WINDING, on hulls of at most CHECK_WINDING_MAX points x triangles, every
 * point must also be within the tolerance of the triangles or inside them (winding number 1): not
 * promised (a point within the tolerance of every plane can lie farther from a razor-thin rim:
 * docs/results/geom3.md, corpus thin_rim), so compiled out. A solid hull is then cut by the plane
 * through three of the points and every piece must be closed with the volumes adding up. Any
 * violation aborts. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "geom3/bvh.h"
#include "geom3/edge_map.h"
#include "geom3/plane_cut.h"
#include "geom3/volume.h"
#include "hull_winding.h" /* tests/support */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#ifdef FUZZ_HULL_CHECK_WINDING
/* Points x triangles up to which the winding number of every point is checked. */
#define CHECK_WINDING_MAX 20000

/* Every point within rtol (relative to the extent) of the triangles or inside them (winding number
 * 1: tests/support/hull_winding.h), in coordinates normalised by the box (centre, extent ext). */
static void check_winding(const acd_hull *h, const double *p, size_t n, const double *cen, double ext, double rtol) {
    for (size_t i = 0; i < n; i++) {
        double near, wn = hull_winding(h, p + 3 * i, cen, ext, &near);
        if (near > rtol && fabs(wn - 1) > 0.25) {
            fprintf(stderr, "point %zu is %g (of the extent) from the triangles, winding number %g\n", i, near, wn);
            abort();
        }
    }
}
#endif

static void check_hull(const acd_hull *h, const double *p, size_t n) {
    if (h->dim < 3) return;
    double lo[3], hi[3];
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            if (i == 0 || p[3 * i + k] < lo[k]) lo[k] = p[3 * i + k];
            if (i == 0 || p[3 * i + k] > hi[k]) hi[k] = p[3 * i + k];
        }
    double ext = 0;
    for (int k = 0; k < 3; k++) ext = fmax(ext, hi[k] - lo[k]);
    double tol = 1e-9 * ext;
    if (h->ntriangles != 2 * h->nvertices - 4) abort();
    for (size_t v = 0; v < h->nvertices; v++)
        if (h->source[v] >= n || memcmp(h->vertices + 3 * v, p + 3 * h->source[v], 3 * sizeof(double))) abort();
    for (size_t t = 0; t < h->ntriangles; t++) {
        for (int e = 0; e < 3; e++) {
            uint32_t u = h->neighbors[3 * t + e];
            if (u >= h->ntriangles) abort();
            int found = 0;
            for (int f = 0; f < 3; f++)
                if (h->triangles[3 * u + f] == h->triangles[3 * t + (e + 1) % 3] &&
                    h->triangles[3 * u + (f + 1) % 3] == h->triangles[3 * t + e] && h->neighbors[3 * u + f] == t)
                    found = 1;
            if (!found) abort();
        }
        const double *pl = h->planes + 4 * t;
        for (size_t i = 0; i < n; i++)
            if (pl[0] * p[3 * i] + pl[1] * p[3 * i + 1] + pl[2] * p[3 * i + 2] + pl[3] > tol) abort();
        for (int k = 0; k < 3; k++) { /* a plane of the triangle (up to the rounding of n.v + d in
                                            these coordinates: sets far from the origin) */
            const double *v = h->vertices + 3 * (size_t)h->triangles[3 * t + k];
            double off = pl[0] * v[0] + pl[1] * v[1] + pl[2] * v[2] + pl[3];
            double rnd = 8 * DBL_EPSILON * (fabs(pl[0] * v[0]) + fabs(pl[1] * v[1]) + fabs(pl[2] * v[2]) + fabs(pl[3]));
            if (fabs(off) > tol + rnd) {
                fprintf(stderr, "triangle %zu: vertex %d is %g off its plane (tol %g)\n", t, k, off, tol);
                abort();
            }
        }
    }
    if (!(h->volume >= 0)) abort(); /* may underflow to 0 for tiny coordinates (documented) */
#ifdef FUZZ_HULL_CHECK_WINDING
    double cen[3] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
    if (n * h->ntriangles <= CHECK_WINDING_MAX) check_winding(h, p, n, cen, ext, 1e-9);
#endif
}

static void check_cut(const acd_hull *h, const double *p, size_t n) {
    if (h->dim < 3 || n < 3) return;
    acd_mesh m = {h->vertices, h->nvertices, h->triangles, h->ntriangles};
    acd_cut_plane pl;
    if (acd_cut_plane_from_points(p, p + 3 * (n / 2), p + 3 * (n - 1), &pl, NULL) != ACD_OK) return;
    acd_cut_result r;
    acd_error err;
    acd_status st = acd_plane_cut(&m, &pl, &r, &err);
    if (st == ACD_ERR_DEGENERATE) return; /* plane points far below the hull's scale */
    if (st != ACD_OK) { /* a hull is always closed */
        fprintf(stderr, "plane cut failed: %s\n", err.message);
        abort();
    }
    double vs = 0;
    for (size_t i = 0; i < r.npieces; i++) {
        acd_edge_map em;
        const acd_mesh *pm = &r.pieces[i].mesh;
        if (acd_edge_map_build(pm->triangles, pm->ntriangles, NULL, &em, NULL) != ACD_OK) abort();
        /* closed as a cycle: every edge used as often in each direction. (Unique half-edges hold for
         * solids that do not self-intersect; qhull's hull is convex only up to its roundoff, so at
         * scales far below that a cap may repeat a face's edge.) */
        for (size_t k = 0; k < em.n; k++) {
            uint32_t a = (uint32_t)(em.key[k] >> 32), b = (uint32_t)em.key[k];
            if (acd_edge_map_count(&em, a, b) != acd_edge_map_count(&em, b, a)) {
                fprintf(stderr, "piece %zu of %zu: edge (%u, %u) unbalanced\n", i, r.npieces, a, b);
                abort();
            }
        }
        acd_edge_map_free(&em);
        vs += acd_geom3_signed_volume(pm);
    }
    double v0 = acd_geom3_signed_volume(&m);
    /* volumes are cubes of lengths: checked only where they neither underflow nor overflow. Crossing
     * points are rounded, so the sum is exact to about 1e-15 extent^3 (not relative to the volume of
     * a sliver) */
    double ext = 0;
    for (size_t i = 0; i < 3 * m.nvertices; i++) ext = fmax(ext, fabs(m.vertices[i]));
    /* flat shells dropped by the cut (geom3/plane_cut.c: mean thickness below 1e-12 of the
     * diagonal) take at most 1e-12 * diagonal * half their area each; their area is at most the
     * mesh's plus twice the section's */
    double area = 0;
    for (size_t t = 0; t < m.ntriangles; t++) {
        const double *a = m.vertices + 3 * m.triangles[3 * t], *b = m.vertices + 3 * m.triangles[3 * t + 1],
                     *c = m.vertices + 3 * m.triangles[3 * t + 2];
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        area += 0.5 * hypot(hypot(u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2]), u[0] * w[1] - u[1] * w[0]);
    }
    double tol = 1e-9 * fabs(v0) + 1e-12 * ext * ext * ext + 1e-12 * 2 * ext * (area + 2 * r.section_area);
    if (fabs(v0) > 1e-250 && fabs(v0) < 1e250 && fabs(vs - v0) > tol) {
        fprintf(stderr, "volumes %.17g vs %.17g\n", vs, v0);
        abort();
    }
    /* (no bound on the number of pieces: qhull's hull is convex only up to its roundoff, and a plane
     * through slivers far below that can meet it in several loops) */
    acd_cut_result_free(&r);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    size_t n;
    double *p;
    if (size > 0 && data[0] == 'D') {
        n = (size - 1) / 24;
        p = malloc((n ? n : 1) * 3 * sizeof *p);
        if (!p) return 0;
        if (n) memcpy(p, data + 1, n * 24);
    } else {
        n = size / 3;
        p = malloc((n ? n : 1) * 3 * sizeof *p);
        if (!p) return 0;
        for (size_t i = 0; i < 3 * n; i++) p[i] = (double)(int8_t)data[i];
    }
    acd_hull h;
    acd_error err;
    acd_status s = acd_hull_compute(p, n, &h, &err);
    if (s == ACD_OK) {
        check_hull(&h, p, n);
        check_cut(&h, p, n);
    } else if (!err.message[0]) {
        abort(); /* every failure must say why */
    }
    acd_hull_free(&h);
    free(p);
    return 0;
}
