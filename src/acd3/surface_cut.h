/* acd3/surface_cut: splitting a surface (surface ACD, dissertation §V.B.3; paper §4.3;
 * spec acd3d.md §5.1).
 *
 * Surface ACD splits a surface along a closed loop of mesh edges and never caps. The loop used
 * here is the boundary between the faces whose centroid lies on the positive side of a cut plane
 * (exact side test, acd_cut_plane_side) and the others: the surface splits along the mesh edges
 * that separate the two classes, and every connected set of faces of one class (across shared
 * edges) is a piece. No new vertices are made; the pieces partition the input's faces. */
#ifndef ACD_ACD3_SURFACE_CUT_H
#define ACD_ACD3_SURFACE_CUT_H

#include "acd/base.h"
#include "acd/mesh.h"
#include "geom3/dijkstra.h"
#include "geom3/plane_cut.h"

/* Fills out (an acd_cut_result, so the driver treats solid and surface cuts alike: is_cap all 0,
 * source = input vertex ids) with the pieces, the + side first, each side by lowest face.
 * near != NULL: only the connected set of separating edges nearest to that point splits (the
 * cut loop at the feature being resolved, like the solid region cut); other crossings of the
 * plane leave the surface whole. */
acd_status acd3_surface_cut(const acd_mesh *m, const acd_edge_graph *g, const acd_cut_plane *pl, const double *near,
                            acd_cut_result *out, acd_error *err);

/* Splits m into its connected components (faces across shared edges), same output form. */
acd_status acd3_surface_components(const acd_mesh *m, const acd_edge_graph *g, acd_cut_result *out, acd_error *err);

#endif
