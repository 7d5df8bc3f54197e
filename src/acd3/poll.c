/* acd3/poll: the cancellation poll of acd3d_decompose's tree; see poll.h. */
#include "acd3/poll.h"

acd3_poll acd3_poll_make(acd_progress_fn fn, void *user, const char *stage) {
    acd3_poll p = {fn, user, thrd_current(), stage, 0};
    return p;
}

int acd3_poll_stopped(const acd3_poll *p) {
    if (!p) return 0;
    int stop;
#ifdef _OPENMP
#pragma omp atomic read
#endif
    stop = p->stop;
    return stop;
}

int acd3_poll_stop(acd3_poll *p) {
    if (!p) return 0;
    int stop = acd3_poll_stopped(p);
    if (!stop && thrd_equal(thrd_current(), p->owner) && p->fn(p->user, -1.0, p->stage)) {
        stop = 1;
#ifdef _OPENMP
#pragma omp atomic write
#endif
        p->stop = 1;
    }
    return stop;
}

void acd3_poll_set_stage(acd3_poll *p, const char *stage) {
    if (p && thrd_equal(thrd_current(), p->owner)) p->stage = stage;
}
