/* geom3/hull_outside: the volume of a closed solid outside a convex hull, exactly up to rounding,
 * by cutting the solid with the hull's planes (acd_hull_volume_outside, declared in acd/hull.h).
 *
 * acd_hull_volume_outside_bound (geom3/volume.c) sums the solid's volume beyond each plane the
 * solid sticks out of, so a region beyond two planes (where the caps of two cuts of a trimmed hull
 * overlap) counts twice. Here the region outside is taken off piece by piece: after the cuts by
 * planes 1..j the pieces left lie on the inner side of each of them, and what plane j + 1 cuts off
 * them lies beyond it and inside the earlier ones, so no region is counted twice. The sides are the
 * plane cut's (acd_orient3d against three points of the plane: exact). A solid the cut refuses but
 * closed as a chain of triangles (pinched by the rounding back to model coordinates, crossing
 * itself) is measured tetrahedron by tetrahedron instead (volume_outside_tets, below). */
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

/* ---- the fallback: tetrahedron by tetrahedron ----
 *
 * For a closed triangle mesh m and any point o, the winding number of m at x is the sum over m's
 * triangles t of sign(t) x [x in the tetrahedron (o, t)] (sign: the tetrahedron's orientation), so the
 * (signed) volume of m in a region R is the sum of sign(t) x volume((o, t) inside R). With R the
 * outside of K (the intersection of the selected planes' inner half-spaces) split into the convex
 * regions "beyond plane j, inside planes 1..j-1", each tetrahedron is cut by the planes in turn, the
 * parts beyond plane j taken off and summed, the parts inside kept for the next plane: convex
 * pieces of a convex piece, no topology. It needs only that m is closed as a chain of triangles
 * (every edge used as often in each direction): a solid the rounding back to model coordinates
 * pinched, or one crossing itself, which a plane cut (a closed, consistently oriented manifold)
 * can refuse, is measured all the same, each region weighted by its winding number as every volume
 * here. o: the centroid of the hull's vertices, inside K, so a triangle with no vertex beyond any
 * plane gives a tetrahedron inside K (nothing outside) and is skipped. The sides are the planes'
 * floating-point values (a point on a plane counts inside): a side decided wrongly at a point within
 * rounding of the plane moves a piece of volume within rounding. */

/* The most pieces one triangle's tetrahedron may be cut into (each plane through it splits a piece
 * into at most 3 inside and 3 beyond): beyond it the fallback gives up (the caller's bound). */
#define HULL_OUTSIDE_TET_PIECES_MAX 65536

typedef struct tet {
    double p[4][3];
} tet;

static double tet_volume_abs(const double a[3], const double b[3], const double c[3], const double d[3]) {
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]},
           w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    return fabs(u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0;
}

/* the point of the segment a b where the plane's value goes from sa to sb (of opposite sides) */
static void cross_point(const double a[3], const double b[3], double sa, double sb, double out[3]) {
    const double t = sa / (sa - sb);
    for (int k = 0; k < 3; k++) out[k] = a[k] + t * (b[k] - a[k]);
}

/* The triangular prism (p0 p1 p2; q0 q1 q2) with edges p_i q_i and planar sides, as 3 tetrahedra. */
static void prism_tets(const double *p0, const double *p1, const double *p2, const double *q0, const double *q1,
                       const double *q2, tet out[3]) {
    const double *v[3][4] = {{p0, p1, p2, q0}, {p1, p2, q0, q1}, {p2, q0, q1, q2}};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) memcpy(out[i].p[j], v[i][j], sizeof out[i].p[j]);
}

static void tet_of(const double *a, const double *b, const double *c, const double *d, tet *out) {
    memcpy(out->p[0], a, sizeof out->p[0]), memcpy(out->p[1], b, sizeof out->p[1]);
    memcpy(out->p[2], c, sizeof out->p[2]), memcpy(out->p[3], d, sizeof out->p[3]);
}

/* Tetrahedron x split by the plane q (value s[i] at its vertex i, > 0 beyond; some beyond, some
 * not): the pieces inside into in (*nin, at most 3), the volume beyond returned. */
static double tet_split(const tet *x, const double s[4], tet in[3], int *nin) {
    int I[4], B[4], ni = 0, nb = 0;
    for (int i = 0; i < 4; i++)
        if (s[i] > 0) B[nb++] = i;
        else I[ni++] = i;
    double e[4][4][3]; /* e[i][j]: the crossing on the edge from inside vertex i to beyond vertex j */
    for (int i = 0; i < ni; i++)
        for (int j = 0; j < nb; j++) cross_point(x->p[I[i]], x->p[B[j]], s[I[i]], s[B[j]], e[I[i]][B[j]]);
    tet out[3];
    double beyond = 0;
    if (ni == 1) { /* inside: the corner at I0; beyond: the prism of the other three */
        const int a = I[0];
        tet_of(x->p[a], e[a][B[0]], e[a][B[1]], e[a][B[2]], &in[0]);
        *nin = 1;
        prism_tets(e[a][B[0]], e[a][B[1]], e[a][B[2]], x->p[B[0]], x->p[B[1]], x->p[B[2]], out);
        for (int k = 0; k < 3; k++) beyond += tet_volume_abs(out[k].p[0], out[k].p[1], out[k].p[2], out[k].p[3]);
    } else if (ni == 3) { /* beyond: the corner at B0; inside: the prism of the other three */
        const int b = B[0];
        tet_of(x->p[b], e[I[0]][b], e[I[1]][b], e[I[2]][b], &out[0]);
        beyond = tet_volume_abs(out[0].p[0], out[0].p[1], out[0].p[2], out[0].p[3]);
        prism_tets(e[I[0]][b], e[I[1]][b], e[I[2]][b], x->p[I[0]], x->p[I[1]], x->p[I[2]], in);
        *nin = 3;
    } else { /* two and two: a prism each side */
        const int a = I[0], b = I[1], c = B[0], d = B[1];
        prism_tets(x->p[a], e[a][c], e[a][d], x->p[b], e[b][c], e[b][d], in);
        *nin = 3;
        prism_tets(x->p[c], e[a][c], e[b][c], x->p[d], e[a][d], e[b][d], out);
        for (int k = 0; k < 3; k++) beyond += tet_volume_abs(out[k].p[0], out[k].p[1], out[k].p[2], out[k].p[3]);
    }
    return beyond;
}

static double plane_value(const double *q, const double *v) { return q[0] * v[0] + q[1] * v[1] + q[2] * v[2] + q[3]; }

typedef struct chain_edge {
    uint32_t a, b; /* a < b */
    int dir;       /* +1: used a -> b, -1: b -> a */
} chain_edge;

static int chain_edge_cmp(const void *pa, const void *pb) {
    const chain_edge *x = pa, *y = pb;
    if (x->a != y->a) return x->a < y->a ? -1 : 1;
    if (x->b != y->b) return x->b < y->b ? -1 : 1;
    return x->dir - y->dir;
}

/* Whether m is closed as a chain of triangles: every edge used as often in one direction as in the
 * other (a manifold or not). -1: out of memory. */
static int closed_chain(const acd_mesh *m) {
    const size_t ne = 3 * m->ntriangles;
    chain_edge *e = malloc((ne ? ne : 1) * sizeof *e);
    if (!e) return -1;
    size_t n = 0;
    for (size_t t = 0; t < m->ntriangles; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t u = m->triangles[3 * t + k], v = m->triangles[3 * t + (k + 1) % 3];
            if (u == v) continue;
            e[n++] = u < v ? (chain_edge){u, v, 1} : (chain_edge){v, u, -1};
        }
    qsort(e, n, sizeof *e, chain_edge_cmp);
    int closed = 1;
    for (size_t i = 0, j; i < n && closed; i = j) {
        int sum = 0;
        for (j = i; j < n && e[j].a == e[i].a && e[j].b == e[i].b; j++) sum += e[j].dir;
        closed = sum == 0;
    }
    free(e);
    return closed;
}

/* m's volume outside the planes sel[0..nsel) of h, tetrahedron by tetrahedron (above). ACD_OK;
 * ACD_ERR_NOMEM; ACD_ERR_DEGENERATE when a tetrahedron is cut into more than
 * HULL_OUTSIDE_TET_PIECES_MAX pieces. */
static acd_status volume_outside_tets(const acd_hull *h, const acd_mesh *m, const size_t *sel, size_t nsel,
                                      double *outside, acd_error *err) {
    double o[3] = {0, 0, 0};
    for (size_t v = 0; v < h->nvertices; v++)
        for (int k = 0; k < 3; k++) o[k] += h->vertices[3 * v + k];
    for (int k = 0; k < 3; k++) o[k] /= (double)h->nvertices;
    tet *cur = NULL, *next = NULL;
    size_t cap = 0;
    double sum = 0;
    acd_status st = ACD_OK;
    for (size_t t = 0; t < m->ntriangles && st == ACD_OK; t++) {
        const double *a = m->vertices + 3 * (size_t)m->triangles[3 * t], *b = m->vertices + 3 * (size_t)m->triangles[3 * t + 1],
                     *c = m->vertices + 3 * (size_t)m->triangles[3 * t + 2];
        int reach = 0;
        for (size_t j = 0; j < nsel && !reach; j++) {
            const double *q = h->planes + 4 * sel[j];
            reach = plane_value(q, a) > 0 || plane_value(q, b) > 0 || plane_value(q, c) > 0;
        }
        if (!reach) continue;
        double u[3] = {a[0] - o[0], a[1] - o[1], a[2] - o[2]}, v[3] = {b[0] - o[0], b[1] - o[1], b[2] - o[2]},
               w[3] = {c[0] - o[0], c[1] - o[1], c[2] - o[2]};
        const double det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                           u[2] * (v[0] * w[1] - v[1] * w[0]);
        if (det == 0) continue; /* flat: no volume anywhere */
        const double sign = det > 0 ? 1 : -1;
        if (cap == 0) {
            cap = 64;
            cur = malloc(cap * sizeof *cur), next = malloc(cap * sizeof *next);
            if (!cur || !next) {
                st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for the pieces of a tetrahedron");
                break;
            }
        }
        size_t ncur = 1, nnext;
        tet_of(o, a, b, c, &cur[0]);
        double beyond = 0;
        for (size_t j = 0; j < nsel && ncur > 0 && st == ACD_OK; j++) {
            const double *q = h->planes + 4 * sel[j];
            nnext = 0;
            for (size_t i = 0; i < ncur; i++) {
                double s[4];
                int nb = 0;
                for (int k = 0; k < 4; k++) nb += (s[k] = plane_value(q, cur[i].p[k])) > 0;
                if (nb == 4) {
                    beyond += tet_volume_abs(cur[i].p[0], cur[i].p[1], cur[i].p[2], cur[i].p[3]);
                    continue;
                }
                if (nnext + 3 > cap) {
                    if (2 * cap > HULL_OUTSIDE_TET_PIECES_MAX) {
                        st = acd_fail(err, ACD_ERR_DEGENERATE,
                                      "triangle %zu's tetrahedron is cut into more than %d pieces", t,
                                      HULL_OUTSIDE_TET_PIECES_MAX);
                        break;
                    }
                    tet *c1 = realloc(cur, 2 * cap * sizeof *c1);
                    if (c1) cur = c1;
                    tet *c2 = c1 ? realloc(next, 2 * cap * sizeof *c2) : NULL;
                    if (c2) next = c2;
                    if (!c1 || !c2) {
                        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for the pieces of a tetrahedron");
                        break;
                    }
                    cap *= 2;
                }
                if (nb == 0) {
                    next[nnext++] = cur[i];
                    continue;
                }
                int nin = 0;
                beyond += tet_split(&cur[i], s, next + nnext, &nin);
                nnext += (size_t)nin;
            }
            tet *sw = cur;
            cur = next, next = sw;
            ncur = nnext;
        }
        sum += sign * beyond;
    }
    free(cur);
    free(next);
    if (st == ACD_OK) *outside = sum;
    return st;
}

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
    /* a cut that failed (not for memory) on a solid closed as a chain of triangles (a piece pinched by
     * the rounding, or crossing itself): the whole solid again, tetrahedron by tetrahedron, which needs
     * no manifold (volume_outside_tets); on an open or misoriented one, or where that too gives up,
     * the cut's failure */
    if (st != ACD_OK && st != ACD_ERR_NOMEM) {
        const int closed = closed_chain(m);
        acd_error terr;
        double tv = NAN;
        acd_status ts = closed < 0 ? ACD_ERR_NOMEM : closed ? volume_outside_tets(h, m, sel, nsel, &tv, &terr) : st;
        if (ts == ACD_OK) st = ACD_OK, sum = tv;
        else if (ts == ACD_ERR_NOMEM) st = acd_fail(err, ACD_ERR_NOMEM, "out of memory measuring a solid outside a hull");
    }
    free(sel);
    if (st == ACD_OK) *outside = sum;
    return st;
}
