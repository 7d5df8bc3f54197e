/* acd2/concavity_sl: SL-concavity (dissertation IV.A.1.a; spec acd2d.md §3.1): the distance of a
 * pocket vertex to the supporting line of its bridge. */
#ifndef ACD_ACD2_CONCAVITY_SL_H
#define ACD_ACD2_CONCAVITY_SL_H

#include <stddef.h>

#include "acd/polygon.h"

/* Bridge p[a] -> p[b] of the ring p[0..n) (counterclockwise hull order); sets conc[k] for every
 * pocket vertex k strictly between a and b (cyclically) to its distance to the bridge line. */
void acd2_sl_pocket(const acd_vec2 *p, size_t n, size_t a, size_t b, double *conc);

#endif
