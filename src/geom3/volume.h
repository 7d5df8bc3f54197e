/* geom3/volume: volumes of closed triangle meshes by the divergence theorem: the whole solid's, the
 * part of it beyond a plane (per triangle and per mesh), and a bound of the part outside a hull.
 * (Declared here: the internal acd_geom3_* functions; the public acd_mesh_volume_beyond and
 * acd_hull_volume_outside_bound, defined in volume.c, are declared in acd/mesh.h and acd/hull.h.) */
#ifndef ACD_GEOM3_VOLUME_H
#define ACD_GEOM3_VOLUME_H

#include "acd/mesh.h"
#include "geom3/vec3.h"

/* Signed volume of a closed mesh (divergence theorem about the bounding-box centre). */
double acd_geom3_signed_volume(const acd_mesh *m);

/* The part of triangle (a, b, c) where n.x > off, coned to apex (a point on the plane n.x = off):
 * the signed volume of that cone. Summed over the triangles of a closed, outward mesh, it is the
 * volume of the solid beyond the plane (the section, in the plane, adds nothing). n need not be
 * unit. Triangles entirely at or below the plane give 0. */
double acd_geom3_triangle_volume_beyond(const double a[3], const double b[3], const double c[3], const double n[3],
                                        double off, const double apex[3]);

/* Its clip and cone, given the corners' s[j] = n.p[j] - off (computed by the caller, as
 * acd_geom3_triangle_volume_beyond computes them: acd3/trim_beyond takes a triangle's n.p once for
 * several offsets): the part of the triangle where s > 0 (Sutherland-Hodgman: at most 4 corners),
 * coned to apex, its signed volume (0 when no corner has s > 0). */
static inline double acd_geom3_clipped_cone_volume(const double *const p[3], const double s[3], const double apex[3]) {
    double poly[4][3];
    int np = 0;
    for (int k = 0; k < 3; k++) {
        const int j = k == 2 ? 0 : k + 1;
        if (s[k] > 0)
            for (int q = 0; q < 3; q++) poly[np][q] = p[k][q] - apex[q];
        np += s[k] > 0;
        if ((s[k] > 0) != (s[j] > 0)) {
            const double t = s[k] / (s[k] - s[j]);
            for (int q = 0; q < 3; q++) poly[np][q] = p[k][q] + t * (p[j][q] - p[k][q]) - apex[q];
            np++;
        }
    }
    double v = 0;
    for (int k = 1; k + 1 < np; k++) {
        double bc[3];
        acd_cross3(poly[k], poly[k + 1], bc);
        v += poly[0][0] * bc[0] + poly[0][1] * bc[1] + poly[0][2] * bc[2];
    }
    return v / 6.0;
}

#endif
