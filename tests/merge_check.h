/* Shared helpers for the merge pass's tests (tests/test_acd3_refine.c, test_acd3_merge_connected.c;
 * header-only, static inline): the atoms of an acd3_merge_result and the hulls of its groups. */
#ifndef ACD_TESTS_MERGE_CHECK_H
#define ACD_TESTS_MERGE_CHECK_H

#include "testutil.h"

#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "acd3/merge.h"

/* The atom k of r (an input part below nparts, else a piece the refinement cut). */
static inline const acd_mesh *mck_atom(const acd_mesh *parts, size_t nparts, const acd3_merge_result *r, size_t k) {
    return k < nparts ? &parts[k] : &r->new_parts[k - nparts];
}

/* Volume of the hull of group g's atoms. */
static inline double mck_group_hull_volume(const acd_mesh *parts, size_t nparts, const acd3_merge_result *r, size_t g) {
    size_t na = nparts + r->nnew, nv = 0;
    for (size_t k = 0; k < na; k++)
        if (r->group_of[k] == g) nv += mck_atom(parts, nparts, r, k)->nvertices;
    double *pts = malloc(3 * (nv ? nv : 1) * sizeof *pts);
    assert_non_null(pts);
    size_t w = 0;
    for (size_t k = 0; k < na; k++)
        if (r->group_of[k] == g) {
            const acd_mesh *m = mck_atom(parts, nparts, r, k);
            memcpy(pts + 3 * w, m->vertices, 3 * m->nvertices * sizeof *pts);
            w += m->nvertices;
        }
    acd_hull h;
    assert_int_equal(acd_hull_compute(pts, nv, &h, NULL), ACD_OK);
    double v = h.volume;
    acd_hull_free(&h);
    free(pts);
    return v;
}

/* Sum over r's groups of the volume of the hull of its atoms. */
static inline double mck_hull_sum(const acd_mesh *parts, size_t nparts, const acd3_merge_result *r) {
    double s = 0;
    for (size_t g = 0; g < r->ngroups; g++) s += mck_group_hull_volume(parts, nparts, r, g);
    return s;
}

#endif
