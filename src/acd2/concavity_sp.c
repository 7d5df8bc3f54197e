/* acd2/concavity_sp: SP-concavity (Lien dissertation IV.A.1.b, Alg. 2). Not yet implemented. */
#include "acd2/concavity_sp.h"

#include <stdlib.h>

void acd2_sp_work_free(acd2_sp_work *w) { (void)w; }

acd_status acd2_sp_pocket(const acd_vec2 *p, size_t n, size_t a, size_t b, double *conc, acd2_sp_work *w) {
    (void)p; (void)n; (void)a; (void)b; (void)conc; (void)w;
    return ACD_ERR_UNSUPPORTED;
}
