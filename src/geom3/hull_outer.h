/* geom3/hull_outer: an enclosing polytope of a solid convex hull with a corner budget, as a subset
 * of the hull's own support planes (so it contains the hull by construction, whatever the rounding
 * of its corners), for cages (acd/cage.h).
 *
 * Greedy cutting planes: start from the bounding box's six support planes (or, for a budget
 * under 8, the four support planes of a regular tetrahedron's face directions); then repeatedly
 * take the corner of the current polytope farthest outside the hull and add the hull facet plane
 * it violates most, as long as the polytope keeps at most max_vertices corners. Corners are
 * found by point/plane duality (qhull). Deterministic. */
#ifndef ACD_GEOM3_HULL_OUTER_H
#define ACD_GEOM3_HULL_OUTER_H

#include <stddef.h>

#include "acd/base.h"
#include "acd/hull.h"

/* h: a dim-3 hull; max_vertices >= 4; push >= 0: the caller will move every plane outward by it
 * (cages), so corners are counted, and the worst corner found, on the pushed planes (distance
 * outside the hull pushed by `push`). *planes (malloc'd, 4 per plane: unit outward normal n and d,
 * n.x + d <= 0 inside, unpushed) gets the chosen planes, *ncorners the corner count of their
 * pushed intersection (as found in floating point). When the hull has at most max_vertices
 * vertices its own planes are returned. */
acd_status acd_hull_outer(const acd_hull *h, size_t max_vertices, double push, double **planes, size_t *nplanes,
                          size_t *ncorners, acd_error *err);

#endif
