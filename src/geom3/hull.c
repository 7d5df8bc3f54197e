/* geom3/hull: 3D convex hull through qhull's reentrant library (Quickhull: Barber, Dobkin and
 * Huhdanpaa 1996), wrapped so that degenerate input has a defined result.
 *
 * CH_P is the basic object of Lien's ACD (dissertation D §II.A.3, polyhedra paper P §2: bridges are
 * hull facets not on the surface). The wrapper:
 *   - rejects NaN/Inf, normalises the points into [-1/2, 1/2]^3 (centre and longest side of the
 *     bounding box) so that huge and tiny coordinates behave the same;
 *   - finds the numerical affine dimension (0..3) at ACD_TOL_REL_DIST x diagonal and handles dim < 3
 *     itself: point, extreme segment, convex polygon by Andrew's monotone chain with exact orient2d;
 *   - runs qhull only on full-dimensional sets, with 'Qt' (triangulated output), never letting its
 *     longjmp escape: qh_new_qhull's own setjmp catches errors and returns a code, errors go to a
 *     memory stream that becomes our message; after it returns only plain data structure walks are done;
 *   - if qhull still reports a precision failure, retries on a copy joggled with a fixed-seed
 *     generator (deterministic), then gives up with ACD_ERR_DEGENERATE;
 *   - checks the facet planes it cannot trust (an ill-shaped triangle, or qhull's normal off the
 *     triangle's own) against every input point (a bounding-box tree prunes the points far below a
 *     plane) and against their triangle's vertices: a plane must have every point below it and its
 *     triangle on it within ACD_TOL_REL_DIST x diagonal (so a plane of every triangle encloses
 *     the input). A plane that fails is replaced by the triangle's own plane if that one encloses
 *     every point; otherwise qhull dropped a point it should have kept (an ill-conditioned facet)
 *     and the hull is rebuilt as the exact convex hull by a Quickhull of exact decisions
 *     (hull_enclose, hull_repair).
 * Orientation comes from qhull's facet toporient flag (topologically consistent, counterclockwise
 * seen from outside); adjacency from the simplicial facets' neighbour sets (neighbour i is opposite
 * vertex i). */
#include "acd/hull.h"

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libqhull_r/qhull_ra.h>

#include "core/error.h"
#include "core/predicates.h"
#include "core/rng.h"
#include "core/tolerance.h"
#include "geom3/vec3.h"

/* Joggle tried when qhull fails on a nearly degenerate full-dimensional set, relative to the
 * normalised extent (1); each retry multiplies it by 100. */
#define HULL_JOGGLE_REL (100.0 * ACD_TOL_REL_WELD)
#define HULL_JOGGLE_TRIES 3
#define HULL_JOGGLE_SEED 0x6a6f67676c65ull

static void sub3(const double *a, const double *b, double *r) {
    r[0] = a[0] - b[0];
    r[1] = a[1] - b[1];
    r[2] = a[2] - b[2];
}
static double norm3(const double *a) { return sqrt(acd_dot3(a, a)); }

void acd_hull_free(acd_hull *h) {
    if (!h) return;
    free(h->vertices);
    free(h->triangles);
    free(h->neighbors);
    free(h->planes);
    free(h->source);
    memset(h, 0, sizeof *h);
    h->dim = -1;
}

acd_hull acd_hull_take(acd_hull *h) {
    acd_hull t = *h;
    memset(h, 0, sizeof *h);
    h->dim = -1;
    return t;
}

/* Allocates the output arrays. */
static acd_status hull_alloc(acd_hull *h, size_t nv, size_t nt, acd_error *err) {
    h->vertices = malloc((nv ? nv : 1) * 3 * sizeof *h->vertices);
    h->source = malloc((nv ? nv : 1) * sizeof *h->source);
    h->triangles = malloc((nt ? nt : 1) * 3 * sizeof *h->triangles);
    h->neighbors = malloc((nt ? nt : 1) * 3 * sizeof *h->neighbors);
    h->planes = malloc((nt ? nt : 1) * 4 * sizeof *h->planes);
    if (!h->vertices || !h->source || !h->triangles || !h->neighbors || !h->planes) {
        acd_hull_free(h);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for a hull of %zu vertices and %zu triangles", nv, nt);
    }
    h->nvertices = nv;
    h->ntriangles = nt;
    return ACD_OK;
}

static void set_vertex(acd_hull *h, size_t k, const double *points, size_t src) {
    memcpy(h->vertices + 3 * k, points + 3 * src, 3 * sizeof(double));
    h->source[k] = (uint32_t)src;
}

/* Index of the point of w farthest from a (ties: lowest index). */
static size_t farthest_from_point(const double *w, size_t n, const double *a, double *dist) {
    size_t best = 0;
    double bd = -1;
    for (size_t i = 0; i < n; i++) {
        double d[3];
        sub3(w + 3 * i, a, d);
        double v = acd_dot3(d, d);
        if (v > bd) {
            bd = v;
            best = i;
        }
    }
    *dist = sqrt(bd);
    return best;
}

/* ---------- dim 2: convex polygon by Andrew's monotone chain on a coordinate projection ---------- */

typedef struct proj_pt {
    double p[2];
    size_t idx;
} proj_pt;

static int cmp_proj(const void *a, const void *b) {
    const proj_pt *x = a, *y = b;
    if (x->p[0] != y->p[0]) return x->p[0] < y->p[0] ? -1 : 1;
    if (x->p[1] != y->p[1]) return x->p[1] < y->p[1] ? -1 : 1;
    return x->idx < y->idx ? -1 : (x->idx > y->idx);
}

/* Counterclockwise convex polygon of the projections (strictly convex: collinear points dropped).
 * Writes indices into hullidx (capacity n + 1), returns the count. */
static size_t monotone_chain(proj_pt *pp, size_t n, size_t *hullidx) {
    qsort(pp, n, sizeof *pp, cmp_proj);
    /* drop exact duplicates of the projection (keep the lowest input index) */
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (m == 0 || pp[i].p[0] != pp[m - 1].p[0] || pp[i].p[1] != pp[m - 1].p[1]) pp[m++] = pp[i];
    if (m < 3) {
        for (size_t i = 0; i < m; i++) hullidx[i] = i;
        return m;
    }
    size_t *st = hullidx, k = 0;
    for (size_t i = 0; i < m; i++) { /* lower hull */
        while (k >= 2 && acd_orient2d(pp[st[k - 2]].p, pp[st[k - 1]].p, pp[i].p) <= 0) k--;
        st[k++] = i;
    }
    size_t lower = k + 1;
    for (size_t i = m - 1; i-- > 0;) { /* upper hull */
        while (k >= lower && acd_orient2d(pp[st[k - 2]].p, pp[st[k - 1]].p, pp[i].p) <= 0) k--;
        st[k++] = i;
    }
    return k - 1; /* the last point repeats the first */
}

static acd_status hull_planar(const double *points, const double *w, size_t n, const double *nrm, double s,
                              acd_hull *out, acd_error *err) {
    int ax = 0;
    for (int k = 1; k < 3; k++)
        if (fabs(nrm[k]) > fabs(nrm[ax])) ax = k;
    int i0 = (ax + 1) % 3, i1 = (ax + 2) % 3;
    proj_pt *pp = malloc(n * sizeof *pp);
    size_t *hidx = malloc((n + 1) * sizeof *hidx);
    if (!pp || !hidx) {
        free(pp);
        free(hidx);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for the planar hull of %zu points", n);
    }
    for (size_t i = 0; i < n; i++) {
        pp[i].p[0] = w[3 * i + i0];
        pp[i].p[1] = w[3 * i + i1];
        pp[i].idx = i;
    }
    size_t m = monotone_chain(pp, n, hidx);
    if (m < 3) { /* projection collapsed: cannot happen above the dimension tolerance */
        free(pp);
        free(hidx);
        return acd_fail(err, ACD_ERR_INTERNAL, "planar hull of %zu points collapsed to %zu vertices", n, m);
    }
    /* normal of the counterclockwise polygon: +e_ax side */
    double un[3];
    memcpy(un, nrm, sizeof un);
    if (un[ax] < 0) un[0] = -un[0], un[1] = -un[1], un[2] = -un[2];
    acd_status st = hull_alloc(out, m, m - 2, err);
    if (st != ACD_OK) {
        free(pp);
        free(hidx);
        return st;
    }
    out->dim = 2;
    for (size_t k = 0; k < m; k++) set_vertex(out, k, points, pp[hidx[k]].idx);
    double d = 0;
    for (size_t k = 0; k < m; k++) {
        double v = -acd_dot3(un, out->vertices + 3 * k);
        if (k == 0 || v < d) d = v;
    }
    double area = 0;
    for (size_t t = 0; t + 2 < m; t++) {
        uint32_t *tri = out->triangles + 3 * t, *nb = out->neighbors + 3 * t;
        tri[0] = 0;
        tri[1] = (uint32_t)(t + 1);
        tri[2] = (uint32_t)(t + 2);
        nb[0] = t > 0 ? (uint32_t)(t - 1) : ACD_HULL_NO_NEIGHBOR;
        nb[1] = ACD_HULL_NO_NEIGHBOR;
        nb[2] = t + 3 < m ? (uint32_t)(t + 1) : ACD_HULL_NO_NEIGHBOR;
        memcpy(out->planes + 4 * t, un, sizeof un);
        out->planes[4 * t + 3] = d;
        const double *a = w + 3 * pp[hidx[0]].idx, *b = w + 3 * pp[hidx[t + 1]].idx, *c = w + 3 * pp[hidx[t + 2]].idx;
        double e1[3], e2[3], cr[3];
        sub3(b, a, e1);
        sub3(c, a, e2);
        acd_cross3(e1, e2, cr);
        area += 0.5 * norm3(cr);
    }
    out->area = area * s * s;
    out->volume = 0;
    free(pp);
    free(hidx);
    return ACD_OK;
}

/* ---------- dim 3 through qhull ---------- */

typedef struct qhull_run {
    qhT *qh;
    FILE *errf;
    char *errbuf;
    size_t errlen;
    int exitcode;
} qhull_run;

static void qhull_run_free(qhull_run *r) {
    if (r->qh) {
        int curlong, totlong;
        qh_freeqhull(r->qh, !qh_ALL);
        qh_memfreeshort(r->qh, &curlong, &totlong);
        free(r->qh);
        r->qh = NULL;
    }
    if (r->errf) {
        fclose(r->errf);
        r->errf = NULL;
    }
    free(r->errbuf);
    r->errbuf = NULL;
}

/* Runs qhull on the normalised points; returns qhull's exit code (0 = success) or -1 when memory
 * for the run itself was missing. */
static int qhull_run_do(qhull_run *r, double *w, size_t n) {
    memset(r, 0, sizeof *r);
    r->qh = calloc(1, sizeof *r->qh);
    if (!r->qh) return -1;
    r->errf = open_memstream(&r->errbuf, &r->errlen);
    if (!r->errf) r->errf = fopen("/dev/null", "w");
    if (!r->errf) {
        free(r->qh);
        r->qh = NULL;
        return -1;
    }
    char flags[] = "qhull Qt Q5";
    qh_zero(r->qh, r->errf);
    /* qh_new_qhull sets its own setjmp for the whole build and sets NOerrexit again before returning */
    r->exitcode = qh_new_qhull(r->qh, 3, (int)n, w, False, flags, NULL, r->errf);
    r->qh->NOerrexit = True;
    fflush(r->errf);
    return r->exitcode;
}

/* First line of qhull's error text (for the message). */
static void qhull_first_line(const qhull_run *r, char *buf, size_t size) {
    buf[0] = '\0';
    if (!r->errbuf) return;
    const char *s = r->errbuf;
    while (*s == '\n' || *s == ' ') s++;
    size_t k = 0;
    while (s[k] && s[k] != '\n' && k + 1 < size) {
        buf[k] = s[k];
        k++;
    }
    buf[k] = '\0';
}

/* qhull's toporient gives a consistent orientation of the simplicial facets; which parity means
 * outward is read off the facet whose (unoriented) triangle normal agrees best, in magnitude, with
 * qhull's outward normal. 1: a facet with toporient set is reversed to face outward. */
static int outward_flip(qhT *qh, const double *w) {
    facetT *facet;
    vertexT *vertex, **vertexp;
    int flip = 0;
    double bestdot = -1;
    FORALLfacets {
        const double *pv[3];
        int i = 0;
        FOREACHvertex_(facet->vertices) pv[i++] = w + 3 * qh_pointid(qh, vertex->point);
        double e1[3], e2[3], cr[3];
        sub3(pv[1], pv[0], e1);
        sub3(pv[2], pv[0], e2);
        acd_cross3(e1, e2, cr);
        double dt = acd_dot3(cr, facet->normal);
        if (fabs(dt) > bestdot) {
            bestdot = fabs(dt);
            flip = (dt > 0) != (facet->toporient != 0);
        }
    }
    return flip;
}

/* The hull out from qhull's facets, or (out NULL) its volume alone into *volume: the same facet
 * checks, orientation and volume sum in the same order either way (so the same bits). */
static acd_status hull_from_qhull(qhull_run *r, const double *points, const double *w, size_t n, double s,
                                  acd_hull *out, double *volume, acd_error *err) {
    qhT *qh = r->qh;
    facetT *facet;
    vertexT *vertex, **vertexp;
    facetT *neighbor, **neighborp;
    size_t nf = 0;
    FORALLfacets nf++;
    unsigned idcap = qh->facet_id + 1;
    uint32_t *fidx = malloc(idcap * sizeof *fidx);
    uint32_t *vmap = malloc(n * sizeof *vmap);
    if (!fidx || !vmap) {
        free(fidx);
        free(vmap);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for a hull of %zu facets", nf);
    }
    for (size_t i = 0; i < n; i++) vmap[i] = UINT32_MAX;
    size_t t = 0;
    FORALLfacets {
        int nv = 0, nn = 0;
        FOREACHvertex_(facet->vertices) {
            int pid = qh_pointid(qh, vertex->point);
            if (pid < 0 || (size_t)pid >= n) {
                free(fidx);
                free(vmap);
                return acd_fail(err, ACD_ERR_INTERNAL, "qhull facet f%u has a vertex that is no input point", facet->id);
            }
            vmap[pid] = 0;
            nv++;
        }
        FOREACHneighbor_(facet) nn++;
        if (nv != 3 || nn != 3 || facet->id >= idcap) {
            free(fidx);
            free(vmap);
            return acd_fail(err, ACD_ERR_INTERNAL, "qhull facet f%u is not a triangle (%d vertices, %d neighbours)",
                            facet->id, nv, nn);
        }
        fidx[facet->id] = (uint32_t)t++;
    }
    size_t nverts = 0, apex = SIZE_MAX; /* apex: the hull vertex of least input index (out->source[0]) */
    for (size_t i = 0; i < n; i++)
        if (vmap[i] == 0) {
            if (apex == SIZE_MAX) apex = i;
            vmap[i] = (uint32_t)nverts++;
        }
    if (out) {
        acd_status st = hull_alloc(out, nverts, nf, err);
        if (st != ACD_OK) {
            free(fidx);
            free(vmap);
            return st;
        }
        out->dim = 3;
        for (size_t i = 0; i < n; i++)
            if (vmap[i] != UINT32_MAX) set_vertex(out, vmap[i], points, i);
    }
    int flip = outward_flip(qh, w);
    double vol = 0, area = 0;
    const double *pa = w + 3 * apex;
    t = 0;
    FORALLfacets {
        size_t pid[3];
        uint32_t opp[3];
        int i = 0;
        FOREACHvertex_(facet->vertices) pid[i++] = (size_t)qh_pointid(qh, vertex->point);
        i = 0;
        FOREACHneighbor_(facet) opp[i++] = fidx[neighbor->id];
        if ((facet->toporient != 0) == flip) { /* inward as listed: swap the first two */
            size_t x = pid[0];
            pid[0] = pid[1];
            pid[1] = x;
            uint32_t y = opp[0];
            opp[0] = opp[1];
            opp[1] = y;
        }
        const double *a = w + 3 * pid[0], *b = w + 3 * pid[1], *c = w + 3 * pid[2];
        /* tetrahedra from a hull vertex (apex), each by the adaptive orient3d (accurate to about
         * its own magnitude, not to the coordinates' cube): on thin hulls the plain triple product
         * about the vertex centroid cancelled to a negative volume (coordinates 1e45 around a
         * slab 1e37 thick gave -4.6e117) */
        vol += acd_orient3d(a, b, c, pa) / 6.0;
        if (!out) continue;
        uint32_t *tri = out->triangles + 3 * t, *nb = out->neighbors + 3 * t;
        for (int k = 0; k < 3; k++) {
            tri[k] = vmap[pid[k]];
            nb[k] = opp[(k + 2) % 3]; /* across edge (k, k+1) = opposite vertex k+2 */
        }
        double nrm[3] = {facet->normal[0], facet->normal[1], facet->normal[2]};
        double len = norm3(nrm);
        if (len > 0)
            for (int c3 = 0; c3 < 3; c3++) nrm[c3] /= len;
        double d = 0;
        for (int k = 0; k < 3; k++) {
            double dv = -acd_dot3(nrm, out->vertices + 3 * tri[k]);
            if (k == 0 || dv < d) d = dv;
        }
        memcpy(out->planes + 4 * t, nrm, sizeof nrm);
        out->planes[4 * t + 3] = d;
        double e1[3], e2[3], cr[3];
        sub3(b, a, e1);
        sub3(c, a, e2);
        acd_cross3(e1, e2, cr);
        area += 0.5 * norm3(cr);
        t++;
    }
    vol = vol > 0 ? vol * s * s * s : 0.0;
    if (out) {
        out->volume = vol;
        out->area = area * s * s;
    } else {
        *volume = vol;
    }
    free(fidx);
    free(vmap);
    return ACD_OK;
}

/* ---------- enclosure: every input point inside every facet plane ----------
 *
 * qhull's facets are convex up to its roundoff, but the plane of an ill-conditioned facet (two of
 * its vertices nearly coincident) can leave a point it merged as coplanar far outside: six points
 * of fuzz_hull (tests/test_hull.c, test_enclosure_ill_conditioned) left one 1.2e-7 of the extent
 * outside. After every build the points are checked against the planes through a bounding-box
 * tree of the (normalised) points: a subtree is skipped when its box lies within the tolerance
 * below the plane, so only the points near a facet's plane are evaluated. A facet plane that a
 * point exceeds by more than the tolerance is lifted to pass through its farthest point (its
 * normal and the triangles unchanged; and then the triangles are dealt with: below); hulls without
 * a violation keep their bits.
 *
 * Only planes that can be off are checked (hull_plane_trusted): a facet whose triangle is well
 * shaped and whose qhull normal agrees with the triangle's own cross product. Such a plane is the
 * true plane of a hull face up to an angle of tilt + 3 eps (L + m) / h (the cross product's rounding,
 * L the longest edge, h the least altitude; and the vertices' own, m their largest normalised
 * coordinate: a triangle of 5e-8 of the extent near a face of the box was off by 1.3e-9, fuzz_hull,
 * 2026-11-26), so no point of the box (within a diagonal of the facet) is off by more than diagonal
 * x that angle, which the test keeps under a quarter of the tolerance. On real meshes 90-96% of the facets pass (bunny00, armadillo, fandisk at tau 0.05:
 * altitudes under 1e-3 of the extent on 4.6%, 4.3%, 10%); fuzz_hull still checks every plane.
 * That trusts qhull to have kept every point below a well-conditioned facet; it once did not (a
 * point lost 1.2e-9 of the extent above one), so when one of 14 extreme points of the set is
 * outside a plane (hull_extremes_outside), or qhull repaired a non-convexity on the way
 * (qhull_repaired), no facet is trusted. */

/* Points per leaf of the tree (the check's time on the hulls of a bunny00 run, against 64:
 * 1.7x with 16, 1.2x with 32, the same with 128). */
#define HULL_ENCLOSE_LEAF 64

typedef struct encl_node {
    double c[3], h[3];      /* box centre and half sides */
    double m[3], mlo, mhi;  /* leaves: a direction (the plane of three spread points) and the range of m.p */
    uint32_t begin, end;    /* range of the index array */
    uint32_t child;         /* first of two children (0: leaf; the root is never a child) */
} encl_node;

typedef struct encl_tree {
    encl_node *node;
    size_t nnode, cap;
    uint32_t *idx;
    double *pts; /* the points in the order of idx (leaves contiguous) */
} encl_tree;

static void encl_box(const double *w, const uint32_t *idx, uint32_t b, uint32_t e, encl_node *nd) {
    double lo[3], hi[3];
    for (uint32_t i = b; i < e; i++) {
        const double *p = w + 3 * (size_t)idx[i];
        for (int k = 0; k < 3; k++) {
            if (i == b || p[k] < lo[k]) lo[k] = p[k];
            if (i == b || p[k] > hi[k]) hi[k] = p[k];
        }
    }
    for (int k = 0; k < 3; k++) {
        nd->c[k] = 0.5 * (lo[k] + hi[k]);
        nd->h[k] = 0.5 * (hi[k] - lo[k]);
    }
    nd->begin = b;
    nd->end = e;
    nd->child = 0;
    nd->m[0] = nd->m[1] = nd->m[2] = 0;
    nd->mlo = nd->mhi = 0;
}

/* A leaf's slab: m the normal of the plane through its first point, the point farthest from it and
 * the point farthest from their line (a surface patch's normal, roughly: the leaf's thin side);
 * any m gives a valid bound, a good one a tight bound. m stays 0 for a collinear leaf. */
static void encl_slab(const double *w, const uint32_t *idx, encl_node *nd) {
    const double *p0 = w + 3 * (size_t)idx[nd->begin], *p1 = p0;
    double best = 0, u[3];
    for (uint32_t i = nd->begin; i < nd->end; i++) {
        const double *q = w + 3 * (size_t)idx[i];
        sub3(q, p0, u);
        double v = acd_dot3(u, u);
        if (v > best) best = v, p1 = q;
    }
    sub3(p1, p0, u);
    best = 0;
    for (uint32_t i = nd->begin; i < nd->end; i++) {
        const double *q = w + 3 * (size_t)idx[i];
        double d[3], cr[3];
        sub3(q, p0, d);
        acd_cross3(u, d, cr);
        double v = acd_dot3(cr, cr);
        if (v > best) best = v, memcpy(nd->m, cr, sizeof cr);
    }
    double len = norm3(nd->m);
    if (!(len > 0)) return;
    for (int k = 0; k < 3; k++) nd->m[k] /= len;
    for (uint32_t i = nd->begin; i < nd->end; i++) {
        double v = acd_dot3(nd->m, w + 3 * (size_t)idx[i]);
        if (i == nd->begin || v < nd->mlo) nd->mlo = v;
        if (i == nd->begin || v > nd->mhi) nd->mhi = v;
    }
}

/* Builds the tree: each node split at the midpoint of its longest side (by halves of its range
 * when that leaves a side empty). Returns 0 when out of memory. */
static int encl_build(encl_tree *T, const double *w, size_t n) {
    T->cap = n / 4 + 16;
    T->node = malloc(T->cap * sizeof *T->node);
    T->idx = malloc((n ? n : 1) * sizeof *T->idx);
    if (!T->node || !T->idx) return 0;
    for (size_t i = 0; i < n; i++) T->idx[i] = (uint32_t)i;
    encl_box(w, T->idx, 0, (uint32_t)n, &T->node[0]);
    T->nnode = 1;
    for (size_t k = 0; k < T->nnode; k++) { /* breadth first: nodes are appended behind k */
        encl_node nd = T->node[k];
        if (nd.end - nd.begin <= HULL_ENCLOSE_LEAF) {
            encl_slab(w, T->idx, &T->node[k]);
            continue;
        }
        int ax = 0;
        for (int a = 1; a < 3; a++)
            if (nd.h[a] > nd.h[ax]) ax = a;
        uint32_t i = nd.begin, j = nd.end;
        while (i < j) { /* partition: coordinate below the centre first */
            if (w[3 * (size_t)T->idx[i] + ax] < nd.c[ax]) {
                i++;
            } else {
                uint32_t x = T->idx[i];
                T->idx[i] = T->idx[--j];
                T->idx[j] = x;
            }
        }
        if (i == nd.begin || i == nd.end) i = nd.begin + (nd.end - nd.begin) / 2;
        if (T->nnode + 2 > T->cap) {
            size_t cap = 2 * T->cap;
            encl_node *g = realloc(T->node, cap * sizeof *g);
            if (!g) return 0;
            T->node = g;
            T->cap = cap;
        }
        T->node[k].child = (uint32_t)T->nnode;
        encl_box(w, T->idx, nd.begin, i, &T->node[T->nnode++]);
        encl_box(w, T->idx, i, nd.end, &T->node[T->nnode++]);
    }
    T->pts = malloc((n ? n : 1) * 3 * sizeof *T->pts);
    if (!T->pts) return 0;
    for (size_t i = 0; i < n; i++) memcpy(T->pts + 3 * i, w + 3 * (size_t)T->idx[i], 3 * sizeof(double));
    return 1;
}

/* Largest n.p + d over the points of the tree, or a value <= tol when every point is within tol. */
static double encl_worst(const encl_tree *T, const double *nrm, double d, double tol) {
    uint32_t stack[128];
    size_t top = 0;
    double worst = -INFINITY;
    stack[top++] = 0;
    while (top > 0) {
        const encl_node *nd = &T->node[stack[--top]];
        double ub = acd_dot3(nrm, nd->c) + d + fabs(nrm[0]) * nd->h[0] + fabs(nrm[1]) * nd->h[1] + fabs(nrm[2]) * nd->h[2];
        if (ub <= tol) continue;
        if (!nd->child) { /* n = a m + r: a (m.p) within the slab, r.p within the box */
            double a = acd_dot3(nrm, nd->m), r[3] = {nrm[0] - a * nd->m[0], nrm[1] - a * nd->m[1], nrm[2] - a * nd->m[2]};
            ub = (a > 0 ? a * nd->mhi : a * nd->mlo) + acd_dot3(r, nd->c) + d + fabs(r[0]) * nd->h[0] + fabs(r[1]) * nd->h[1] +
                 fabs(r[2]) * nd->h[2];
            if (ub <= tol) continue;
        }
        if (nd->child && top + 2 <= sizeof stack / sizeof *stack) {
            stack[top++] = nd->child;
            stack[top++] = nd->child + 1;
            continue;
        }
        for (uint32_t i = nd->begin; i < nd->end; i++) { /* a leaf (or a subtree past the stack's depth) */
            double v = acd_dot3(nrm, T->pts + 3 * (size_t)i) + d;
            if (v > worst) worst = v;
        }
    }
    return worst;
}

/* Checks the planes of out (built from w, the points normalised by s) against every point and
 * lifts those exceeded by more than tol (normalised units). */
/* Rounding of a triangle's plane, in units of DBL_EPSILON x (L + m) / h (3 in the analysis, with a
 * margin): the cross product's (L / h), and the vertices' own (m / h, m their largest normalised
 * coordinate: w carries the normalisation's rounding, eps x |w|, and qhull decided on w with its
 * roundoff of the same size), and the share of the tolerance a trusted plane may be off by. */
#define HULL_ENCLOSE_ROUNDOFF 8.0
/* A hull whose volume is under this fraction of its points' box diagonal cubed is thin (hull_enclose
 * then trusts none of its facets; 1e-6 cost 2-3% of the armadillo's budget run, many of its pieces'
 * hulls then counting as thin; the fuzz input that needed it is at 4e-8). */
#define HULL_THIN_REL 1e-7
#define HULL_ENCLOSE_TRUST_SHARE 0.25

/* A facet plane (unit normal nrm) of the triangle a, b, c that no point of a box of diagonal diag
 * can exceed by more than tol x HULL_ENCLOSE_TRUST_SHARE: the triangle's own normal agrees with
 * nrm (same side, small tilt) and is well conditioned. */
static int hull_plane_trusted(const double *nrm, const double *a, const double *b, const double *c, double diag,
                              double tol) {
    double e1[3], e2[3], e3[3], cr[3], x[3];
    sub3(b, a, e1);
    sub3(c, a, e2);
    sub3(c, b, e3);
    acd_cross3(e1, e2, cr);
    double area2 = norm3(cr), lmax = fmax(norm3(e1), fmax(norm3(e2), norm3(e3)));
    if (!(area2 > 0) || acd_dot3(nrm, cr) <= 0) return 0;
    double h = area2 / lmax; /* the least altitude */
    for (int k = 0; k < 3; k++) cr[k] /= area2;
    acd_cross3(nrm, cr, x);
    /* the vertices' magnitude: a sliver far from the centre (fuzz_hull: altitude 4.9e-11, edges
     * 5.5e-8, at |w| 0.5) is tilted by its vertices' rounding far more than by its cross product's */
    double m = 0;
    for (int k = 0; k < 3; k++) m = fmax(m, fmax(fabs(a[k]), fmax(fabs(b[k]), fabs(c[k]))));
    double angle = norm3(x) + HULL_ENCLOSE_ROUNDOFF * DBL_EPSILON * (lmax + m) / h;
    return diag * angle <= HULL_ENCLOSE_TRUST_SHARE * tol;
}

/* ---------- the triangles: a plane of each triangle encloses every point ----------
 *
 * The planes above enclose every point, but a lifted plane no longer passes through its triangle:
 * the triangles (the mesh written to OBJ) still miss the point. What the mesh promises: each
 * triangle has a plane that passes within the tolerance of its three vertices (a plane of the
 * triangle) and has every input point below it within the tolerance; the planes out holds are
 * those planes. A trusted facet's qhull plane is one (hull_plane_trusted: within a quarter of the
 * tolerance of the triangle's own plane); for the others hull_enclose checks both halves: no point
 * more than tol above qhull's plane and no vertex more than tol below it. When either fails, the
 * triangle's own plane (its cross product, computed to about eps: tri_plane) is taken if every
 * point is below it within tol. (qhull's plane of a sliver from a merged facet is the facet's, and
 * the right one: the sliver's own plane turns about its long edge with the roundoff of its short
 * one, and on knot1's parts it had other hull vertices 5e-6 of the diagonal above it; so the own
 * plane is tried only after qhull's fails.) When neither plane works, qhull dropped a point it
 * should have kept (fuzz_hull's six points: B 1.2e-7 of the extent outside facet (C, D, A), qhull
 * took it as coplanar) and the hull is rebuilt (hull_repair): the exact convex hull, by a
 * Quickhull of our own over the same normalised points whose every decision is exact
 * (acd_orient3d), adding the point farthest above a triangle's own plane among those strictly
 * above it until there is none. Its mesh is exactly convex at every step (a point strictly outside
 * sees a disk of triangles, replaced by the cone from the point over the disk's boundary), every
 * point is inside it, and its vertices are input points, as qhull's. (Adding only the points more
 * than tol above a plane was tried: on the six points it kept the tetrahedron A, C, E, F, every
 * point within tol of every plane, yet B 1.1e-6 from the solid beyond its razor-thin rim, the
 * distance the brief was about; the exact hull has B as a vertex.) Chosen over a second qhull run
 * (other options, or a joggled copy: the joggle moves points by its amplitude, and the result would
 * need the same check and a fallback again) and over a local Quickhull step on qhull's mesh (tried
 * first: qhull's mesh is convex only up to its roundoff, and on 240 of the 720 orders of the six
 * points the step left a hull vertex 1.5e-8 above a new triangle, which no step can add): it is
 * exact, its cost falls only on the hulls that need it, and hulls without a violation keep every
 * bit of qhull's.
 *
 * The promise is on planes: near a razor-thin rim (two faces meeting at a dihedral angle phi near
 * 0) a point within tol of every plane may lie up to about tol / sin(phi / 2) from the solid, and
 * qhull's hull is kept when its planes pass (fuzz corpus thin_rim: 1.2e-7 of the extent).
 *
 * acd_hull_volume (the volume alone, no hull: no check) keeps qhull's volume: it differs from a
 * rebuilt hull's (on the six points' flat hull 3.36084547e-7 against 3.36084586e-7, 1.2e-7 of
 * it). Its callers rank cut planes by it and compare it only with volumes it computed itself
 * (docs/results/geom3.md). */

/* Largest angle (radians) tri_plane's normal may be off the triangle's exact normal for the
 * triangle to have a computed plane (beyond: a triangle of near-collinear vertices). */
#define HULL_TRI_MAX_ANGLE 1e-2

/* a - b as hi + lo exactly (Knuth's two-sum of a and -b). */
static void two_diff(double a, double b, double *hi, double *lo) {
    double s = a - b, bv = s - a, av = s - bv;
    *hi = s;
    *lo = (a - av) - (b + bv);
}

/* u1 v2 - u2 v1 for factors given as exact hi + lo pairs: the high parts' products with their exact
 * errors (fma), the terms with one low part; the two low parts' product (eps^2 of the factors' sizes)
 * left out. Off by at most about 2 eps of the result plus 8 eps^2 |u| |v|. */
static double cross_term(double u1h, double u1l, double v2h, double v2l, double u2h, double u2l, double v1h,
                         double v1l) {
    double p = u1h * v2h, q = u2h * v1h;
    double ep = fma(u1h, v2h, -p), eq = fma(u2h, v1h, -q);
    return (p - q) + ((ep - eq) + (u1h * v2l + u1l * v2h) - (u2h * v1l + u2l * v1h));
}

/* The triangle a, b, c's own plane: unit normal nrm (the cross product of the edges at the vertex
 * opposite the longest, from their exact differences: cross_term), offset *d through the highest
 * vertex along nrm and *angle, how far nrm may be off the exact plane's normal. 0 (no plane) when
 * that angle exceeds HULL_TRI_MAX_ANGLE. */
static int tri_plane(const double *a, const double *b, const double *c, double *nrm, double *d, double *angle) {
    const double *v[3] = {a, b, c};
    double len[3];
    for (int k = 0; k < 3; k++) { /* the edge opposite v[k] */
        double e[3];
        sub3(v[(k + 2) % 3], v[(k + 1) % 3], e);
        len[k] = norm3(e);
    }
    int o = 0;
    for (int k = 1; k < 3; k++)
        if (len[k] > len[o]) o = k;
    const double *p = v[o], *q = v[(o + 1) % 3], *r = v[(o + 2) % 3];
    double uh[3], ul[3], wh[3], wl[3];
    for (int k = 0; k < 3; k++) {
        two_diff(q[k], p[k], &uh[k], &ul[k]);
        two_diff(r[k], p[k], &wh[k], &wl[k]);
    }
    nrm[0] = cross_term(uh[1], ul[1], wh[2], wl[2], uh[2], ul[2], wh[1], wl[1]);
    nrm[1] = cross_term(uh[2], ul[2], wh[0], wl[0], uh[0], ul[0], wh[2], wl[2]);
    nrm[2] = cross_term(uh[0], ul[0], wh[1], wl[1], uh[1], ul[1], wh[0], wl[0]);
    double area2 = norm3(nrm);
    if (!(area2 > 0)) return 0;
    *angle = 8.0 * DBL_EPSILON + 32.0 * DBL_EPSILON * DBL_EPSILON * norm3(uh) * norm3(wh) / area2;
    if (!(*angle <= HULL_TRI_MAX_ANGLE)) return 0;
    for (int k = 0; k < 3; k++) nrm[k] /= area2;
    *d = -fmax(acd_dot3(nrm, a), fmax(acd_dot3(nrm, b), acd_dot3(nrm, c)));
    return 1;
}

/* Slack of the selection by a triangle's computed plane (angle from tri_plane) in a box of
 * diagonal diag: |n.p + d - the exact distance| <= angle x diag plus rounding. */
static double tri_slack(double angle, double diag) { return 2.0 * angle * diag + 16.0 * DBL_EPSILON * diag; }

/* p outside the exact plane of the triangle a, b, c (counterclockwise seen from outside, computed
 * unit normal nrm) by more than tol: p - tol nrm strictly above it. */
static int tri_outside(const double *a, const double *b, const double *c, const double *nrm, const double *p,
                       double tol) {
    double q[3] = {p[0] - tol * nrm[0], p[1] - tol * nrm[1], p[2] - tol * nrm[2]};
    return acd_orient3d(a, b, c, q) < 0;
}

/* The point of the tree outside the triangle a, b, c by more than tol (tri_outside) farthest above
 * its computed plane (nrm, d), among the points with n.p + d > thr; UINT32_MAX when none. */
static uint32_t encl_tri_violator(const encl_tree *T, const double *nrm, double d, double thr, const double *a,
                                  const double *b, const double *c, double tol) {
    uint32_t stack[128], best = UINT32_MAX;
    size_t top = 0;
    double bestv = -INFINITY;
    stack[top++] = 0;
    while (top > 0) {
        const encl_node *nd = &T->node[stack[--top]];
        double ub = acd_dot3(nrm, nd->c) + d + fabs(nrm[0]) * nd->h[0] + fabs(nrm[1]) * nd->h[1] + fabs(nrm[2]) * nd->h[2];
        if (ub <= thr) continue;
        if (!nd->child) {
            double al = acd_dot3(nrm, nd->m), r[3] = {nrm[0] - al * nd->m[0], nrm[1] - al * nd->m[1], nrm[2] - al * nd->m[2]};
            ub = (al > 0 ? al * nd->mhi : al * nd->mlo) + acd_dot3(r, nd->c) + d + fabs(r[0]) * nd->h[0] +
                 fabs(r[1]) * nd->h[1] + fabs(r[2]) * nd->h[2];
            if (ub <= thr) continue;
        }
        if (nd->child && top + 2 <= sizeof stack / sizeof *stack) {
            stack[top++] = nd->child;
            stack[top++] = nd->child + 1;
            continue;
        }
        for (uint32_t i = nd->begin; i < nd->end; i++) {
            const double *p = T->pts + 3 * (size_t)i;
            double v = acd_dot3(nrm, p) + d;
            if (v > thr && v > bestv && tri_outside(a, b, c, nrm, p, tol)) {
                bestv = v;
                best = T->idx[i];
            }
        }
    }
    return best;
}

/* The mesh being repaired: triangles by input point index. */
typedef struct rep_edge {
    uint32_t a, b, u, t; /* horizon edge a -> b of the seen triangle t, u the triangle across */
} rep_edge;

typedef struct rep_mesh {
    uint32_t *tri, *nb;   /* 3 per triangle: point indices, the triangle across edge (k, k+1) */
    double *pl;           /* 4 per triangle: the plane, in input coordinates */
    unsigned char *state; /* per triangle: 0 alive, 1 removed, 2 seen by the point being added */
    size_t m, cap;
    unsigned char *isv;   /* per point: a vertex of the mesh */
    uint32_t *hstart;     /* per point: the horizon edge from it (UINT32_MAX: none) */
    uint32_t *vis, *order;
    rep_edge *hor;
    size_t vcap;          /* capacity of vis, order and hor */
} rep_mesh;

static void rep_free(rep_mesh *M) {
    free(M->tri);
    free(M->nb);
    free(M->pl);
    free(M->state);
    free(M->isv);
    free(M->hstart);
    free(M->vis);
    free(M->order);
    free(M->hor);
}

/* Room for k more triangles (and for a step over every triangle). 0 when out of memory. */
static int rep_reserve(rep_mesh *M, size_t k) {
    if (M->m + k > M->cap) {
        size_t cap = 2 * (M->m + k);
        uint32_t *tri = realloc(M->tri, 3 * cap * sizeof *tri);
        if (tri) M->tri = tri;
        uint32_t *nb = realloc(M->nb, 3 * cap * sizeof *nb);
        if (nb) M->nb = nb;
        double *pl = realloc(M->pl, 4 * cap * sizeof *pl);
        if (pl) M->pl = pl;
        unsigned char *state = realloc(M->state, cap);
        if (state) M->state = state;
        if (!tri || !nb || !pl || !state) return 0;
        M->cap = cap;
    }
    if (M->vcap < M->cap) {
        size_t cap = M->cap;
        uint32_t *vis = realloc(M->vis, cap * sizeof *vis);
        if (vis) M->vis = vis;
        uint32_t *order = realloc(M->order, cap * sizeof *order);
        if (order) M->order = order;
        rep_edge *hor = realloc(M->hor, cap * sizeof *hor);
        if (hor) M->hor = hor;
        if (!vis || !order || !hor) return 0;
        M->vcap = cap;
    }
    return 1;
}

/* Point p strictly above triangle t's exact plane. */
static int rep_sees(const rep_mesh *M, const double *w, uint32_t t, const double *p) {
    const uint32_t *tr = M->tri + 3 * (size_t)t;
    return acd_orient3d(w + 3 * (size_t)tr[0], w + 3 * (size_t)tr[1], w + 3 * (size_t)tr[2], p) < 0;
}

/* A triangle's plane in input coordinates (points), lifted as hull_enclose lifts qhull's. */
static void rep_plane(rep_mesh *M, size_t t, const double *points, const double *w, double s, const encl_tree *T,
                      double tol) {
    const uint32_t *tr = M->tri + 3 * t;
    const double *a = w + 3 * (size_t)tr[0], *b = w + 3 * (size_t)tr[1], *c = w + 3 * (size_t)tr[2];
    double nrm[3], e1[3], e2[3], dw = 0, d = 0, angle;
    if (!tri_plane(a, b, c, nrm, &dw, &angle)) { /* too thin for tri_plane: the plain cross product */
        sub3(b, a, e1);
        sub3(c, a, e2);
        acd_cross3(e1, e2, nrm);
        double len = norm3(nrm);
        if (len > 0) /* (exactly it is not 0: p strictly above a triangle with a, b) */
            for (int k = 0; k < 3; k++) nrm[k] /= len;
        else /* collinear to doubles: the plane of the triangle across (a, b), which holds a and b */
            memcpy(nrm, M->pl + 4 * (size_t)M->nb[3 * t], sizeof nrm);
    }
    for (int k = 0; k < 3; k++) {
        double v = -acd_dot3(nrm, points + 3 * (size_t)tr[k]), vw = -acd_dot3(nrm, w + 3 * (size_t)tr[k]);
        if (k == 0 || v < d) d = v;
        if (k == 0 || vw < dw) dw = vw;
    }
    double worst = encl_worst(T, nrm, dw, tol);
    if (worst > tol) d -= worst * s;
    memcpy(M->pl + 4 * t, nrm, sizeof nrm);
    M->pl[4 * t + 3] = d;
}

/* One Quickhull step: point p (no vertex yet), outside triangle t0, made a vertex. Returns 1 done,
 * 0 not possible (the seen triangles are no disk, or p is a vertex: the mesh is unchanged), -1 out
 * of memory. The planes of the new triangles come after the cone is linked (rep_plane may take a
 * neighbour's). */
static int rep_add(rep_mesh *M, const double *points, const double *w, double s, const encl_tree *T, double tol,
                   uint32_t p, uint32_t t0) {
    if (M->isv[p]) return 0;
    if (!rep_reserve(M, M->m)) return -1; /* vis, order and hor: room for 2m (a horizon has at most 1.5m edges) */
    const double *pp = w + 3 * (size_t)p;
    size_t nvis = 0, nh = 0;
    M->state[t0] = 2;
    M->vis[nvis++] = t0;
    for (size_t k = 0; k < nvis; k++) { /* the connected triangles p sees */
        uint32_t t = M->vis[k];
        for (int e = 0; e < 3; e++) {
            uint32_t u = M->nb[3 * (size_t)t + e];
            if (M->state[u] == 0 && rep_sees(M, w, u, pp)) {
                M->state[u] = 2;
                M->vis[nvis++] = u;
            }
        }
    }
    int ok = 1;
    for (size_t k = 0; k < nvis && ok; k++) { /* the horizon: each vertex starts one edge */
        uint32_t t = M->vis[k];
        for (int e = 0; e < 3 && ok; e++) {
            uint32_t u = M->nb[3 * (size_t)t + e];
            if (M->state[u] == 2) continue;
            rep_edge h = {M->tri[3 * (size_t)t + e], M->tri[3 * (size_t)t + (e + 1) % 3], u, t};
            if (M->hstart[h.a] != UINT32_MAX || nh >= M->vcap) {
                ok = 0;
                break;
            }
            M->hstart[h.a] = (uint32_t)nh;
            M->hor[nh++] = h;
        }
    }
    if (ok && nh < 3) ok = 0;
    for (size_t i = 0, k = 0; ok && i < nh; i++) { /* one cycle through every horizon edge */
        M->order[i] = (uint32_t)k;
        k = M->hstart[M->hor[k].b];
        if (k == UINT32_MAX || (k == 0) != (i + 1 == nh)) ok = 0;
    }
    if (ok && !rep_reserve(M, nh)) ok = -1;
    if (ok != 1) {
        for (size_t k = 0; k < nvis; k++) M->state[M->vis[k]] = 0;
        for (size_t i = 0; i < nh; i++) M->hstart[M->hor[i].a] = UINT32_MAX;
        return ok;
    }
    size_t base = M->m;
    for (size_t i = 0; i < nh; i++) { /* the cone: (a, b, p) across a -> b from u */
        const rep_edge *h = &M->hor[M->order[i]];
        size_t t = base + i;
        uint32_t *tr = M->tri + 3 * t, *nb = M->nb + 3 * t;
        tr[0] = h->a;
        tr[1] = h->b;
        tr[2] = p;
        nb[0] = h->u;
        nb[1] = (uint32_t)(base + (i + 1) % nh);
        nb[2] = (uint32_t)(base + (i + nh - 1) % nh);
        M->state[t] = 0;
        uint32_t *un = M->nb + 3 * (size_t)h->u;
        for (int f = 0; f < 3; f++)
            if (un[f] == h->t && M->tri[3 * (size_t)h->u + f] == h->b) un[f] = (uint32_t)t;
    }
    M->m += nh;
    for (size_t k = 0; k < nvis; k++) { /* vertices inside the seen disk leave the hull */
        const uint32_t *tr = M->tri + 3 * (size_t)M->vis[k];
        for (int f = 0; f < 3; f++)
            if (M->hstart[tr[f]] == UINT32_MAX) M->isv[tr[f]] = 0;
        M->state[M->vis[k]] = 1;
    }
    for (size_t i = 0; i < nh; i++) M->hstart[M->hor[i].a] = UINT32_MAX;
    M->isv[p] = 1;
    for (size_t i = 0; i < nh; i++) rep_plane(M, base + i, points, w, s, T, tol);
    return 1;
}

/* The first tetrahedron, of four of out's vertices (the first, the farthest from it, the farthest
 * from their line, the farthest from their plane), its faces outward. 0 when the four are
 * exactly coplanar (not for a solid hull: its extreme points are vertices). */
static int rep_simplex(rep_mesh *M, const acd_hull *out, const double *w) {
    const uint32_t *src = out->source;
    uint32_t v[4] = {src[0], src[0], src[0], src[0]};
    double best = 0;
    const double *p0 = w + 3 * (size_t)v[0];
    for (size_t k = 0; k < out->nvertices; k++) {
        double d[3];
        sub3(w + 3 * (size_t)src[k], p0, d);
        if (acd_dot3(d, d) > best) best = acd_dot3(d, d), v[1] = src[k];
    }
    double u[3];
    sub3(w + 3 * (size_t)v[1], p0, u);
    best = 0;
    for (size_t k = 0; k < out->nvertices; k++) {
        double d[3], cr[3];
        sub3(w + 3 * (size_t)src[k], p0, d);
        acd_cross3(u, d, cr);
        if (acd_dot3(cr, cr) > best) best = acd_dot3(cr, cr), v[2] = src[k];
    }
    best = 0;
    double o3 = 0;
    for (size_t k = 0; k < out->nvertices; k++) {
        double o = acd_orient3d(p0, w + 3 * (size_t)v[1], w + 3 * (size_t)v[2], w + 3 * (size_t)src[k]);
        if (fabs(o) > best) best = fabs(o), o3 = o, v[3] = src[k];
    }
    if (!(best > 0)) return 0;
    if (o3 < 0) { /* v[3] above (v0, v1, v2): swap two for the positive orientation */
        uint32_t x = v[1];
        v[1] = v[2];
        v[2] = x;
    }
    static const int face[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    for (int f = 0; f < 4; f++)
        for (int k = 0; k < 3; k++) M->tri[3 * f + k] = v[face[f][k]];
    for (int f = 0; f < 4; f++) /* neighbours: the face running the edge backwards */
        for (int k = 0; k < 3; k++)
            for (int g = 0; g < 4; g++)
                for (int l = 0; l < 3; l++)
                    if (M->tri[3 * g + l] == M->tri[3 * f + (k + 1) % 3] && M->tri[3 * g + (l + 1) % 3] == M->tri[3 * f + k])
                        M->nb[3 * f + k] = (uint32_t)g;
    memset(M->state, 0, 4);
    memset(M->pl, 0, 16 * sizeof *M->pl);
    M->m = 4;
    for (int k = 0; k < 4; k++) M->isv[v[k]] = 1;
    return 1;
}

/* The point to add for triangle t: the one farthest above its own plane among those strictly above
 * it (exact); every point is scanned for a triangle too thin for a computed plane. UINT32_MAX when
 * none. */
static uint32_t rep_violator(const rep_mesh *M, size_t t, const double *w, size_t n, const encl_tree *T, double diag) {
    const uint32_t *tr = M->tri + 3 * t;
    const double *a = w + 3 * (size_t)tr[0], *b = w + 3 * (size_t)tr[1], *c = w + 3 * (size_t)tr[2];
    double nrm[3], d, angle;
    if (tri_plane(a, b, c, nrm, &d, &angle)) return encl_tri_violator(T, nrm, d, -tri_slack(angle, diag), a, b, c, 0.0);
    uint32_t best = UINT32_MAX;
    double bo = 0;
    for (size_t i = 0; i < n; i++) {
        double o = acd_orient3d(a, b, c, w + 3 * i);
        if (o < bo) bo = o, best = (uint32_t)i;
    }
    return best;
}

/* Rebuilds out as the exact convex hull of the normalised points w (tree T) by a Quickhull whose
 * decisions are exact: from a tetrahedron of out's vertices, the point farthest above a triangle's
 * own plane among those strictly above it is added (rep_add) until no triangle has one; out keeps
 * qhull's hull when a step is not possible (not seen: the mesh is exactly convex) or the steps
 * exceed n. */
static acd_status hull_repair(acd_hull *out, const double *points, const double *w, size_t n, double s, double diag,
                              const encl_tree *T, acd_error *err) {
    const double tol = ACD_TOL_REL_DIST * diag;
    rep_mesh M = {0};
    M.isv = calloc(n, 1);
    M.hstart = malloc(n * sizeof *M.hstart);
    int ok = M.isv && M.hstart && rep_reserve(&M, 64) ? 1 : -1;
    if (ok == 1) {
        for (size_t i = 0; i < n; i++) M.hstart[i] = UINT32_MAX;
        ok = rep_simplex(&M, out, w);
    }
    for (size_t t = 0; ok == 1 && t < M.m; t++) rep_plane(&M, t, points, w, s, T, tol);
    size_t steps = 0;
    for (size_t t = 0; ok == 1 && t < M.m; t++) {
        if (M.state[t]) continue;
        uint32_t p = rep_violator(&M, t, w, n, T, diag);
        if (p == UINT32_MAX) continue;
        ok = ++steps > n ? 0 : rep_add(&M, points, w, s, T, tol, p, (uint32_t)t);
    }
    acd_hull h = {0};
    uint32_t *tmap = NULL, *vmap = NULL;
    if (ok == 1) { /* out from the alive triangles, vertices in input order (as hull_from_qhull) */
        tmap = malloc((M.m ? M.m : 1) * sizeof *tmap);
        vmap = malloc(n * sizeof *vmap);
        if (!tmap || !vmap) ok = -1;
    }
    size_t nt = 0, nv = 0, apex = SIZE_MAX;
    if (ok == 1) {
        for (size_t t = 0; t < M.m; t++) tmap[t] = M.state[t] ? UINT32_MAX : (uint32_t)nt++;
        for (size_t i = 0; i < n; i++) {
            vmap[i] = M.isv[i] ? (uint32_t)nv++ : UINT32_MAX;
            if (M.isv[i] && apex == SIZE_MAX) apex = i;
        }
        for (size_t t = 0; t < M.m && ok == 1; t++)
            for (int k = 0; k < 3 && !M.state[t]; k++)
                if (vmap[M.tri[3 * t + k]] == UINT32_MAX) ok = 0; /* cannot happen: a removed vertex in use */
        if (ok == 1 && nt != 2 * nv - 4) ok = 0;
    }
    if (ok == 1) {
        acd_status st = hull_alloc(&h, nv, nt, err);
        if (st != ACD_OK) ok = -1;
    }
    if (ok == 1) {
        h.dim = 3;
        for (size_t i = 0; i < n; i++)
            if (vmap[i] != UINT32_MAX) set_vertex(&h, vmap[i], points, i);
        double vol = 0, area = 0;
        const double *pa = w + 3 * apex;
        for (size_t t = 0; t < M.m; t++) {
            if (M.state[t]) continue;
            size_t q = tmap[t];
            const uint32_t *tr = M.tri + 3 * t;
            for (int k = 0; k < 3; k++) {
                h.triangles[3 * q + k] = vmap[tr[k]];
                h.neighbors[3 * q + k] = tmap[M.nb[3 * t + k]];
            }
            memcpy(h.planes + 4 * q, M.pl + 4 * t, 4 * sizeof *h.planes);
            const double *a = w + 3 * (size_t)tr[0], *b = w + 3 * (size_t)tr[1], *c = w + 3 * (size_t)tr[2];
            vol += acd_orient3d(a, b, c, pa) / 6.0; /* as hull_from_qhull sums it */
            double e1[3], e2[3], cr[3];
            sub3(b, a, e1);
            sub3(c, a, e2);
            acd_cross3(e1, e2, cr);
            area += 0.5 * norm3(cr);
        }
        h.volume = vol > 0 ? vol * s * s * s : 0.0;
        h.area = area * s * s;
        acd_hull_free(out);
        *out = h;
    }
    free(tmap);
    free(vmap);
    rep_free(&M);
    if (ok < 0) {
        acd_hull_free(&h);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory repairing a hull of %zu points", n);
    }
    return ACD_OK;
}

/* Directions whose extreme points hull_extremes_outside checks: the axes and the cube's diagonals. */
#define HULL_EXTREME_DIRS 7

/* Whether an extreme point of w along an axis or a cube diagonal (each direction both ways) is more
 * than tol above a plane of out: qhull lost a point, and no facet is to be trusted. qhull can lose
 * one above a well-conditioned facet: fuzz_hull found 17 points at 1e40 with tiny ones mixed in
 * where the one of greatest y lay 1.2e-9 of the extent above the facet of normal (0, 1, 0) (qhull's
 * max_outside: 2.8e-16; docs/results/geom3.md). A guard, not a proof: a lost point that is extreme
 * in none of these 14 directions stays unseen above a trusted facet. */
static int hull_extremes_outside(const acd_hull *out, const double *w, size_t n, double tol) { /* n >= 4 */
    static const double dir[HULL_EXTREME_DIRS][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1},
                                                     {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
    size_t ext[2 * HULL_EXTREME_DIRS];
    double best[2 * HULL_EXTREME_DIRS];
    for (int k = 0; k < 2 * HULL_EXTREME_DIRS; k++) {
        ext[k] = 0;
        best[k] = acd_dot3(dir[k / 2], w);
    }
    for (size_t i = 1; i < n; i++) {
        const double *p = w + 3 * i;
        for (int k = 0; k < HULL_EXTREME_DIRS; k++) {
            double v = acd_dot3(dir[k], p);
            if (v > best[2 * k]) best[2 * k] = v, ext[2 * k] = i;
            if (v < best[2 * k + 1]) best[2 * k + 1] = v, ext[2 * k + 1] = i;
        }
    }
    for (size_t t = 0; t < out->ntriangles; t++) {
        const double *pl = out->planes + 4 * t;
        const uint32_t *tri = out->triangles + 3 * t;
        double d = 0; /* in normalised coordinates, as hull_enclose computes it */
        for (int k = 0; k < 3; k++) {
            double dv = -acd_dot3(pl, w + 3 * (size_t)out->source[tri[k]]);
            if (k == 0 || dv < d) d = dv;
        }
        for (int k = 0; k < 2 * HULL_EXTREME_DIRS; k++)
            if (acd_dot3(pl, w + 3 * ext[k]) + d > tol) return 1;
    }
    return 0;
}

/* Whether qhull repaired a non-convexity while building (its own statistics): a new facet flipped
 * (its normal against its horizon) or a concave ridge between two facets within its merge tolerance
 * of coplanar. Both are merged away, and a point partitioned before the merge may end up above the
 * merged facet, however well shaped: fuzz_hull's 17 points spanning 1e45 to 1e-314 (a flipped facet,
 * a concave-coplanar ridge) left one 1.35e-9 of the extent above a trusted facet, extreme in none of
 * hull_extremes_outside's directions; its 17 points at 1e40 (test_lost_extreme_point) had a
 * concave-coplanar ridge too. Rare on real parts: 1 hull in about 850 of the bunny00 and fandisk
 * budget runs, no flipped facet (docs/results/geom3.md). */
static int qhull_repaired(qhT *qh) { return zzval_(Zflippedfacets) > 0 || zzval_(Zconcavecoplanarridge) > 0; }

/* Checks the planes of out (built from w, the points normalised by s, box diagonal diag) that are
 * not trusted (none when qhull repaired a non-convexity, repaired: qhull_repaired, or an extreme
 * point is outside: hull_extremes_outside): each must have every point below it and its triangle's
 * vertices on it, within ACD_TOL_REL_DIST x diag (normalised units). A plane that fails is replaced by its triangle's
 * own plane when that one has every point below it; otherwise it is lifted to its farthest point and
 * the hull rebuilt (hull_repair; the lifted planes stay if the rebuild is not possible). */
static acd_status hull_enclose(acd_hull *out, const double *points, const double *w, size_t n, double s, double diag,
                               int repaired, acd_error *err) {
    const double tol = ACD_TOL_REL_DIST * diag;
    encl_tree T = {0};
    /* a thin hull (volume under HULL_THIN_REL x diag^3, normalised units): qhull's precision is
     * weakest there, and fuzz_hull found a point 1.3e-9 of the extent above a trusted facet of one
     * (17 points spanning 1e45 to 1e-314, neither repaired nor an extreme outside): every plane checked */
    const double vn = out->volume / (s * s * s);
    int thin = !(vn >= HULL_THIN_REL * diag * diag * diag);
    int built = 0, missed = 0, lost = repaired || thin || hull_extremes_outside(out, w, n, tol);
    acd_status st = ACD_OK;
    for (size_t t = 0; t < out->ntriangles; t++) {
        double *pl = out->planes + 4 * t;
        const uint32_t *tri = out->triangles + 3 * t;
        const double *a = w + 3 * (size_t)out->source[tri[0]], *b = w + 3 * (size_t)out->source[tri[1]],
                     *c = w + 3 * (size_t)out->source[tri[2]];
        if (!lost && hull_plane_trusted(pl, a, b, c, diag, tol)) continue;
        if (!built) {
            built = 1;
            if (!encl_build(&T, w, n)) {
                st = acd_fail(err, ACD_ERR_NOMEM, "out of memory checking a hull of %zu points", n);
                break;
            }
        }
        double d = 0, low = 0; /* the plane's offset in normalised coordinates, as hull_from_qhull sets
                                  it (through the highest vertex), and the lowest vertex's height */
        for (int k = 0; k < 3; k++) {
            double dv = -acd_dot3(pl, w + 3 * (size_t)out->source[tri[k]]);
            if (k == 0 || dv < d) d = dv;
            if (k == 0 || dv > low) low = dv;
        }
        double worst = encl_worst(&T, pl, d, tol);
        if (worst <= tol && low - d <= tol) continue;
        double nrm[3], dw, angle;
        if (tri_plane(a, b, c, nrm, &dw, &angle) &&
            encl_tri_violator(&T, nrm, dw, tol - tri_slack(angle, diag), a, b, c, tol) == UINT32_MAX) {
            double dp = 0; /* the triangle's own plane: every point within tol below it */
            for (int k = 0; k < 3; k++) {
                double v = -acd_dot3(nrm, points + 3 * (size_t)out->source[tri[k]]);
                if (k == 0 || v < dp) dp = v;
            }
            double wo = encl_worst(&T, nrm, dw, tol); /* within the rounding of tol */
            memcpy(pl, nrm, sizeof nrm);
            pl[3] = wo > tol ? dp - wo * s : dp;
            continue;
        }
        if (worst > tol) pl[3] -= worst * s;
        missed = 1;
    }
    if (st == ACD_OK && missed) st = hull_repair(out, points, w, n, s, diag, &T, err);
    free(T.node);
    free(T.idx);
    free(T.pts);
    return st;
}

/* Runs qhull on w (joggled copies if it fails) and builds out, or (out NULL) the volume alone. */
static acd_status hull_solid(const double *points, double *w, size_t n, double s, double diag, acd_hull *out,
                             double *volume, acd_error *err) {
    qhull_run r;
    int code = qhull_run_do(&r, w, n);
    char msg[200] = "";
    if (code == 0) {
        acd_status st = hull_from_qhull(&r, points, w, n, s, out, volume, err);
        int repaired = qhull_repaired(r.qh);
        qhull_run_free(&r);
        if (st == ACD_OK && out) st = hull_enclose(out, points, w, n, s, diag, repaired, err);
        return st;
    }
    qhull_first_line(&r, msg, sizeof msg);
    qhull_run_free(&r);
    if (code < 0) return acd_fail(err, ACD_ERR_NOMEM, "out of memory starting qhull on %zu points", n);
    /* precision trouble on a nearly degenerate set: joggle a copy deterministically */
    double *j = malloc(3 * n * sizeof *j);
    if (!j) return acd_fail(err, ACD_ERR_NOMEM, "out of memory for a joggled copy of %zu points", n);
    acd_rng rng;
    acd_rng_seed(&rng, HULL_JOGGLE_SEED);
    double amp = HULL_JOGGLE_REL;
    for (int attempt = 0; attempt < HULL_JOGGLE_TRIES; attempt++, amp *= 100.0) {
        for (size_t i = 0; i < 3 * n; i++) j[i] = w[i] + amp * (2.0 * acd_rng_uniform(&rng) - 1.0);
        code = qhull_run_do(&r, j, n);
        if (code == 0) {
            acd_status st = hull_from_qhull(&r, points, w, n, s, out, volume, err);
            int repaired = qhull_repaired(r.qh);
            qhull_run_free(&r);
            free(j);
            if (st == ACD_OK && out) st = hull_enclose(out, points, w, n, s, diag, repaired, err);
            return st;
        }
        qhull_run_free(&r);
        if (code < 0) break;
    }
    free(j);
    return acd_fail(err, ACD_ERR_DEGENERATE, "qhull failed on %zu points (exit code %d): %s", n, code,
                    msg[0] ? msg : "no message");
}

/* The hull into out, or (out NULL) its volume alone into *volume (0 unless dim 3). */
static acd_status hull_compute(const double *points, size_t n, acd_hull *out, double *volume, acd_error *err) {
    if (out) {
        memset(out, 0, sizeof *out);
        out->dim = -1;
    } else {
        *volume = 0;
    }
    if (n > 0 && !points) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_hull_compute: points is NULL");
    if (n > (size_t)INT_MAX || n >= UINT32_MAX)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_hull_compute: %zu points exceed the limit %d", n, INT_MAX);
    double lo[3], hi[3];
    for (size_t i = 0; i < n; i++) {
        const double *p = points + 3 * i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "hull: point %zu has a non-finite coordinate (%g, %g, %g)", i,
                            p[0], p[1], p[2]);
        for (int k = 0; k < 3; k++) {
            if (i == 0 || p[k] < lo[k]) lo[k] = p[k];
            if (i == 0 || p[k] > hi[k]) hi[k] = p[k];
        }
    }
    acd_error_clear(err);
    if (n == 0) return ACD_OK;
    double c[3], s = 0;
    for (int k = 0; k < 3; k++) {
        double side = hi[k] - lo[k];
        if (!isfinite(side))
            return acd_fail(err, ACD_ERR_INVALID_INPUT,
                            "hull: coordinate range along axis %d ([%g, %g]) overflows a double", k, lo[k], hi[k]);
        if (side > s) s = side;
        c[k] = lo[k] + 0.5 * side;
    }
    if (!out && (s == 0 || n < 4)) return ACD_OK; /* volume 0 */
    if (s == 0 || n == 1) { /* all points identical */
        acd_status st = hull_alloc(out, 1, 0, err);
        if (st != ACD_OK) return st;
        out->dim = 0;
        set_vertex(out, 0, points, 0);
        return ACD_OK;
    }
    double *w = malloc(3 * n * sizeof *w);
    if (!w) return acd_fail(err, ACD_ERR_NOMEM, "out of memory for %zu hull points", n);
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) w[3 * i + k] = (points[3 * i + k] - c[k]) / s;
    double diag = 0;
    for (int k = 0; k < 3; k++) diag += ((hi[k] - lo[k]) / s) * ((hi[k] - lo[k]) / s);
    diag = sqrt(diag);
    double tol = ACD_TOL_REL_DIST * diag;
    acd_status st = ACD_OK;
    /* numerical affine dimension: a far point, the point farthest from it, from their line, from the plane */
    double zero[3] = {0, 0, 0}, dist;
    size_t ia = farthest_from_point(w, n, zero, &dist);
    size_t ib = farthest_from_point(w, n, w + 3 * ia, &dist);
    if (dist <= tol && !out) {
        free(w);
        return ACD_OK;
    }
    if (dist <= tol) {
        st = hull_alloc(out, 1, 0, err);
        if (st == ACD_OK) {
            out->dim = 0;
            set_vertex(out, 0, points, ia < ib ? ia : ib);
        }
        free(w);
        return st;
    }
    double u[3];
    sub3(w + 3 * ib, w + 3 * ia, u);
    double ulen = norm3(u);
    for (int k = 0; k < 3; k++) u[k] /= ulen;
    size_t ic = 0;
    double best = -1;
    for (size_t i = 0; i < n; i++) {
        double d[3], cr[3];
        sub3(w + 3 * i, w + 3 * ia, d);
        acd_cross3(u, d, cr);
        double v = norm3(cr);
        if (v > best) best = v, ic = i;
    }
    if (best <= tol && !out) {
        free(w);
        return ACD_OK;
    }
    if (best <= tol) { /* collinear: the extreme points along u */
        size_t imin = 0, imax = 0;
        double tmin = 0, tmax = 0;
        for (size_t i = 0; i < n; i++) {
            double d[3];
            sub3(w + 3 * i, w + 3 * ia, d);
            double tt = acd_dot3(d, u);
            if (i == 0 || tt < tmin) tmin = tt, imin = i;
            if (i == 0 || tt > tmax) tmax = tt, imax = i;
        }
        st = hull_alloc(out, 2, 0, err);
        if (st == ACD_OK) {
            out->dim = 1;
            size_t first = imin < imax ? imin : imax, second = imin < imax ? imax : imin;
            set_vertex(out, 0, points, first);
            set_vertex(out, 1, points, second);
        }
        free(w);
        return st;
    }
    double e1[3], e2[3], nrm[3];
    sub3(w + 3 * ib, w + 3 * ia, e1);
    sub3(w + 3 * ic, w + 3 * ia, e2);
    acd_cross3(e1, e2, nrm);
    double nlen = norm3(nrm);
    for (int k = 0; k < 3; k++) nrm[k] /= nlen;
    best = -1;
    for (size_t i = 0; i < n; i++) {
        double d[3];
        sub3(w + 3 * i, w + 3 * ia, d);
        double v = fabs(acd_dot3(d, nrm));
        if (v > best) best = v;
    }
    if (best <= tol)
        st = out ? hull_planar(points, w, n, nrm, s, out, err) : ACD_OK;
    else
        st = hull_solid(points, w, n, s, diag, out, volume, err);
    free(w);
    if (st != ACD_OK && out) acd_hull_free(out);
    return st;
}

acd_status acd_hull_compute(const double *points, size_t n, acd_hull *out, acd_error *err) {
    if (!out) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_hull_compute: out is NULL");
    return hull_compute(points, n, out, NULL, err);
}

acd_status acd_hull_volume(const double *points, size_t n, double *volume, acd_error *err) {
    if (!volume) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_hull_volume: volume is NULL");
    return hull_compute(points, n, NULL, volume, err);
}


/* Distance from p to the segment [a, b]. */
static double seg_dist(const double *p, const double *a, const double *b) {
    double ab[3], ap[3];
    sub3(b, a, ab);
    sub3(p, a, ap);
    double l2 = acd_dot3(ab, ab), t = l2 > 0 ? acd_dot3(ap, ab) / l2 : 0;
    if (t < 0) t = 0;
    if (t > 1) t = 1;
    double q[3] = {a[0] + t * ab[0] - p[0], a[1] + t * ab[1] - p[1], a[2] + t * ab[2] - p[2]};
    return norm3(q);
}

double acd_hull_plane_distance(const acd_hull *h, const double p[3]) {
    if (!h || h->nvertices == 0) return INFINITY;
    if (h->dim == 3) {
        double m = -INFINITY;
        for (size_t t = 0; t < h->ntriangles; t++) {
            const double *pl = h->planes + 4 * t;
            double v = pl[0] * p[0] + pl[1] * p[1] + pl[2] * p[2] + pl[3];
            if (v > m) m = v;
        }
        return m;
    }
    if (h->dim == 0 || h->nvertices == 1) {
        double d[3];
        sub3(p, h->vertices, d);
        return norm3(d);
    }
    if (h->dim == 1 || h->ntriangles == 0) return seg_dist(p, h->vertices, h->vertices + 3);
    /* dim 2: polygon in order 0..m-1, counterclockwise about the plane normal */
    const double *pl = h->planes;
    double hgt = pl[0] * p[0] + pl[1] * p[1] + pl[2] * p[2] + pl[3];
    double q[3] = {p[0] - hgt * pl[0], p[1] - hgt * pl[1], p[2] - hgt * pl[2]};
    size_t m = h->nvertices;
    int inside = 1;
    double edge = INFINITY;
    for (size_t i = 0; i < m; i++) {
        const double *a = h->vertices + 3 * i, *b = h->vertices + 3 * ((i + 1) % m);
        double ab[3], aq[3], cr[3];
        sub3(b, a, ab);
        sub3(q, a, aq);
        acd_cross3(ab, aq, cr);
        if (acd_dot3(cr, pl) < 0) inside = 0;
        double de = seg_dist(p, a, b);
        if (de < edge) edge = de;
    }
    return inside ? fabs(hgt) : edge;
}

static int cmp_hull_edge(const void *x, const void *y) {
    const acd_hull_edge *a = x, *b = y;
    if (a->v[0] != b->v[0]) return a->v[0] < b->v[0] ? -1 : 1;
    return (a->v[1] > b->v[1]) - (a->v[1] < b->v[1]);
}

acd_status acd_hull_edges(const acd_hull *h, acd_hull_edge **edges, size_t *nedges, acd_error *err) {
    *edges = NULL;
    *nedges = 0;
    size_t cap = h->ntriangles * 3 + 1;
    acd_hull_edge *e = malloc(cap * sizeof *e);
    if (!e) return acd_fail(err, ACD_ERR_NOMEM, "out of memory for the edges of %zu hull triangles", h->ntriangles);
    size_t n = 0;
    if (h->dim == 1 && h->nvertices == 2) {
        e[n].v[0] = 0;
        e[n].v[1] = 1;
        e[n].left = e[n].right = ACD_HULL_NO_NEIGHBOR;
        n++;
    }
    for (size_t t = 0; t < h->ntriangles; t++)
        for (int i = 0; i < 3; i++) {
            uint32_t a = h->triangles[3 * t + i], b = h->triangles[3 * t + (i + 1) % 3];
            uint32_t u = h->neighbors[3 * t + i];
            if (a < b) {
                e[n].v[0] = a;
                e[n].v[1] = b;
                e[n].left = (uint32_t)t;
                e[n].right = u;
                n++;
            } else if (u == ACD_HULL_NO_NEIGHBOR) {
                e[n].v[0] = b;
                e[n].v[1] = a;
                e[n].left = ACD_HULL_NO_NEIGHBOR;
                e[n].right = (uint32_t)t;
                n++;
            }
        }
    qsort(e, n, sizeof *e, cmp_hull_edge);
    *edges = e;
    *nedges = n;
    return ACD_OK;
}
