/* acd2/concavity_sl: SL-concavity, Lien dissertation IV.A.1.a, Fig. 11b (left), Lemma C.2's
 * retraction along the bridge normal (spec acd2d.md §3.1, ★ supporting line, §11 A2). */
#include "acd2/concavity_sl.h"

#include <math.h>

#include "acd2/ring.h"

void acd2_sl_pocket(const acd_vec2 *p, size_t n, size_t a, size_t b, double *conc) {
    acd_vec2 A = p[a], B = p[b];
    double len = hypot(B.x - A.x, B.y - A.y);
    for (size_t k = acd2_next(a, n); k != b; k = acd2_next(k, n)) {
        /* pocket vertices lie left of (or on) the hull edge A->B: orient >= 0 (exact sign) */
        double o = acd2_orient(A, B, p[k]);
        conc[k] = len > 0 && o > 0 ? o / len : 0.0;
    }
}
