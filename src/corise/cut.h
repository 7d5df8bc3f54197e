/* corise/cut: convex ridge separation by sequential binary graph cuts, CoRiSe §5.2 ("Segmentation
 * using graph cut", "Discussion") and Eq. 8 (Liu, Xi, Lien, CAD 2016); spec corise.md §1.11,
 * §2.7, A11, A12, A16, A17.
 *
 * Ridges are cut off one at a time, smallest first (axis-aligned bounding-box diagonal of the
 * ridge's hull vertices, ties by id). For ridge k, on the dual graph of the facets not yet taken:
 * must-link facets of k are tied to the source and those of the ridges not yet cut to the sink by
 * "infinite" t-links (1 + 2 sum w), fuzzy facets have no t-link, and adjacent facets f, g are
 * joined both ways by Eq. 8:
 *     w_fg = alpha Theta_fg / mu_Theta + (1 - alpha) |e_fg| / mu_e,
 * Theta = concave_weight on concave edges, 1 on convex and flat ones (decided exactly with
 * acd_orient3d), mu_* the means over the interior edges of the mesh being cut (A11). The part of
 * k is the minimal source set of the minimum cut (corise/maxflow). What is left after the n - 1
 * cuts is the last ridge's part. */
#ifndef ACD_CORISE_CUT_H
#define ACD_CORISE_CUT_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "acd/mesh.h"
#include "acd3/poll.h"
#include "corise/ridge.h"
#include "corise/valley.h"

typedef struct acd_corise_cut_params {
    double alpha;          /* Eq. 8, default 0.8 */
    double concave_weight; /* Theta on concave edges, default 0.3 */
} acd_corise_cut_params;

acd_corise_cut_params acd_corise_cut_default_params(void);

/* part: m->ntriangles entries, set to 0 .. *nparts - 1 (parts numbered in cut order, empty
 * parts skipped). must_link: per facet a ridge id (< r->nridges) or ACD_CORISE_FUZZY. */
acd_status acd_corise_cut(const acd_mesh *m, const acd_corise_bridges *b, const acd_corise_ridges *r,
                          const uint32_t *must_link, const acd_corise_cut_params *params, uint32_t *part,
                          size_t *nparts, acd_error *err);

/* The same, polling poll (may be NULL; acd3/poll) after the dual graph, before each ridge's cut
 * and within its max-flow (acd_maxflow_solve_poll): when it says stop, ACD_ERR_CANCELLED (part
 * is then undefined). The parts are the same with or without a poll. */
acd_status acd_corise_cut_poll(const acd_mesh *m, const acd_corise_bridges *b, const acd_corise_ridges *r,
                               const uint32_t *must_link, const acd_corise_cut_params *params, acd3_poll *poll,
                               uint32_t *part, size_t *nparts, acd_error *err);

#endif
