/* geom3/bvh: axis-aligned bounding-box tree over the triangles of a mesh.
 *
 * Build: binned surface-area heuristic (16 bins per axis, split on triangle centroids), median
 * split when the centroids coincide on every axis; leaves hold at most ACD_BVH_LEAF_MAX
 * triangles. The build depends only on the input: the same mesh always gives the same tree (node
 * numbering included), built sequentially or (acd_bvh_build_threads) by parallel subtree tasks.
 *
 * Queries: closest point on the mesh to a point, first hit of a ray, triangles whose boxes meet
 * a box or an axis-parallel line, and every pair of triangles whose (optionally enlarged) boxes
 * overlap (the broad phase of self-intersection tests). Box tests are closed (touching boxes
 * overlap) and use comparisons only, so no candidate is lost to rounding.
 *
 * The tree keeps pointers to the caller's vertex and triangle arrays: they must outlive it and
 * stay unchanged. A tree may be queried from several threads at once (queries do not write). */
#ifndef ACD_GEOM3_BVH_H
#define ACD_GEOM3_BVH_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"

#define ACD_BVH_LEAF_MAX 4

typedef struct acd_bvh_node {
    double lo[3], hi[3]; /* box of the node's triangles */
    uint32_t first;      /* leaf: first index into acd_bvh.order; inner: index of the left child
                            (the right child is first + 1) */
    uint32_t count;      /* leaf: number of triangles (1..ACD_BVH_LEAF_MAX); inner node: 0 */
} acd_bvh_node;

typedef struct acd_bvh {
    const double *vertices;    /* 3 * nvertices, caller-owned */
    size_t nvertices;
    const uint32_t *triangles; /* 3 * ntriangles, caller-owned */
    size_t ntriangles;
    acd_bvh_node *nodes;       /* node 0 is the root; children always have larger indices than
                                  their parent (so a reverse sweep visits children first) */
    size_t nnodes;             /* 0 when the mesh has no triangles */
    uint32_t *order;           /* ntriangles: triangle indices, leaf by leaf */
    double *boxes;             /* 6 * ntriangles: box (lo, hi) of triangle order[i] at 6 * i */
} acd_bvh;

/* Builds the tree. Fails with ACD_ERR_INVALID_INPUT (naming the triangle) on an index out of
 * range or a non-finite coordinate of a used vertex, ACD_ERR_NOMEM on allocation failure.
 * ntriangles == 0 gives an empty tree (queries then find nothing). On failure *bvh is empty. */
acd_status acd_bvh_build(acd_bvh *bvh, const double *vertices, size_t nvertices, const uint32_t *triangles,
                         size_t ntriangles, acd_error *err);
/* The same tree, bit for bit (nodes, order, boxes), built with up to `threads` OpenMP workers
 * (<= 1: acd_bvh_build): a large tree's subtrees are built by parallel tasks and numbered as the
 * sequential build numbers them. Inside an active parallel region it runs on the calling thread. */
acd_status acd_bvh_build_threads(acd_bvh *bvh, const double *vertices, size_t nvertices, const uint32_t *triangles,
                                 size_t ntriangles, int threads, acd_error *err);
void acd_bvh_free(acd_bvh *bvh);
/* Whether bvh (may be NULL) is a tree over exactly these arrays (the same pointers and counts): what a
 * caller handed a tree built elsewhere checks before using it in place of building one (it promises the
 * rest: built by acd_bvh_build or acd_bvh_build_threads, the arrays unchanged since). */
int acd_bvh_is_over(const acd_bvh *bvh, const double *vertices, size_t nvertices, const uint32_t *triangles,
                    size_t ntriangles);

/* Closest point of triangle (a, b, c) to p (also for degenerate triangles); returns the
 * squared distance and writes the point to q. */
double acd_closest_point_triangle(const double p[3], const double a[3], const double b[3], const double c[3],
                                  double q[3]);

typedef struct acd_bvh_closest_result {
    double dist2;      /* squared distance from the query to point */
    double point[3];   /* the closest point of the mesh */
    uint32_t triangle; /* the triangle it lies on (the lowest index among equally close ones
                          found first in the deterministic traversal) */
} acd_bvh_closest_result;

/* Closest point of the mesh to p among points at squared distance <= max_dist2 (pass INFINITY
 * for no limit). Returns 1 and fills *out when one exists, else 0. */
int acd_bvh_closest(const acd_bvh *bvh, const double p[3], double max_dist2, acd_bvh_closest_result *out);

/* The same restricted to closest points that `accept` accepts (called with the triangle and the
 * candidate point; non-zero accepts). Finds the nearest accepted candidate among the per-triangle
 * closest points: an accepted triangle whose own closest point is refused is not searched further. */
typedef int (*acd_bvh_accept_fn)(void *user, uint32_t triangle, const double point[3]);
int acd_bvh_closest_filtered(const acd_bvh *bvh, const double p[3], double max_dist2, acd_bvh_accept_fn accept,
                             void *user, acd_bvh_closest_result *out);

/* First intersection of the ray origin + t dir, 0 <= t <= tmax, with the mesh (Moller-Trumbore in
 * floating point: not exact at edges; spatial.h gives exact inside/outside). Returns 1 with *t
 * and *triangle set on a hit, else 0. */
int acd_bvh_raycast(const acd_bvh *bvh, const double origin[3], const double dir[3], double tmax, double *t,
                    uint32_t *triangle);

/* Visitor: return non-zero to stop the traversal. */
typedef int (*acd_bvh_tri_fn)(void *user, uint32_t triangle);
typedef int (*acd_bvh_pair_fn)(void *user, uint32_t a, uint32_t b);

/* Calls fn for every triangle whose box meets the closed box [lo, hi]. Returns 1 if fn stopped
 * the traversal, else 0. */
int acd_bvh_query_box(const acd_bvh *bvh, const double lo[3], const double hi[3], acd_bvh_tri_fn fn, void *user);

/* Calls fn for every triangle whose box reaches beyond the plane n.x = off (some corner with
 * n.x > off): every triangle with a point beyond it, and some without. Returns 1 if fn stopped the
 * traversal, else 0. */
int acd_bvh_query_halfspace(const acd_bvh *bvh, const double n[3], double off, acd_bvh_tri_fn fn, void *user);

/* Calls fn for every triangle whose box meets the line through p parallel to coordinate axis
 * `axis` (0, 1, 2), restricted to coordinates >= p[axis] when `forward` is non-zero. */
int acd_bvh_query_axis_line(const acd_bvh *bvh, const double p[3], int axis, int forward, acd_bvh_tri_fn fn,
                            void *user);

/* Calls fn(a, b) with a < b once for every pair of distinct triangles whose boxes, each enlarged
 * by `margin` (>= 0) on every side, overlap. Pairs sharing vertices are reported too (the
 * caller decides). The order of the calls is deterministic. Returns 1 if fn stopped it. */
int acd_bvh_overlap_pairs(const acd_bvh *bvh, double margin, acd_bvh_pair_fn fn, void *user);

/* The same pairs collected into a malloc'd array of 2 * *npairs indices, sorted by (a, b).
 * *pairs is NULL when there are none. */
acd_status acd_bvh_collect_pairs(const acd_bvh *bvh, double margin, uint32_t **pairs, size_t *npairs,
                                 acd_error *err);

#endif
