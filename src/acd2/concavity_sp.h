/* acd2/concavity_sp: SP-concavity (dissertation IV.A.1.b, Alg. 2, Lemmas A.1-A.4; spec acd2d.md
 * §3.2): the length of the shortest path from a pocket vertex to the bridge segment, inside the
 * pocket polygon (the pocket chain closed by its bridge). */
#ifndef ACD_ACD2_CONCAVITY_SP_H
#define ACD_ACD2_CONCAVITY_SP_H

#include <stddef.h>

#include "acd/base.h"
#include "acd/polygon.h"

/* Reusable scratch memory (zero-initialize; free with acd2_sp_work_free). */
typedef struct acd2_sp_work {
    size_t cap;
    acd_vec2 *q;      /* pocket polygon */
    size_t *tri;      /* triangles, 3 per */
    int *adj;         /* neighbour triangle across each triangle edge */
    size_t *prev, *next;
    size_t *par[2];   /* shortest-path tree parents, rooted at the two bridge ends */
    double *dist[2];  /* geodesic distances to the roots */
    double *g[2];     /* distance to the bridge through the tree (spec §3.2 recurrence) */
    size_t *order;    /* scratch */
    size_t *funnel;   /* deque storage */
    int *tstack;
} acd2_sp_work;

void acd2_sp_work_free(acd2_sp_work *w);

/* Bridge p[a] -> p[b] of the ring p[0..n); sets conc[k] for every pocket vertex k strictly
 * between a and b (cyclically). Returns ACD_ERR_NOMEM on allocation failure. */
acd_status acd2_sp_pocket(const acd_vec2 *p, size_t n, size_t a, size_t b, double *conc, acd2_sp_work *w);

#endif
