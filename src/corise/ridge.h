/* corise/ridge: convex ridges, CoRiSe §4.1 and Eq. 2 (Liu, Xi, Lien, CAD 2016); spec corise.md
 * §1.6 and §2.4 (our reconstruction of the supplement's Algorithm 1).
 *
 * Hull vertices are clustered greedily: low bridges (valley concavity <= tau) are collapsed in
 * ascending order of valley length (ties: bridge order), except when a high bridge (concavity >
 * tau) already joins the two clusters. Every final cluster is a convex ridge, so (Eq. 2) no high
 * bridge joins two vertices of one ridge, and every low bridge between two ridges is parallel to
 * a high bridge between them. Bridges without a valley (unreachable) are ignored. */
#ifndef ACD_CORISE_RIDGE_H
#define ACD_CORISE_RIDGE_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "corise/valley.h"

typedef struct acd_corise_ridges {
    size_t nridges;
    uint32_t *ridge_of; /* per hull vertex (index into bridges->hull_vertex): its ridge */
    size_t nhull;
} acd_corise_ridges;

/* Ridges are numbered by their smallest hull-vertex index. */
acd_status acd_corise_ridges_compute(const acd_corise_bridges *b, double tau, acd_corise_ridges *out, acd_error *err);
void acd_corise_ridges_free(acd_corise_ridges *r);

/* Index of mesh vertex v among b->hull_vertex, or SIZE_MAX. */
size_t acd_corise_hull_index(const acd_corise_bridges *b, uint32_t v);

#endif
