/* acd3/surface_cut: splitting a surface (surface ACD, dissertation §V.B.3; paper §4.3;
 * spec acd3d.md §5.1).
 *
 * Surface ACD splits a surface along a closed loop of mesh edges and never caps. The loop used
 * here follows the section of the surface by a cut plane: every vertex gets its exact side of the
 * plane (acd_cut_plane_side; on the plane counts as +), every face the side of two or three of its
 * vertices. Faces meeting across an edge whose ends are on one side are then on one side, so the
 * surface separates only along edges crossing the plane: the chain of crossing edges between
 * faces of different sides, which follows the section loop (or an open chain from boundary to
 * boundary on an open surface) one mesh edge at a time. Every connected set of faces across the
 * other edges is a piece. No new vertices are made; the pieces partition the input's faces. */
#ifndef ACD_ACD3_SURFACE_CUT_H
#define ACD_ACD3_SURFACE_CUT_H

#include "acd/base.h"
#include "acd/mesh.h"
#include "geom3/dijkstra.h"
#include "geom3/plane_cut.h"

/* Fills out (an acd_cut_result, so the driver treats solid and surface cuts alike: is_cap all 0,
 * source = input vertex ids) with the pieces, the + side first, each side by lowest face.
 * near != NULL: only the section strip (the faces crossed by the plane, joined across crossing
 * edges: one per section loop) with the crossing edge nearest to that point splits -- the cut
 * loop at the feature being resolved, like the solid region cut (spec §5.1); other crossings of
 * the plane leave the surface whole. One strip's chain has two sides: pieces it cuts off between
 * itself and the mesh boundary (where it runs along the boundary) are joined back to the
 * neighbour they share most chain length with until two pieces are left. */
acd_status acd3_surface_cut(const acd_mesh *m, const acd_edge_graph *g, const acd_cut_plane *pl, const double *near,
                            acd_cut_result *out, acd_error *err);

/* Splits m along a chain of mesh edges, v[0..n) (consecutive vertices joined by an edge; a closed
 * loop repeats its first vertex last): the global cut's cycle (acd3/global_cut), the surface
 * split of the dissertation (§V.B.3). A piece made only of faces along the chain, and every
 * piece but the two of largest area (where the loop touches itself), is joined to the neighbour
 * it shares most chain length with. A chain that does not separate m cuts it open (one piece,
 * more vertices) or leaves it whole. Same output form as acd3_surface_cut. */
acd_status acd3_surface_cut_chain(const acd_mesh *m, const acd_edge_graph *g, const uint32_t *v, size_t n,
                                  acd_cut_result *out, acd_error *err);

/* Splits m into the faces around vertex `seed` that have a vertex v with level[v] >= thr (joined
 * across edges between two such faces) and the rest: a cut along a level line of `level` (the
 * measure's per-vertex concavity: the pocket around the witness apart from its bridge). No
 * vertex with level >= thr lies on the cut, so the seed is in one piece only. Same output form. */
acd_status acd3_surface_cut_deep(const acd_mesh *m, const acd_edge_graph *g, const double *level, double thr,
                                 uint32_t seed, acd_cut_result *out, acd_error *err);

/* Splits m into its connected components (faces across shared edges), same output form. */
acd_status acd3_surface_components(const acd_mesh *m, const acd_edge_graph *g, acd_cut_result *out, acd_error *err);

#endif
