/* mesh/selfintersect: exact detection of intersecting triangle pairs.
 *
 * Broad phase: the triangle BVH of geom3/bvh (closed box overlaps); for coordinates of subnormal or
 * near-overflow magnitude an exact sort-and-sweep on x instead. Narrow phase, all decisions
 * by the exact predicates acd_orient3d / acd_orient2d:
 * - no shared vertex: the closed triangles meet iff an edge of one meets the other (for two
 *   triangles the intersection, when not empty, always contains a point of some edge);
 * - one shared vertex v: they meet beyond v iff the edge opposite v of one meets the other, or
 *   an edge from v of one lies in the other's plane inside its angle at v (the intersection lies
 *   on the line of the two planes through v, and ends on an edge of one of them);
 * - a shared edge: they overlap iff they are coplanar with the two other vertices on the same
 *   side of the edge (otherwise the intersection is the edge itself);
 * - three shared vertices: a duplicate face, reported by the validator instead.
 * "Shared" compares coordinates, not indices. Zero-area triangles are skipped. */
#include <stdlib.h>
#include <string.h>

#include "acd/mesh.h"
#include "core/error.h"
#include "core/predicates.h"
#include "geom3/bvh.h"
#include "mesh/selfintersect.h"

typedef const double *pt;

static void proj(pt p, int drop, double out[2]) {
    out[0] = p[(drop + 1) % 3];
    out[1] = p[(drop + 2) % 3];
}

/* The axis to drop so that the projected triangle keeps the largest area; -1 if it has none. */
static int drop_axis(pt a, pt b, pt c) {
    int best = -1;
    double bestv = 0;
    for (int d = 0; d < 3; d++) {
        double pa[2], pb[2], pc[2];
        proj(a, d, pa);
        proj(b, d, pb);
        proj(c, d, pc);
        double v = acd_orient2d(pa, pb, pc);
        if (v < 0) v = -v;
        if (acd_orient2d_sign(pa, pb, pc) != 0 && (best < 0 || v > bestv)) {
            best = d;
            bestv = v;
        }
    }
    return best;
}

static int point_in_tri2(const double p[2], const double a[2], const double b[2], const double c[2]) {
    int o1 = acd_orient2d_sign(a, b, p), o2 = acd_orient2d_sign(b, c, p), o3 = acd_orient2d_sign(c, a, p);
    return (o1 >= 0 && o2 >= 0 && o3 >= 0) || (o1 <= 0 && o2 <= 0 && o3 <= 0);
}

/* Closed segment pq meets closed non-degenerate triangle abc, given sp = acd_orient3d_sign(a, b, c, p)
 * and sq = acd_orient3d_sign(a, b, c, q). */
static int seg_tri_s(pt p, pt q, pt a, pt b, pt c, int sp, int sq) {
    if (sp * sq > 0) return 0;
    if (sp == 0 && sq == 0) {
        int d = drop_axis(a, b, c);
        if (d < 0) return 0;
        double P[2], Q[2], A[2], B[2], C[2];
        proj(p, d, P);
        proj(q, d, Q);
        proj(a, d, A);
        proj(b, d, B);
        proj(c, d, C);
        if (point_in_tri2(P, A, B, C) || point_in_tri2(Q, A, B, C)) return 1;
        return acd_segments_relation(P, Q, A, B) != ACD_SEG_DISJOINT ||
               acd_segments_relation(P, Q, B, C) != ACD_SEG_DISJOINT ||
               acd_segments_relation(P, Q, C, A) != ACD_SEG_DISJOINT;
    }
    int s1 = acd_orient3d_sign(p, q, a, b), s2 = acd_orient3d_sign(p, q, b, c), s3 = acd_orient3d_sign(p, q, c, a);
    return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

/* Closed segment pq meets closed non-degenerate triangle abc. */
static int seg_tri(pt p, pt q, pt a, pt b, pt c) {
    return seg_tri_s(p, q, a, b, c, acd_orient3d_sign(a, b, c, p), acd_orient3d_sign(a, b, c, q));
}

/* x (coplanar with triangle v a b, x != v) lies in the closed angle of the triangle at v. */
static int in_angle(pt v, pt a, pt b, pt x) {
    int d = drop_axis(v, a, b);
    if (d < 0) return 0;
    double V[2], A[2], B[2], X[2];
    proj(v, d, V);
    proj(a, d, A);
    proj(b, d, B);
    proj(x, d, X);
    int o = acd_orient2d_sign(V, A, B);
    int s1 = acd_orient2d_sign(V, A, X) * o, s2 = acd_orient2d_sign(V, X, B) * o;
    return s1 >= 0 && s2 >= 0;
}

static int same(pt p, pt q) { return p[0] == q[0] && p[1] == q[1] && p[2] == q[2]; }

/* Exact test of two non-degenerate triangles; see the file comment. */
static int tri_tri(pt t1[3], pt t2[3]) {
    int m1[3] = {-1, -1, -1}; /* m1[i] = index in t2 of the vertex equal to t1[i] */
    int shared = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (same(t1[i], t2[j])) {
                m1[i] = j;
                shared++;
                break;
            }
    if (shared == 0) {
        for (int i = 0; i < 3; i++) {
            if (seg_tri(t1[i], t1[(i + 1) % 3], t2[0], t2[1], t2[2])) return 1;
            if (seg_tri(t2[i], t2[(i + 1) % 3], t1[0], t1[1], t1[2])) return 1;
        }
        return 0;
    }
    if (shared == 1) {
        int i = m1[0] >= 0 ? 0 : m1[1] >= 0 ? 1 : 2, j = m1[i];
        pt v = t1[i], a1 = t1[(i + 1) % 3], b1 = t1[(i + 2) % 3], a2 = t2[(j + 1) % 3], b2 = t2[(j + 2) % 3];
        /* the sides of the far corners of each triangle to the other's plane, each computed once (the
         * edge tests and the in-plane tests below both need them) */
        const int s1a = acd_orient3d_sign(v, a2, b2, a1), s1b = acd_orient3d_sign(v, a2, b2, b1);
        if (seg_tri_s(a1, b1, v, a2, b2, s1a, s1b)) return 1;
        const int s2a = acd_orient3d_sign(v, a1, b1, a2), s2b = acd_orient3d_sign(v, a1, b1, b2);
        if (seg_tri_s(a2, b2, v, a1, b1, s2a, s2b)) return 1;
        if (s1a == 0 && in_angle(v, a2, b2, a1)) return 1;
        if (s2a == 0 && in_angle(v, a1, b1, a2)) return 1;
        if (s1b == 0 && in_angle(v, a2, b2, b1)) return 1;
        if (s2b == 0 && in_angle(v, a1, b1, b2)) return 1;
        return 0;
    }
    if (shared == 2) {
        int i = m1[0] < 0 ? 0 : m1[1] < 0 ? 1 : 2; /* the unshared vertex of t1 */
        int j = 3 - m1[(i + 1) % 3] - m1[(i + 2) % 3];
        pt u = t1[(i + 1) % 3], w = t1[(i + 2) % 3], c1 = t1[i], c2 = t2[j];
        if (acd_orient3d_sign(u, w, c1, c2) != 0) return 0;
        int d = drop_axis(u, w, c1);
        if (d < 0) return 0;
        double U[2], W[2], C1[2], C2[2];
        proj(u, d, U);
        proj(w, d, W);
        proj(c1, d, C1);
        proj(c2, d, C2);
        return acd_orient2d_sign(U, W, C1) * acd_orient2d_sign(U, W, C2) > 0;
    }
    return 0;
}

typedef struct si_ctx {
    const acd_mesh *m;
    const unsigned char *degenerate;
    size_t count;
    uint32_t *pairs;
    size_t max_pairs;
    int first_only; /* stop at the first intersecting pair */
} si_ctx;

static int visit_pair(void *user, uint32_t a, uint32_t b) {
    si_ctx *c = user;
    if (c->degenerate[a] || c->degenerate[b]) return 0;
    const double *v = c->m->vertices;
    const uint32_t *ta = c->m->triangles + 3 * (size_t)a, *tb = c->m->triangles + 3 * (size_t)b;
    pt t1[3] = {v + 3 * (size_t)ta[0], v + 3 * (size_t)ta[1], v + 3 * (size_t)ta[2]};
    pt t2[3] = {v + 3 * (size_t)tb[0], v + 3 * (size_t)tb[1], v + 3 * (size_t)tb[2]};
    if (tri_tri(t1, t2)) {
        if (c->pairs && c->count < c->max_pairs) {
            c->pairs[2 * c->count] = a;
            c->pairs[2 * c->count + 1] = b;
        }
        c->count++;
        return c->first_only;
    }
    return 0;
}

/* Coordinates beyond the range the BVH's floating-point binning handles (subnormal or near-overflow
 * magnitudes, which no real model has): an exact sort-and-sweep on x is used instead. */
#define SI_HUGE 1e300
#define SI_TINY 1e-290

static int extreme_coordinates(const acd_mesh *m) {
    for (size_t i = 0; i < 3 * m->nvertices; i++) {
        double a = m->vertices[i] < 0 ? -m->vertices[i] : m->vertices[i];
        if (a > SI_HUGE || (a != 0 && a < SI_TINY)) return 1;
    }
    return 0;
}

typedef struct sweep_box {
    double lo[3], hi[3];
    uint32_t t;
} sweep_box;

static int cmp_sweep(const void *x, const void *y) {
    const sweep_box *a = x, *b = y;
    if (a->lo[0] != b->lo[0]) return a->lo[0] < b->lo[0] ? -1 : 1;
    return a->t < b->t ? -1 : a->t > b->t;
}

static acd_status sweep_pairs(const acd_mesh *m, si_ctx *c, acd_error *err) {
    sweep_box *b = malloc(m->ntriangles * sizeof *b);
    if (!b) return acd_fail(err, ACD_ERR_NOMEM, "out of memory testing self-intersections");
    for (size_t t = 0; t < m->ntriangles; t++) {
        b[t].t = (uint32_t)t;
        for (int k = 0; k < 3; k++) {
            b[t].lo[k] = b[t].hi[k] = m->vertices[3 * (size_t)m->triangles[3 * t] + (size_t)k];
            for (int j = 1; j < 3; j++) {
                double v = m->vertices[3 * (size_t)m->triangles[3 * t + (size_t)j] + (size_t)k];
                if (v < b[t].lo[k]) b[t].lo[k] = v;
                if (v > b[t].hi[k]) b[t].hi[k] = v;
            }
        }
    }
    qsort(b, m->ntriangles, sizeof *b, cmp_sweep);
    for (size_t i = 0; i < m->ntriangles; i++)
        for (size_t j = i + 1; j < m->ntriangles && b[j].lo[0] <= b[i].hi[0]; j++)
            if (b[j].lo[1] <= b[i].hi[1] && b[i].lo[1] <= b[j].hi[1] && b[j].lo[2] <= b[i].hi[2] &&
                b[i].lo[2] <= b[j].hi[2]) {
                uint32_t x = b[i].t, y = b[j].t;
                if (visit_pair(c, x < y ? x : y, x < y ? y : x)) {
                    free(b);
                    return ACD_OK;
                }
            }
    free(b);
    return ACD_OK;
}

acd_status acd_mesh_self_intersections(const acd_mesh *m, size_t *count, uint32_t *pairs, size_t max_pairs,
                                       acd_error *err) {
    return acd_mesh_self_intersections_bvh(m, NULL, count, pairs, max_pairs, err);
}

static acd_status self_intersections(const acd_mesh *m, const acd_bvh *given, size_t *count, uint32_t *pairs,
                                     size_t max_pairs, int first_only, acd_error *err) {
    if (!m || !count) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_self_intersections: NULL argument");
    *count = 0;
    if (m->ntriangles == 0) return ACD_OK;
    for (size_t i = 0; i < 3 * m->ntriangles; i++)
        if (m->triangles[i] >= m->nvertices)
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "triangle %zu refers to vertex %u of %zu", i / 3, m->triangles[i],
                            m->nvertices);
    unsigned char *deg = malloc(m->ntriangles);
    if (!deg) return acd_fail(err, ACD_ERR_NOMEM, "out of memory testing self-intersections");
    for (size_t t = 0; t < m->ntriangles; t++) {
        const uint32_t *i = m->triangles + 3 * t;
        deg[t] = drop_axis(m->vertices + 3 * (size_t)i[0], m->vertices + 3 * (size_t)i[1],
                           m->vertices + 3 * (size_t)i[2]) < 0;
    }
    si_ctx c = {m, deg, 0, pairs, pairs ? max_pairs : 0, first_only};
    acd_status s;
    if (extreme_coordinates(m)) {
        s = sweep_pairs(m, &c, err);
    } else if (acd_bvh_is_over(given, m->vertices, m->nvertices, m->triangles, m->ntriangles)) {
        acd_bvh_overlap_pairs(given, 0.0, visit_pair, &c);
        s = ACD_OK;
    } else {
        acd_bvh bvh;
        s = acd_bvh_build(&bvh, m->vertices, m->nvertices, m->triangles, m->ntriangles, err);
        if (s == ACD_OK) {
            acd_bvh_overlap_pairs(&bvh, 0.0, visit_pair, &c);
            acd_bvh_free(&bvh);
        }
    }
    free(deg);
    if (s != ACD_OK) return s;
    *count = c.count;
    return ACD_OK;
}

acd_status acd_mesh_self_intersections_bvh(const acd_mesh *m, const acd_bvh *given, size_t *count, uint32_t *pairs,
                                           size_t max_pairs, acd_error *err) {
    return self_intersections(m, given, count, pairs, max_pairs, 0, err);
}

acd_status acd_mesh_self_intersects_bvh(const acd_mesh *m, const acd_bvh *given, int *crosses, acd_error *err) {
    size_t count = 0;
    if (!crosses) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_self_intersects: NULL argument");
    acd_status s = self_intersections(m, given, &count, NULL, 0, 1, err);
    *crosses = s == ACD_OK && count > 0;
    return s;
}
