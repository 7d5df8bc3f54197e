/* acd3/patches: bridge patches by Alg. 6 + Lloyd (VSA) clustering; see patches.h. */
#include "acd3/patches.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/minheap.h"
#include "geom3/vec3.h"

/* Lloyd iterations: the first clustering runs up to 20 (spec §3.3); after a patch split only the
 * neighbourhood changes, and a few iterations settle it. After SPLIT_ROUNDS_MAX split rounds the
 * step-1 grouping (which meets the eps bound by construction: every facet within eps of its
 * seed facet's plane, a plane tangent to the hull) is used instead, bounding the time. */
enum { LLOYD_MAX_ITERATIONS = 20, LLOYD_SPLIT_ITERATIONS = 4, SPLIT_ROUNDS_MAX = 12 };

typedef struct facet_info {
    double n[3];
    double area;
} facet_info;

static void facet_infos(const acd_hull *h, facet_info *fi) {
    for (size_t f = 0; f < h->ntriangles; f++) {
        const double *a = h->vertices + 3 * h->triangles[3 * f];
        const double *b = h->vertices + 3 * h->triangles[3 * f + 1];
        const double *c = h->vertices + 3 * h->triangles[3 * f + 2];
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double cr[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        fi[f].area = 0.5 * sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
        /* the hull's plane normal is the reliable one (outward, unit) */
        for (int k = 0; k < 3; k++) fi[f].n[k] = h->planes[4 * f + k];
    }
}

/* Largest depth of facet f's vertices below the plane {N.x = hval}. */
static double facet_depth(const acd_hull *h, size_t f, const double N[3], double hval) {
    double worst = 0.0;
    for (int k = 0; k < 3; k++) {
        const double *x = h->vertices + 3 * h->triangles[3 * f + k];
        double d = hval - (N[0] * x[0] + N[1] * x[1] + N[2] * x[2]);
        if (d > worst) worst = d;
    }
    return worst;
}

/* Hull vertex adjacency (compressed rows), for support queries by hill climbing. */
typedef struct vadj {
    size_t *row;
    uint32_t *adj;
} vadj;

static int vadj_build(const acd_hull *h, vadj *va) {
    size_t nv = h->nvertices, nf = h->ntriangles;
    va->row = calloc(nv + 1, sizeof *va->row);
    va->adj = malloc((3 * nf + 1) * sizeof *va->adj);
    if (!va->row || !va->adj) return 0;
    /* each directed edge (t[i] -> t[i+1]) once: on a closed hull that lists every neighbour once */
    for (size_t f = 0; f < nf; f++)
        for (int k = 0; k < 3; k++) va->row[h->triangles[3 * f + k] + 1]++;
    for (size_t v = 0; v < nv; v++) va->row[v + 1] += va->row[v];
    size_t *fill = malloc((nv + 1) * sizeof *fill);
    if (!fill) return 0;
    memcpy(fill, va->row, (nv + 1) * sizeof *fill);
    for (size_t f = 0; f < nf; f++)
        for (int k = 0; k < 3; k++) va->adj[fill[h->triangles[3 * f + k]]++] = h->triangles[3 * f + (k + 1) % 3];
    free(fill);
    return 1;
}


/* max over hull vertices of N.v: a linear function's local maximum on a convex polytope's vertex
 * graph is global, so climb from `start`. */
static double support(const acd_hull *h, const vadj *va, uint32_t start, const double N[3]) {
    uint32_t v = start;
    double best = acd_dot3(N, h->vertices + 3 * (size_t)v);
    for (;;) {
        uint32_t next = v;
        for (size_t k = va->row[v]; k < va->row[v + 1]; k++) {
            uint32_t u = va->adj[k];
            double s = acd_dot3(N, h->vertices + 3 * (size_t)u);
            if (s > best) {
                best = s;
                next = u;
            }
        }
        if (next == v) return best;
        v = next;
    }
}

static double l21_error(const facet_info *fi, size_t f, const double N[3]) {
    double d0 = fi[f].n[0] - N[0], d1 = fi[f].n[1] - N[1], d2 = fi[f].n[2] - N[2];
    return fi[f].area * (d0 * d0 + d1 * d1 + d2 * d2);
}

/* One VSA partition: flood from the seeds. label[] gets the proxy of every facet. The queue holds
 * core/minheap items (key: the error, id: the facet, tie: the proxy), so equal errors pop by facet,
 * then proxy. */
/* An item that does not precede the best one already queued for its facet can never label it
 * (the facet takes its first pop): it is not queued, which leaves the partition unchanged (and
 * the queued items distinct, so they pop in one order whatever the queue's layout). */
static int flood_better(acd_minheap_item *best, acd_minheap_item it) {
    if (best[it.id].id != UINT32_MAX && !acd_minheap_less(it, best[it.id])) return 0;
    best[it.id] = it;
    return 1;
}

/* The least item a labelled facet adds waits outside the heap (have_next, the others are pushed):
 * the next item taken is it or the heap's top, whichever precedes (acd_minheap_pushpop, which
 * hands it back untouched when it precedes the top, as it often does inside a flat patch). The
 * queue thus gives up its least item every time, the same sequence as a plain heap's. */
static int flood(const acd_hull *h, const facet_info *fi, const double *N, const uint32_t *seeds, size_t k,
                 uint32_t *label, acd_minheap *hp, acd_minheap_item *best) {
    size_t nf = h->ntriangles;
    for (size_t f = 0; f < nf; f++) {
        label[f] = UINT32_MAX;
        best[f].id = UINT32_MAX;
    }
    hp->n = 0;
    size_t unlabelled = nf;
    for (size_t i = 0; i < k; i++) {
        unlabelled -= label[seeds[i]] == UINT32_MAX;
        label[seeds[i]] = (uint32_t)i;
    }
    for (size_t i = 0; i < k; i++) {
        uint32_t s = seeds[i];
        for (int e = 0; e < 3; e++) {
            uint32_t g = h->neighbors[3 * s + e];
            if (g < nf && label[g] == UINT32_MAX) {
                acd_minheap_item it = {l21_error(fi, g, N + 3 * i), g, (uint32_t)i};
                if (flood_better(best, it) && !acd_minheap_push_item(hp, it)) return 0;
            }
        }
    }
    acd_minheap_item next = {0, 0, 0};
    int have_next = 0;
    /* once every facet has its label, what is left queued is stale: not popped */
    while (unlabelled) {
        acd_minheap_item it;
        if (have_next) {
            it = acd_minheap_pushpop(hp, next);
            have_next = 0;
        } else if (hp->n) {
            it = acd_minheap_pop(hp);
        } else {
            break;
        }
        if (label[it.id] != UINT32_MAX) continue;
        label[it.id] = it.tie;
        unlabelled--;
        for (int e = 0; e < 3; e++) {
            uint32_t g = h->neighbors[3 * it.id + e];
            if (g >= nf || label[g] != UINT32_MAX) continue;
            acd_minheap_item x = {l21_error(fi, g, N + 3 * it.tie), g, it.tie};
            if (!flood_better(best, x)) continue;
            if (!acd_minheap_offer(hp, &next, &have_next, x)) return 0;
        }
    }
    return 1;
}

/* Fits proxies to the partition and re-picks seeds (the facet of least error in each region). */
static void fit(const acd_hull *h, const facet_info *fi, const uint32_t *label, size_t k, double *N, uint32_t *seeds) {
    size_t nf = h->ntriangles;
    double *acc = calloc(3 * k, sizeof *acc);
    if (!acc) return; /* keep the old proxies: still a valid (if less refined) clustering */
    for (size_t f = 0; f < nf; f++)
        for (int c = 0; c < 3; c++) acc[3 * label[f] + c] += fi[f].area * fi[f].n[c];
    for (size_t i = 0; i < k; i++) {
        double len = sqrt(acc[3 * i] * acc[3 * i] + acc[3 * i + 1] * acc[3 * i + 1] + acc[3 * i + 2] * acc[3 * i + 2]);
        if (len > 0)
            for (int c = 0; c < 3; c++) N[3 * i + c] = acc[3 * i + c] / len;
    }
    free(acc);
    double *best = malloc(k * sizeof *best);
    if (!best) return;
    for (size_t i = 0; i < k; i++) best[i] = INFINITY;
    for (size_t f = 0; f < nf; f++) {
        uint32_t i = label[f];
        double e = l21_error(fi, f, N + 3 * i);
        if (e < best[i]) {
            best[i] = e;
            seeds[i] = (uint32_t)f;
        }
    }
    free(best);
}

static int cmp_area_desc(const void *a, const void *b, const facet_info *fi) {
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    if (fi[x].area != fi[y].area) return fi[x].area > fi[y].area ? -1 : 1;
    return (x > y) - (x < y);
}

/* qsort has no context argument in C17: a small merge sort with one. */
static void sort_by_area(uint32_t *idx, uint32_t *tmp, size_t n, const facet_info *fi) {
    if (n < 2) return;
    size_t m = n / 2;
    sort_by_area(idx, tmp, m, fi);
    sort_by_area(idx + m, tmp, n - m, fi);
    size_t i = 0, j = m, k = 0;
    while (i < m && j < n) tmp[k++] = cmp_area_desc(&idx[j], &idx[i], fi) < 0 ? idx[j++] : idx[i++];
    while (i < m) tmp[k++] = idx[i++];
    while (j < n) tmp[k++] = idx[j++];
    memcpy(idx, tmp, n * sizeof *idx);
}

acd_status acd3_patches_build(const acd_hull *h, double eps, double tol, acd3_patches *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    if (h->dim != 3 || h->ntriangles == 0)
        return acd_fail(err, ACD_ERR_DEGENERATE, "bridge patches need a 3D hull (got dimension %d)", h->dim);
    size_t nf = h->ntriangles;
    facet_info *fi = malloc(nf * sizeof *fi);
    uint32_t *order = malloc(nf * sizeof *order), *tmp = malloc(nf * sizeof *tmp);
    uint32_t *label = malloc(nf * sizeof *label), *prev = malloc(nf * sizeof *prev);
    uint32_t *seeds = malloc(nf * sizeof *seeds), *queue = malloc(nf * sizeof *queue);
    double *N = malloc(3 * nf * sizeof *N), *prevN = malloc(3 * nf * sizeof *prevN);
    uint32_t *prev_seeds = malloc(nf * sizeof *prev_seeds);
    acd_minheap_item *fbest = malloc(nf * sizeof *fbest);
    acd_minheap hp = {0};
    vadj va = {0};
    uint32_t *label1 = NULL, *seeds1 = NULL; /* the step-1 grouping, kept as the fallback */
    double *N1 = NULL;
    acd_status st = ACD_OK;
    if (!vadj_build(h, &va) || !fi || !order || !tmp || !label || !prev || !seeds || !queue || !N || !fbest || !prevN || !prev_seeds) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory grouping %zu hull facets", nf);
        goto done;
    }
    facet_infos(h, fi);

    /* Step 1 (Alg. 6): greedy growth from the largest unassigned facet. */
    for (size_t f = 0; f < nf; f++) order[f] = (uint32_t)f;
    sort_by_area(order, tmp, nf, fi);
    for (size_t f = 0; f < nf; f++) label[f] = UINT32_MAX;
    size_t k = 0;
    for (size_t oi = 0; oi < nf; oi++) {
        uint32_t beta = order[oi];
        if (label[beta] != UINT32_MAX) continue;
        const double *bn = fi[beta].n;
        double bh = -h->planes[4 * beta + 3]; /* n.x + d = 0  ->  n.x = -d */
        seeds[k] = beta;
        memcpy(N + 3 * k, bn, sizeof(double[3]));
        size_t qh = 0, qt = 0;
        queue[qt++] = beta;
        label[beta] = (uint32_t)k;
        while (qh < qt) {
            uint32_t f = queue[qh++];
            for (int e = 0; e < 3; e++) {
                uint32_t g = h->neighbors[3 * f + e];
                if (g >= nf || label[g] != UINT32_MAX) continue;
                if (facet_depth(h, g, bn, bh) <= eps + tol) {
                    label[g] = (uint32_t)k;
                    queue[qt++] = g;
                }
            }
        }
        k++;
    }

    /* Step 2: Lloyd iterations, then split patches that break the eps bound, until none does. */
    /* keep the step-1 grouping as the fallback */
    size_t k1 = k;
    label1 = malloc(nf * sizeof *label1);
    seeds1 = malloc(k * sizeof *seeds1);
    N1 = malloc(3 * k * sizeof *N1);
    if (!label1 || !seeds1 || !N1) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory in bridge clustering");
        goto done;
    }
    memcpy(label1, label, nf * sizeof *label);
    memcpy(seeds1, seeds, k * sizeof *seeds);
    memcpy(N1, N, 3 * k * sizeof *N);
    for (int round = 0;; round++) {
        if (round == SPLIT_ROUNDS_MAX) {
            k = k1;
            memcpy(label, label1, nf * sizeof *label);
            memcpy(seeds, seeds1, k * sizeof *seeds);
            memcpy(N, N1, 3 * k * sizeof *N);
            break;
        }
        int iters = round == 0 ? LLOYD_MAX_ITERATIONS : LLOYD_SPLIT_ITERATIONS;
        for (int it = 0; it < iters; it++) {
            memcpy(prev, label, nf * sizeof *label);
            if (!flood(h, fi, N, seeds, k, label, &hp, fbest)) {
                st = acd_fail(err, ACD_ERR_NOMEM, "out of memory in bridge clustering");
                goto done;
            }
            memcpy(prevN, N, 3 * k * sizeof *N);
            memcpy(prev_seeds, seeds, k * sizeof *seeds);
            fit(h, fi, label, k, N, seeds);
            if (it > 0 && !memcmp(prev, label, nf * sizeof *label)) break;
            /* the fit left the proxies as they were: the next flood would repeat this partition
             * (and stop the loop with this state), so it is not run */
            if (!memcmp(prevN, N, 3 * k * sizeof *N) && !memcmp(prev_seeds, seeds, k * sizeof *seeds)) break;
        }
        /* worst facet of each patch against its tangent plane */
        size_t added = 0, k0 = k;
        double *worst = malloc(k0 * sizeof *worst);
        uint32_t *worst_f = malloc(k0 * sizeof *worst_f);
        double *hv = malloc(k0 * sizeof *hv);
        if (!worst || !worst_f || !hv) {
            free(worst), free(worst_f), free(hv);
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory in bridge clustering");
            goto done;
        }
        for (size_t i = 0; i < k0; i++) {
            worst[i] = 0;
            worst_f[i] = UINT32_MAX;
            hv[i] = support(h, &va, h->triangles[3 * (size_t)seeds[i]], N + 3 * i);
        }
        /* A patch that breaks the bound gets a new proxy at its deepest facet other than its seed
         * (a patch of one facet never breaks it: its own tangent plane has depth 0). */
        uint8_t *violates = calloc(k0, 1);
        if (!violates) {
            free(worst), free(worst_f), free(hv);
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory in bridge clustering");
            goto done;
        }
        for (size_t f = 0; f < nf; f++) {
            uint32_t i = label[f];
            double d = facet_depth(h, f, N + 3 * i, hv[i]);
            if (d > eps + tol) violates[i] = 1;
            if (f != seeds[i] && (worst_f[i] == UINT32_MAX || d > worst[i])) {
                worst[i] = d;
                worst_f[i] = (uint32_t)f;
            }
        }
        for (size_t i = 0; i < k0; i++) {
            if (!violates[i] || worst_f[i] == UINT32_MAX) continue;
            uint32_t f = worst_f[i];
            seeds[k] = f;
            memcpy(N + 3 * k, fi[f].n, sizeof(double[3]));
            k++;
            added++;
        }
        free(violates);
        free(worst), free(worst_f), free(hv);
        if (!added) break;
    }

    out->npatches = k;
    out->facet_patch = label;
    label = NULL;
    out->planes = malloc(4 * k * sizeof *out->planes);
    out->seed = malloc(k * sizeof *out->seed);
    if (!out->planes || !out->seed) {
        acd3_patches_free(out);
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory in bridge clustering");
        goto done;
    }
    for (size_t i = 0; i < k; i++) {
        memcpy(out->planes + 4 * i, N + 3 * i, sizeof(double[3]));
        out->planes[4 * i + 3] = support(h, &va, h->triangles[3 * (size_t)seeds[i]], N + 3 * i);
        out->seed[i] = seeds[i];
    }
done:
    free(fi), free(order), free(tmp), free(label), free(prev), free(seeds), free(queue), free(N), free(fbest);
    acd_minheap_free(&hp);
    free(prevN), free(prev_seeds);
    free(va.row), free(va.adj);
    free(label1), free(seeds1), free(N1);
    return st;
}

void acd3_patches_free(acd3_patches *p) {
    if (!p) return;
    free(p->facet_patch);
    free(p->planes);
    free(p->seed);
    memset(p, 0, sizeof *p);
}
