/* acd3/volume_plane: cut planes chosen for the tightness of the pieces' hulls (CoACD's objective):
 * planes across the part's principal axes at nine evenly spaced offsets, refined three times
 * around the best (half the step each time), scored by the sum of the volumes of the two sides'
 * convex hulls, the best kept. docs/acd3d.md, "Hull tightness".
 *
 * A side's hull is the hull of the part's vertices on that side and of the points where the
 * part's edges cross the plane: exactly the hull of the piece a plane cut gives (the caps add no
 * vertex but the crossings). Large parts are scored on every k-th vertex (and every crossing):
 * the score only ranks planes, the cut itself is made and measured by the caller. An estimate's
 * scores (max_scored > 0 below) and acd3_volume_plane_sides are hull volumes by geom3/hull_volume's
 * own Quickhull (within 1e-9 of qhull's on the sets tests/test_hull_volume.c checks: they rank the
 * merge's moves, whose gains are then measured exactly), the full search's by qhull. */
#ifndef ACD_ACD3_VOLUME_PLANE_H
#define ACD_ACD3_VOLUME_PLANE_H

#include "acd/mesh.h"
#include "acd3/resolve.h"

/* Up to nmax planes (kind "volume"), best first, at most one per principal axis; returns how
 * many (0 for a flat part or on allocation failure). */
int acd3_volume_planes(const acd_mesh *m, int nmax, acd3_plane_candidate *out);
/* The same, with the score of each plane returned (score may be NULL): the sum of the two sides'
 * hull volumes as scored above (on every k-th vertex of a large part: an estimate). max_scored > 0
 * makes it a coarser, cheaper estimate: at most that many vertices and the crossings of at most
 * twice as many triangles scored, 5 offsets refined twice (only on the axes whose best coarse
 * score is within 2% of the best axis's); 0: as acd3_volume_planes. Only the
 * first naxes (1-3) principal axes are tried (the first: the largest extent). whole (may be NULL):
 * the hull volume of the scored vertices (what the scores compare with: a plane saves
 * whole - score). */
int acd3_volume_planes_scored(const acd_mesh *m, int nmax, size_t max_scored, int naxes, acd3_plane_candidate *out,
                              double *score, double *whole);
/* The sum of the two sides' hull volumes of the plane through point with unit normal `normal`, on
 * every vertex and crossing (the hulls of the two pieces a cut there gives); -1 on failure. */
double acd3_volume_plane_sides(const acd_mesh *m, const double normal[3], const double point[3]);

#endif
