/* acd3/trim_beyond: the volumes beyond a candidate plane that acd3/trim scores its cuts by (trim.h,
 * docs/acd3d.md "Trimmed hulls"), at all of the plane's depths in one pass over the triangles.
 *
 * A candidate is a plane n.x = off moved inward by ACD3_TRIM_NDEPTHS depths: levels off[k]
 * (decreasing) with cone apexes on each. The volume of a closed, outward mesh beyond level k is the
 * sum over its triangles of acd_geom3_triangle_volume_beyond (geom3/volume.c); here each
 * triangle's dots with n are computed once for all levels, and the part's triangles are read from a
 * copy of its BVH laid out in the order of its half-space query. The sums are bitwise those of
 * calling acd_geom3_triangle_volume_beyond per level in the query's order (the trimmed hulls depend
 * on every bit: tests/test_acd3_trim.c checks it). */
#ifndef ACD_ACD3_TRIM_BEYOND_H
#define ACD_ACD3_TRIM_BEYOND_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "geom3/bvh.h"
#include "geom3/vec3.h"
#include "geom3/volume.h"

#define ACD3_TRIM_NDEPTHS 6

/* A candidate plane's levels, shallowest first: offsets (decreasing) and the apexes of the cones
 * (points on each level's plane), by coordinate. */
typedef struct acd3_trim_levels {
    double off[ACD3_TRIM_NDEPTHS];
    double ax[ACD3_TRIM_NDEPTHS], ay[ACD3_TRIM_NDEPTHS], az[ACD3_TRIM_NDEPTHS];
} acd3_trim_levels;

/* The largest and the smallest of a triangle's corners' n.x (as fmax and fmin for the finite values
 * they are given, but without their calls: only compared) */
static inline double acd3_trim_top(const double d[3]) {
    const double m = d[0] > d[1] ? d[0] : d[1];
    return m > d[2] ? m : d[2];
}

static inline double acd3_trim_bot(const double d[3]) {
    const double m = d[0] < d[1] ? d[0] : d[1];
    return m < d[2] ? m : d[2];
}

/* acd_geom3_clipped_cone_volume(p, s, apex) bit for bit, its polygon by case instead of by the
 * clipping loop: the corners with s > 0 and the edges' crossings in the loop's order (corner k, then
 * the crossing on edge k -> k + 1), each coordinate by the same operations (a crossing p[k] + t * e[k]
 * - apex, e[k] = p[k + 1] - p[k] computed once per triangle by the caller: the function's p[j] -
 * p[k]), and the same fan (v from 0, a term per triangle of the fan, then / 6).
 * tests/test_acd3_trim.c compares the two for every sign pattern of s. */
static inline void acd3_trim_corner(const double *p, const double apex[3], double o[3]) {
    for (int q = 0; q < 3; q++) o[q] = p[q] - apex[q];
}

static inline void acd3_trim_crossing(const double *pk, const double ek[3], double sk, double sj, const double apex[3],
                                      double o[3]) {
    const double t = sk / (sk - sj);
    for (int q = 0; q < 3; q++) o[q] = pk[q] + t * ek[q] - apex[q];
}

/* a . (b x c), as the function adds it (acd_cross3, then the dot left to right) */
static inline double acd3_trim_fan_term(const double a[3], const double b[3], const double c[3]) {
    const double r0 = b[1] * c[2] - b[2] * c[1], r1 = b[2] * c[0] - b[0] * c[2], r2 = b[0] * c[1] - b[1] * c[0];
    return a[0] * r0 + a[1] * r1 + a[2] * r2;
}

/* (always inlined: called per level from acd3_trim_tri_beyond, its arrays then stay in registers) */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline double acd3_trim_clip_cone(const double *const p[3], const double e[3][3], const double s[3],
                                         const double apex[3]) {
    const int mask = (s[0] > 0) | (s[1] > 0) << 1 | (s[2] > 0) << 2;
    double a[3], b[3], c[3], d[3];
    double v = 0;
    switch (mask) {
    case 1: /* P0, X0, X2 */
        acd3_trim_corner(p[0], apex, a);
        acd3_trim_crossing(p[0], e[0], s[0], s[1], apex, b);
        acd3_trim_crossing(p[2], e[2], s[2], s[0], apex, c);
        v += acd3_trim_fan_term(a, b, c);
        break;
    case 2: /* X0, P1, X1 */
        acd3_trim_crossing(p[0], e[0], s[0], s[1], apex, a);
        acd3_trim_corner(p[1], apex, b);
        acd3_trim_crossing(p[1], e[1], s[1], s[2], apex, c);
        v += acd3_trim_fan_term(a, b, c);
        break;
    case 4: /* X1, P2, X2 */
        acd3_trim_crossing(p[1], e[1], s[1], s[2], apex, a);
        acd3_trim_corner(p[2], apex, b);
        acd3_trim_crossing(p[2], e[2], s[2], s[0], apex, c);
        v += acd3_trim_fan_term(a, b, c);
        break;
    case 3: /* P0, P1, X1, X2 */
        acd3_trim_corner(p[0], apex, a);
        acd3_trim_corner(p[1], apex, b);
        acd3_trim_crossing(p[1], e[1], s[1], s[2], apex, c);
        acd3_trim_crossing(p[2], e[2], s[2], s[0], apex, d);
        v += acd3_trim_fan_term(a, b, c);
        v += acd3_trim_fan_term(a, c, d);
        break;
    case 5: /* P0, X0, X1, P2 */
        acd3_trim_corner(p[0], apex, a);
        acd3_trim_crossing(p[0], e[0], s[0], s[1], apex, b);
        acd3_trim_crossing(p[1], e[1], s[1], s[2], apex, c);
        acd3_trim_corner(p[2], apex, d);
        v += acd3_trim_fan_term(a, b, c);
        v += acd3_trim_fan_term(a, c, d);
        break;
    case 6: /* X0, P1, P2, X2 */
        acd3_trim_crossing(p[0], e[0], s[0], s[1], apex, a);
        acd3_trim_corner(p[1], apex, b);
        acd3_trim_corner(p[2], apex, c);
        acd3_trim_crossing(p[2], e[2], s[2], s[0], apex, d);
        v += acd3_trim_fan_term(a, b, c);
        v += acd3_trim_fan_term(a, c, d);
        break;
    case 7: /* P0, P1, P2 */
        acd3_trim_corner(p[0], apex, a);
        acd3_trim_corner(p[1], apex, b);
        acd3_trim_corner(p[2], apex, c);
        v += acd3_trim_fan_term(a, b, c);
        break;
    default: /* no corner beyond: no polygon */
        break;
    }
    return v / 6.0;
}

/* The volumes beyond the levels k >= k_lo of the triangle (p[0], p[1], p[2]), whose corners' dots
 * with n are d[0..2] (acd_dot3(n, p), as acd_geom3_triangle_volume_beyond rounds n.x before
 * subtracting the offset), added to v[k]. Each term is the arithmetic of
 * acd_geom3_triangle_volume_beyond operation for operation (its n.x - off is d - off): a level
 * crossing the triangle goes through its clip, acd_geom3_clipped_cone_volume; a level above the
 * triangle (and every shallower one) is skipped, its term 0 (adding 0 to a sum that starts at +0
 * changes nothing: such a sum is never -0); at the levels below the triangle (the deepest ones) it is
 * a whole cone, computed in one loop over them. */
static inline void acd3_trim_tri_beyond(const double *const p[3], const double d[3], const acd3_trim_levels *L,
                                        size_t k_lo, double *v) {
    const double top = acd3_trim_top(d), bot = acd3_trim_bot(d);
    size_t k_whole = ACD3_TRIM_NDEPTHS; /* from k_whole on the triangle lies beyond the level */
    while (k_whole > k_lo && bot > L->off[k_whole - 1]) k_whole--;
    for (size_t k = k_whole; k < ACD3_TRIM_NDEPTHS; k++) {
        const double p0[3] = {p[0][0] - L->ax[k], p[0][1] - L->ay[k], p[0][2] - L->az[k]};
        const double p1[3] = {p[1][0] - L->ax[k], p[1][1] - L->ay[k], p[1][2] - L->az[k]};
        const double p2[3] = {p[2][0] - L->ax[k], p[2][1] - L->ay[k], p[2][2] - L->az[k]};
        const double bc0 = p1[1] * p2[2] - p1[2] * p2[1], bc1 = p1[2] * p2[0] - p1[0] * p2[2],
                     bc2 = p1[0] * p2[1] - p1[1] * p2[0];
        double w = 0;
        w += p0[0] * bc0 + p0[1] * bc1 + p0[2] * bc2;
        v[k] += w / 6.0;
    }
    if (k_whole == k_lo || !(top > L->off[k_whole - 1])) return;
    double e[3][3]; /* the edges k -> k + 1, for the crossings at every level */
    for (int c = 0; c < 3; c++) {
        const double *a = p[c], *b = p[c == 2 ? 0 : c + 1];
        for (int q = 0; q < 3; q++) e[c][q] = b[q] - a[q];
    }
    for (size_t k = k_whole; k-- > k_lo;) { /* the level crosses the triangle, or is above it */
        if (!(top > L->off[k])) break;
        const double apex[3] = {L->ax[k], L->ay[k], L->az[k]};
        const double s[3] = {d[0] - L->off[k], d[1] - L->off[k], d[2] - L->off[k]};
        v[k] += acd3_trim_clip_cone(p, (const double(*)[3])e, s, apex);
    }
}

/* A part's triangles for acd3_trim_tree_beyond: the nodes of its acd_bvh in the order
 * acd_bvh_query_halfspace visits them (a node, the subtree of its second child, then that of its
 * first), each with the index past its subtree, and the leaves' triangles' corners in that order. */
typedef struct acd3_trim_tree_node {
    double box[2][3];      /* lo, hi */
    uint32_t skip;         /* the index past the node's subtree */
    uint32_t first, count; /* a leaf (count > 0): its triangles, from corner + 9 * first */
} acd3_trim_tree_node;

typedef struct acd3_trim_tree {
    acd3_trim_tree_node *node;
    size_t nnode;
    double *corner; /* 9 per triangle */
} acd3_trim_tree;

/* 1 done (an empty tree for an empty BVH), 0 out of memory (R then empty). R does not refer to b. */
int acd3_trim_tree_build(acd3_trim_tree *R, const acd_bvh *b);
void acd3_trim_tree_free(acd3_trim_tree *R);

/* The volumes beyond the levels k >= k_lo of the triangles reaching beyond the deepest level, added
 * to v: the triangles acd_bvh_query_halfspace(b, n, L->off[ACD3_TRIM_NDEPTHS - 1]) visits, in its
 * order, each through acd3_trim_tri_beyond. top: NULL, or set to the largest n.x of those triangles'
 * corners (-INFINITY when none reaches beyond the deepest level): how far the part reaches beyond
 * each level (acd3/trim's distance bound). */
void acd3_trim_tree_beyond(const acd3_trim_tree *R, const double n[3], const acd3_trim_levels *L, size_t k_lo,
                           double *v, double *top);

/* The part volume a cut by the plane n.x = off removes from its hull exactly (up to rounding): the
 * volume of the part beyond the plane and on the inner side (n_c.x <= off_c) of each of the hull's
 * earlier cuts, cuts[4 c .. 4 c + 3] = (n_c, off_c), c < ncuts: the part's volume between the hull
 * before the cut and after it (the part lies in the initial hull, whose facets need no clip). For a
 * closed, outward mesh and any point o, the volume inside it of a region K is the sum over its
 * triangles t of sign(t) x |tetrahedron (o, t) inside K| (winding numbers); with o = apex, on the
 * plane, a triangle entirely below the plane adds nothing, so only the triangles reaching beyond it
 * are visited (through R, as acd3_trim_tree_beyond), each tetrahedron clipped by the plane and by the
 * cuts it crosses (a convex polytope as its faces' directed edges). acd3/trim charges this instead of
 * the loss less the plane's base, an upper bound, which counts a region beyond two cuts' planes
 * twice. NaN when out of memory or a polytope outgrows the clipper's fixed capacity (the caller then
 * keeps the bound). */
double acd3_trim_tree_charge(const acd3_trim_tree *R, const double n[3], double off, const double apex[3],
                             const double *cuts, size_t ncuts);

#endif
