/* eval/concavity2d_ref: the verifier's own concavity of a simple polygon (Lien, dissertation
 * Ch. IV.A.1, spec ../shared/spec/acd2d.md §3.1-§3.3), written independently of src/acd2/.
 *
 * Straightforward on purpose: convex hull by Andrew's monotone chain (exact orientation,
 * collinear points dropped), pockets = polygon chains between consecutive hull vertices,
 *   SL(v) = distance from v to the bridge's supporting line,
 *   SP(v) = shortest path from v to the bridge segment inside the pocket polygon, by Dijkstra
 *           over the visibility graph of the pocket's vertices (terminal edges: the bridge's
 *           endpoints and unobstructed perpendicular drops onto the bridge),
 *   H1 = SP in pockets with a hazard edge (an edge whose direction opposes the bridge's,
 *        i.e. whose outward normal opposes the bridge's), else SL,
 *   H2 = SL if the pocket's SL maximum exceeds tau or there is no hazard, else SP.
 * The concavity of the polygon is the maximum over its notches (spec §11 A3). */
#ifndef ACD_EVAL_CONCAVITY2D_REF_H
#define ACD_EVAL_CONCAVITY2D_REF_H

#include "acd/acd2d.h"
#include "core/predicates.h"

/* The exact predicates on acd_vec2 values. */
static inline double acd_ref_orient(acd_vec2 a, acd_vec2 b, acd_vec2 c) {
    double A[2] = {a.x, a.y}, B[2] = {b.x, b.y}, C[2] = {c.x, c.y};
    return acd_orient2d(A, B, C);
}
static inline acd_seg_relation acd_ref_segrel(acd_vec2 a, acd_vec2 b, acd_vec2 c, acd_vec2 d) {
    double A[2] = {a.x, a.y}, B[2] = {b.x, b.y}, C[2] = {c.x, c.y}, D[2] = {d.x, d.y};
    return acd_segments_relation(A, B, C, D);
}
static inline int acd_ref_on_segment(acd_vec2 p, acd_vec2 a, acd_vec2 b) {
    double P[2] = {p.x, p.y}, A[2] = {a.x, a.y}, B[2] = {b.x, b.y};
    return acd_point_on_segment(P, A, B);
}

/* Vertex v of pts (n points, cyclic) is a notch: (v-u)x(w-v) < -notch_tol, or, with
 * notch_tol == 0, the exact orientation of (u, v, w) is clockwise. */
int acd_ref_is_notch(const acd_vec2 *pts, size_t n, size_t v, double notch_tol);

/* Concavity of every vertex (conc[n], 0 on the hull) under measure m; returns 0 on success,
 * -1 when out of memory. `hazard_pockets` (may be NULL) receives how many pockets had a hazard. */
int acd_ref_vertex_concavity(const acd_vec2 *pts, size_t n, acd2d_measure m, double tau, double notch_tol,
                             double *conc, size_t *hazard_pockets);

/* Shortest-path distance from each vertex of a pocket polygon to its bridge. The pocket is the
 * chain q[0..k-1] (q[0], q[k-1] the bridge's endpoints, the chain running clockwise around the
 * pocket, i.e. counterclockwise along the polygon it was taken from). dist[k]. 0 / -1 (memory). */
int acd_ref_pocket_sp(const acd_vec2 *q, size_t k, double *dist);

#endif
