/* corise/regions: potential, must-link and fuzzy regions, CoRiSe §5.2 Eqs. 4-7 (Liu, Xi, Lien,
 * CAD 2016); spec corise.md §1.10 and §2.6.
 *
 * Every deep valley is split at its separators (corise/separator). Each end piece touches a
 * ridge R_k at its end vertex r; T = the facets whose three vertices are all at Dijkstra distance
 * < len(piece) from r (spec A10, "max" rule); U_k = union of its T (Eq. 4). A facet claimed by
 * exactly one ridge is must-link for it (Eqs. 5-6); every other facet is fuzzy (Eq. 7). Safety
 * net (spec §2.6): a ridge with no must-link facet gets the facets incident to its hull vertices
 * that no other ridge claims. */
#ifndef ACD_CORISE_REGIONS_H
#define ACD_CORISE_REGIONS_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "acd/mesh.h"
#include "acd3/poll.h"
#include "corise/ridge.h"
#include "corise/valley.h"
#include "geom3/dijkstra.h"

#define ACD_CORISE_FUZZY UINT32_MAX

/* must_link: m->ntriangles entries, set to a ridge id or ACD_CORISE_FUZZY. *nsub (may be NULL):
 * number of sub-valleys attached to ridges. */
acd_status acd_corise_regions(const acd_mesh *m, const acd_edge_graph *g, const acd_corise_bridges *b,
                              const acd_corise_ridges *r, double tau, uint32_t *must_link, size_t *nsub,
                              acd_error *err);

/* Same, with the valley splits and the balls shared among nthreads OpenMP threads (when the
 * caller is not already in a parallel region and the mesh has at least
 * ACD_CORISE_PARALLEL_MIN_FACES facets: below, a parallel region costs more than it saves; at most
 * ACD_CORISE_MAX_THREADS); the result is the same for any nthreads. poll (may be NULL; acd3/poll)
 * is polled before each valley split and each ball (the calling thread calls the callback, the
 * others read its flag); when it says stop, ACD_ERR_CANCELLED. It decides nothing else. */
#define ACD_CORISE_MAX_THREADS 256
acd_status acd_corise_regions_mt(const acd_mesh *m, const acd_edge_graph *g, const acd_corise_bridges *b,
                                 const acd_corise_ridges *r, double tau, int nthreads, acd3_poll *poll,
                                 uint32_t *must_link, size_t *nsub, acd_error *err);

#endif
