/* acd3/measure: concavity of a polyhedron or surface by bridges and pockets
 * (dissertation §V.B.1, Fig. 37; paper §4.1, Fig. 8; spec acd3d.md §3.1-3.4).
 *
 * 1. Hull CH_P (qhull) and bridge patches (acd3/patches, eps = tau/2).
 * 2. Every hull edge on a patch boundary is projected onto the surface as the Dijkstra shortest
 *    path between its end vertices on the mesh edge graph (Euclidean weights).
 * 3. The projected paths are barriers: the faces flood-fill into regions (pockets). Each region is
 *    given the patch on its side of its boundary paths: the face left of a path half-edge
 *    a -> b (in the direction of the hull edge as it runs counterclockwise around its left patch)
 *    votes for the left patch, the face on the right for the right patch, by edge length.
 *    A region claimed by several patches and bounded by two or more of their paths' loops is a
 *    pocket shared by handle caps (genus > 0): acd3/handles cuts it along shortest arcs between
 *    the caps (a forest) and measures each of its faces against the nearest cap.
 * 4. concavity(v) = depth of v below the supporting plane of its region's patch; a vertex on a
 *    path belongs to two regions and takes the larger depth (spec decision A5). concavity(P) is
 *    the maximum over the vertices; the witness is the vertex attaining it (lowest id on ties).
 *
 * Open surfaces (surface mode) are measured the same way; a region bounded only by the mesh's
 * own boundary (no projected path) takes the patch whose plane it lies deepest within least. */
#ifndef ACD_ACD3_MEASURE_H
#define ACD_ACD3_MEASURE_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "acd/hull.h"
#include "acd/mesh.h"
#include "acd3/handles.h"
#include "acd3/patches.h"
#include "acd3/poll.h"
#include "geom3/dijkstra.h"

typedef struct acd3_measure {
    double concavity;       /* max over vertices (0 for a flat or empty input) */
    uint32_t witness;       /* vertex attaining it (UINT32_MAX when flat) */
    double *vconc;          /* per mesh vertex */
    acd_hull hull;
    acd3_patches patches;   /* empty when the hull is flat */
    uint32_t *face_region;  /* per mesh face */
    size_t nregions;
    uint32_t *region_patch; /* per region */
    uint8_t *edge_barrier;  /* per graph edge: on a projected path */
    size_t nprojected;      /* projected hull edges */
    size_t nhandle_pockets; /* shared pockets split between their handle caps (spec §6, acd3/handles) */
    uint8_t *edge_handle;   /* per graph edge: on a handle arc (NULL when the flat hull skipped it) */
    acd3_handle_arcs handle_arcs;
    size_t nhandle_candidates; /* candidate arcs (the shortest per pair of cap loops that meet) */
    /* kept for the part's cut graph (acd3/pocket_cut), NULL when the hull is flat: acd3_edge_faces,
     * and per face side the graph edge from corner k to k + 1 (3f + k; ACD_NO_VERTEX when none) */
    uint32_t *face_of, *face_edge;
} acd3_measure;

/* Measures m (whose edge graph g was built from it). eps: bridge clustering threshold; tol: a
 * scale-relative length for "exactly coplanar". */
acd_status acd3_measure_compute(const acd_mesh *m, const acd_edge_graph *g, double eps, double tol,
                                acd3_measure *out, acd_error *err);
/* The same with m's hull already computed (acd_hull_compute of m's vertices): *hull is taken over
 * (left empty, also on failure); NULL computes it. poll (acd3/poll; NULL: none) is polled between
 * the phases and every ACD3_MEASURE_POLL_PATHS projected hull edges (each a shortest path over the
 * part): once it says stop, ACD_ERR_CANCELLED with nothing kept. */
acd_status acd3_measure_compute_hull(const acd_mesh *m, const acd_edge_graph *g, acd_hull *hull, double eps,
                                     double tol, acd3_poll *poll, acd3_measure *out, acd_error *err);
void acd3_measure_free(acd3_measure *ms);

/* Per graph edge, the faces on its two sides: face_of[2e] has the half-edge lower->upper
 * (edge_v[2e] -> edge_v[2e+1]), face_of[2e+1] the opposite one; UINT32_MAX where absent. */
acd_status acd3_edge_faces(const acd_mesh *m, const acd_edge_graph *g, uint32_t **face_of, acd_error *err);

#endif
