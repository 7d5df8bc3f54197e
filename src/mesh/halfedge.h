/* mesh/halfedge: the edge and half-edge view of an indexed triangle mesh, for any mesh
 * (boundaries, non-manifold edges, inconsistent orientation included).
 *
 * Half-edge h = 3t + k belongs to triangle t and goes from corner k to corner (k+1)%3, i.e.
 * from triangles[h] to triangles[3t + (k+1)%3]. Half-edges with the same two end vertices (in
 * either direction) form one undirected edge. An edge with 1 half-edge is a boundary edge, with
 * 2 a manifold edge (consistently oriented when they run in opposite directions), with more a
 * non-manifold edge. Triangles that repeat a vertex index take no part (their half-edges have
 * edge == ACD_HE_NONE): they are reported as degenerate by the validator. Edge ids follow the
 * first half-edge that uses them, so the view is deterministic. */
#ifndef ACD_MESH_HALFEDGE_H
#define ACD_MESH_HALFEDGE_H

#include <stddef.h>
#include <stdint.h>

#include "acd/mesh.h"

#define ACD_HE_NONE UINT32_MAX

typedef struct acd_halfedges {
    size_t nhalfedges;       /* 3 * ntriangles */
    uint32_t *edge;          /* per half-edge: its undirected edge, or ACD_HE_NONE */
    uint32_t *twin;          /* per half-edge: the other half-edge of a manifold edge, else ACD_HE_NONE */
    size_t nedges;
    uint32_t *edge_v;        /* per edge: its two vertices, smaller first */
    uint32_t *edge_start;    /* nedges + 1 offsets into edge_he */
    uint32_t *edge_he;       /* the half-edges of edge e: edge_he[edge_start[e] .. edge_start[e+1]) */
} acd_halfedges;

static inline uint32_t acd_he_from(const acd_mesh *m, uint32_t h) { return m->triangles[h]; }
static inline uint32_t acd_he_to(const acd_mesh *m, uint32_t h) {
    return m->triangles[h - h % 3 + (h % 3 + 1) % 3];
}
static inline uint32_t acd_he_next(uint32_t h) { return h - h % 3 + (h % 3 + 1) % 3; }
static inline uint32_t acd_he_prev(uint32_t h) { return h - h % 3 + (h % 3 + 2) % 3; }
static inline uint32_t acd_edge_valence(const acd_halfedges *he, uint32_t e) {
    return he->edge_start[e + 1] - he->edge_start[e];
}

/* Builds the view. Indices must be < nvertices (ACD_ERR_INVALID_INPUT naming the triangle
 * otherwise); more than 2^32 / 3 - 1 triangles is ACD_ERR_UNSUPPORTED. */
acd_status acd_halfedges_build(const acd_mesh *m, acd_halfedges *he, acd_error *err);

/* Half-edges between two calls of acd_halfedges_build_poll's stop (2^18: some 0.1 s on this
 * project's VM at 2.5 M half-edges, the 832k-triangle armadillo of docs/results/3d-large.md). */
#define ACD_HE_POLL_HALFEDGES ((size_t)1 << 18)

/* The same, calling stop(user) (may be NULL: never) every ACD_HE_POLL_HALFEDGES half-edges of its
 * passes over them: when it returns non-zero, ACD_ERR_CANCELLED with he empty (the caller's message
 * says who asked; this one is generic). The view is the same with or without stop. */
acd_status acd_halfedges_build_poll(const acd_mesh *m, acd_halfedges *he, int (*stop)(void *), void *user,
                                    acd_error *err);
void acd_halfedges_free(acd_halfedges *he);

#endif
