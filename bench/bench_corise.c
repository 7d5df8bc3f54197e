/* Timing of the CoRiSe loop (src/corise/corise.c) on closed trench boxes of growing size (the
 * synthetic meshes of the tests), literal and with the hull-depth clamp. Prints one line per run:
 * facets, tau, clamp, parts, cuts, seconds. Results: docs/results/corise.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "corise/corise.h"
#include "../tests/corise_meshes.h"

#include "bench_clock.h"

static double trench_top(double x, double y, const void *u) {
    (void)y;
    (void)u;
    double d = fabs(x - 1.0) / 0.25;
    return 1.0 - (d < 1 ? 0.6 * (1 - d) : 0);
}

int main(void) {
    const size_t sizes[] = {32, 64, 128};
    const double taus[] = {0.1, 0.3};
    printf("%10s %6s %6s %6s %6s %9s\n", "facets", "tau", "clamp", "parts", "cuts", "seconds");
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        acd_mesh m;
        cm_heightfield_box(&m, sizes[s], sizes[s] / 2, sizes[s] / 2, 2.0, 1.0, trench_top, NULL);
        uint32_t *lab = malloc(m.ntriangles * sizeof *lab);
        if (!lab) return 1;
        for (size_t t = 0; t < sizeof taus / sizeof taus[0]; t++)
            for (int clamp = 0; clamp < 2; clamp++) {
                acd_corise_params p = acd_corise_default_params();
                p.tau = taus[t];
                p.clamp_hull_depth = clamp;
                acd_corise_stats st;
                acd_error err;
                double t0 = bench_wall();
                if (acd_corise_segment(&m, &p, lab, &st, &err) != ACD_OK) {
                    fprintf(stderr, "bench_corise: %s\n", err.message);
                    return 1;
                }
                printf("%10zu %6.2f %6d %6zu %6zu %9.3f\n", m.ntriangles, p.tau, clamp, st.parts, st.cuts, bench_wall() - t0);
            }
        free(lab);
        acd_mesh_free(&m);
    }
    return 0;
}
