/* acd3/poll: the progress callback's cancellation poll inside acd3d_decompose's tree (issue 4 item
 * 7: "progress on stderr for runs over a second; cancellable through the API").
 *
 * One poll object per call, made by the calling thread and passed down explicitly (no globals, no
 * thread-locals) to the long loops of a node's work: between candidate cuts (acd3/decompose), per
 * phase and per projected hull edge of the measure (acd3/measure), per knot source of the cut graph
 * (acd3/pocket_cut), per edge of the edge planes (acd3/resolve). The callback is called only by
 * the thread that made the poll (the caller's: the callback need not be thread-safe); any other
 * thread reads the stop flag the calling thread sets once the callback asks to stop. A poll decides
 * nothing about the result: a run that is not cancelled is the same with or without one. */
#ifndef ACD_ACD3_POLL_H
#define ACD_ACD3_POLL_H

#include <threads.h>

#include "acd/base.h"

typedef struct acd3_poll {
    acd_progress_fn fn; /* not NULL */
    void *user;
    thrd_t owner;       /* the thread that calls fn */
    const char *stage;  /* the stage fn is told */
    int stop;           /* set once fn asked to stop; read and written atomically */
} acd3_poll;

/* A poll calling fn(user, -1, stage) from the calling thread. */
acd3_poll acd3_poll_make(acd_progress_fn fn, void *user, const char *stage);

/* Whether to stop: 0 for p NULL; else the stop flag, after calling the callback when the caller
 * is p's owner and the flag is not set yet (the callback's non-zero sets it). */
int acd3_poll_stop(acd3_poll *p);

/* Whether the flag is set (the callback is not called): after a step, whether it was cut short. */
int acd3_poll_stopped(const acd3_poll *p);

/* Sets the stage p tells (a static string), from p's owner only (the only thread that reads it):
 * from another thread, or for p NULL, nothing. With several threads working, it is the stage of the
 * owner's own work. */
void acd3_poll_set_stage(acd3_poll *p, const char *stage);

#endif
