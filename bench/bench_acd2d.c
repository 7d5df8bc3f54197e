/* bench_acd2d: time of the reference sweep of spec acd2d.md §9 (every model x 4 measures x 9 tau,
 * decomposition only, I/O excluded) and of the 10240-vertex star at tau = 0 with SL.
 * Usage: bench_acd2d [shared-data-dir]. Prints one line per model/measure and the totals. */
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "acd/acd2d.h"

#include "bench_clock.h"

int main(int argc, char **argv) {
    const char *dir = argc > 1 ? argv[1] : ACD_SHARED_DATA;
    const char *models[] = {"wierd2_n", "nazca_nazca_monkey", "nazca_nazca_monkey_2", "nazca_nazca_heron", "texas", "bird"};
    const double taus[9] = {0, 0.01, 0.1, 0.5, 1, 5, 10, 20, 40};
    double total = 0;
    for (size_t i = 0; i < sizeof models / sizeof models[0]; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/polygons-lien/%s.poly", dir, models[i]);
        acd_polygon_set set;
        acd_error err;
        if (acd_polygon_set_read_file(&set, path, ACD_POLY_FORMAT_AUTO, NULL, &err) != ACD_OK) {
            fprintf(stderr, "%s\n", err.message);
            return 1;
        }
        for (int m = 0; m < 4; m++) {
            double t0 = bench_wall();
            printf("%-22s %s:", models[i], acd2d_measure_name((acd2d_measure)m));
            for (int t = 0; t < 9; t++) {
                acd2d_params prm = acd2d_default_params();
                prm.measure = (acd2d_measure)m;
                prm.tau = taus[t];
                acd2d_result res;
                if (acd2d_decompose(&set.polygons[0], &prm, &res, &err) != ACD_OK) {
                    fprintf(stderr, "%s\n", err.message);
                    return 1;
                }
                printf(" %zu", res.ncomponents);
                acd2d_result_free(&res);
            }
            double dt = bench_wall() - t0;
            total += dt;
            printf("  %.3f s\n", dt);
        }
        acd_polygon_set_free(&set);
    }
    printf("sweep total: %.3f s\n", total);
    char path[1024];
    snprintf(path, sizeof path, "%s/polygons-lien/star_star6.poly", dir);
    acd_polygon_set set;
    acd_error err;
    if (acd_polygon_set_read_file(&set, path, ACD_POLY_FORMAT_AUTO, NULL, &err) == ACD_OK) {
        acd2d_params prm = acd2d_default_params();
        for (int tol = 0; tol < 2; tol++) {
            prm.notch_tolerance = tol ? 0 : 1e-5;
            double t0 = bench_wall();
            acd2d_result res;
            if (acd2d_decompose(&set.polygons[0], &prm, &res, &err) != ACD_OK) return 1;
            printf("star6 tau 0 SL notch-tol %g: %zu vertices, %zu notches, %zu components, %.4f s\n", prm.notch_tolerance,
                   res.input_vertices, res.input_notches, res.ncomponents, bench_wall() - t0);
            acd2d_result_free(&res);
        }
        acd_polygon_set_free(&set);
    }
    return 0;
}
