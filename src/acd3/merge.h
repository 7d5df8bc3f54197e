/* acd3/merge: after the decomposition, adjacent parts whose union is still nearly convex are
 * joined (issue 4 item 6: fewer parts at the same concavity). docs/acd3d.md, "Merge pass".
 *
 * Two parts are adjacent when they share at least three non-collinear vertex positions (the
 * vertices of a section they were cut along: plane_cut gives both sides the same points). The
 * union U = A u B of two adjacent groups is scored against its hull H = conv(A u B):
 *
 *   d_in  = max over the vertices of A and B that lie on the input surface of their distance to
 *           the boundary of H (exact: min over H's facet planes, the vertices being inside H);
 *   d_out = max over the points x of the boundary of H of dist(x, U), bounded from above: every
 *           hull triangle is subdivided until each piece has a point q of U within tau of all
 *           its corners (then of all its points: |x - q| is convex), q being the point of U
 *           closest to the piece's centroid or, without a query, the one its parent found; or
 *           refused as soon as one centroid is farther than tau.
 *
 * The pair is joinable when both are <= tau and, without a stop (stop_at 0: the default pipeline),
 * its joint hull adds at most 2% of the input's volume to the two hulls (vol H - vol conv A - vol conv
 * B; opts.max_added; the added volume: a thin wall joined to a stub of floor, or two prongs across a slot narrower
 * than 2 tau, are within tau both ways, but their hull fills the wedge or the slot; GEB's default run
 * lost 0.13 IoU by one such join). Its cost is max(d_in, d_out's bound), or (by_volume)
 * the hull volume the join adds. Cheapest first (ties: the lower group ids), greedily, until no
 * adjacent pair is joinable or stop_at groups remain; a joined group is a new group and its pairs
 * with its neighbours are scored again. Deterministic for any
 * thread count (pairs are scored independently, the choice is sequential).
 *
 * What the bound means: d_out is the directed Hausdorff distance from the joined hull to the
 * joined part (an upper bound of it: how far the hull reaches out); d_in is the depth of the
 * part's surface points inside the hull. The decomposition's own measure (acd3/measure) is the
 * depth below the bridge patch covering each pocket, which is >= d_in (a patch plane supports
 * H, so a point's depth below it is at least its distance to the boundary of H): d_in is not an
 * upper bound of it, d_out is not comparable to it (a thin deep crack has a small d_out and a
 * large depth). The pair of one-sided distances is the measure the evaluation uses (eval3d,
 * CoACD's Hausdorff concavity), and the joined records carry it. Cap vertices off the input
 * surface (on sections between parts) are left out of d_in: the caps are inside the input. */
#ifndef ACD_ACD3_MERGE_H
#define ACD_ACD3_MERGE_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "acd/hull.h"
#include "acd/mesh.h"
#include "geom3/bvh.h"

typedef struct acd3_merge_result {
    size_t ngroups;
    uint32_t *group_of; /* per input part: its group; groups numbered by their lowest part */
    size_t *group_size; /* per group: how many parts */
    double *bound;      /* per group of >= 2 parts: max(d_in, bound of d_out) <= tau; 0 otherwise */
    size_t merges;      /* joins made */
    /* the refinement (acd3_merge_opts.refine): pieces of parts cut by it, numbered after the input
     * parts (atom nparts + k is new_parts[k]); group_of covers them too (nparts + nnew entries), a
     * part or piece that was cut having UINT32_MAX. The pieces of one cut are consecutive. */
    size_t nnew;
    acd_mesh *new_parts;  /* owned */
    uint32_t *new_parent; /* per piece: the atom (input part or earlier piece) it was cut from */
    double (*new_plane)[4]; /* per piece: its parent's cut plane n.x + d = 0 */
    double *new_volume;   /* per piece: its volume */
    size_t trades;        /* refinement steps made (one cut, one join each) */
    /* with acd3_merge_opts.keep_trees (else empty), the trees the merge built, handed over (owned):
     * the input's (empty when it built none), and per input part (npart_bvh entries, or none) the
     * part's tree when the part is alone in its group at the end (empty otherwise, and where the
     * caller's tree, acd3_merge_kept.bvh, was used) */
    acd_bvh input_bvh;
    acd_bvh *part_bvh;
    size_t npart_bvh;
} acd3_merge_result;

typedef struct acd3_merge_opts {
    int by_volume;  /* non-zero: the joinable pair whose hull adds the least volume first
                       (vol conv(A u B) - vol conv A - vol conv B); else the smallest bound */
    size_t stop_at; /* 0: join while a pair is joinable; else stop at this many groups */
    size_t refine;  /* with stop_at: at most this many refinement steps after the greedy joins (0:
                       none). A step cuts the group whose best volume plane (acd3/volume_plane)
                       lowers the sum of hull volumes the most, both sides within tau under the
                       bound above, and joins the cheapest joinable pair; taken only when the cut
                       saves more hull volume than the join adds (docs/acd3d.md "Hull tightness").
                       A side is made one group per connected component (adjacency among its
                       atoms), each within tau, and one more cheapest pair joined per extra
                       component (none joinable: one group more): every group stays connected */
    acd_progress_fn progress; /* optional (NULL: none): called between steps, from the calling
                                 thread only; non-zero cancels (ACD_ERR_CANCELLED) */
    void *progress_user;
    int keep_trees; /* non-zero: the trees built are handed over (acd3_merge_result.input_bvh,
                       part_bvh), for acd3/trim */
    double max_added; /* without a stop: the largest hull volume a join may add, as a fraction of the
                         input's volume (0: the default, 0.02; INFINITY: no limit); with a stop none */
} acd3_merge_opts;

/* Joins the adjacent parts of the closed input mesh `input` (all parts closed, together tiling
 * it), tau and tol in model units. threads: OpenMP workers for the scoring (<= 1: one). opts may
 * be NULL (bound order, no stop). */
acd_status acd3_merge_adjacent(const acd_mesh *input, const acd_mesh *parts, size_t nparts, double tau, double tol,
                               const acd3_merge_opts *opts, int threads, acd3_merge_result *out, acd_error *err);
/* A hull's facet table: per facet of a dim 3 hull H, its corners in canonical (lexicographic) order
 * and the bound of the distance from its points to a part (the facet subdivision above, at tau;
 * INFINITY: not bounded within tau), the facets sorted by their corners. What the merge keeps per
 * group; acd3_merge_hull_reach_table makes one for a part (acd3/leaf_test hands it to the merge). */
typedef struct acd3_facet_table {
    double *key; /* 9 per facet */
    double *ub;  /* per facet */
    size_t n;    /* H->ntriangles */
    double tau;  /* the tau of the bounds */
} acd3_facet_table;
void acd3_facet_table_free(acd3_facet_table *t);

/* What the caller computed already for part i (acd3_merge_adjacent_kept), read only; each field
 * NULL or: */
typedef struct acd3_merge_kept {
    const acd_hull *hull;           /* the part's hull: acd_hull_compute of exactly its vertices, in their
                                       order (used when acd3_kept_hull_matches) */
    const acd_bvh *bvh;             /* the part's tree: acd_bvh_build of the part's own vertex and triangle
                                       arrays (used when it points at them) */
    const acd3_facet_table *table;  /* hull's facet table over that tree (acd3_merge_hull_reach_table;
                                       used with both, at the same tau) */
} acd3_merge_kept;

/* As acd3_merge_adjacent, with hulls (NULL, or per part NULL or the part's hull: acd_hull_compute of
 * exactly its vertices, in their order; read only) used instead of computing the parts' hulls again:
 * the same result, bit for bit. A hull whose vertices are not the part's points its source names is
 * not used (computed again). */
acd_status acd3_merge_adjacent_hulls(const acd_mesh *input, const acd_mesh *parts, const acd_hull *const *hulls,
                                     size_t nparts, double tau, double tol, const acd3_merge_opts *opts, int threads,
                                     acd3_merge_result *out, acd_error *err);
/* As acd3_merge_adjacent_hulls, with kept (NULL, or nparts records, acd3_merge_kept) used instead of
 * computing the parts' hulls, trees and facet tables again: the same result, bit for bit. */
acd_status acd3_merge_adjacent_kept(const acd_mesh *input, const acd_mesh *parts, const acd3_merge_kept *kept,
                                    size_t nparts, double tau, double tol, const acd3_merge_opts *opts, int threads,
                                    acd3_merge_result *out, acd_error *err);
void acd3_merge_result_free(acd3_merge_result *r);
/* Whether kept can stand for the hull of the n points pts (the test acd3_merge_adjacent_hulls
 * applies): each of its vertices is the input point its source names, bit for bit; the caller
 * promises the rest (kept is acd_hull_compute of exactly these points, in this order). Also used
 * by acd3/budget. */
int acd3_kept_hull_matches(const acd_hull *kept, const double *pts, size_t n);

/* d_out of one part: an upper bound of the largest distance from a point of the boundary of H (a
 * dim 3 hull) to the triangles of `part` (its tree), by the facet subdivision above; INFINITY as
 * soon as it exceeds tau, when the query budget runs out, or for a hull that is not dim 3. Used by
 * acd3/leaf_test. */
double acd3_merge_hull_reach(const acd_bvh *part, const acd_hull *H, double tau);
/* The same, and when the bound is <= tau and table is not NULL, the facet table of H over part at tau
 * into *table (the one the merge's set-up makes for a part with this hull and tree; otherwise, or out
 * of memory for it, *table is left empty: key NULL). */
double acd3_merge_hull_reach_table(const acd_bvh *part, const acd_hull *H, double tau, acd3_facet_table *table);

#endif
