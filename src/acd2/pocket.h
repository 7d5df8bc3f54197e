/* acd2/pocket: hull, bridges and pockets of a ring, and the concavity of every vertex under a
 * measure (dissertation III.B.2, IV.A.1; spec acd2d.md §1.5, §3.0, §3.4). */
#ifndef ACD_ACD2_POCKET_H
#define ACD_ACD2_POCKET_H

#include <stddef.h>
#include <stdint.h>

#include "acd/acd2d.h"
#include "acd2/concavity_sp.h"

typedef struct acd2_work {
    size_t cap;
    size_t *hull;     /* cap + 1 */
    size_t *scratch;  /* cap + 1 */
    acd2_sp_work sp;
} acd2_work;

int acd2_work_reserve(acd2_work *w, size_t n);
void acd2_work_free(acd2_work *w);

typedef struct acd2_measure_opts {
    acd2d_measure measure;
    double tau;        /* model units; H2 compares SL with it */
    double notch_tol;  /* raw cross-product units; 0 = exact */
} acd2_measure_opts;

/* Hull vertices of the ring p[0..n) in ring order (w->hull[0..*nh)). Returns ACD_OK. */
size_t acd2_ring_hull(const acd_vec2 *p, size_t n, acd2_work *w);

/* Measures every vertex of the ring: conc[k] (0 on the hull). *witness receives the notch of
 * largest concavity (ties: smallest id; SIZE_MAX when no vertex is a notch) and *value its
 * concavity (0 when there is none).
 * Cache (spec §3.0 [EXT] caching, optional): cache_be/cache_c (may be NULL) are the bridge ends
 * and concavities of an earlier measurement of a ring this one was cut from, position by
 * position (ids unique); a bridge (a, b) with a < b whose start carried cache_be[a] == ids[b]
 * has the same pocket chain, and its values are reused. out_be (may be NULL) receives this
 * measurement's bridge ends. */
acd_status acd2_measure_ring(const acd_vec2 *p, const int64_t *ids, size_t n, const acd2_measure_opts *o,
                             acd2_work *w, double *conc, size_t *witness, double *value, const int64_t *cache_be,
                             const double *cache_c, int64_t *out_be);

#endif
