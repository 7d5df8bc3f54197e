/* geom3/hull_simplify: enclosing convex polytope with a vertex budget.
 *
 * Plane pushing: the facets of the hull of a farthest-point subset are moved outward to support
 * the whole point set, then intersected through point/plane duality (a half-space n.x + d <= 0
 * with the interior point c at the origin maps to the dual point n / -(d + n.c); the facets of the
 * dual hull map back to the vertices of the intersection). This is the outer-approximation route
 * the spec suggests as a stand-in for Lien's "simplified hulls" (dissertation Ch. VI.D, the
 * triboxes of Crosnier and Rossignac), labelled as a substitute in docs/eval.md. */
#include "geom3/hull_simplify.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/tolerance.h"
#include "geom3/vec3.h"

#define SIMPLIFY_MARGIN_TRIES 4


/* The first kmax (>= 4) vertices of a farthest-point ordering of the hull's vertices, started by a
 * large tetrahedron (farthest from the centroid, farthest from it, farthest from their line,
 * farthest from their plane) so the first four are never coplanar. Deterministic: ties go to the
 * lower index. */
static void farthest_order(const acd_hull *h, size_t kmax, uint32_t *order, double *mind) {
    size_t nv = h->nvertices;
    const double *V = h->vertices;
    double c[3] = {0, 0, 0};
    for (size_t v = 0; v < nv; v++)
        for (int k = 0; k < 3; k++) c[k] += V[3 * v + k] / (double)nv;
    size_t pick[4] = {0, 0, 0, 0};
    for (int stage = 0; stage < 4; stage++) {
        double best = -1;
        for (size_t v = 0; v < nv; v++) {
            const double *p = V + 3 * v;
            double val;
            if (stage == 0 || stage == 1) {
                const double *q = stage == 0 ? c : V + 3 * pick[0];
                double d[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
                val = acd_dot3(d, d);
            } else {
                const double *a = V + 3 * pick[0], *b = V + 3 * pick[1];
                double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
                if (stage == 2) {
                    double x[3] = {ab[1] * ap[2] - ab[2] * ap[1], ab[2] * ap[0] - ab[0] * ap[2], ab[0] * ap[1] - ab[1] * ap[0]};
                    val = acd_dot3(x, x);
                } else {
                    const double *cc = V + 3 * pick[2];
                    double ac[3] = {cc[0] - a[0], cc[1] - a[1], cc[2] - a[2]};
                    double nrm[3] = {ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0]};
                    val = fabs(acd_dot3(nrm, ap));
                }
            }
            if (val > best) {
                best = val;
                pick[stage] = v;
            }
        }
    }
    if (pick[1] == 0 && pick[0] == 0) pick[1] = 1; /* cannot happen for a solid hull */
    for (size_t v = 0; v < nv; v++) mind[v] = INFINITY;
    for (size_t i = 0; i < kmax; i++) {
        size_t cur;
        if (i < 4) {
            cur = pick[i];
        } else {
            double far = -1;
            cur = 0;
            for (size_t v = 0; v < nv; v++)
                if (mind[v] > far) {
                    far = mind[v];
                    cur = v;
                }
        }
        order[i] = (uint32_t)cur;
        const double *p = V + 3 * cur;
        for (size_t v = 0; v < nv; v++) {
            double d[3] = {V[3 * v] - p[0], V[3 * v + 1] - p[1], V[3 * v + 2] - p[2]};
            double dd = acd_dot3(d, d);
            if (dd < mind[v]) mind[v] = dd;
        }
    }
}

/* Pushed-plane polytope of the first k ordered vertices; *out gets its hull. */
static acd_status pushed_polytope(const acd_hull *full, const uint32_t *order, size_t k, const double *points,
                                  size_t n, double margin, acd_hull *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    acd_status st;
    double *sub = malloc(3 * k * sizeof(double));
    if (!sub) return acd_fail(err, ACD_ERR_NOMEM, "hull simplify: out of memory");
    for (size_t i = 0; i < k; i++) memcpy(sub + 3 * i, full->vertices + 3 * (size_t)order[i], 3 * sizeof(double));
    acd_hull small;
    st = acd_hull_compute(sub, k, &small, err);
    free(sub);
    if (st != ACD_OK) return st;
    if (small.dim != 3) {
        acd_hull_free(&small);
        return ACD_ERR_DEGENERATE; /* caller tries more points */
    }
    double c[3] = {0, 0, 0};
    for (size_t v = 0; v < small.nvertices; v++)
        for (int j = 0; j < 3; j++) c[j] += small.vertices[3 * v + j] / (double)small.nvertices;
    size_t nf = small.ntriangles;
    double *dual = malloc(3 * (nf ? nf : 1) * sizeof(double));
    double *verts = NULL;
    acd_hull dh;
    memset(&dh, 0, sizeof dh);
    if (!dual) {
        acd_hull_free(&small);
        return acd_fail(err, ACD_ERR_NOMEM, "hull simplify: out of memory");
    }
    size_t nd = 0;
    for (size_t f = 0; f < nf; f++) {
        const double *pl = small.planes + 4 * f;
        int dup = 0;
        for (size_t g = 0; g < f && !dup; g++) dup = memcmp(small.planes + 4 * g, pl, 3 * sizeof(double)) == 0;
        if (dup) continue;
        double mx = -INFINITY;
        for (size_t i = 0; i < n; i++) {
            double v = acd_dot3(pl, points + 3 * i);
            if (v > mx) mx = v;
        }
        double dc = -mx - margin + acd_dot3(pl, c); /* pushed offset, interior point at the origin */
        for (int j = 0; j < 3; j++) dual[3 * nd + j] = pl[j] / -dc;
        nd++;
    }
    acd_hull_free(&small);
    st = acd_hull_compute(dual, nd, &dh, err);
    free(dual);
    if (st != ACD_OK) return st;
    if (dh.dim != 3) {
        acd_hull_free(&dh);
        return acd_fail(err, ACD_ERR_DEGENERATE, "hull simplify: the pushed planes do not bound a solid");
    }
    verts = malloc(3 * (dh.ntriangles ? dh.ntriangles : 1) * sizeof(double));
    if (!verts) {
        acd_hull_free(&dh);
        return acd_fail(err, ACD_ERR_NOMEM, "hull simplify: out of memory");
    }
    size_t nv = 0;
    for (size_t f = 0; f < dh.ntriangles; f++) {
        const double *pl = dh.planes + 4 * f;
        /* triangles of one dual facet share its normal: one primal vertex, the farthest out */
        int dup = 0;
        for (size_t g = 0; g < f && !dup; g++) dup = memcmp(dh.planes + 4 * g, pl, 3 * sizeof(double)) == 0;
        if (dup) continue;
        double e = pl[3];
        for (size_t g = f + 1; g < dh.ntriangles; g++)
            if (memcmp(dh.planes + 4 * g, pl, 3 * sizeof(double)) == 0 && dh.planes[4 * g + 3] > e) e = dh.planes[4 * g + 3];
        if (!(e < 0)) {
            free(verts);
            acd_hull_free(&dh);
            return acd_fail(err, ACD_ERR_DEGENERATE, "hull simplify: dual hull does not hold the origin");
        }
        for (int j = 0; j < 3; j++) verts[3 * nv + j] = c[j] + pl[j] / -e;
        nv++;
    }
    acd_hull_free(&dh);
    st = acd_hull_compute(verts, nv, out, err);
    free(verts);
    if (st == ACD_OK)
        for (size_t v = 0; v < out->nvertices; v++) out->source[v] = UINT32_MAX;
    return st;
}

acd_status acd_hull_simplify(const double *points, size_t n, size_t max_vertices, acd_hull *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    if (max_vertices < 4)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "hull simplify: at least 4 vertices are needed, not %zu",
                        max_vertices);
    acd_hull full;
    acd_status st = acd_hull_compute(points, n, &full, err);
    if (st != ACD_OK) return st;
    if (full.nvertices <= max_vertices) {
        *out = full;
        return ACD_OK;
    }
    if (full.dim != 3) {
        size_t nv = full.nvertices;
        acd_hull_free(&full);
        return acd_fail(err, ACD_ERR_UNSUPPORTED, "hull simplify: flat hull (dim %d) with %zu vertices cannot be "
                        "reduced to %zu", full.dim, nv, max_vertices);
    }
    acd_scale sc = acd_scale_of_points(points, n, 3);
    uint32_t *order = malloc(full.nvertices * sizeof *order);
    double *mind = malloc(full.nvertices * sizeof *mind);
    if (!order || !mind) {
        free(order);
        free(mind);
        acd_hull_free(&full);
        return acd_fail(err, ACD_ERR_NOMEM, "hull simplify: out of memory for %zu vertices", full.nvertices);
    }
    farthest_order(&full, max_vertices, order, mind);
    double margin = sc.dist;
    size_t k = max_vertices;
    int done = 0, margin_tries = 0;
    st = ACD_OK;
    for (int tries = 0; tries < 256 && !done; tries++) {
        acd_hull cand;
        acd_error e2;
        acd_status s2 = pushed_polytope(&full, order, k, points, n, margin, &cand, &e2);
        if (s2 == ACD_ERR_DEGENERATE && cand.nvertices == 0 && k < max_vertices) {
            k++;
            continue;
        }
        if (s2 != ACD_OK) {
            st = acd_fail(err, s2, "hull simplify: %s", e2.message);
            done = 1;
            break;
        }
        if (cand.nvertices > max_vertices) {
            size_t over = cand.nvertices - max_vertices;
            acd_hull_free(&cand);
            if (k == 4) {
                st = acd_fail(err, ACD_ERR_INTERNAL, "hull simplify: 4 pushed planes gave %zu vertices", over + max_vertices);
                done = 1;
                break;
            }
            size_t step = (over + 1) / 2;
            k = k > 4 + step ? k - step : 4;
            continue;
        }
        /* every point inside (the margin absorbs the rounding of the dual construction) */
        double worst = -INFINITY;
        for (size_t i = 0; i < n; i++) {
            double d = acd_hull_plane_distance(&cand, points + 3 * i);
            if (d > worst) worst = d;
        }
        if (worst <= sc.dist) {
            *out = cand;
            done = 1;
            break;
        }
        acd_hull_free(&cand);
        if (++margin_tries > SIMPLIFY_MARGIN_TRIES) break;
        margin *= 100;
    }
    free(order);
    free(mind);
    acd_hull_free(&full);
    if (!done)
        return acd_fail(err, ACD_ERR_INTERNAL, "hull simplify: no enclosing polytope with %zu vertices found",
                        max_vertices);
    return st;
}
