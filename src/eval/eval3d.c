/* eval/eval3d: scoring a 3D decomposition against its mesh (issue "3D mesh foundation", item 6).
 *
 * Volumes: stratified Monte Carlo over the box holding the mesh and the hulls. The box is cut into
 * nx * ny * nz cells of about equal sides, one sample per cell. The (y, z) jitter is drawn once per
 * row of cells along x (each sample is still uniform in its cell), so one line serves all samples
 * of a row: the mesh's crossings of the line are found once through the BVH and every sample is
 * classified exactly from them (src/geom3/spatial.h), and each hull's interval on the line comes
 * from its planes. Integer counts only, so the figures do not depend on the thread count.
 *
 * Surface distances (docs/eval.md, "Distance to the boundary of the union"): d(p, dU) for p on
 * the mesh is the distance to the nearest hull-surface point when p is outside every hull or that
 * point lies on dU (a probe pushed out of its facet lands in no other hull): exact; otherwise the
 * nearest point among hull-surface points on dU (closest-point search with the boundary test as
 * filter, and the boundary samples): an upper bound within the boundary sample spacing. The
 * boundary dU is sampled by area-uniform points on the hull surfaces kept by the same probe test.
 *
 * Lien's dissertation, Ch. V, measures a decomposition by the concavity left in its components;
 * the distance between the mesh and the hulls' union boundary is that concavity seen from outside,
 * in the form used by V-HACD and CoACD (Wei et al., SIGGRAPH 2022, sec. 3.1: Hausdorff distance
 * between the mesh boundary and the hulls' boundary). */
#include "eval/eval3d.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cjson/cJSON.h>

#include "acd/eval.h"
#include "core/error.h"
#include "core/rng.h"
#include "core/tolerance.h"
#include "geom3/spatial.h"
#include "geom3/vec3.h"

/* ------------------------------------------------------------------------------------------ */
/* the union of hulls */

acd_status acd_hullset_build(acd_hullset *hs, const acd_hull *hulls, size_t nhulls, double diagonal,
                             acd_error *err) {
    memset(hs, 0, sizeof *hs);
    size_t nh = 0, nv = 0, nt = 0;
    for (size_t i = 0; i < nhulls; i++)
        if (hulls[i].dim == 3) {
            nh++;
            nv += hulls[i].nvertices;
            nt += hulls[i].ntriangles;
        }
    hs->probe = ACD_EVAL_PROBE_REL * diagonal;
    if (nv >= UINT32_MAX) return acd_fail(err, ACD_ERR_INVALID_INPUT, "eval: too many hull vertices (%zu)", nv);
    hs->hulls = calloc(nh ? nh : 1, sizeof *hs->hulls);
    hs->planes = malloc((nt ? nt : 1) * 4 * sizeof(double));
    hs->vertices = malloc((nv ? nv : 1) * 3 * sizeof(double));
    hs->triangles = malloc((nt ? nt : 1) * 3 * sizeof(uint32_t));
    hs->tri_hull = malloc((nt ? nt : 1) * sizeof(uint32_t));
    hs->tri_normal = malloc((nt ? nt : 1) * 3 * sizeof(double));
    if (!hs->hulls || !hs->planes || !hs->vertices || !hs->triangles || !hs->tri_hull || !hs->tri_normal) {
        acd_hullset_free(hs);
        return acd_fail(err, ACD_ERR_NOMEM, "eval: out of memory for %zu hulls", nh);
    }
    size_t np = 0;
    for (size_t i = 0; i < nhulls; i++) {
        const acd_hull *h = &hulls[i];
        if (h->dim != 3) continue;
        acd_hullset_hull *o = &hs->hulls[hs->nhulls];
        o->first_plane = np;
        o->first_vertex = hs->nvertices;
        o->nvertices = h->nvertices;
        for (int k = 0; k < 3; k++) {
            o->lo[k] = INFINITY;
            o->hi[k] = -INFINITY;
            o->centroid[k] = 0;
        }
        for (size_t v = 0; v < h->nvertices; v++)
            for (int k = 0; k < 3; k++) {
                double x = h->vertices[3 * v + k];
                if (!isfinite(x)) {
                    acd_hullset_free(hs);
                    return acd_fail(err, ACD_ERR_INVALID_INPUT, "eval: hull %zu vertex %zu has a non-finite coordinate",
                                    i, v);
                }
                o->lo[k] = fmin(o->lo[k], x);
                o->hi[k] = fmax(o->hi[k], x);
                o->centroid[k] += x / (double)h->nvertices;
                hs->vertices[3 * (hs->nvertices + v) + k] = x;
            }
        for (size_t t = 0; t < h->ntriangles; t++) {
            const double *pl = h->planes + 4 * t;
            size_t q = o->first_plane;
            while (q < np && memcmp(hs->planes + 4 * q, pl, 4 * sizeof(double)) != 0) q++;
            if (q == np) memcpy(hs->planes + 4 * np++, pl, 4 * sizeof(double));
            for (int k = 0; k < 3; k++) {
                hs->triangles[3 * hs->ntriangles + k] = (uint32_t)(hs->nvertices + h->triangles[3 * t + k]);
                hs->tri_normal[3 * hs->ntriangles + k] = pl[k];
            }
            hs->tri_hull[hs->ntriangles] = (uint32_t)hs->nhulls;
            hs->ntriangles++;
        }
        o->nplanes = np - o->first_plane;
        hs->nvertices += h->nvertices;
        hs->nhulls++;
    }
    acd_status st = acd_spatial_build(&hs->sp, hs->vertices, hs->nvertices, hs->triangles, hs->ntriangles, err);
    if (st != ACD_OK) acd_hullset_free(hs);
    return st;
}

void acd_hullset_free(acd_hullset *hs) {
    if (!hs) return;
    acd_spatial_free(&hs->sp);
    free(hs->hulls);
    free(hs->planes);
    free(hs->vertices);
    free(hs->triangles);
    free(hs->tri_hull);
    free(hs->tri_normal);
    memset(hs, 0, sizeof *hs);
}

int acd_hullset_in_hull(const acd_hullset *hs, size_t h, const double p[3]) {
    const acd_hullset_hull *o = &hs->hulls[h];
    for (int k = 0; k < 3; k++)
        if (p[k] < o->lo[k] || p[k] > o->hi[k]) return 0;
    const double *pl = hs->planes + 4 * o->first_plane;
    for (size_t i = 0; i < o->nplanes; i++, pl += 4)
        if (pl[0] * p[0] + pl[1] * p[1] + pl[2] * p[2] + pl[3] > 0) return 0;
    return 1;
}

typedef struct count_ctx {
    const acd_hullset *hs;
    const double *p;
    size_t skip;
    int winding, on;
} count_ctx;

static int count_visit(void *user, uint32_t t) {
    count_ctx *c = user;
    if (c->hs->tri_hull[t] == c->skip) return 0;
    int on = 0;
    c->winding += acd_spatial_ray_crossing(&c->hs->sp, t, c->p, &on);
    c->on |= on;
    return 0;
}

int acd_hullset_contains(const acd_hullset *hs, const double p[3], size_t skip) {
    size_t h;
    for (h = 0; h < hs->nhulls; h++) {
        const acd_hullset_hull *o = &hs->hulls[h];
        if (h != skip && p[0] >= o->lo[0] && p[0] <= o->hi[0] && p[1] >= o->lo[1] && p[1] <= o->hi[1] &&
            p[2] >= o->lo[2] && p[2] <= o->hi[2])
            break;
    }
    if (h == hs->nhulls) return 0; /* in no other hull's box */
    count_ctx c = {hs, p, skip, 0, 0};
    acd_bvh_query_axis_line(&hs->sp.bvh, p, 0, 1, count_visit, &c);
    return c.winding > 0 || c.on;
}

int acd_hullset_on_boundary(const acd_hullset *hs, size_t h, const double q[3], const double dir[3]) {
    double x[3] = {q[0] + hs->probe * dir[0], q[1] + hs->probe * dir[1], q[2] + hs->probe * dir[2]};
    return !acd_hullset_contains(hs, x, h);
}

int acd_hullset_x_interval(const acd_hullset *hs, size_t h, double y, double z, double *t0, double *t1) {
    const acd_hullset_hull *o = &hs->hulls[h];
    if (y < o->lo[1] || y > o->hi[1] || z < o->lo[2] || z > o->hi[2]) return 0;
    double a = -INFINITY, b = INFINITY;
    const double *pl = hs->planes + 4 * o->first_plane;
    for (size_t i = 0; i < o->nplanes; i++, pl += 4) {
        double c = pl[1] * y + pl[2] * z + pl[3];
        if (pl[0] > 0) b = fmin(b, -c / pl[0]);
        else if (pl[0] < 0) a = fmax(a, -c / pl[0]);
        else if (c > 0) return 0;
        if (a > b) return 0;
    }
    *t0 = a;
    *t1 = b;
    return 1;
}

/* ------------------------------------------------------------------------------------------ */
/* evaluation */

acd_eval_params acd_eval_default_params(void) {
    acd_eval_params p;
    memset(&p, 0, sizeof p);
    p.cookie = ACD_EVAL_PARAMS_COOKIE;
    p.samples = 1000000;
    p.surface_samples = 200000;
    p.seed = 1;
    return p;
}

static double now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Acceptance factor of the generalized winding number for open meshes: only its sign against 1/2
 * is used, so a coarser far field than spatial.h's default does (docs/eval.md). */
#define EVAL_GWN_BETA 2.0

/* Independent generator for (stream, index): results do not depend on the order of the work. */
static void rng_for(acd_rng *r, uint64_t seed, uint64_t stream, uint64_t index) {
    acd_rng_seed(r, seed ^ (0x9E3779B97F4A7C15ull * (index + 1)) ^ (0xD1B54A32D192ED03ull * (stream + 1)));
}

static int progress(const acd_eval_params *p, double f, const char *stage) {
    return p->progress ? p->progress(p->progress_user, f, stage) : 0;
}

typedef struct eval_ctx {
    const acd_eval_params *prm;
    const acd_spatial *mesh;
    const acd_hullset *hs;
    double lo[3], hi[3]; /* sampling box */
    double diag;
} eval_ctx;

/* Monte Carlo counts over the box: samples in M, in U, in both. */
static acd_status volume_counts(const eval_ctx *c, size_t *nsamples, size_t counts[3], acd_error *err) {
    double ext[3], vol = 1;
    for (int k = 0; k < 3; k++) {
        ext[k] = c->hi[k] - c->lo[k];
        vol *= ext[k];
    }
    double cell = cbrt(vol / (double)c->prm->samples);
    size_t n[3];
    for (int k = 0; k < 3; k++) {
        double m = floor(ext[k] / cell + 0.5);
        n[k] = m < 1 ? 1 : (size_t)m;
    }
    double h[3] = {ext[0] / (double)n[0], ext[1] / (double)n[1], ext[2] / (double)n[2]};
    size_t rows = n[1] * n[2];
    *nsamples = n[0] * rows;
    size_t cm = 0, cu = 0, cmu = 0;
    int failed = 0;
    if (progress(c->prm, 0.1, "volume")) return acd_fail(err, ACD_ERR_CANCELLED, "eval: cancelled");
#ifdef _OPENMP
#pragma omp parallel reduction(+ : cm, cu, cmu) reduction(| : failed)
#endif
    {
        acd_spatial_line line = {0}, hline = {0};
#ifdef _OPENMP
#pragma omp for schedule(dynamic, 16)
#endif
        for (long lrow = 0; lrow < (long)rows; lrow++) {
            size_t row = (size_t)lrow;
            if (failed) continue;
            acd_rng r;
            rng_for(&r, c->prm->seed, 1, row);
            size_t j = row % n[1], k = row / n[1];
            double y = c->lo[1] + ((double)j + acd_rng_uniform(&r)) * h[1];
            double z = c->lo[2] + ((double)k + acd_rng_uniform(&r)) * h[2];
            if (acd_spatial_line_set(&c->hs->sp, y, z, &hline, NULL) != ACD_OK ||
                (c->mesh->closed && acd_spatial_line_set(c->mesh, y, z, &line, NULL) != ACD_OK)) {
                failed = 1;
                continue;
            }
            for (size_t i = 0; i < n[0]; i++) {
                double x = c->lo[0] + ((double)i + acd_rng_uniform(&r)) * h[0];
                int in_m, on = 0;
                if (c->mesh->closed) {
                    in_m = line.n ? (acd_spatial_line_winding(c->mesh, &line, x, &on) != 0 || on) : 0;
                } else {
                    double p[3] = {x, y, z};
                    in_m = fabs(acd_spatial_gwn_beta(c->mesh, p, EVAL_GWN_BETA)) >= 0.5;
                }
                on = 0;
                int in_u = hline.n ? (acd_spatial_line_winding(&c->hs->sp, &hline, x, &on) > 0 || on) : 0;
                cm += (size_t)in_m;
                cu += (size_t)in_u;
                cmu += (size_t)(in_m && in_u);
            }
        }
        acd_spatial_line_free(&line);
        acd_spatial_line_free(&hline);
    }
    if (failed) return acd_fail(err, ACD_ERR_NOMEM, "eval: out of memory while sampling volumes");
    counts[0] = cm;
    counts[1] = cu;
    counts[2] = cmu;
    return ACD_OK;
}

/* n area-uniform points on a triangle set (systematic sampling along the cumulative area, then a
 * uniform point in the chosen triangle); tri_of receives each point's triangle. */
static acd_status sample_surface(const double *v, const uint32_t *t, size_t nt, size_t n, uint64_t seed,
                                 uint64_t stream, double *pts, uint32_t *tri_of, double *total_area,
                                 acd_error *err) {
    double *cum = malloc((nt ? nt : 1) * sizeof(double));
    if (!cum) return acd_fail(err, ACD_ERR_NOMEM, "eval: out of memory for %zu triangle areas", nt);
    double acc = 0;
    for (size_t i = 0; i < nt; i++) {
        const double *a = v + 3 * (size_t)t[3 * i], *b = v + 3 * (size_t)t[3 * i + 1], *c = v + 3 * (size_t)t[3 * i + 2];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double x = e1[1] * e2[2] - e1[2] * e2[1], y = e1[2] * e2[0] - e1[0] * e2[2], z = e1[0] * e2[1] - e1[1] * e2[0];
        acc += 0.5 * sqrt(x * x + y * y + z * z);
        cum[i] = acc;
    }
    *total_area = acc;
    acd_rng r0;
    rng_for(&r0, seed, stream, 0);
    double off = acd_rng_uniform(&r0);
    size_t ti = 0;
    for (size_t s = 0; s < n; s++) {
        double u = ((double)s + off) / (double)n * acc;
        while (ti + 1 < nt && cum[ti] <= u) ti++;
        acd_rng r;
        rng_for(&r, seed, stream, s + 1);
        double r1 = sqrt(acd_rng_uniform(&r)), r2 = acd_rng_uniform(&r);
        const double *a = v + 3 * (size_t)t[3 * ti], *b = v + 3 * (size_t)t[3 * ti + 1], *c = v + 3 * (size_t)t[3 * ti + 2];
        for (int k = 0; k < 3; k++) pts[3 * s + k] = (1 - r1) * a[k] + r1 * (1 - r2) * b[k] + r1 * r2 * c[k];
        tri_of[s] = (uint32_t)ti;
    }
    free(cum);
    return ACD_OK;
}

typedef struct boundary_filter {
    const acd_hullset *hs;
} boundary_filter;

static int accept_boundary(void *user, uint32_t t, const double q[3]) {
    const acd_hullset *hs = ((boundary_filter *)user)->hs;
    return acd_hullset_on_boundary(hs, hs->tri_hull[t], q, hs->tri_normal + 3 * (size_t)t);
}

/* Closest point on a tree with a warm start: `hint` (>= the true distance, or INFINITY) prunes the
 * search; the result does not depend on it (the minimum over the triangles is the same). */
static double closest_hinted(const acd_bvh *b, const double p[3], double hint, acd_bvh_closest_result *q) {
    if (isfinite(hint)) {
        double h = hint * (1 + 1e-9) + DBL_MIN;
        if (acd_bvh_closest(b, p, h * h, q)) return sqrt(q->dist2);
    }
    if (!acd_bvh_closest(b, p, INFINITY, q)) return INFINITY;
    return sqrt(q->dist2);
}

/* Distance from p to the boundary of the union (see the file comment). Returns the exact value,
 * or, with *exact = 0, the upper bound from the boundary test filter (the boundary samples are
 * consulted afterwards). hint: an upper bound of the distance to the hull surfaces or INFINITY. */
static double dist_to_union_boundary(const acd_hullset *hs, const double p[3], double hint, int *exact,
                                     double *surface_dist) {
    acd_bvh_closest_result q0;
    *exact = 1;
    double d0 = closest_hinted(&hs->sp.bvh, p, hint, &q0);
    *surface_dist = d0;
    if (!isfinite(d0)) return INFINITY;
    /* the nearest hull-surface point is on the boundary: nothing on the boundary is nearer */
    if (accept_boundary(&(boundary_filter){hs}, q0.triangle, q0.point)) return d0;
    /* p outside every hull: its distance to the union is attained on the boundary */
    if (!acd_hullset_contains(hs, p, SIZE_MAX)) return d0;
    *exact = 0;
    acd_bvh_closest_result q1;
    boundary_filter f = {hs};
    if (acd_bvh_closest_filtered(&hs->sp.bvh, p, INFINITY, accept_boundary, &f, &q1)) return sqrt(q1.dist2);
    return INFINITY;
}

#define EVAL_CHUNK 512 /* samples per unit of parallel work (fixed: results do not depend on threads) */

/* Distances of points pts[0..n) to the mesh surface into d[], warm-started along each chunk. */
static void dist_to_mesh(const acd_spatial *mesh, const double *pts, size_t n, double *d) {
    long nchunks = (long)((n + EVAL_CHUNK - 1) / EVAL_CHUNK);
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1)
#endif
    for (long ch = 0; ch < nchunks; ch++) {
        size_t s0 = (size_t)ch * EVAL_CHUNK, s1 = s0 + EVAL_CHUNK < n ? s0 + EVAL_CHUNK : n;
        double prev = INFINITY;
        for (size_t s = s0; s < s1; s++) {
            acd_bvh_closest_result q;
            double hint = s > s0 ? prev + acd_dist3(pts + 3 * s, pts + 3 * (s - 1)) : INFINITY;
            d[s] = prev = closest_hinted(&mesh->bvh, pts + 3 * s, hint, &q);
        }
    }
}

/* Distances of points to the boundary of the union into d[]; exact[] (0/1) per point. */
static void dist_to_boundary(const acd_hullset *hs, const double *pts, size_t n, double *d, unsigned char *exact) {
    long nchunks = (long)((n + EVAL_CHUNK - 1) / EVAL_CHUNK);
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1)
#endif
    for (long ch = 0; ch < nchunks; ch++) {
        size_t s0 = (size_t)ch * EVAL_CHUNK, s1 = s0 + EVAL_CHUNK < n ? s0 + EVAL_CHUNK : n;
        double prev = INFINITY;
        for (size_t s = s0; s < s1; s++) {
            double hint = s > s0 ? prev + acd_dist3(pts + 3 * s, pts + 3 * (s - 1)) : INFINITY;
            int ex;
            d[s] = dist_to_union_boundary(hs, pts + 3 * s, hint, &ex, &prev);
            exact[s] = (unsigned char)ex;
        }
    }
}

static acd_status surface_distances(const eval_ctx *c, const acd_mesh *mesh, acd_eval_report *rep, acd_error *err) {
    const acd_hullset *hs = c->hs;
    /* the mesh's vertices join its samples: only those a triangle uses (a vertex no face uses is
     * not on the surface; a stray one read as the surface 3.5 from the hulls of a cube) */
    unsigned char *used = calloc(mesh->nvertices ? mesh->nvertices : 1, 1);
    if (!used) return acd_fail(err, ACD_ERR_NOMEM, "eval: out of memory for %zu vertices", mesh->nvertices);
    for (size_t k = 0; k < 3 * mesh->ntriangles; k++) used[mesh->triangles[k]] = 1;
    size_t nv = 0;
    for (size_t v = 0; v < mesh->nvertices; v++) nv += used[v];
    size_t n = c->prm->surface_samples, nm = n + nv;
    acd_status st = ACD_OK;
    double *hp = malloc((n ? n : 1) * 3 * sizeof(double));
    uint32_t *ht = malloc((nm ? nm : 1) * sizeof(uint32_t));
    double *mp = malloc((nm ? nm : 1) * 3 * sizeof(double));
    double *dist = malloc((nm ? nm : 1) * sizeof(double));
    unsigned char *flag = malloc(nm ? nm : 1);
    uint32_t *btri = NULL;
    acd_bvh bs;
    memset(&bs, 0, sizeof bs);
    if (!hp || !ht || !mp || !dist || !flag) {
        st = acd_fail(err, ACD_ERR_NOMEM, "eval: out of memory for %zu surface samples", n);
        goto done;
    }
    /* boundary of the union: hull-surface samples kept by the probe test */
    double harea = 0, marea = 0;
    st = sample_surface(hs->vertices, hs->triangles, hs->ntriangles, n, c->prm->seed, 2, hp, ht, &harea, err);
    if (st != ACD_OK) goto done;
#ifdef _OPENMP
#pragma omp parallel for schedule(static)
#endif
    for (long s = 0; s < (long)n; s++) {
        uint32_t t = ht[s];
        flag[s] = (unsigned char)acd_hullset_on_boundary(hs, hs->tri_hull[t], hp + 3 * s, hs->tri_normal + 3 * (size_t)t);
    }
    size_t nb = 0;
    for (size_t s = 0; s < n; s++) {
        if (!flag[s]) continue;
        memmove(hp + 3 * nb, hp + 3 * s, 3 * sizeof(double));
        nb++;
    }
    rep->boundary_samples = nb;
    double barea = n ? harea * (double)nb / (double)n : 0;
    rep->boundary_spacing = nb ? sqrt(barea / (double)nb) / c->diag : 0;
    if (progress(c->prm, 0.6, "boundary to mesh")) {
        st = acd_fail(err, ACD_ERR_CANCELLED, "eval: cancelled");
        goto done;
    }

    /* boundary -> mesh: mean over the samples, max over samples and boundary hull vertices */
    dist_to_mesh(c->mesh, hp, nb, dist);
    double sum = 0, mx = 0;
    for (size_t s = 0; s < nb; s++) {
        sum += dist[s];
        if (dist[s] > mx) mx = dist[s];
    }
    for (size_t h = 0; h < hs->nhulls; h++) {
        const acd_hullset_hull *o = &hs->hulls[h];
        for (size_t v = o->first_vertex; v < o->first_vertex + o->nvertices; v++) {
            const double *x = hs->vertices + 3 * v;
            double dir[3] = {x[0] - o->centroid[0], x[1] - o->centroid[1], x[2] - o->centroid[2]};
            double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
            if (!(len > 0)) continue;
            for (int k = 0; k < 3; k++) dir[k] /= len;
            if (!acd_hullset_on_boundary(hs, h, x, dir)) continue;
            double d = acd_spatial_distance(c->mesh, x, NULL);
            if (d > mx) mx = d;
        }
    }
    rep->hulls_to_mesh_mean = nb ? sum / (double)nb / c->diag : 0;
    rep->hulls_to_mesh_max = mx / c->diag;
    if (progress(c->prm, 0.8, "mesh to boundary")) {
        st = acd_fail(err, ACD_ERR_CANCELLED, "eval: cancelled");
        goto done;
    }

    /* mesh -> boundary: mean over area-uniform samples, max over samples and mesh vertices */
    st = sample_surface(mesh->vertices, mesh->triangles, mesh->ntriangles, n, c->prm->seed, 3, mp, ht, &marea, err);
    if (st != ACD_OK) goto done;
    for (size_t v = 0, k = n; v < mesh->nvertices; v++)
        if (used[v]) memcpy(mp + 3 * k++, mesh->vertices + 3 * v, 3 * sizeof(double));
    dist_to_boundary(hs, mp, nm, dist, flag);
    size_t inexact = 0;
    for (size_t s = 0; s < nm; s++) inexact += (size_t)!flag[s];
    if (inexact && nb) {
        /* the few points whose nearest boundary point was not found exactly: also the nearest
         * boundary sample (both are points of the boundary, so the smaller is the better bound) */
        btri = malloc(nb * 3 * sizeof(uint32_t));
        if (!btri) {
            st = acd_fail(err, ACD_ERR_NOMEM, "eval: out of memory for %zu boundary samples", nb);
            goto done;
        }
        for (size_t s = 0; s < nb; s++) btri[3 * s] = btri[3 * s + 1] = btri[3 * s + 2] = (uint32_t)s;
        st = acd_bvh_build(&bs, hp, nb, btri, nb, err);
        if (st != ACD_OK) goto done;
        for (size_t s = 0; s < nm; s++) {
            if (flag[s]) continue;
            acd_bvh_closest_result q;
            double lim = isfinite(dist[s]) ? dist[s] * dist[s] : INFINITY;
            if (acd_bvh_closest(&bs, mp + 3 * s, lim, &q) && sqrt(q.dist2) < dist[s]) dist[s] = sqrt(q.dist2);
        }
    }
    sum = 0;
    mx = 0;
    for (size_t s = 0; s < nm; s++) {
        if (s < n) sum += dist[s];
        if (dist[s] > mx) mx = dist[s];
    }
    rep->mesh_to_hulls_mean = n ? sum / (double)n / c->diag : 0;
    rep->mesh_to_hulls_max = mx / c->diag;
    rep->inexact_distances = inexact;
done:
    acd_bvh_free(&bs);
    free(btri);
    free(hp);
    free(ht);
    free(mp);
    free(dist);
    free(flag);
    free(used);
    return st;
}

static int used_vertex_ok(const acd_mesh *m, acd_error *err, acd_status *st) {
    for (size_t t = 0; t < m->ntriangles; t++)
        for (int k = 0; k < 3; k++)
            if (m->triangles[3 * t + k] >= m->nvertices) {
                *st = acd_fail(err, ACD_ERR_INVALID_INPUT, "eval: mesh triangle %zu refers to vertex %u of %zu", t,
                               m->triangles[3 * t + k], m->nvertices);
                return 0;
            }
    acd_error ce;
    if (m->nvertices && acd_check_coordinates(m->vertices, m->nvertices, 3, &ce) != ACD_OK) {
        *st = acd_fail(err, ACD_ERR_INVALID_INPUT, "eval: mesh %s", ce.message);
        return 0;
    }
    return 1;
}

acd_status acd_eval_hulls(const acd_mesh *mesh, const acd_hull *hulls, size_t nhulls, const acd_eval_params *params,
                          acd_eval_report *out, acd_error *err) {
    double t0 = now_seconds();
    acd_eval_params prm = params ? *params : acd_eval_default_params();
    if (prm.cookie != ACD_EVAL_PARAMS_COOKIE)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "eval: parameters not made by acd_eval_default_params");
    if (!mesh || !out || (nhulls && !hulls)) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "eval: NULL argument");
    if (prm.samples < 1 || prm.surface_samples < 1)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "eval: samples and surface samples must be >= 1");
    memset(out, 0, sizeof *out);
    if (mesh->ntriangles == 0) return acd_fail(err, ACD_ERR_DEGENERATE, "eval: the mesh has no triangles");
    acd_status st = ACD_OK;
    if (!used_vertex_ok(mesh, err, &st)) return st;

    /* hulls beyond ACD_COORD_MAX overflow the sampling box (a 1e300 part was reported as "the mesh
     * encloses no volume (no sample of 1 fell inside)") */
    for (size_t i = 0; i < nhulls; i++) {
        acd_error ce;
        if (hulls[i].nvertices && acd_check_coordinates(hulls[i].vertices, hulls[i].nvertices, 3, &ce) != ACD_OK)
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "eval: hull of part %zu: %s", i, ce.message);
    }
    out->parts = nhulls;
    out->seed = prm.seed;
    for (size_t i = 0; i < nhulls; i++) {
        out->hull_vertices += hulls[i].nvertices;
        if (hulls[i].dim != 3) out->degenerate_parts++;
        else out->hull_volume_sum += hulls[i].volume;
    }
    acd_spatial sp;
    st = acd_spatial_build(&sp, mesh->vertices, mesh->nvertices, mesh->triangles, mesh->ntriangles, err);
    if (st != ACD_OK) return st;
    out->mesh_closed = sp.closed;
    const acd_bvh_node *root = &sp.bvh.nodes[0];
    double ctr[3], vol = 0;
    for (int k = 0; k < 3; k++) ctr[k] = 0.5 * (root->lo[k] + root->hi[k]);
    for (size_t t = 0; t < mesh->ntriangles; t++) {
        double a[3], b[3], c[3];
        for (int k = 0; k < 3; k++) {
            a[k] = mesh->vertices[3 * (size_t)mesh->triangles[3 * t] + k] - ctr[k];
            b[k] = mesh->vertices[3 * (size_t)mesh->triangles[3 * t + 1] + k] - ctr[k];
            c[k] = mesh->vertices[3 * (size_t)mesh->triangles[3 * t + 2] + k] - ctr[k];
        }
        vol += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    out->mesh_volume = fabs(vol) / 6.0;
    out->diagonal = sp.scale.extent;
    acd_hullset hs;
    st = acd_hullset_build(&hs, hulls, nhulls, out->diagonal, err);
    if (st != ACD_OK) {
        acd_spatial_free(&sp);
        return st;
    }
    if (hs.nhulls == 0) {
        st = acd_fail(err, ACD_ERR_DEGENERATE, "eval: none of the %zu parts has a solid (3D) hull", nhulls);
        goto done;
    }
    eval_ctx c = {&prm, &sp, &hs, {0}, {0}, out->diagonal};
    for (int k = 0; k < 3; k++) {
        c.lo[k] = fmin(root->lo[k], hs.sp.bvh.nodes[0].lo[k]);
        c.hi[k] = fmax(root->hi[k], hs.sp.bvh.nodes[0].hi[k]);
        if (!(c.hi[k] > c.lo[k])) {
            st = acd_fail(err, ACD_ERR_DEGENERATE, "eval: the mesh and hulls are flat along axis %d", k);
            goto done;
        }
    }
    size_t counts[3] = {0, 0, 0};
    st = volume_counts(&c, &out->samples, counts, err);
    if (st != ACD_OK) goto done;
    if (counts[0] == 0) {
        st = acd_fail(err, ACD_ERR_DEGENERATE, "eval: the mesh encloses no volume (no sample of %zu fell inside)",
                      out->samples);
        goto done;
    }
    double box = (c.hi[0] - c.lo[0]) * (c.hi[1] - c.lo[1]) * (c.hi[2] - c.lo[2]);
    out->union_volume = box * (double)counts[1] / (double)out->samples;
    out->iou = (double)counts[2] / (double)(counts[0] + counts[1] - counts[2]);
    out->coverage = (double)counts[2] / (double)counts[0];
    out->excess = (double)(counts[1] - counts[2]) / (double)counts[0];
    out->surface_samples = prm.surface_samples;
    st = surface_distances(&c, mesh, out, err);
    if (st != ACD_OK) goto done;
    out->concavity_max = fmax(out->mesh_to_hulls_max, out->hulls_to_mesh_max);
    progress(&prm, 1.0, "done");
done:
    acd_hullset_free(&hs);
    acd_spatial_free(&sp);
    out->seconds = now_seconds() - t0;
    return st;
}

acd_status acd_eval_parts(const acd_mesh *mesh, const acd_mesh_parts *parts, const acd_eval_params *params,
                          acd_eval_report *out, acd_error *err) {
    if (!parts || (parts->count && !parts->parts)) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "eval: NULL parts");
    acd_hull *hulls = calloc(parts->count ? parts->count : 1, sizeof *hulls);
    if (!hulls) return acd_fail(err, ACD_ERR_NOMEM, "eval: out of memory for %zu hulls", parts->count);
    acd_status st = ACD_OK;
    size_t i;
    for (i = 0; i < parts->count; i++) {
        const acd_mesh *pm = &parts->parts[i].mesh;
        acd_error e2;
        st = pm->nvertices ? acd_check_coordinates(pm->vertices, pm->nvertices, 3, &e2) : ACD_OK;
        if (st == ACD_OK) st = acd_hull_compute(pm->vertices, pm->nvertices, &hulls[i], &e2);
        if (st != ACD_OK) {
            st = acd_fail(err, st, "eval: hull of part %zu ('%s'): %s", i, parts->parts[i].name ? parts->parts[i].name : "",
                          e2.message);
            break;
        }
    }
    if (st == ACD_OK) st = acd_eval_hulls(mesh, hulls, parts->count, params, out, err);
    for (size_t j = 0; j < parts->count; j++) acd_hull_free(&hulls[j]);
    free(hulls);
    return st;
}

acd_status acd_eval_report_json(const acd_eval_report *r, char **json, acd_error *err) {
    *json = NULL;
    cJSON *o = cJSON_CreateObject(), *d = cJSON_CreateObject();
    if (!o || !d) {
        cJSON_Delete(o);
        cJSON_Delete(d);
        return acd_fail(err, ACD_ERR_NOMEM, "eval: out of memory for the JSON report");
    }
    cJSON_AddNumberToObject(o, "parts", (double)r->parts);
    cJSON_AddNumberToObject(o, "degenerate_parts", (double)r->degenerate_parts);
    cJSON_AddNumberToObject(o, "hull_vertices", (double)r->hull_vertices);
    cJSON_AddNumberToObject(o, "mesh_volume", r->mesh_volume);
    cJSON_AddNumberToObject(o, "hull_volume_sum", r->hull_volume_sum);
    cJSON_AddNumberToObject(o, "union_volume", r->union_volume);
    cJSON_AddNumberToObject(o, "iou", r->iou);
    cJSON_AddNumberToObject(o, "coverage", r->coverage);
    cJSON_AddNumberToObject(o, "excess", r->excess);
    cJSON_AddNumberToObject(d, "mesh_to_hulls_max", r->mesh_to_hulls_max);
    cJSON_AddNumberToObject(d, "mesh_to_hulls_mean", r->mesh_to_hulls_mean);
    cJSON_AddNumberToObject(d, "hulls_to_mesh_max", r->hulls_to_mesh_max);
    cJSON_AddNumberToObject(d, "hulls_to_mesh_mean", r->hulls_to_mesh_mean);
    cJSON_AddItemToObject(o, "distance", d);
    cJSON_AddNumberToObject(o, "concavity_max", r->concavity_max);
    cJSON_AddNumberToObject(o, "diagonal", r->diagonal);
    cJSON_AddNumberToObject(o, "boundary_spacing", r->boundary_spacing);
    cJSON_AddNumberToObject(o, "inexact_distances", (double)r->inexact_distances);
    cJSON_AddBoolToObject(o, "mesh_closed", r->mesh_closed);
    cJSON_AddNumberToObject(o, "samples", (double)r->samples);
    cJSON_AddNumberToObject(o, "surface_samples", (double)r->surface_samples);
    cJSON_AddNumberToObject(o, "boundary_samples", (double)r->boundary_samples);
    cJSON_AddNumberToObject(o, "seed", (double)r->seed);
    cJSON_AddNumberToObject(o, "seconds", r->seconds);
    char *s = cJSON_Print(o);
    cJSON_Delete(o);
    if (!s) return acd_fail(err, ACD_ERR_NOMEM, "eval: out of memory for the JSON report");
    *json = s;
    return ACD_OK;
}
