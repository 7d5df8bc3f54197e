/* mesh/selfintersect: acd_mesh_self_intersections (acd/mesh.h) on a tree the caller already has.
 * Internal part. */
#ifndef ACD_MESH_SELFINTERSECT_H
#define ACD_MESH_SELFINTERSECT_H

#include <stddef.h>
#include <stdint.h>

#include "acd/mesh.h"
#include "geom3/bvh.h"

/* As acd_mesh_self_intersections, its broad phase on bvh when bvh is m's tree (acd_bvh_is_over m's
 * own arrays: the tree acd_bvh_build makes of them), else on a tree built here (NULL: always). The
 * same count and pairs, in the same order, as acd_mesh_self_intersections: the tree is the one it
 * builds. */
acd_status acd_mesh_self_intersections_bvh(const acd_mesh *m, const acd_bvh *bvh, size_t *count, uint32_t *pairs,
                                           size_t max_pairs, acd_error *err);

/* Whether m intersects itself (*crosses 1: acd_mesh_self_intersections_bvh's count would be > 0), the
 * pairs tested in the same order but stopping at the first that intersects. */
acd_status acd_mesh_self_intersects_bvh(const acd_mesh *m, const acd_bvh *bvh, int *crosses, acd_error *err);

#endif
