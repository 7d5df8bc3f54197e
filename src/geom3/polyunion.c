/* geom3/polyunion: exact boundary of a union of convex polytopes (see polyunion.h).
 *
 * Bit budget (G = ACD_POLYUNION_GRID_BITS = 26, B = ACD_POLYUNION_NORMAL_BITS = 20): grid
 * coordinates of the polytopes lie in [-2^G, 2^G]^3, the bounding box planes of the initial
 * squares at +-M = +-2^(G+1). A facet plane (a, b, c, d) has |a|, |b|, |c| <= 2^B and
 * |d| <= 2^B * 3 * 2^G + 3 < 2^48. The meet of three planes has
 *   W = det(normals)            |W| <= 6 * 2^(3B)              < 2^63,
 *   X, Y, Z (Cramer)            |X| <= 6 * 2^48 * 2^(2B)       < 2^91,
 * and a plane at such a point, a X + b Y + c Z + d W, stays below 3 * 2^(B+91) + 2^(48+63) <
 * 2^114: every value fits a signed 128-bit integer, so every sign is exact. Reduced
 * coordinates (divided by their gcd, W > 0) make equal points bitwise equal. */
#include "geom3/polyunion.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

__extension__ typedef __int128 i128;
__extension__ typedef unsigned __int128 u128;

#define PU_BOX_PLANES 6
/* Candidate search for inserted vertices: a box this much wider (grid units) than the edge. */
#define PU_SEARCH_MARGIN 1e-3
/* Half extent of the grid over that of the points' box grown by the offset. */
#define PU_GRID_ROOM 1.25

typedef struct plane_t {
    int64_t c[4]; /* a x + b y + c z + d w; a polytope is where every plane is <= 0 */
} plane_t;

typedef struct hpt {
    i128 c[4]; /* X, Y, Z, W (W > 0, gcd 1) */
} hpt;

typedef struct pvert {
    hpt p;
    uint32_t tri[3]; /* three planes meeting at p (independent) */
    uint32_t e;      /* plane holding the edge from this vertex to the next */
} pvert;

typedef struct poly {
    pvert *v;
    size_t n, cap;
    uint32_t plane; /* the facet's plane */
    uint32_t owner; /* polytope */
    double lo[3], hi[3];
} poly;

typedef struct polyvec {
    poly *p;
    size_t n, cap;
} polyvec;

typedef struct polytope {
    size_t first, nplanes; /* its planes in the table */
    double lo[3], hi[3];
    int solid;
} polytope;

typedef struct pu_ctx {
    plane_t *pl;
    size_t npl, capl;
    polytope *pt;
    size_t npt;
    acd_error *err;
} pu_ctx;

static int sgn128(i128 x) { return (x > 0) - (x < 0); }

static i128 peval(const plane_t *h, const hpt *p) {
    return (i128)h->c[0] * p->c[0] + (i128)h->c[1] * p->c[1] + (i128)h->c[2] * p->c[2] + (i128)h->c[3] * p->c[3];
}

static uint64_t gcd64(uint64_t a, uint64_t b) {
    while (b) {
        uint64_t t = a % b;
        a = b;
        b = t;
    }
    return a;
}

static u128 abs128(i128 x) { return x < 0 ? (u128)0 - (u128)x : (u128)x; }

/* Meet of three planes; 0 when they do not meet in one point. */
static int meet(const plane_t *P, const plane_t *Q, const plane_t *R, hpt *out) {
    i128 a1 = P->c[0], b1 = P->c[1], c1 = P->c[2], d1 = -(i128)P->c[3];
    i128 a2 = Q->c[0], b2 = Q->c[1], c2 = Q->c[2], d2 = -(i128)Q->c[3];
    i128 a3 = R->c[0], b3 = R->c[1], c3 = R->c[2], d3 = -(i128)R->c[3];
    i128 m_bc = b2 * c3 - b3 * c2, m_ac = a2 * c3 - a3 * c2, m_ab = a2 * b3 - a3 * b2;
    i128 m_dc = d2 * c3 - d3 * c2, m_db = d2 * b3 - d3 * b2, m_ad = a2 * d3 - a3 * d2, m_bd = b2 * d3 - b3 * d2;
    i128 W = a1 * m_bc - b1 * m_ac + c1 * m_ab;
    if (W == 0) return 0;
    i128 X = d1 * m_bc - b1 * m_dc + c1 * m_db;
    i128 Y = a1 * m_dc - d1 * m_ac + c1 * m_ad;
    i128 Z = a1 * m_bd - b1 * m_ad + d1 * m_ab;
    if (W < 0) {
        W = -W;
        X = -X;
        Y = -Y;
        Z = -Z;
    }
    uint64_t g = (uint64_t)W; /* |W| < 2^63 */
    g = gcd64(g, (uint64_t)(abs128(X) % g));
    if (g > 1) g = gcd64(g, (uint64_t)(abs128(Y) % g));
    if (g > 1) g = gcd64(g, (uint64_t)(abs128(Z) % g));
    if (g > 1) {
        X /= (i128)g;
        Y /= (i128)g;
        Z /= (i128)g;
        W /= (i128)g;
    }
    out->c[0] = X;
    out->c[1] = Y;
    out->c[2] = Z;
    out->c[3] = W;
    return 1;
}

static int hpt_cmp(const hpt *a, const hpt *b) {
    for (int k = 0; k < 4; k++) {
        int i = (k + 3) % 4;
        if (a->c[i] != b->c[i]) return a->c[i] < b->c[i] ? -1 : 1;
    }
    return 0;
}

static int hpt_qcmp(const void *a, const void *b) { return hpt_cmp(a, b); }

static void hpt_double(const hpt *p, double *x) {
    double w = (double)p->c[3];
    for (int k = 0; k < 3; k++) x[k] = (double)p->c[k] / w;
}

static int poly_reserve(poly *q, size_t n) {
    if (n <= q->cap) return 1;
    size_t cap = q->cap ? 2 * q->cap : 8;
    while (cap < n) cap *= 2;
    pvert *v = realloc(q->v, cap * sizeof *v);
    if (!v) return 0;
    q->v = v;
    q->cap = cap;
    return 1;
}

static void poly_free(poly *q) {
    free(q->v);
    memset(q, 0, sizeof *q);
}

static void poly_bbox(poly *q) {
    for (int k = 0; k < 3; k++) {
        q->lo[k] = INFINITY;
        q->hi[k] = -INFINITY;
    }
    for (size_t i = 0; i < q->n; i++) {
        double x[3];
        hpt_double(&q->v[i].p, x);
        for (int k = 0; k < 3; k++) {
            if (x[k] < q->lo[k]) q->lo[k] = x[k];
            if (x[k] > q->hi[k]) q->hi[k] = x[k];
        }
    }
}

static int pv_push(polyvec *pv, poly *q) {
    if (pv->n == pv->cap) {
        size_t cap = pv->cap ? 2 * pv->cap : 16;
        poly *p = realloc(pv->p, cap * sizeof *p);
        if (!p) return 0;
        pv->p = p;
        pv->cap = cap;
    }
    pv->p[pv->n++] = *q;
    memset(q, 0, sizeof *q);
    return 1;
}

static void pv_free(polyvec *pv) {
    for (size_t i = 0; i < pv->n; i++) poly_free(&pv->p[i]);
    free(pv->p);
    memset(pv, 0, sizeof *pv);
}

/* Side of every vertex of q against plane H; returns the count of negative and positive ones. */
static void signs_of(const pu_ctx *c, const poly *q, uint32_t H, int *s, size_t *neg, size_t *pos) {
    *neg = *pos = 0;
    for (size_t i = 0; i < q->n; i++) {
        s[i] = sgn128(peval(&c->pl[H], &q->v[i].p));
        if (s[i] < 0) (*neg)++;
        if (s[i] > 0) (*pos)++;
    }
}

/* The part of q on side `keep` (-1 or +1) of H, closed; q must have vertices strictly on both
 * sides. Sutherland-Hodgman with plane-labelled edges: a crossing of edge k is the meet of the
 * facet plane, the edge's plane and H, so it is exact. */
static acd_status clip(const pu_ctx *c, const poly *q, const int *s, uint32_t H, int keep, poly *out) {
    out->n = 0;
    out->plane = q->plane;
    out->owner = q->owner;
    if (!poly_reserve(out, q->n + 2)) return acd_fail(c->err, ACD_ERR_NOMEM, "polytope union: out of memory");
    for (size_t k = 0; k < q->n; k++) {
        size_t k1 = (k + 1) % q->n;
        int sk = s[k] * keep, sn = s[k1] * keep; /* >= 0: kept */
        if (sk >= 0) {
            pvert v = q->v[k];
            v.e = (sn >= 0 || sk > 0) ? q->v[k].e : H;
            out->v[out->n++] = v;
        }
        if ((sk > 0 && sn < 0) || (sk < 0 && sn > 0)) {
            pvert v;
            v.tri[0] = q->plane;
            v.tri[1] = q->v[k].e;
            v.tri[2] = H;
            if (!meet(&c->pl[q->plane], &c->pl[q->v[k].e], &c->pl[H], &v.p))
                return acd_fail(c->err, ACD_ERR_INTERNAL, "polytope union: a clipped edge is parallel to its cutting plane");
            v.e = sn > 0 ? q->v[k].e : H;
            out->v[out->n++] = v;
        }
    }
    return ACD_OK;
}

/* The big square of plane P (within the box planes), counterclockwise seen from outside. */
static acd_status initial_square(const pu_ctx *c, uint32_t P, poly *out) {
    const plane_t *pl = &c->pl[P];
    int k = 0;
    for (int a = 1; a < 3; a++)
        if (llabs(pl->c[a]) > llabs(pl->c[k])) k = a;
    int i = (k + 1) % 3, j = (k + 2) % 3;
    /* corners (s_i, s_j) and the box plane of the edge leaving each corner */
    int si[4] = {-1, 1, 1, -1}, sj[4] = {-1, -1, 1, 1};
    uint32_t eplane[4];
    eplane[0] = (uint32_t)(2 * j + 0); /* x_j = -M */
    eplane[1] = (uint32_t)(2 * i + 1); /* x_i = +M */
    eplane[2] = (uint32_t)(2 * j + 1); /* x_j = +M */
    eplane[3] = (uint32_t)(2 * i + 0); /* x_i = -M */
    out->n = 0;
    out->plane = P;
    if (!poly_reserve(out, 4)) return acd_fail(c->err, ACD_ERR_NOMEM, "polytope union: out of memory");
    for (int t = 0; t < 4; t++) {
        int u = pl->c[k] > 0 ? t : (4 - t) % 4;
        pvert v;
        v.tri[0] = P;
        v.tri[1] = (uint32_t)(2 * i + (si[u] > 0));
        v.tri[2] = (uint32_t)(2 * j + (sj[u] > 0));
        if (!meet(&c->pl[P], &c->pl[v.tri[1]], &c->pl[v.tri[2]], &v.p))
            return acd_fail(c->err, ACD_ERR_INTERNAL, "polytope union: degenerate initial square");
        /* outgoing edge: forward order uses eplane[u]; reversed order goes to corner u-1 */
        v.e = pl->c[k] > 0 ? eplane[u] : eplane[(u + 3) % 4];
        out->v[out->n++] = v;
    }
    return ACD_OK;
}

static int plane_cmp(const void *x, const void *y) {
    const plane_t *a = x, *b = y;
    for (int k = 0; k < 4; k++)
        if (a->c[k] != b->c[k]) return a->c[k] < b->c[k] ? -1 : 1;
    return 0;
}

static int plane_equal(const plane_t *a, const plane_t *b) { return plane_cmp(a, b) == 0; }

static int plane_opposite(const plane_t *a, const plane_t *b) {
    return a->c[0] == -b->c[0] && a->c[1] == -b->c[1] && a->c[2] == -b->c[2] && a->c[3] == -b->c[3];
}

static int64_t gcd64s(int64_t a, int64_t b) { return (int64_t)gcd64((uint64_t)llabs(a), (uint64_t)llabs(b)); }

static int boxes_overlap(const double *alo, const double *ahi, const double *blo, const double *bhi) {
    for (int k = 0; k < 3; k++)
        if (ahi[k] + PU_SEARCH_MARGIN < blo[k] || bhi[k] + PU_SEARCH_MARGIN < alo[k]) return 0;
    return 1;
}

/* Subtracts polytope j from the pieces of one facet of polytope i (owner); the pieces outside
 * replace *pieces. */
static acd_status subtract(const pu_ctx *c, polyvec *pieces, size_t j, int **sbuf, size_t *sbufn) {
    polyvec outv = {0};
    acd_status st = ACD_OK;
    const polytope *T = &c->pt[j];
    poly in = {0}, tmp = {0};
    for (size_t f = 0; f < pieces->n && st == ACD_OK; f++) {
        poly *cur = &pieces->p[f];
        if (!boxes_overlap(cur->lo, cur->hi, T->lo, T->hi)) {
            if (!pv_push(&outv, cur)) st = acd_fail(c->err, ACD_ERR_NOMEM, "polytope union: out of memory");
            continue;
        }
        const plane_t *P = &c->pl[cur->plane];
        int inside = 1;
        for (size_t h = 0; h < T->nplanes && st == ACD_OK; h++) {
            uint32_t H = (uint32_t)(T->first + h);
            const plane_t *ph = &c->pl[H];
            if (plane_equal(ph, P)) {
                if (j < cur->owner) continue; /* the lower polytope keeps the shared region */
                inside = 0;
                break;
            }
            if (plane_opposite(ph, P)) continue; /* glued faces: interior to the union */
            if (*sbufn < cur->n) {
                free(*sbuf);
                *sbufn = 2 * cur->n + 8;
                *sbuf = malloc(*sbufn * sizeof **sbuf);
                if (!*sbuf) {
                    *sbufn = 0;
                    st = acd_fail(c->err, ACD_ERR_NOMEM, "polytope union: out of memory");
                    break;
                }
            }
            size_t neg, pos;
            signs_of(c, cur, H, *sbuf, &neg, &pos);
            if (!neg) {
                inside = 0;
                break;
            }
            if (!pos) continue;
            st = clip(c, cur, *sbuf, H, +1, &tmp);
            if (st != ACD_OK) break;
            poly_bbox(&tmp);
            if (!pv_push(&outv, &tmp)) {
                st = acd_fail(c->err, ACD_ERR_NOMEM, "polytope union: out of memory");
                break;
            }
            st = clip(c, cur, *sbuf, H, -1, &in);
            if (st != ACD_OK) break;
            poly_bbox(&in);
            poly t = *cur;
            *cur = in;
            in = t;
        }
        if (st != ACD_OK) break;
        if (!inside) {
            if (!pv_push(&outv, cur)) st = acd_fail(c->err, ACD_ERR_NOMEM, "polytope union: out of memory");
        }
    }
    poly_free(&in);
    poly_free(&tmp);
    if (st != ACD_OK) {
        pv_free(&outv);
        return st;
    }
    pv_free(pieces);
    *pieces = outv;
    return ACD_OK;
}

/* Global vertices: one per distinct point. */
typedef struct gvert {
    hpt p;
    uint32_t tri[3];
    double x[3];
} gvert;

typedef struct vref {
    uint32_t frag, idx;
} vref;

typedef struct sort_ctx_item {
    const hpt *p;
    uint32_t frag, idx;
} sort_item;

static int cmp_sort_item(const void *x, const void *y) {
    const sort_item *a = x, *b = y;
    int r = hpt_cmp(a->p, b->p);
    if (r) return r;
    if (a->frag != b->frag) return a->frag < b->frag ? -1 : 1;
    return (a->idx > b->idx) - (a->idx < b->idx);
}

typedef struct xkey {
    double x;
    uint32_t id;
} xkey;

static int cmp_xkey(const void *a, const void *b) {
    const xkey *p = a, *q = b;
    if (p->x != q->x) return p->x < q->x ? -1 : 1;
    return (p->id > q->id) - (p->id < q->id);
}

/* Boundary vertex of a fragment after insertion: global id and the fragment edges holding it. */
typedef struct bv {
    uint32_t id;
    int e1, e2;
} bv;

static int on_common_edge(const bv *a, const bv *b) {
    return a->e1 == b->e1 || a->e1 == b->e2 || a->e2 == b->e1 || a->e2 == b->e2;
}

static int collinear3(const bv *a, const bv *b, const bv *c) {
    int eb[2] = {b->e1, b->e2};
    for (int t = 0; t < 2; t++) {
        int e = eb[t];
        if ((a->e1 == e || a->e2 == e) && (c->e1 == e || c->e2 == e)) return 1;
    }
    return 0;
}

typedef struct tri_out {
    uint32_t *t;
    size_t n, cap;
} tri_out;

static int tri_push(tri_out *o, uint32_t a, uint32_t b, uint32_t c) {
    if (o->n == o->cap) {
        size_t cap = o->cap ? 2 * o->cap : 256;
        uint32_t *t = realloc(o->t, 3 * cap * sizeof *t);
        if (!t) return 0;
        o->t = t;
        o->cap = cap;
    }
    o->t[3 * o->n] = a;
    o->t[3 * o->n + 1] = b;
    o->t[3 * o->n + 2] = c;
    o->n++;
    return 1;
}

/* Ear clipping of a convex polygon with extra points on its edges: an ear at b is cut when a, b, c
 * are not on one edge (b is a true corner of the current polygon) and a, c share no edge (the
 * cut does not run along an edge, which would leave a flat remainder). */
static acd_status triangulate(bv *cyc, size_t m, tri_out *o, acd_error *err) {
    size_t start = 0;
    while (m > 3) {
        size_t found = SIZE_MAX;
        for (size_t t = 0; t < m; t++) {
            size_t b = (start + t) % m, a = (b + m - 1) % m, c = (b + 1) % m;
            if (!collinear3(&cyc[a], &cyc[b], &cyc[c]) && !on_common_edge(&cyc[a], &cyc[c])) {
                found = b;
                break;
            }
        }
        if (found == SIZE_MAX) return acd_fail(err, ACD_ERR_INTERNAL, "polytope union: no ear in a fragment of %zu vertices", m);
        size_t a = (found + m - 1) % m, c = (found + 1) % m;
        if (!tri_push(o, cyc[a].id, cyc[found].id, cyc[c].id))
            return acd_fail(err, ACD_ERR_NOMEM, "polytope union: out of memory");
        memmove(cyc + found, cyc + found + 1, (m - found - 1) * sizeof *cyc);
        m--;
        start = found % m;
    }
    if (collinear3(&cyc[0], &cyc[1], &cyc[2]))
        return acd_fail(err, ACD_ERR_INTERNAL, "polytope union: flat last triangle in a fragment");
    if (!tri_push(o, cyc[0].id, cyc[1].id, cyc[2].id)) return acd_fail(err, ACD_ERR_NOMEM, "polytope union: out of memory");
    return ACD_OK;
}

/* Quantized planes of hull h appended to the table; returns the count through *np. */
static acd_status quantize_hull(pu_ctx *c, const acd_polyunion_polytope *h, const double *o, double unit, double push,
                                size_t *np) {
    size_t nf = h->nplanes + PU_BOX_PLANES, nv = h->npoints;
    double *q = malloc(3 * (nv ? nv : 1) * sizeof *q);
    plane_t *loc = malloc(nf * sizeof *loc);
    if (!q || !loc) {
        free(q);
        free(loc);
        return acd_fail(c->err, ACD_ERR_NOMEM, "polytope union: out of memory");
    }
    for (size_t v = 0; v < nv; v++)
        for (int k = 0; k < 3; k++) q[3 * v + k] = (h->points[3 * v + k] - o[k]) / unit;
    const double nscale = ldexp(1.0, ACD_POLYUNION_NORMAL_BITS);
    size_t m = 0;
    for (size_t f = 0; f < nf; f++) {
        double axis[3] = {0, 0, 0};
        if (f >= h->nplanes) axis[(f - h->nplanes) / 2] = (f - h->nplanes) % 2 ? 1 : -1;
        const double *pl = f < h->nplanes ? h->planes + 4 * f : axis;
        double len = sqrt(pl[0] * pl[0] + pl[1] * pl[1] + pl[2] * pl[2]);
        if (!(len > 0) || !isfinite(len)) continue;
        int64_t a[3];
        for (int k = 0; k < 3; k++) a[k] = llround(pl[k] / len * nscale);
        if (!a[0] && !a[1] && !a[2]) continue;
        double mx = -INFINITY;
        for (size_t v = 0; v < nv; v++) {
            double s = (double)a[0] * q[3 * v] + (double)a[1] * q[3 * v + 1] + (double)a[2] * q[3 * v + 2];
            if (s > mx) mx = s;
        }
        /* n.q + d <= -2 at every vertex: 2 units of slack for the rounding of n.q (< 2^-4) */
        int64_t d = -(int64_t)ceil(mx + push * sqrt((double)a[0] * a[0] + (double)a[1] * a[1] + (double)a[2] * a[2])) - 2;
        int64_t g = gcd64s(gcd64s(a[0], a[1]), gcd64s(a[2], d));
        if (g > 1) {
            for (int k = 0; k < 3; k++) a[k] /= g;
            d /= g;
        }
        loc[m].c[0] = a[0];
        loc[m].c[1] = a[1];
        loc[m].c[2] = a[2];
        loc[m].c[3] = d;
        m++;
    }
    free(q);
    qsort(loc, m, sizeof *loc, plane_cmp);
    size_t u = 0;
    for (size_t i = 0; i < m; i++)
        if (!u || !plane_equal(&loc[u - 1], &loc[i])) loc[u++] = loc[i];
    if (c->npl + u > c->capl) {
        size_t cap = c->capl ? c->capl : 64;
        while (cap < c->npl + u) cap *= 2;
        plane_t *p = realloc(c->pl, cap * sizeof *p);
        if (!p) {
            free(loc);
            return acd_fail(c->err, ACD_ERR_NOMEM, "polytope union: out of memory");
        }
        c->pl = p;
        c->capl = cap;
    }
    memcpy(c->pl + c->npl, loc, u * sizeof *loc);
    c->npl += u;
    *np = u;
    free(loc);
    return ACD_OK;
}

acd_status acd_polyunion(const acd_polyunion_polytope *hulls, size_t n, double offset, acd_mesh *out,
                         acd_polyunion_stats *stats,
                         acd_error *err) {
    memset(out, 0, sizeof *out);
    acd_polyunion_stats stl;
    memset(&stl, 0, sizeof stl);
    if (n && !hulls) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "polytope union: hulls is NULL");
    if (!(offset >= 0) || !isfinite(offset))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "polytope union: offset %g must be finite and >= 0", offset);
    pu_ctx c;
    memset(&c, 0, sizeof c);
    c.err = err;
    acd_status st = ACD_OK;
    polyvec frags = {0}, facets = {0};
    int *sbuf = NULL;
    size_t sbufn = 0;
    gvert *gv = NULL;
    sort_item *items = NULL;
    uint32_t **ids = NULL;
    xkey *xs = NULL;
    bv *cyc = NULL;
    uint32_t *ins = NULL;
    tri_out tris = {0};
    size_t ng = 0;

    /* grid: centre of the box of the solid hulls' vertices, 2^G units per half extent */
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t h = 0; h < n; h++) {
        if (!hulls[h].npoints) continue;
        stl.polytopes++;
        for (size_t p = 0; p < 4 * hulls[h].nplanes; p++)
            if (!isfinite(hulls[h].planes[p]))
                return acd_fail(err, ACD_ERR_INVALID_INPUT, "polytope union: polytope %zu has a non-finite plane", h);
        for (size_t v = 0; v < hulls[h].npoints; v++)
            for (int k = 0; k < 3; k++) {
                double x = hulls[h].points[3 * v + k];
                if (!isfinite(x)) return acd_fail(err, ACD_ERR_INVALID_INPUT, "polytope union: hull %zu has a non-finite vertex", h);
                if (x < lo[k]) lo[k] = x;
                if (x > hi[k]) hi[k] = x;
            }
    }
    if (!stl.polytopes) return acd_fail(err, ACD_ERR_DEGENERATE, "polytope union: no polytope with points among %zu", n);
    double o[3], half = 0;
    for (int k = 0; k < 3; k++) {
        o[k] = 0.5 * (lo[k] + hi[k]);
        if (0.5 * (hi[k] - lo[k]) > half) half = 0.5 * (hi[k] - lo[k]);
    }
    /* every polytope also has the six axis planes, so pushed, it stays within the box grown by the
       offset; the grid gets twice that room (and the initial squares twice more) */
    half = PU_GRID_ROOM * (half + offset);
    double unit = half / ldexp(1.0, ACD_POLYUNION_GRID_BITS) * (1 + 1e-9);
    const int64_t M = (int64_t)1 << (ACD_POLYUNION_GRID_BITS + 1);

    c.capl = 64;
    c.pl = malloc(c.capl * sizeof *c.pl);
    c.pt = calloc(stl.polytopes, sizeof *c.pt);
    if (!c.pl || !c.pt) {
        st = acd_fail(err, ACD_ERR_NOMEM, "polytope union: out of memory");
        goto done;
    }
    for (int a = 0; a < 3; a++)
        for (int s = 0; s < 2; s++) {
            plane_t *p = &c.pl[2 * a + s];
            memset(p, 0, sizeof *p);
            p->c[a] = 1;
            p->c[3] = s ? -M : M;
        }
    c.npl = PU_BOX_PLANES;

    /* quantized polytopes and their facets */
    for (size_t h = 0; h < n && st == ACD_OK; h++) {
        if (!hulls[h].npoints) continue;
        polytope *T = &c.pt[c.npt];
        T->first = c.npl;
        st = quantize_hull(&c, &hulls[h], o, unit, offset / unit, &T->nplanes);
        c.npt++;
    }
    for (size_t t = 0; t < c.npt && st == ACD_OK; t++) {
        polytope *T = &c.pt[t];
        for (int k = 0; k < 3; k++) {
            T->lo[k] = INFINITY;
            T->hi[k] = -INFINITY;
        }
        size_t first_facet = facets.n;
        for (size_t a = 0; a < T->nplanes && st == ACD_OK; a++) {
            poly cur = {0}, nxt = {0};
            uint32_t P = (uint32_t)(T->first + a);
            st = initial_square(&c, P, &cur);
            cur.owner = (uint32_t)t;
            int empty = 0;
            for (size_t b = 0; b < T->nplanes && st == ACD_OK && !empty; b++) {
                if (b == a) continue;
                uint32_t H = (uint32_t)(T->first + b);
                if (sbufn < cur.n) {
                    free(sbuf);
                    sbufn = 2 * cur.n + 8;
                    sbuf = malloc(sbufn * sizeof *sbuf);
                    if (!sbuf) {
                        sbufn = 0;
                        st = acd_fail(err, ACD_ERR_NOMEM, "polytope union: out of memory");
                        break;
                    }
                }
                size_t neg, pos;
                signs_of(&c, &cur, H, sbuf, &neg, &pos);
                if (!neg) {
                    empty = 1;
                    break;
                }
                if (!pos) continue;
                st = clip(&c, &cur, sbuf, H, -1, &nxt);
                poly tt = cur;
                cur = nxt;
                nxt = tt;
            }
            poly_free(&nxt);
            if (st == ACD_OK && !empty)
                for (size_t i = 0; i < cur.n && st == ACD_OK; i++)
                    if (cur.v[i].tri[1] < PU_BOX_PLANES || cur.v[i].tri[2] < PU_BOX_PLANES)
                        st = acd_fail(err, ACD_ERR_INTERNAL, "polytope union: polytope %zu is not bounded", t);
            if (st == ACD_OK && !empty) {
                poly_bbox(&cur);
                for (int k = 0; k < 3; k++) {
                    if (cur.lo[k] < T->lo[k]) T->lo[k] = cur.lo[k];
                    if (cur.hi[k] > T->hi[k]) T->hi[k] = cur.hi[k];
                }
                stl.planes++;
                if (!pv_push(&facets, &cur)) st = acd_fail(err, ACD_ERR_NOMEM, "polytope union: out of memory");
            }
            poly_free(&cur);
        }
        /* distinct corners of this polytope */
        if (st == ACD_OK) {
            size_t cnt = 0;
            for (size_t f = first_facet; f < facets.n; f++) cnt += facets.p[f].n;
            hpt *pts = malloc((cnt ? cnt : 1) * sizeof *pts);
            if (!pts) {
                st = acd_fail(err, ACD_ERR_NOMEM, "polytope union: out of memory");
                break;
            }
            size_t w = 0;
            for (size_t f = first_facet; f < facets.n; f++)
                for (size_t i = 0; i < facets.p[f].n; i++) pts[w++] = facets.p[f].v[i].p;
            qsort(pts, w, sizeof *pts, hpt_qcmp);
            for (size_t i = 0; i < w; i++)
                if (!i || hpt_cmp(&pts[i - 1], &pts[i])) stl.corners++;
            free(pts);
        }
    }
    if (st != ACD_OK) goto done;

    /* pieces of every facet outside every other polytope */
    for (size_t f = 0; f < facets.n && st == ACD_OK; f++) {
        polyvec pieces = {0};
        if (!pv_push(&pieces, &facets.p[f])) {
            st = acd_fail(err, ACD_ERR_NOMEM, "polytope union: out of memory");
            break;
        }
        uint32_t owner = pieces.p[0].owner;
        for (size_t j = 0; j < c.npt && st == ACD_OK && pieces.n; j++) {
            if (j == owner) continue;
            st = subtract(&c, &pieces, j, &sbuf, &sbufn);
        }
        for (size_t i = 0; i < pieces.n && st == ACD_OK; i++)
            if (!pv_push(&frags, &pieces.p[i])) st = acd_fail(err, ACD_ERR_NOMEM, "polytope union: out of memory");
        pv_free(&pieces);
    }
    if (st != ACD_OK) goto done;
    stl.fragments = frags.n;
    if (!frags.n) {
        st = acd_fail(err, ACD_ERR_INTERNAL, "polytope union: no boundary left");
        goto done;
    }

    /* global vertices */
    size_t nitems = 0;
    for (size_t f = 0; f < frags.n; f++) nitems += frags.p[f].n;
    items = malloc(nitems * sizeof *items);
    ids = malloc(frags.n * sizeof *ids);
    gv = malloc(nitems * sizeof *gv);
    if (!items || !ids || !gv) {
        st = acd_fail(err, ACD_ERR_NOMEM, "polytope union: out of memory");
        goto done;
    }
    memset(ids, 0, frags.n * sizeof *ids);
    size_t w = 0;
    for (size_t f = 0; f < frags.n; f++) {
        ids[f] = malloc(frags.p[f].n * sizeof **ids);
        if (!ids[f]) {
            st = acd_fail(err, ACD_ERR_NOMEM, "polytope union: out of memory");
            goto done;
        }
        for (size_t i = 0; i < frags.p[f].n; i++) items[w++] = (sort_item){&frags.p[f].v[i].p, (uint32_t)f, (uint32_t)i};
    }
    qsort(items, nitems, sizeof *items, cmp_sort_item);
    for (size_t i = 0; i < nitems; i++) {
        if (!i || hpt_cmp(items[i - 1].p, items[i].p)) {
            const pvert *v = &frags.p[items[i].frag].v[items[i].idx];
            gv[ng].p = v->p;
            memcpy(gv[ng].tri, v->tri, sizeof v->tri);
            hpt_double(&v->p, gv[ng].x);
            ng++;
        }
        ids[items[i].frag][items[i].idx] = (uint32_t)(ng - 1);
    }
    free(items);
    items = NULL;
    xs = malloc(ng * sizeof *xs);
    if (!xs) {
        st = acd_fail(err, ACD_ERR_NOMEM, "polytope union: out of memory");
        goto done;
    }
    for (size_t i = 0; i < ng; i++) xs[i] = (xkey){gv[i].x[0], (uint32_t)i};
    qsort(xs, ng, sizeof *xs, cmp_xkey);

    /* conforming pieces, triangulated */
    size_t cyccap = 0, inscap = 0;
    for (size_t f = 0; f < frags.n && st == ACD_OK; f++) {
        const poly *q = &frags.p[f];
        size_t m = 0;
        for (size_t k = 0; k < q->n && st == ACD_OK; k++) {
            size_t kp = (k + q->n - 1) % q->n, k1 = (k + 1) % q->n, k2 = (k + 2) % q->n;
            const hpt *u = &q->v[k].p, *v = &q->v[k1].p;
            const plane_t *P = &c.pl[q->plane], *E = &c.pl[q->v[k].e], *Ep = &c.pl[q->v[kp].e], *En = &c.pl[q->v[k1].e];
            int sp = sgn128(peval(Ep, v)), sn = sgn128(peval(En, u));
            (void)k2;
            if (!sp || !sn) {
                st = acd_fail(err, ACD_ERR_INTERNAL, "polytope union: collinear edges in a fragment");
                break;
            }
            /* candidates: global vertices in the edge's box */
            double blo[3], bhi[3];
            const double *xu = gv[ids[f][k]].x, *xv = gv[ids[f][k1]].x;
            for (int a = 0; a < 3; a++) {
                blo[a] = fmin(xu[a], xv[a]) - PU_SEARCH_MARGIN;
                bhi[a] = fmax(xu[a], xv[a]) + PU_SEARCH_MARGIN;
            }
            size_t lo_i = 0, hi_i = ng;
            while (lo_i < hi_i) {
                size_t mid = (lo_i + hi_i) / 2;
                if (xs[mid].x < blo[0]) lo_i = mid + 1;
                else hi_i = mid;
            }
            size_t nins = 0;
            for (size_t t = lo_i; t < ng && xs[t].x <= bhi[0]; t++) {
                uint32_t g = xs[t].id;
                if (g == ids[f][k] || g == ids[f][k1]) continue;
                const double *x = gv[g].x;
                if (x[1] < blo[1] || x[1] > bhi[1] || x[2] < blo[2] || x[2] > bhi[2]) continue;
                const hpt *p = &gv[g].p;
                if (peval(P, p) != 0 || peval(E, p) != 0) continue;
                if (sgn128(peval(Ep, p)) != sp || sgn128(peval(En, p)) != sn) continue;
                if (nins == inscap) {
                    inscap = inscap ? 2 * inscap : 16;
                    uint32_t *ni = realloc(ins, inscap * sizeof *ins);
                    if (!ni) {
                        st = acd_fail(err, ACD_ERR_NOMEM, "polytope union: out of memory");
                        break;
                    }
                    ins = ni;
                }
                ins[nins++] = g;
            }
            if (st != ACD_OK) break;
            /* order along the edge from u: x before y when x is on u's side of a plane through y
               that crosses the edge's line */
            for (size_t i = 1; i < nins; i++) {
                uint32_t x = ins[i];
                size_t j = i;
                while (j > 0) {
                    uint32_t y = ins[j - 1];
                    /* is x before y? */
                    const plane_t *Y = NULL;
                    for (int r = 0; r < 3 && !Y; r++) {
                        const plane_t *cand = &c.pl[gv[y].tri[r]];
                        if (peval(cand, u) != 0 || peval(cand, v) != 0) Y = cand;
                    }
                    if (!Y) {
                        st = acd_fail(err, ACD_ERR_INTERNAL, "polytope union: a vertex's planes all contain an edge");
                        break;
                    }
                    int before = sgn128(peval(Y, &gv[x].p)) == sgn128(peval(Y, u));
                    if (!before) break;
                    ins[j] = ins[j - 1];
                    j--;
                }
                if (st != ACD_OK) break;
                ins[j] = x;
            }
            if (st != ACD_OK) break;
            stl.inserted += nins;
            if (m + nins + 1 > cyccap) {
                cyccap = 2 * (m + nins + 1) + 16;
                bv *nc = realloc(cyc, cyccap * sizeof *cyc);
                if (!nc) {
                    st = acd_fail(err, ACD_ERR_NOMEM, "polytope union: out of memory");
                    break;
                }
                cyc = nc;
            }
            cyc[m++] = (bv){ids[f][k], (int)kp, (int)k};
            for (size_t i = 0; i < nins; i++) cyc[m++] = (bv){ins[i], (int)k, (int)k};
        }
        if (st != ACD_OK) break;
        st = triangulate(cyc, m, &tris, err);
    }
    if (st != ACD_OK) goto done;

    out->vertices = malloc(3 * ng * sizeof *out->vertices);
    if (!out->vertices) {
        st = acd_fail(err, ACD_ERR_NOMEM, "polytope union: out of memory");
        goto done;
    }
    for (size_t i = 0; i < ng; i++)
        for (int k = 0; k < 3; k++) out->vertices[3 * i + k] = o[k] + gv[i].x[k] * unit;
    out->nvertices = ng;
    out->triangles = tris.t;
    out->ntriangles = tris.n;
    tris.t = NULL;

done:
    if (st != ACD_OK) acd_mesh_free(out);
    if (ids)
        for (size_t f = 0; f < frags.n; f++) free(ids[f]);
    free(ids);
    free(items);
    free(gv);
    free(xs);
    free(cyc);
    free(ins);
    free(tris.t);
    free(sbuf);
    pv_free(&frags);
    pv_free(&facets);
    free(c.pl);
    free(c.pt);
    if (stats) *stats = stl;
    return st;
}
