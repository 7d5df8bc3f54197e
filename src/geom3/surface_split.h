/* geom3/surface_split: split a triangulated surface along edge paths into patches.
 *
 * Surface ACD resolves a cut loop by cutting the surface along it (Lien D §V.B, spec acd3d.md §5.1):
 * duplicate the loop's vertices, flood-fill the faces without crossing loop edges, each connected face
 * set becomes a component. No faces are created (surface ACD never caps).
 *
 * Here the vertices are duplicated exactly where needed: the corners of a vertex are grouped into fans
 * that are connected across uncut edges, and each fan gets its own copy. So a closed loop on a sphere
 * gives two patches, a loop around a torus's tube gives one patch (a cylinder) with the loop's vertices
 * doubled, and an open slit inside a surface opens it (interior slit vertices doubled, slit ends not). */
#ifndef ACD_GEOM3_SURFACE_SPLIT_H
#define ACD_GEOM3_SURFACE_SPLIT_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "acd/mesh.h"

typedef struct acd_patch {
    acd_mesh mesh;           /* the patch's faces, with its own vertex copies */
    uint32_t *source_vertex; /* mesh.nvertices: the input vertex of each copy */
    uint32_t *source_face;   /* mesh.ntriangles: the input triangle */
} acd_patch;

typedef struct acd_split_result {
    acd_patch *patches;   /* ordered by their lowest input triangle */
    size_t npatches;
    uint32_t *face_patch; /* per input triangle: its patch */
    size_t cut_edges;     /* distinct mesh edges cut */
} acd_split_result;

/* Splits m along the undirected edges given as vertex pairs (edges[2i], edges[2i+1]); every pair must be
 * an edge of m (ACD_ERR_INVALID_INPUT naming it otherwise). m must be an oriented surface, open or
 * closed: each half-edge (a, b) at most once (ACD_ERR_NON_MANIFOLD otherwise). */
acd_status acd_surface_split_edges(const acd_mesh *m, const uint32_t *edges, size_t nedges, acd_split_result *out,
                                   acd_error *err);

/* Same along a vertex path v0 v1 ... v(n-1) (consecutive vertices joined by mesh edges); closed adds
 * the edge v(n-1) v0. Several paths: call acd_surface_split_edges with all their edges. */
acd_status acd_surface_split_path(const acd_mesh *m, const uint32_t *path, size_t n, int closed,
                                  acd_split_result *out, acd_error *err);

void acd_split_result_free(acd_split_result *r);

#endif
