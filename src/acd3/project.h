/* acd3/project: projecting hull edges onto the surface (dissertation §V.B.1; paper §4.1;
 * spec acd3d.md §3.2 and its speed-up note in §3.5).
 *
 * The projection of a hull edge (a, b) is the shortest path from a to b on the mesh's edge graph
 * with Euclidean edge lengths. A* with the straight-line distance to b as heuristic returns the
 * same shortest paths as Dijkstra (the heuristic is consistent) while visiting only an ellipse-
 * like neighbourhood of the edge; the work arrays are reused across queries (a visit stamp
 * resets them in O(1)), so projecting hundreds of edges costs about their paths' neighbourhoods,
 * not hundreds of whole-mesh passes. Ties: the heap orders by (estimate, vertex id). */
#ifndef ACD_ACD3_PROJECT_H
#define ACD_ACD3_PROJECT_H

#include <stddef.h>
#include <stdint.h>

#include "core/minheap.h"
#include "geom3/dijkstra.h"

typedef struct acd3_pathfinder {
    const acd_edge_graph *g;
    const double *coords; /* 3 per vertex */
    double *dist;
    uint32_t *pred;
    uint32_t *stamp;      /* dist/pred valid where stamp == cur */
    uint8_t *closed;
    uint32_t cur;
    acd_minheap heap;     /* (estimate, vertex) */
    uint32_t *path;       /* the last path, source first */
    size_t path_len, path_cap;
} acd3_pathfinder;

/* Returns 0 on allocation failure. */
int acd3_pathfinder_init(acd3_pathfinder *pf, const acd_edge_graph *g, const double *coords);
void acd3_pathfinder_free(acd3_pathfinder *pf);

/* Shortest path s -> t; on success pf->path[0..pf->path_len) holds it (s first) and 1 is
 * returned; 0 when t is unreachable, -1 on allocation failure. */
int acd3_shortest_path(acd3_pathfinder *pf, uint32_t s, uint32_t t);

#endif
