/* Meshes moved far from the origin, for the local-frame tests (test_frame, test_acd3_far; header-only,
 * static). Two ways:
 *  - exactly: coordinates rounded to a grid of 2^GRID first, then + D with D a multiple of the power
 *    of two above the extent and |D| up to ~1e8 extents, so that every x + D is a double (checked) and
 *    the local frame's translation is D itself: the library sees the same mesh bit for bit, so its
 *    results must be the near run's, moved;
 *  - rounded: + a decimal offset, each coordinate rounded (what a real file holds): a different mesh
 *    by an ulp of the offset per coordinate. */
#ifndef ACD_TESTS_FAR_MESH_H
#define ACD_TESTS_FAR_MESH_H

#include "testutil.h"

#include <math.h>

#include "acd/mesh.h"

/* the largest side of m's bounding box */
static inline double far_extent(const acd_mesh *m) {
    double e = 0;
    for (int k = 0; k < 3; k++) {
        double lo = INFINITY, hi = -INFINITY;
        for (size_t v = 0; v < m->nvertices; v++) lo = fmin(lo, m->vertices[3 * v + k]), hi = fmax(hi, m->vertices[3 * v + k]);
        e = fmax(e, hi - lo);
    }
    return e;
}

/* coordinates rounded to multiples of 2^grid */
static inline void far_quantize(acd_mesh *m, int grid) {
    for (size_t i = 0; i < 3 * m->nvertices; i++) m->vertices[i] = ldexp(nearbyint(ldexp(m->vertices[i], -grid)), grid);
}

/* The exact offset for `ratio` extents E along (1, 1, 1) scaled by dir: a multiple of the power of
 * two above E (so that the frame's translation is the offset itself: a mesh whose box centre is
 * within half that power of the origin). */
static inline void far_offset(double E, double ratio, const double dir[3], double D[3]) {
    int ex;
    (void)frexp(E, &ex);
    double P = ldexp(1.0, ex);
    for (int k = 0; k < 3; k++) D[k] = P * nearbyint(dir[k] * ratio * E / P);
}

/* m + D; exact: asserts that every coordinate moved back gives the original */
static inline void far_translate_exact(acd_mesh *m, const double D[3]) {
    for (size_t v = 0; v < m->nvertices; v++)
        for (int k = 0; k < 3; k++) {
            double x = m->vertices[3 * v + k], y = x + D[k];
            assert_true(y - D[k] == x && (y - x) == D[k]);
            m->vertices[3 * v + k] = y;
        }
}

/* m + d on every coordinate, rounded */
static inline void far_translate_rounded(acd_mesh *m, double d) {
    for (size_t i = 0; i < 3 * m->nvertices; i++) m->vertices[i] += d;
}

/* ulp of the largest coordinate magnitude of n points: the model coordinates' spacing there */
static inline double far_spacing(const double *p, size_t n) {
    double big = 0;
    for (size_t i = 0; i < 3 * n; i++) big = fmax(big, fabs(p[i]));
    return nextafter(big, INFINITY) - big;
}

/* Signed volume and area of m about the point o (the tests' own, in their local frame). */
static inline double far_volume_about(const acd_mesh *m, const double o[3], double *area) {
    double v = 0, a = 0;
    for (size_t t = 0; t < m->ntriangles; t++) {
        double p[3][3];
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++) p[i][k] = m->vertices[3 * (size_t)m->triangles[3 * t + i] + k] - o[k];
        double bc[3] = {p[1][1] * p[2][2] - p[1][2] * p[2][1], p[1][2] * p[2][0] - p[1][0] * p[2][2],
                        p[1][0] * p[2][1] - p[1][1] * p[2][0]};
        v += p[0][0] * bc[0] + p[0][1] * bc[1] + p[0][2] * bc[2];
        double u[3], w[3];
        for (int k = 0; k < 3; k++) u[k] = p[1][k] - p[0][k], w[k] = p[2][k] - p[0][k];
        double x = u[1] * w[2] - u[2] * w[1], y = u[2] * w[0] - u[0] * w[2], z = u[0] * w[1] - u[1] * w[0];
        a += 0.5 * sqrt(x * x + y * y + z * z);
    }
    if (area) *area = a;
    return v / 6;
}

#endif
