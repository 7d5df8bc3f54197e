/* geom3/plane_cut: closed mesh split by a plane into closed pieces with capped cross-sections.
 *
 * Solid ACD's cut (Lien D §V.B.3, P §4.3; capping as in spec acd3d.md §5.3 after Chazelle, D §II.B.2):
 *   1. every vertex gets its exact side s in {-1, 0, +1}: acd_orient3d against the plane's points;
 *   2. every edge with s = +1 at one end and -1 at the other gets one new vertex (interpolated with
 *      the orient3d values, always from its lower-index end, so both triangles share it);
 *   3. every triangle goes whole to the side of its non-zero vertices, or is split into a triangle
 *      and a triangle or quad (fanned) on each side; a triangle lying in the plane goes to the side
 *      opposite its outward normal (decided by exact orient2d in the plane's projection);
 *   4. the boundary of the + side's faces consists of edges in the plane; it is traced into loops
 *      (at a vertex with several outgoing edges, the first one clockwise from the incoming edge, which
 *      keeps touching loops apart), loops are classified by signed area in the plane's 2D frame
 *      (counterclockwise seen from +normal: outer; clockwise: hole), each hole goes to the smallest
 *      outer loop containing it (exact point-in-polygon), and each region is triangulated by
 *      geom2/triangulate (hole bridging + ear clipping); the triangles close the - side as they are
 *      and the + side reversed, so the caps cancel exactly and volume is conserved;
 *   5. pieces are the edge-connected components of each side. */
#include "geom3/plane_cut.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "core/error.h"
#include "core/union_find.h"
#include "core/predicates.h"
#include "geom2/triangulate.h"
#include "geom3/edge_map.h"
#include "geom3/spatial.h"
#include "geom3/vec3.h"
#include "geom3/volume.h"

#define NONE UINT32_MAX


/* fmax's value for x, y >= 0 or NaN (no -0, so no tie between different bits), without the call. */
static inline double fmax_abs(double x, double y) {
    if (x != x) return y;
    if (y != y) return x;
    return x > y ? x : y;
}

/* Euclidean norm without overflow or underflow of the squares (tiny and huge models). */
static double norm3_safe(const double *v) {
    double m = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
    if (!(m > 0) || !isfinite(m)) return m;
    double a = v[0] / m, b = v[1] / m, c = v[2] / m;
    return m * sqrt(a * a + b * b + c * c);
}

acd_status acd_cut_plane_from_points(const double a[3], const double b[3], const double c[3], acd_cut_plane *out,
                                     acd_error *err) {
    memset(out, 0, sizeof *out);
    for (int k = 0; k < 3; k++)
        if (!isfinite(a[k]) || !isfinite(b[k]) || !isfinite(c[k]))
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "cut plane: a non-finite coordinate");
    /* collinear iff all three coordinate projections are (exact) */
    int collinear = 1;
    for (int k = 0; k < 3 && collinear; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        double pa[2] = {a[i], a[j]}, pb[2] = {b[i], b[j]}, pc[2] = {c[i], c[j]};
        if (acd_orient2d_sign(pa, pb, pc) != 0) collinear = 0;
    }
    if (collinear)
        return acd_fail(err, ACD_ERR_DEGENERATE, "cut plane: the points (%g, %g, %g), (%g, %g, %g), (%g, %g, %g) are collinear",
                        a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]);
    memcpy(out->a, a, sizeof out->a);
    memcpy(out->b, b, sizeof out->b);
    memcpy(out->c, c, sizeof out->c);
    /* the normal's components are the projections' orientations: exact signs, adaptive magnitudes,
     * so even a plane through nearly collinear points gets a usable normal */
    double n[3], mx = 0;
    for (int k = 0; k < 3; k++) mx = fmax(mx, fmax(fabs(a[k]), fmax(fabs(b[k]), fabs(c[k]))));
    int e = 0; /* huge or tiny points: orientations of copies scaled by a power of two (exact) */
    if (mx > 1e90 || mx < 1e-90) frexp(mx, &e);
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        double pa[2] = {ldexp(a[i], -e), ldexp(a[j], -e)}, pb[2] = {ldexp(b[i], -e), ldexp(b[j], -e)};
        double pc[2] = {ldexp(c[i], -e), ldexp(c[j], -e)};
        n[k] = acd_orient2d(pa, pb, pc);
    }
    double l = norm3_safe(n);
    if (!(l > 0) || !isfinite(l))
        return acd_fail(err, ACD_ERR_DEGENERATE, "cut plane: the points' scales differ too much for a normal");
    for (int k = 0; k < 3; k++) out->normal[k] = n[k] / l;
    return ACD_OK;
}

acd_status acd_cut_plane_from_normal(const double point[3], const double normal[3], double size, acd_cut_plane *out,
                                     acd_error *err) {
    double l = sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    if (!(l > 0) || !isfinite(l))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "cut plane: normal (%g, %g, %g) has no direction", normal[0],
                        normal[1], normal[2]);
    if (!(size > 0) || !isfinite(size)) size = 1;
    double n[3] = {normal[0] / l, normal[1] / l, normal[2] / l};
    int small = 0; /* axis of the smallest normal component */
    for (int k = 1; k < 3; k++)
        if (fabs(n[k]) < fabs(n[small])) small = k;
    double e[3] = {0, 0, 0}, u[3], w[3];
    e[small] = 1;
    acd_cross3(n, e, u);
    double ul = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int k = 0; k < 3; k++) u[k] /= ul;
    acd_cross3(n, u, w); /* u x w = n |u|^2: the points' orientation gives the normal's side as + */
    double a[3], b[3], c[3];
    for (int k = 0; k < 3; k++) {
        a[k] = point[k];
        b[k] = point[k] + size * u[k];
        c[k] = point[k] + size * w[k];
    }
    return acd_cut_plane_from_points(a, b, c, out, err);
}

/* Coordinates this many binary orders below the model's largest are flushed to zero. */
#define PLANE_CUT_FLUSH_BITS 200

static double flush_tiny(double x, double below) { return fabs(x) < below ? 0.0 : x; }

int acd_cut_plane_side(const acd_cut_plane *pl, const double v[3]) {
    double mx = 0;
    for (int k = 0; k < 3; k++) mx = fmax(mx, fmax(fmax(fabs(pl->a[k]), fabs(v[k])), fmax(fabs(pl->b[k]), fabs(pl->c[k]))));
    int e = 0; /* as in acd_plane_cut: huge or tiny coordinates scaled by a power of two first, */
    if (mx > 1e90 || mx < 1e-90) frexp(mx, &e);
    double fl = ldexp(mx, -e - PLANE_CUT_FLUSH_BITS); /* and tiny coordinates flushed */
    double a[3], b[3], c[3], w[3];
    for (int k = 0; k < 3; k++) {
        a[k] = flush_tiny(ldexp(pl->a[k], -e), fl);
        b[k] = flush_tiny(ldexp(pl->b[k], -e), fl);
        c[k] = flush_tiny(ldexp(pl->c[k], -e), fl);
        w[k] = flush_tiny(ldexp(v[k], -e), fl);
    }
    /* orient3d > 0 when v is below the plane of a, b, c (counterclockwise seen from above) */
    return -acd_orient3d_sign(a, b, c, w);
}

acd_status acd_cut_result_check_closed(const acd_cut_result *r) {
    for (size_t p = 0; p < r->npieces; p++) {
        const acd_mesh *pm = &r->pieces[p].mesh;
        if (r->pieces[p].closed) continue;
        acd_status es = acd_edge_map_closed(pm->triangles, pm->ntriangles, NULL, NULL);
        if (es != ACD_OK) return es;
    }
    return ACD_OK;
}

void acd_cut_result_free(acd_cut_result *r) {
    if (!r) return;
    for (size_t i = 0; i < r->npieces; i++) {
        acd_mesh_free(&r->pieces[i].mesh);
        free(r->pieces[i].is_cap);
        free(r->pieces[i].source);
    }
    free(r->pieces);
    memset(r, 0, sizeof *r);
}

/* ---------- working state ---------- */

typedef struct cut_ctx {
    const acd_cut_plane *pl;
    double *V; /* vertex coordinates: input vertices, then crossing points */
    uint32_t *src;
    size_t nv, capv;
    uint32_t *T; /* triangles */
    int8_t *tside;
    uint8_t *tcap;
    size_t nt, capt;
    int ax, swap; /* 2D frame: drop axis ax; swap the two others when the normal's ax component < 0 */
    int scale_exp;          /* working coordinates are the input's times 2^scale_exp (exact) */
    const double *orig;     /* the input vertices */
    unsigned flags;         /* ACD_PLANE_CUT_* */
    acd_error *err;
    /* the input's half-edges paired (side_map): itw[h], the input half-edge opposite h; per input
     * triangle t, wside[t] its side when it went whole to one (its one triangle tout[t]), 0 when
     * split (its triangles tout[t] .. tout[t + 1]); ncut: the triangles before the caps */
    const uint32_t *itw;
    int8_t *wside;
    uint32_t *tout;
    size_t nin, ncut;
} cut_ctx;

/* The triangles' room doubled (push_tri, when full). */
static acd_status grow_tris(cut_ctx *c) {
    size_t nc = c->capt ? 2 * c->capt : 64;
    uint32_t *T = realloc(c->T, nc * 3 * sizeof *T);
    if (!T) return acd_fail(c->err, ACD_ERR_NOMEM, "out of memory for %zu cut triangles", nc);
    c->T = T;
    int8_t *s = realloc(c->tside, nc * sizeof *s);
    if (!s) return acd_fail(c->err, ACD_ERR_NOMEM, "out of memory for %zu cut triangles", nc);
    c->tside = s;
    uint8_t *cp = realloc(c->tcap, nc * sizeof *cp);
    if (!cp) return acd_fail(c->err, ACD_ERR_NOMEM, "out of memory for %zu cut triangles", nc);
    c->tcap = cp;
    c->capt = nc;
    return ACD_OK;
}

static inline acd_status push_tri(cut_ctx *c, uint32_t a, uint32_t b, uint32_t d, int side, int cap) {
    if (c->nt == c->capt) {
        acd_status st = grow_tris(c);
        if (st != ACD_OK) return st;
    }
    c->T[3 * c->nt] = a;
    c->T[3 * c->nt + 1] = b;
    c->T[3 * c->nt + 2] = d;
    c->tside[c->nt] = (int8_t)side;
    c->tcap[c->nt] = (uint8_t)cap;
    c->nt++;
    return ACD_OK;
}

static void proj2(const cut_ctx *c, uint32_t v, double out[2]) {
    int i = (c->ax + 1) % 3, j = (c->ax + 2) % 3;
    const double *p = c->V + 3 * (size_t)v;
    out[0] = c->swap ? p[j] : p[i];
    out[1] = c->swap ? p[i] : p[j];
}

/* Monotone pseudo-angle of a 2D direction in [0, 4). */
static double pseudo_angle(double dx, double dy) {
    double s = fabs(dx) + fabs(dy);
    if (s == 0) return 0;
    double p = dy / s;
    if (dx < 0) return 2 - p;
    if (dy < 0) return 4 + p;
    return p;
}

/* Exact point-in-polygon by winding number (orient2d); 1 inside, 0 outside, -1 on the boundary. */
static int point_in_loop(const double q[2], const double (*P)[2], size_t n) {
    int wn = 0;
    for (size_t i = 0; i < n; i++) {
        const double *a = P[i], *b = P[(i + 1) % n];
        if (acd_point_on_segment(q, a, b)) return -1;
        if (a[1] <= q[1]) {
            if (b[1] > q[1] && acd_orient2d_sign(a, b, q) > 0) wn++;
        } else if (b[1] <= q[1] && acd_orient2d_sign(a, b, q) < 0) {
            wn--;
        }
    }
    return wn != 0;
}

typedef struct loop_info {
    size_t start, len; /* in the loop vertex list */
    double area;       /* signed, 2D frame */
    size_t outer;      /* for holes: the containing outer loop, NONE if none */
} loop_info;

static int cmp_u64(const void *x, const void *y) {
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return (a > b) - (a < b);
}

/* +1 if every ring edge (k, k+1) of the region (local point indices, rings in rs) is an edge of
 * the triangles in that direction, -1 if every one is there reversed, 0 otherwise. */
static int region_direction(const size_t *tris, size_t ntris, const size_t *rs, size_t nr) {
    uint64_t *keys = malloc((ntris ? ntris : 1) * 3 * sizeof *keys);
    if (!keys) return 0;
    for (size_t t = 0; t < ntris; t++)
        for (int i = 0; i < 3; i++)
            keys[3 * t + i] = ((uint64_t)tris[3 * t + i] << 32) | (uint64_t)tris[3 * t + (i + 1) % 3];
    qsort(keys, 3 * ntris, sizeof *keys, cmp_u64);
    int fwd = 1, rev = 1;
    for (size_t q = 0; q < nr; q++)
        for (size_t k = rs[q]; k < rs[q + 1]; k++) {
            uint64_t a = k, b = k + 1 < rs[q + 1] ? k + 1 : rs[q];
            uint64_t kf = (a << 32) | b, kr = (b << 32) | a;
            if (!bsearch(&kf, keys, 3 * ntris, sizeof *keys, cmp_u64)) fwd = 0;
            if (!bsearch(&kr, keys, 3 * ntris, sizeof *keys, cmp_u64)) rev = 0;
        }
    free(keys);
    return fwd ? 1 : (rev ? -1 : 0);
}

/* The half-edges of one side's triangles (tside == side, caps included when there are) in two sets.
 * Regular: a half-edge a -> b of an input triangle t that went whole to the side, whose opposite
 * input half-edge (itw) is of a triangle u that went whole to it too, and (capv not NULL: the caps
 * are there) a or b no cap vertex. Its key occurs once among the side's half-edges and so does
 * the reverse (u's): no other whole triangle has them (the input's map is closed: keys unique),
 * a split triangle's pieces have its own input edges (in their direction) or a point made on an
 * edge, and a cap's edges join two cap vertices. Such a pair is each other's twin, and joins t's
 * and u's triangles (parent not NULL: acd_uf_union). The others (special): collected into *sm in
 * the order acd_edge_map_build gives over the side's triangles, with their twins *stw (as
 * acd_edge_map_twins). Every half-edge with the key or the reverse key of a special one is
 * special (a regular one's pair is all of its two keys), so *sm and *stw agree with the side's
 * whole map and twins on them: the same twins, repeats and boundary. */
static acd_status side_map(cut_ctx *c, int side, const uint8_t *capv, uint32_t *parent, acd_edge_map *sm,
                           uint32_t **stw) {
    memset(sm, 0, sizeof *sm);
    *stw = NULL;
    size_t cap = 256, n = 0;
    uint64_t *key = malloc(cap * sizeof *key);
    uint32_t *half = malloc(cap * sizeof *half);
    int ok = key && half;
#define SIDE_PUSH(k_, h_)                                                                                            \
    do {                                                                                                               \
        if (n == cap) {                                                                                                \
            cap *= 2;                                                                                                  \
            uint64_t *k2 = realloc(key, cap * sizeof *key);                                                            \
            if (k2) key = k2;                                                                                          \
            uint32_t *h2 = k2 ? realloc(half, cap * sizeof *half) : NULL;                                              \
            if (h2) half = h2;                                                                                         \
            if (!k2 || !h2) ok = 0;                                                                                    \
        }                                                                                                              \
        if (ok) key[n] = (k_), half[n] = (h_), n++;                                                                    \
    } while (0)
    const uint32_t *T = c->T;
    for (size_t t = 0; t < c->nin && ok; t++) {
        int ws = c->wside[t];
        if (ws == side) {
            uint32_t o = c->tout[t];
            const uint32_t *q = T + 3 * (size_t)o;
            for (int i = 0; i < 3; i++) {
                uint32_t a = q[i], b = q[i == 2 ? 0 : i + 1];
                uint32_t u = c->itw[3 * t + (size_t)i] / 3;
                if (c->wside[u] == side && !(capv && capv[a] && capv[b])) {
                    if (parent && o < c->tout[u]) acd_uf_union(parent, o, c->tout[u]);
                } else {
                    SIDE_PUSH(((uint64_t)a << 32) | b, 3 * o + (uint32_t)i);
                }
            }
        } else if (ws == 0) {
            for (uint32_t o = c->tout[t]; o < c->tout[t + 1]; o++) {
                if (c->tside[o] != side) continue;
                const uint32_t *q = T + 3 * (size_t)o;
                for (int i = 0; i < 3; i++) SIDE_PUSH(((uint64_t)q[i] << 32) | q[i == 2 ? 0 : i + 1], 3 * o + (uint32_t)i);
            }
        }
    }
    for (size_t o = c->ncut; o < c->nt && ok; o++) {
        if (c->tside[o] != side) continue;
        const uint32_t *q = T + 3 * o;
        for (int i = 0; i < 3; i++) SIDE_PUSH(((uint64_t)q[i] << 32) | q[i == 2 ? 0 : i + 1], (uint32_t)(3 * o) + (uint32_t)i);
    }
#undef SIDE_PUSH
    if (!ok) {
        free(key);
        free(half);
        return acd_fail(c->err, ACD_ERR_NOMEM, "out of memory for the cut's half-edges");
    }
    sm->key = key;
    sm->half = half;
    sm->n = n;
    acd_status st = acd_edge_map_sort(sm, c->err);
    if (st == ACD_OK) st = acd_edge_map_twins(sm, stw, c->err);
    if (st != ACD_OK) acd_edge_map_free(sm);
    return st;
}

/* Traces the + side boundary into loops, caps both sides. */
static acd_status cap_sections(cut_ctx *c, acd_cut_result *res) {
    acd_error *err = c->err;
    /* boundary half-edges of the + side (those without a twin: all among side_map's special
     * ones), sorted by (from, to) since its map is */
    acd_edge_map pm;
    uint32_t *ptw = NULL;
    acd_status st = side_map(c, +1, NULL, NULL, &pm, &ptw);
    if (st != ACD_OK) return st;
    size_t nb = 0;
    uint32_t *bfrom = malloc((pm.n ? pm.n : 1) * sizeof *bfrom), *bto = malloc((pm.n ? pm.n : 1) * sizeof *bto);
    if (!bfrom || !bto) {
        free(bfrom);
        free(bto);
        free(ptw);
        acd_edge_map_free(&pm);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for the section boundary");
    }
    for (size_t i = 0; i < pm.n; i++) {
        uint32_t a = (uint32_t)(pm.key[i] >> 32), b = (uint32_t)pm.key[i];
        if (ptw[i] == ACD_EDGE_NONE) {
            bfrom[nb] = a;
            bto[nb] = b;
            nb++;
        }
    }
    free(ptw);
    acd_edge_map_free(&pm);
    if (nb == 0) {
        free(bfrom);
        free(bto);
        return ACD_OK;
    }
    uint8_t *used = calloc(nb, 1);
    uint32_t *lv = malloc((nb + 1) * sizeof *lv); /* loop vertices, loops one after the other */
    loop_info *loops = malloc(nb * sizeof *loops);
    double(*P)[2] = malloc((nb + 1) * sizeof *P);
    if (!used || !lv || !loops || !P) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for %zu section edges", nb);
        goto done;
    }
    size_t nloops = 0, nlv = 0;
    for (size_t e0 = 0; e0 < nb; e0++) {
        if (used[e0]) continue;
        size_t e = e0, start = nlv;
        for (;;) {
            used[e] = 1;
            lv[nlv++] = bfrom[e];
            uint32_t u = bfrom[e], v = bto[e];
            /* outgoing edges of v: a run in the sorted arrays (binary search) */
            size_t lo = 0, hi = nb;
            while (lo < hi) {
                size_t mid = lo + (hi - lo) / 2;
                if (bfrom[mid] < v)
                    lo = mid + 1;
                else
                    hi = mid;
            }
            size_t best = NONE;
            double bestang = 0, pu[2], pv[2];
            proj2(c, u, pu);
            proj2(c, v, pv);
            double ref = pseudo_angle(pu[0] - pv[0], pu[1] - pv[1]);
            for (size_t k = lo; k < nb && bfrom[k] == v; k++) {
                if (used[k] && k != e0) continue;
                double pw[2];
                proj2(c, bto[k], pw);
                double ang = ref - pseudo_angle(pw[0] - pv[0], pw[1] - pv[1]); /* clockwise from v->u */
                while (ang <= 0) ang += 4;
                while (ang > 4) ang -= 4;
                if (best == NONE || ang < bestang) best = k, bestang = ang;
            }
            if (best == NONE) {
                st = acd_fail(err, ACD_ERR_INTERNAL, "plane cut: section loop broken at vertex %u (no outgoing edge)", v);
                goto done;
            }
            if (best == e0) break;
            e = best;
            if (nlv > nb) {
                st = acd_fail(err, ACD_ERR_INTERNAL, "plane cut: section loop does not close");
                goto done;
            }
        }
        loops[nloops].start = start;
        loops[nloops].len = nlv - start;
        loops[nloops].outer = NONE;
        double a2 = 0;
        for (size_t i = 0; i < nlv - start; i++) {
            double p[2], q[2];
            proj2(c, lv[start + i], p);
            proj2(c, lv[start + (i + 1) % (nlv - start)], q);
            a2 += p[0] * q[1] - q[0] * p[1];
        }
        loops[nloops].area = 0.5 * a2;
        nloops++;
    }
    res->nloops += nloops;
    /* holes to their smallest containing outer loop */
    for (size_t h = 0; h < nloops; h++) {
        if (!(loops[h].area < 0)) continue;
        size_t best = NONE;
        for (size_t o = 0; o < nloops; o++) {
            if (!(loops[o].area > 0)) continue;
            if (best != NONE && loops[o].area >= loops[best].area) continue;
            for (size_t i = 0; i < loops[o].len; i++) proj2(c, lv[loops[o].start + i], P[i]);
            int inside = -1;
            for (size_t i = 0; i < loops[h].len && inside < 0; i++) { /* a hole vertex not on the outer loop */
                double q[2];
                proj2(c, lv[loops[h].start + i], q);
                inside = point_in_loop(q, (const double(*)[2])P, loops[o].len);
            }
            if (inside < 0) { /* every vertex on it: try an edge midpoint */
                double q[2], r[2];
                proj2(c, lv[loops[h].start], q);
                proj2(c, lv[loops[h].start + 1], r);
                double mid[2] = {0.5 * (q[0] + r[0]), 0.5 * (q[1] + r[1])};
                inside = point_in_loop(mid, (const double(*)[2])P, loops[o].len) != 0;
            }
            if (inside) best = o;
        }
        loops[h].outer = best;
    }
    /* triangulate each region: an outer loop (or an orphan loop) with its holes */
    for (size_t o = 0; o < nloops; o++) {
        if (loops[o].area < 0 && loops[o].outer != NONE) continue; /* a hole: with its outer loop */
        size_t nr = 1, npts = loops[o].len;
        for (size_t h = 0; h < nloops; h++)
            if (h != o && loops[h].outer == o) nr++, npts += loops[h].len;
        acd_vec2 *pts = malloc(npts * sizeof *pts);
        uint32_t *pid = malloc(npts * sizeof *pid);
        size_t *rs = malloc((nr + 1) * sizeof *rs);
        if (!pts || !pid || !rs) {
            free(pts);
            free(pid);
            free(rs);
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for a section region of %zu points", npts);
            goto done;
        }
        size_t k = 0, r = 0;
        for (size_t h = NONE;;) { /* the outer ring first, then its holes in loop order */
            size_t cur = h == NONE ? o : h;
            if (h == NONE || (h != o && loops[h].outer == o)) {
                rs[r++] = k;
                for (size_t i = 0; i < loops[cur].len; i++) {
                    double p[2];
                    uint32_t v = lv[loops[cur].start + i];
                    proj2(c, v, p);
                    pts[k].x = p[0];
                    pts[k].y = p[1];
                    pid[k] = v;
                    k++;
                }
            }
            h = h == NONE ? 0 : h + 1;
            if (h >= nloops) break;
        }
        rs[r] = k;
        size_t *tris = NULL, ntris = 0, nforced = 0;
        st = acd_triangulate_rings(pts, rs, r, ACD_TRI_BEST_EFFORT, &tris, &ntris, NULL, &nforced, err);
        if (st != ACD_OK) {
            free(pts);
            free(pid);
            free(rs);
            goto done;
        }
        res->nforced += nforced;
        res->nregions++;
        /* the - cap must run along every loop edge in the loop's direction (so it pairs with the
         * - faces); if rounding made the rings self-touching so that no consistent triangulation came
         * out, fan each ring: combinatorially closed with the exact signed area, but overlapping */
        int dir = region_direction(tris, ntris, rs, r);
        if (dir == 0) {
            free(tris);
            ntris = 0;
            for (size_t q = 0; q < r; q++) ntris += rs[q + 1] - rs[q] - 2;
            tris = malloc((ntris ? ntris : 1) * 3 * sizeof *tris);
            if (!tris) {
                free(pts);
                free(pid);
                free(rs);
                st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for a section fan");
                goto done;
            }
            size_t w = 0;
            for (size_t q = 0; q < r; q++)
                for (size_t i = rs[q] + 1; i + 1 < rs[q + 1]; i++, w++) {
                    tris[3 * w] = rs[q];
                    tris[3 * w + 1] = i;
                    tris[3 * w + 2] = i + 1;
                }
            res->nforced++;
            dir = 1;
        }
        int flip = dir < 0;
        for (size_t t = 0; t < ntris && st == ACD_OK; t++) {
            uint32_t a = pid[tris[3 * t]], b = pid[tris[3 * t + 1]], d = pid[tris[3 * t + 2]];
            if (flip) {
                uint32_t x = b;
                b = d;
                d = x;
            }
            const double *pa = c->V + 3 * (size_t)a, *pb = c->V + 3 * (size_t)b, *pd = c->V + 3 * (size_t)d;
            double e1[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]}, e2[3] = {pd[0] - pa[0], pd[1] - pa[1], pd[2] - pa[2]};
            double cr[3];
            acd_cross3(e1, e2, cr);
            res->section_area += 0.5 * norm3_safe(cr);
            st = push_tri(c, a, b, d, -1, 1); /* - side: outward along +normal */
            if (st == ACD_OK) st = push_tri(c, a, d, b, +1, 1);
        }
        free(tris);
        free(pts);
        free(pid);
        free(rs);
        if (st != ACD_OK) goto done;
    }
done:
    free(used);
    free(lv);
    free(loops);
    free(P);
    free(bfrom);
    free(bto);
    return st;
}

/* A shell whose mean thickness (signed volume over half its area) is below this fraction of the
 * mesh's bounding-box diagonal encloses nothing but rounding: a flattened sheet, two coincident
 * layers, left where the plane runs through coplanar faces or exactly through vertices of a part
 * that was already cut there. It is neither a piece nor a cavity: it is dropped (its
 * volume is zero, so the pieces' volumes still add up). Taken as a cavity, such a sheet of
 * volume -1e-20 used to join a real piece, which then self-intersected and could not be cut
 * again (a part left above tau). */
#define ACD_PLANE_CUT_FLAT_REL 1e-12

/* A shell's signed volume is a sum of triple products a.(b x d)/6 from the box centre; the
 * rounding error of each is bounded by a small multiple of DBL_EPSILON times |a||b||d|/6. A shell
 * of negative volume within that bound, inside a piece, is no cavity but a speck of rounding and
 * is dropped: four faces of area 1e-33 left where a plane runs through nearly coincident section
 * points (CGAL's spool.off) measured volume -3e-22 against the box centre, far above the
 * thickness bound of their area, and were joined to a piece as a cavity, which then
 * self-intersected and stayed above tau. (Specks inside no piece, and positive ones, stay
 * pieces, so acd3/decompose's sliver rule refuses such cuts as before: accepting them changed
 * the armadillo's decomposition, 39 -> 53 parts at the target tau.) */
#define ACD_PLANE_CUT_VOLUME_ROUNDING (64.0 * DBL_EPSILON)

/* Shells of negative volume (cavities: inward-facing surfaces) join the smallest shell of positive
 * volume on the same side that contains them (exact ray winding number of one of their vertices
 * not on that shell's surface). flat[root] is set for the flat shells (ACD_PLANE_CUT_FLAT_REL),
 * which join nothing. */
static acd_status group_cavities(cut_ctx *c, uint32_t *parent, uint8_t *flat) {
    acd_error *err = c->err;
    size_t nt = c->nt;
    double *vol = calloc(nt ? nt : 1, sizeof *vol), *area = calloc(nt ? nt : 1, sizeof *area);
    double *avol = calloc(nt ? nt : 1, sizeof *avol); /* sum of |a||b||d|/6: rounding scale */
    if (!vol || !area || !avol) {
        free(vol);
        free(area);
        free(avol);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory grouping cavities");
    }
    double lo[3], hi[3], o[3];
    for (size_t v = 0; v < c->nv; v++)
        for (int k = 0; k < 3; k++) {
            double x = c->V[3 * v + k];
            if (v == 0 || x < lo[k]) lo[k] = x;
            if (v == 0 || x > hi[k]) hi[k] = x;
        }
    for (int k = 0; k < 3; k++) o[k] = c->nv ? lo[k] + 0.5 * (hi[k] - lo[k]) : 0;
    size_t nneg = 0;
    for (size_t t = 0; t < nt; t++) {
        const double *p[3];
        for (int i = 0; i < 3; i++) p[i] = c->V + 3 * (size_t)c->T[3 * t + i];
        double a[3], b[3], d[3], bd[3];
        for (int k = 0; k < 3; k++) a[k] = p[0][k] - o[k], b[k] = p[1][k] - o[k], d[k] = p[2][k] - o[k];
        acd_cross3(b, d, bd);
        double tv = (a[0] * bd[0] + a[1] * bd[1] + a[2] * bd[2]) / 6.0;
        uint32_t r = acd_uf_find(parent, (uint32_t)t);
        vol[r] += tv;
        double e1[3], e2[3], nn[3];
        for (int k = 0; k < 3; k++) e1[k] = p[1][k] - p[0][k], e2[k] = p[2][k] - p[0][k];
        acd_cross3(e1, e2, nn);
        area[r] += 0.5 * (fabs(nn[0]) + fabs(nn[1]) + fabs(nn[2])); /* for now a bound (below) */
    }
    double diag = 0;
    for (int k = 0; k < 3; k++) diag += c->nv ? (hi[k] - lo[k]) * (hi[k] - lo[k]) : 0;
    diag = sqrt(diag);
    /* the shells' areas, needed only to tell a flat shell (|volume| at most FLAT_REL x diag x half
     * the area): area[r] holds a sum of the triangles' half L1 norms of the cross products, at
     * least the Euclidean norms' sum; a shell whose |volume| is above the threshold for twice that
     * (beyond any rounding of the two sums) is not flat, and its area stays 0 (so the threshold,
     * 0, says not flat again below). The others' areas are summed exactly as before, in a second
     * pass in the same triangle order (the same sums). */
    int need_area = 0;
    for (size_t t = 0; t < nt; t++) {
        if (parent[t] != t) continue;
        double thr = ACD_PLANE_CUT_FLAT_REL * diag * 0.5 * (2.0 * area[t]);
        if (fabs(vol[t]) > thr) {
            area[t] = 0;
        } else {
            area[t] = -1; /* marks a shell measured again */
            need_area = 1;
        }
    }
    if (need_area) {
        for (size_t t = 0; t < nt; t++)
            if (parent[t] == t && area[t] < 0) area[t] = 0;
            else if (parent[t] == t) area[t] = -2; /* decided: not flat */
        for (size_t t = 0; t < nt; t++) {
            uint32_t r = acd_uf_find(parent, (uint32_t)t);
            if (area[r] < -1) continue;
            const double *p[3];
            for (int i = 0; i < 3; i++) p[i] = c->V + 3 * (size_t)c->T[3 * t + i];
            double e1[3], e2[3], nn[3];
            for (int k = 0; k < 3; k++) e1[k] = p[1][k] - p[0][k], e2[k] = p[2][k] - p[0][k];
            acd_cross3(e1, e2, nn);
            double big = fmax_abs(fabs(nn[0]), fmax_abs(fabs(nn[1]), fabs(nn[2]))); /* no overflow in the squares */
            if (big > 0) area[r] += 0.5 * big * sqrt((nn[0] / big) * (nn[0] / big) + (nn[1] / big) * (nn[1] / big) +
                                                     (nn[2] / big) * (nn[2] / big));
        }
        for (size_t t = 0; t < nt; t++)
            if (parent[t] == t && area[t] < -1) area[t] = 0;
    }
    /* the rounding scales, needed only for the specks dropped (DROP_SPECKS) and the cavities (a shell
     * of negative volume that is not flat): a second pass in the same order (the same sums) */
    int need_avol = (c->flags & ACD_PLANE_CUT_DROP_SPECKS) != 0;
    for (size_t t = 0; t < nt && !need_avol; t++) {
        double thr = ACD_PLANE_CUT_FLAT_REL * diag * 0.5 * area[t];
        int fl = parent[t] == t && isfinite(thr) && !(fabs(vol[t]) > thr);
        need_avol = parent[t] == t && !fl && vol[t] < 0;
    }
    for (size_t t = 0; t < nt && need_avol; t++) {
        const double *p[3];
        for (int i = 0; i < 3; i++) p[i] = c->V + 3 * (size_t)c->T[3 * t + i];
        double a[3], b[3], d[3];
        for (int k = 0; k < 3; k++) a[k] = p[0][k] - o[k], b[k] = p[1][k] - o[k], d[k] = p[2][k] - o[k];
        double aa = a[0] * a[0] + a[1] * a[1] + a[2] * a[2], bb = b[0] * b[0] + b[1] * b[1] + b[2] * b[2],
               dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], ab = aa * bb;
        /* the product of the squares is the sixth power of the size: it overflows beyond ~1e51
         * (the budget pass then found no cut at all); the product of the norms does not (same
         * value up to rounding, used only where the other would overflow) */
        avol[acd_uf_find(parent, (uint32_t)t)] +=
            (ab <= DBL_MAX / dd || dd == 0 ? sqrt(ab * dd) : sqrt(aa) * sqrt(bb) * sqrt(dd)) / 6.0;
    }
    for (size_t t = 0; t < nt; t++) {
        /* (a threshold that overflows decides nothing: such a shell is kept) */
        double thr = ACD_PLANE_CUT_FLAT_REL * diag * 0.5 * area[t];
        flat[t] = parent[t] == t && isfinite(thr) && !(fabs(vol[t]) > thr);
        /* DROP_SPECKS: every shell whose volume is within rounding is dropped too (without it,
         * only the negative ones that a shell contains are, below; the others stay pieces, and
         * acd3/decompose's sliver rule refuses the cut, as before) */
        if (!flat[t] && parent[t] == t && (c->flags & ACD_PLANE_CUT_DROP_SPECKS) &&
            fabs(vol[t]) <= ACD_PLANE_CUT_VOLUME_ROUNDING * avol[t])
            flat[t] = 1;
        if (flat[t]) vol[t] = 0; /* neither a piece nor a cavity */
    }
    free(area);
    for (size_t t = 0; t < nt; t++)
        if (parent[t] == t && vol[t] < 0) nneg++;
    if (nneg == 0) {
        free(vol);
        free(avol);
        return ACD_OK;
    }
    /* triangles grouped by component root */
    uint32_t *order = malloc(nt * sizeof *order), *start = calloc(nt + 1, sizeof *start), *root = malloc(nt * sizeof *root);
    acd_spatial *sp = calloc(nt, sizeof *sp);
    uint8_t *built = calloc(nt, 1);
    uint32_t *merge = malloc(nt * sizeof *merge);
    acd_status st = ACD_OK;
    if (!order || !start || !root || !sp || !built || !merge) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory grouping cavities");
        goto out;
    }
    for (size_t t = 0; t < nt; t++) {
        root[t] = acd_uf_find(parent, (uint32_t)t);
        start[root[t] + 1]++;
        merge[t] = NONE;
    }
    for (size_t t = 0; t < nt; t++) start[t + 1] += start[t];
    {
        uint32_t *fill = calloc(nt, sizeof *fill);
        if (!fill) {
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory grouping cavities");
            goto out;
        }
        for (size_t t = 0; t < nt; t++) order[start[root[t]] + fill[root[t]]++] = (uint32_t)t;
        free(fill);
    }
    uint32_t *tris = malloc(3 * nt * sizeof *tris); /* triangles copied in root order */
    if (!tris) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory grouping cavities");
        goto out;
    }
    for (size_t i = 0; i < nt; i++) memcpy(tris + 3 * i, c->T + 3 * (size_t)order[i], 3 * sizeof *tris);
    for (size_t n = 0; n < nt && st == ACD_OK; n++) {
        if (parent[n] != n || !(vol[n] < 0)) continue;
        size_t best = NONE;
        for (size_t p = 0; p < nt && st == ACD_OK; p++) {
            if (parent[p] != p || !(vol[p] > 0) || c->tside[p] != c->tside[n]) continue;
            if (best != NONE && vol[p] >= vol[best]) continue;
            if (!built[p]) {
                st = acd_spatial_build(&sp[p], c->V, c->nv, tris + 3 * (size_t)start[p], start[p + 1] - start[p], err);
                if (st != ACD_OK) break;
                built[p] = 1;
            }
            int inside = 0;
            for (size_t i = start[n]; i < start[n + 1]; i++) {
                int on = 0;
                const double *q = c->V + 3 * (size_t)tris[3 * i];
                int w = acd_spatial_ray_winding(&sp[p], q, &on);
                if (on) continue;
                inside = w != 0;
                break;
            }
            if (inside) best = p;
        }
        if (best != NONE && -vol[n] <= ACD_PLANE_CUT_VOLUME_ROUNDING * avol[n]) {
            flat[n] = 1; /* a speck within rounding inside a piece: dropped, not a cavity */
            best = NONE;
        }
        merge[n] = (uint32_t)best;
    }
    free(tris);
    for (size_t n = 0; n < nt; n++)
        if (merge[n] != NONE) acd_uf_union(parent, (uint32_t)n, merge[n]);
out:
    if (sp)
        for (size_t p = 0; p < nt; p++)
            if (built && built[p]) acd_spatial_free(&sp[p]);
    free(sp);
    free(built);
    free(merge);
    free(order);
    free(start);
    free(root);
    free(vol);
    free(avol);
    return st;
}

static acd_status make_pieces(cut_ctx *c, acd_cut_result *res) {
    acd_error *err = c->err;
    uint32_t *parent = malloc((c->nt ? c->nt : 1) * sizeof *parent);
    uint8_t *flat = calloc(c->nt ? c->nt : 1, 1);
    if (!parent || !flat) {
        free(parent);
        free(flat);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for the cut pieces");
    }
    for (size_t t = 0; t < c->nt; t++) parent[t] = (uint32_t)t;
    acd_status st = ACD_OK;
    /* per side: closed as acd_edge_map_check_closed says (its conditions checked here in the walk
     * that joins the twins: every half-edge unique with its opposite present, no triangle repeating
     * a vertex): then so is every piece of that side (a piece is a union of components joined across
     * twins, its vertices renumbered one to one) */
    int closed[2] = {0, 0};
    /* the caps' vertices (side_map: a half-edge between two of them may meet a cap's) */
    uint8_t *capv = calloc(c->nv ? c->nv : 1, 1);
    if (!capv) st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for the cut pieces");
    for (size_t t = c->ncut; t < c->nt && st == ACD_OK; t++)
        for (int i = 0; i < 3; i++) capv[c->T[3 * t + i]] = 1;
    for (int side = 1; side >= -1 && st == ACD_OK; side -= 2) {
        /* the regular half-edges joined and closed (side_map), the special ones here */
        acd_edge_map m;
        uint32_t *tw = NULL;
        st = side_map(c, side, capv, parent, &m, &tw);
        if (st != ACD_OK) break;
        int cl = 1;
        for (size_t i = 0; i < m.n; i++) {
            /* a -> b with a > b, the only one of its key: the first b -> a (its twin) joins the
             * same two triangles (the sets do not depend on the unions' order) */
            int dup = i > 0 && m.key[i - 1] == m.key[i];
            int redundant = (uint32_t)(m.key[i] >> 32) > (uint32_t)m.key[i] && !dup && !acd_edge_map_repeated(&m, i);
            if (tw[i] != ACD_EDGE_NONE && !redundant) acd_uf_union(parent, m.half[i] / 3, tw[i] / 3);
            cl &= acd_edge_map_entry_closed(&m, tw, i);
        }
        for (size_t t = 0; cl && t < c->nt; t++)
            if (c->tside[t] == side) cl = acd_edge_map_triangle_proper(c->T + 3 * t);
        closed[side > 0 ? 0 : 1] = cl;
        free(tw);
        acd_edge_map_free(&m);
    }
    free(capv);
    if (st == ACD_OK) st = group_cavities(c, parent, flat);
    if (st != ACD_OK) {
        free(parent);
        free(flat);
        return st;
    }
    /* pieces: roots in order, + side first */
    uint32_t *pidx = malloc((c->nt ? c->nt : 1) * sizeof *pidx);
    uint32_t *vmap = malloc((c->nv ? c->nv : 1) * sizeof *vmap);
    if (!pidx || !vmap) {
        free(parent);
        free(pidx);
        free(vmap);
        free(flat);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for the cut pieces");
    }
    size_t np = 0;
    for (int side = 1; side >= -1; side -= 2)
        for (size_t t = 0; t < c->nt; t++)
            if (c->tside[t] == side && acd_uf_find(parent, (uint32_t)t) == t) pidx[t] = flat[t] ? NONE : (uint32_t)np++;
    /* each triangle's root, then (below) its piece: parent[t] = the root is a valid compression */
    for (size_t t = 0; t < c->nt; t++) parent[t] = acd_uf_find(parent, (uint32_t)t);
    for (size_t t = 0; t < c->nt; t++) parent[t] = pidx[parent[t]];
    uint32_t *const tpiece = parent;
    for (size_t t = 0; t < c->nt; t++) res->ndropped += tpiece[t] == NONE;
    free(flat);
    res->pieces = calloc(np ? np : 1, sizeof *res->pieces);
    if (!res->pieces) {
        free(parent);
        free(pidx);
        free(vmap);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for %zu cut pieces", np);
    }
    res->npieces = np;
    /* the pieces' triangles in order (a counting sort by piece): ptri[poff[p] .. poff[p + 1]) */
    size_t *poff = calloc(np + 1, sizeof *poff);
    uint32_t *ptri = malloc((c->nt ? c->nt : 1) * sizeof *ptri), *vlist = malloc((c->nv ? c->nv : 1) * sizeof *vlist);
    if (!poff || !ptri || !vlist) st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for %zu cut pieces", np);
    for (size_t t = 0; t < c->nt && st == ACD_OK; t++)
        if (tpiece[t] != NONE) poff[tpiece[t] + 1]++;
    for (size_t p = 0; p < np && st == ACD_OK; p++) poff[p + 1] += poff[p];
    if (st == ACD_OK) {
        size_t *fill = malloc((np ? np : 1) * sizeof *fill);
        if (!fill) st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for %zu cut pieces", np);
        else {
            memcpy(fill, poff, np * sizeof *fill);
            for (size_t t = 0; t < c->nt; t++)
                if (tpiece[t] != NONE) ptri[fill[tpiece[t]]++] = (uint32_t)t;
            free(fill);
        }
    }
    for (size_t p = 0; p < np && st == ACD_OK; p++) {
        acd_cut_piece *pc = &res->pieces[p];
        size_t ntri = poff[p + 1] - poff[p];
        pc->mesh.triangles = malloc(ntri * 3 * sizeof *pc->mesh.triangles);
        pc->is_cap = malloc(ntri ? ntri : 1);
        if (!pc->mesh.triangles || !pc->is_cap) st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for a cut piece");
    }
    /* fill triangles with piece-local vertex ids in order of first use */
    for (size_t v = 0; v < c->nv; v++) vmap[v] = NONE;
    for (size_t p = 0; p < np && st == ACD_OK; p++) {
        acd_cut_piece *pc = &res->pieces[p];
        size_t nv = 0, k = 0;
        for (size_t q = poff[p]; q < poff[p + 1]; q++) {
            size_t t = ptri[q];
            pc->side = c->tside[t];
            for (int i = 0; i < 3; i++) {
                uint32_t v = c->T[3 * t + i];
                if (vmap[v] == NONE) vlist[nv] = v, vmap[v] = (uint32_t)nv++;
                pc->mesh.triangles[3 * k + i] = vmap[v];
            }
            pc->is_cap[k] = c->tcap[t];
            k++;
        }
        pc->mesh.ntriangles = k;
        pc->mesh.nvertices = nv;
        pc->closed = closed[pc->side > 0 ? 0 : 1];
        pc->mesh.vertices = malloc((nv ? nv : 1) * 3 * sizeof(double));
        pc->source = malloc((nv ? nv : 1) * sizeof *pc->source);
        if (!pc->mesh.vertices || !pc->source) {
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for a cut piece of %zu vertices", nv);
            break;
        }
        for (size_t i = 0; i < nv; i++) {
            uint32_t v = vlist[i];
            double *dst = pc->mesh.vertices + 3 * i;
            if (c->src[v] != ACD_CUT_NEW_VERTEX)
                memcpy(dst, c->orig + 3 * (size_t)c->src[v], 3 * sizeof(double));
            else
                for (int k = 0; k < 3; k++) dst[k] = ldexp(c->V[3 * v + k], -c->scale_exp);
            pc->source[i] = c->src[v];
            vmap[v] = NONE;
        }
    }
    free(poff);
    free(ptri);
    free(vlist);
    free(parent);
    free(pidx);
    free(vmap);
    return st;
}

acd_status acd_plane_cut_bodies(const acd_mesh *m, const acd_edge_map *map, acd_cut_result *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    if (!m || m->nvertices == 0)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "bodies: %s", m ? "a mesh without vertices" : "NULL mesh");
    /* the plane x = X with X the next double above the largest x (below the smallest when that
     * overflows): every vertex lies exactly on its negative side (orient3d decides the sides), so
     * the cut's last step alone runs: the side's components, cavities grouped */
    double lo = m->vertices[0], hi = m->vertices[0];
    for (size_t v = 1; v < m->nvertices; v++) {
        double x = m->vertices[3 * v];
        if (x < lo) lo = x;
        if (x > hi) hi = x;
    }
    double X = nextafter(hi, INFINITY);
    acd_cut_plane pl = {{X, 0, 0}, {X, 1, 0}, {X, 0, 1}, {1, 0, 0}};
    if (!isfinite(X)) { /* x beyond the largest double: the plane below the smallest x instead */
        X = nextafter(lo, -INFINITY);
        pl = (acd_cut_plane){{X, 0, 0}, {X, 0, 1}, {X, 1, 0}, {-1, 0, 0}};
        if (!isfinite(X))
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "bodies: x coordinates span every finite double");
    }
    return acd_plane_cut_map(m, map, &pl, 0, out, err);
}

acd_status acd_plane_cut(const acd_mesh *m, const acd_cut_plane *pl, acd_cut_result *out, acd_error *err) {
    return acd_plane_cut_flags(m, pl, 0, out, err);
}

acd_status acd_plane_cut_flags(const acd_mesh *m, const acd_cut_plane *pl, unsigned flags, acd_cut_result *out,
                               acd_error *err) {
    return acd_plane_cut_map(m, NULL, pl, flags, out, err);
}

acd_status acd_plane_cut_map(const acd_mesh *m, const acd_edge_map *map, const acd_cut_plane *pl, unsigned flags,
                             acd_cut_result *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    if (!m || !pl) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "plane cut: NULL mesh or plane");
    if (m->nvertices >= UINT32_MAX / 2 || m->ntriangles >= UINT32_MAX / 8)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "plane cut: mesh too large (%zu vertices, %zu triangles)",
                        m->nvertices, m->ntriangles);
    for (size_t v = 0; v < m->nvertices; v++)
        for (int k = 0; k < 3; k++)
            if (!isfinite(m->vertices[3 * v + k]))
                return acd_fail(err, ACD_ERR_INVALID_INPUT, "plane cut: vertex %zu has a non-finite coordinate", v);
    for (size_t t = 0; t < 3 * m->ntriangles; t++)
        if (m->triangles[t] >= m->nvertices)
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "plane cut: triangle %zu uses vertex %u of %zu", t / 3,
                            m->triangles[t], m->nvertices);
    /* the input's twins by half-edge: the map's (acd_edge_map_closed keeps them), else from its
     * twins by entry; without a map, acd_edge_map_closed builds and checks one */
    acd_edge_map own = {0};
    uint32_t *own_tw = NULL;
    const uint32_t *itw = NULL;
    acd_status st = ACD_OK;
    if (!map) {
        st = acd_edge_map_closed(m->triangles, m->ntriangles, &own, err);
        if (st != ACD_OK) return st;
        itw = own.twin;
    } else if (map->twin) {
        itw = map->twin;
    } else {
        uint32_t *tw = NULL;
        st = acd_edge_map_twins(map, &tw, err);
        if (st != ACD_OK) return st;
        own_tw = malloc((map->n ? map->n : 1) * sizeof *own_tw);
        if (!own_tw) {
            free(tw);
            return acd_fail(err, ACD_ERR_NOMEM, "out of memory for the twins of %zu half-edges", map->n);
        }
        for (size_t i = 0; i < map->n; i++) own_tw[map->half[i]] = tw[i];
        free(tw);
        itw = own_tw;
    }
    /* huge or tiny models: work on the input scaled by a power of two (exact, unless it flushes
     * coordinates below 2^-1074 of the largest one) so that the largest coordinate is about 1: the
     * predicates' products then neither overflow nor underflow */
    double maxabs = 0;
    for (size_t i = 0; i < 3 * m->nvertices; i++) { /* finite (checked above): fmax's value */
        double x = fabs(m->vertices[i]);
        if (x > maxabs) maxabs = x;
    }
    for (int k = 0; k < 3; k++) maxabs = fmax(maxabs, fmax(fabs(pl->a[k]), fmax(fabs(pl->b[k]), fabs(pl->c[k]))));
    int e2 = 0; /* only outside [1e-90, 1e90]: scaling down could flush subnormal coordinates */
    if (maxabs > 0 && (maxabs > 1e90 || maxabs < 1e-90)) frexp(maxabs, &e2);
    /* and coordinates below 2^-200 of the largest are flushed to zero in the working copy: the
     * predicates' products of differences cannot underflow (exact decisions, for a geometry moved by
     * less than 1e-60 of the model's size) */
    double flush = ldexp(maxabs, -e2 - PLANE_CUT_FLUSH_BITS);
    acd_cut_plane spl = *pl;
    for (int k = 0; k < 3; k++) {
        spl.a[k] = flush_tiny(ldexp(pl->a[k], -e2), flush);
        spl.b[k] = flush_tiny(ldexp(pl->b[k], -e2), flush);
        spl.c[k] = flush_tiny(ldexp(pl->c[k], -e2), flush);
    }
    {
        acd_cut_plane chk;
        if (acd_cut_plane_from_points(spl.a, spl.b, spl.c, &chk, NULL) != ACD_OK) {
            double plmax = 0;
            for (int k = 0; k < 3; k++) plmax = fmax(plmax, fmax(fabs(pl->a[k]), fmax(fabs(pl->b[k]), fabs(pl->c[k]))));
            acd_edge_map_free(&own);
            free(own_tw);
            return acd_fail(err, ACD_ERR_DEGENERATE,
                            "plane cut: the plane's points (up to %g) vanish next to the mesh's coordinates (up to %g)",
                            plmax, maxabs);
        }
    }
    pl = &spl;
    cut_ctx c;
    memset(&c, 0, sizeof c);
    c.pl = pl;
    c.scale_exp = -e2;
    c.orig = m->vertices;
    c.flags = flags;
    c.err = err;
    c.ax = 0;
    for (int k = 1; k < 3; k++)
        if (fabs(pl->normal[k]) > fabs(pl->normal[c.ax])) c.ax = k;
    c.swap = pl->normal[c.ax] < 0;
    size_t nt = m->ntriangles, nv = m->nvertices;
    c.capv = nv + 3 * nt / 2 + 1;
    c.V = malloc(c.capv * 3 * sizeof *c.V);
    c.src = malloc(c.capv * sizeof *c.src);
    int8_t *s = malloc((nv ? nv : 1) * sizeof *s);
    double *f = malloc((nv ? nv : 1) * sizeof *f);
    uint32_t *xv = malloc((nt ? nt : 1) * 3 * sizeof *xv); /* crossing vertex of each half-edge */
    c.itw = itw;
    c.nin = nt;
    c.wside = malloc((nt ? nt : 1) * sizeof *c.wside);
    c.tout = malloc((nt + 1) * sizeof *c.tout);
    c.capt = nt + nt / 4 + 64; /* the triangles' room (push_tri grows it): the input's and the splits' */
    c.T = malloc(c.capt * 3 * sizeof *c.T);
    c.tside = malloc(c.capt * sizeof *c.tside);
    c.tcap = malloc(c.capt * sizeof *c.tcap);
    if (!c.V || !c.src || !s || !f || !xv || !c.wside || !c.tout || !c.T || !c.tside || !c.tcap) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory cutting a mesh of %zu triangles", nt);
        goto fail;
    }
    if (e2 == 0) /* ldexp by 0 is the identity */
        for (size_t i = 0; i < 3 * nv; i++) c.V[i] = flush_tiny(m->vertices[i], flush);
    else
        for (size_t i = 0; i < 3 * nv; i++) c.V[i] = flush_tiny(ldexp(m->vertices[i], -e2), flush);
    for (size_t v = 0; v < nv; v++) {
        c.src[v] = (uint32_t)v;
        f[v] = -acd_orient3d(pl->a, pl->b, pl->c, c.V + 3 * v); /* > 0 on the + side */
        s[v] = (int8_t)((f[v] > 0) - (f[v] < 0));
    }
    c.nv = nv;
    for (size_t h = 0; h < 3 * nt; h++) xv[h] = NONE;
    for (size_t t = 0; t < nt && st == ACD_OK; t++) {
        const uint32_t *q = m->triangles + 3 * t;
        int hasp = 0, hasn = 0;
        for (int i = 0; i < 3; i++) hasp |= s[q[i]] > 0, hasn |= s[q[i]] < 0;
        c.tout[t] = (uint32_t)c.nt;
        if (hasp && !hasn) {
            c.wside[t] = +1;
            st = push_tri(&c, q[0], q[1], q[2], +1, 0);
            continue;
        }
        if (hasn && !hasp) {
            c.wside[t] = -1;
            st = push_tri(&c, q[0], q[1], q[2], -1, 0);
            continue;
        }
        if (!hasp && !hasn) { /* in the plane: material lies opposite the outward normal */
            double p0[2], p1[2], p2[2];
            proj2(&c, q[0], p0);
            proj2(&c, q[1], p1);
            proj2(&c, q[2], p2);
            int o = acd_orient2d_sign(p0, p1, p2);
            c.wside[t] = (int8_t)(o > 0 ? -1 : +1);
            st = push_tri(&c, q[0], q[1], q[2], o > 0 ? -1 : +1, 0);
            continue;
        }
        c.wside[t] = 0;
        /* split: walk the edges, building the + and - polygons */
        uint32_t Pp[4], Pn[4];
        int np_ = 0, nn_ = 0;
        for (int i = 0; i < 3; i++) {
            uint32_t a = q[i], b = q[(i + 1) % 3];
            if (s[a] >= 0) Pp[np_++] = a;
            if (s[a] <= 0) Pn[nn_++] = a;
            if (s[a] * s[b] < 0) {
                size_t h = 3 * t + (size_t)i;
                if (xv[h] == NONE) {
                    uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
                    double fl = f[lo], fh = f[hi], tt = fl / (fl - fh);
                    if (!(tt >= 0)) tt = 0; /* also NaN */
                    if (tt > 1) tt = 1;
                    const double *pa = c.V + 3 * (size_t)lo, *pb = c.V + 3 * (size_t)hi;
                    uint32_t nvx = (uint32_t)c.nv++;
                    for (int k = 0; k < 3; k++) c.V[3 * (size_t)nvx + k] = pa[k] + tt * (pb[k] - pa[k]);
                    c.src[nvx] = ACD_CUT_NEW_VERTEX;
                    xv[h] = nvx;
                    xv[itw[h]] = nvx;
                }
                Pp[np_++] = xv[h];
                Pn[nn_++] = xv[h];
            }
        }
        for (int k = 1; k + 1 < np_ && st == ACD_OK; k++) st = push_tri(&c, Pp[0], Pp[k], Pp[k + 1], +1, 0);
        for (int k = 1; k + 1 < nn_ && st == ACD_OK; k++) st = push_tri(&c, Pn[0], Pn[k], Pn[k + 1], -1, 0);
    }
    c.tout[nt] = (uint32_t)c.nt;
    c.ncut = c.nt;
    if (st == ACD_OK) st = cap_sections(&c, out);
    if (st == ACD_OK) st = make_pieces(&c, out);
    out->section_area = ldexp(out->section_area, 2 * e2);
fail:
    acd_edge_map_free(&own);
    free(own_tw);
    free(c.wside);
    free(c.tout);
    free(c.V);
    free(c.src);
    free(c.T);
    free(c.tside);
    free(c.tcap);
    free(s);
    free(f);
    free(xv);
    if (st != ACD_OK) acd_cut_result_free(out);
    return st;
}
