/* acd3/resolve: choosing the plane that resolves the most concave feature of a solid
 * (dissertation §V.B.3, Eqn 5.3; paper §4.3, Eqn 5; spec acd3d.md §5.2, §5.4).
 *
 * Candidates, tried in order until one splits the part into two or more solids:
 * 1. The valley plane. The global cut of the dissertation is a loop of concave valleys through
 *    the witness; its plane is the concavity-weighted best-fit (PCA) plane of the loop. We take as
 *    the loop the vertices connected to the witness whose concavity is at least half of the
 *    witness's, and fit their concavity-weighted PCA plane when they spread in two dimensions
 *    (a ring around a neck, a valley around a bump), through the witness.
 * 2. The notch planes (the resolver without feature grouping, spec §5.4): through the most reflex
 *    edge at the witness, bisecting its dihedral angle, and the two planes extending the faces
 *    that meet there.
 * 3. Planes through the witness and the part's centroid containing a principal axis (across a
 *    ring or a bent limb, where the concave valley is not a loop around a neck).
 * 4. Planes through the witness perpendicular to the part's principal axes (the fallback that
 *    guarantees progress whenever the witness is not an extreme point of the part). */
#ifndef ACD_ACD3_RESOLVE_H
#define ACD_ACD3_RESOLVE_H

#include "acd/mesh.h"
#include "acd3/measure.h"
#include "geom3/dijkstra.h"

enum { ACD3_MAX_CANDIDATES = 10 };

typedef struct acd3_plane_candidate {
    double point[3];
    double normal[3]; /* unit */
    const char *kind; /* "valley", "notch", "face", "centroid", "axis" */
} acd3_plane_candidate;

/* Fills up to ACD3_MAX_CANDIDATES candidate planes for the measured part; returns their count
 * (0 only when the part has no witness or an allocation failed). */
int acd3_cut_candidates(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms,
                        acd3_plane_candidate *out);

#endif
