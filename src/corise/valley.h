/* corise/valley: bridges, valleys and valley concavity of CoRiSe (G. Liu, Z. Xi, J.-M. Lien,
 * "Nearly convex segmentation of polyhedra through convex ridge separation", CAD 2016, §3 Step 1,
 * §4, Eq. 1; spec corise.md §1.2-1.5, §2.2-2.3).
 *
 * A bridge is an edge (a, b) of the convex hull of the mesh's vertices; its valley is the
 * shortest vertex path from a to b along the mesh edges (Dijkstra, Euclidean edge lengths,
 * spec A2), where paths of (almost) equal length are told apart by their closeness to the
 * bridge (ACD_CORISE_VALLEY_TIEBREAK), then by vertex ids. The concavity of a valley vertex p is measured in 2D after the
 * projection of Eq. 1, p' = ((p - a).u, d(p, [a, b])) with u = (b - a)/|b - a| (spec A4: ab
 * normalised), as the shortest-path distance from p' to the projected bridge [0, |ab|] x {0}
 * inside the polygon formed by the projected valley and the bridge:
 *   - x-monotone projected valley (the usual case): C(p) = y, the vertical drop (exact);
 *   - otherwise, if that polygon is simple: the exact shortest path inside it (the funnel
 *     algorithm of acd2/concavity_sp, the same SP-concavity as the 2D ACD);
 *   - otherwise (self-intersecting projection, spec A5): C(p) = y, counted in `fallbacks`.
 * C(valley) = max over its vertices; deep iff C > tau (spec A9). */
#ifndef ACD_CORISE_VALLEY_H
#define ACD_CORISE_VALLEY_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "acd/mesh.h"
#include "acd3/poll.h"
#include "geom3/dijkstra.h"

/* Relative weight of the tie-break: an edge uv costs |uv| (1 + k (dev(u) + dev(v)) / (2 |ab|)),
 * dev = distance to the bridge segment. Small enough to change the path only between paths
 * whose lengths differ by less than about k times their length. */
#define ACD_CORISE_VALLEY_TIEBREAK 1e-6

/* How a chain's concavity was obtained. */
typedef enum acd_corise_conc_kind {
    ACD_CORISE_CONC_TRIVIAL = 0, /* fewer than 3 vertices: all 0 */
    ACD_CORISE_CONC_MONOTONE,    /* x-monotone: vertical drop */
    ACD_CORISE_CONC_SP,          /* simple non-monotone polygon: shortest path inside it */
    ACD_CORISE_CONC_FALLBACK     /* self-intersecting projection: vertical drop (spec A5) */
} acd_corise_conc_kind;

/* Concavity of the chain vertices[chain[0..m)] against its own bridge (chain[0], chain[m-1]),
 * the construction used for valleys and for the sub-valleys of §4.2. conc (m values, may be NULL)
 * receives C per vertex (0 at both ends); *max (may be NULL) the maximum and *argmax (may be
 * NULL) its first index; *kind (may be NULL) how it was computed. Coincident end points give 0
 * and the distance to the point. */
acd_status acd_corise_chain_concavity(const double *vertices, const uint32_t *chain, size_t m, double *conc,
                                      double *max, size_t *argmax, acd_corise_conc_kind *kind, acd_error *err);

/* A cheap lower bound of the chain's concavity (the max of acd_corise_chain_concavity): the
 * largest vertical drop of the projected chain, O(m), no allocation. *exact = 1 when the chain is
 * x-monotone (or has fewer than 3 vertices): then *bound is the concavity, bit for bit. Otherwise
 * the concavity is a shortest path inside the polygon (at least the drop, up to the rounding of
 * its path sums: ACD_CORISE_CHAIN_BOUND_REL) or the drop itself (self-intersecting projection). */
void acd_corise_chain_bound(const double *vertices, const uint32_t *chain, size_t m, double *bound, int *exact);

/* Relative slack of that bound: a computed shortest-path concavity is a sum of at most m rounded
 * distances, each at least the drop's share, so concavity >= bound * (1 - ACD_CORISE_CHAIN_BOUND_REL)
 * for chains far below 1e6 vertices (each sum loses at most m ulps, 1e6 x 1.1e-16 = 1.1e-10). */
#define ACD_CORISE_CHAIN_BOUND_REL 1e-9

typedef struct acd_corise_bridge {
    uint32_t a, b;        /* mesh vertex ids of the hull edge, a < b */
    size_t first, count;  /* valley vertices: path[first .. first + count) of the set, a first */
    double length;        /* valley length (sum of its edge lengths); INFINITY when unreachable */
    double concavity;     /* C(valley); 0 when unreachable */
    size_t deepest;       /* index in the valley of the first vertex of maximal concavity */
    acd_corise_conc_kind kind;
} acd_corise_bridge;

typedef struct acd_corise_bridges {
    acd_corise_bridge *bridge; /* sorted by (a, b) */
    size_t nbridges;
    uint32_t *hull_vertex;     /* mesh ids of the hull's vertices, increasing */
    size_t nhull;
    uint32_t *path;            /* all valleys, one after the other */
    size_t npath;
    size_t unreachable;        /* bridges whose ends are not connected on the mesh (spec A13) */
    size_t fallbacks;          /* valleys measured with the fallback */
    int hull_dim;              /* affine dimension of the vertex set (3 for a solid) */
} acd_corise_bridges;

/* Bridges and valleys of the vertices of m used by its triangles, on the edge graph g of m
 * (acd_edge_graph_from_mesh). A vertex set of affine dimension < 2 gives no bridge. */
acd_status acd_corise_bridges_compute(const acd_mesh *m, const acd_edge_graph *g, acd_corise_bridges *out,
                                      acd_error *err);
void acd_corise_bridges_free(acd_corise_bridges *b);

/* Same, with an option that is not in the paper (docs/corise.md): clamp_depth != 0 caps the
 * concavity of every valley vertex by its depth below the hull's surface (-acd_hull_plane_
 * distance), so that valley points lying on the hull (Dijkstra detours over flat hull faces)
 * count as 0. It also lowers features that open onto a flat hull face. */
acd_status acd_corise_bridges_compute_ex(const acd_mesh *m, const acd_edge_graph *g, int clamp_depth,
                                         acd_corise_bridges *out, acd_error *err);

/* Same, with the bridges shared among nthreads OpenMP threads when there are at least
 * ACD_CORISE_PARALLEL_MIN_BRIDGES of them, the mesh has at least ACD_CORISE_PARALLEL_MIN_FACES
 * facets and the caller is not already in a parallel region; the result is the same for any
 * nthreads. Below these sizes a parallel region (fork, join, and idle threads spinning between
 * regions) costs more than the work it shares.
 * poll (may be NULL; acd3/poll): polled after the hull and every ACD_CORISE_POLL_POPS heap pops
 * of the valley searches (the calling thread calls the callback, the others read its flag); when
 * it says stop, ACD_ERR_CANCELLED. It decides nothing else: the bridges are the same with or
 * without it. */
#define ACD_CORISE_PARALLEL_MIN_BRIDGES 32
#define ACD_CORISE_PARALLEL_MIN_FACES 4000
#define ACD_CORISE_POLL_POPS 8192
acd_status acd_corise_bridges_compute_mt(const acd_mesh *m, const acd_edge_graph *g, int clamp_depth, int nthreads,
                                         acd3_poll *poll, acd_corise_bridges *out, acd_error *err);

#endif
