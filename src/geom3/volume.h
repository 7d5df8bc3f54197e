/* geom3/volume: volumes of closed triangle meshes by the divergence theorem: the whole solid's, the
 * part of it beyond a plane (per triangle and per mesh), and a bound of the part outside a hull.
 * (Declared here: the internal acd_geom3_* functions; the public acd_mesh_volume_beyond and
 * acd_hull_volume_outside_bound, defined in volume.c, are declared in acd/mesh.h and acd/hull.h.) */
#ifndef ACD_GEOM3_VOLUME_H
#define ACD_GEOM3_VOLUME_H

#include "acd/mesh.h"

/* Signed volume of a closed mesh (divergence theorem about the bounding-box centre). */
double acd_geom3_signed_volume(const acd_mesh *m);

/* The part of triangle (a, b, c) where n.x > off, coned to apex (a point on the plane n.x = off):
 * the signed volume of that cone. Summed over the triangles of a closed, outward mesh, it is the
 * volume of the solid beyond the plane (the section, in the plane, adds nothing). n need not be
 * unit. Triangles entirely at or below the plane give 0. */
double acd_geom3_triangle_volume_beyond(const double a[3], const double b[3], const double c[3], const double n[3],
                                        double off, const double apex[3]);

#endif
