/* geom3/dijkstra: shortest paths on a mesh's edge graph (Dijkstra 1959, binary heap).
 *
 * Lien's ACD uses Dijkstra to project hull edges onto the surface (D §V.B.1, P §4.1), between knots
 * (D §V.B.2), for handle cuts with several sources (D §V.C) and, in CoRiSe, along the surface.
 * Ties are broken deterministically: the heap orders by (distance, vertex id) and, at equal distance,
 * a vertex keeps the predecessor with the smaller vertex id. */
#ifndef ACD_GEOM3_DIJKSTRA_H
#define ACD_GEOM3_DIJKSTRA_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "core/minheap.h"

#define ACD_NO_VERTEX UINT32_MAX

/* Undirected edge graph in compressed rows. Edge e joins edge_v[2e] < edge_v[2e+1]; edges are
 * numbered in increasing (lower, upper) vertex order; each row lists neighbours by increasing id. */
typedef struct acd_edge_graph {
    size_t nvertices;
    size_t nedges;
    uint32_t *edge_v;   /* 2 * nedges */
    double *length;     /* nedges: Euclidean length (graphs built from a mesh) or the given weight */
    size_t *row;        /* nvertices + 1 */
    uint32_t *adj;      /* 2 * nedges: neighbour vertex */
    uint32_t *adj_edge; /* 2 * nedges: the edge id of that incidence */
} acd_edge_graph;

/* Edge graph of a triangle mesh (edges of the triangles, Euclidean lengths). Triangle indices must be
 * < nvertices (ACD_ERR_INVALID_INPUT names the triangle otherwise). Free with acd_edge_graph_free. */
acd_status acd_edge_graph_from_mesh(const double *vertices, size_t nvertices, const uint32_t *triangles,
                                    size_t ntriangles, acd_edge_graph *g, acd_error *err);
/* Edge graph of explicit edges (pairs of vertex ids; duplicates merged keeping the smallest weight;
 * self-loops dropped). weights: one per edge, finite and >= 0, NULL for all 1. */
acd_status acd_edge_graph_from_edges(size_t nvertices, const uint32_t *edges, const double *weights, size_t nedges,
                                     acd_edge_graph *g, acd_error *err);
void acd_edge_graph_free(acd_edge_graph *g);
/* Edge id joining a and b, or ACD_NO_VERTEX. O(degree). Inline: the measure looks up every side
 * of every face (acd3/measure's edge_faces), where the call cost about as much as the scan. */
static inline uint32_t acd_edge_graph_find(const acd_edge_graph *g, uint32_t a, uint32_t b) {
    if (a >= g->nvertices || b >= g->nvertices) return ACD_NO_VERTEX;
    for (size_t k = g->row[a], end = g->row[a + 1]; k < end; k++)
        if (g->adj[k] == b) return g->adj_edge[k];
    return ACD_NO_VERTEX;
}

/* Options of a search; zero-initialise and set what is needed. */
typedef struct acd_dijkstra_opts {
    const double *weights;          /* per edge, >= 0; NULL: g->length */
    const uint8_t *edge_blocked;    /* per edge, non-zero: not crossed (barriers); NULL: none */
    const uint8_t *vertex_allowed;  /* per vertex, zero: not entered (regions); NULL: all */
    uint32_t target;                /* stop once this vertex is settled; ACD_NO_VERTEX: settle all */
    double max_distance;            /* stop beyond this distance; 0 or less: no limit */
} acd_dijkstra_opts;

/* Shortest-path forest. Unreached vertices have dist = +INFINITY and pred = ACD_NO_VERTEX. */
typedef struct acd_sp_tree {
    size_t nvertices;
    double *dist;
    uint32_t *pred;      /* predecessor vertex */
    uint32_t *pred_edge; /* edge to the predecessor */
    uint32_t *origin;    /* index (in the sources array) of the source the vertex was reached from */
} acd_sp_tree;

/* Multi-source Dijkstra from sources[0..nsources) (all at distance 0). opts may be NULL. */
acd_status acd_dijkstra(const acd_edge_graph *g, const uint32_t *sources, size_t nsources,
                        const acd_dijkstra_opts *opts, acd_sp_tree *tree, acd_error *err);
void acd_sp_tree_free(acd_sp_tree *t);

/* Vertices of the path from the tree's source to target, source first, in a malloc'd array
 * (*len vertices). ACD_ERR_DEGENERATE when target was not reached. */
acd_status acd_sp_path(const acd_sp_tree *t, uint32_t target, uint32_t **path, size_t *len, acd_error *err);

/* Convenience: one shortest path from s to t (vertices, s first). */
acd_status acd_shortest_path(const acd_edge_graph *g, uint32_t s, uint32_t t, const acd_dijkstra_opts *opts,
                             uint32_t **path, size_t *len, double *length, acd_error *err);

/* A reusable, bounded single-source Dijkstra (the per-source searches of corise/regions' balls,
 * acd3/pocket_cut's knot-to-knot cuts and acd3/global_cut's dynamic cuts). Its arrays are sized
 * once for the graph; a run touches only the vertices it reaches (a run stamp tells this run's
 * entries from older ones), so a run costs its own region, not a pass over the graph. Settles in
 * (distance, vertex id) order with a lazy heap; at equal distance a vertex keeps the predecessor
 * with the smaller id: the distances and predecessors of acd_dijkstra with the same weights and
 * allowed vertices (a distance is the smallest left-to-right rounded sum of weights over the
 * paths, and rounding is monotone, so any exact Dijkstra gives the same bits). */
typedef struct acd_sp_ws {
    size_t nvertices;
    double *dist;      /* valid where stamp == run: final when settled, tentative otherwise */
    uint32_t *pred;    /* predecessor (ACD_NO_VERTEX at the source), where stamp == run (unless no_pred) */
    uint32_t *stamp;   /* == run: reached by this run */
    uint32_t *done;    /* == run: settled by this run */
    uint32_t *tstamp;  /* == run: a target of this run */
    uint32_t run;
    uint32_t *visited; /* visited[0..nvisited): the settled vertices, in settling order */
    size_t nvisited;
    acd_minheap heap;  /* (distance, vertex) */
} acd_sp_ws;

/* Limits of a run; zero-initialise and set what is needed. */
typedef struct acd_sp_limits {
    const double *weights;         /* per edge, finite and >= 0 (not checked); NULL: g->length */
    const uint8_t *vertex_allowed; /* per vertex, zero: not entered (nor the source); NULL: all */
    double below;                  /* > 0: settle only vertices at distance < below (strictly; for
                                      "<= d" pass nextafter(d, INFINITY)); else no bound */
    const uint32_t *targets;       /* non-NULL: stop once targets[0..ntargets) are all settled (their
                                      distances and paths are the full run's); none given: no run */
    size_t ntargets;
    int no_pred;                   /* non-zero: no predecessors kept (w->pred is left undefined), for
                                      runs that want only distances or the visited set */
} acd_sp_limits;

/* Sizes the workspace for nvertices (ACD_ERR_NOMEM names the size). Free with acd_sp_ws_free. */
acd_status acd_sp_ws_init(acd_sp_ws *w, size_t nvertices, acd_error *err);
void acd_sp_ws_free(acd_sp_ws *w);
/* Runs from src on g (g->nvertices == w->nvertices) within lim (NULL: none); the previous run's
 * results are dropped. 0 when out of memory (the heap grows), else 1. */
int acd_sp_ws_run(acd_sp_ws *w, const acd_edge_graph *g, uint32_t src, const acd_sp_limits *lim);
/* Distance of v from the last run's source: final when settled, tentative when only reached (an
 * early stop), INFINITY when not reached. */
static inline double acd_sp_ws_dist(const acd_sp_ws *w, uint32_t v) {
    return w->stamp[v] == w->run ? w->dist[v] : INFINITY;
}
/* Whether the last run settled v. */
static inline int acd_sp_ws_settled(const acd_sp_ws *w, uint32_t v) { return w->done[v] == w->run; }

#endif
