/* acd3/leaf_test: the hull-distance stopping test; see leaf_test.h. */
#include "acd3/leaf_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd3/merge.h"
#include "core/error.h"
#include "geom3/bvh.h"
#include "geom3/vec3.h"

/* A triangle whose d_in bound is above the limit is subdivided, down to pieces of this
 * circumradius (a fraction of the limit); a piece that small still above it refuses the part. */
#define LEAF_MIN_RADIUS_REL 1e-3
/* Pieces subdivided per part at most (the part is refused beyond). */
#define LEAF_MAX_PIECES 20000

/* Depth of x below facet f's plane (positive inside). */
static double depth_f(const acd_hull *H, size_t f, const double x[3]) {
    const double *q = H->planes + 4 * f;
    return -(q[0] * x[0] + q[1] * x[1] + q[2] * x[2] + q[3]);
}

/* min over the facets of the largest corner depth below each (the bound of leaf_test.h; with one
 * corner: the exact distance to the boundary), trying `first` first and stopping as soon as the
 * minimum is <= stop. *arg: the facet giving it. */
static double corners_bound(const acd_hull *H, const double *const *c, int nc, size_t first, double stop, size_t *arg) {
    size_t nf = H->ntriangles, f = first;
    double best = INFINITY;
    for (size_t k = 0; k < nf; k++) {
        double b = -INFINITY;
        for (int i = 0; i < nc; i++) {
            double d = depth_f(H, f, c[i]);
            if (d > b) b = d;
        }
        if (b < best) {
            best = b;
            *arg = f;
            if (best <= stop) break;
        }
        f = f + 1 == nf ? 0 : f + 1;
    }
    return best;
}

/* Subdivides triangle tri (9 coordinates) until every piece's bound is <= limit. Returns the
 * largest piece bound (<= limit), or INFINITY when a corner is deeper than the limit, a piece gets
 * too small or the budget runs out; NaN on allocation failure. */
static double subdivide(const acd_hull *H, const double tri0[9], double limit, size_t *pieces) {
    size_t cap = 64, n = 1;
    double *stack = malloc(cap * 9 * sizeof *stack);
    if (!stack) return NAN;
    memcpy(stack, tri0, 9 * sizeof *stack);
    double worst = 0;
    size_t hint = 0;
    while (n) {
        double t[9];
        memcpy(t, stack + 9 * (--n), sizeof t);
        const double *c[3] = {t, t + 3, t + 6};
        double b = corners_bound(H, c, 3, hint, -INFINITY, &hint); /* exact min: no early stop */
        if (b <= limit) {
            if (b > worst) worst = b;
            continue;
        }
        for (int i = 0; i < 3; i++) {
            size_t a;
            if (corners_bound(H, c + i, 1, hint, -INFINITY, &a) > limit) { /* a point of the part too deep */
                free(stack);
                return INFINITY;
            }
        }
        double g[3];
        for (int k = 0; k < 3; k++) g[k] = (t[k] + t[3 + k] + t[6 + k]) / 3.0;
        double r = fmax(acd_dist3(g, t), fmax(acd_dist3(g, t + 3), acd_dist3(g, t + 6)));
        if (r < LEAF_MIN_RADIUS_REL * limit || (*pieces += 4) > LEAF_MAX_PIECES) {
            free(stack);
            return INFINITY;
        }
        if (n + 4 > cap) {
            double *ns = realloc(stack, 2 * cap * 9 * sizeof *ns);
            if (!ns) {
                free(stack);
                return NAN;
            }
            stack = ns;
            cap *= 2;
        }
        acd_tri_split4(t, (double(*)[9])(stack + 9 * n));
        n += 4;
    }
    free(stack);
    return worst;
}

/* d_in (leaf_test.h): returns the bound (> limit as soon as it is known to exceed it), or NaN on
 * allocation failure (NaN). */
static double inner_bound(const acd_mesh *m, const acd_hull *H, double limit, uint32_t hint) {
    size_t nv = m->nvertices, nt = m->ntriangles;
    size_t *vf = malloc((nv ? nv : 1) * sizeof *vf); /* per vertex: its nearest facet */
    if (!vf) return NAN;
    double dmax = -INFINITY;
    size_t f = 0;
    /* the hint first: a deep witness refuses the part after one scan of the facets */
    if (hint < nv && corners_bound(H, (const double *const[]){m->vertices + 3 * (size_t)hint}, 1, 0, -INFINITY, &f) > limit) {
        free(vf);
        return INFINITY;
    }
    /* every vertex (exact: the nearest facet plane) */
    for (size_t v = 0; v < nv; v++) {
        const double *c[1] = {m->vertices + 3 * v};
        double d = corners_bound(H, c, 1, f, dmax, &f);
        vf[v] = f;
        if (d > dmax) dmax = d;
        if (dmax > limit) {
            free(vf);
            return dmax;
        }
    }
    /* every triangle: the facets of its corners first */
    size_t pieces = 0;
    for (size_t t = 0; t < nt; t++) {
        const uint32_t *tv = m->triangles + 3 * t;
        const double *c[3] = {m->vertices + 3 * (size_t)tv[0], m->vertices + 3 * (size_t)tv[1], m->vertices + 3 * (size_t)tv[2]};
        double best = INFINITY;
        size_t a = vf[tv[0]];
        for (int i = 0; i < 3 && best > dmax; i++) {
            double b = corners_bound(H, c, 3, vf[tv[i]], INFINITY, &a); /* that facet only */
            if (b < best) best = b;
        }
        if (best > dmax) best = corners_bound(H, c, 3, vf[tv[0]], dmax, &a);
        if (best > limit) {
            double tri[9];
            for (int i = 0; i < 3; i++) memcpy(tri + 3 * i, c[i], sizeof(double[3]));
            best = subdivide(H, tri, limit, &pieces);
            if (isnan(best)) {
                free(vf);
                return NAN;
            }
        }
        if (best > dmax) dmax = best;
        if (dmax > limit) break;
    }
    free(vf);
    return dmax;
}

acd_status acd3_leaf_test(const acd_mesh *part, const acd_hull *H, double limit, uint32_t hint, int *accepted,
                          double *bound, acd_error *err) {
    return acd3_leaf_test_keep(part, H, limit, hint, accepted, bound, NULL, NULL, err);
}

acd_status acd3_leaf_test_keep(const acd_mesh *part, const acd_hull *H, double limit, uint32_t hint, int *accepted,
                               double *bound, acd_bvh *bvh_out, acd3_facet_table *table, acd_error *err) {
    *accepted = 0;
    *bound = INFINITY;
    if (bvh_out) memset(bvh_out, 0, sizeof *bvh_out);
    if (table) memset(table, 0, sizeof *table);
    if (H->dim != 3 || H->ntriangles == 0 || part->ntriangles == 0) return ACD_OK;
    double din = inner_bound(part, H, limit, hint);
    if (isnan(din)) return acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    if (!(din <= limit)) {
        *bound = din;
        return ACD_OK;
    }
    acd_bvh bvh;
    acd_status st = acd_bvh_build(&bvh, part->vertices, part->nvertices, part->triangles, part->ntriangles, err);
    if (st != ACD_OK) return st;
    double dout = acd3_merge_hull_reach_table(&bvh, H, limit, table);
    if (bvh_out) *bvh_out = bvh;
    else acd_bvh_free(&bvh);
    *bound = fmax(din, dout);
    *accepted = *bound <= limit;
    if (table && !*accepted) acd3_facet_table_free(table); /* (din <= limit: dout was above it) */
    return ACD_OK;
}
