/* bench_progress_gap: the longest silence of the progress callback (issue 4 item 7: "progress on
 * stderr for runs over a second; cancellable through the API") and the latency of a cancel.
 *
 *   bench_progress_gap 3d|segment|repair MESH [--threads N] [--cancel-after S] [--budget N] [--trace]
 *
 * Runs acd3d_decompose (default parameters), acd_segment or acd_mesh_repair (default options, holes
 * of any size filled: acd 3d's repair of an open mesh) on MESH with a callback that records the
 * time of every call (CLOCK_MONOTONIC from just before the call) and prints the calls, the longest
 * gap between two calls (or between the start and the first call, or the last call and the end)
 * with the stages at its two ends, and, with --cancel-after S, the time from the first call after S
 * seconds (which returns non-zero) to the return of the call. CPU time of the whole process too, and
 * the largest process CPU time between two calls (with --threads 1, the silence without the load of
 * other jobs on the machine).
 * --trace: every call on stderr (seconds from the start, since the previous call, stage, fraction). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd/segment.h"
#include "bench_clock.h"

typedef struct gap_log {
    double t0, last, cancel_after, cancel_at;
    double max_gap, gap_from, gap_to;
    double cpu_last, max_cpu_gap, cpu_gap_at; /* process CPU seconds between calls (steadier under load) */
    char last_stage[96], gap_stage_from[96], gap_stage_to[96];
    long calls;
    int cancelled, trace;
} gap_log;

static void note(gap_log *L, double now, const char *stage) {
    double gap = now - L->last, cpu = bench_cpu();
    if (cpu - L->cpu_last > L->max_cpu_gap) {
        L->max_cpu_gap = cpu - L->cpu_last;
        L->cpu_gap_at = now - L->t0;
    }
    L->cpu_last = cpu;
    if (gap > L->max_gap) {
        L->max_gap = gap;
        L->gap_from = L->last - L->t0;
        L->gap_to = now - L->t0;
        snprintf(L->gap_stage_from, sizeof L->gap_stage_from, "%s", L->last_stage);
        snprintf(L->gap_stage_to, sizeof L->gap_stage_to, "%s", stage);
    }
    L->last = now;
    snprintf(L->last_stage, sizeof L->last_stage, "%s", stage);
}

static int on_progress(void *user, double fraction, const char *stage) {
    (void)fraction;
    gap_log *L = user;
    double now = bench_wall();
    L->calls++;
    if (L->trace)
        fprintf(stderr, "call %.3f (+%.3f, CPU +%.3f) %s %g\n", now - L->t0, now - L->last, bench_cpu() - L->cpu_last,
                stage, fraction);
    note(L, now, stage);
    if (L->cancel_after >= 0 && now - L->t0 >= L->cancel_after) {
        if (!L->cancelled) L->cancel_at = now;
        L->cancelled = 1;
        return 1;
    }
    return 0;
}

int main(int argc, char **argv) {
    if (argc < 3 || (strcmp(argv[1], "3d") && strcmp(argv[1], "segment") && strcmp(argv[1], "repair"))) {
        fprintf(stderr, "usage: %s 3d|segment|repair MESH [--threads N] [--cancel-after S] [--budget N] [--trace]\n",
                argv[0]);
        return 2;
    }
    int seg = !strcmp(argv[1], "segment"), rep = !strcmp(argv[1], "repair"), threads = 0;
    size_t budget = 0;
    gap_log L;
    memset(&L, 0, sizeof L);
    L.cancel_after = -1;
    for (int i = 3; i < argc; i += 2) {
        if (!strcmp(argv[i], "--trace")) {
            L.trace = 1;
            i--;
            continue;
        }
        if (i + 1 >= argc) {
            fprintf(stderr, "%s needs a value\n", argv[i]);
            return 2;
        }
        if (!strcmp(argv[i], "--threads")) threads = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--cancel-after")) L.cancel_after = atof(argv[i + 1]);
        else if (!strcmp(argv[i], "--budget")) budget = (size_t)atol(argv[i + 1]);
        else {
            fprintf(stderr, "unknown option %s\n", argv[i]);
            return 2;
        }
    }
    acd_mesh m;
    acd_error err = {0};
    if (acd_mesh_read(argv[2], &m, &err) != ACD_OK) {
        fprintf(stderr, "%s: %s\n", argv[2], err.message);
        return 1;
    }
    snprintf(L.last_stage, sizeof L.last_stage, "(start)");
    double c0 = bench_cpu();
    L.cpu_last = c0;
    L.t0 = L.last = bench_wall();
    if (L.trace) fprintf(stderr, "start %.3f\n", L.t0);
    acd_status st;
    size_t nparts = 0;
    if (rep) {
        acd_repair_options o = acd_repair_default_options();
        o.fill_holes_max_edges = SIZE_MAX;
        o.progress = on_progress;
        o.progress_user = &L;
        st = acd_mesh_repair(&m, &o, NULL, &err);
        nparts = m.ntriangles;
    } else if (seg) {
        acd_segment_params p = acd_segment_default_params();
        p.threads = threads;
        p.progress = on_progress;
        p.progress_user = &L;
        acd_segment_result r;
        st = acd_segment(&m, &p, &r, &err);
        if (st == ACD_OK) {
            nparts = r.nparts;
            acd_segment_result_free(&r);
        }
    } else {
        acd3d_params p = acd3d_default_params();
        p.threads = threads;
        p.progress = on_progress;
        p.progress_user = &L;
        if (budget) {
            p.budget_parts = budget;
            p.trim_coverage = 0.0008;
        }
        acd3d_result r;
        st = acd3d_decompose(&m, &p, &r, &err);
        if (st == ACD_OK) {
            nparts = r.nparts;
            acd3d_result_free(&r);
        }
    }
    double end = bench_wall();
    note(&L, end, "(end)");
    printf("%s %s: %s, %zu %s, %.2f s wall, %.2f s CPU, %ld calls\n", argv[1], argv[2], acd_status_string(st),
           nparts, rep ? "faces" : "parts", end - L.t0, bench_cpu() - c0, L.calls);
    printf("longest silence: %.3f s (%.2f -> %.2f s, '%s' -> '%s')\n", L.max_gap, L.gap_from, L.gap_to,
           L.gap_stage_from, L.gap_stage_to);
    printf("longest CPU time between calls: %.3f s (the call at %.2f s)\n", L.max_cpu_gap, L.cpu_gap_at);
    if (L.cancelled) printf("cancel asked at %.2f s, returned %.3f s later\n", L.cancel_at - L.t0, end - L.cancel_at);
    acd_mesh_free(&m);
    return st == ACD_OK || (L.cancelled && st == ACD_ERR_CANCELLED) ? 0 : 1;
}
