/* eval/eval3d: the union of a set of convex hulls as a queryable object (plane tests, line
 * intervals, boundary test, closest hull-surface point), shared by `acd eval` (include/acd/eval.h)
 * and any --verify check that needs "is this point covered by the hulls". */
#ifndef ACD_EVAL_EVAL3D_H
#define ACD_EVAL_EVAL3D_H

#include <stddef.h>
#include <stdint.h>

#include "acd/hull.h"
#include "geom3/bvh.h"
#include "geom3/spatial.h"

/* A point pushed this far (relative to the model's diagonal) out of a hull's facet and found in
 * another hull is not on the boundary of the union: hulls closer than this count as touching. */
#define ACD_EVAL_PROBE_REL 1e-7

typedef struct acd_hullset_hull {
    double lo[3], hi[3];   /* bounding box */
    double centroid[3];    /* mean of the vertices */
    size_t first_plane, nplanes; /* distinct facet planes in acd_hullset.planes */
    size_t first_vertex, nvertices; /* its vertices in acd_hullset.vertices */
} acd_hullset_hull;

typedef struct acd_hullset {
    acd_hullset_hull *hulls; /* the solid (dim 3) hulls only */
    size_t nhulls;
    double *planes;          /* 4 per plane: n, d with n.x + d <= 0 inside */
    double *vertices;        /* all hull vertices, hull after hull */
    size_t nvertices;
    uint32_t *triangles;     /* all hull triangles, indexed into vertices */
    size_t ntriangles;
    uint32_t *tri_hull;      /* hull of each triangle */
    double *tri_normal;      /* 3 per triangle: the outward unit normal of its facet */
    double probe;            /* ACD_EVAL_PROBE_REL times the reference diagonal */
    acd_spatial sp;          /* over the triangles (a closed mesh: its winding number at a point is
                                the number of hulls holding it, decided exactly) */
} acd_hullset;

/* Builds the set from the dim-3 hulls among `hulls` (others are skipped). `diagonal` is the
 * reference length for the probe distance. */
acd_status acd_hullset_build(acd_hullset *hs, const acd_hull *hulls, size_t nhulls, double diagonal,
                             acd_error *err);
void acd_hullset_free(acd_hullset *hs);

/* 1 when p lies in hull h (closed: every plane value <= 0). */
int acd_hullset_in_hull(const acd_hullset *hs, size_t h, const double p[3]);
/* 1 when a hull other than `skip` (SIZE_MAX for none) holds p (closed hulls; exact ray crossings
 * over the hulls' triangles, see geom3/spatial.h). */
int acd_hullset_contains(const acd_hullset *hs, const double p[3], size_t skip);
/* 1 when the point q on the surface of hull h, with outward direction dir (unit), is on the
 * boundary of the union: q + probe * dir lies in no other hull. */
int acd_hullset_on_boundary(const acd_hullset *hs, size_t h, const double q[3], const double dir[3]);
/* Interval [*t0, *t1] of x where the line {(x, y, z)} is in hull h; 0 when it misses it. */
int acd_hullset_x_interval(const acd_hullset *hs, size_t h, double y, double z, double *t0, double *t1);

#endif
