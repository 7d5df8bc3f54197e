/* acd3/decompose's internal entry point (the public one: acd3d_decompose, include/acd/acd3d.h): the
 * decomposition with the hull volume screen's margin given, for the screen's tests
 * (tests/test_acd3_screen.c; docs/acd3d.md "Cut choice by volume").
 *
 * The screen (by volume, ACD3D_CHOICE_VOLUME in solid mode; screen_decide in acd3/split.c): once the
 * best cut a candidate is compared with is final and makes progress, the candidate's pieces' hull
 * volumes are first estimated (geom3/hull_volume, not above the qhull hulls' up to rounding); a sum
 * above the best's hull volume by more than the margin (relative) drops the candidate before its
 * pieces' qhull hulls, as those hulls' sum would. */
#ifndef ACD_ACD3_DECOMPOSE_H
#define ACD_ACD3_DECOMPOSE_H

#include <stddef.h>

#include "acd/acd3d.h"
#include "acd/base.h"

/* The screen's margin on the default path (acd3d_decompose). On bunny00's tight run the dropped
 * candidates' sums were above the best's by 3.2e-4 or more (175 of 252). */
#define ACD3_VOLUME_SCREEN_REL 1e-4

/* What the splits' candidate evaluations did (summed over the tree's splits; with more than one
 * thread the counts depend on the schedule, the output does not). */
typedef struct acd3_decompose_stats {
    size_t screened; /* candidates the screen dropped on their estimates (before their qhull hulls) */
    size_t hulled;   /* candidates whose pieces' qhull hulls were computed */
    size_t halved;   /* parts no candidate split, cut by their halving planes (decompose.c; the same
                        for any number of threads) */
} acd3_decompose_stats;

/* As acd3d_decompose with the screen's margin screen_rel instead of ACD3_VOLUME_SCREEN_REL:
 * screen_rel <= -1 or NaN: no screen (every candidate evaluated gets its pieces' qhull hulls, no
 * estimate is made); >= 0: the same output for any margin unless an estimate is above its qhull
 * hull's volume by more than the margin; in (-1, 0): a screen that is wrong on purpose (it drops
 * candidates whose estimate is below the best's hull volume, some of which would have won: for the
 * tests' control). stats (may be NULL): the counts above. */
acd_status acd3_decompose_screen(const acd_mesh *mesh, const acd3d_params *params, double screen_rel,
                                 acd3_decompose_stats *stats, acd3d_result *out, acd_error *err);

#endif
