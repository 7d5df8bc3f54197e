/* acd3/resolve: choosing the plane that resolves the most concave feature of a solid
 * (dissertation §V.B.3, Eqn 5.3; paper §4.3, Eqn 5; spec acd3d.md §5.2, §5.4).
 *
 * Candidates, tried in order until one splits the part into two or more solids:
 * E. The edge planes (ours; docs/acd3d.md "Planes through reflex edges"), only when the witness
 *    has a sharp reflex edge (its faces' normals turn by more than 30 degrees): the planes through
 *    it that hold and resolve other sharp reflex edges of the part (within the input's rounding),
 *    with a fourth endpoint of those edges exactly in them (orient3d) or two of them crossing the
 *    plane apart from each other, ranked by how many they hold, at most 3 (kind "edges"): a cube
 *    corner's face planes, a slot's floor, also after rotation and rounding. Not in the notch
 *    resolver.
 * 0. The global cut's plane (solid mode, default resolver; acd3/global_cut): the concavity-
 *    weighted best-fit plane of the minimum-weight cycle of pocket cuts through the witness's
 *    pocket (kind "global"), of the root pocket cut alone when no cycle closes ("pocket"), or of
 *    the cut through the witness of a cup-shaped pocket ("cup").
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
 *    guarantees progress whenever the witness is not an extreme point of the part).
 * With acd3_resolve_opts.notch (ACD3D_RESOLVER_NOTCH, the resolver without feature grouping) the
 * bisector of 2. (degenerate faces and edges within rounding of flat are not notches), then only
 * the axis planes of 4., when the witness has a reflex edge; else 1.-4. as above. */
#ifndef ACD_ACD3_RESOLVE_H
#define ACD_ACD3_RESOLVE_H

#include "acd/mesh.h"
#include "acd3/measure.h"
#include "acd3/pocket_cut.h"
#include "geom3/dijkstra.h"

enum { ACD3_MAX_CANDIDATES = 14 };

typedef struct acd3_plane_candidate {
    double point[3];
    double normal[3]; /* unit */
    const char *kind; /* "edges", "global", "pocket", "cup", "valley", "notch", "face", "centroid", "axis" */
    /* kind "edges" only (set by nothing else): the three points the plane was spanned by, which the
     * cut goes through exactly (a plane made from point and normal misses two of them by rounding
     * and leaves needles along the edge it holds), and the input's rounding at the part (distance;
     * concavities closer than this are the same: a cut beats the edge plane only by more) */
    double span[3][3];
    double rounding;
} acd3_plane_candidate;

typedef struct acd3_resolve_opts {
    int global;       /* non-zero: the global cut's plane first */
    acd3_gc_opts gc;  /* its parameters */
    int notch;        /* non-zero (and global zero): the resolver without feature grouping (spec §5.4,
                         A14): the bisector of the most reflex edge at the witness and the axis
                         planes, or the witness planes when the witness has no reflex edge */
} acd3_resolve_opts;

/* Fills up to ACD3_MAX_CANDIDATES candidate planes for the measured part; returns their count
 * (0 only when the part has no witness or an allocation failed). ro may be NULL (no global
 * cut). poll (acd3/poll; NULL: none) is polled within the edge planes and the global cut's graph;
 * once it says stop, the candidates are cut short (the caller tells by acd3_poll_stopped). */
int acd3_cut_candidates(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms,
                        const acd3_resolve_opts *ro, acd3_poll *poll, acd3_plane_candidate *out);

#endif
