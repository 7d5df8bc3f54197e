/* geom3/spatial: point queries against a triangle mesh through its BVH: unsigned and signed
 * distance, winding number, inside/outside.
 *
 * Inside/outside (docs/eval.md, "Point in mesh"):
 *  - Closed meshes (every undirected edge is used as often in one direction as in the other,
 *    vertices with equal coordinates taken as one (a soup whose faces meet exactly is closed), so
 *    the triangles form a cycle without boundary; self-intersections and non-manifold edges are
 *    allowed): the winding number is an integer and equals the signed count of the crossings of
 *    the ray from the point towards +x. Each crossing is decided with the exact predicates
 *    (orient2d in the yz projection, orient3d for the side), and rays through edges or vertices
 *    are resolved by simulation of simplicity (the point is moved by (0, e, e^2) with e -> 0),
 *    so every point gets one consistent answer, with no tolerance. A point found exactly on a
 *    crossed triangle is reported on the surface.
 *  - Open meshes (holes, missing faces): the generalized winding number of Jacobson et al.
 *    (SIGGRAPH 2013), evaluated hierarchically as in Barill et al., "Fast winding numbers for
 *    soups and clouds" (SIGGRAPH 2018, sec. 3): a BVH node farther than ACD_SPATIAL_GWN_BETA times
 *    its radius contributes its Taylor expansion to second order (area vector at the area-weighted
 *    centroid plus the first moment of the area vectors about it); nearer
 *    nodes are opened down to exact triangle solid angles (Van Oosterom and Strackee 1983).
 *    The point is inside when |w| >= 1/2.
 * Both give the same answer on closed meshes away from the surface (up to the dipole error).
 *
 * The structure keeps pointers to the caller's arrays (see bvh.h). Queries are read-only and
 * may run in parallel. */
#ifndef ACD_GEOM3_SPATIAL_H
#define ACD_GEOM3_SPATIAL_H

#include "acd/base.h"
#include "core/tolerance.h"
#include "geom3/bvh.h"

/* Far-field acceptance: a node is approximated when the point is farther than beta * radius. */
#define ACD_SPATIAL_GWN_BETA 4.0

enum { ACD_SPATIAL_OUTSIDE = -1, ACD_SPATIAL_ON_SURFACE = 0, ACD_SPATIAL_INSIDE = 1 };

typedef struct acd_spatial {
    acd_bvh bvh;
    int closed;            /* no boundary edges: exact ray winding numbers */
    size_t boundary_edges; /* undirected edges whose two directions are not used equally often
                              (vertices with equal coordinates identified) */
    double *moments;       /* 16 per BVH node: area vector, area-weighted centroid, radius,
                              second-order moment (sum of area vector x offset of centroid) */
    acd_scale scale;       /* of the vertices used by triangles */
} acd_spatial;

acd_status acd_spatial_build(acd_spatial *sp, const double *vertices, size_t nvertices,
                             const uint32_t *triangles, size_t ntriangles, acd_error *err);
void acd_spatial_free(acd_spatial *sp);

/* Unsigned distance from p to the mesh (INFINITY for an empty mesh); closest may be NULL. */
double acd_spatial_distance(const acd_spatial *sp, const double p[3], acd_bvh_closest_result *closest);

/* Exact signed crossing count of the ray p + t (1, 0, 0), t > 0 (simulation of simplicity at
 * edges and vertices). *on_surface (may be NULL) is set when p was found on a crossed triangle. */
int acd_spatial_ray_winding(const acd_spatial *sp, const double p[3], int *on_surface);

/* Contribution of triangle t to acd_spatial_ray_winding(p): +1 or -1 when the ray from p towards
 * +x crosses it (exactly, with the same symbolic perturbation), else 0; *on_surface set when p
 * lies on it. For callers that count crossings per group of triangles (eval3d: per hull). */
int acd_spatial_ray_crossing(const acd_spatial *sp, uint32_t t, const double p[3], int *on_surface);

/* Generalized winding number, hierarchical approximation (any mesh), beta = ACD_SPATIAL_GWN_BETA
 * (error below 1e-2 on the test meshes). */
double acd_spatial_gwn(const acd_spatial *sp, const double p[3]);
/* The same with another acceptance factor (> 1): smaller is faster and coarser; 2 still decides
 * inside/outside (|w| >= 1/2) away from the surface; near it the exact near field rules. */
double acd_spatial_gwn_beta(const acd_spatial *sp, const double p[3], double beta);

/* Winding number by the method chosen for the mesh (ray for closed, generalized for open). */
double acd_spatial_winding_number(const acd_spatial *sp, const double p[3]);

/* ACD_SPATIAL_INSIDE, ACD_SPATIAL_OUTSIDE or (closed meshes, p on the surface) _ON_SURFACE. */
int acd_spatial_classify(const acd_spatial *sp, const double p[3]);

/* Distance, negative inside, 0 on the surface. */
double acd_spatial_signed_distance(const acd_spatial *sp, const double p[3]);

/* The crossings of one line parallel to x (at y, z), found once and then used to classify many
 * points of that line: the row-wise Monte Carlo sampling of eval3d. Caller-owned; reuse it
 * across lines and free it with acd_spatial_line_free. */
typedef struct acd_spatial_line {
    double y, z;
    uint32_t *triangles; /* crossed triangles */
    int8_t *signs;       /* +1 where the triangle's normal points to +x */
    size_t n, cap;
} acd_spatial_line;

acd_status acd_spatial_line_set(const acd_spatial *sp, double y, double z, acd_spatial_line *line,
                                acd_error *err);
/* Exact winding number at (x, line->y, line->z) from the line's crossings (closed meshes);
 * *on_surface as for acd_spatial_ray_winding. */
int acd_spatial_line_winding(const acd_spatial *sp, const acd_spatial_line *line, double x, int *on_surface);
/* Contribution of the line's crossing i to the winding number at x (see acd_spatial_ray_crossing). */
int acd_spatial_line_crossing(const acd_spatial *sp, const acd_spatial_line *line, size_t i, double x,
                              int *on_surface);
void acd_spatial_line_free(acd_spatial_line *line);

#endif
