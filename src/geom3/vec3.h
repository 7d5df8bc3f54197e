/* geom3/vec3: small vector helpers shared by the 3D modules (header only). */
#ifndef ACD_GEOM3_VEC3_H
#define ACD_GEOM3_VEC3_H

#include <math.h>

/* Euclidean distance between points a and b. */
static inline double acd_dist3(const double a[3], const double b[3]) {
    double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
    return sqrt(x * x + y * y + z * z);
}

#endif
