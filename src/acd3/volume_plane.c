/* acd3/volume_plane: cut planes for tight hulls; see volume_plane.h. */
#include "acd3/volume_plane.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "geom3/hull_volume.h"
#include "geom3/pca.h"

/* Offsets tried per axis: the planes at i / (VP_OFFSETS + 1) of the part's extent along it. */
#define VP_OFFSETS 9
/* Then refined around the best: half a step either side, a quarter, an eighth. */
#define VP_REFINE 3
/* The same for an estimate (acd3_volume_planes_scored with max_scored > 0). */
#define VP_OFFSETS_ESTIMATE 5
#define VP_REFINE_ESTIMATE 2
/* An estimate refines only the axes whose best coarse score is within this fraction of the best
 * coarse score over the axes (the full search refines every axis). On the tight runs of the six
 * target meshes (docs/results/3d-speed.md, 2026-11-25 22:00) an axis 2% or more behind after the
 * coarse pass won after the refinements in 2 of 130 searches (bunny00, armadillo, camel) and
 * changed no hull OBJ; it skips about half of the axes' refinements (a fifth of the trial cuts,
 * ~3% of the tight CPU). */
#define VP_REFINE_SLACK_ESTIMATE 0.02
/* Vertices used for scoring at most (every k-th beyond), plus every crossing point. */
#define VP_MAX_SCORED 4000

static double hull_volume(const double *pts, size_t n) {
    if (n < 4) return 0;
    double v;
    return acd_hull_volume(pts, n, &v, NULL) == ACD_OK ? v : -1;
}

/* Sum of the two sides' hull volumes of the plane (unit normal nrm, offset c: n.x = c); -1 on
 * failure. buf holds room for every vertex and crossing (twice). The hulls by qhull
 * (acd_hull_volume), or with a workspace w by geom3/hull_volume's own Quickhull (an estimate's
 * scores: they only rank planes). */
static double score_plane(const acd_mesh *m, size_t stride, size_t tstride, const double nrm[3], double c, double *bufa,
                          double *bufb, acd_hull_volume_ws *w) {
    size_t na = 0, nb = 0;
    for (size_t v = 0; v < m->nvertices; v += stride) {
        const double *p = m->vertices + 3 * v;
        double s = nrm[0] * p[0] + nrm[1] * p[1] + nrm[2] * p[2] - c;
        double *dst = s >= 0 ? bufa + 3 * na++ : bufb + 3 * nb++;
        memcpy(dst, p, sizeof(double[3]));
    }
    for (size_t t = 0; t < m->ntriangles; t += tstride)
        for (int k = 0; k < 3; k++) {
            uint32_t i = m->triangles[3 * t + k], j = m->triangles[3 * t + (k + 1) % 3];
            if (i > j) continue; /* each edge once (a closed mesh has both directions) */
            const double *p = m->vertices + 3 * (size_t)i, *q = m->vertices + 3 * (size_t)j;
            double sp = nrm[0] * p[0] + nrm[1] * p[1] + nrm[2] * p[2] - c;
            double sq = nrm[0] * q[0] + nrm[1] * q[1] + nrm[2] * q[2] - c;
            if ((sp >= 0) == (sq >= 0)) continue;
            double a = sp / (sp - sq), x[3];
            for (int d = 0; d < 3; d++) x[d] = p[d] + a * (q[d] - p[d]);
            memcpy(bufa + 3 * na++, x, sizeof x);
            memcpy(bufb + 3 * nb++, x, sizeof x);
        }
    double va = w ? acd_hull_volume_fast(bufa, na, w, NULL) : hull_volume(bufa, na);
    double vb = w ? acd_hull_volume_fast(bufb, nb, w, NULL) : hull_volume(bufb, nb);
    return va < 0 || vb < 0 ? -1 : va + vb;
}

int acd3_volume_planes(const acd_mesh *m, int nmax, acd3_plane_candidate *out) {
    return acd3_volume_planes_scored(m, nmax, 0, 3, out, NULL, NULL);
}

int acd3_volume_planes_scored(const acd_mesh *m, int nmax, size_t max_scored, int naxes, acd3_plane_candidate *out,
                              double *score, double *whole) {
    if (nmax <= 0 || m->nvertices < 4) return 0;
    acd_pca pca;
    if (acd_pca_points(m->vertices, m->nvertices, NULL, &pca, NULL) != ACD_OK) return 0;
    size_t cap = m->nvertices + 3 * m->ntriangles + 1;
    double *bufa = malloc(3 * cap * sizeof *bufa), *bufb = malloc(3 * cap * sizeof *bufb);
    if (!bufa || !bufb) {
        free(bufa), free(bufb);
        return 0;
    }
    size_t stride = (m->nvertices + VP_MAX_SCORED - 1) / VP_MAX_SCORED, tstride = 1;
    if (max_scored > 0) { /* an estimate: vertices and triangles sampled */
        stride = (m->nvertices + max_scored - 1) / max_scored;
        tstride = (m->ntriangles + 2 * max_scored - 1) / (2 * max_scored);
        if (tstride < 1) tstride = 1;
    }
    if (whole) { /* the hull volume of the scored vertices: the score of no cut */
        size_t k = 0;
        for (size_t v = 0; v < m->nvertices; v += stride) memcpy(bufa + 3 * k++, m->vertices + 3 * v, sizeof(double[3]));
        *whole = hull_volume(bufa, k);
    }
    /* an estimate's scores by the own Quickhull (geom3/hull_volume), the full search's by qhull */
    acd_hull_volume_ws hw;
    memset(&hw, 0, sizeof hw);
    acd_hull_volume_ws *hwp = max_scored > 0 ? &hw : NULL;
    double best[3];
    int n = 0, order[3];
    acd3_plane_candidate cand[3];
    /* an estimate (max_scored > 0): fewer offsets and refinements */
    const int noff = max_scored > 0 ? VP_OFFSETS_ESTIMATE : VP_OFFSETS, nref = max_scored > 0 ? VP_REFINE_ESTIMATE : VP_REFINE;
    /* the coarse pass over every axis first (its best offset, score and step per axis), then the
     * refinements */
    double abest[3], acut[3], astep[3], coarse_min = INFINITY;
    int atried[3] = {0, 0, 0};
    for (int a = 0; a < 3 && a < naxes; a++) {
        const double *ax = pca.axes[a];
        double lo = INFINITY, hi = -INFINITY;
        for (size_t v = 0; v < m->nvertices; v++) {
            const double *p = m->vertices + 3 * v;
            double s = ax[0] * p[0] + ax[1] * p[1] + ax[2] * p[2];
            lo = fmin(lo, s), hi = fmax(hi, s);
        }
        if (!(hi > lo)) continue;
        double bs = INFINITY, bc = 0, step = (hi - lo) / (noff + 1);
        for (int i = 1; i <= noff; i++) {
            double c = lo + step * i;
            double s = score_plane(m, stride, tstride, ax, c, bufa, bufb, hwp);
            if (s >= 0 && s < bs) bs = s, bc = c;
        }
        abest[a] = bs, acut[a] = bc, astep[a] = step, atried[a] = 1;
        coarse_min = fmin(coarse_min, bs);
    }
    for (int a = 0; a < 3 && a < naxes; a++) {
        if (!atried[a]) continue;
        const double *ax = pca.axes[a];
        double bs = abest[a], bc = acut[a], step = astep[a];
        /* refined around the best (nref times, halving the step); an estimate only refines the
         * axes near the best coarse score */
        int refine = max_scored == 0 || bs <= coarse_min * (1 + VP_REFINE_SLACK_ESTIMATE);
        for (int r = 0; refine && r < nref && bs < INFINITY; r++) {
            step *= 0.5;
            double c0 = bc;
            for (int sgn = -1; sgn <= 1; sgn += 2) {
                double c = c0 + sgn * step;
                double s = score_plane(m, stride, tstride, ax, c, bufa, bufb, hwp);
                if (s >= 0 && s < bs) bs = s, bc = c;
            }
        }
        if (!(bs < INFINITY)) continue;
        for (int k = 0; k < 3; k++) {
            cand[n].normal[k] = ax[k];
            cand[n].point[k] = pca.centroid[k] + (bc - (ax[0] * pca.centroid[0] + ax[1] * pca.centroid[1] + ax[2] * pca.centroid[2])) * ax[k];
        }
        cand[n].kind = "volume";
        best[n] = bs;
        order[n] = n;
        n++;
    }
    free(bufa);
    free(bufb);
    acd_hull_volume_ws_free(&hw);
    /* best first (stable: the axes' order on ties) */
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && best[order[j]] < best[order[j - 1]]; j--) {
            int x = order[j];
            order[j] = order[j - 1];
            order[j - 1] = x;
        }
    if (n > nmax) n = nmax;
    for (int i = 0; i < n; i++) {
        out[i] = cand[order[i]];
        if (score) score[i] = best[order[i]];
    }
    return n;
}

double acd3_volume_plane_sides(const acd_mesh *m, const double normal[3], const double point[3]) {
    size_t cap = m->nvertices + 3 * m->ntriangles + 1;
    double *bufa = malloc(3 * cap * sizeof *bufa), *bufb = malloc(3 * cap * sizeof *bufb), s = -1;
    acd_hull_volume_ws hw;
    memset(&hw, 0, sizeof hw);
    if (bufa && bufb)
        s = score_plane(m, 1, 1, normal, normal[0] * point[0] + normal[1] * point[1] + normal[2] * point[2], bufa, bufb, &hw);
    acd_hull_volume_ws_free(&hw);
    free(bufa);
    free(bufb);
    return s;
}
