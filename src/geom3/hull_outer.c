/* geom3/hull_outer: greedy cutting-plane outer approximation of a convex hull (see hull_outer.h). */
#include "geom3/hull_outer.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/tolerance.h"

/* Corners of the bounded intersection of k half-spaces n.x + d <= 0 holding c strictly: the dual
 * points n / -(n.c + d) and their hull; each dual facet m.y + e = 0 is the corner c + m / -e.
 * Corners closer than tol are one. *corners malloc'd (3 per corner). */
static acd_status corners_of(const double *S, size_t k, const double *c, double tol, double **corners, size_t *m,
                             acd_error *err) {
    *corners = NULL;
    *m = 0;
    double *dual = malloc(3 * k * sizeof *dual);
    if (!dual) return acd_fail(err, ACD_ERR_NOMEM, "hull outer: out of memory");
    for (size_t i = 0; i < k; i++) {
        const double *p = S + 4 * i;
        double den = -(p[0] * c[0] + p[1] * c[1] + p[2] * c[2] + p[3]);
        if (!(den > 0)) {
            free(dual);
            return acd_fail(err, ACD_ERR_INTERNAL, "hull outer: interior point not inside plane %zu", i);
        }
        for (int j = 0; j < 3; j++) dual[3 * i + j] = p[j] / den;
    }
    acd_hull dh;
    acd_status st = acd_hull_compute(dual, k, &dh, err);
    free(dual);
    if (st != ACD_OK) return st;
    if (dh.dim != 3) {
        acd_hull_free(&dh);
        return acd_fail(err, ACD_ERR_INTERNAL, "hull outer: the planes do not bound a solid");
    }
    double *x = malloc(3 * (dh.ntriangles ? dh.ntriangles : 1) * sizeof *x);
    if (!x) {
        acd_hull_free(&dh);
        return acd_fail(err, ACD_ERR_NOMEM, "hull outer: out of memory");
    }
    size_t n = 0;
    for (size_t f = 0; f < dh.ntriangles; f++) {
        const double *pl = dh.planes + 4 * f;
        if (!(pl[3] < 0)) continue;
        double q[3];
        for (int j = 0; j < 3; j++) q[j] = c[j] + pl[j] / -pl[3];
        int dup = 0;
        for (size_t i = 0; i < n && !dup; i++)
            dup = fabs(x[3 * i] - q[0]) <= tol && fabs(x[3 * i + 1] - q[1]) <= tol && fabs(x[3 * i + 2] - q[2]) <= tol;
        if (!dup) {
            memcpy(x + 3 * n, q, sizeof q);
            n++;
        }
    }
    acd_hull_free(&dh);
    *corners = x;
    *m = n;
    return ACD_OK;
}

acd_status acd_hull_outer(const acd_hull *h, size_t max_vertices, double push, double **planes, size_t *nplanes,
                          size_t *ncorners, acd_error *err) {
    *planes = NULL;
    *nplanes = *ncorners = 0;
    if (!h || h->dim != 3) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "hull outer: a solid hull is needed");
    if (max_vertices < 4) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "hull outer: budget %zu < 4", max_vertices);
    size_t nv = h->nvertices, nf = h->ntriangles;
    const double *V = h->vertices;
    if (nv <= max_vertices) {
        double *p = malloc(4 * nf * sizeof *p);
        if (!p) return acd_fail(err, ACD_ERR_NOMEM, "hull outer: out of memory");
        memcpy(p, h->planes, 4 * nf * sizeof *p);
        *planes = p;
        *nplanes = nf;
        *ncorners = nv;
        return ACD_OK;
    }
    acd_scale sc = acd_scale_of_points(V, nv, 3);
    double tol = 10 * sc.dist, c[3] = {0, 0, 0};
    for (size_t v = 0; v < nv; v++)
        for (int j = 0; j < 3; j++) c[j] += V[3 * v + j] / (double)nv;
    size_t cap = 4 * max_vertices + 16, k = 0;
    double *S = malloc(4 * cap * sizeof *S);
    if (!S) return acd_fail(err, ACD_ERR_NOMEM, "hull outer: out of memory");
    /* start: bounding box, or a tetrahedron for budgets under 8 */
    static const double tet[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    size_t nstart = max_vertices >= 8 ? 6 : 4;
    for (size_t i = 0; i < nstart; i++) {
        double n[3] = {0, 0, 0};
        if (nstart == 6) n[i / 2] = i % 2 ? 1 : -1;
        else
            for (int j = 0; j < 3; j++) n[j] = tet[i][j] / sqrt(3.0);
        double mx = -INFINITY;
        for (size_t v = 0; v < nv; v++) {
            double s = n[0] * V[3 * v] + n[1] * V[3 * v + 1] + n[2] * V[3 * v + 2];
            if (s > mx) mx = s;
        }
        memcpy(S + 4 * k, n, sizeof n);
        S[4 * k + 3] = -mx;
        k++;
    }
    double *C = NULL, *C2 = NULL;
    size_t m = 0, m2 = 0;
    /* corners are those of the planes pushed by `push` (the polytope the caller builds) */
    double *Sp = malloc(4 * cap * sizeof *Sp);
    if (!Sp) {
        free(S);
        return acd_fail(err, ACD_ERR_NOMEM, "hull outer: out of memory");
    }
    for (size_t i = 0; i < 4 * k; i++) Sp[i] = i % 4 == 3 ? S[i] - push : S[i];
    acd_status st = corners_of(Sp, k, c, tol, &C, &m, err);
    while (st == ACD_OK && k < cap) {
        double worst = tol;
        size_t fw = SIZE_MAX;
        for (size_t i = 0; i < m; i++)
            for (size_t f = 0; f < nf; f++) {
                const double *p = h->planes + 4 * f;
                double s = p[0] * C[3 * i] + p[1] * C[3 * i + 1] + p[2] * C[3 * i + 2] + p[3] - push;
                if (s > worst) {
                    worst = s;
                    fw = f;
                }
            }
        if (fw == SIZE_MAX) break; /* every corner on the hull: the polytope is the hull */
        memcpy(S + 4 * k, h->planes + 4 * fw, 4 * sizeof *S);
        memcpy(Sp + 4 * k, h->planes + 4 * fw, 4 * sizeof *S);
        Sp[4 * k + 3] -= push;
        st = corners_of(Sp, k + 1, c, tol, &C2, &m2, err);
        if (st != ACD_OK) break;
        if (m2 > max_vertices) {
            free(C2);
            break;
        }
        k++;
        free(C);
        C = C2;
        m = m2;
    }
    free(C);
    free(Sp);
    if (st != ACD_OK) {
        free(S);
        return st;
    }
    *planes = S;
    *nplanes = k;
    *ncorners = m;
    return ACD_OK;
}
