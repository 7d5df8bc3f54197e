/* geom3/polyunion: the boundary of the union of convex polytopes as one closed triangle mesh,
 * with every decision exact (plane-based geometry on integer planes, 128-bit arithmetic).
 *
 * Method (docs/corise.md, "Cages"):
 *  - planes: the given directions plus the six axis directions, each supporting the polytope's
 *    points, then pushed outward by the offset (the axis planes cap sharp pushed corners);
 *  - quantize: the polytopes are put on a grid of 2^ACD_POLYUNION_GRID_BITS units per half extent;
 *    each facet plane gets an integer normal (ACD_POLYUNION_NORMAL_BITS bits) and an integer offset
 *    rounded OUTWARD past every vertex of its polytope, so each quantized polytope (the
 *    intersection of its half-spaces) contains the input polytope;
 *  - every point is the meet of three integer planes, kept as exact homogeneous coordinates
 *    (X, Y, Z, W) in 128-bit integers (reduced, W > 0), and every side test is the exact sign of
 *    a plane at such a point (the bit budget is in polyunion.c);
 *  - each facet (its plane's big square clipped by its polytope's other planes) is cut by the
 *    planes of every other polytope; the pieces inside another polytope are dropped. Coplanar
 *    facets: facing the same way, the lower polytope index keeps the shared region; facing each
 *    other (polytopes glued along a face), both drop it;
 *  - the surviving convex pieces are made conforming (every vertex lying inside a piece's edge,
 *    exactly, is inserted there) and triangulated by ear clipping without degenerate triangles;
 *    equal points are one vertex (equal reduced coordinates).
 * The result is closed (every edge used once in each direction) and has no interior faces;
 * polytopes touching along an edge or at a vertex give a non-manifold edge or vertex there.
 * Output coordinates are the exact points rounded to double. */
#ifndef ACD_GEOM3_POLYUNION_H
#define ACD_GEOM3_POLYUNION_H

#include <stddef.h>

#include "acd/base.h"
#include "acd/hull.h"
#include "acd/mesh.h"

#define ACD_POLYUNION_NORMAL_BITS 20
#define ACD_POLYUNION_GRID_BITS 26

typedef struct acd_polyunion_stats {
    size_t polytopes;  /* solid (dim 3) input hulls used */
    size_t planes;     /* facet planes after quantization (duplicate and redundant ones dropped) */
    size_t corners;    /* sum over the polytopes of their distinct facet corners after quantization */
    size_t fragments;  /* convex facet pieces on the union's boundary */
    size_t inserted;   /* vertices inserted into piece edges to make the pieces conforming */
} acd_polyunion_stats;

/* One polytope: the intersection of half-spaces n.x + d <= 0 with the given normals (only the
 * directions are read) and the six axis directions, each d chosen (outward, exactly) so that
 * every point is inside, then pushed out by the offset. With the points of a convex hull and its
 * facet planes this is the hull; with a subset of the planes, an enclosing polytope. The polytope
 * must be solid: points spanning 3D, or a positive offset. */
typedef struct acd_polyunion_polytope {
    const double *planes; /* 4 per plane (normal, offset); the normal is normalised here */
    size_t nplanes;
    const double *points; /* 3 per point */
    size_t npoints;       /* 0: the polytope is skipped */
} acd_polyunion_polytope;

/* Union of polytopes[0..n) (at least one with points, else ACD_ERR_DEGENERATE), each with its
 * planes pushed outward by `offset` (model units, >= 0; the pushed polytope holds every point
 * within offset of the points' polytope). out is caller-owned (freed with acd_mesh_free, also
 * after a failure); stats may be NULL. */
acd_status acd_polyunion(const acd_polyunion_polytope *polytopes, size_t n, double offset, acd_mesh *out,
                         acd_polyunion_stats *stats, acd_error *err);

#endif
