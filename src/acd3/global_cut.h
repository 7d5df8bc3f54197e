/* acd3/global_cut: the global cut through the most concave feature and its cut plane
 * (dissertation §V.B.2.e-§V.B.3, Eqn 5.3, Figs 42-44; paper §4.2.4-4.3, Eqn 5, Figs 13-15;
 * spec acd3d.md §4.3 (cup pockets), §4.5, §5.2, decisions A9, A11, A17).
 *
 * Root (A17): the pocket cut of G_K in the witness's pocket closest to the witness (lower W on
 * ties). Cup-shaped pocket (dissertation Fig. 42): when the witness's pocket has no cut, or none
 * within one edge of the witness while every knot of the pocket is shallower than the witness by
 * more than delta, the pocket is subdivided through the witness: the cut runs from the boundary
 * vertex u of the pocket nearest the witness (valley cost) through the witness to the boundary
 * vertex w on the opposite side (the direction from the witness most opposite to u's, in the
 * bridge's plane); the witness becomes a knot of the new boundary u-x-w, which is the cut.
 *
 * Cycle (A11): from the root cut a -> b, a tree is grown from knot a into the pocket on the
 * other side of a's chain, best first by accumulated W; a node (knot k, entering pocket p)
 * grows along the cuts of p at k, into the pocket beyond the far knot's chain, never into a
 * pocket an ancestor visited (each pocket once, the root's pocket included). The first branch
 * that reaches knot b closes the minimum-weight cycle root + branch (at most 10^4 expansions).
 * With no cycle, the global cut is the root cut alone. With acd3_gc_opts.dynamic (surface mode's
 * --surface-cut cycle), when no cycle of G_K closes (or the root is a cup cut, whose ends lie on
 * the pocket's rim), the search runs again with the paper's dynamic geodesic cuts (§4.2.4): from
 * every node also valley-cost shortest paths inside the entered pocket to the nearest vertex of
 * each knot-less chain (a pseudo-knot), from a pseudo-knot to the knots of the pocket's other
 * chains, and to the root's other end; the plane stays fitted to the root (and G_K's cycle).
 *
 * Cut plane (§5.2): the concavity-weighted best-fit plane of the cut (PCA on the edges' end and
 * mid points, weight = edge length x concavity), pushed toward the cut where it misses it: a cut
 * vertex farther than theta = max(tau, 2 x mean cut edge length) from the plane has its weight
 * doubled and the plane refitted, at most 10 times, then the plane is made to pass through the
 * worst vertex. A cut that does not spread in two dimensions (a straight valley) gives the plane
 * containing its direction and the mean surface normal along it (across the valley). Finally the
 * plane is moved parallel to itself through the witness (our addition: the cut must resolve the
 * most concave vertex; measured better than the fitted position on every Table 5 model). */
#ifndef ACD_ACD3_GLOBAL_CUT_H
#define ACD_ACD3_GLOBAL_CUT_H

#include "acd3/pocket_cut.h"

typedef struct acd3_global_cut {
    uint32_t *v;    /* the cut's vertices in order (a cycle repeats its first vertex last) */
    size_t n;
    size_t root_n;  /* the root cut (or the cup cut) is v[0 .. root_n) */
    size_t ncuts;   /* pocket cuts in it */
    int closed;     /* a cycle of G_K */
    int cup;        /* a cut through the witness of a cup-shaped pocket */
    int dynamic;    /* the cycle needed the dynamic geodesic cuts (acd3_gc_opts.dynamic) */
    size_t plane_n; /* the cut plane is fitted to v[0 .. plane_n): the root and the cycle of G_K,
                       not the dynamic search's extension */
    double weight;  /* total W */
} acd3_global_cut;

/* Finds the global cut at the witness of ms. out->n = 0 when there is none (no witness, no
 * pocket). ACD_ERR_NOMEM only. */
acd_status acd3_global_cut_find(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms,
                                const acd3_cut_graph *cg, const acd3_gc_opts *o, acd3_global_cut *out,
                                acd_error *err);
void acd3_global_cut_free(acd3_global_cut *gc);

/* The cut plane of gc: returns 1 and a point (the witness: the fitted plane is moved parallel to
 * itself through it) and unit normal, and (when fitted is not NULL) a point of the plane as
 * fitted (the witness projected on it), or 0
 * when the cut is degenerate (fewer than two distinct points, or an allocation failed). */
int acd3_global_cut_plane(const acd_mesh *m, const acd3_measure *ms, const acd3_cut_graph *cg,
                          const acd3_global_cut *gc, const acd3_gc_opts *o, double point[3], double normal[3],
                          double fitted[3]);

/* acd3_cut_graph_build (polling poll, NULL: none), acd3_global_cut_find and acd3_global_cut_plane
 * in one call (the cut graph is freed): *has_plane = 1 when point and normal were set.
 * ACD_ERR_NOMEM, or ACD_ERR_CANCELLED once poll says stop. */
acd_status acd3_global_cut_at_witness(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms,
                                      const acd3_gc_opts *o, acd3_poll *poll, acd3_global_cut *gc, double point[3],
                                      double normal[3], int *has_plane, acd_error *err);

#endif
