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
 *     plane) and lifts a plane that a point exceeds by more than ACD_TOL_REL_DIST x diagonal
 *     (qhull's roundoff on an ill-conditioned facet: hull_enclose).
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
static void cross3(const double *a, const double *b, double *r) {
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}
static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double norm3(const double *a) { return sqrt(dot3(a, a)); }

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
        double v = dot3(d, d);
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
        double v = -dot3(un, out->vertices + 3 * k);
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
        cross3(e1, e2, cr);
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
        cross3(e1, e2, cr);
        double dt = dot3(cr, facet->normal);
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
            double dv = -dot3(nrm, out->vertices + 3 * tri[k]);
            if (k == 0 || dv < d) d = dv;
        }
        memcpy(out->planes + 4 * t, nrm, sizeof nrm);
        out->planes[4 * t + 3] = d;
        double e1[3], e2[3], cr[3];
        sub3(b, a, e1);
        sub3(c, a, e2);
        cross3(e1, e2, cr);
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
 * normal and the triangles unchanged); hulls without a violation keep their bits.
 *
 * Only planes that can be off are checked (hull_plane_trusted): a facet whose triangle is well
 * shaped and whose qhull normal agrees with the triangle's own cross product. Such a plane is the
 * true plane of a hull face up to an angle of tilt + 3 eps L / h (the cross product's rounding: L
 * the longest edge, h the least altitude), so no point of the box (within a diagonal of the facet)
 * is off by more than diagonal x that angle, which the test keeps under a quarter of the
 * tolerance. On real meshes 90-96% of the facets pass (bunny00, armadillo, fandisk at tau 0.05:
 * altitudes under 1e-3 of the extent on 4.6%, 4.3%, 10%); fuzz_hull still checks every plane. */

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
        double v = dot3(u, u);
        if (v > best) best = v, p1 = q;
    }
    sub3(p1, p0, u);
    best = 0;
    for (uint32_t i = nd->begin; i < nd->end; i++) {
        const double *q = w + 3 * (size_t)idx[i];
        double d[3], cr[3];
        sub3(q, p0, d);
        cross3(u, d, cr);
        double v = dot3(cr, cr);
        if (v > best) best = v, memcpy(nd->m, cr, sizeof cr);
    }
    double len = norm3(nd->m);
    if (!(len > 0)) return;
    for (int k = 0; k < 3; k++) nd->m[k] /= len;
    for (uint32_t i = nd->begin; i < nd->end; i++) {
        double v = dot3(nd->m, w + 3 * (size_t)idx[i]);
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
        double ub = dot3(nrm, nd->c) + d + fabs(nrm[0]) * nd->h[0] + fabs(nrm[1]) * nd->h[1] + fabs(nrm[2]) * nd->h[2];
        if (ub <= tol) continue;
        if (!nd->child) { /* n = a m + r: a (m.p) within the slab, r.p within the box */
            double a = dot3(nrm, nd->m), r[3] = {nrm[0] - a * nd->m[0], nrm[1] - a * nd->m[1], nrm[2] - a * nd->m[2]};
            ub = (a > 0 ? a * nd->mhi : a * nd->mlo) + dot3(r, nd->c) + d + fabs(r[0]) * nd->h[0] + fabs(r[1]) * nd->h[1] +
                 fabs(r[2]) * nd->h[2];
            if (ub <= tol) continue;
        }
        if (nd->child && top + 2 <= sizeof stack / sizeof *stack) {
            stack[top++] = nd->child;
            stack[top++] = nd->child + 1;
            continue;
        }
        for (uint32_t i = nd->begin; i < nd->end; i++) { /* a leaf (or a subtree past the stack's depth) */
            double v = dot3(nrm, T->pts + 3 * (size_t)i) + d;
            if (v > worst) worst = v;
        }
    }
    return worst;
}

/* Checks the planes of out (built from w, the points normalised by s) against every point and
 * lifts those exceeded by more than tol (normalised units). */
/* Rounding of a triangle's cross product, in units of DBL_EPSILON x L / h (3 in the analysis, with
 * a margin), and the share of the tolerance a trusted plane may be off by. */
#define HULL_ENCLOSE_ROUNDOFF 8.0
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
    cross3(e1, e2, cr);
    double area2 = norm3(cr), lmax = fmax(norm3(e1), fmax(norm3(e2), norm3(e3)));
    if (!(area2 > 0) || dot3(nrm, cr) <= 0) return 0;
    double h = area2 / lmax; /* the least altitude */
    for (int k = 0; k < 3; k++) cr[k] /= area2;
    cross3(nrm, cr, x);
    double angle = norm3(x) + HULL_ENCLOSE_ROUNDOFF * DBL_EPSILON * lmax / h;
    return diag * angle <= HULL_ENCLOSE_TRUST_SHARE * tol;
}

/* Checks the planes of out (built from w, the points normalised by s, box diagonal diag) that are
 * not trusted against every point and lifts those exceeded by more than ACD_TOL_REL_DIST x diag
 * (normalised units). */
static acd_status hull_enclose(acd_hull *out, const double *w, size_t n, double s, double diag, acd_error *err) {
    const double tol = ACD_TOL_REL_DIST * diag;
    encl_tree T = {0};
    int built = 0;
    acd_status st = ACD_OK;
    for (size_t t = 0; t < out->ntriangles; t++) {
        double *pl = out->planes + 4 * t;
        const uint32_t *tri = out->triangles + 3 * t;
        const double *a = w + 3 * (size_t)out->source[tri[0]], *b = w + 3 * (size_t)out->source[tri[1]],
                     *c = w + 3 * (size_t)out->source[tri[2]];
        if (hull_plane_trusted(pl, a, b, c, diag, tol)) continue;
        if (!built) {
            built = 1;
            if (!encl_build(&T, w, n)) {
                st = acd_fail(err, ACD_ERR_NOMEM, "out of memory checking a hull of %zu points", n);
                break;
            }
        }
        double d = 0; /* the plane's offset in normalised coordinates, as hull_from_qhull sets it */
        for (int k = 0; k < 3; k++) {
            double dv = -dot3(pl, w + 3 * (size_t)out->source[tri[k]]);
            if (k == 0 || dv < d) d = dv;
        }
        double worst = encl_worst(&T, pl, d, tol);
        if (worst > tol) pl[3] -= worst * s;
    }
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
        qhull_run_free(&r);
        if (st == ACD_OK && out) st = hull_enclose(out, w, n, s, diag, err);
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
            qhull_run_free(&r);
            free(j);
            if (st == ACD_OK && out) st = hull_enclose(out, w, n, s, diag, err);
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
        cross3(u, d, cr);
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
            double tt = dot3(d, u);
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
    cross3(e1, e2, nrm);
    double nlen = norm3(nrm);
    for (int k = 0; k < 3; k++) nrm[k] /= nlen;
    best = -1;
    for (size_t i = 0; i < n; i++) {
        double d[3];
        sub3(w + 3 * i, w + 3 * ia, d);
        double v = fabs(dot3(d, nrm));
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
    double l2 = dot3(ab, ab), t = l2 > 0 ? dot3(ap, ab) / l2 : 0;
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
        cross3(ab, aq, cr);
        if (dot3(cr, pl) < 0) inside = 0;
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
