/* bench_exact2d: time and size of the exact 2D decompositions (MCD, Hertel-Mehlhorn) and of the
 * triangulation on the star scaling series and the Nazca figures (Lien, IV.D.3, Table 3).
 *
 * usage: bench_exact2d [--mcd-max N] [--reps R] [DATA_DIR]
 *   --mcd-max N  skip MCD above N vertices (default 10000: monkey2 in, star6 out; star6, 10240
 *                vertices, takes about 5 minutes of CPU and 2.7 GB: --mcd-max 11000)
 *   --reps R     repetitions for inputs under 2000 vertices (median reported; default 3)
 * Times are process CPU time (the benchmark machine is shared). Prints a Markdown table
 * (docs/results/exact2d.md). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "acd/exact2d.h"
#include "acd/polygon.h"
#include "geom2/triangulate.h"

#include "bench_clock.h"

static int cmp_d(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* median time of reps runs of method m (-1: triangulation); *count = pieces or triangles */
static double run(const acd_polygon *p, int m, int reps, size_t *count, const char **fail) {
    double t[16];
    *fail = NULL;
    for (int r = 0; r < reps; r++) {
        acd_error err;
        double t0 = bench_cpu();
        if (m < 0) {
            size_t *tris, nt;
            if (acd_triangulate_polygon(p, &tris, &nt, NULL, &err) != ACD_OK) {
                *fail = "error";
                return 0;
            }
            t[r] = bench_cpu() - t0;
            *count = nt;
            free(tris);
        } else {
            acd_exact2d_result res;
            acd_status st = acd_exact2d_decompose(p, (acd_exact2d_method)m, &res, &err);
            if (st != ACD_OK) {
                *fail = st == ACD_ERR_UNSUPPORTED ? "holes" : "error";
                return 0;
            }
            t[r] = bench_cpu() - t0;
            *count = res.npieces;
            acd_exact2d_result_free(&res);
        }
    }
    qsort(t, (size_t)reps, sizeof *t, cmp_d);
    return t[reps / 2];
}

int main(int argc, char **argv) {
    const char *dir = ACD_SHARED_DATA "/polygons-lien";
    size_t mcd_max = 10000;
    int reps = 3;
    for (int a = 1; a < argc; a++) {
        if (!strcmp(argv[a], "--mcd-max") && a + 1 < argc) mcd_max = (size_t)atol(argv[++a]);
        else if (!strcmp(argv[a], "--reps") && a + 1 < argc) reps = atoi(argv[++a]);
        else dir = argv[a];
    }
    if (reps < 1) reps = 1;
    if (reps > 15) reps = 15;
    const char *files[] = {"star_star1", "star_star2", "star_star3", "star_star4", "star_star5", "star_star6",
                           "star_star2_noise", "star_star3_noise", "star_star4_noise", "star_star5_noise",
                           "texas", "bird", "nazca_nazca_heron", "nazca_nazca_monkey", "nazca_nazca_monkey_2",
                           "wierd2", "wierd2_n", "hole3", "hole5", "torus1"};
    printf("| polygon | n | notches | holes | triangulation ms | HM pieces | HM ms | MCD pieces | MCD s |\n");
    printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (size_t f = 0; f < sizeof files / sizeof *files; f++) {
        char path[2048];
        snprintf(path, sizeof path, "%s/%s.poly", dir, files[f]);
        acd_polygon_set set;
        acd_error err;
        if (acd_polygon_set_read_file(&set, path, ACD_POLY_FORMAT_AUTO, NULL, &err) != ACD_OK) {
            printf("| %s | (not read: %s) |\n", files[f], err.message);
            continue;
        }
        for (size_t i = 0; i < set.count; i++) {
            const acd_polygon *p = &set.polygons[i];
            size_t n = acd_polygon_num_points(p), ntri = 0, nhm = 0, nmcd = 0, notches = 0;
            int r = n < 2000 ? reps : 1;
            const char *fail;
            double tt = run(p, -1, r, &ntri, &fail);
            double th = run(p, ACD_EXACT2D_HM, r, &nhm, &fail);
            const char *hmfail = fail;
            {
                acd_exact2d_result res;
                if (acd_exact2d_decompose(p, ACD_EXACT2D_HM, &res, &err) == ACD_OK) {
                    notches = res.input_notches;
                    acd_exact2d_result_free(&res);
                }
            }
            printf("| %s%s | %zu | %zu | %zu | %.2f | %s%zu | %.2f | ", files[f], set.count > 1 ? "*" : "", n, notches,
                   p->nrings - 1, 1e3 * tt, hmfail ? hmfail : "", nhm, 1e3 * th);
            if (p->nrings > 1) printf("(holes) | - |\n");
            else if (n > mcd_max) printf("(skipped, n > %zu) | - |\n", mcd_max);
            else {
                double tm = run(p, ACD_EXACT2D_MCD, r, &nmcd, &fail);
                if (fail) printf("%s | - |\n", fail);
                else printf("%zu | %.3f |\n", nmcd, tm);
            }
            fflush(stdout);
        }
        acd_polygon_set_free(&set);
    }
    return 0;
}
