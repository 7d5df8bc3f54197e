/* acd3/resolve: candidate cut planes for a measured solid; see resolve.h. */
#include "acd3/resolve.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd3/global_cut.h"
#include "geom3/pca.h"

/* Fraction of the witness's concavity above which a vertex belongs to the valley. */
#define VALLEY_FRACTION 0.5
/* The valley is two-dimensional (a ring, not a line) when its second PCA variance exceeds this
 * multiple of the third. */
#define VALLEY_PLANARITY 4.0

/* A notch is an edge whose faces turn by more than this (1 - cos of the angle between their
 * normals; 1e-8 is about 1.4e-4 rad): an edge between two coplanar faces of a cap, which
 * rounding may leave reflex, is not one (its bisector would be the cap's own plane). */
#define NOTCH_MIN_TURN 1e-8
/* A face whose doubled area is below this fraction of its squared longest edge (the sine of its
 * smallest angle, about) has no reliable normal: in notch mode it is not a side of a notch. */
#define FACE_MIN_SINE 1e-9

static void normalize(double v[3]) {
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0) v[0] /= l, v[1] /= l, v[2] /= l;
}

/* Returns the length of the unnormalized normal (twice the face's area). */
static double face_normal(const acd_mesh *m, uint32_t f, double n[3]) {
    const double *a = m->vertices + 3 * (size_t)m->triangles[3 * f], *b = m->vertices + 3 * (size_t)m->triangles[3 * f + 1],
                 *c = m->vertices + 3 * (size_t)m->triangles[3 * f + 2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    normalize(n);
    /* against the squared longest edge: a needle or a point has no normal */
    double e = fmax(u[0] * u[0] + u[1] * u[1] + u[2] * u[2], v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    double w[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
    e = fmax(e, w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    return l > FACE_MIN_SINE * e ? l : 0.0;
}

static int valley_plane(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms, acd3_plane_candidate *c) {
    uint32_t x = ms->witness;
    double thr = VALLEY_FRACTION * ms->vconc[x];
    size_t nv = m->nvertices;
    uint32_t *queue = malloc(nv * sizeof *queue);
    uint8_t *seen = calloc(nv, 1);
    double *pts = malloc(3 * nv * sizeof *pts), *w = malloc(nv * sizeof *w);
    int ok = 0;
    if (!queue || !seen || !pts || !w) goto done;
    size_t qh = 0, qt = 0;
    queue[qt++] = x;
    seen[x] = 1;
    while (qh < qt) {
        uint32_t v = queue[qh++];
        for (size_t k = g->row[v]; k < g->row[v + 1]; k++) {
            uint32_t u = g->adj[k];
            if (!seen[u] && ms->vconc[u] >= thr) {
                seen[u] = 1;
                queue[qt++] = u;
            }
        }
    }
    for (size_t i = 0; i < qt; i++) {
        memcpy(pts + 3 * i, m->vertices + 3 * (size_t)queue[i], sizeof(double[3]));
        w[i] = ms->vconc[queue[i]];
    }
    if (qt >= 3) {
        acd_pca pca;
        if (acd_pca_points(pts, qt, w, &pca, NULL) == ACD_OK && pca.values[1] > VALLEY_PLANARITY * pca.values[2] &&
            pca.values[1] > 0) {
            memcpy(c->point, m->vertices + 3 * (size_t)x, sizeof(double[3]));
            memcpy(c->normal, pca.axes[2], sizeof(double[3]));
            c->kind = "valley";
            ok = 1;
        }
    }
done:
    free(queue), free(seen), free(pts), free(w);
    return ok;
}

/* The most reflex edge at the witness, bisected: normal = n1 - n2 (outward face normals). strict
 * (the notch resolver): degenerate faces and edges within rounding of flat are no notches. */
static int notch_plane(const acd_mesh *m, const acd3_measure *ms, int strict, acd3_plane_candidate *c) {
    /* c[0]: bisector, c[1], c[2]: the planes of the two faces */
    uint32_t x = ms->witness;
    double best = 0;
    int ok = 0;
    /* faces around x: for each face with corner x, its edge (x, next) and the opposite face */
    for (size_t f = 0; f < m->ntriangles; f++)
        for (int k = 0; k < 3; k++) {
            if (m->triangles[3 * f + k] != x) continue;
            uint32_t y = m->triangles[3 * f + (k + 1) % 3];
            /* the face holding y -> x */
            for (size_t h = 0; h < m->ntriangles; h++) {
                if (h == f) continue;
                const uint32_t *t = m->triangles + 3 * h;
                int has = (t[0] == y && t[1] == x) || (t[1] == y && t[2] == x) || (t[2] == y && t[0] == x);
                if (!has) continue;
                double n1[3], n2[3];
                double a1 = face_normal(m, (uint32_t)f, n1), a2 = face_normal(m, (uint32_t)h, n2);
                /* strict (the notch resolver): degenerate faces and edges within rounding of flat
                 * are no notches; the witness planes keep their earlier candidates */
                if (strict && (a1 == 0 || a2 == 0)) break;
                /* reflex when the opposite face's far vertex is above face f's plane */
                uint32_t far = t[0] != x && t[0] != y ? t[0] : t[1] != x && t[1] != y ? t[1] : t[2];
                const double *p = m->vertices + 3 * (size_t)far, *q = m->vertices + 3 * (size_t)x;
                double above = n1[0] * (p[0] - q[0]) + n1[1] * (p[1] - q[1]) + n1[2] * (p[2] - q[2]);
                if (above <= 0) continue;
                double turn = 1.0 - (n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2]); /* 0 flat .. 2 folded */
                if (turn > best && (!strict || turn > NOTCH_MIN_TURN)) {
                    /* the plane containing the edge that bisects the material's (reflex) angle
                     * separates the two faces: normal n1 - n2. (n1 + n2, used here until
                     * 2026-11-25, is the other bisector: it leaves both faces on its positive
                     * side and does not resolve the notch; on an L it only touches the material
                     * along the notch edge. Fixing it: Table 5 solid at tau 0.02 7-31% fewer
                     * parts, docs/acd3d.md "Without feature grouping".) */
                    double n[3] = {n1[0] - n2[0], n1[1] - n2[1], n1[2] - n2[2]};
                    if (n[0] == 0 && n[1] == 0 && n[2] == 0) continue;
                    normalize(n);
                    best = turn;
                    for (int j = 0; j < 3; j++) memcpy(c[j].point, q, sizeof(double[3]));
                    memcpy(c[0].normal, n, sizeof(double[3]));
                    memcpy(c[1].normal, n1, sizeof(double[3]));
                    memcpy(c[2].normal, n2, sizeof(double[3]));
                    c[0].kind = "notch";
                    c[1].kind = c[2].kind = "face";
                    ok = 3;
                }
                break;
            }
        }
    return ok;
}

/* The global cut's plane (acd3/global_cut); 1 if found. */
static int global_plane(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms, const acd3_gc_opts *o,
                        acd3_plane_candidate *c) {
    acd3_cut_graph cg;
    if (acd3_cut_graph_build(m, g, ms, o, &cg, NULL) != ACD_OK) return 0;
    acd3_global_cut gc;
    int ok = 0;
    if (acd3_global_cut_find(m, g, ms, &cg, o, &gc, NULL) == ACD_OK) {
        if (gc.n >= 2 && acd3_global_cut_plane(m, ms, &cg, &gc, o, c->point, c->normal, NULL)) {
            c->kind = gc.cup ? "cup" : gc.closed ? "global" : "pocket";
            ok = 1;
        }
        acd3_global_cut_free(&gc);
    }
    acd3_cut_graph_free(&cg);
    return ok;
}

/* The planes through the witness perpendicular to the part's principal axes (at most max). */
static int axis_planes(const acd_mesh *m, const acd3_measure *ms, int max, acd3_plane_candidate *out) {
    acd_pca pca;
    if (acd_pca_points(m->vertices, m->nvertices, NULL, &pca, NULL) != ACD_OK) return 0;
    int n = 0;
    for (int a = 0; a < 3 && n < max; a++) {
        memcpy(out[n].point, m->vertices + 3 * (size_t)ms->witness, sizeof(double[3]));
        memcpy(out[n].normal, pca.axes[a], sizeof(double[3]));
        out[n].kind = "axis";
        n++;
    }
    return n;
}

int acd3_cut_candidates(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms,
                        const acd3_resolve_opts *ro, acd3_plane_candidate *out) {
    if (ms->witness == UINT32_MAX) return 0;
    int n = 0;
    if (ro && ro->global) n += global_plane(m, g, ms, &ro->gc, &out[n]);
    else if (ro && ro->notch) {
        /* notch cutting (spec §5.4, A14): the bisector, then only the axis planes (progress when
         * the bisector cannot split the part: a notch whose bisector runs along an earlier cap,
         * or one that only cuts off a sliver); the face planes it also fills are not proposed */
        if (notch_plane(m, ms, 1, &out[0])) {
            n = 1 + axis_planes(m, ms, ACD3_MAX_CANDIDATES - 1, &out[1]);
            return n;
        }
    }
    if (valley_plane(m, g, ms, &out[n])) n++;
    n += notch_plane(m, ms, 0, &out[n]);
    acd_pca pca;
    if (acd_pca_points(m->vertices, m->nvertices, NULL, &pca, NULL) != ACD_OK) return n;
    /* planes through the witness and the centroid containing a principal axis: across a ring
     * (a handle, a torus) or a bent limb, where the valley is not a loop around a neck */
    const double *x = m->vertices + 3 * (size_t)ms->witness;
    double dx[3] = {x[0] - pca.centroid[0], x[1] - pca.centroid[1], x[2] - pca.centroid[2]};
    for (int a = 2; a >= 0 && n < ACD3_MAX_CANDIDATES; a--) {
        const double *ax = pca.axes[a];
        double nrm[3] = {ax[1] * dx[2] - ax[2] * dx[1], ax[2] * dx[0] - ax[0] * dx[2], ax[0] * dx[1] - ax[1] * dx[0]};
        double l = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        if (!(l > 1e-6 * sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]))) continue; /* witness on the axis */
        memcpy(out[n].point, x, sizeof(double[3]));
        for (int k = 0; k < 3; k++) out[n].normal[k] = nrm[k] / l;
        out[n].kind = "centroid";
        n++;
    }
    return n + axis_planes(m, ms, ACD3_MAX_CANDIDATES - n, &out[n]);
}
