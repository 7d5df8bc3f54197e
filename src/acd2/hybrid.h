/* acd2/hybrid: the hazard test of the hybrid measures H1 and H2 (dissertation IV.A.1.c,
 * Obs. A.5, Algs. 3-4; spec acd2d.md §3.3). */
#ifndef ACD_ACD2_HYBRID_H
#define ACD_ACD2_HYBRID_H

#include <stddef.h>

#include "acd/polygon.h"

/* hazard(beta, rho): some pocket edge, from p[a] to p[b] along the ring, has an outward normal
 * opposing the bridge's, n_e . n_beta < 0, which for edges and bridge of the same orientation
 * is (e_end - e_start) . (p[b] - p[a]) < 0 (spec §11 A4: edges, strict). */
int acd2_pocket_hazard(const acd_vec2 *p, size_t n, size_t a, size_t b);

#endif
