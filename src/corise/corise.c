/* corise/corise: the CoRiSe loop (§3, §5.2; spec corise.md §2.1, §2.8). */
#include "corise/corise.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd3/poll.h"
#include "core/error.h"
#include "core/union_find.h"
#include "corise/edgesort.h"
#include "corise/regions.h"
#include "corise/ridge.h"
#include "corise/valley.h"
#include "geom3/dijkstra.h"
#ifdef _OPENMP
#include <omp.h>
#endif

acd_corise_params acd_corise_default_params(void) {
    acd_corise_params p;
    memset(&p, 0, sizeof p);
    p.tau = 0.1;
    p.normalize = 1;
    p.cut = acd_corise_cut_default_params();
    p.max_depth = 64;
    p.threads = 1;
    return p;
}

typedef acd_corise_ef ef;

/* Edge-connected components of the facets faces[0..n) of m: comp[i] = component of faces[i],
 * numbered by first occurrence. Returns the count, or SIZE_MAX when out of memory. */
static size_t components(const acd_mesh *m, const uint32_t *faces, size_t n, uint32_t *comp) {
    ef *e = malloc((n ? 3 * n : 1) * sizeof *e);
    uint32_t *p = malloc((n ? n : 1) * sizeof *p), *id = malloc((n ? n : 1) * sizeof *id);
    if (!e || !p || !id) {
        free(e);
        free(p);
        free(id);
        return SIZE_MAX;
    }
    for (size_t i = 0; i < n; i++) {
        p[i] = (uint32_t)i;
        const uint32_t *T = m->triangles + 3 * (size_t)faces[i];
        for (int k = 0; k < 3; k++) {
            uint32_t u = T[k], v = T[(k + 1) % 3];
            e[3 * i + k] = (ef){u < v ? u : v, u < v ? v : u, (uint32_t)i};
        }
    }
    if (!acd_corise_ef_sort(e, 3 * n)) {
        free(e);
        free(p);
        free(id);
        return SIZE_MAX;
    }
    for (size_t i = 1; i < 3 * n; i++)
        if (e[i].lo == e[i - 1].lo && e[i].hi == e[i - 1].hi) {
            uint32_t a = acd_uf_find(p, e[i].face), b = acd_uf_find(p, e[i - 1].face);
            if (a != b) p[a < b ? b : a] = a < b ? a : b;
        }
    size_t nc = 0;
    for (size_t i = 0; i < n; i++) id[i] = UINT32_MAX;
    for (size_t i = 0; i < n; i++) {
        uint32_t r = acd_uf_find(p, (uint32_t)i);
        if (id[r] == UINT32_MAX) id[r] = (uint32_t)nc++;
        comp[i] = id[r];
    }
    free(e);
    free(p);
    free(id);
    return nc;
}

typedef struct part {
    uint32_t *faces;
    size_t n;
    size_t depth;
    double conc; /* final parts: the largest valley concavity the loop measured on it */
} part;

typedef struct part_list {
    part *p;
    size_t n, cap, head;
} part_list;

static int push_part(part_list *l, uint32_t *faces, size_t n, size_t depth) {
    if (l->n == l->cap) {
        size_t nc = l->cap ? 2 * l->cap : 16;
        part *q = realloc(l->p, nc * sizeof *q);
        if (!q) return 0;
        l->p = q;
        l->cap = nc;
    }
    l->p[l->n++] = (part){faces, n, depth, 0};
    return 1;
}

/* Pushes every component of faces[0..n) (taking ownership of faces). */
static int push_components(const acd_mesh *m, part_list *q, uint32_t *faces, size_t n, size_t depth) {
    uint32_t *comp = malloc((n ? n : 1) * sizeof *comp);
    if (!comp) {
        free(faces);
        return 0;
    }
    size_t nc = components(m, faces, n, comp);
    if (nc == SIZE_MAX) {
        free(comp);
        free(faces);
        return 0;
    }
    if (nc == 1) {
        free(comp);
        return push_part(q, faces, n, depth) ? 1 : (free(faces), 0);
    }
    int ok = 1;
    for (size_t c = 0; c < nc && ok; c++) {
        size_t k = 0;
        for (size_t i = 0; i < n; i++) k += comp[i] == c;
        uint32_t *f = malloc(k * sizeof *f);
        if (!f) {
            ok = 0;
            break;
        }
        k = 0;
        for (size_t i = 0; i < n; i++)
            if (comp[i] == c) f[k++] = faces[i];
        if (!push_part(q, f, k, depth)) {
            free(f);
            ok = 0;
        }
    }
    free(comp);
    free(faces);
    return ok;
}

/* Submesh of the facets faces[0..n): vertices in order of first use; l2g (3n entries) receives
 * the global id of each local vertex. */
static int extract(const acd_mesh *m, const uint32_t *faces, size_t n, uint32_t *map, uint32_t *l2g, acd_mesh *out) {
    memset(out, 0, sizeof *out);
    out->triangles = malloc((n ? 3 * n : 1) * sizeof *out->triangles);
    out->vertices = malloc((n ? 3 * n : 1) * 3 * sizeof *out->vertices);
    if (!out->triangles || !out->vertices) {
        acd_mesh_free(out);
        return 0;
    }
    size_t nv = 0;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            uint32_t v = m->triangles[3 * (size_t)faces[i] + k];
            if (map[v] == UINT32_MAX) {
                map[v] = (uint32_t)nv;
                l2g[nv] = v;
                memcpy(out->vertices + 3 * nv, m->vertices + 3 * (size_t)v, 3 * sizeof(double));
                nv++;
            }
            out->triangles[3 * i + k] = map[v];
        }
    for (size_t i = 0; i < n; i++) /* reset the map for the next call */
        for (int k = 0; k < 3; k++) map[m->triangles[3 * (size_t)faces[i] + k]] = UINT32_MAX;
    out->nvertices = nv;
    out->ntriangles = n;
    return 1;
}

/* Edges of the whole (normalised) mesh with their facet counts, to tell the boundaries a cut
 * opened from the input's own boundaries. */
typedef struct edge_count {
    uint32_t lo, hi;
    size_t count;
} edge_count;

static int cmp_edge_count(const void *x, const void *y) {
    const edge_count *p = x, *q = y;
    if (p->lo != q->lo) return p->lo < q->lo ? -1 : 1;
    return (p->hi > q->hi) - (p->hi < q->hi);
}

/* The distinct edges sorted by (lo, hi), with their counts: one order and one array whatever the
 * sort (the records of an edge are counted, not kept), sorted by corise/edgesort's radix sort
 * (qsort of 2.5 M records took 0.5 s at 832k facets). */
static edge_count *global_edges(const acd_mesh *m, size_t *n) {
    size_t ne = 3 * m->ntriangles;
    ef *r = malloc((ne ? ne : 1) * sizeof *r);
    edge_count *e = malloc((ne ? ne : 1) * sizeof *e);
    if (!r || !e) {
        free(r);
        free(e);
        return NULL;
    }
    for (size_t t = 0; t < m->ntriangles; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t u = m->triangles[3 * t + k], v = m->triangles[3 * t + (k + 1) % 3];
            r[3 * t + k] = (ef){u < v ? u : v, u < v ? v : u, (uint32_t)t};
        }
    if (!acd_corise_ef_sort(r, ne)) {
        free(r);
        free(e);
        return NULL;
    }
    size_t k = 0;
    for (size_t i = 0; i < ne; i++) {
        if (k && e[k - 1].lo == r[i].lo && e[k - 1].hi == r[i].hi)
            e[k - 1].count++;
        else
            e[k++] = (edge_count){r[i].lo, r[i].hi, 1};
    }
    free(r);
    *n = k;
    return e;
}

static size_t global_count(const edge_count *e, size_t n, uint32_t a, uint32_t b) {
    edge_count key = {a < b ? a : b, a < b ? b : a, 0};
    const edge_count *f = bsearch(&key, e, n, sizeof *e, cmp_edge_count);
    return f ? f->count : 0;
}

/* Caps the holes a cut opened in the part s (decision recorded in docs/corise.md): every
 * boundary edge of s that is interior in the whole mesh gets a triangle to the centroid of its
 * connected boundary curve, so that valleys (and region balls, and later cuts) may cross the
 * opening, where the solid was, instead of running around its rim. out = s plus the caps (the
 * first s->ntriangles facets are s's). */
static int cap_cut_holes(const acd_mesh *s, const uint32_t *l2g, const edge_count *ge, size_t nge, acd_mesh *out) {
    memset(out, 0, sizeof *out);
    size_t nt = s->ntriangles, ne = 3 * nt;
    ef *e = malloc((ne ? ne : 1) * sizeof *e);
    uint32_t *cu = malloc((ne ? ne : 1) * 2 * sizeof *cu); /* directed cut edges */
    uint32_t *p = malloc((s->nvertices ? s->nvertices : 1) * sizeof *p);
    uint32_t *gid = malloc((s->nvertices ? s->nvertices : 1) * sizeof *gid);
    if (!e || !cu || !p || !gid) goto fail;
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t u = s->triangles[3 * t + k], v = s->triangles[3 * t + (k + 1) % 3];
            e[3 * t + k] = (ef){u < v ? u : v, u < v ? v : u, (uint32_t)(3 * t + (size_t)k)};
        }
    if (!acd_corise_ef_sort(e, ne)) goto fail;
    size_t nc = 0;
    for (size_t i = 0; i < ne;) {
        size_t j = i + 1;
        while (j < ne && e[j].lo == e[i].lo && e[j].hi == e[i].hi) j++;
        if (j == i + 1 && e[i].lo != e[i].hi && global_count(ge, nge, l2g[e[i].lo], l2g[e[i].hi]) >= 2) {
            size_t t = e[i].face / 3, k = e[i].face % 3;
            cu[2 * nc] = s->triangles[3 * t + k];
            cu[2 * nc + 1] = s->triangles[3 * t + (k + 1) % 3];
            nc++;
        }
        i = j;
    }
    for (size_t v = 0; v < s->nvertices; v++) p[v] = (uint32_t)v, gid[v] = UINT32_MAX;
    for (size_t i = 0; i < nc; i++) {
        uint32_t a = acd_uf_find(p, cu[2 * i]), b = acd_uf_find(p, cu[2 * i + 1]);
        if (a != b) p[a < b ? b : a] = a < b ? a : b;
    }
    size_t ng = 0;
    for (size_t i = 0; i < nc; i++) {
        uint32_t r = acd_uf_find(p, cu[2 * i]);
        if (gid[r] == UINT32_MAX) gid[r] = (uint32_t)ng++;
    }
    out->nvertices = s->nvertices + ng;
    out->ntriangles = nt + nc;
    out->vertices = calloc(3 * (out->nvertices ? out->nvertices : 1), sizeof *out->vertices);
    out->triangles = malloc(3 * (out->ntriangles ? out->ntriangles : 1) * sizeof *out->triangles);
    double *cnt = calloc(ng ? ng : 1, sizeof *cnt);
    if (!out->vertices || !out->triangles || !cnt) {
        free(cnt);
        goto fail;
    }
    memcpy(out->vertices, s->vertices, 3 * s->nvertices * sizeof *out->vertices);
    memcpy(out->triangles, s->triangles, 3 * nt * sizeof *out->triangles);
    for (size_t i = 0; i < nc; i++) { /* centroid of each curve's edge endpoints */
        uint32_t g = gid[acd_uf_find(p, cu[2 * i])];
        for (int k = 0; k < 2; k++)
            for (int c = 0; c < 3; c++)
                out->vertices[3 * (s->nvertices + g) + c] += s->vertices[3 * (size_t)cu[2 * i + k] + c];
        cnt[g] += 2;
    }
    for (size_t g = 0; g < ng; g++)
        for (int c = 0; c < 3; c++) out->vertices[3 * (s->nvertices + g) + c] /= cnt[g];
    for (size_t i = 0; i < nc; i++) {
        uint32_t g = gid[acd_uf_find(p, cu[2 * i])];
        uint32_t *T = out->triangles + 3 * (nt + i);
        T[0] = cu[2 * i + 1]; /* reversed edge: consistent orientation with the part */
        T[1] = cu[2 * i];
        T[2] = (uint32_t)(s->nvertices + g);
    }
    free(cnt);
    free(e);
    free(cu);
    free(p);
    free(gid);
    return 1;
fail:
    free(e);
    free(cu);
    free(p);
    free(gid);
    acd_mesh_free(out);
    return 0;
}

/* Normalised coordinates (A1): AABB centre of the used vertices at the origin, largest distance
 * of a used vertex 1; w->vertices is a copy of m's. *scale (may be NULL) receives the factor. */
static void normalise(const acd_mesh *m, acd_mesh *w, double *scale) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t t = 0; t < 3 * m->ntriangles; t++)
        for (int c = 0; c < 3; c++) {
            double x = m->vertices[3 * (size_t)m->triangles[t] + c];
            if (x < lo[c]) lo[c] = x;
            if (x > hi[c]) hi[c] = x;
        }
    double cen[3] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])}, rad = 0;
    for (size_t t = 0; t < 3 * m->ntriangles; t++) {
        const double *p = m->vertices + 3 * (size_t)m->triangles[t];
        double d = sqrt((p[0] - cen[0]) * (p[0] - cen[0]) + (p[1] - cen[1]) * (p[1] - cen[1]) +
                        (p[2] - cen[2]) * (p[2] - cen[2]));
        if (d > rad) rad = d;
    }
    if (rad > 0) {
        if (scale) *scale = 1.0 / rad;
        for (size_t v = 0; v < m->nvertices; v++)
            for (int c = 0; c < 3; c++) w->vertices[3 * v + c] = (m->vertices[3 * v + c] - cen[c]) / rad;
    }
}

/* The progress callback between the phases of a step, when it is a wave's only part (caller
 * non-zero: the root's above all; run on the calling thread, and so for any number of threads);
 * the fraction is the wave's. ACD_ERR_CANCELLED when it asks to stop. */
static acd_status step_progress(const acd_corise_params *prm, int caller, double fraction, acd_error *err) {
    if (caller && prm->progress && prm->progress(prm->progress_user, fraction, "corise"))
        return acd_fail(err, ACD_ERR_CANCELLED, "corise: cancelled by the progress callback within a part's step");
    return ACD_OK;
}

/* acd3/poll's callback for acd_corise_poll_init: the caller's, told the last milestone's fraction. */
static int poll_call(void *user, double fraction, const char *stage) {
    (void)fraction;
    const acd_corise_poll_ctx *c = user;
    return c->fn(c->user, c->fraction, stage);
}

acd3_poll *acd_corise_poll_init(acd3_poll *p, acd_corise_poll_ctx *ctx, acd_progress_fn fn, void *user, double fraction,
                                const char *stage) {
    ctx->fn = fn;
    ctx->user = user;
    ctx->fraction = fraction;
    if (!fn) return NULL;
    *p = acd3_poll_make(poll_call, ctx, stage);
    return p;
}


static acd_status poll_cancelled(acd_error *err, const char *where) {
    return acd_fail(err, ACD_ERR_CANCELLED, "corise: cancelled by the progress callback %s", where);
}

/* One CoRiSe step on the submesh s: *nparts = 0 when s is final (no deep valley or flat hull),
 * else part[] holds the cut result. *maxc: the largest valley concavity of s (0 when its hull is
 * flat), as max_valley_concavity computes it. caller, fraction: step_progress's. */
static acd_status step(const acd_mesh *s, const acd_corise_params *prm, int caller, double fraction, acd3_poll *poll,
                       uint32_t *part, size_t *nparts, double *maxc, acd_corise_stats *stats, acd_error *err) {
    *nparts = 0;
    *maxc = 0;
    acd_edge_graph g;
    acd_corise_bridges b;
    acd_corise_ridges r;
    memset(&g, 0, sizeof g);
    memset(&b, 0, sizeof b);
    memset(&r, 0, sizeof r);
    uint32_t *ml = NULL;
    acd_status st = acd_edge_graph_from_mesh(s->vertices, s->nvertices, s->triangles, s->ntriangles, &g, err);
    if (st == ACD_OK) st = step_progress(prm, caller, fraction, err);
    if (st == ACD_OK && !caller && acd3_poll_stop(poll)) st = poll_cancelled(err, "before a part's valleys");
    acd3_poll_set_stage(poll, "corise: bridges");
    if (st == ACD_OK) st = acd_corise_bridges_compute_mt(s, &g, prm->clamp_hull_depth, prm->threads, poll, &b, err);
    if (st == ACD_OK) st = step_progress(prm, caller, fraction, err);
    if (st != ACD_OK) goto done;
    stats->fallbacks += b.fallbacks;
    stats->unreachable += b.unreachable;
    if (b.hull_dim < 3) goto done;
    int deep = 0;
    for (size_t i = 0; i < b.nbridges; i++)
        if (isfinite(b.bridge[i].length)) {
            if (b.bridge[i].concavity > prm->tau) deep = 1;
            if (b.bridge[i].concavity > *maxc) *maxc = b.bridge[i].concavity;
        }
    if (!deep) goto done;
    if ((st = acd_corise_ridges_compute(&b, prm->tau, &r, err)) != ACD_OK) goto done;
    if ((st = step_progress(prm, caller, fraction, err)) != ACD_OK) goto done;
    acd3_poll_set_stage(poll, "corise: regions");
    ml = malloc(s->ntriangles * sizeof *ml);
    if (!ml) {
        st = acd_fail(err, ACD_ERR_NOMEM, "corise: out of memory for %zu facets", s->ntriangles);
        goto done;
    }
    if ((st = acd_corise_regions_mt(s, &g, &b, &r, prm->tau, prm->threads, poll, ml, NULL, err)) != ACD_OK) goto done;
    if ((st = step_progress(prm, caller, fraction, err)) != ACD_OK) goto done;
    acd3_poll_set_stage(poll, "corise: cut");
    st = acd_corise_cut_poll(s, &b, &r, ml, &prm->cut, poll, part, nparts, err);
done:
    free(ml);
    acd_corise_ridges_free(&r);
    acd_corise_bridges_free(&b);
    acd_edge_graph_free(&g);
    return st;
}

/* The calling thread, waiting for the other threads' parts of a wave, sleeps ACD_CORISE_WAVE_POLL_MS
   ms at a time and calls the callback at once and then every ACD_CORISE_WAVE_POLL_EVERY sleeps (about
   every 8 ms). */
#define ACD_CORISE_WAVE_POLL_MS 1
#define ACD_CORISE_WAVE_POLL_EVERY 8

/* One part of a wave, processed on its own (any thread): extracted, capped, stepped. */
typedef struct part_work {
    acd_status st;
    acd_error err;
    uint32_t *cutpart; /* step's labels of the capped part's facets (the part's first) */
    size_t np;         /* pieces (0: final) */
    double maxc;       /* the part's largest valley concavity */
    size_t fallbacks, unreachable;
} part_work;

static void free_work(part_work *wk, size_t n) {
    if (!wk) return;
    for (size_t i = 0; i < n; i++) free(wk[i].cutpart);
    free(wk);
}

static void process_part(const acd_mesh *w, const part *cur, const edge_count *ge, size_t nge,
                         const acd_corise_params *prm, int caller, double fraction, acd3_poll *poll, uint32_t *map,
                         uint32_t *l2g, part_work *out) {
    acd_mesh sub, aug;
    out->st = ACD_OK;
    acd3_poll_set_stage(poll, "corise: extracting");
    if (acd3_poll_stop(poll)) {
        out->st = poll_cancelled(&out->err, "before a part");
        return;
    }
    if (!extract(w, cur->faces, cur->n, map, l2g, &sub)) {
        out->st = acd_fail(&out->err, ACD_ERR_NOMEM, "corise: out of memory extracting a part of %zu facets", cur->n);
        return;
    }
    int capped = !acd3_poll_stop(poll) && cap_cut_holes(&sub, l2g, ge, nge, &aug);
    acd_mesh_free(&sub);
    if (acd3_poll_stopped(poll)) {
        if (capped) acd_mesh_free(&aug);
        out->st = poll_cancelled(&out->err, "capping a part");
        return;
    }
    out->cutpart = capped ? malloc((aug.ntriangles ? aug.ntriangles : 1) * sizeof *out->cutpart) : NULL;
    if (!out->cutpart) {
        acd_mesh_free(&aug);
        out->st = acd_fail(&out->err, ACD_ERR_NOMEM, "corise: out of memory capping a part of %zu facets", cur->n);
        return;
    }
    acd_corise_stats st;
    memset(&st, 0, sizeof st);
    out->st = !acd3_poll_stop(poll) ? step(&aug, prm, caller, fraction, poll, out->cutpart, &out->np, &out->maxc, &st,
                                           &out->err)
                                    : poll_cancelled(&out->err, "before a part's step");
    out->fallbacks = st.fallbacks;
    out->unreachable = st.unreachable;
    acd_mesh_free(&aug);
}

typedef struct final_part {
    uint32_t first; /* smallest facet */
    size_t index;   /* in the final list */
} final_part;

static int cmp_final(const void *x, const void *y) {
    const final_part *p = x, *q = y;
    return (p->first > q->first) - (p->first < q->first);
}

acd_status acd_corise_segment(const acd_mesh *m, const acd_corise_params *params, uint32_t *labels,
                              acd_corise_stats *stats, acd_error *err) {
    return acd_corise_segment_ex(m, params, labels, NULL, stats, err);
}

acd_status acd_corise_segment_ex(const acd_mesh *m, const acd_corise_params *params, uint32_t *labels,
                                 double **part_conc, acd_corise_stats *stats, acd_error *err) {
    if (part_conc) *part_conc = NULL;
    if (!m || !labels) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "corise: NULL argument");
    acd_corise_params prm = params ? *params : acd_corise_default_params();
    acd_corise_stats local;
    acd_corise_stats *S = stats ? stats : &local;
    memset(S, 0, sizeof *S);
    if (!isfinite(prm.tau) || prm.tau < 0)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "corise: tau %g must be finite and >= 0", prm.tau);
    if (m->ntriangles == 0) return acd_fail(err, ACD_ERR_DEGENERATE, "corise: the mesh has no facets");
    if (m->ntriangles > UINT32_MAX / 3)
        return acd_fail(err, ACD_ERR_UNSUPPORTED, "corise: %zu facets exceed the supported size", m->ntriangles);
    for (size_t t = 0; t < 3 * m->ntriangles; t++)
        if (m->triangles[t] >= m->nvertices)
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "corise: triangle %zu uses vertex %u, but the mesh has %zu", t / 3,
                            m->triangles[t], m->nvertices);
    for (size_t i = 0; i < 3 * m->nvertices; i++)
        if (!isfinite(m->vertices[i]))
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "corise: vertex %zu has a non-finite coordinate", i / 3);
    /* normalised copy (A1) */
    acd_mesh w = *m;
    w.vertices = malloc(3 * (m->nvertices ? m->nvertices : 1) * sizeof *w.vertices);
    int nthreads = prm.threads;
#ifdef _OPENMP
    if (nthreads <= 0) nthreads = omp_get_num_procs();
#else
    nthreads = 1;
#endif
    if (nthreads < 1) nthreads = 1;
    prm.threads = nthreads;
    part_list q = {0};
    part_list fin = {0};
    uint32_t *all = malloc(m->ntriangles * sizeof *all);
    /* per-thread scratch of extract (vertex map, reset after each use; local-to-global ids) */
    uint32_t **maps = calloc((size_t)nthreads, sizeof *maps), **l2gs = calloc((size_t)nthreads, sizeof *l2gs);
    part_work *work = NULL;
    size_t nwork = 0;
    size_t nge = 0;
    edge_count *ge = NULL;
    acd_status st = ACD_OK;
    size_t done_faces = 0;
    acd_corise_poll_ctx pctx;
    acd3_poll poll_obj;
    acd3_poll *poll = acd_corise_poll_init(&poll_obj, &pctx, prm.progress, prm.progress_user, 0.0, "corise: preparing");
    if (!w.vertices || !all || !maps || !l2gs) goto nomem;
    for (int t = 0; t < nthreads; t++) {
        maps[t] = malloc((m->nvertices ? m->nvertices : 1) * sizeof **maps);
        l2gs[t] = malloc(3 * m->ntriangles * sizeof **l2gs);
        if (!maps[t] || !l2gs[t]) goto nomem;
        for (size_t v = 0; v < m->nvertices; v++) maps[t][v] = UINT32_MAX;
    }
    memcpy(w.vertices, m->vertices, 3 * m->nvertices * sizeof *w.vertices);
    S->scale = 1.0;
    if (prm.normalize) normalise(m, &w, &S->scale);
    if (acd3_poll_stop(poll)) goto cancelled;
    if (!(ge = global_edges(&w, &nge))) goto nomem;
    if (acd3_poll_stop(poll)) goto cancelled;
    for (size_t f = 0; f < m->ntriangles; f++) all[f] = (uint32_t)f;
    uint32_t *first = malloc(m->ntriangles * sizeof *first);
    if (!first) goto nomem;
    memcpy(first, all, m->ntriangles * sizeof *first);
    if (!push_components(&w, &q, first, m->ntriangles, 0)) goto nomem;
    /* Parts are processed in waves: every part waiting when a wave starts is extracted, capped and
       stepped independently (in parallel when there are several), then the results are taken in
       queue order exactly as one part at a time would: the same pieces pushed in the same order,
       the same final parts, statistics and progress calls, for any number of threads. The callback
       is called from the calling thread only: after each final part, at the start of each wave and,
       in a wave of one part (the root's above all), between the phases of its step. */
    while (q.head < q.n) {
        if (prm.progress && prm.progress(prm.progress_user, (double)done_faces / (double)m->ntriangles, "corise")) {
            st = acd_fail(err, ACD_ERR_CANCELLED, "corise: cancelled by the progress callback after %zu of %zu facets",
                          done_faces, m->ntriangles);
            goto done;
        }
        size_t b0 = q.head, b1 = q.n, nw = b1 - b0;
        pctx.fraction = (double)done_faces / (double)m->ntriangles;
        work = calloc(nw, sizeof *work);
        if (!work) goto nomem;
        nwork = nw;
        int nt = 1;
#ifdef _OPENMP
        size_t wave_faces = 0;
        for (size_t j = b0; j < b1; j++) wave_faces += q.p[j].n;
        if (nthreads > 1 && nw > 1 && wave_faces >= ACD_CORISE_PARALLEL_MIN_FACES)
            nt = nthreads < (int)nw ? nthreads : (int)nw;
#endif
        /* The parts are claimed one at a time from a counter by the team's threads (the calling
           thread among them); each part's result goes to its own slot, whoever processed it. Once
           none is left to claim, the calling thread keeps polling (ACD_CORISE_WAVE_POLL_MS sleeps,
           stage "corise: wave") until the other threads have finished theirs, so a long part on
           another thread does not leave the callback silent; a stop reaches them by the flag. */
        size_t next = 0, finished = 0;
#ifdef _OPENMP
#pragma omp parallel num_threads(nt) if (nt > 1)
#endif
        {
            int t = 0;
#ifdef _OPENMP
            t = omp_get_thread_num();
#endif
            for (;;) {
                size_t j;
#ifdef _OPENMP
#pragma omp atomic capture
#endif
                j = next++;
                if (j >= nw) break;
                process_part(&w, &q.p[b0 + j], ge, nge, &prm, nw == 1, (double)done_faces / (double)m->ntriangles,
                             poll, maps[t], l2gs[t], &work[j]);
#ifdef _OPENMP
#pragma omp atomic update
#endif
                finished++;
            }
            if (t == 0 && nt > 1 && poll) {
                acd3_poll_set_stage(poll, "corise: wave");
                for (unsigned k = 1;; k++) {
                    size_t f;
#ifdef _OPENMP
#pragma omp atomic read
#endif
                    f = finished;
                    if (f >= nw) break;
                    if ((k - 1) % ACD_CORISE_WAVE_POLL_EVERY == 0) acd3_poll_stop(poll);
                    thrd_sleep(&(struct timespec){.tv_nsec = ACD_CORISE_WAVE_POLL_MS * 1000000L}, NULL);
                }
            }
        }
        /* cancelled within the wave: no part of it is taken (and the callback is not called again) */
        if (acd3_poll_stopped(poll)) goto cancelled;
        for (size_t j = 0; j < nw; j++) {
            part cur = q.p[b0 + j];
            q.p[b0 + j].faces = NULL;
            q.head = b0 + j + 1;
            part_work *pw = &work[j];
            if (pw->st != ACD_OK) {
                st = pw->st;
                if (err) *err = pw->err;
                free(cur.faces);
                goto done;
            }
            S->fallbacks += pw->fallbacks;
            S->unreachable += pw->unreachable;
            uint32_t *cutpart = pw->cutpart;
            size_t np = pw->np;
            size_t real = 0; /* pieces holding facets of the part (not only caps) */
            for (uint32_t k = 0; k < np; k++) {
                size_t i = 0;
                while (i < cur.n && cutpart[i] != k) i++;
                real += i < cur.n;
            }
            if (np > 1 && real < 2) np = 1;
            if (np == 0 || np == 1 || cur.depth >= prm.max_depth) {
                if (np == 1 || (np > 1 && cur.depth >= prm.max_depth)) S->unresolved++;
                if (!push_part(&fin, cur.faces, cur.n, cur.depth)) {
                    free(cur.faces);
                    goto nomem;
                }
                fin.p[fin.n - 1].conc = pw->maxc;
                done_faces += cur.n;
                pctx.fraction = (double)done_faces / (double)m->ntriangles;
                if (prm.progress &&
                    prm.progress(prm.progress_user, (double)done_faces / (double)m->ntriangles, "corise")) {
                    st = acd_fail(err, ACD_ERR_CANCELLED,
                                  "corise: cancelled by the progress callback after %zu of %zu facets", done_faces,
                                  m->ntriangles);
                    goto done;
                }
                continue;
            }
            S->cuts++;
            if (cur.depth + 1 > S->depth) S->depth = cur.depth + 1;
            int ok = 1;
            acd3_poll_set_stage(poll, "corise: pieces");
            for (uint32_t k = 0; k < np && ok; k++) {
                if (acd3_poll_stop(poll)) {
                    free(cur.faces);
                    goto cancelled;
                }
                size_t cnt = 0;
                for (size_t i = 0; i < cur.n; i++) cnt += cutpart[i] == k;
                if (!cnt) continue;
                uint32_t *f = malloc(cnt * sizeof *f);
                if (!f) {
                    ok = 0;
                    break;
                }
                cnt = 0;
                for (size_t i = 0; i < cur.n; i++)
                    if (cutpart[i] == k) f[cnt++] = cur.faces[i];
                ok = push_components(&w, &q, f, cnt, cur.depth + 1);
            }
            free(cur.faces);
            if (!ok) goto nomem;
        }
        free_work(work, nwork);
        work = NULL;
        nwork = 0;
    }
    /* number the final parts by their smallest facet */
    final_part *fp = malloc((fin.n ? fin.n : 1) * sizeof *fp);
    if (!fp) goto nomem;
    for (size_t i = 0; i < fin.n; i++) {
        uint32_t mn = UINT32_MAX;
        for (size_t k = 0; k < fin.p[i].n; k++)
            if (fin.p[i].faces[k] < mn) mn = fin.p[i].faces[k];
        fp[i] = (final_part){mn, i};
    }
    qsort(fp, fin.n, sizeof *fp, cmp_final);
    double *pc = NULL;
    if (part_conc && !(pc = malloc((fin.n ? fin.n : 1) * sizeof *pc))) {
        free(fp);
        goto nomem;
    }
    for (size_t r = 0; r < fin.n; r++) {
        const part *p = &fin.p[fp[r].index];
        for (size_t k = 0; k < p->n; k++) labels[p->faces[k]] = (uint32_t)r;
        if (pc) pc[r] = p->conc;
    }
    if (part_conc) *part_conc = pc;
    free(fp);
    S->parts = fin.n;
    goto done;
cancelled:
    st = acd_fail(err, ACD_ERR_CANCELLED, "corise: cancelled by the progress callback after %zu of %zu facets",
                  done_faces, m->ntriangles);
    goto done;
nomem:
    st = acd_fail(err, ACD_ERR_NOMEM, "corise: out of memory segmenting %zu facets", m->ntriangles);
done:
    for (size_t i = q.head; i < q.n; i++) free(q.p[i].faces);
    for (size_t i = 0; i < fin.n; i++) free(fin.p[i].faces);
    free(q.p);
    free(fin.p);
    free(w.vertices);
    free_work(work, nwork);
    for (int t = 0; maps && l2gs && t < nthreads; t++) {
        free(maps[t]);
        free(l2gs[t]);
    }
    free(maps);
    free(l2gs);
    free(all);
    free(ge);
    return st;
}

/* Largest valley concavity of the (capped) submesh s, 0 when its hull is flat. */
static acd_status max_valley_concavity(const acd_mesh *s, int clamp, double *out, acd_error *err) {
    *out = 0;
    acd_edge_graph g;
    acd_corise_bridges b;
    memset(&g, 0, sizeof g);
    memset(&b, 0, sizeof b);
    acd_status st = acd_edge_graph_from_mesh(s->vertices, s->nvertices, s->triangles, s->ntriangles, &g, err);
    if (st == ACD_OK) st = acd_corise_bridges_compute_ex(s, &g, clamp, &b, err);
    if (st == ACD_OK && b.hull_dim >= 3)
        for (size_t i = 0; i < b.nbridges; i++)
            if (isfinite(b.bridge[i].length) && b.bridge[i].concavity > *out) *out = b.bridge[i].concavity;
    acd_corise_bridges_free(&b);
    acd_edge_graph_free(&g);
    return st;
}

acd_status acd_corise_parts_concavity(const acd_mesh *m, const acd_corise_params *params, const uint32_t *labels,
                                      size_t nparts, double *conc, acd_error *err) {
    if (!m || !labels || (nparts && !conc)) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "corise: NULL argument");
    acd_corise_params prm = params ? *params : acd_corise_default_params();
    if (m->ntriangles == 0) return acd_fail(err, ACD_ERR_DEGENERATE, "corise: the mesh has no facets");
    if (m->ntriangles > UINT32_MAX / 3)
        return acd_fail(err, ACD_ERR_UNSUPPORTED, "corise: %zu facets exceed the supported size", m->ntriangles);
    for (size_t t = 0; t < 3 * m->ntriangles; t++)
        if (m->triangles[t] >= m->nvertices)
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "corise: triangle %zu uses vertex %u, but the mesh has %zu", t / 3,
                            m->triangles[t], m->nvertices);
    for (size_t f = 0; f < m->ntriangles; f++)
        if (labels[f] >= nparts)
            return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "corise: face %zu has label %u, but there are %zu parts", f,
                            labels[f], nparts);
    for (size_t i = 0; i < 3 * m->nvertices; i++)
        if (!isfinite(m->vertices[i]))
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "corise: vertex %zu has a non-finite coordinate", i / 3);
    acd_mesh w = *m;
    w.vertices = malloc(3 * (m->nvertices ? m->nvertices : 1) * sizeof *w.vertices);
    uint32_t *map = malloc((m->nvertices ? m->nvertices : 1) * sizeof *map);
    uint32_t *faces = malloc(m->ntriangles * sizeof *faces);
    uint32_t *l2g = malloc(3 * m->ntriangles * sizeof *l2g);
    size_t nge = 0;
    edge_count *ge = NULL;
    acd_status st = ACD_OK;
    if (!w.vertices || !map || !faces || !l2g) goto nomem;
    memcpy(w.vertices, m->vertices, 3 * m->nvertices * sizeof *w.vertices);
    for (size_t v = 0; v < m->nvertices; v++) map[v] = UINT32_MAX;
    if (prm.normalize) normalise(m, &w, NULL);
    if (!(ge = global_edges(&w, &nge))) goto nomem;
    for (size_t k = 0; k < nparts && st == ACD_OK; k++) {
        size_t n = 0;
        for (size_t f = 0; f < m->ntriangles; f++)
            if (labels[f] == k) faces[n++] = (uint32_t)f;
        conc[k] = 0;
        if (!n) continue;
        acd_mesh sub, aug;
        if (!extract(&w, faces, n, map, l2g, &sub)) goto nomem;
        int capped = cap_cut_holes(&sub, l2g, ge, nge, &aug);
        acd_mesh_free(&sub);
        if (!capped) goto nomem;
        st = max_valley_concavity(&aug, prm.clamp_hull_depth, &conc[k], err);
        acd_mesh_free(&aug);
    }
    goto done;
nomem:
    st = acd_fail(err, ACD_ERR_NOMEM, "corise: out of memory measuring the parts of %zu facets", m->ntriangles);
done:
    free(w.vertices);
    free(map);
    free(faces);
    free(l2g);
    free(ge);
    return st;
}
