/* Timing and output of the public segmentation API (acd_segment, CoRiSe) on real meshes (CGAL's
 * camel, homer, elephant, armadillo, dino, hand, fetched by scripts/fetch-data.sh into
 * ACD_MESH_DATA) at tau 0.1: with the default hull-depth clamp on 1 and 2 threads, and literally on
 * 1 thread. Each run is repeated REPS times and the fastest wall time kept (the machine is shared);
 * the CPU time is that run's process CPU time (all threads). Prints one line per run: faces, clamp,
 * threads, parts, cuts, unresolved, wall seconds, CPU seconds, wall seconds per 20k faces,
 * hull-to-mesh volume ratio, largest part concavity; then, per mesh, the 2-thread speed-up over 1
 * thread measured in the same run, and whether the labels were the same. A missing mesh is
 * reported and skipped. Results: docs/results/corise.md. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "acd/mesh.h"
#include "acd/segment.h"

#include "bench_clock.h"

#define REPS 3

/* Best of REPS runs; *r keeps the last result (caller frees). Returns 0 on failure. */
static int timed(const acd_mesh *m, const acd_segment_params *p, acd_segment_result *r, double *w, double *c) {
    *w = 1e300;
    for (int k = 0; k < REPS; k++) {
        acd_error err;
        if (k) acd_segment_result_free(r);
        double w0 = bench_wall(), c0 = bench_cpu();
        if (acd_segment(m, p, r, &err) != ACD_OK) {
            printf("failed: %s\n", err.message);
            return 0;
        }
        double dw = bench_wall() - w0, dc = bench_cpu() - c0;
        if (dw < *w) *w = dw, *c = dc;
    }
    return 1;
}

int main(void) {
    const char *names[] = {"camel.off", "homer.off", "elephant.off", "armadillo.off", "dino.off", "hand.off"};
    printf("%-14s %7s %5s %7s %6s %5s %10s %8s %8s %9s %10s %8s\n", "mesh", "faces", "clamp", "threads", "parts", "cuts",
           "unresolved", "wall s", "cpu s", "s/20k f", "hull/mesh", "max conc");
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", ACD_MESH_DATA, names[i]);
        acd_mesh m;
        acd_error err;
        if (acd_mesh_read(path, &m, &err) != ACD_OK) {
            printf("%-14s skipped: %s (run scripts/fetch-data.sh)\n", names[i], err.message);
            continue;
        }
        const int runs[3][2] = {{1, 1}, {1, 2}, {0, 1}}; /* clamp, threads */
        double wt[3] = {0, 0, 0};
        acd_segment_result r[3];
        int ok[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++) {
            acd_segment_params p = acd_segment_default_params();
            p.tau = 0.1;
            p.clamp_hull_depth = runs[k][0];
            p.threads = runs[k][1];
            double c = 0;
            if (!(ok[k] = timed(&m, &p, &r[k], &wt[k], &c))) continue;
            double mx = 0;
            for (size_t j = 0; j < r[k].nparts; j++)
                if (r[k].parts[j].concavity_rel > mx) mx = r[k].parts[j].concavity_rel;
            printf("%-14s %7zu %5d %7d %6zu %5zu %10zu %8.3f %8.3f %9.3f %10.4f %8.4f\n", names[i], r[k].nfaces, runs[k][0],
                   runs[k][1], r[k].nparts, r[k].cuts, r[k].unresolved, wt[k], c, wt[k] * 20000.0 / (double)m.ntriangles,
                   r[k].mesh_volume > 0 ? r[k].hull_volume / r[k].mesh_volume : 0.0, mx);
        }
        if (ok[0] && ok[1])
            printf("%-14s 2 threads / 1 thread: wall speed-up %.2f, labels %s\n", names[i], wt[0] / wt[1],
                   r[0].nparts == r[1].nparts && !memcmp(r[0].labels, r[1].labels, m.ntriangles * sizeof *r[0].labels)
                       ? "identical"
                       : "DIFFERENT");
        for (int k = 0; k < 3; k++)
            if (ok[k]) acd_segment_result_free(&r[k]);
        acd_mesh_free(&m);
    }
    return 0;
}
