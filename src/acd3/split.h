/* acd3/split: the choice of a part's cut (dissertation §V.B; spec acd3d.md §2, §7.1): the candidate
 * planes (acd3/resolve) cut and their pieces measured, compared by the least piece concavity or by
 * the pieces' hull volume within a band (docs/acd3d.md "Cut choice by volume"), screened on hull
 * volume estimates, evaluated by the splitting thread and any idle helper with the choice replayed
 * in candidate order (the sequential loop's, whoever evaluated what). acd3/decompose calls it for
 * every part of the tree. */
#ifndef ACD_ACD3_SPLIT_H
#define ACD_ACD3_SPLIT_H

#include <stddef.h>

#include "acd/hull.h"
#include "acd/mesh.h"
#include "acd3/decompose.h"
#include "acd3/measure.h"
#include "acd3/poll.h"
#include "acd3/resolve.h"
#include "geom3/edge_map.h"
#include "geom3/plane_cut.h"

/* A part measured while its parent's cut was chosen keeps that measure until it is processed. */
typedef struct acd3_measured {
    acd_edge_graph g;
    acd3_measure ms;
    int valid;
} acd3_measured;

/* Frees x's measure and graph (when valid); x is left invalid. */
void acd3_measured_free(acd3_measured *x);

/* Measures m (its edge graph, then acd3/measure) into *out. hull: m's hull when already computed
 * (taken over, also on failure), else NULL; poll: the run's (NULL: none), polled by the measure
 * (ACD_ERR_CANCELLED once it says stop). */
acd_status acd3_measure_mesh(const acd_mesh *m, double eps, double tol, acd_hull *hull, acd3_poll *poll,
                             acd3_measured *out, acd_error *err);

/* A part's chosen cut: the cut's pieces with their measures (kept for when they are processed). */
typedef struct acd3_split_choice {
    acd_cut_result cut;
    acd3_measured *pieces; /* cut.npieces measures */
    acd3_plane_candidate plane;
    double concavity; /* the largest over the pieces */
    double hullvol;   /* the sum of the pieces' hull volumes */
    int bodies;       /* the root split into its bodies (no plane; split_bodies) */
} acd3_split_choice;

/* Frees c's cut and measures; c is zeroed. */
void acd3_split_choice_free(acd3_split_choice *c);

/* m's edge map, checked closed (acd_edge_map_closed); returns 1 when built and m is closed, else 0
 * (nothing to free). em NULL: only whether m is closed. A part's, built once for all the cuts of
 * its splits (without it, each cut builds and checks the map and reports that). */
int acd3_part_edge_map(const acd_mesh *m, acd_edge_map *em);

/* A part no candidate splits, above tau and not within tau of its hull (it would be a no_cut leaf),
 * is cut by planes through the centroid of its volume across its principal axes (acd3_halving_planes;
 * acd3/decompose's process_node tries them), with the sliver rule and then its retry, the best by the usual rule. Such parts are crumpled
 * pieces (volume 1e-6 to 4e-4 of their hull's: thin wedges, folded layers) that earlier cuts left
 * after a one-rounding perturbation of the input; the witness planes only shave them, as the
 * witness is a tip of a layer. Halving shrinks them until the measure, at most their extent, meets
 * tau (docs/acd3d.md "Crumpled parts"). */
#define ACD3_HALVING_PLANES 3

/* The halving planes of m (ACD3_HALVING_PLANES): through the centroid of its volume, perpendicular
 * to each principal axis of its vertices, the longest first. Returns how many: 0 when m encloses no
 * positive volume. */
int acd3_halving_planes(const acd_mesh *m, acd3_plane_candidate out[ACD3_HALVING_PLANES]);

/* Splits m by the best of the first candidates that give >= 2 solid pieces: the smallest largest
 * piece concavity (up to tol), then the fewest pieces, then the candidates' order. A cut whose
 * pieces all meet tau, or that at least halves the concavity, is taken at once. With
 * restrict_cut, each plane cuts only its section region nearest the witness (acd3/region_cut). The pieces'
 * measures are kept for when they are processed. helpers: how many other threads may join the
 * evaluation of the candidates (the result is the same). em (solid mode, may be NULL): m's edge map,
 * checked closed (acd3_part_edge_map). Returns 1 if split, 0 if no candidate
 * splits, or -(status) on failure. choice: by concavity as above; by volume (solid mode) the volume
 * plane joins the candidates, every candidate is compared (up to its budget) and split_better's band
 * rule decides; by band (solid mode) the band rule on the same candidates, with the early acceptance
 * kept (docs/acd3d.md "Cut choice by band"). screen_rel: the hull volume screen's margin (by volume;
 * acd3_decompose_screen: <= -1 or NaN, none); its counts are added to *stats. fixed (nfixed of
 * them; NULL: none): these candidates instead of the resolver's (the halving planes). */
int acd3_try_split(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms, double extent, double eps,
                   double tau, double tol, int solid, int restrict_cut, double min_piece_volume,
                   unsigned cut_flags, const acd3_resolve_opts *ro, acd3d_cut_choice choice, int helpers,
                   const acd_edge_map *em, double screen_rel, acd3_poll *poll,
                   const acd3_plane_candidate *fixed, int nfixed, acd3_decompose_stats *stats, acd3_split_choice *best,
                   acd_error *err);

#endif
