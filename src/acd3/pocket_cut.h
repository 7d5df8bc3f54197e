/* acd3/pocket_cut: knots on the pocket boundaries, pocket cuts between them and the cut graph G_K
 * (dissertation §V.B.2.a-e, Obs B.2, Eqn 5.2, Figs 39-43; paper §4.2.1-4.2.4, Obs 4.2, Eqn 4;
 * spec acd3d.md §4.1-4.5, decisions A1, A5-A8, A10).
 *
 * 1. Boundary chains. The projected hull edges (measure's barrier edges) that separate two
 *    different pockets are traced into maximal chains with the same pair of pockets on their
 *    sides (decision A8: a "boundary" is a contiguous shared boundary segment). A chain ends
 *    where the barrier network branches; a chain with no branch point is a closed loop.
 * 2. Knots (acd3/knots): Douglas-Peucker in concavity space along each chain, delta = delta_ratio
 *    * tau; a knot is a concavity peak above delta. A knot lies on the boundary of both pockets
 *    of its chain.
 * 3. Pocket cuts: inside each pocket, the cheapest path between two knots on different chains of
 *    its boundary, with edge cost |uv| / (eta + mean concavity) (decision A7: the path follows
 *    concave valleys), scored by the cut weight W (below). For each pair of chains of a pocket
 *    the cuts kept are a minimum-weight bipartite matching of their knots (Hungarian method,
 *    maximum cardinality); then, while two kept cuts of a pocket cross (splitting the pocket
 *    along one leaves interior vertices of the other on both sides, Obs B.2), the heavier of
 *    the cuts involved is deleted.
 * 4. Cut weight of a path kappa: omega = |kappa| / sum concavity (the reciprocal of the mean
 *    concavity; |kappa| = number of vertices), gamma = accumulated curvature = sum over its edges
 *    of the turning angle between the two faces at the edge (decision A10's cheap fallback:
 *    the angle integrates the curvature across the edge along its length). W = omega / gamma
 *    (paper Eqn 4, default) or omega * gamma (dissertation Eqn 5.2).
 *
 * G_K has the knots as vertices and the matched cuts as edges; those the crossing rule deletes
 * stay in the graph flagged `crossed` (the non-crossed ones are K_rho, the set a surface split
 * along several cuts at once needs): a cycle visits each pocket once, so it never uses two cuts
 * of one pocket, and removing crossed cuts would only remove cycles (on a peanut's neck the
 * ring's cut through one pocket crosses a cheaper cut to a far, shallow knot). */
#ifndef ACD_ACD3_POCKET_CUT_H
#define ACD_ACD3_POCKET_CUT_H

#include <stddef.h>
#include <stdint.h>

#include "acd/acd3d.h"
#include "acd/mesh.h"
#include "acd3/measure.h"
#include "geom3/dijkstra.h"

typedef struct acd3_gc_opts {
    double tau;          /* model units */
    double delta;        /* knot threshold (model units) */
    acd3d_weight weight; /* ratio (paper) or product (dissertation) */
    int dynamic;         /* non-zero: when no cycle of G_K closes, search again with P's dynamic
                            geodesic cuts (acd3/global_cut) */
    int witness_root;    /* with dynamic: the root is always the cut through the witness that
                            cup-shaped pockets get (acd3/global_cut) */
} acd3_gc_opts;

typedef struct acd3_pocket_cut {
    uint32_t knot[2]; /* knot ids; path runs knot[0] -> knot[1] */
    uint32_t region;  /* the pocket it lies in */
    size_t off, n;    /* its vertices: cut_v[off .. off+n) */
    double w;         /* cut weight W */
    int crossed;      /* deleted from K_rho because it crosses a kept cut of its pocket; kept in the
                         graph: a cycle uses one cut per pocket, so crossings never meet in a cycle */
} acd3_pocket_cut;

typedef struct acd3_cut_graph {
    /* boundary chains */
    size_t nchains;
    size_t *chain_off;      /* nchains + 1 into chain_v */
    uint32_t *chain_v;
    uint32_t *chain_region; /* 2 per chain (lower id first) */
    uint8_t *chain_closed;  /* first vertex == last vertex */
    /* knots */
    size_t nknots;
    uint32_t *knot_v, *knot_chain;
    /* kept pocket cuts and their vertices */
    size_t ncuts;
    acd3_pocket_cut *cuts;
    uint32_t *cut_v;
    /* knot -> incident cuts (CSR) */
    size_t *knot_row;
    uint32_t *knot_cut;
    /* helpers shared with the cycle search */
    uint32_t *face_of;      /* acd3_edge_faces */
    size_t *vf_row;         /* vertex -> incident faces (CSR) */
    uint32_t *vf;
} acd3_cut_graph;

/* poll (acd3/poll; NULL: none) is polled per knot source (each a shortest-path search over its
 * pocket): once it says stop, ACD_ERR_CANCELLED with nothing kept. */
acd_status acd3_cut_graph_build(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms,
                                const acd3_gc_opts *o, acd3_poll *poll, acd3_cut_graph *out, acd_error *err);
void acd3_cut_graph_free(acd3_cut_graph *cg);

/* W of the path p[0..n) (see above); face_of from acd3_edge_faces. */
double acd3_cut_weight(const acd_mesh *m, const acd_edge_graph *g, const uint32_t *face_of, const double *vconc,
                       const uint32_t *p, size_t n, const acd3_gc_opts *o);

/* Edge cost of the valley-following paths: |uv| / (eta + mean concavity), eta = 1e-3 tau. */
double acd3_valley_cost(const acd_edge_graph *g, const double *vconc, uint32_t e, double tau);

/* The pocket (region) in which vertex v has its concavity: the region of an incident face whose
 * patch plane v lies deepest below (lowest region id on ties); UINT32_MAX if none. */
uint32_t acd3_vertex_region(const acd_mesh *m, const acd3_measure *ms, const acd3_cut_graph *cg, uint32_t v);

#endif
