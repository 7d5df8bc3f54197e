/* geom3/spatial: distance, winding number and inside/outside for triangle meshes.
 *
 * Ray crossing with exact predicates and simulation of simplicity (Edelsbrunner and Mucke,
 * ACM TOG 1990, sec. 4); generalized winding number (Jacobson, Kavan, Sorkine-Hornung,
 * SIGGRAPH 2013, eq. 4-5) with the first-order far-field expansion of Barill, Dickson, Schmidt,
 * Levin, Jacobson (SIGGRAPH 2018, sec. 3.2); triangle solid angle by Van Oosterom and Strackee
 * (IEEE TBME 1983, eq. 8). Choice and accuracy: spatial.h and docs/eval.md. */
#include "geom3/spatial.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/predicates.h"
#include "geom3/vec3.h"

#define GWN_STACK 128
#define GWN_M 16 /* doubles per node: area vector, centroid, radius, 3x3 moment */
#define FOUR_PI 12.566370614359172953850573533118

typedef struct edge_key {
    uint32_t a, b; /* a < b */
    int dir;       /* +1 for a -> b, -1 for b -> a */
} edge_key;

static int cmp_edge(const void *x, const void *y) {
    const edge_key *e = x, *f = y;
    if (e->a != f->a) return e->a < f->a ? -1 : 1;
    return (e->b > f->b) - (e->b < f->b);
}

typedef struct vkey {
    const double *p;
    uint32_t i;
} vkey;

static int cmp_vkey(const void *x, const void *y) {
    const vkey *a = x, *b = y;
    for (int k = 0; k < 3; k++)
        if (a->p[k] != b->p[k]) return a->p[k] < b->p[k] ? -1 : 1;
    return (a->i > b->i) - (a->i < b->i);
}

/* Boundary edges of the mesh with vertices of equal coordinates identified (a polygon soup whose
 * faces meet exactly is closed: the ray crossings depend on coordinates only). */
static acd_status count_boundary(acd_spatial *sp, acd_error *err) {
    size_t nt = sp->bvh.ntriangles, ne = 0, nv = sp->bvh.nvertices;
    edge_key *e = malloc((nt ? 3 * nt : 1) * sizeof *e);
    uint32_t *canon = malloc((nv ? nv : 1) * sizeof *canon);
    vkey *vk = malloc((nv ? nv : 1) * sizeof *vk);
    if (!e || !canon || !vk) {
        free(e);
        free(canon);
        free(vk);
        return acd_fail(err, ACD_ERR_NOMEM, "spatial: out of memory for %zu edges", 3 * nt);
    }
    for (size_t v = 0; v < nv; v++) vk[v] = (vkey){sp->bvh.vertices + 3 * v, (uint32_t)v};
    qsort(vk, nv, sizeof *vk, cmp_vkey);
    for (size_t v = 0; v < nv; v++)
        canon[vk[v].i] = (v > 0 && memcmp(vk[v].p, vk[v - 1].p, 3 * sizeof(double)) == 0) ? canon[vk[v - 1].i] : vk[v].i;
    free(vk);
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = canon[sp->bvh.triangles[3 * t + k]], b = canon[sp->bvh.triangles[3 * t + (k + 1) % 3]];
            if (a == b) continue;
            e[ne++] = a < b ? (edge_key){a, b, 1} : (edge_key){b, a, -1};
        }
    free(canon);
    qsort(e, ne, sizeof *e, cmp_edge);
    size_t boundary = 0;
    for (size_t i = 0; i < ne;) {
        size_t j = i;
        int net = 0;
        while (j < ne && e[j].a == e[i].a && e[j].b == e[i].b) net += e[j++].dir;
        if (net != 0) boundary++;
        i = j;
    }
    free(e);
    sp->boundary_edges = boundary;
    sp->closed = boundary == 0 && nt > 0;
    return ACD_OK;
}


/* Fills the moments bottom-up: area vector, area-weighted centroid, radius of the ball around
 * the centroid that holds the node's box. Areas are kept in a scratch array. */
static acd_status build_moments(acd_spatial *sp, acd_error *err) {
    const acd_bvh *b = &sp->bvh;
    double *area = malloc((b->nnodes ? b->nnodes : 1) * sizeof(double));
    if (!area) return acd_fail(err, ACD_ERR_NOMEM, "spatial: out of memory for %zu nodes", b->nnodes);
    for (size_t i = b->nnodes; i-- > 0;) {
        const acd_bvh_node *n = &b->nodes[i];
        double *m = sp->moments + GWN_M * i;
        double nv[3] = {0, 0, 0}, c[3] = {0, 0, 0}, w = 0;
        if (n->count) {
            for (uint32_t j = 0; j < n->count; j++) {
                const uint32_t *tr = b->triangles + 3 * (size_t)b->order[n->first + j];
                const double *p0 = b->vertices + 3 * (size_t)tr[0], *p1 = b->vertices + 3 * (size_t)tr[1],
                             *p2 = b->vertices + 3 * (size_t)tr[2];
                double e1[3], e2[3], x[3];
                for (int k = 0; k < 3; k++) {
                    e1[k] = p1[k] - p0[k];
                    e2[k] = p2[k] - p0[k];
                }
                x[0] = 0.5 * (e1[1] * e2[2] - e1[2] * e2[1]);
                x[1] = 0.5 * (e1[2] * e2[0] - e1[0] * e2[2]);
                x[2] = 0.5 * (e1[0] * e2[1] - e1[1] * e2[0]);
                double a = sqrt(acd_dot3(x, x));
                for (int k = 0; k < 3; k++) {
                    nv[k] += x[k];
                    c[k] += a * (p0[k] + p1[k] + p2[k]) / 3.0;
                }
                w += a;
            }
        } else {
            for (int s = 0; s < 2; s++) {
                uint32_t ch = n->first + (uint32_t)s;
                const double *mc = sp->moments + GWN_M * (size_t)ch;
                for (int k = 0; k < 3; k++) {
                    nv[k] += mc[k];
                    c[k] += area[ch] * mc[3 + k];
                }
                w += area[ch];
            }
        }
        area[i] = w;
        double r2 = 0;
        for (int k = 0; k < 3; k++) {
            m[k] = nv[k];
            m[3 + k] = w > 0 ? c[k] / w : 0.5 * (n->lo[k] + n->hi[k]);
            /* keep the centroid inside the box against rounding */
            if (m[3 + k] < n->lo[k]) m[3 + k] = n->lo[k];
            if (m[3 + k] > n->hi[k]) m[3 + k] = n->hi[k];
            double d = fmax(m[3 + k] - n->lo[k], n->hi[k] - m[3 + k]);
            r2 += d * d;
        }
        m[6] = sqrt(r2);
        /* second-order moment T_ij = sum over triangles of N_i (c - centroid)_j */
        double *T = m + 7;
        for (int k = 0; k < 9; k++) T[k] = 0;
        if (n->count) {
            for (uint32_t j = 0; j < n->count; j++) {
                const uint32_t *tr = b->triangles + 3 * (size_t)b->order[n->first + j];
                const double *p0 = b->vertices + 3 * (size_t)tr[0], *p1 = b->vertices + 3 * (size_t)tr[1],
                             *p2 = b->vertices + 3 * (size_t)tr[2];
                double x[3], d[3];
                x[0] = 0.5 * ((p1[1] - p0[1]) * (p2[2] - p0[2]) - (p1[2] - p0[2]) * (p2[1] - p0[1]));
                x[1] = 0.5 * ((p1[2] - p0[2]) * (p2[0] - p0[0]) - (p1[0] - p0[0]) * (p2[2] - p0[2]));
                x[2] = 0.5 * ((p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]));
                for (int k = 0; k < 3; k++) d[k] = (p0[k] + p1[k] + p2[k]) / 3.0 - m[3 + k];
                for (int a = 0; a < 3; a++)
                    for (int bb = 0; bb < 3; bb++) T[3 * a + bb] += x[a] * d[bb];
            }
        } else {
            for (int s = 0; s < 2; s++) {
                const double *mc = sp->moments + GWN_M * (size_t)(n->first + (uint32_t)s);
                for (int a = 0; a < 3; a++)
                    for (int bb = 0; bb < 3; bb++) T[3 * a + bb] += mc[7 + 3 * a + bb] + mc[a] * (mc[3 + bb] - m[3 + bb]);
            }
        }
    }
    free(area);
    return ACD_OK;
}

acd_status acd_spatial_build(acd_spatial *sp, const double *vertices, size_t nvertices,
                             const uint32_t *triangles, size_t ntriangles, acd_error *err) {
    memset(sp, 0, sizeof *sp);
    acd_status st = acd_bvh_build(&sp->bvh, vertices, nvertices, triangles, ntriangles, err);
    if (st != ACD_OK) return st;
    if (sp->bvh.nnodes) {
        sp->scale.extent = 0;
        const acd_bvh_node *r = &sp->bvh.nodes[0];
        double d2 = 0;
        for (int k = 0; k < 3; k++) d2 += (r->hi[k] - r->lo[k]) * (r->hi[k] - r->lo[k]);
        sp->scale.extent = sqrt(d2) > 0 ? sqrt(d2) : 1.0;
    } else {
        sp->scale.extent = 1.0;
    }
    sp->scale.weld = ACD_TOL_REL_WELD * sp->scale.extent;
    sp->scale.dist = ACD_TOL_REL_DIST * sp->scale.extent;
    st = count_boundary(sp, err);
    if (st == ACD_OK) {
        sp->moments = malloc((sp->bvh.nnodes ? sp->bvh.nnodes : 1) * GWN_M * sizeof(double));
        if (!sp->moments) st = acd_fail(err, ACD_ERR_NOMEM, "spatial: out of memory for %zu nodes", sp->bvh.nnodes);
        else st = build_moments(sp, err);
    }
    if (st != ACD_OK) acd_spatial_free(sp);
    return st;
}

void acd_spatial_free(acd_spatial *sp) {
    if (!sp) return;
    acd_bvh_free(&sp->bvh);
    free(sp->moments);
    memset(sp, 0, sizeof *sp);
}

double acd_spatial_distance(const acd_spatial *sp, const double p[3], acd_bvh_closest_result *closest) {
    acd_bvh_closest_result r;
    if (!acd_bvh_closest(&sp->bvh, p, INFINITY, &r)) return INFINITY;
    if (closest) *closest = r;
    return sqrt(r.dist2);
}

/* ---- exact ray crossings ---- */

/* Sign of orient2d in the (y, z) projection of (u, v, q), with q moved by (e, e^2): never 0
 * unless u and v project to the same point. */
static int orient_yz_sos(const double *u, const double *v, double qy, double qz) {
    double a[2] = {u[1], u[2]}, b[2] = {v[1], v[2]}, c[2] = {qy, qz};
    int s = acd_orient2d_sign(a, b, c);
    if (s) return s;
    if (v[2] != u[2]) return v[2] < u[2] ? 1 : -1; /* d/dqy of the determinant is -(vz - uz) */
    if (v[1] != u[1]) return v[1] > u[1] ? 1 : -1; /* d/dqz is (vy - uy) */
    return 0;
}

/* +1 / -1 when the perturbed line {(t, y, z)} crosses triangle t (the sign of its normal's x),
 * 0 when it misses it or the triangle is parallel to x. */
static int line_cross_sign(const acd_bvh *b, uint32_t t, double y, double z) {
    const uint32_t *tr = b->triangles + 3 * (size_t)t;
    const double *p0 = b->vertices + 3 * (size_t)tr[0], *p1 = b->vertices + 3 * (size_t)tr[1],
                 *p2 = b->vertices + 3 * (size_t)tr[2];
    double a[2] = {p0[1], p0[2]}, bb[2] = {p1[1], p1[2]}, c[2] = {p2[1], p2[2]};
    int s = acd_orient2d_sign(a, bb, c);
    if (s == 0) return 0;
    if (orient_yz_sos(p0, p1, y, z) != s) return 0;
    if (orient_yz_sos(p1, p2, y, z) != s) return 0;
    if (orient_yz_sos(p2, p0, y, z) != s) return 0;
    return s;
}

/* Contribution of a crossing triangle (sign s) to the winding number at p: s when the crossing
 * lies ahead of p (larger x), 0 behind; on_surface set when p is on the triangle. */
static int crossing_ahead(const acd_bvh *b, uint32_t t, int s, const double p[3], int *on_surface) {
    const uint32_t *tr = b->triangles + 3 * (size_t)t;
    int o = acd_orient3d_sign(b->vertices + 3 * (size_t)tr[0], b->vertices + 3 * (size_t)tr[1],
                              b->vertices + 3 * (size_t)tr[2], p);
    if (o == 0) {
        if (on_surface) *on_surface = 1;
        return 0;
    }
    return s * o > 0 ? s : 0;
}

int acd_spatial_ray_crossing(const acd_spatial *sp, uint32_t t, const double p[3], int *on_surface) {
    int s = line_cross_sign(&sp->bvh, t, p[1], p[2]);
    return s ? crossing_ahead(&sp->bvh, t, s, p, on_surface) : 0;
}

int acd_spatial_line_crossing(const acd_spatial *sp, const acd_spatial_line *line, size_t i, double x,
                              int *on_surface) {
    double p[3] = {x, line->y, line->z};
    return crossing_ahead(&sp->bvh, line->triangles[i], line->signs[i], p, on_surface);
}

typedef struct ray_ctx {
    const acd_bvh *b;
    const double *p;
    int winding, on_surface;
} ray_ctx;

static int ray_visit(void *user, uint32_t t) {
    ray_ctx *c = user;
    int s = line_cross_sign(c->b, t, c->p[1], c->p[2]);
    if (s) c->winding += crossing_ahead(c->b, t, s, c->p, &c->on_surface);
    return 0;
}

int acd_spatial_ray_winding(const acd_spatial *sp, const double p[3], int *on_surface) {
    ray_ctx c = {&sp->bvh, p, 0, 0};
    acd_bvh_query_axis_line(&sp->bvh, p, 0, 1, ray_visit, &c);
    if (on_surface) *on_surface = c.on_surface;
    return c.winding;
}

/* ---- generalized winding number ---- */

static double tri_solid_angle(const double *p0, const double *p1, const double *p2, const double q[3]) {
    double a[3], b[3], c[3];
    for (int k = 0; k < 3; k++) {
        a[k] = p0[k] - q[k];
        b[k] = p1[k] - q[k];
        c[k] = p2[k] - q[k];
    }
    double la = sqrt(acd_dot3(a, a)), lb = sqrt(acd_dot3(b, b)), lc = sqrt(acd_dot3(c, c));
    double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                 a[2] * (b[0] * c[1] - b[1] * c[0]);
    double den = la * lb * lc + acd_dot3(a, b) * lc + acd_dot3(a, c) * lb + acd_dot3(b, c) * la;
    if (det == 0 && den >= 0) return 0; /* in the triangle's plane, outside it (or on it) */
    return 2.0 * atan2(det, den);
}

double acd_spatial_gwn(const acd_spatial *sp, const double q[3]) {
    return acd_spatial_gwn_beta(sp, q, ACD_SPATIAL_GWN_BETA);
}

double acd_spatial_gwn_beta(const acd_spatial *sp, const double q[3], double beta) {
    const acd_bvh *b = &sp->bvh;
    if (!(beta > 1)) beta = ACD_SPATIAL_GWN_BETA;
    if (b->nnodes == 0) return 0;
    uint32_t stack[GWN_STACK];
    int top = 0;
    double w = 0;
    stack[top++] = 0;
    while (top > 0) {
        uint32_t i = stack[--top];
        const acd_bvh_node *n = &b->nodes[i];
        const double *m = sp->moments + GWN_M * (size_t)i;
        double d[3] = {m[3] - q[0], m[4] - q[1], m[5] - q[2]};
        double dist2 = acd_dot3(d, d);
        double far = beta * m[6];
        if (dist2 > far * far && dist2 > 0) {
            /* f(x) = (x - q) / |x - q|^3 expanded at the centroid: f.N + J : T, with
             * J_ij = delta_ij / |d|^3 - 3 d_i d_j / |d|^5 */
            double r = sqrt(dist2), r3 = dist2 * r, r5 = r3 * dist2;
            const double *T = m + 7;
            double dTd = 0;
            for (int a = 0; a < 3; a++)
                for (int bb = 0; bb < 3; bb++) dTd += d[a] * T[3 * a + bb] * d[bb];
            w += acd_dot3(m, d) / r3 + (T[0] + T[4] + T[8]) / r3 - 3.0 * dTd / r5;
            continue;
        }
        if (n->count) {
            for (uint32_t j = 0; j < n->count; j++) {
                const uint32_t *tr = b->triangles + 3 * (size_t)b->order[n->first + j];
                w += tri_solid_angle(b->vertices + 3 * (size_t)tr[0], b->vertices + 3 * (size_t)tr[1],
                                     b->vertices + 3 * (size_t)tr[2], q);
            }
            continue;
        }
        if (top + 2 > GWN_STACK) break; /* cannot happen for trees built by acd_bvh_build */
        stack[top++] = n->first + 1;
        stack[top++] = n->first;
    }
    return w / FOUR_PI;
}

double acd_spatial_winding_number(const acd_spatial *sp, const double p[3]) {
    if (sp->closed) return (double)acd_spatial_ray_winding(sp, p, NULL);
    return acd_spatial_gwn(sp, p);
}

int acd_spatial_classify(const acd_spatial *sp, const double p[3]) {
    if (sp->closed) {
        int on = 0;
        int w = acd_spatial_ray_winding(sp, p, &on);
        if (on) return ACD_SPATIAL_ON_SURFACE;
        return w != 0 ? ACD_SPATIAL_INSIDE : ACD_SPATIAL_OUTSIDE;
    }
    return fabs(acd_spatial_gwn(sp, p)) >= 0.5 ? ACD_SPATIAL_INSIDE : ACD_SPATIAL_OUTSIDE;
}

double acd_spatial_signed_distance(const acd_spatial *sp, const double p[3]) {
    double d = acd_spatial_distance(sp, p, NULL);
    int c = acd_spatial_classify(sp, p);
    if (c == ACD_SPATIAL_ON_SURFACE) return 0.0;
    return c == ACD_SPATIAL_INSIDE ? -d : d;
}

/* ---- lines ---- */

typedef struct line_ctx {
    const acd_bvh *b;
    acd_spatial_line *line;
    int failed;
} line_ctx;

static int line_visit(void *user, uint32_t t) {
    line_ctx *c = user;
    int s = line_cross_sign(c->b, t, c->line->y, c->line->z);
    if (!s) return 0;
    acd_spatial_line *l = c->line;
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 16;
        uint32_t *tt = realloc(l->triangles, cap * sizeof *tt);
        if (!tt) {
            c->failed = 1;
            return 1;
        }
        l->triangles = tt;
        int8_t *ss = realloc(l->signs, cap * sizeof *ss);
        if (!ss) {
            c->failed = 1;
            return 1;
        }
        l->signs = ss;
        l->cap = cap;
    }
    l->triangles[l->n] = t;
    l->signs[l->n] = (int8_t)s;
    l->n++;
    return 0;
}

acd_status acd_spatial_line_set(const acd_spatial *sp, double y, double z, acd_spatial_line *line,
                                acd_error *err) {
    line->y = y;
    line->z = z;
    line->n = 0;
    double p[3] = {0, y, z};
    line_ctx c = {&sp->bvh, line, 0};
    acd_bvh_query_axis_line(&sp->bvh, p, 0, 0, line_visit, &c);
    if (c.failed) return acd_fail(err, ACD_ERR_NOMEM, "spatial: out of memory for the crossings of a line");
    return ACD_OK;
}

int acd_spatial_line_winding(const acd_spatial *sp, const acd_spatial_line *line, double x, int *on_surface) {
    double p[3] = {x, line->y, line->z};
    int w = 0, on = 0;
    for (size_t i = 0; i < line->n; i++) w += crossing_ahead(&sp->bvh, line->triangles[i], line->signs[i], p, &on);
    if (on_surface) *on_surface = on;
    return w;
}

void acd_spatial_line_free(acd_spatial_line *line) {
    if (!line) return;
    free(line->triangles);
    free(line->signs);
    memset(line, 0, sizeof *line);
}
