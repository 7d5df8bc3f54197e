/* geom3/vec3: small vector and triangle helpers shared by the 3D modules (header only). */
#ifndef ACD_GEOM3_VEC3_H
#define ACD_GEOM3_VEC3_H

#include <math.h>
#include <string.h>

/* The dot product a.b, summed in the order x, y, z. */
static inline double acd_dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* The cross product a x b into r (r must not alias a or b). */
static inline void acd_cross3(const double a[3], const double b[3], double r[3]) {
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

/* Euclidean distance between points a and b. */
static inline double acd_dist3(const double a[3], const double b[3]) {
    double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
    return sqrt(x * x + y * y + z * z);
}

/* The largest n.x over the axis-aligned box (lo, hi): whether any of it reaches beyond a plane. */
static inline double acd_box_max_dot(const double n[3], const double lo[3], const double hi[3]) {
    double s = 0;
    for (int k = 0; k < 3; k++) s += n[k] * (n[k] >= 0 ? hi[k] : lo[k]);
    return s;
}

/* Triangle t (corners a, b, c: 9 coordinates) split at its edges' midpoints into four, written to
 * sub (9 coordinates each): the triangles at a, b and c, then the middle one. */
static inline void acd_tri_split4(const double t[9], double sub[4][9]) {
    double m[9]; /* midpoints ab, bc, ca */
    for (int k = 0; k < 3; k++) {
        m[k] = 0.5 * (t[k] + t[3 + k]);
        m[3 + k] = 0.5 * (t[3 + k] + t[6 + k]);
        m[6 + k] = 0.5 * (t[6 + k] + t[k]);
    }
    const double *c[4][3] = {{t, m, m + 6}, {m, t + 3, m + 3}, {m + 6, m + 3, t + 6}, {m, m + 3, m + 6}};
    for (int s = 0; s < 4; s++)
        for (int k = 0; k < 3; k++) memcpy(sub[s] + 3 * k, c[s][k], sizeof(double[3]));
}

#endif
