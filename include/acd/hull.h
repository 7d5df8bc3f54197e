/* acd/hull.h: 3D convex hulls (through qhull's reentrant library), with defined results for
 * degenerate input and facet adjacency for the decomposition code. Implemented in src/geom3/. */
#ifndef ACD_HULL_H
#define ACD_HULL_H

#include "acd/base.h"
#include "acd/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ACD_HULL_NO_NEIGHBOR UINT32_MAX

typedef struct acd_hull {
    int dim;              /* affine dimension of the input: 3 (solid), 2 (planar), 1 (collinear), 0 (one point), -1 empty */
    double *vertices;     /* 3 * nvertices: the hull's vertices */
    size_t nvertices;
    uint32_t *triangles;  /* 3 * ntriangles, counterclockwise seen from outside (dim 3); for dim 2 the
                             polygon triangulated (both sides not duplicated); none for dim < 2 */
    size_t ntriangles;
    uint32_t *neighbors;  /* 3 * ntriangles: the triangle across edge (t[i], t[i+1 mod 3]);
                             ACD_HULL_NO_NEIGHBOR on the boundary of a planar (dim 2) hull */
    double *planes;       /* 4 * ntriangles: outward unit normal n and offset d, n.x + d = 0 (dim 3);
                             for dim 2 every row is the polygon's plane, n the side seen counterclockwise.
                             dim 3: every input point p has n.p + d <= ACD_TOL_REL_DIST x the bounding-box
                             diagonal (a plane qhull left a point outside of is lifted to it, so it may
                             pass below its triangle's vertices by that much: docs/results/fuzz.md) */
    uint32_t *source;     /* nvertices: index of each hull vertex in the input points */
    double volume;        /* 0 unless dim == 3 */
    double area;
} acd_hull;

/* Hull of n points (3 doubles each). Duplicates, coplanar and collinear sets and n < 4 give a
 * hull of lower dim rather than an error; NaN/Inf coordinates are ACD_ERR_INVALID_INPUT.
 * The dimension is the numerical affine dimension at ACD_TOL_REL_DIST x the bounding-box diagonal:
 * points within that distance of a plane (line, point) give a dim 2 (1, 0) hull (docs/geom3.md).
 * dim 0: one vertex; dim 1: the two extreme points, in input order along the line; dim 2: the convex
 * polygon's vertices in counterclockwise order (seen from the planes' normal), fanned into triangles.
 * Every hull vertex is an input point (source gives which). out is caller-owned, freed with
 * acd_hull_free (also safe after a failure). */
acd_status acd_hull_compute(const double *points, size_t n, acd_hull *out, acd_error *err);
void acd_hull_free(acd_hull *h);
/* Moves h out: returns it and leaves h empty (as acd_hull_free leaves it), so that the arrays have
 * one owner. */
acd_hull acd_hull_take(acd_hull *h);
/* The volume of the same hull (acd_hull_compute's out.volume, the same bits: 0 unless dim 3)
 * without building it; except where acd_hull_compute had to rebuild qhull's hull because qhull lost
 * an input point (rare ill-conditioned sets, docs/results/geom3.md): then this is still qhull's
 * volume, which may differ in the last digits (3.36084547e-7 against 3.36084586e-7 on the fuzz case). */
acd_status acd_hull_volume(const double *points, size_t n, double *volume, acd_error *err);

/* dim 3: max over facets of n.p + d (<= 0 inside; a lower bound of the signed distance outside).
 * dim 0, 1, 2: the Euclidean distance from p to the point, segment or polygon (>= 0).
 * Empty hull: +INFINITY. */
double acd_hull_plane_distance(const acd_hull *h, const double p[3]);

/* An upper bound of the volume of the closed, outward solid m outside the hull h (dim 3): the
 * solid's volume beyond each plane of a facet some vertex of m lies beyond by more than tol, summed
 * over the distinct planes (the triangles of one facet share its plane, planes within 1e-9 in
 * normal and 1e-9 x tol_scale in offset count once; a region beyond two planes is counted twice).
 * 0 when every vertex of m is within tol of h. NaN when out of memory. Used to check trimmed hulls
 * (acd3d_params.trim_coverage) where acd_hull_volume_outside fails. */
double acd_hull_volume_outside_bound(const acd_hull *h, const acd_mesh *m, double tol, double tol_scale);
/* The volume of the closed, outward solid m outside the hull h, exactly up to rounding: m cut
 * successively by each of the planes acd_hull_volume_outside_bound sums over (the distinct planes of
 * the facets some vertex of m lies beyond by more than tol; the same tol and tol_scale), every piece
 * that reaches beyond the plane split by it (acd_plane_cut, exact sides: geom3/plane_cut.h; each
 * plane turned into three points once, through the facet's centre projected onto it), the pieces
 * beyond taken off; *outside is the sum of their volumes, the pieces left lie inside every plane.
 * A region beyond several planes counts once, so *outside <= the bound (up to rounding), and is 0
 * when no vertex of m is beyond h by more than tol (then m is not looked at further: not checked
 * closed). h of dim < 3 (no interior): the whole solid's volume. Specks of volume within rounding
 * and flat shells are dropped by the cuts (acd_plane_cut_flags with ACD_PLANE_CUT_DROP_SPECKS).
 * On a solid that crosses itself the volumes are signed (winding numbers), as every volume here.
 * Where a cut fails on a solid that is closed as a chain of triangles (every edge used as often
 * in each direction) but not a manifold the cut takes (a part the rounding back to model
 * coordinates pinched, one crossing itself), the volume is taken tetrahedron by tetrahedron
 * instead: each triangle's tetrahedron from the centroid of h's vertices, signed by its
 * orientation, is split by the same planes in turn and the pieces beyond each summed (convex
 * pieces, no topology: winding numbers again), ACD_OK.
 * Returns ACD_OK; ACD_ERR_NOMEM when out of memory (also inside a cut); ACD_ERR_INVALID_ARGUMENT
 * for NULL pointers or a tol or tol_scale that is not finite; any other status is a plane cut that
 * failed on a solid not closed as a chain (open, or a triangle flipped), its own status with the
 * plane named in err (ACD_ERR_NON_MANIFOLD), or where a tetrahedron would be split into more than
 * 65536 pieces. On failure *outside is NaN: a caller may fall back to the bound. Serial and
 * deterministic. */
acd_status acd_hull_volume_outside(const acd_hull *h, const acd_mesh *m, double tol, double tol_scale,
                                   double *outside, acd_error *err);

/* An undirected hull edge v[0] < v[1]: left is the triangle that runs v[0] -> v[1] (the facet on the
 * left walking from v[0] to v[1], seen from outside), right the one that runs v[1] -> v[0];
 * ACD_HULL_NO_NEIGHBOR on the boundary of a planar hull. */
typedef struct acd_hull_edge {
    uint32_t v[2];
    uint32_t left, right;
} acd_hull_edge;

/* The hull's edges in increasing (v[0], v[1]) order, in a malloc'd array (caller frees). dim < 2:
 * none for dim 0, one (0, 1) for dim 1 (left = right = ACD_HULL_NO_NEIGHBOR). */
acd_status acd_hull_edges(const acd_hull *h, acd_hull_edge **edges, size_t *nedges, acd_error *err);

#ifdef __cplusplus
}
#endif
#endif
