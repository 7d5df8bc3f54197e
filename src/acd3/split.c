/* acd3/split: the choice of a part's cut (acd3/split.h). */
#include "acd3/split.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "acd3/global_cut.h"
#include "acd3/region_cut.h"
#include "acd3/surface_cut.h"
#include "acd3/volume_plane.h"
#include "core/error.h"
#include "geom3/hull_volume.h"
#include "geom3/pca.h"
#include "geom3/volume.h"

void acd3_measured_free(acd3_measured *x) {
    if (x->valid) {
        acd3_measure_free(&x->ms);
        acd_edge_graph_free(&x->g);
    }
    x->valid = 0;
}

acd_status acd3_measure_mesh(const acd_mesh *m, double eps, double tol, acd_hull *hull, acd3_poll *poll,
                             acd3_measured *out, acd_error *err) {
    out->valid = 0;
    acd_status st = acd_edge_graph_from_mesh(m->vertices, m->nvertices, m->triangles, m->ntriangles, &out->g, err);
    if (st == ACD_OK && acd3_poll_stop(poll)) {
        acd_edge_graph_free(&out->g);
        st = acd_fail(err, ACD_ERR_CANCELLED, "cancelled measuring a part of %zu triangles", m->ntriangles);
    }
    if (st != ACD_OK) {
        if (hull) acd_hull_free(hull);
        return st;
    }
    st = acd3_measure_compute_hull(m, &out->g, hull, eps, tol, poll, &out->ms, err);
    if (st != ACD_OK) {
        acd_edge_graph_free(&out->g);
        return st;
    }
    out->valid = 1;
    return ACD_OK;
}


/* How many splitting candidates are compared (each costs a measure of its pieces). */
#define ACD3_COMPARED_CANDIDATES 6
/* With the cut choice by volume (every candidate compared up to this budget): 9 gave higher IoU at
 * 40 parts than 6 on all six target meshes (docs/acd3d.md "Hull tightness"). The cut choice by band
 * has the same budget: with 6 the armadillo at tau 0.02 has 141 parts (251 leaves) instead of 123
 * (202); all 11 candidates, 122 (203). (By concavity, 9 would give 145 (243) instead of 152 (276).) */
#define ACD3_COMPARED_CANDIDATES_VOLUME 9
/* Cut choice by hull volume (ACD3D_CHOICE_VOLUME): how many volume planes join the candidates,
 * and the band of concavity (a fraction of the part's) within which the pieces' hull volume
 * decides (also by band, ACD3D_CHOICE_BAND: on the armadillo at tau 0.02 a band of 0.1 to 1 gave
 * 120-123 parts, 0.03 152, 0.001 156; an absolute band of eps, the measure's slack, 149). */
#define ACD3_VOLUME_PLANES 1
/* The volume plane is searched on an estimate (acd3_volume_planes_scored): at most this many of
 * the part's vertices scored, 5 offsets refined twice. Against the full search (every vertex up to
 * 4000, 9 offsets refined three times), same run: tight CPU armadillo 8.45 -> 5.35 s, bunny00
 * 10.3 -> 7.35 s, knot1 3.13 -> 2.83, npm bunny 2.17 -> 1.92; IoU armadillo 0.9315 -> 0.9304,
 * bunny00 0.9744 -> 0.9712, knot1 0.9674 -> 0.9678, npm bunny 0.9776 -> 0.9790, camel 0.9651 ->
 * 0.9642, fandisk 0.9796 -> 0.9814 (the plane only joins the candidates: each is cut and measured
 * exactly). */
#define ACD3_VOLUME_PLANE_SCORED 400
/* ... on all three principal axes */
#define ACD3_VOLUME_PLANE_AXES 3
#define ACD3_VOLUME_BAND 0.5
/* By volume (not by band): once the best cut makes progress, a candidate whose pieces' hull volume
 * (known from the screen's hulls) is not below the best's is dropped without measuring its pieces,
 * even if it could have been more than the band less concave (which split_better would prefer). On
 * the 11 tight target runs (docs/results/3d-speed.md, 2026-11-25 "fast2") only fandisk changed
 * (IoU 0.9613 -> 0.9631 at tau 0.03, 0.9819 -> 0.9814 at 0.025, concavity_max within 0.02); bunny00
 * and the armadillo kept their output with 3-10% less CPU (their candidates lost after measuring
 * the largest piece: 29 of 252 and 42 of 495). 0: split_better's rule throughout. */
#define ACD3_VOLUME_SCREEN_HULL 1
/* ... and before its pieces' qhull hulls are computed, once the best it is compared with is final,
 * the sum of their hull volume estimates (geom3/hull_volume: the hull of the same points by a
 * Quickhull of floating-point tests, which can only miss a point, i.e. underestimate, apart from
 * rounding) above the best's hull volume by ACD3_VOLUME_SCREEN_REL (relative; acd3/decompose.h,
 * where acd3_decompose_screen takes another margin or none) drops it as the qhull hulls' sum
 * would (split_screen); a candidate within the margin gets its qhull hulls. */


void acd3_split_choice_free(acd3_split_choice *c) {
    if (c->pieces)
        for (size_t k = 0; k < c->cut.npieces; k++) acd3_measured_free(&c->pieces[k]);
    free(c->pieces);
    acd_cut_result_free(&c->cut);
    memset(c, 0, sizeof *c);
}

/* Surface mode's progress rule. A surface cut may leave the most concave vertex (the witness)
 * as deep as before: a plane through a witness already on the part's boundary (an earlier cut
 * through it) re-cuts along that boundary and chips off the teeth of its jagged chain, one or two
 * faces each, while the rest keeps the witness's concavity (cheese, genus 133: ~300 such cuts in a
 * row until the depth guard). A cut makes progress when it opens the part without separating it
 * (a handle: its genus drops, which happens at most genus times), or when every copy of the
 * witness in the pieces is measured shallower than the witness was by more than tol, i.e. the cut
 * separated the witness from (part of) the bridge it lay under. */
static int surface_progress(const acd_mesh *m, const acd3_measure *ms, const acd3_split_choice *trial, double tol) {
    (void)m;
    if (trial->cut.npieces == 1) return 1; /* cut open (acd3_surface_cut: more vertices, one piece) */
    double wc = ms->vconc[ms->witness], worst = -1;
    for (size_t k = 0; k < trial->cut.npieces; k++) {
        const acd_cut_piece *pc = &trial->cut.pieces[k];
        for (size_t v = 0; v < pc->mesh.nvertices; v++)
            if (pc->source[v] == ms->witness && trial->pieces[k].ms.vconc[v] > worst) worst = trial->pieces[k].ms.vconc[v];
    }
    return worst < wc - tol;
}

/* Surface mode's bridge plane: parallel to the patch the witness lies under, halfway between the
 * witness and that patch (the patch whose depth at the witness is its concavity). Cutting there
 * (the section strip nearest the witness) separates the witness from its bridge or opens the
 * handle the witness lies in; 1 if found. */
static int surface_bridge_plane(const acd_mesh *m, const acd3_measure *ms, acd3_plane_candidate *c) {
    const double *x = m->vertices + 3 * (size_t)ms->witness;
    double wc = ms->vconc[ms->witness], bestd = INFINITY;
    size_t bp = SIZE_MAX;
    for (size_t p = 0; p < ms->patches.npatches; p++) {
        double d = fabs(acd3_patch_depth(&ms->patches, p, x) - wc);
        if (d < bestd) bestd = d, bp = p;
    }
    if (bp == SIZE_MAX || !(wc > 0)) return 0;
    const double *q = ms->patches.planes + 4 * bp;
    for (int k = 0; k < 3; k++) {
        c->normal[k] = q[k];
        c->point[k] = x[k] + 0.5 * wc * q[k];
    }
    c->kind = "bridge";
    return 1;
}

/* The candidates of one split are evaluated by a small work queue (split_state): the thread that
 * splits the part claims them in order, and so does any thread that would otherwise wait (a helper
 * task; none when the part's batch keeps every thread busy). Each candidate is cut and its pieces
 * measured independently of the others; the choice is replayed in candidate order (split_replay),
 * so it is the sequential loop's, whoever evaluated what. */

/* Candidate slots of one split: the candidates in the sequential loop's order, and (while the
 * global cut's plane is computed) the planes that do not depend on it, evaluated ahead. */
#define ACD3_SPLIT_SLOTS (2 * (ACD3_MAX_CANDIDATES + 1 + ACD3_VOLUME_PLANES) + 1)

/* One candidate's evaluation. */
typedef struct cand_eval {
    int done;      /* evaluated, or abandoned (the replay no longer needs it) */
    acd_status st; /* a failure the sequential loop would report (out of memory), with err */
    acd_error err;
    size_t failed_at; /* the piece (in measuring order) whose measure failed; SIZE_MAX: none */
    int ok;           /* the cut gives acceptable pieces */
    size_t order[2], *ord; /* pieces largest first */
    size_t nmeasured;      /* pieces measured, in that order */
    acd3_split_choice trial;
    /* solid mode: the pieces' hulls, computed before any piece is measured (each taken over by its
     * measure), and what they tell before the measures (split_screen) */
    acd_hull *hulls;
    size_t nhulls;
    double cbound;   /* a lower bound on the trial's concavity (0: none) */
    int have_hullvol; /* by volume: hullvol is the sum of the pieces' hull volumes (as the replay sums them) */
    double hullvol;
    /* the hull volume screen still to be decided (screen_decide): the sum of the pieces' hull volume
     * estimates, of all their points with est_full, else of a subset; -1: none, or decided */
    double est;
    int est_full;
    int screened; /* dropped by the screen (screen_decide): its replay drops it */
} cand_eval;

typedef struct split_state {
    acd3_poll *poll; /* NULL: no progress callback */
    const acd_mesh *m;
    const acd_edge_graph *g;
    const acd3_measure *ms;
    double extent, eps, tau, tol, min_piece_volume;
    int solid, restrict_cut;
    int by_volume; /* ACD3D_CHOICE_VOLUME or ACD3D_CHOICE_BAND (solid mode): the band rule */
    int early;     /* ACD3D_CHOICE_BAND: a cut meeting tau or halving the concavity is still taken at once */
    double band;   /* its band of concavity */
    unsigned cut_flags; /* acd_plane_cut_flags */
    const acd_edge_map *em; /* solid mode: the part's edge map, checked closed (NULL: each cut builds it) */
    uint8_t *onhull; /* by volume: 1 for m's vertices on its hull (ms->hull.source), for the hull volume screen (pieces_hull_estimate); NULL: none */
    double screen_rel; /* the screen's margin (ACD3_VOLUME_SCREEN_REL; with onhull NULL, no screen) */
    acd3_decompose_stats stats; /* counted atomically (any thread evaluating a candidate) */
    /* The candidates are slots (cand[id], ev[id]); ord[i] is the slot of the i-th candidate in the
     * sequential loop's order (pos[id]: its index there, -1 when not a candidate), set once
     * `ordered` (acd3_try_split may start evaluating slots while it still computes the global cut's
     * plane: an evaluation depends only on its plane, the order only decides which are used) */
    const acd3_plane_candidate *cand;
    int nc, nbridge;
    cand_eval *ev;
    int ord[ACD3_SPLIT_SLOTS], pos[ACD3_SPLIT_SLOTS];
    /* shared, read and written only under the critical section "acd3_split" */
    int ordered;      /* ord, pos, nc and nbridge are set */
    int pre_next, pre_end; /* before that: the next slot to claim, and the end of those slots */
    uint8_t claimed[ACD3_SPLIT_SLOTS];
    int next;    /* the next candidate to claim */
    int cursor;  /* the next candidate to replay */
    int stopped; /* the replay is over (a failure, an accepted cut, or no candidate left) */
    int found, compared, best_progress;
    acd3_split_choice best;
    int fail; /* a status (the first failure in candidate order) */
    acd_error err;
} split_state;

static void cand_eval_free(cand_eval *e) {
    if (e->ord && e->ord != e->order) free(e->ord);
    e->ord = NULL;
    if (e->hulls)
        for (size_t k = 0; k < e->nhulls; k++) acd_hull_free(&e->hulls[k]);
    free(e->hulls);
    e->hulls = NULL;
    acd3_split_choice_free(&e->trial);
}

/* Whether the sequential loop skips candidate i (the compared budget is spent; the bridge plane is
 * still tried unless a cut that makes progress was found). */
static int split_skips(const split_state *S, int i) {
    return S->compared >= (S->by_volume ? ACD3_COMPARED_CANDIDATES_VOLUME : ACD3_COMPARED_CANDIDATES) && (i < S->nbridge || S->best_progress);
}

/* Whether a trial of concavity c (so far) has lost against the best choice of the candidates before
 * it (a cut that makes progress beats one that does not: in surface mode only against a best that
 * makes progress is a higher concavity a loss). r: how many candidates before it are not replayed
 * yet. Each of them may replace the best by one at most tol (by volume: the band) more concave
 * (split_better), so c above the best by (r + 1) margins has lost against any best they leave; one
 * margin more covers the rounding of those sums. */
static int split_lost(const split_state *S, double c, int r) {
    double margin = S->by_volume ? S->band : S->tol;
    return S->found && S->best_progress && c > S->best.concavity + (r ? r + 2 : 1) * margin;
}

/* split_lost for the trial of e, its pieces measured so far of concavity conc (their largest; 0:
 * none), c = conc or more by e's lower bound; by volume, also: once a best that makes progress is
 * found (the best makes progress from then on), a trial of conc not below the part's by tol makes
 * none and cannot be better (split_better), whatever its other pieces measure; and with the
 * candidates before e's all replayed (r = 0: the best is the one e is compared with) and e's hull
 * volume known: whether a trial of concavity c cannot be better, or is not to be measured. Its hull
 * volume is not smaller than the best's: by band it would need a concavity below the band; by
 * volume (ACD3D_CHOICE_VOLUME) it is lost unmeasured (ACD3_VOLUME_SCREEN_HULL); else it needs a
 * concavity within the band. */
static int split_lost_at(const split_state *S, const cand_eval *e, double conc, int r) {
    double c = fmax(conc, e->cbound);
    if (split_lost(S, c, r)) return 1;
    if (S->by_volume && S->found && S->best_progress && !(conc < S->ms->concavity - S->tol)) return 1;
    if (r || !S->by_volume || !e->have_hullvol || !S->found || !S->best_progress) return 0;
    if (e->hullvol >= S->best.hullvol && ACD3_VOLUME_SCREEN_HULL && !S->early) return 1;
    return e->hullvol >= S->best.hullvol ? c >= S->best.concavity - S->band : c > S->best.concavity + S->band;
}

/* Whether trial (its progress given) is better than the best so far: the smallest largest piece
 * concavity (up to tol), then the fewest pieces, then the candidates' order. By volume: a
 * concavity lower by more than the band, else (within the band) the smaller sum of the pieces'
 * hull volumes, then the candidates' order. */
static int split_better(const split_state *S, const acd3_split_choice *trial, int progress) {
    const acd3_split_choice *best = &S->best;
    if (S->by_volume)
        return !S->found || (progress && !S->best_progress) ||
               (progress == S->best_progress &&
                (trial->concavity < best->concavity - S->band ||
                 (trial->concavity <= best->concavity + S->band && trial->hullvol < best->hullvol)));
    /* against an edge plane, less concave only by more than the input's rounding (acd3/resolve) */
    double tie = best->plane.kind && !strcmp(best->plane.kind, "edges") ? fmax(S->tol, best->plane.rounding) : S->tol;
    return !S->found || (progress && !S->best_progress) ||
           (progress == S->best_progress &&
            (trial->concavity < best->concavity - tie ||
             (trial->concavity <= best->concavity + S->tol && trial->cut.npieces < best->cut.npieces)));
}

/* Whether c is the cut of an edge plane (acd3/resolve, kind "edges") into three or more pieces:
 * the plane passes through material away from the reflex edges it resolves, and is compared with
 * the other candidates instead of being taken at once (P.off at tau 0.05: one of its edge planes
 * cut a part into three, where a plane after it gave two as deep; docs/acd3d.md "Planes through
 * reflex edges"). */
static int split_edges_elsewhere(const acd3_split_choice *c) {
    return c->plane.kind && !strcmp(c->plane.kind, "edges") && c->cut.npieces > 2;
}

/* Under "acd3_split": replays the evaluated candidates from the cursor in order, as the
 * sequential loop would have taken them, until one is not evaluated yet or the loop is over. */
static void split_replay(split_state *S) {
    while (!S->stopped && S->cursor < S->nc) {
        int i = S->cursor;
        if (split_skips(S, i)) {
            S->cursor++;
            continue;
        }
        cand_eval *e = &S->ev[S->ord[i]];
        if (!e->done) return;
        S->cursor++;
        if (e->st != ACD_OK && e->failed_at == SIZE_MAX) { /* the cut itself failed */
            S->fail = (int)e->st;
            S->err = e->err;
            S->stopped = 1;
            return;
        }
        if (!e->ok) continue;
        S->compared++;
        /* the pieces in measuring order, until one is above the best (the sequential loop stops
         * measuring there: a failure past that point is not its failure) */
        acd3_split_choice *t = &e->trial;
        double conc = 0;
        int lost = e->screened || split_lost_at(S, e, 0, 0);
        for (size_t i2 = 0; i2 < t->cut.npieces && !lost; i2++) {
            if (i2 == e->failed_at) {
                S->fail = (int)e->st;
                S->err = e->err;
                S->stopped = 1;
                return;
            }
            if (i2 >= e->nmeasured) { /* cannot happen: an evaluation stops only where the replay does */
                S->fail = (int)ACD_ERR_INTERNAL;
                acd_fail(&S->err, ACD_ERR_INTERNAL, "3d: candidate %d evaluated partially", i);
                S->stopped = 1;
                return;
            }
            double c = t->pieces[e->ord[i2]].ms.concavity;
            if (c > conc) conc = c;
            lost = split_lost_at(S, e, conc, 0);
        }
        if (lost) {
            cand_eval_free(e);
            continue;
        }
        t->concavity = conc;
        t->hullvol = 0;
        for (size_t k = 0; k < t->cut.npieces; k++) t->hullvol += t->pieces[k].ms.hull.volume;
        /* by volume, a solid cut makes progress when it lowers the concavity (the band could
         * otherwise prefer a cut that leaves the witness as deep) */
        int progress = S->by_volume ? conc < S->ms->concavity - S->tol
                                    : S->solid || surface_progress(S->m, S->ms, t, S->tol);
        if (split_better(S, t, progress)) {
            if (S->found) acd3_split_choice_free(&S->best);
            S->best = *t;
            memset(t, 0, sizeof *t);
            S->found = 1;
            S->best_progress = progress;
        }
        cand_eval_free(e);
        /* (by volume, every candidate is compared, up to the budget; by band, as by concavity) */
        if ((!S->by_volume || S->early) && S->best_progress &&
            (S->best.concavity <= S->tau + S->tol || S->best.concavity <= 0.5 * S->ms->concavity) &&
            !split_edges_elsewhere(&S->best))
            S->stopped = 1;
    }
    if (S->cursor >= S->nc) S->stopped = 1;
}

/* Whether the replay no longer needs the candidate of slot id (*lost: a trial whose pieces measured so
 * far have concavity conc has lost against any best the replay can reach at its index i
 * (split_lost_at), so its other pieces need no measure; the replay finds the same when it reaches
 * i). Before the order is known, every slot is needed. */
static int split_abandoned(split_state *S, int id, double conc, int *lost) {
    int gone = 0;
    *lost = 0;
#ifdef _OPENMP
#pragma omp critical(acd3_split)
#endif
    if (S->ordered) {
        int i = S->pos[id];
        gone = i < 0 || S->stopped || S->cursor > i || (S->cursor == i && split_skips(S, i));
        *lost = !gone && split_lost_at(S, &S->ev[id], conc, i - S->cursor);
    }
    return gone;
}

/* How many of a piece's vertices, the deepest in the part, bound its concavity from below. */
#define ACD3_SCREEN_VERTICES 24

/* A lower bound on the concavity of piece pc (of part S->m) whose hull is h: a vertex's concavity is
 * its depth below a plane tangent to the hull, at least its distance to the hull's boundary (the
 * ball of that radius lies in the hull, so on the plane's inner side). Taken over the piece's
 * vertices deepest in the part (no deeper in the piece: its hull lies in the part's), less S->tol for
 * rounding; 0 when none. */
static double piece_concavity_bound(const split_state *S, const acd_cut_piece *pc, const acd_hull *h) {
    if (h->dim != 3 || !pc->source) return 0;
    uint32_t top[ACD3_SCREEN_VERTICES];
    double key[ACD3_SCREEN_VERTICES];
    size_t n = 0;
    for (size_t v = 0; v < pc->mesh.nvertices; v++) {
        uint32_t src = pc->source[v];
        if (src == ACD_CUT_NEW_VERTEX || src >= S->m->nvertices) continue;
        double d = S->ms->vconc[src];
        if (!(d > S->tol) || (n == ACD3_SCREEN_VERTICES && d <= key[n - 1])) continue;
        size_t j = n < ACD3_SCREEN_VERTICES ? n++ : n - 1;
        while (j > 0 && key[j - 1] < d) {
            key[j] = key[j - 1], top[j] = top[j - 1];
            j--;
        }
        key[j] = d, top[j] = (uint32_t)v;
    }
    double lb = 0;
    for (size_t j = 0; j < n && key[j] - S->tol > lb; j++) {
        double d = -acd_hull_plane_distance(h, pc->mesh.vertices + 3 * (size_t)top[j]) - S->tol;
        if (d > lb) lb = d;
    }
    return lb;
}

/* Where the replay stands for the candidate of slot id, for the hull volume screen (split_screen):
 * SCREEN_GONE, the replay no longer needs it (split_abandoned's gone: its hulls would not be used);
 * SCREEN_READY, the candidates before it are all replayed and the best makes progress: the best is
 * the one its replay compares it with (nothing but those replays changes the best), *best its hull
 * volume; SCREEN_NONE, replayed up to it but no such best (it cannot be dropped on its hull volume);
 * SCREEN_LATER, candidates before it are still to be replayed (or the order is not known yet). */
enum { SCREEN_GONE, SCREEN_READY, SCREEN_NONE, SCREEN_LATER };

static int screen_state(split_state *S, int id, double *best) {
    int r = SCREEN_LATER;
#ifdef _OPENMP
#pragma omp critical(acd3_split)
#endif
    if (S->ordered) {
        int i = S->pos[id];
        if (i < 0 || S->stopped || S->cursor > i || (S->cursor == i && split_skips(S, i))) r = SCREEN_GONE;
        else if (S->cursor < i) r = SCREEN_LATER;
        else r = S->found && S->best_progress ? SCREEN_READY : SCREEN_NONE;
        *best = S->best.hullvol;
    }
    return r;
}

/* The sum of the hull volume estimates (acd_hull_volume_fast) of e's pieces; with sub, of their
 * points on the part's hull (S->onhull) or new on the cutting plane only. -1 when out of memory. */
static double pieces_hull_estimate(const split_state *S, const cand_eval *e, int sub, acd_hull_volume_ws *w) {
    const acd3_split_choice *trial = &e->trial;
    double *buf = NULL;
    if (sub) {
        size_t nmax = 1;
        for (size_t k = 0; k < trial->cut.npieces; k++)
            if (trial->cut.pieces[k].mesh.nvertices > nmax) nmax = trial->cut.pieces[k].mesh.nvertices;
        buf = malloc(3 * nmax * sizeof *buf);
        if (!buf) return -1;
    }
    double sum = 0;
    for (size_t k = 0; k < trial->cut.npieces; k++) {
        const acd_cut_piece *pc = &trial->cut.pieces[e->ord[k]];
        const double *pts = pc->mesh.vertices;
        size_t n = pc->mesh.nvertices;
        if (sub) {
            n = 0;
            for (size_t v = 0; v < pc->mesh.nvertices; v++) {
                uint32_t src = pc->source ? pc->source[v] : ACD_CUT_NEW_VERTEX;
                if (src == ACD_CUT_NEW_VERTEX || (src < S->m->nvertices && S->onhull[src]))
                    memcpy(buf + 3 * n++, pc->mesh.vertices + 3 * (size_t)v, sizeof(double[3]));
            }
            pts = buf;
        }
        double vk = acd_hull_volume_fast(pts, n, w, NULL);
        if (vk < 0) {
            sum = -1;
            break;
        }
        sum += vk;
    }
    free(buf);
    return sum;
}

/* By volume (ACD3_VOLUME_SCREEN_HULL, not by band; the part's hull vertices known): whether its
 * candidates may be dropped on estimates of their hull volumes before their qhull hulls
 * (screen_decide). */
static int screen_on(const split_state *S) {
    return ACD3_VOLUME_SCREEN_HULL && !S->early && S->by_volume && S->onhull;
}

/* The hull volume screen on estimates, for the candidate of slot id whose e->est is set: returns 1
 * when the candidate is dropped (or the replay no longer needs it: SCREEN_GONE), else 0, e->est
 * kept when the test cannot be made yet (SCREEN_LATER), -1 when it was made.
 * The candidate's replay's first test, split_lost_at(e, 0, 0), returns 1 for any trial whose hull
 * volume is not below the best's once the best makes progress (that test comes last; the others can
 * only return 1 too), whatever the trial's concavity bound. The pieces' estimated hull volumes
 * (geom3/hull_volume: hulls of subsets of the pieces' points, by floating-point tests that can miss
 * a point but not add volume, so not above the qhull hulls' volumes up to rounding) above the best's
 * by ACD3_VOLUME_SCREEN_REL: their qhull hulls' sum is not below it either, and the candidate is
 * dropped as it would be after its hulls; e->hullvol is then the estimate (the replay's test gives
 * the same). The estimate of a subset first (split_evaluate), then, once the best is known, of all
 * the points. */
static int screen_decide(split_state *S, int id, cand_eval *e) {
    double best = 0;
    int state = screen_state(S, id, &best);
    if (state == SCREEN_GONE) return 1;
    if (state == SCREEN_LATER) return 0;
    if (state == SCREEN_READY) {
        const double above = best * (1 + S->screen_rel);
        if (!(e->est > above) && !e->est_full) {
            acd_hull_volume_ws w;
            memset(&w, 0, sizeof w);
            e->est = pieces_hull_estimate(S, e, 0, &w);
            e->est_full = 1;
            acd_hull_volume_ws_free(&w);
        }
        if (e->est >= 0 && e->est > above) {
            e->hullvol = e->est;
            e->have_hullvol = 1;
            e->screened = 1; /* (with a margin >= 0 split_lost_at drops it too) */
#ifdef _OPENMP
#pragma omp atomic
#endif
            S->stats.screened++;
            return 1;
        }
    }
    e->est = -1;
    return 0;
}

/* Solid mode: the pieces' hulls (kept for their measures), their volumes' sum (by volume) and the
 * lower bound on the trial's concavity. A hull that cannot be computed is left to the measure (which
 * reports the failure when it is reached). A candidate whose screen is still to be decided
 * (e->est >= 0: evaluated ahead of the replay, SCREEN_LATER) is tested again before each piece's
 * hull: the replay may have caught up (returns 1 when it is dropped so, else 0). */
static int split_screen(split_state *S, int id, cand_eval *e) {
    acd3_split_choice *trial = &e->trial;
    size_t np = trial->cut.npieces;
    e->hulls = calloc(np, sizeof *e->hulls);
    if (!e->hulls) return 0;
    e->nhulls = np;
    int all = 1;
    double vol = 0, cb = 0;
    for (size_t k = 0; k < np; k++) {
        if (e->est >= 0 && screen_decide(S, id, e)) return 1;
        const acd_mesh *pm = &trial->cut.pieces[k].mesh;
        if (acd_hull_compute(pm->vertices, pm->nvertices, &e->hulls[k], NULL) != ACD_OK) {
            acd_hull_free(&e->hulls[k]);
            all = 0;
            continue;
        }
        vol += e->hulls[k].volume;
        double b = piece_concavity_bound(S, &trial->cut.pieces[k], &e->hulls[k]);
        if (b > cb) cb = b;
    }
    e->cbound = cb;
    e->have_hullvol = S->by_volume && all;
    e->hullvol = vol;
#ifdef _OPENMP
#pragma omp atomic
#endif
    S->stats.hulled++;
    return 0;
}

int acd3_part_edge_map(const acd_mesh *m, acd_edge_map *em) {
    return acd_edge_map_closed(m->triangles, m->ntriangles, em, NULL) == ACD_OK;
}

/* Cuts the part by the candidate of slot i and measures the pieces (largest first, stopping when the
 * trial has lost, or when the replay no longer needs it). By volume, the hull volume screen on
 * estimates first (screen_decide): at once when the candidates before it are all replayed; for a
 * candidate evaluated ahead of the replay (SCREEN_LATER) the first estimate is made and the test is
 * made again before each of its pieces' qhull hulls (split_screen): the replay may catch up. */
static void split_evaluate(split_state *S, int i) {
    cand_eval *e = &S->ev[i];
    e->failed_at = SIZE_MAX;
    e->ord = e->order;
    acd_cut_plane pl;
    const acd3_plane_candidate *cd = &S->cand[i];
    /* an edge plane (acd3/resolve) goes exactly through the three points it was spanned by */
    int spanned = cd->kind && !strcmp(cd->kind, "edges");
    if ((spanned ? acd_cut_plane_from_points(cd->span[0], cd->span[1], cd->span[2], &pl, NULL)
                 : acd_cut_plane_from_normal(cd->point, cd->normal, S->extent, &pl, NULL)) != ACD_OK)
        return;
    acd3_split_choice *trial = &e->trial;
    acd_error cerr;
    acd_status cst = S->solid ? acd_plane_cut_map(S->m, S->em, &pl, S->cut_flags, &trial->cut, &cerr)
                              : acd3_surface_cut(S->m, S->g, &pl, S->restrict_cut ? cd->point : NULL, &trial->cut, &cerr);
    if (cst != ACD_OK) {
        if (cerr.status == ACD_ERR_NOMEM) {
            e->st = ACD_ERR_NOMEM;
            e->err = cerr;
        }
        return;
    }
    if (S->solid && S->restrict_cut && acd3_restrict_cut(&trial->cut, cd->point, &e->err) != ACD_OK) {
        e->st = ACD_ERR_NOMEM;
        return;
    }
    if (acd3_poll_stop(S->poll)) return; /* cancelled: the batch is dropped (the cut is freed with it) */
    /* two or more pieces; in surface mode also one piece cut open along a loop that does not
     * separate it (around a handle: its genus drops) */
    int ok = trial->cut.npieces >= 2 ||
             (!S->solid && trial->cut.npieces == 1 && trial->cut.pieces[0].mesh.nvertices > S->m->nvertices);
    for (size_t k = 0; ok && S->solid && k < trial->cut.npieces; k++) {
        const acd_mesh *pm = &trial->cut.pieces[k].mesh;
        if (acd_geom3_signed_volume(pm) < S->min_piece_volume) ok = 0;
        /* every piece must be a closed, consistently oriented surface; a cut that rounding left
         * otherwise is not used */
        if (ok && trial->cut.pieces[k].closed && !S->restrict_cut) continue; /* checked by the cut */
        if (ok && !acd3_part_edge_map(pm, NULL)) ok = 0;
    }
    if (!ok) {
        acd3_split_choice_free(trial);
        return;
    }
    trial->plane = *cd;
    trial->pieces = calloc(trial->cut.npieces, sizeof *trial->pieces);
    if (trial->cut.npieces > 2) e->ord = malloc(trial->cut.npieces * sizeof *e->ord);
    if (!trial->pieces || !e->ord) {
        e->st = acd_fail(&e->err, ACD_ERR_NOMEM, "out of memory");
        e->failed_at = 0; /* reported as the sequential loop would: once the candidate is compared */
        e->ok = 1;
        return;
    }
    for (size_t k = 0; k < trial->cut.npieces; k++) {
        size_t j = k, nv = trial->cut.pieces[k].mesh.nvertices;
        while (j > 0 && trial->cut.pieces[e->ord[j - 1]].mesh.nvertices < nv) {
            e->ord[j] = e->ord[j - 1];
            j--;
        }
        e->ord[j] = k;
    }
    e->ok = 1;
    e->est = -1;
    if (screen_on(S)) { /* (by volume: solid mode only) */
        double best;
        int state = screen_state(S, i, &best);
        if (state == SCREEN_GONE) return;
        if (state != SCREEN_NONE) {
            acd_hull_volume_ws w;
            memset(&w, 0, sizeof w);
            e->est = pieces_hull_estimate(S, e, 1, &w);
            acd_hull_volume_ws_free(&w);
        }
    }
    if (S->by_volume && ((e->est >= 0 && screen_decide(S, i, e)) || split_screen(S, i, e))) return;
    double conc = 0;
    for (size_t i2 = 0; i2 < trial->cut.npieces; i2++) {
        int lost = 0;
        if (split_abandoned(S, i, conc, &lost) || lost) return;
        size_t k = e->ord[i2];
        acd_hull *hk = e->hulls && e->hulls[k].dim >= 0 ? &e->hulls[k] : NULL;
        acd_status st = acd3_measure_mesh(&trial->cut.pieces[k].mesh, S->eps, S->tol, hk, S->poll, &trial->pieces[k], &e->err);
        if (st != ACD_OK) {
            e->st = st;
            e->failed_at = i2;
            return;
        }
        e->nmeasured = i2 + 1;
        if (trial->pieces[k].ms.concavity > conc) conc = trial->pieces[k].ms.concavity;
    }
}

/* Claims candidates in order (before the order is known: the slots evaluated ahead) and evaluates
 * them until the replay is over. */
static void split_work(split_state *S) {
    for (;;) {
        if (acd3_poll_stop(S->poll)) return;
        int id = -1;
#ifdef _OPENMP
#pragma omp critical(acd3_split)
#endif
        {
            if (S->ordered) {
                /* skipped already, or claimed ahead */
                while (!S->stopped && S->next < S->nc && (S->next < S->cursor || S->claimed[S->ord[S->next]])) S->next++;
                if (!S->stopped && S->next < S->nc) id = S->ord[S->next++];
            } else if (S->pre_next < S->pre_end) {
                id = S->pre_next++;
            }
            if (id >= 0) S->claimed[id] = 1;
        }
        if (id < 0) return;
        int lost;
        if (!split_abandoned(S, id, 0, &lost)) split_evaluate(S, id);
#ifdef _OPENMP
#pragma omp critical(acd3_split)
#endif
        {
            S->ev[id].done = 1;
            if (S->ordered) split_replay(S);
        }
    }
}

static int same_candidate(const acd3_plane_candidate *a, const acd3_plane_candidate *b) {
    return a->kind == b->kind && !memcmp(a->point, b->point, sizeof a->point) && !memcmp(a->normal, b->normal, sizeof a->normal);
}

/* Surface mode's cut along the global cut's cycle (acd3/global_cut with the dynamic geodesic
 * cuts, spec §5.1: "split the surface at the edges of kappa"; docs/acd3d.md "Splitting a
 * surface"). Fills cand with the candidate planes as acd3_cut_candidates does (the global cut's
 * plane first) and returns their count, or -(status) on failure. When the cycle separates the
 * part and makes progress (surface_progress), *cyc is that cut with its pieces measured and
 * *have = 1; it then competes with the planes as the first compared candidate. */
static int surface_cycle_cut(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms,
                             const acd3_resolve_opts *ro, double eps, double tol, acd3_poll *poll,
                             acd3_plane_candidate *cand, acd3_split_choice *cyc, int *have, acd_error *err) {
    *have = 0;
    if (ms->witness == UINT32_MAX) return 0;
    acd3_global_cut gc;
    int hp = 0, nc = 0;
    acd_status st = acd3_global_cut_at_witness(m, g, ms, &ro->gc, poll, &gc, cand[0].point, cand[0].normal, &hp, err);
    if (st != ACD_OK) return -(int)st;
    if (hp) cand[0].kind = gc.cup ? "cup" : gc.closed && !gc.dynamic ? "global" : "pocket", nc = 1;
    acd3_resolve_opts r2 = *ro;
    r2.global = 0;
    nc += acd3_cut_candidates(m, g, ms, &r2, poll, cand + nc);
    if (!gc.closed || gc.n < 4) {
        acd3_global_cut_free(&gc);
        return nc;
    }
    acd3_split_choice trial;
    memset(&trial, 0, sizeof trial);
    st = acd3_surface_cut_chain(m, g, gc.v, gc.n, &trial.cut, err);
    acd3_global_cut_free(&gc);
    int ok = st == ACD_OK && trial.cut.npieces >= 2;
    if (ok) {
        trial.pieces = calloc(trial.cut.npieces, sizeof *trial.pieces);
        if (!trial.pieces) st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
        for (size_t k = 0; st == ACD_OK && k < trial.cut.npieces; k++) {
            st = acd3_measure_mesh(&trial.cut.pieces[k].mesh, eps, tol, NULL, poll, &trial.pieces[k], err);
            if (st == ACD_OK && trial.pieces[k].ms.concavity > trial.concavity) trial.concavity = trial.pieces[k].ms.concavity;
        }
        for (size_t k = 0; st == ACD_OK && k < trial.cut.npieces; k++) trial.hullvol += trial.pieces[k].ms.hull.volume;
        ok = st == ACD_OK && surface_progress(m, ms, &trial, tol);
    }
    if (st != ACD_OK) {
        acd3_split_choice_free(&trial);
        return -(int)st;
    }
    if (!ok) {
        acd3_split_choice_free(&trial);
        return nc;
    }
    if (hp) {
        trial.plane = cand[0]; /* recorded only */
    } else {
        memcpy(trial.plane.point, m->vertices + 3 * (size_t)ms->witness, sizeof(double[3]));
        trial.plane.normal[0] = trial.plane.normal[1] = 0, trial.plane.normal[2] = 1;
    }
    trial.plane.kind = "cycle";
    *cyc = trial;
    *have = 1;
    return nc;
}

/* The volume planes that join m's candidates (ACD3D_CHOICE_VOLUME) into vp; returns how many. */
static int split_volume_planes(const acd_mesh *m, acd3_plane_candidate vp[ACD3_VOLUME_PLANES]) {
    return acd3_volume_planes_scored(m, ACD3_VOLUME_PLANES, ACD3_VOLUME_PLANE_SCORED, ACD3_VOLUME_PLANE_AXES, vp, NULL,
                                     NULL);
}

int acd3_halving_planes(const acd_mesh *m, acd3_plane_candidate out[ACD3_HALVING_PLANES]) {
    acd_pca pca;
    if (!m->nvertices || acd_pca_points(m->vertices, m->nvertices, NULL, &pca, NULL) != ACD_OK) return 0;
    /* the signed tetrahedra from the vertices' centroid o (near the part: little cancellation) */
    const double *o = pca.centroid;
    double v6 = 0, c[3] = {0, 0, 0};
    for (size_t t = 0; t < m->ntriangles; t++) {
        const double *a = m->vertices + 3 * (size_t)m->triangles[3 * t];
        const double *b = m->vertices + 3 * (size_t)m->triangles[3 * t + 1];
        const double *d = m->vertices + 3 * (size_t)m->triangles[3 * t + 2];
        const double p[3] = {a[0] - o[0], a[1] - o[1], a[2] - o[2]}, q[3] = {b[0] - o[0], b[1] - o[1], b[2] - o[2]},
                     r[3] = {d[0] - o[0], d[1] - o[1], d[2] - o[2]};
        const double w = p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) +
                         p[2] * (q[0] * r[1] - q[1] * r[0]);
        v6 += w;
        for (int k = 0; k < 3; k++) c[k] += w * (p[k] + q[k] + r[k]);
    }
    if (!(v6 > 0) || !isfinite(v6)) return 0;
    for (int a = 0; a < ACD3_HALVING_PLANES; a++) {
        for (int k = 0; k < 3; k++) out[a].point[k] = o[k] + c[k] / (4 * v6);
        memcpy(out[a].normal, pca.axes[a], sizeof(double[3]));
        out[a].kind = "halving";
    }
    return ACD3_HALVING_PLANES;
}

/* (acd3/split.h) */
int acd3_try_split(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms, double extent, double eps,
                   double tau, double tol, int solid, int restrict_cut, double min_piece_volume,
                   unsigned cut_flags, const acd3_resolve_opts *ro, acd3d_cut_choice choice, int helpers,
                   const acd_edge_map *em, double screen_rel, acd3_poll *poll,
                   const acd3_plane_candidate *fixed, int nfixed, acd3_decompose_stats *stats, acd3_split_choice *best,
                   acd_error *err) {
    /* slots: [0, npre) the planes evaluated ahead (if any), then the candidates in order */
    acd3_plane_candidate slot[ACD3_SPLIT_SLOTS];
    cand_eval ev[ACD3_SPLIT_SLOTS];
    memset(ev, 0, sizeof ev);
    split_state S;
    memset(&S, 0, sizeof S);
    int by_volume = solid && (choice == ACD3D_CHOICE_VOLUME || choice == ACD3D_CHOICE_BAND);
    int vplanes = by_volume && choice == ACD3D_CHOICE_VOLUME; /* the volume planes join the candidates */
    S.m = m, S.g = g, S.ms = ms, S.extent = extent, S.eps = eps, S.tau = tau, S.tol = tol;
    S.min_piece_volume = min_piece_volume, S.solid = solid, S.restrict_cut = restrict_cut;
    S.by_volume = by_volume, S.early = choice == ACD3D_CHOICE_BAND, S.band = ACD3_VOLUME_BAND * ms->concavity;
    S.cut_flags = cut_flags;
    S.em = solid ? em : NULL;
    S.cand = slot, S.ev = ev;
    S.screen_rel = screen_rel;
    S.poll = poll;
    if (by_volume && ACD3_VOLUME_SCREEN_HULL && !S.early && screen_rel > -1 && ms->hull.dim == 3 && ms->hull.source) {
        S.onhull = calloc(m->nvertices ? m->nvertices : 1, 1);
        for (size_t v = 0; S.onhull && v < ms->hull.nvertices; v++)
            if (ms->hull.source[v] < m->nvertices) S.onhull[ms->hull.source[v]] = 1;
    }
    /* solid mode with the global cut and a thread to spare: the candidates that do not depend on the
     * global cut's plane (the volume planes, the witness planes acd3_cut_candidates lists after
     * it) are evaluated by the helpers while this thread computes that plane (the part's serial
     * step, the root's above all) */
    int npre = 0, nvp = 0;
    acd3_plane_candidate vp[ACD3_VOLUME_PLANES];
    int ahead = !fixed && solid && ro && ro->global && helpers > 0 && ms->witness != UINT32_MAX;
    if (ahead) {
        acd3_resolve_opts r2 = *ro;
        r2.global = r2.notch = 0;
        npre = acd3_cut_candidates(m, g, ms, &r2, poll, slot);
        S.pre_end = npre;
#ifdef _OPENMP
        int nh = helpers < npre ? helpers : npre;
        for (int h = 0; h < nh; h++) {
#pragma omp task default(shared)
            split_work(&S);
        }
#endif
        /* the volume planes too, while the helpers start on those */
        if (vplanes) nvp = split_volume_planes(m, vp);
        if (nvp > 0) {
#ifdef _OPENMP
#pragma omp critical(acd3_split)
#endif
            {
                memcpy(slot + npre, vp, (size_t)nvp * sizeof *slot);
                npre += nvp;
                S.pre_end = npre;
            }
        }
    }
    acd3_plane_candidate *cand = slot + npre;
    /* surface mode with acd3d_params.surface_cut: the global cut's cycle first */
    acd3_split_choice cyc;
    memset(&cyc, 0, sizeof cyc);
    int nc, have_cyc = 0;
    if (!solid && ro && ro->global && ro->gc.dynamic) {
        nc = surface_cycle_cut(m, g, ms, ro, eps, tol, poll, cand, &cyc, &have_cyc, err);
        if (nc < 0) return nc;
        if (have_cyc && (cyc.concavity <= tau + tol || cyc.concavity <= 0.5 * ms->concavity)) {
            *best = cyc;
            return 1;
        }
    } else if (fixed) {
        nc = nfixed;
        memcpy(cand, fixed, (size_t)nfixed * sizeof *cand);
    } else {
        nc = acd3_cut_candidates(m, g, ms, ro, poll, cand);
    }
    if (vplanes && nc > 0 && !fixed) { /* the volume planes after the first candidate */
        if (!ahead) nvp = split_volume_planes(m, vp);
        memmove(cand + 1 + nvp, cand + 1, (size_t)(nc - 1) * sizeof *cand);
        memcpy(cand + 1, vp, (size_t)nvp * sizeof *cand);
        nc += nvp;
    }
    /* surface mode: the bridge plane last (tried when no candidate before it makes progress) */
    int nbridge = nc;
    if (!solid && nc > 0 && surface_bridge_plane(m, ms, &cand[nc])) nc++;
    memset(best, 0, sizeof *best);
    /* the order: each candidate in a slot evaluated ahead for the same plane (the first one not
     * matched yet), else in its own */
#ifdef _OPENMP
#pragma omp critical(acd3_split)
#endif
    {
        for (int id = 0; id < npre + nc; id++) S.pos[id] = -1;
        for (int i = 0; i < nc; i++) {
            int id = npre + i;
            for (int q = 0; q < npre; q++)
                if (S.pos[q] < 0 && same_candidate(&slot[q], &cand[i])) {
                    id = q;
                    break;
                }
            S.ord[i] = id;
            S.pos[id] = i;
        }
        S.nc = nc, S.nbridge = nbridge;
        if (have_cyc) S.best = cyc, S.found = S.best_progress = S.compared = 1;
        S.ordered = 1;
        split_replay(&S); /* the slots evaluated ahead so far */
    }
    if (!ahead && helpers > nc - 1) helpers = nc - 1;
#ifdef _OPENMP
    for (int h = 0; !ahead && h < helpers; h++) {
#pragma omp task default(shared)
        split_work(&S);
    }
#endif
    split_work(&S);
#ifdef _OPENMP
    if (ahead || helpers > 0) {
#pragma omp taskwait
    }
#endif
    for (int i = 0; i < npre + nc; i++) cand_eval_free(&ev[i]);
    free(S.onhull);
    stats->screened += S.stats.screened;
    stats->hulled += S.stats.hulled;
    if (S.fail) {
        if (S.found) acd3_split_choice_free(&S.best);
        if (err) *err = S.err;
        return -S.fail;
    }
    int found = S.found, best_progress = S.best_progress;
    *best = S.best;
    /* surface mode, no cut made progress: the pocket of the witness, cut along the level line of
     * half its concavity (acd3_surface_cut_deep), apart from its bridge */
    if (!solid && !best_progress && ms->witness != UINT32_MAX && ms->concavity > 0) {
        acd3_split_choice trial;
        memset(&trial, 0, sizeof trial);
        acd_error cerr;
        acd_status cst = acd3_surface_cut_deep(m, g, ms->vconc, 0.5 * ms->concavity, ms->witness, &trial.cut, &cerr);
        if (cst == ACD_ERR_NOMEM) {
            if (found) acd3_split_choice_free(best);
            *err = cerr;
            return -(int)ACD_ERR_NOMEM;
        }
        int ok = cst == ACD_OK && trial.cut.npieces >= 2;
        if (ok) {
            if (nc > nbridge) {
                trial.plane = cand[nbridge];
            } else { /* recorded only: through the witness */
                memcpy(trial.plane.point, m->vertices + 3 * (size_t)ms->witness, sizeof(double[3]));
                trial.plane.normal[0] = trial.plane.normal[1] = 0, trial.plane.normal[2] = 1;
            }
            trial.plane.kind = "deep";
            trial.pieces = calloc(trial.cut.npieces, sizeof *trial.pieces);
            if (!trial.pieces) {
                acd3_split_choice_free(&trial);
                if (found) acd3_split_choice_free(best);
                acd_fail(err, ACD_ERR_NOMEM, "out of memory");
                return -(int)ACD_ERR_NOMEM;
            }
            for (size_t k = 0; k < trial.cut.npieces; k++) {
                acd_status st = acd3_measure_mesh(&trial.cut.pieces[k].mesh, eps, tol, NULL, poll, &trial.pieces[k], err);
                if (st != ACD_OK) {
                    acd3_split_choice_free(&trial);
                    if (found) acd3_split_choice_free(best);
                    return -(int)st;
                }
                if (trial.pieces[k].ms.concavity > trial.concavity) trial.concavity = trial.pieces[k].ms.concavity;
            }
            ok = surface_progress(m, ms, &trial, tol);
        }
        if (ok) {
            if (found) acd3_split_choice_free(best);
            *best = trial;
            found = 1;
        } else {
            acd3_split_choice_free(&trial);
        }
    }
    return found;
}
