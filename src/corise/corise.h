/* corise/corise: the CoRiSe segmentation loop, CoRiSe §3 and §5.2 (Liu, Xi, Lien, CAD 2016);
 * spec corise.md §2.1 and §2.8. Internal driver; a public API can wrap it.
 *
 *   normalise once to the unit bounding sphere (A1: AABB centre, max vertex distance);
 *   queue <- edge-connected components of the facets;
 *   for each part: bridges and valleys of its own hull; if no valley is deeper than tau (or its
 *   hull is flat), the part is final; otherwise ridges, separators, must-link regions and the
 *   sequential cuts split it, and every edge-connected component of every piece goes back into
 *   the queue (A15). A part whose cuts leave fewer than 2 pieces, or that is max_depth cuts deep,
 *   is final and counted as unresolved (A14).
 * Deterministic: FIFO queue, every stage deterministic. */
#ifndef ACD_CORISE_CORISE_H
#define ACD_CORISE_CORISE_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "acd/mesh.h"
#include "acd3/poll.h"
#include "corise/cut.h"

typedef struct acd_corise_params {
    double tau;                 /* concavity tolerance, in normalised units (default 0.1) */
    int normalize;              /* scale to the unit bounding sphere first (default 1) */
    acd_corise_cut_params cut;  /* Eq. 8 (alpha 0.8, concave weight 0.3) */
    size_t max_depth;           /* safety cap on nested cuts (default 64) */
    int clamp_hull_depth;       /* not in the paper: cap valley concavity by the depth below the
                                   hull (acd_corise_bridges_compute_ex; default 0 = literal) */
    int threads;                /* OpenMP threads (parts of a wave, then the bridges of a lone
                                   part); <= 0: all cores; default 1. The output is the same
                                   for any count */
    acd_progress_fn progress;   /* optional: called after each part, at each wave and polled
                                   within the steps (acd_corise_poll_init); fraction = facets in
                                   final parts / all facets; non-zero return cancels */
    void *progress_user;
} acd_corise_params;

acd_corise_params acd_corise_default_params(void);

/* The cancellation poll of the loop and of acd_segment (acd3/poll; docs/corise.md "Progress and
 * cancellation"): one per call, made by the calling thread, passed down explicitly to the long
 * loops (the valley searches, the regions' splits and balls, the cuts' max-flows, the input's
 * preparation, the parts' hulls). Its callback, called by the calling thread only, calls
 * ctx->fn(ctx->user, ctx->fraction, stage): the caller's callback with the fraction of the last
 * milestone (ctx->fraction, written by the calling thread) and the poll's stage. */
typedef struct acd_corise_poll_ctx {
    acd_progress_fn fn;
    void *user;
    double fraction;
} acd_corise_poll_ctx;

/* Makes *p calling fn through ctx, from the calling thread; returns p, or NULL (no poll: every
 * poll a no-op) when fn is NULL. The steps name their stage by acd3_poll_set_stage. */
acd3_poll *acd_corise_poll_init(acd3_poll *p, acd_corise_poll_ctx *ctx, acd_progress_fn fn, void *user, double fraction,
                                const char *stage);

typedef struct acd_corise_stats {
    size_t parts;        /* final parts */
    size_t cuts;         /* parts that were split */
    size_t depth;        /* deepest nesting of cuts */
    size_t unresolved;   /* parts left final although still deeper than tau */
    size_t fallbacks;    /* valleys measured with the Eq. 1 fallback */
    size_t unreachable;  /* bridges without a valley */
    double scale;        /* normalisation factor applied to the coordinates */
} acd_corise_stats;

/* labels: m->ntriangles entries, set to the part of each facet, 0 .. parts-1, numbered by their
 * smallest facet. stats may be NULL. */
acd_status acd_corise_segment(const acd_mesh *m, const acd_corise_params *params, uint32_t *labels,
                              acd_corise_stats *stats, acd_error *err);

/* The same, and *part_conc (when part_conc is not NULL; malloc'd, stats->parts entries, indexed
 * by label, freed by the caller) receives each final part's largest valley concavity as the loop
 * measured it on that part: bit for bit what acd_corise_parts_concavity returns for the labels
 * (the loop's parts are extracted in facet order, capped and measured the same way), without
 * measuring them again. */
acd_status acd_corise_segment_ex(const acd_mesh *m, const acd_corise_params *params, uint32_t *labels,
                                 double **part_conc, acd_corise_stats *stats, acd_error *err);

/* The valley test of the loop, re-run on a labelling: for each part k < nparts (the facets with
 * labels[f] == k, in facet order) the part is extracted, the holes that separate it from the rest
 * of the mesh are capped (as in the loop), and conc[k] receives the largest valley concavity of
 * its bridges in normalised units (0 for a part with a flat hull or no valley), computed with
 * params' normalisation and clamp_hull_depth. The loop's final parts pass this test with
 * conc <= tau unless counted as unresolved. Labels >= nparts are ACD_ERR_INVALID_ARGUMENT. */
acd_status acd_corise_parts_concavity(const acd_mesh *m, const acd_corise_params *params, const uint32_t *labels,
                                      size_t nparts, double *conc, acd_error *err);

#endif
