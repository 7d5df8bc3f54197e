/* core/rng: small deterministic pseudo-random generator (xoshiro256** seeded by splitmix64).
 * State is always explicit: no hidden global generator. */
#ifndef ACD_CORE_RNG_H
#define ACD_CORE_RNG_H

#include <stdint.h>

typedef struct acd_rng {
    uint64_t s[4];
} acd_rng;

void acd_rng_seed(acd_rng *r, uint64_t seed);
uint64_t acd_rng_next(acd_rng *r);
/* Uniform in [0, 1). */
double acd_rng_uniform(acd_rng *r);
/* Uniform integer in [0, n), n > 0. */
uint64_t acd_rng_below(acd_rng *r, uint64_t n);

#endif
