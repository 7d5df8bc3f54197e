/* Clocks for the bench programs (header-only): wall time, the process's CPU time (all threads),
 * and the calling thread's CPU time, in seconds. CPU time is the steadier figure when other jobs
 * share the cores. */
#ifndef ACD_BENCH_CLOCK_H
#define ACD_BENCH_CLOCK_H

#include <time.h>

static inline double bench_clock_s(clockid_t id) {
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
static inline double bench_wall(void) { return bench_clock_s(CLOCK_MONOTONIC); }
static inline double bench_cpu(void) { return bench_clock_s(CLOCK_PROCESS_CPUTIME_ID); }
static inline double bench_thread_cpu(void) { return bench_clock_s(CLOCK_THREAD_CPUTIME_ID); }

#endif
