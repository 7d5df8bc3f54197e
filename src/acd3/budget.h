/* acd3/budget: splitting under a part budget by hull excess (CoACD's objective; issue 4 item 6,
 * docs/acd3d.md "Hull tightness", "Excess-driven budget").
 *
 * The decomposition's leaves (or the input alone) are split further, best first by the hull
 * volume a split saves: each part's best split is the cut, among its volume planes
 * (acd3/volume_plane, one across each principal axis), of smallest sum of the pieces' exact hull
 * volumes; the part whose best split saves the most is cut, until `budget` parts exist. Every part
 * must also meet `limit` both ways (acd3/leaf_test: its surface and its hull's boundary within
 * limit of each other, the merge pass's kind of bound): a part that does not is cut (its best
 * split, whatever it saves) even beyond the budget, but only by a cut that makes progress (each
 * piece's bounding-box diagonal at most 0.95 of the part's: its best such cut among its candidates
 * and the midplanes of its bounding box), at most 96 such cuts deep and 32 x (budget + nparts) in
 * all (budget.c, BUDGET_P1_SHRINK: the termination argument; docs/acd3d.md "Excess-driven budget").
 * A part no cut splits (slivers refused) or none makes progress on stays as it is (counted in
 * `over` when above limit, phase1_stop saying why).
 * Deterministic for any thread count (the candidate planes are scored in parallel, every choice is
 * sequential). */
#ifndef ACD_ACD3_BUDGET_H
#define ACD_ACD3_BUDGET_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "acd/hull.h"
#include "acd/mesh.h"
#include "acd3/merge.h"
#include "geom3/bvh.h"

typedef struct acd3_budget_result {
    /* pieces, numbered after the input parts (atom nparts + k is new_parts[k]); the pieces of one
     * cut are consecutive */
    size_t nnew;
    acd_mesh *new_parts;    /* owned (pieces cut again too) */
    uint32_t *new_parent;   /* per piece: the atom it was cut from */
    double (*new_plane)[4]; /* per piece: its parent's cut plane n.x + d = 0 */
    double *new_volume;     /* per piece: its volume */
    double *new_bound;      /* per piece: its leaf_test bound (<= limit unless it is in `over`) */
    acd_hull *new_hull;     /* per piece: its hull (acd_hull_compute of its vertices, the one its hull
                             * volume and bound came from) when it is a part, owned; dim -1 (nothing
                             * allocated) for a piece cut again */
    acd_bvh *new_bvh;       /* per piece that is a part: its triangle tree over new_parts[k]'s arrays (its
                             * leaf test's), owned; empty (nnodes 0) when none */
    acd3_facet_table *new_table; /* per piece that is a part: new_hull's facet table at limit over
                             * new_bvh when its leaf test accepted it (acd3/merge), owned; else empty */
    size_t nalive;          /* parts after the splits (input parts not cut and pieces not cut) */
    size_t over;            /* of them, parts above limit that no cut could split */
    size_t cuts;            /* cuts made */
    size_t phase1_cuts;     /* of them, cuts of parts above limit once the budget was spent */
    const char *phase1_stop; /* when parts stay above limit (over > 0), why (a static string), else NULL */
    double hull_volume;     /* the sum of the parts' hull volumes */
    size_t screen_fallbacks; /* evaluations in which no candidate the screen left was good, so the
                             * others got their qhull hulls too (budget.c, BUDGET_SCREEN_REL) */
    size_t directions_bounded; /* directions of the evaluations given a bound (budget.c, BUDGET_BOUND_REL) */
    size_t directions_scored;  /* of all directions (bounded or not), those scored on the whole sample */
} acd3_budget_result;

/* parts: the closed parts tiling a closed input (every one tested against limit too); limit in
 * model units; extent: the model's extent (plane construction); min_gain: a split made for the
 * budget must save more than this much hull volume. threads: OpenMP workers (<= 1: one). */
acd_status acd3_budget_split(const acd_mesh *parts, size_t nparts, size_t budget, double limit,
                             double min_gain, double extent, int threads, acd3_budget_result *out, acd_error *err);
/* As acd3_budget_split, with hulls (NULL, or per part NULL or the part's hull: acd_hull_compute of
 * exactly its vertices, in their order; read only) used instead of computing the parts' hulls again
 * (a hull whose vertices are not the part's points its source names is computed as before), and a
 * progress callback (NULL: none; called before each choice from the calling thread, the fraction
 * parts / budget; non-zero cancels: ACD_ERR_CANCELLED, nothing returned). */
acd_status acd3_budget_split_hulls(const acd_mesh *parts, const acd_hull *const *hulls, size_t nparts, size_t budget,
                                   double limit, double min_gain, double extent, int threads, acd_progress_fn progress,
                                   void *progress_user, acd3_budget_result *out, acd_error *err);
/* As acd3_budget_split with the screen's margin screen_rel instead of BUDGET_SCREEN_REL (budget.c:
 * an atom's exact candidates whose estimated hull volume sum lies more than screen_rel above its best
 * estimated sum get qhull hulls only when none of the others is good; INFINITY: every candidate gets
 * them; -1: none passes, every evaluation takes the fallback). The choice is the same for any margin
 * unless an estimate is off by more than it; for the tests of the fallback. */
acd_status acd3_budget_split_screen(const acd_mesh *parts, size_t nparts, size_t budget, double limit, double min_gain,
                                    double extent, int threads, double screen_rel, acd3_budget_result *out,
                                    acd_error *err);
/* As acd3_budget_split_screen, with the directions' bound's margin bound_rel instead of
 * BUDGET_BOUND_REL (budget.c: a direction is scored only when its bound less bound_rel of it is not
 * above the scores that would make it one of the directions refined; bound_rel <= -1 or NaN: every
 * direction is scored). The result is the same for any margin >= 0 unless an estimate is off by more
 * than it; a margin in (-1, 0) raises the bound above the score it bounds (for the tests: a bound
 * that is not one). */
acd_status acd3_budget_split_tuned(const acd_mesh *parts, size_t nparts, size_t budget, double limit, double min_gain,
                                   double extent, int threads, double screen_rel, double bound_rel,
                                   acd3_budget_result *out, acd_error *err);
void acd3_budget_result_free(acd3_budget_result *r);
/* The vertices the plane search samples from (flag[v] = 1, else 0; flag: room for m->nvertices):
 * those some plane through them has strictly above the other corners of their triangles (tried:
 * the vertex normal, the offset from the neighbours' mean), the only ones that can be a vertex of
 * the hull of any region holding their triangles (a flat, concave or saddle vertex, a midpoint of
 * two neighbours, never is). How many; SIZE_MAX when out of memory. */
size_t acd3_budget_hull_candidates(const acd_mesh *m, unsigned char *flag);

#endif
