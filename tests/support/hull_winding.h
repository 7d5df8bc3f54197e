/* tests/support/hull_winding.h: the winding number of a hull's triangles about a point, and the
 * point's distance to them: the enclosure check of tests/test_hull.c (assert_mesh_encloses) and of
 * fuzz/fuzz_hull.c (built with -DFUZZ_HULL_CHECK_WINDING), which both include it. */
#ifndef ACD_TEST_HULL_WINDING_H
#define ACD_TEST_HULL_WINDING_H

#include <math.h>
#include <stddef.h>

#include "acd/hull.h"
#include "geom3/bvh.h"

/* The winding number of h's triangles about point p (the solid angles of the triangles seen from
 * p, by Van Oosterom and Strackee's formula, over 4 pi: 1 inside a closed outward mesh, 0 outside)
 * and in *dist p's distance to the triangles, both in coordinates normalised by the box centre cen
 * and the extent ext (so that any scale behaves the same; *dist in units of ext). */
static inline double hull_winding(const acd_hull *h, const double *p, const double cen[3], double ext, double *dist) {
    double q[3], cq[3], near = INFINITY, omega = 0;
    for (int k = 0; k < 3; k++) q[k] = (p[k] - cen[k]) / ext;
    for (size_t t = 0; t < h->ntriangles; t++) {
        double v[3][3], r[3][3], l[3];
        for (int j = 0; j < 3; j++) {
            for (int k = 0; k < 3; k++) {
                v[j][k] = (h->vertices[3 * (size_t)h->triangles[3 * t + j] + k] - cen[k]) / ext;
                r[j][k] = v[j][k] - q[k];
            }
            l[j] = sqrt(r[j][0] * r[j][0] + r[j][1] * r[j][1] + r[j][2] * r[j][2]);
        }
        near = fmin(near, sqrt(acd_closest_point_triangle(q, v[0], v[1], v[2], cq)));
        double det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                     r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
        double d01 = r[0][0] * r[1][0] + r[0][1] * r[1][1] + r[0][2] * r[1][2];
        double d02 = r[0][0] * r[2][0] + r[0][1] * r[2][1] + r[0][2] * r[2][2];
        double d12 = r[1][0] * r[2][0] + r[1][1] * r[2][1] + r[1][2] * r[2][2];
        omega += 2 * atan2(det, l[0] * l[1] * l[2] + d01 * l[2] + d02 * l[1] + d12 * l[0]);
    }
    *dist = near;
    return omega / (4 * 3.14159265358979323846);
}

#endif
