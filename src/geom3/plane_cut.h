/* geom3/plane_cut: split a closed triangle mesh by a plane into closed, consistently oriented
 * pieces, every cross-section capped by a triangulation of polygons with holes.
 *
 * Solid ACD resolves a cut loop by a plane (Lien D §V.B.3, P §4.3) and caps the section
 * (spec acd3d.md §5.3, after Chazelle's cut as summarised in D §II.B.2).
 *
 * The plane is three points a, b, c (positive side: where (b - a) x (c - a) points). Every side
 * decision is acd_orient3d(a, b, c, v), exact: a vertex is above, below or exactly on the plane.
 * A plane given by point and normal is turned into three such points once (acd_cut_plane_from_normal);
 * the plane actually used is then the one through those points, which differs from the requested
 * one only by the rounding of the two spanning points. */
#ifndef ACD_GEOM3_PLANE_CUT_H
#define ACD_GEOM3_PLANE_CUT_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "acd/mesh.h"
#include "geom3/edge_map.h"

typedef struct acd_cut_plane {
    double a[3], b[3], c[3]; /* three points of the plane, not collinear */
    double normal[3];        /* unit normal (b - a) x (c - a) normalised (approximate; sides are exact) */
} acd_cut_plane;

/* Plane through three points. ACD_ERR_DEGENERATE if they are collinear (exactly). */
acd_status acd_cut_plane_from_points(const double a[3], const double b[3], const double c[3], acd_cut_plane *out,
                                     acd_error *err);
/* Plane through point with the given normal (any length > 0). size: the distance of the two
 * spanning points from point (use the model's extent; <= 0 means 1). */
acd_status acd_cut_plane_from_normal(const double point[3], const double normal[3], double size, acd_cut_plane *out,
                                     acd_error *err);
/* +1 on the normal's side, -1 on the other, 0 exactly on the plane. */
int acd_cut_plane_side(const acd_cut_plane *pl, const double v[3]);

typedef struct acd_cut_piece {
    acd_mesh mesh;       /* closed, counterclockwise seen from outside */
    int side;            /* +1: on the normal's side, -1: the other side */
    uint8_t *is_cap;     /* mesh.ntriangles: 1 for triangles of the cap (the cross-section) */
    uint32_t *source;    /* mesh.nvertices: the input vertex, or ACD_CUT_NEW_VERTEX for a point made on
                            a crossing edge */
    int closed;          /* 1: known to pass acd_edge_map_check_closed (checked by the cut); 0: not known */
} acd_cut_piece;

#define ACD_CUT_NEW_VERTEX UINT32_MAX

typedef struct acd_cut_result {
    acd_cut_piece *pieces; /* the + side pieces first, then the - side; each side by lowest input triangle */
    size_t npieces;
    size_t nloops;         /* section loops */
    size_t nregions;       /* section regions (an outer loop with its holes) */
    double section_area;   /* area of the cross-section (the cap) */
    size_t nforced;        /* triangulation steps forced on loops that rounding made self-touching */
    size_t ndropped;       /* faces of flat shells dropped (enclosing no volume: plane_cut.c) */
} acd_cut_result;

/* Splits the closed mesh m (every edge used once in each direction; ACD_ERR_NON_MANIFOLD otherwise)
 * by the plane. Faces lying in the plane go to the side their interior lies on (the side opposite to
 * their outward normal). A mesh entirely on one side comes back as its connected components. Flat
 * shells (mean thickness below 1e-12 of the bounding-box diagonal) are dropped (ndropped), so the
 * pieces' volumes add up to m's within rounding plus 1e-12 * diagonal * half the dropped area. */
acd_status acd_plane_cut(const acd_mesh *m, const acd_cut_plane *pl, acd_cut_result *out, acd_error *err);
/* Flags of acd_plane_cut_flags. DROP_SPECKS: every shell whose volume is within rounding (see
 * ACD_PLANE_CUT_VOLUME_ROUNDING in plane_cut.c) is dropped; by default only those of negative
 * volume inside a piece are (the others come back as pieces of their own). */
#define ACD_PLANE_CUT_DROP_SPECKS 1u
acd_status acd_plane_cut_flags(const acd_mesh *m, const acd_cut_plane *pl, unsigned flags, acd_cut_result *out,
                               acd_error *err);
/* The same with the mesh's edge map (acd_edge_map_build of all its triangles) already built and
 * checked by acd_edge_map_check_closed (NULL: built and checked here): for several cuts of one mesh.
 * A map from acd_edge_map_closed carries its twins (map->twin), which the cut uses; without them
 * each cut computes them again. */
acd_status acd_plane_cut_map(const acd_mesh *m, const acd_edge_map *map, const acd_cut_plane *pl, unsigned flags,
                             acd_cut_result *out, acd_error *err);
/* The bodies of the closed mesh m, as pieces without a cut (no cap, nloops 0): its edge-connected
 * shells, each shell of negative volume (a cavity) joined to the smallest shell of positive volume
 * containing it, flat shells dropped, exactly as acd_plane_cut's pieces of one side (it is that cut
 * by a plane beyond m's bounding box). A mesh of one body comes back as one piece. map: as for
 * acd_plane_cut_map (NULL: built and checked here). */
acd_status acd_plane_cut_bodies(const acd_mesh *m, const acd_edge_map *map, acd_cut_result *out, acd_error *err);
void acd_cut_result_free(acd_cut_result *r);
/* Whether every piece of r is closed and consistently oriented (acd_edge_map_check_closed; a
 * piece the cut already checked, closed = 1, is not checked again): ACD_OK, else the first failing
 * piece's status (ACD_ERR_NOMEM when the check ran out of memory). Rounding can leave a piece with
 * a triangle repeating a vertex, or on a pinched part an edge used twice in one direction. */
acd_status acd_cut_result_check_closed(const acd_cut_result *r);

#endif
