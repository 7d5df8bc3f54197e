/* acd3/topology: genus of a part (spec acd3d.md §6, §12 item 8: Euler characteristic and genus).
 *
 * For a triangle mesh whose edges have at most two faces, with c edge-connected components and
 * b boundary loops, chi = V - E + F = 2c - 2g - b gives the genus g (the sum over the
 * components: handles of a closed surface, or of an open one once its holes are capped).
 * V counts the vertices used by faces; a boundary loop is a connected set of boundary edges
 * (joined at their vertices). Non-manifold input (an edge of three or more faces) gives the value
 * of the same formula, which is then only an estimate. */
#ifndef ACD_ACD3_TOPOLOGY_H
#define ACD_ACD3_TOPOLOGY_H

#include <stddef.h>

#include "acd/base.h"
#include "acd/mesh.h"

typedef struct acd3_topology {
    size_t components;     /* edge-connected */
    size_t boundary_loops;
    long euler;            /* V - E + F */
    long genus;            /* (2 components - euler - boundary_loops) / 2, summed over components;
                              0 where that is negative (not a 2-manifold) */
} acd3_topology;

acd_status acd3_topology_of(const acd_mesh *m, acd3_topology *out, acd_error *err);

#endif
