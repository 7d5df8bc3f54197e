/* bench_2d: timing of the 2D decomposition (Lien, dissertation IV.D; spec
 * ../shared/spec/acd2d.md §7, §9). Not a test.
 *
 *   reference sweep: maze, monkey1, monkey2, heron1, texas, bird x {sl, sp, h1, h2} x
 *                    tau in {0, 0.01, 0.1, 0.5, 1, 5, 10, 20, 40}: components and time per run
 *   star series:     star1..star6 (10 to 10240 vertices) at tau = 0: time, components, and
 *                    time / (n r) to show the growth against the O(n r) bound (Thm C.5)
 *
 * usage: bench_2d [--data DIR] [--reps N] [--verify] [--sweep-only | --stars-only]
 * The polygons are read from DIR (default ../shared/data/polygons-lien beside the checkout);
 * nothing is copied into the repository. Results: docs/results/2d.md. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "acd/acd2d.h"
#include "acd/polygon.h"
#include "acd/verify2d.h"

#include "bench_clock.h"

static int load(const char *dir, const char *file, acd_polygon_set *set) {
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", dir, file);
    acd_error err;
    if (acd_polygon_set_read_file(set, path, ACD_POLY_FORMAT_AUTO, NULL, &err) != ACD_OK) {
        fprintf(stderr, "bench_2d: %s: %s\n", path, err.message);
        return 0;
    }
    for (size_t i = 0; i < set->count; i++)
        if (acd_polygon_validate(&set->polygons[i], i, &err) != ACD_OK) {
            fprintf(stderr, "bench_2d: %s: %s\n", path, err.message);
            acd_polygon_set_free(set);
            return 0;
        }
    return 1;
}

/* Decomposes polygon 0 reps times; returns the best wall time, fills components and the
 * verification outcome (when asked). -1 on failure. */
static double run(const acd_polygon *p, acd2d_measure m, double tau, int reps, int verify, size_t *ncomp,
                  size_t *notches, double *vsec, int *vok, double *cpu, char *msg, size_t msgsize) {
    acd2d_params prm = acd2d_default_params();
    prm.measure = m;
    prm.tau = tau;
    double best = -1;
    *cpu = -1;
    for (int r = 0; r < reps; r++) {
        acd2d_result res;
        acd_error err;
        double t0 = bench_wall(), c0 = bench_thread_cpu();
        acd_status st = acd2d_decompose(p, &prm, &res, &err);
        double t = bench_wall() - t0, c = bench_thread_cpu() - c0;
        if (*cpu < 0 || c < *cpu) *cpu = c;
        if (st != ACD_OK) {
            snprintf(msg, msgsize, "%s", err.message);
            return -1;
        }
        if (best < 0 || t < best) best = t;
        *ncomp = res.ncomponents;
        *notches = res.input_notches;
        if (verify && r == 0) {
            double v0 = bench_wall();
            acd_verify2d_report rep;
            *vok = acd_verify2d_result(p, &res, &prm, 0, &rep, &err) == ACD_OK;
            *vsec = bench_wall() - v0;
            if (!*vok) snprintf(msg, msgsize, "%s", err.message);
        }
        acd2d_result_free(&res);
    }
    return best;
}

static void machine(void) {
    char model[256] = "unknown";
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (f) {
        char line[512];
        while (fgets(line, sizeof line, f))
            if (!strncmp(line, "model name", 10)) {
                char *c = strchr(line, ':');
                if (c) {
                    snprintf(model, sizeof model, "%s", c + 2);
                    model[strcspn(model, "\n")] = 0;
                }
                break;
            }
        fclose(f);
    }
    time_t t = time(NULL);
    char date[64];
    strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", gmtime(&t));
    double load[1] = {-1};
    FILE *la = fopen("/proc/loadavg", "r");
    if (la) {
        if (fscanf(la, "%lf", &load[0]) != 1) load[0] = -1;
        fclose(la);
    }
    printf("machine: %ld cores online, %s; load average %.2f; %s\n", sysconf(_SC_NPROCESSORS_ONLN), model, load[0],
           date);
}

int main(int argc, char **argv) {
    const char *dir = ACD_SHARED_DATA "/polygons-lien";
    int reps = 3, verify = 0, sweep = 1, stars = 1;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--data") && i + 1 < argc)
            dir = argv[++i];
        else if (!strcmp(argv[i], "--reps") && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--verify"))
            verify = 1;
        else if (!strcmp(argv[i], "--sweep-only"))
            stars = 0;
        else if (!strcmp(argv[i], "--stars-only"))
            sweep = 0;
        else {
            fprintf(stderr, "usage: bench_2d [--data DIR] [--reps N] [--verify] [--sweep-only | --stars-only]\n");
            return 1;
        }
    }
    if (reps < 1) reps = 1;
    machine();
    printf("times: best of %d runs of acd2d_decompose, wall and thread CPU time (I/O and validation excluded)%s\n\n",
           reps,
           verify ? "; verify = independent recheck (eval/verify2d)" : "");
    static const char *const names[] = {"maze", "monkey1", "monkey2", "heron1", "texas", "bird"};
    static const char *const files[] = {"wierd2_n.poly", "nazca_nazca_monkey.poly", "nazca_nazca_monkey_2.poly",
                                        "nazca_nazca_heron.poly", "texas.poly", "bird.poly"};
    static const double taus[] = {0, 0.01, 0.1, 0.5, 1, 5, 10, 20, 40};
    int failures = 0;
    if (sweep) {
        printf("## reference sweep (components / milliseconds)\n\n");
        printf("| model | measure |");
        for (size_t t = 0; t < 9; t++) printf(" tau=%g |", taus[t]);
        printf(" total ms |\n|---|---|");
        for (size_t t = 0; t < 10; t++) printf("---|");
        printf("\n");
        double total = 0, vtotal = 0, ctotal = 0;
        for (size_t k = 0; k < 6; k++) {
            acd_polygon_set set;
            if (!load(dir, files[k], &set)) {
                failures++;
                continue;
            }
            for (int m = 0; m < 4; m++) {
                double row = 0;
                printf("| %s | %s |", names[k], acd2d_measure_name((acd2d_measure)m));
                for (size_t t = 0; t < 9; t++) {
                    size_t nc = 0, nr = 0;
                    double vs = 0;
                    int vok = 1;
                    char msg[ACD_ERROR_MESSAGE_SIZE] = "";
                    double cpu = 0;
                    double s = run(&set.polygons[0], (acd2d_measure)m, taus[t], reps, verify, &nc, &nr, &vs, &vok,
                                   &cpu, msg, sizeof msg);
                    if (s < 0) {
                        printf(" error |");
                        fprintf(stderr, "bench_2d: %s %s tau %g: %s\n", names[k], acd2d_measure_name((acd2d_measure)m),
                                taus[t], msg);
                        failures++;
                        continue;
                    }
                    row += s;
                    vtotal += vs;
                    ctotal += cpu;
                    printf(" %zu / %.1f%s |", nc, 1e3 * s, vok ? "" : " VERIFY FAILED");
                    if (!vok) fprintf(stderr, "bench_2d: %s %s tau %g: verify: %s\n", names[k],
                                      acd2d_measure_name((acd2d_measure)m), taus[t], msg);
                    fflush(stdout);
                }
                total += row;
                printf(" %.1f |\n", 1e3 * row);
            }
            acd_polygon_set_free(&set);
        }
        printf("\nwhole sweep: %.3f s wall, %.3f s CPU (target < 3 s on 2 cores)", total, ctotal);
        if (verify) printf("; independent verification of every run: %.3f s", vtotal);
        printf("\n\n");
    }
    if (stars) {
        printf("## star series, tau = 0\n\n");
        printf("| model | n | notches r | measure | components | ms | CPU ms | ns / (n r) |\n"
               "|---|---|---|---|---|---|---|---|\n");
        for (int s = 1; s <= 6; s++) {
            char file[64];
            snprintf(file, sizeof file, "star_star%d.poly", s);
            acd_polygon_set set;
            if (!load(dir, file, &set)) {
                failures++;
                continue;
            }
            size_t n = acd_polygon_num_points(&set.polygons[0]);
            for (int m = 0; m < 4; m++) {
                size_t nc = 0, nr = 0;
                double vs = 0;
                int vok = 1;
                char msg[ACD_ERROR_MESSAGE_SIZE] = "";
                double cpu = 0;
                double t = run(&set.polygons[0], (acd2d_measure)m, 0, reps, verify, &nc, &nr, &vs, &vok, &cpu, msg,
                               sizeof msg);
                if (t < 0) {
                    printf("| star%d | %zu | | %s | error | | | |\n", s, n, acd2d_measure_name((acd2d_measure)m));
                    fprintf(stderr, "bench_2d: star%d: %s\n", s, msg);
                    failures++;
                    continue;
                }
                printf("| star%d | %zu | %zu | %s | %zu%s | %.2f | %.2f | %.2f |\n", s, n, nr,
                       acd2d_measure_name((acd2d_measure)m), nc, vok ? "" : " VERIFY FAILED", 1e3 * t, 1e3 * cpu,
                       1e9 * cpu / ((double)n * (double)(nr ? nr : 1)));
                fflush(stdout);
            }
            acd_polygon_set_free(&set);
        }
        printf("\ntarget: star6 (10240 vertices) at tau = 0 with sl under 100 ms\n");
    }
    return failures ? 2 : 0;
}
