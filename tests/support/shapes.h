/* Test meshes made in code: closed, consistently oriented (counterclockwise seen from outside). */
#ifndef ACD_SHAPES_H
#define ACD_SHAPES_H

#include "acd/mesh.h"

/* Star-shaped closed surface around the origin: the point at polar angle theta (from +z) and
 * azimuth phi is r(theta, phi) times the unit direction. nu >= 3 azimuth steps, nv >= 2 polar steps.
 * Returns 0 on allocation failure. */
typedef double (*mg_radius_fn)(double theta, double phi, void *user);
int mg_radial(acd_mesh *m, int nu, int nv, mg_radius_fn r, void *user);
/* A radius for mg_radial: a sphere with bumps (1 + 0.25 sin 3theta cos 4phi + 0.1 cos 5theta), hull
 * excess everywhere as on a scanned surface's relief; user unused. */
double mg_bumpy_r(double theta, double phi, void *user);

/* Torus with radii R > r around the z axis. */
int mg_torus(acd_mesh *m, int nu, int nv, double R, double r);

/* Closed surface of a union of unit voxels: occ[(z * ny + y) * nx + x] non-zero for filled cells.
 * The voxel set must not touch itself along an edge or at a vertex only (manifold output). */
int mg_voxels(acd_mesh *m, const unsigned char *occ, int nx, int ny, int nz);

/* Signed volume (divergence theorem). */
double mg_volume(const acd_mesh *m);

#endif
