/* acd3/patches: bridge patches, the feature grouping of hull facets used to measure concavity
 * (dissertation §V.A.3, §V.B.1, Alg. 6, Obs. B.1; paper §4.1 Ext. 1, App. A Alg. 2;
 * spec acd3d.md §3.3).
 *
 * Contiguous, nearly coplanar hull facets are grouped into a patch with one supporting plane
 * tangent to the hull; every facet vertex of a patch lies within eps of that plane. Step 1
 * (Alg. 6) estimates the number of patches by greedy region growing from the largest unassigned
 * facet; step 2 refines the grouping with Lloyd iterations of variational shape approximation
 * (L^{2,1} normal metric, priority-queue flooding, area-weighted mean normals; at most 20
 * iterations or until the partition is stable). Patches that break the eps bound are split by
 * seeding a new proxy at their worst facet, until every patch meets it. */
#ifndef ACD_ACD3_PATCHES_H
#define ACD_ACD3_PATCHES_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "acd/hull.h"

typedef struct acd3_patches {
    size_t npatches;
    uint32_t *facet_patch; /* per hull triangle: its patch */
    double *planes;        /* 4 per patch: unit normal N and h, the plane {x : N.x = h} tangent to the hull;
                              the depth of a point x below it is h - N.x */
    uint32_t *seed;        /* per patch: a facet of it (the proxy's seed) */
} acd3_patches;

/* Groups the facets of a 3D hull (dim 3) into patches with max facet-vertex depth <= eps + tol
 * (tol: a scale-relative length, e.g. acd_scale.dist, so exactly coplanar facets merge when
 * eps = 0). Deterministic. */
acd_status acd3_patches_build(const acd_hull *h, double eps, double tol, acd3_patches *out, acd_error *err);
void acd3_patches_free(acd3_patches *p);

/* Depth of point x below patch i's supporting plane (>= 0 for points of the hull). */
static inline double acd3_patch_depth(const acd3_patches *p, size_t i, const double x[3]) {
    const double *q = p->planes + 4 * i;
    return q[3] - (q[0] * x[0] + q[1] * x[1] + q[2] * x[2]);
}

#endif
