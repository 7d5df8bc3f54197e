/* acd3/handles: handle cuts for the bridge/pocket map of a surface of genus > 0 (dissertation
 * §V.C, Figs 45-46; paper §5, Figs 16-17; spec acd3d.md §6, decision A15).
 *
 * CH_P is a ball, so on a surface with handles one pocket can be enclosed by the projected paths
 * of several bridges, none of which encloses it alone (the two sides of a cup's handle: its
 * *handle caps*). After the labelling (acd3/measure: projected paths as barriers, faces flooded
 * into regions, each region claimed by the patches on its side of its paths), for every region
 * claimed by two or more patches (each with at least ACD3_HANDLE_VOTE_SHARE of the leading vote):
 *
 * 1. Its boundary loops: the region cut open along the barriers (projected paths, earlier arcs,
 *    the mesh's openings) is a surface; its boundary sides (an edge side whose face is in the
 *    region) are joined around every vertex through the region's faces between two barriers (a
 *    wedge), so loops that touch at a vertex stay apart. A loop with a projected path on it is a
 *    cap loop; a region with two or more cap loops is a *shared pocket* (a disk has one loop).
 * 2. One multi-source Dijkstra restricted to the region from the vertices of its cap loops, each
 *    vertex labelled with its loop (a vertex on two loops: the smaller loop id).
 * 3. Every edge (u, v) inside the region, not a barrier, whose ends carry different loops A != B
 *    gives a candidate arc backtrace(u) + (u, v) + backtrace(v) of length dist(u) + |uv| +
 *    dist(v); the shortest per pair (A, B) is kept (ties: the lower edge id).
 * 4. Kruskal, shortest first: an arc is kept when it joins two loops not yet joined, so the graph
 *    G_h of loops and arcs is a forest and cutting along the arcs never separates the region
 *    (m - 1 arcs turn a region of m cap loops into a disk, when the candidates connect them).
 *    The dissertation's G_h has the caps (bridges) as vertices; we use their loops, which is the
 *    same when each cap bounds the pocket by one loop and stays correct when one bridge's path
 *    meets another's on the same loop (an arc between two sides of one loop would cut the region
 *    apart, or open a handle inside it instead of joining two caps).
 * 5. The arcs are barriers: the region is measured cap by cap. A second multi-source Dijkstra,
 *    from the vertices of the paths of each substantial claimant (labelled with its patch),
 *    crossing no barrier and no arc, gives every face of the pocket the patch of its vertex
 *    nearest to a cap: a hand through the handle enters under one cap and leaves under the
 *    other, and the handle's wall lies under the nearer one (the hole of a torus measures r, not
 *    2 r). Measuring each vertex against its own nearest cap instead (per face corner) was
 *    tried: turbine, solid, tau 0.05 gave 90 parts instead of 46 (docs/acd3d.md).
 *
 * Re-projection. A15 re-projects the bridges with the arcs as barriers and loops (at most
 * 2g + 2 rounds). Here the arcs lie in regions that no projected path enters (their inner
 * vertices are off every path, their edges are no path's edges, their ends on the caps' paths):
 * no path crosses an arc, re-projecting changes no path, the regions are the same once the arcs
 * are barriers (the forest never separates), and a second round finds every shared pocket with
 * one cap loop. One round is therefore the fixed point; test_acd3_handles checks the invariants
 * (arcs off the paths, regions unchanged) instead of looping.
 *
 * Genus 0. Nothing is done on a surface without handles (genus by Euler's formula): a region
 * with two loops there is an annulus between paths that encircle another region, not a pocket
 * shared by handle caps (and genus-0 results stay what they were without handle cuts).
 *
 * Hidden handles (a handle inside one pocket, one cap loop) are not cut: the decomposition
 * unearths them when their concavity is above tau (dissertation §V.C). */
#ifndef ACD_ACD3_HANDLES_H
#define ACD_ACD3_HANDLES_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "acd/mesh.h"
#include "geom3/dijkstra.h"

/* a claimant of a region must have at least this share of the leading claimant's vote length */
#define ACD3_HANDLE_VOTE_SHARE 0.25

/* One side of a projected path edge: the face on that side votes for a patch (acd3/measure). */
typedef struct acd3_claim {
    uint32_t region; /* the face's region (its face id until the regions are known) */
    uint32_t patch;
    double w;        /* the edge's length */
    uint32_t face;
    uint32_t edge;
} acd3_claim;

/* Sorts claims by (region, patch, w, face, edge): a total order, so sums over runs are bitwise
 * reproducible. */
void acd3_claims_sort(acd3_claim *c, size_t n);

typedef struct acd3_handle_arcs {
    size_t narcs;
    uint32_t *vert;    /* arc i: vert[off[i] .. off[i + 1]), from a vertex of loop a[i] to one of b[i] */
    size_t *off;       /* narcs + 1 (NULL when narcs == 0) */
    uint32_t *region;  /* per arc: the shared pocket it cuts */
    uint32_t *a, *b;   /* per arc: the two cap loops it joins (ids local to the region, a < b) */
    double *length;
} acd3_handle_arcs;

void acd3_handle_arcs_free(acd3_handle_arcs *h);

typedef struct acd3_handle_input {
    const acd_mesh *m;
    const acd_edge_graph *g;
    const uint32_t *face_of;     /* acd3_edge_faces */
    const uint32_t *face_region; /* per face */
    size_t nregions;
    const uint8_t *edge_path;    /* per edge: on a projected path */
    const acd3_claim *claims;    /* region set, sorted by acd3_claims_sort */
    size_t nclaims;
    const double *best;          /* per region: the leading patch's summed vote (-1: none) */
} acd3_handle_input;

typedef struct acd3_handle_result {
    uint8_t *edge_arc;      /* per edge: on an arc */
    acd3_handle_arcs arcs;
    uint32_t *face_patch;   /* per face: the cap it is measured against, UINT32_MAX outside the
                             * shared pockets; NULL when there is none */
    size_t npockets;        /* shared pockets */
    size_t ncandidates;     /* candidate arcs (one per pair of cap loops that meet) */
    long genus;             /* of the mesh (Euler characteristic), computed once a region has two
                             * substantial claimants (else 0); 0: nothing more was looked for */
} acd3_handle_result;

/* Genus by Euler's formula, chi = V - E + F = 2c - 2g - b over c components and b boundary
 * loops (as acd3/topology, on the graph and faces at hand); 0 where the formula gives a negative
 * value (not a 2-manifold: sheets touching at a vertex); -1 on allocation failure. */
long acd3_handles_genus(const acd_mesh *m, const acd_edge_graph *g, const uint32_t *face_of);

/* Finds the shared pockets of a labelling, their arcs and the cap of every face in them. Only on
 * a surface of genus > 0: a surface without handles has no handle caps. */
acd_status acd3_handle_cuts(const acd3_handle_input *in, acd3_handle_result *out, acd_error *err);
void acd3_handle_result_free(acd3_handle_result *r);

#endif
