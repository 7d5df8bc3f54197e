/* geom3/hull_outside: the volume of a closed solid outside a convex hull, exactly up to rounding,
 * by cutting the solid with the hull's planes (acd_hull_volume_outside, declared in acd/hull.h).
 *
 * acd_hull_volume_outside_bound (geom3/volume.c) sums the solid's volume beyond each plane the
 * solid sticks out of, so a region beyond two planes (where the caps of two cuts of a trimmed hull
 * overlap) counts twice. Here the region outside is taken off piece by piece: after the cuts by
 * planes 1..j the pieces left lie on the inner side of each of them, and what plane j + 1 cuts off
 * them lies beyond it and inside the earlier ones, so no region is counted twice. The sides are the
 * plane cut's (acd_orient3d against three points of the plane: exact). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "acd/mesh.h"
#include "core/error.h"
#include "geom3/frame.h"
#include "geom3/plane_cut.h"
#include "geom3/volume.h"

typedef struct piece {
    acd_mesh mesh;
    int owned; /* 0: the caller's solid (not freed) */
} piece;

static void pieces_free(piece *p, size_t n) {
    for (size_t i = 0; i < n; i++)
        if (p[i].owned) acd_mesh_free(&p[i].mesh);
    free(p);
}

/* Appends to *p (n used of *cap); 0 when out of memory. */
static int push_piece(piece **p, size_t *n, size_t *cap, acd_mesh mesh, int owned) {
    if (*n == *cap) {
        size_t c = *cap ? 2 * *cap : 8;
        piece *q = realloc(*p, c * sizeof *q);
        if (!q) return 0;
        *p = q, *cap = c;
    }
    (*p)[(*n)++] = (piece){mesh, owned};
    return 1;
}

/* Whether some vertex of m lies strictly beyond pl (exactly). */
static int reaches_beyond(const acd_mesh *m, const acd_cut_plane *pl) {
    for (size_t v = 0; v < m->nvertices; v++)
        if (acd_cut_plane_side(pl, m->vertices + 3 * v) > 0) return 1;
    return 0;
}

static acd_status volume_outside(const acd_hull *h, const acd_mesh *m, double tol, double tol_scale, double *outside,
                                 acd_error *err);

/* Far from the origin (geom3/frame) the solid and the hull are taken in the local frame (the
 * planes' offsets d + n.c rounded once): the cuts' points and the pieces' volumes then carry the
 * local coordinates' rounding, not the model coordinates' spacing. Near it, as always. */
acd_status acd_hull_volume_outside(const acd_hull *h, const acd_mesh *m, double tol, double tol_scale,
                                   double *outside, acd_error *err) {
    if (outside) *outside = NAN;
    if (!h || !m || !outside)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "volume outside a hull: NULL hull, mesh or result");
    if (!isfinite(tol) || !isfinite(tol_scale))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "volume outside a hull: tolerance %g or scale %g not finite",
                        tol, tol_scale);
    if (m->nvertices == 0 || m->ntriangles == 0) {
        *outside = 0;
        return ACD_OK;
    }
    if (h->dim != 3) { /* no interior: all of the solid is outside */
        *outside = acd_geom3_signed_volume(m);
        return ACD_OK;
    }
    acd_frame fr;
    acd_geom3_frame_of(m->vertices, m->nvertices, &fr);
    if (!fr.moved) return volume_outside(h, m, tol, tol_scale, outside, err);
    acd_mesh lm;
    acd_hull lh;
    acd_status st = acd_geom3_frame_mesh_view(&fr, m, &lm, err);
    if (st != ACD_OK) return st;
    st = acd_geom3_frame_hull_view(&fr, h, &lh, err);
    if (st == ACD_OK) st = volume_outside(&lh, &lm, tol, tol_scale, outside, err);
    acd_geom3_frame_view_free(&lm, &lh);
    return st;
}

static acd_status volume_outside(const acd_hull *h, const acd_mesh *m, double tol, double tol_scale, double *outside,
                                 acd_error *err) {
    /* the planes, as acd_hull_volume_outside_bound picks them: reached beyond by more than tol,
     * one of each group within 1e-9 (normal) and 1e-9 x tol_scale (offset) of each other */
    size_t *sel = NULL, nsel = 0;
    for (size_t f = 0; f < h->ntriangles; f++) {
        const double *q = h->planes + 4 * f;
        int reached = 0; /* the bound's max over the vertices > tol: some vertex > tol */
        for (size_t k = 0; k < m->nvertices && !reached; k++) {
            const double *v = m->vertices + 3 * k;
            reached = q[0] * v[0] + q[1] * v[1] + q[2] * v[2] + q[3] > tol;
        }
        if (!reached) continue;
        int dup = 0;
        for (size_t j = 0; j < nsel && !dup; j++) {
            const double *s = h->planes + 4 * sel[j];
            dup = fabs(s[0] - q[0]) <= 1e-9 && fabs(s[1] - q[1]) <= 1e-9 && fabs(s[2] - q[2]) <= 1e-9 &&
                  fabs(s[3] - q[3]) <= 1e-9 * tol_scale;
        }
        if (dup) continue;
        if (!sel && !(sel = malloc(h->ntriangles * sizeof *sel)))
            return acd_fail(err, ACD_ERR_NOMEM, "out of memory for the planes of a hull of %zu triangles", h->ntriangles);
        sel[nsel++] = f;
    }
    if (nsel == 0) {
        *outside = 0;
        return ACD_OK;
    }
    /* the spanning points of each cut plane at the solid's extent from the facet's centre */
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) lo[k] = hi[k] = m->vertices[k];
    for (size_t v = 1; v < m->nvertices; v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], m->vertices[3 * v + k]);
            hi[k] = fmax(hi[k], m->vertices[3 * v + k]);
        }
    const double size = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                             (hi[2] - lo[2]) * (hi[2] - lo[2]));
    piece *cur = NULL, *next = NULL;
    size_t ncur = 0, ccur = 0, nnext = 0, cnext = 0;
    acd_status st = ACD_OK;
    double sum = 0;
    if (!push_piece(&cur, &ncur, &ccur, *m, 0)) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for the pieces of a solid");
        goto done;
    }
    for (size_t j = 0; j < nsel && st == ACD_OK; j++) {
        const size_t f = sel[j];
        const double *q = h->planes + 4 * f;
        double c[3] = {0, 0, 0};
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++) c[k] += h->vertices[3 * (size_t)h->triangles[3 * f + i] + k] / 3;
        const double s = q[0] * c[0] + q[1] * c[1] + q[2] * c[2] + q[3];
        for (int k = 0; k < 3; k++) c[k] -= s * q[k];
        acd_cut_plane pl;
        acd_error cerr;
        acd_status cs = acd_cut_plane_from_normal(c, q, size, &pl, &cerr);
        if (cs != ACD_OK) {
            st = acd_fail(err, cs, "volume outside a hull: the plane of facet %zu: %s", f, cerr.message);
            break;
        }
        nnext = 0;
        for (size_t i = 0; i < ncur; i++) {
            if (!reaches_beyond(&cur[i].mesh, &pl)) {
                if (!push_piece(&next, &nnext, &cnext, cur[i].mesh, cur[i].owned)) {
                    st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for the pieces of a solid");
                    break;
                }
                cur[i].owned = 0; /* moved */
                continue;
            }
            acd_cut_result r;
            cs = acd_plane_cut_flags(&cur[i].mesh, &pl, ACD_PLANE_CUT_DROP_SPECKS, &r, &cerr);
            if (cs != ACD_OK) {
                st = cs == ACD_ERR_NOMEM ? acd_fail(err, cs, "out of memory cutting a solid by its hull's planes: %s",
                                                    cerr.message)
                                         : acd_fail(err, cs, "volume outside a hull: the cut by the plane of facet %zu "
                                                             "(piece %zu of %zu) failed: %s",
                                                    f, i, ncur, cerr.message);
                acd_cut_result_free(&r);
                break;
            }
            for (size_t k = 0; k < r.npieces && st == ACD_OK; k++) {
                if (r.pieces[k].side > 0) {
                    sum += acd_geom3_signed_volume(&r.pieces[k].mesh);
                } else if (push_piece(&next, &nnext, &cnext, r.pieces[k].mesh, 1)) {
                    memset(&r.pieces[k].mesh, 0, sizeof r.pieces[k].mesh); /* moved */
                } else {
                    st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for the pieces of a solid");
                }
            }
            acd_cut_result_free(&r);
            if (cur[i].owned) acd_mesh_free(&cur[i].mesh);
            cur[i].owned = 0;
        }
        /* the pieces inside every plane so far become the current ones (on failure: freed below) */
        piece *t = cur;
        size_t tc = ccur;
        for (size_t i = 0; i < ncur; i++)
            if (cur[i].owned) acd_mesh_free(&cur[i].mesh);
        cur = next, ncur = nnext, ccur = cnext;
        next = t, nnext = 0, cnext = tc;
    }
done:
    pieces_free(cur, ncur);
    pieces_free(next, nnext);
    free(sel);
    if (st == ACD_OK) *outside = sum;
    return st;
}
