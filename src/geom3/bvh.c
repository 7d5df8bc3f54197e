/* geom3/bvh: bounding-volume hierarchy over a triangle mesh.
 *
 * Binned SAH build after I. Wald, "On fast construction of SAH-based bounding volume
 * hierarchies" (IEEE RT 2007, sec. 3: 16 bins over the centroid bounds, cost = area * count);
 * closest point on a triangle after C. Ericson, "Real-Time Collision Detection" (2005, sec.
 * 5.1.5); ray/triangle after Moller and Trumbore (JGT 1997). */
#include "geom3/bvh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "core/error.h"
#include "geom3/vec3.h"

#define BVH_BINS 16
#define BVH_STACK 128 /* depth bound: the SAH/median split always separates, depth < 64 in practice */

static const double *vtx(const acd_bvh *b, uint32_t i) { return b->vertices + 3 * (size_t)i; }

static inline double min2(double a, double b) { return a < b ? a : b; }
static inline double max2(double a, double b) { return a > b ? a : b; }

static void tri_box(const acd_bvh *b, uint32_t t, double lo[3], double hi[3]) {
    const uint32_t *tr = b->triangles + 3 * (size_t)t;
    for (int k = 0; k < 3; k++) {
        double x = b->vertices[3 * (size_t)tr[0] + k], y = b->vertices[3 * (size_t)tr[1] + k],
               z = b->vertices[3 * (size_t)tr[2] + k];
        lo[k] = min2(x, min2(y, z));
        hi[k] = max2(x, max2(y, z));
    }
}

static double box_area(const double lo[3], const double hi[3]) {
    double dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    if (dx < 0) return 0;
    return dx * dy + dy * dz + dz * dx;
}

static void box_empty(double lo[3], double hi[3]) {
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
}

/* (stored unconditionally: a conditional store was a branch, mispredicted about half the time; the
 * same selection, min/max instructions) */
static inline void box_grow(double lo[3], double hi[3], const double l2[3], const double h2[3]) {
#ifdef __SSE2__
    /* two coordinates at a time: minpd / maxpd return their second operand unless the first is
     * less / greater (NaN, equal or signed zeros alike), as the expressions below (the same bits) */
    _mm_storeu_pd(lo, _mm_min_pd(_mm_loadu_pd(l2), _mm_loadu_pd(lo)));
    _mm_store_sd(lo + 2, _mm_min_sd(_mm_load_sd(l2 + 2), _mm_load_sd(lo + 2)));
    _mm_storeu_pd(hi, _mm_max_pd(_mm_loadu_pd(h2), _mm_loadu_pd(hi)));
    _mm_store_sd(hi + 2, _mm_max_sd(_mm_load_sd(h2 + 2), _mm_load_sd(hi + 2)));
#else
    for (int k = 0; k < 3; k++) {
        lo[k] = l2[k] < lo[k] ? l2[k] : lo[k];
        hi[k] = h2[k] > hi[k] ? h2[k] : hi[k];
    }
#endif
}

static const double *tbox_sorted(const acd_bvh *b, size_t i) { return b->boxes + 6 * i; }

/* One triangle during the build: its box, its box's centre and its index. The items are permuted
 * in place (the order the tree ends with), so every pass over a node's triangles reads them in
 * sequence. */
typedef struct bvh_item {
    double lo[3], hi[3], c[3];
    uint32_t t;
} bvh_item;

typedef struct build_item {
    uint32_t node;
    uint32_t start, end;
    uint32_t depth;
    double clo[3], chi[3]; /* the bounds of the node's centroids (its box is in the node) */
} build_item;

/* Below this depth SAH chooses the split; deeper, the median split bounds the depth by
 * BVH_SAH_DEPTH + log2(n) whatever the distribution of the triangles. */
#define BVH_SAH_DEPTH 48

static void item_swap(bvh_item *a, bvh_item *b) {
    bvh_item x = *a;
    *a = *b;
    *b = x;
}

/* A node's box and the bounds of its triangles' centroids. */
typedef struct node_bounds {
    double lo[3], hi[3], clo[3], chi[3];
} node_bounds;

static void bounds_empty(node_bounds *b) {
    box_empty(b->lo, b->hi);
    box_empty(b->clo, b->chi);
}

static void bounds_add(node_bounds *b, const bvh_item *x) {
    box_grow(b->lo, b->hi, x->lo, x->hi);
    box_grow(b->clo, b->chi, x->c, x->c);
}

/* Partitions it[start, end) by the split; returns the first index of the right half. The bounds of
 * both halves are gathered on the way (each item is classified once; min and max do not depend on
 * the order: range_bounds' values). */
static uint32_t partition_bounds(bvh_item *it, uint32_t start, uint32_t end, int axis, double split, node_bounds *l,
                                 node_bounds *r) {
    uint32_t i = start, j = end;
    bounds_empty(l);
    bounds_empty(r);
    while (i < j) {
        if (it[i].c[axis] < split) {
            bounds_add(l, &it[i]);
            i++;
        } else {
            j--;
            item_swap(&it[i], &it[j]);
            bounds_add(r, &it[j]);
        }
    }
    return i;
}

static int cmp_item_t(const void *a, const void *b) {
    uint32_t x = ((const bvh_item *)a)->t, y = ((const bvh_item *)b)->t;
    return (x > y) - (x < y);
}

/* (centroid[axis], index) order: a strict total order, so the split is deterministic. */
static int cent_less(int axis, const bvh_item *a, const bvh_item *b) {
    double ka = a->c[axis], kb = b->c[axis];
    return ka < kb || (ka == kb && a->t < b->t);
}

/* Puts the element of rank k (within [start, end)) at position k, smaller ones before it,
 * larger after (quickselect with a median-of-three pivot). */
static void median_split(bvh_item *it, uint32_t start, uint32_t end, int axis, uint32_t k) {
    uint32_t lo = start, hi = end - 1;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        const bvh_item *a = &it[lo], *b = &it[mid], *c = &it[hi];
        bvh_item piv;
        if (cent_less(axis, a, b)) piv = cent_less(axis, b, c) ? *b : (cent_less(axis, a, c) ? *c : *a);
        else piv = cent_less(axis, a, c) ? *a : (cent_less(axis, b, c) ? *c : *b);
        uint32_t i = lo, j = hi;
        while (i <= j) {
            while (cent_less(axis, &it[i], &piv)) i++;
            while (cent_less(axis, &piv, &it[j])) j--;
            if (i <= j) {
                item_swap(&it[i], &it[j]);
                i++;
                if (j == 0) break;
                j--;
            }
        }
        if (k <= j) hi = j;
        else if (k >= i) lo = i;
        else break;
    }
}

/* The box of it[start, end) and the bounds of their centroids. */
static void range_bounds(const bvh_item *it, uint32_t start, uint32_t end, double lo[3], double hi[3], double clo[3],
                         double chi[3]) {
    box_empty(lo, hi);
    box_empty(clo, chi);
    for (uint32_t i = start; i < end; i++) {
        box_grow(lo, hi, it[i].lo, it[i].hi);
        box_grow(clo, chi, it[i].c, it[i].c);
    }
}

/* One step of the build: node nd (its box set) of item it is made a leaf (returns 0: first and count
 * set) or split (returns 1: the halves' items l and r, their node field unset, and their boxes into
 * ln and rn; nd's first and count are the caller's). The items of it are permuted in place. */
static int split_step(bvh_item *items, acd_bvh_node *nd, const build_item *itp, build_item *lp, build_item *rp,
                      acd_bvh_node *ln, acd_bvh_node *rn) {
    const build_item it = *itp;
    const double *clo = it.clo, *chi = it.chi;
    uint32_t n = it.end - it.start;
    if (n <= 2) {
        nd->first = it.start;
        nd->count = n;
        return 0;
    }
    /* binned SAH over the three axes (the bins of all three filled in one pass) */
    int best_axis = -1;
    double best_cost = INFINITY, best_split = 0;
    double blo[3][BVH_BINS][3], bhi[3][BVH_BINS][3], scale[3];
    uint32_t bcnt[3][BVH_BINS];
    int active[3], nactive = 0;
    for (int ax = 0; ax < 3; ax++) {
        double ext = chi[ax] - clo[ax];
        active[ax] = 0;
        if (!(ext > 0) || it.depth >= BVH_SAH_DEPTH) continue;
        scale[ax] = BVH_BINS / ext;
        if (!isfinite(scale[ax])) continue; /* a subnormal extent: no binning on this axis */
        active[ax] = 1;
        nactive++;
        for (int b = 0; b < BVH_BINS; b++) {
            box_empty(blo[ax][b], bhi[ax][b]);
            bcnt[ax][b] = 0;
        }
    }
    if (nactive > 0)
        for (uint32_t i = it.start; i < it.end; i++) {
            const bvh_item *x = &items[i];
            for (int ax = 0; ax < 3; ax++) {
                if (!active[ax]) continue;
                /* clamp in floating point before converting (NaN and overflow go to a bin too) */
                double fb = (x->c[ax] - clo[ax]) * scale[ax];
                int b = fb >= BVH_BINS ? BVH_BINS - 1 : fb > 0 ? (int)fb : 0;
                bcnt[ax][b]++;
                box_grow(blo[ax][b], bhi[ax][b], x->lo, x->hi);
            }
        }
    for (int ax = 0; ax < 3; ax++) {
        if (!active[ax]) continue;
        double rarea[BVH_BINS];
        uint32_t rcnt[BVH_BINS];
        double lo[3], hi[3];
        box_empty(lo, hi);
        uint32_t c = 0;
        for (int b = BVH_BINS - 1; b > 0; b--) {
            box_grow(lo, hi, blo[ax][b], bhi[ax][b]);
            c += bcnt[ax][b];
            rarea[b] = box_area(lo, hi);
            rcnt[b] = c;
        }
        box_empty(lo, hi);
        c = 0;
        for (int b = 0; b < BVH_BINS - 1; b++) {
            box_grow(lo, hi, blo[ax][b], bhi[ax][b]);
            c += bcnt[ax][b];
            if (c == 0 || rcnt[b + 1] == 0) continue;
            double cost = box_area(lo, hi) * c + rarea[b + 1] * rcnt[b + 1];
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = ax;
                best_split = clo[ax] + (b + 1) / scale[ax];
            }
        }
    }
    uint32_t mid;
    int have_bounds = 0;
    node_bounds lb, rb;
    if (best_axis >= 0) {
        double leaf_cost = box_area(nd->lo, nd->hi) * n;
        if (n <= ACD_BVH_LEAF_MAX && leaf_cost <= best_cost + 0.5 * box_area(nd->lo, nd->hi)) {
            nd->first = it.start;
            nd->count = n;
            return 0;
        }
        mid = partition_bounds(items, it.start, it.end, best_axis, best_split, &lb, &rb);
        have_bounds = 1;
        if (mid == it.start || mid == it.end) { /* rounding at the bin edge: fall back */
            have_bounds = 0;
            mid = it.start + n / 2;
            median_split(items, it.start, it.end, best_axis, mid);
        }
    } else if (it.depth >= BVH_SAH_DEPTH && n > ACD_BVH_LEAF_MAX) {
        int ax = 0;
        for (int k = 1; k < 3; k++)
            if (chi[k] - clo[k] > chi[ax] - clo[ax]) ax = k;
        mid = it.start + n / 2;
        median_split(items, it.start, it.end, ax, mid);
    } else {
        /* all centroids coincide: split the index range in half (sorted for determinism) */
        if (n <= ACD_BVH_LEAF_MAX) {
            nd->first = it.start;
            nd->count = n;
            return 0;
        }
        qsort(items + it.start, n, sizeof *items, cmp_item_t);
        mid = it.start + n / 2;
    }
    /* the children's boxes and centroid bounds */
    build_item r = {0, mid, it.end, it.depth + 1, {0, 0, 0}, {0, 0, 0}};
    build_item l = {0, it.start, mid, it.depth + 1, {0, 0, 0}, {0, 0, 0}};
    if (have_bounds) {
        memcpy(rn->lo, rb.lo, sizeof rb.lo);
        memcpy(rn->hi, rb.hi, sizeof rb.hi);
        memcpy(r.clo, rb.clo, sizeof rb.clo);
        memcpy(r.chi, rb.chi, sizeof rb.chi);
        memcpy(ln->lo, lb.lo, sizeof lb.lo);
        memcpy(ln->hi, lb.hi, sizeof lb.hi);
        memcpy(l.clo, lb.clo, sizeof lb.clo);
        memcpy(l.chi, lb.chi, sizeof lb.chi);
    } else {
        range_bounds(items, mid, it.end, rn->lo, rn->hi, r.clo, r.chi);
        range_bounds(items, it.start, mid, ln->lo, ln->hi, l.clo, l.chi);
    }
    *lp = l;
    *rp = r;
    return 1;
}

/* Builds the subtree of item root (its node's box set, in nodes[root.node]) in nodes, new nodes
 * numbered from nnodes on, children after their parent, the left subtree before the right; returns
 * the node count. */
static size_t build_loop(bvh_item *items, acd_bvh_node *nodes, build_item *stack, build_item root, size_t nnodes) {
    size_t sp = 0;
    stack[sp++] = root;
    while (sp > 0) {
        build_item it = stack[--sp], l, r;
        acd_bvh_node *nd = &nodes[it.node];
        uint32_t left = (uint32_t)nnodes;
        if (!split_step(items, nd, &it, &l, &r, &nodes[left], &nodes[left + 1])) continue;
        nnodes += 2;
        nd->first = left;
        nd->count = 0;
        l.node = left;
        r.node = left + 1;
        /* push right first so the left subtree is built (and numbered) first */
        stack[sp++] = r;
        stack[sp++] = l;
    }
    return nnodes;
}

/* A subtree built apart (acd_bvh_build_threads): its root split here into two such subtrees (split,
 * kid), or built whole by build_loop into nodes[0 .. nnodes) (nodes[0] its root, the rest numbered
 * from 1 on as build_loop numbers them). */
typedef struct bvh_sub {
    build_item it;
    acd_bvh_node root; /* its box; its leaf fields when a leaf */
    int split;
    struct bvh_sub *kid; /* [2] when split */
    acd_bvh_node *nodes;
    size_t nnodes;
} bvh_sub;

/* Builds subtree s: split in two tasks while it has at least par_min triangles, else whole. Sets
 * *fail out of memory. */
static void sub_build(bvh_item *items, bvh_sub *s, uint32_t par_min, int *fail) {
    uint32_t n = s->it.end - s->it.start;
    if (n >= par_min) {
        build_item l, r;
        acd_bvh_node ln, rn;
        if (!split_step(items, &s->root, &s->it, &l, &r, &ln, &rn)) return; /* a leaf (split 0, no nodes) */
        s->kid = calloc(2, sizeof *s->kid);
        if (!s->kid) {
#ifdef _OPENMP
#pragma omp atomic write
#endif
            *fail = 1;
            return;
        }
        s->split = 1;
        s->kid[0].it = l;
        s->kid[0].root = ln;
        s->kid[1].it = r;
        s->kid[1].root = rn;
        bvh_sub *k0 = &s->kid[0], *k1 = &s->kid[1];
#ifdef _OPENMP
#pragma omp task default(none) firstprivate(items, k1, par_min, fail)
#endif
        sub_build(items, k1, par_min, fail);
        sub_build(items, k0, par_min, fail);
#ifdef _OPENMP
#pragma omp taskwait
#endif
        return;
    }
    size_t cap = 2 * (size_t)n;
    s->nodes = malloc(cap * sizeof *s->nodes);
    build_item *stack = malloc(cap * sizeof *stack);
    if (!s->nodes || !stack) {
        free(stack);
#ifdef _OPENMP
#pragma omp atomic write
#endif
        *fail = 1;
        return;
    }
    s->nodes[0] = s->root;
    build_item root = s->it;
    root.node = 0;
    s->nnodes = build_loop(items, s->nodes, stack, root, 1);
    free(stack);
}

/* Copies subtree s into out with the numbering of the sequential build: its root at gi, its new
 * nodes from *next on. */
static void sub_place(const bvh_sub *s, acd_bvh_node *out, size_t gi, size_t *next) {
    if (s->split) {
        size_t left = *next;
        *next += 2;
        out[gi] = s->root;
        out[gi].first = (uint32_t)left;
        out[gi].count = 0;
        sub_place(&s->kid[0], out, left, next);
        sub_place(&s->kid[1], out, left + 1, next);
        return;
    }
    if (!s->nodes) { /* a leaf split_step made */
        out[gi] = s->root;
        return;
    }
    /* local node k >= 1 is node base + k - 1 */
    size_t base = *next;
    for (size_t k = 0; k < s->nnodes; k++) {
        acd_bvh_node nd = s->nodes[k];
        if (nd.count == 0) nd.first = (uint32_t)(base + nd.first - 1);
        out[k ? base + k - 1 : gi] = nd;
    }
    *next += s->nnodes - 1;
}

static void sub_free(bvh_sub *s) {
    if (s->kid) {
        sub_free(&s->kid[0]);
        sub_free(&s->kid[1]);
        free(s->kid);
    }
    free(s->nodes);
}

/* Below this many triangles the build is sequential; subtrees of fewer than (the larger of) this
 * and 1/8 of the triangles are built whole by one task. */
#define BVH_PAR_MIN 4096

acd_status acd_bvh_build(acd_bvh *bvh, const double *vertices, size_t nvertices, const uint32_t *triangles,
                         size_t ntriangles, acd_error *err) {
    return acd_bvh_build_threads(bvh, vertices, nvertices, triangles, ntriangles, 1, err);
}

acd_status acd_bvh_build_threads(acd_bvh *bvh, const double *vertices, size_t nvertices, const uint32_t *triangles,
                                 size_t ntriangles, int threads, acd_error *err) {
    memset(bvh, 0, sizeof *bvh);
    if (ntriangles > 0 && (!vertices || !triangles))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "bvh: NULL vertex or triangle array");
    if (ntriangles >= UINT32_MAX / 2)
        return acd_fail(err, ACD_ERR_INVALID_INPUT, "bvh: too many triangles (%zu)", ntriangles);
    bvh->vertices = vertices;
    bvh->nvertices = nvertices;
    bvh->triangles = triangles;
    bvh->ntriangles = ntriangles;
    if (ntriangles == 0) return ACD_OK;
    for (size_t t = 0; t < ntriangles; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t v = triangles[3 * t + k];
            if (v >= nvertices)
                return acd_fail(err, ACD_ERR_INVALID_INPUT,
                                "bvh: triangle %zu refers to vertex %u, but there are %zu vertices", t, v,
                                nvertices);
            const double *p = vertices + 3 * (size_t)v;
            if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
                return acd_fail(err, ACD_ERR_INVALID_INPUT,
                                "bvh: triangle %zu uses vertex %u with a non-finite coordinate (%g %g %g)", t, v,
                                p[0], p[1], p[2]);
        }
    size_t maxnodes = 2 * ntriangles;
    bvh->nodes = malloc(maxnodes * sizeof *bvh->nodes);
    bvh->order = malloc(ntriangles * sizeof *bvh->order);
    bvh->boxes = malloc(ntriangles * 6 * sizeof(double));
    bvh_item *items = malloc(ntriangles * sizeof *items);
    const int par = threads > 1 && ntriangles >= BVH_PAR_MIN;
    build_item *stack = par ? NULL : malloc(maxnodes * sizeof *stack);
    if (!bvh->nodes || !bvh->order || !bvh->boxes || !items || (!par && !stack)) goto nomem;
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(threads) if (par)
#endif
    for (long lt = 0; lt < (long)ntriangles; lt++) {
        uint32_t t = (uint32_t)lt;
        bvh_item *x = &items[t];
        tri_box(bvh, t, x->lo, x->hi);
        for (int k = 0; k < 3; k++) x->c[k] = 0.5 * (x->lo[k] + x->hi[k]);
        x->t = t;
    }
    build_item root = {0, 0, (uint32_t)ntriangles, 0, {0, 0, 0}, {0, 0, 0}};
    range_bounds(items, 0, (uint32_t)ntriangles, bvh->nodes[0].lo, bvh->nodes[0].hi, root.clo, root.chi);
    if (!par) {
        bvh->nnodes = build_loop(items, bvh->nodes, stack, root, 1);
        free(stack);
    } else {
        /* the same splits, subtrees in parallel tasks, then numbered as the sequential build does */
        bvh_sub top;
        memset(&top, 0, sizeof top);
        top.it = root;
        top.root = bvh->nodes[0];
        uint32_t par_min = (uint32_t)(ntriangles / 8);
        if (par_min < BVH_PAR_MIN) par_min = BVH_PAR_MIN;
        int fail = 0;
#ifdef _OPENMP
#pragma omp parallel num_threads(threads)
#pragma omp single
#endif
        sub_build(items, &top, par_min, &fail);
        if (!fail) {
            size_t next = 1;
            sub_place(&top, bvh->nodes, 0, &next);
            bvh->nnodes = next;
        }
        sub_free(&top);
        if (fail) goto nomem;
    }
    /* triangles and their boxes in leaf order, for the queries */
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(threads) if (par)
#endif
    for (long li = 0; li < (long)ntriangles; li++) {
        size_t i = (size_t)li;
        bvh->order[i] = items[i].t;
        memcpy(bvh->boxes + 6 * i, items[i].lo, 3 * sizeof(double));
        memcpy(bvh->boxes + 6 * i + 3, items[i].hi, 3 * sizeof(double));
    }
    free(items);
    return ACD_OK;
nomem: /* stack: NULL, or not freed yet (the sequential build frees it and cannot fail) */
    free(items);
    free(stack);
    acd_bvh_free(bvh);
    return acd_fail(err, ACD_ERR_NOMEM, "bvh: out of memory for %zu triangles", ntriangles);
}

int acd_bvh_is_over(const acd_bvh *bvh, const double *vertices, size_t nvertices, const uint32_t *triangles,
                    size_t ntriangles) {
    return bvh && bvh->vertices == vertices && bvh->nvertices == nvertices && bvh->triangles == triangles &&
           bvh->ntriangles == ntriangles && (bvh->nnodes > 0) == (ntriangles > 0);
}

void acd_bvh_free(acd_bvh *bvh) {
    if (!bvh) return;
    free(bvh->nodes);
    free(bvh->order);
    free(bvh->boxes);
    memset(bvh, 0, sizeof *bvh);
}

/* ---- closest point ---- */

static void sub3(double r[3], const double a[3], const double b[3]) {
    r[0] = a[0] - b[0];
    r[1] = a[1] - b[1];
    r[2] = a[2] - b[2];
}
static double dist2(const double a[3], const double b[3]) {
    double d[3];
    sub3(d, a, b);
    return acd_dot3(d, d);
}

static double closest_segment(const double p[3], const double a[3], const double b[3], double q[3]) {
    double ab[3], ap[3];
    sub3(ab, b, a);
    sub3(ap, p, a);
    double l2 = acd_dot3(ab, ab), t = 0;
    if (l2 > 0) {
        t = acd_dot3(ap, ab) / l2;
        if (t < 0) t = 0;
        if (t > 1) t = 1;
    }
    for (int k = 0; k < 3; k++) q[k] = a[k] + t * ab[k];
    return dist2(p, q);
}

double acd_closest_point_triangle(const double p[3], const double a[3], const double b[3], const double c[3],
                                  double q[3]) {
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    sub3(ab, b, a);
    sub3(ac, c, a);
    sub3(ap, p, a);
    double d1 = acd_dot3(ab, ap), d2 = acd_dot3(ac, ap);
    if (d1 <= 0 && d2 <= 0) {
        memcpy(q, a, 3 * sizeof(double));
        return dist2(p, q);
    }
    sub3(bp, p, b);
    double d3 = acd_dot3(ab, bp), d4 = acd_dot3(ac, bp);
    if (d3 >= 0 && d4 <= d3) {
        memcpy(q, b, 3 * sizeof(double));
        return dist2(p, q);
    }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) {
        double v = d1 / (d1 - d3);
        for (int k = 0; k < 3; k++) q[k] = a[k] + v * ab[k];
        return dist2(p, q);
    }
    sub3(cp, p, c);
    double d5 = acd_dot3(ab, cp), d6 = acd_dot3(ac, cp);
    if (d6 >= 0 && d5 <= d6) {
        memcpy(q, c, 3 * sizeof(double));
        return dist2(p, q);
    }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) {
        double w = d2 / (d2 - d6);
        for (int k = 0; k < 3; k++) q[k] = a[k] + w * ac[k];
        return dist2(p, q);
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0 && (d4 - d3) + (d5 - d6) > 0) {
        double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        for (int k = 0; k < 3; k++) q[k] = b[k] + w * (c[k] - b[k]);
        return dist2(p, q);
    }
    double den = va + vb + vc;
    if (den > 0 && va >= 0 && vb >= 0 && vc >= 0) {
        double v = vb / den, w = vc / den;
        for (int k = 0; k < 3; k++) q[k] = a[k] + ab[k] * v + ac[k] * w;
        return dist2(p, q);
    }
    /* degenerate (collinear or repeated vertices) or rounding: best of the three edges */
    double q2[3], best = closest_segment(p, a, b, q);
    double d = closest_segment(p, b, c, q2);
    if (d < best) {
        best = d;
        memcpy(q, q2, sizeof q2);
    }
    d = closest_segment(p, c, a, q2);
    if (d < best) {
        best = d;
        memcpy(q, q2, sizeof q2);
    }
    return best;
}

/* The gap along axis k between p and the box [lo, hi] (lo <= hi): lo - p below it, p - hi above
 * it, else 0 (the larger of the two differences when positive: the same values, without branches). */
static inline double axis_gap(double p, double lo, double hi) {
    double a = lo - p, b = p - hi;
    double e = a > b ? a : b;
    return e > 0 ? e : 0;
}

static double box_dist2(const acd_bvh_node *n, const double p[3]) {
    double d = 0;
    for (int k = 0; k < 3; k++) {
        double e = axis_gap(p[k], n->lo[k], n->hi[k]);
        d += e * e;
    }
    return d;
}

int acd_bvh_closest(const acd_bvh *bvh, const double p[3], double max_dist2, acd_bvh_closest_result *out) {
    return acd_bvh_closest_filtered(bvh, p, max_dist2, NULL, NULL, out);
}

int acd_bvh_closest_filtered(const acd_bvh *bvh, const double p[3], double max_dist2, acd_bvh_accept_fn accept,
                             void *user, acd_bvh_closest_result *out) {
    if (bvh->nnodes == 0) return 0;
    /* the stack keeps each node's box distance, computed when it was pushed (the same value the
     * pop would compute again) */
    uint32_t stack[BVH_STACK];
    double sdist[BVH_STACK];
    int sp = 0, found = 0;
    double best = max_dist2, d0 = box_dist2(&bvh->nodes[0], p);
    if (d0 > best) return 0;
    stack[sp] = 0;
    sdist[sp++] = d0;
    while (sp > 0) {
        --sp;
        if (sdist[sp] > best) continue;
        const acd_bvh_node *n = &bvh->nodes[stack[sp]];
        if (n->count) {
            for (uint32_t i = 0; i < n->count; i++) {
                /* a triangle whose box is farther than the best cannot be closer (nor tie) */
                const double *bx = bvh->boxes + 6 * ((size_t)n->first + i);
                double e2 = 0;
                for (int k = 0; k < 3; k++) {
                    double e = axis_gap(p[k], bx[k], bx[3 + k]);
                    e2 += e * e;
                }
                if (e2 > best) continue;
                uint32_t t = bvh->order[n->first + i];
                const uint32_t *tr = bvh->triangles + 3 * (size_t)t;
                double q[3];
                double d = acd_closest_point_triangle(p, vtx(bvh, tr[0]), vtx(bvh, tr[1]), vtx(bvh, tr[2]), q);
                if ((d < best || (d == best && (!found || t < out->triangle))) && (!accept || accept(user, t, q))) {
                    best = d;
                    found = 1;
                    out->dist2 = d;
                    memcpy(out->point, q, sizeof q);
                    out->triangle = t;
                }
            }
            continue;
        }
        double dl = box_dist2(&bvh->nodes[n->first], p), dr = box_dist2(&bvh->nodes[n->first + 1], p);
        if (sp + 2 > BVH_STACK) return found; /* cannot happen for a tree built here */
        /* visit the nearer child first (push it last) */
        if (dl <= dr) {
            if (dr <= best) stack[sp] = n->first + 1, sdist[sp++] = dr;
            if (dl <= best) stack[sp] = n->first, sdist[sp++] = dl;
        } else {
            if (dl <= best) stack[sp] = n->first, sdist[sp++] = dl;
            if (dr <= best) stack[sp] = n->first + 1, sdist[sp++] = dr;
        }
    }
    return found;
}

/* ---- rays ---- */

static int ray_box(const acd_bvh_node *n, const double o[3], const double inv[3], double tmax) {
    double t0 = 0, t1 = tmax;
    for (int k = 0; k < 3; k++) {
        if (isinf(inv[k])) {
            if (o[k] < n->lo[k] || o[k] > n->hi[k]) return 0;
            continue;
        }
        double a = (n->lo[k] - o[k]) * inv[k], b = (n->hi[k] - o[k]) * inv[k];
        if (a > b) {
            double t = a;
            a = b;
            b = t;
        }
        /* widen by a few ulps so rounding never drops a box the ray touches */
        a -= fabs(a) * 1e-15;
        b += fabs(b) * 1e-15;
        if (a > t0) t0 = a;
        if (b < t1) t1 = b;
        if (t0 > t1) return 0;
    }
    return 1;
}

int acd_bvh_raycast(const acd_bvh *bvh, const double o[3], const double d[3], double tmax, double *tout,
                    uint32_t *triangle) {
    if (bvh->nnodes == 0) return 0;
    double inv[3];
    for (int k = 0; k < 3; k++) inv[k] = d[k] != 0 ? 1.0 / d[k] : INFINITY;
    uint32_t stack[BVH_STACK];
    int sp = 0, hit = 0;
    double best = tmax;
    stack[sp++] = 0;
    while (sp > 0) {
        const acd_bvh_node *n = &bvh->nodes[stack[--sp]];
        if (!ray_box(n, o, inv, best)) continue;
        if (n->count) {
            for (uint32_t i = 0; i < n->count; i++) {
                uint32_t t = bvh->order[n->first + i];
                const uint32_t *tr = bvh->triangles + 3 * (size_t)t;
                const double *a = vtx(bvh, tr[0]), *b = vtx(bvh, tr[1]), *c = vtx(bvh, tr[2]);
                double e1[3], e2[3], s[3], pv[3], qv[3];
                sub3(e1, b, a);
                sub3(e2, c, a);
                pv[0] = d[1] * e2[2] - d[2] * e2[1];
                pv[1] = d[2] * e2[0] - d[0] * e2[2];
                pv[2] = d[0] * e2[1] - d[1] * e2[0];
                double det = acd_dot3(e1, pv);
                if (det == 0) continue;
                double id = 1.0 / det;
                sub3(s, o, a);
                double u = acd_dot3(s, pv) * id;
                if (u < 0 || u > 1) continue;
                qv[0] = s[1] * e1[2] - s[2] * e1[1];
                qv[1] = s[2] * e1[0] - s[0] * e1[2];
                qv[2] = s[0] * e1[1] - s[1] * e1[0];
                double v = acd_dot3(d, qv) * id;
                if (v < 0 || u + v > 1) continue;
                double tt = acd_dot3(e2, qv) * id;
                if (tt < 0 || tt > best) continue;
                if (!hit || tt < best || (tt == best && t < *triangle)) {
                    best = tt;
                    *tout = tt;
                    *triangle = t;
                    hit = 1;
                }
            }
            continue;
        }
        if (sp + 2 > BVH_STACK) return hit;
        stack[sp++] = n->first + 1;
        stack[sp++] = n->first;
    }
    return hit;
}

/* ---- box and line queries ---- */

static int box_meets(const double alo[3], const double ahi[3], const double blo[3], const double bhi[3]) {
    for (int k = 0; k < 3; k++)
        if (alo[k] > bhi[k] || blo[k] > ahi[k]) return 0;
    return 1;
}

int acd_bvh_query_box(const acd_bvh *bvh, const double lo[3], const double hi[3], acd_bvh_tri_fn fn, void *user) {
    if (bvh->nnodes == 0) return 0;
    uint32_t stack[BVH_STACK];
    int sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const acd_bvh_node *n = &bvh->nodes[stack[--sp]];
        if (!box_meets(n->lo, n->hi, lo, hi)) continue;
        if (n->count) {
            for (uint32_t i = 0; i < n->count; i++) {
                uint32_t t = bvh->order[n->first + i];
                const double *tb = tbox_sorted(bvh, n->first + i);
                if (box_meets(tb, tb + 3, lo, hi) && fn(user, t)) return 1;
            }
            continue;
        }
        if (sp + 2 > BVH_STACK) return 0;
        stack[sp++] = n->first + 1;
        stack[sp++] = n->first;
    }
    return 0;
}

int acd_bvh_query_halfspace(const acd_bvh *bvh, const double n[3], double off, acd_bvh_tri_fn fn, void *user) {
    if (bvh->nnodes == 0) return 0;
    uint32_t stack[BVH_STACK];
    int sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const acd_bvh_node *nd = &bvh->nodes[stack[--sp]];
        if (!(acd_box_max_dot(n, nd->lo, nd->hi) > off)) continue;
        if (nd->count) {
            for (uint32_t i = 0; i < nd->count; i++) {
                const double *tb = tbox_sorted(bvh, nd->first + i);
                if (acd_box_max_dot(n, tb, tb + 3) > off && fn(user, bvh->order[nd->first + i])) return 1;
            }
            continue;
        }
        if (sp + 2 > BVH_STACK) return 0; /* cannot happen for a tree built here (see BVH_STACK) */
        stack[sp++] = nd->first;
        stack[sp++] = nd->first + 1;
    }
    return 0;
}

static inline int line_meets(const double lo[3], const double hi[3], const double p[3], int axis, int forward) {
    int a1 = axis == 0 ? 1 : 0, a2 = axis == 2 ? 1 : 2;
    if (p[a1] < lo[a1] || p[a1] > hi[a1] || p[a2] < lo[a2] || p[a2] > hi[a2]) return 0;
    return !forward || hi[axis] >= p[axis];
}

int acd_bvh_query_axis_line(const acd_bvh *bvh, const double p[3], int axis, int forward, acd_bvh_tri_fn fn,
                            void *user) {
    if (bvh->nnodes == 0 || axis < 0 || axis > 2) return 0;
    uint32_t stack[BVH_STACK];
    int sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const acd_bvh_node *n = &bvh->nodes[stack[--sp]];
        if (!line_meets(n->lo, n->hi, p, axis, forward)) continue;
        if (n->count) {
            for (uint32_t i = 0; i < n->count; i++) {
                uint32_t t = bvh->order[n->first + i];
                const double *tb = tbox_sorted(bvh, n->first + i);
                if (line_meets(tb, tb + 3, p, axis, forward) && fn(user, t)) return 1;
            }
            continue;
        }
        if (sp + 2 > BVH_STACK) return 0;
        stack[sp++] = n->first + 1;
        stack[sp++] = n->first;
    }
    return 0;
}

/* ---- overlapping pairs ---- */

static void grow_box(const double lo[3], const double hi[3], double m, double l2[3], double h2[3]) {
    for (int k = 0; k < 3; k++) {
        l2[k] = lo[k] - m;
        h2[k] = hi[k] + m;
    }
}

typedef struct pair_item {
    uint32_t a, b;
} pair_item;

/* (the triangles' boxes from bvh->boxes, which holds tri_box's values: the same pairs, in the same
 * order) */
int acd_bvh_overlap_pairs(const acd_bvh *bvh, double margin, acd_bvh_pair_fn fn, void *user) {
    if (bvh->nnodes == 0) return 0;
    if (!(margin >= 0)) margin = 0;
    /* (a, a) means "pairs within node a"; the stack holds at most depth * 3 items */
    pair_item stack[3 * BVH_STACK];
    int sp = 0;
    stack[sp++] = (pair_item){0, 0};
    while (sp > 0) {
        pair_item it = stack[--sp];
        const acd_bvh_node *na = &bvh->nodes[it.a], *nb = &bvh->nodes[it.b];
        if (it.a == it.b) {
            if (na->count) {
                for (uint32_t i = 0; i < na->count; i++) {
                    uint32_t t = bvh->order[na->first + i];
                    const double *b1 = bvh->boxes + 6 * ((size_t)na->first + i);
                    double l1[3], h1[3];
                    grow_box(b1, b1 + 3, margin, l1, h1);
                    for (uint32_t j = i + 1; j < na->count; j++) {
                        uint32_t u = bvh->order[na->first + j];
                        const double *b2 = bvh->boxes + 6 * ((size_t)na->first + j);
                        double l2[3], h2[3];
                        grow_box(b2, b2 + 3, margin, l2, h2);
                        if (box_meets(l1, h1, l2, h2) && fn(user, t < u ? t : u, t < u ? u : t)) return 1;
                    }
                }
                continue;
            }
            if (sp + 3 > 3 * BVH_STACK) return 0;
            stack[sp++] = (pair_item){na->first, na->first + 1};
            stack[sp++] = (pair_item){na->first + 1, na->first + 1};
            stack[sp++] = (pair_item){na->first, na->first};
            continue;
        }
        double la[3], ha[3], lb[3], hb[3];
        grow_box(na->lo, na->hi, margin, la, ha);
        grow_box(nb->lo, nb->hi, margin, lb, hb);
        if (!box_meets(la, ha, lb, hb)) continue;
        if (na->count && nb->count) {
            for (uint32_t i = 0; i < na->count; i++) {
                uint32_t t = bvh->order[na->first + i];
                const double *b1 = bvh->boxes + 6 * ((size_t)na->first + i);
                double l1[3], h1[3];
                grow_box(b1, b1 + 3, margin, l1, h1);
                for (uint32_t j = 0; j < nb->count; j++) {
                    uint32_t u = bvh->order[nb->first + j];
                    const double *b2 = bvh->boxes + 6 * ((size_t)nb->first + j);
                    double l2[3], h2[3];
                    grow_box(b2, b2 + 3, margin, l2, h2);
                    if (box_meets(l1, h1, l2, h2) && fn(user, t < u ? t : u, t < u ? u : t)) return 1;
                }
            }
            continue;
        }
        if (sp + 2 > 3 * BVH_STACK) return 0;
        /* descend into the larger (or the inner) node */
        int split_a = nb->count || (!na->count && box_area(na->lo, na->hi) >= box_area(nb->lo, nb->hi));
        if (split_a) {
            stack[sp++] = (pair_item){na->first + 1, it.b};
            stack[sp++] = (pair_item){na->first, it.b};
        } else {
            stack[sp++] = (pair_item){it.a, nb->first + 1};
            stack[sp++] = (pair_item){it.a, nb->first};
        }
    }
    return 0;
}

typedef struct pair_vec {
    uint32_t *data;
    size_t n, cap;
    int failed;
} pair_vec;

static int collect_pair(void *user, uint32_t a, uint32_t b) {
    pair_vec *v = user;
    if (v->n == v->cap) {
        size_t cap = v->cap ? 2 * v->cap : 1024;
        uint32_t *d = realloc(v->data, cap * 2 * sizeof(uint32_t));
        if (!d) {
            v->failed = 1;
            return 1;
        }
        v->data = d;
        v->cap = cap;
    }
    v->data[2 * v->n] = a;
    v->data[2 * v->n + 1] = b;
    v->n++;
    return 0;
}

static int cmp_pair(const void *x, const void *y) {
    const uint32_t *a = x, *b = y;
    if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
    return (a[1] > b[1]) - (a[1] < b[1]);
}

acd_status acd_bvh_collect_pairs(const acd_bvh *bvh, double margin, uint32_t **pairs, size_t *npairs,
                                 acd_error *err) {
    pair_vec v = {0};
    acd_bvh_overlap_pairs(bvh, margin, collect_pair, &v);
    if (v.failed) {
        free(v.data);
        *pairs = NULL;
        *npairs = 0;
        return acd_fail(err, ACD_ERR_NOMEM, "bvh: out of memory collecting %zu overlapping pairs", v.n);
    }
    if (v.n) qsort(v.data, v.n, 2 * sizeof(uint32_t), cmp_pair);
    *pairs = v.data;
    *npairs = v.n;
    return ACD_OK;
}
