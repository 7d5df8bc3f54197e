/* acd3/surface_merge: the merge pass of surface mode (issue 4: fewer parts at the same tau;
 * docs/acd3d.md, "Surface mode: teeth and the merge pass").
 *
 * Surface mode's parts are open pieces of the input surface, cut along chains of mesh edges
 * without new vertices, so two parts cut apart share the positions of their chain's vertices.
 * Two parts are adjacent when they share an edge (both ends at the same positions, exactly).
 * The union of two adjacent groups is welded along their shared vertices (a position that occurs
 * more than once in one group, the two sides of a slit that opened a handle, is not welded there)
 * and measured with the decomposition's own measure (acd3/measure, with eps given): the pair is
 * joinable when that concavity is <= tau, and its cost is the concavity. Cheapest first (ties:
 * the lower group ids), greedily, until no adjacent pair is joinable; a joined group is a new
 * group and its pairs with its neighbours are measured again, lazily: each starts at the larger
 * cost of the two pairs it grew from (a lower bound where the measure does not drop as a patch
 * grows) and is measured when it is the cheapest (4 such at once). When no pair is joinable, moves
 * (up to 8 rounds, each followed by joins again): a pair whose union measures above tau but within
 * 1.6 tau is joined when one of its parts (the one holding the union's witness first, then those
 * next to a third group; 12 at most) can go to a third adjacent group C, the rest staying
 * connected and within tau and C with the part within tau: one group fewer. Every group is thus
 * within tau by the same measure as the leaves, and connected. Deterministic for any thread count
 * (pairs are measured independently, the choices and the moves are sequential). docs/acd3d.md
 * "Splitting a surface", "Moves in the surface merge pass". */
#ifndef ACD_ACD3_SURFACE_MERGE_H
#define ACD_ACD3_SURFACE_MERGE_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "acd/mesh.h"

typedef struct acd3_surface_merge_result {
    size_t ngroups;
    uint32_t *group_of;  /* per input part: its group; groups numbered by their lowest part */
    size_t *group_size;  /* per group: how many parts */
    double *concavity;   /* per group of >= 2 parts: its measured concavity (<= tau); 0 otherwise */
    acd_mesh *meshes;    /* per group of >= 2 parts: the welded union; empty otherwise */
    size_t merges;       /* joins made */
    size_t moves;        /* parts moved from a nearly joinable pair to a third group (refine) */
} acd3_surface_merge_result;

/* eps, tol, tau in model units (eps: the bridge clustering threshold of the measure). threads:
 * OpenMP workers for the measuring (<= 1: one). progress: NULL, or called before each join from the
 * calling thread; non-zero cancels (ACD_ERR_CANCELLED, nothing returned). */
acd_status acd3_surface_merge(const acd_mesh *parts, size_t nparts, double eps, double tau, double tol, int threads,
                              acd_progress_fn progress, void *progress_user, acd3_surface_merge_result *out,
                              acd_error *err);
void acd3_surface_merge_result_free(acd3_surface_merge_result *r);

#endif
