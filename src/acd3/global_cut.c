/* acd3/global_cut: root, cup pockets, the minimum-weight cycle of G_K and its plane; see
 * global_cut.h. */
#include "acd3/global_cut.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/minheap.h"
#include "geom3/pca.h"
#include "geom3/vec3.h"

/* Expansions of the cycle search before it gives up (spec §4.5). */
#define CYCLE_MAX_EXPANSIONS 10000
/* The cut spreads in two dimensions when its second PCA variance exceeds this multiple of the
 * third. */
#define CUT_PLANARITY 4.0
/* Plane push (spec §5.2): refits with doubled weights. */
#define PUSH_ITERATIONS 10

void acd3_global_cut_free(acd3_global_cut *gc) {
    if (!gc) return;
    free(gc->v);
    memset(gc, 0, sizeof *gc);
}

/* The other region of knot k's chain than r (UINT32_MAX when r is not on it). */
static uint32_t beyond(const acd3_cut_graph *cg, uint32_t k, uint32_t r) {
    const uint32_t *cr = cg->chain_region + 2 * (size_t)cg->knot_chain[k];
    return cr[0] == r ? cr[1] : cr[1] == r ? cr[0] : UINT32_MAX;
}

typedef struct item {
    uint32_t knot, region, cut; /* region: the pocket entered; cut: the cut that led here */
    int32_t parent;
    double w;
} item;


static int append(acd3_global_cut *gc, size_t *cap, uint32_t v) {
    if (gc->n && gc->v[gc->n - 1] == v) return 1;
    if (gc->n == *cap) {
        size_t nc = *cap ? 2 * *cap : 64;
        uint32_t *na = realloc(gc->v, nc * sizeof *na);
        if (!na) return 0;
        gc->v = na;
        *cap = nc;
    }
    gc->v[gc->n++] = v;
    return 1;
}

/* Appends the vertices of cut c walked from knot `from` to its other knot. */
static int append_cut(acd3_global_cut *gc, size_t *cap, const acd3_cut_graph *cg, uint32_t c, uint32_t from) {
    const acd3_pocket_cut *pc = &cg->cuts[c];
    const uint32_t *p = cg->cut_v + pc->off;
    int fwd = pc->knot[0] == from;
    for (size_t i = 0; i < pc->n; i++)
        if (!append(gc, cap, p[fwd ? i : pc->n - 1 - i])) return 0;
    gc->ncuts++;
    gc->weight += pc->w;
    return 1;
}

/* Minimum-weight cycle through root cut `root` (spec A11), appended to gc after the root.
 * Returns 1 found, 0 not found, -1 out of memory. */
static int grow_cycle(const acd3_cut_graph *cg, uint32_t root, uint32_t rx, acd3_global_cut *gc, size_t *cap) {
    const acd3_pocket_cut *rc = &cg->cuts[root];
    uint32_t a = rc->knot[0], b = rc->knot[1];
    uint32_t ra = beyond(cg, a, rx);
    if (ra == UINT32_MAX) return 0;
    size_t nitems = 0, capitems = 1024;
    item *it = malloc(capitems * sizeof *it);
    acd_minheap heap = {0}; /* (branch weight, item) */
    uint8_t *closed = calloc(2 * cg->nknots + 1, 1);
    int res = 0;
    if (!it || !closed) {
        res = -1;
        goto done;
    }
    it[nitems] = (item){a, ra, UINT32_MAX, -1, 0};
    if (!acd_minheap_push(&heap, 0, (uint32_t)nitems++)) {
        res = -1;
        goto done;
    }
    int32_t goal = -1;
    for (size_t pops = 0; heap.n && pops < CYCLE_MAX_EXPANSIONS; pops++) {
        acd_minheap_item top = acd_minheap_pop(&heap);
        item cur = it[top.id];
        if (cur.knot == b && cur.parent >= 0) {
            goal = (int32_t)top.id;
            break;
        }
        const uint32_t *cr = cg->chain_region + 2 * (size_t)cg->knot_chain[cur.knot];
        size_t slot = 2 * (size_t)cur.knot + (cr[1] == cur.region);
        if (closed[slot]) continue;
        closed[slot] = 1;
        for (size_t q = cg->knot_row[cur.knot]; q < cg->knot_row[cur.knot + 1]; q++) {
            uint32_t c = cg->knot_cut[q];
            if (c == root || cg->cuts[c].region != cur.region) continue;
            uint32_t k2 = cg->cuts[c].knot[0] == cur.knot ? cg->cuts[c].knot[1] : cg->cuts[c].knot[0];
            uint32_t nr = beyond(cg, k2, cur.region);
            if (nr == UINT32_MAX) continue;
            if (k2 == b) {
                if (nr != rx) continue;
            } else {
                if (nr == rx) continue;
                /* no pocket twice on the branch */
                int visited = 0;
                for (int32_t p = (int32_t)top.id; p >= 0 && !visited; p = it[p].parent) visited = it[p].region == nr;
                if (visited) continue;
            }
            if (nitems == capitems) {
                capitems *= 2;
                item *ni = realloc(it, capitems * sizeof *ni);
                if (!ni) {
                    res = -1;
                    goto done;
                }
                it = ni;
            }
            double w = cur.w + cg->cuts[c].w;
            it[nitems] = (item){k2, nr, c, (int32_t)top.id, w};
            if (!acd_minheap_push(&heap, w, (uint32_t)nitems++)) {
                res = -1;
                goto done;
            }
        }
    }
    if (goal >= 0) {
        /* the branch from b back to a continues the root a -> b */
        for (int32_t p = goal; it[p].parent >= 0; p = it[p].parent)
            if (!append_cut(gc, cap, cg, it[p].cut, it[p].knot)) {
                res = -1;
                goto done;
            }
        res = 1;
    }
done:
    free(it), free(closed);
    acd_minheap_free(&heap);
    return res;
}

/* Runs of the region Dijkstra in the dynamic search before it gives up. */
#define DYNAMIC_MAX_RUNS 4096

typedef struct ditem {
    uint32_t v, region, chain, knot, cut; /* knot UINT32_MAX: a pseudo-knot; cut UINT32_MAX: a dynamic path */
    int32_t parent;
    size_t off, n; /* a dynamic path: pool[off .. off+n), from the parent's vertex to v */
    double w;
} ditem;

/* Open-addressing set of (vertex, region) pairs. */
typedef struct pairset {
    uint64_t *a;
    size_t cap, n;
} pairset;

static uint64_t pair_hash(uint64_t k) {
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdULL;
    k ^= k >> 33;
    return k;
}

/* 1 if (v, r) was added, 0 if present, -1 out of memory. */
static int pairset_add(pairset *s, uint32_t v, uint32_t r) {
    if (2 * (s->n + 1) > s->cap) {
        size_t nc = s->cap ? 2 * s->cap : 1024;
        uint64_t *na = malloc(nc * sizeof *na);
        if (!na) return -1;
        for (size_t i = 0; i < nc; i++) na[i] = UINT64_MAX;
        for (size_t i = 0; i < s->cap; i++)
            if (s->a[i] != UINT64_MAX) {
                size_t h = pair_hash(s->a[i]) & (nc - 1);
                while (na[h] != UINT64_MAX) h = (h + 1) & (nc - 1);
                na[h] = s->a[i];
            }
        free(s->a);
        s->a = na;
        s->cap = nc;
    }
    uint64_t k = (uint64_t)v << 32 | r;
    size_t h = pair_hash(k) & (s->cap - 1);
    while (s->a[h] != UINT64_MAX) {
        if (s->a[h] == k) return 0;
        h = (h + 1) & (s->cap - 1);
    }
    s->a[h] = k;
    s->n++;
    return 1;
}

/* The chain of cg holding vertex v with region r on one side (lowest chain id), or UINT32_MAX. */
static uint32_t chain_at(const acd3_cut_graph *cg, uint32_t v, uint32_t r) {
    for (size_t c = 0; c < cg->nchains; c++) {
        if (cg->chain_region[2 * c] != r && cg->chain_region[2 * c + 1] != r) continue;
        for (size_t i = cg->chain_off[c]; i < cg->chain_off[c + 1]; i++)
            if (cg->chain_v[i] == v) return (uint32_t)c;
    }
    return UINT32_MAX;
}

static uint32_t chain_other(const acd3_cut_graph *cg, uint32_t c, uint32_t r) {
    const uint32_t *cr = cg->chain_region + 2 * (size_t)c;
    return cr[0] == r ? cr[1] : cr[1] == r ? cr[0] : UINT32_MAX;
}

/* The cycle search with the paper's dynamic geodesic cuts (§4.2.4, spec §4.5): as grow_cycle,
 * from vertex av (on chain ach of rx, knot ak or UINT32_MAX) back to vertex bv (on chain bch of
 * rx), and from every node (vertex v entering pocket p) also along valley-cost shortest paths
 * inside p to each knot-less chain of p (to its nearest vertex, a pseudo-knot), from a pseudo-
 * knot to each knot of p's other chains, and to bv when p borders rx along bch. A path crossing
 * a convex area weighs much more than a valley (its mean concavity is ~0), so the cycles of G_K
 * alone come first. Returns 1 found (appended to gc), 0 not, -1 out of memory. */
static int grow_cycle_dynamic(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms,
                              const acd3_cut_graph *cg, const acd3_gc_opts *o, uint32_t root, uint32_t av, uint32_t ach,
                              uint32_t ak, uint32_t bv, uint32_t bch, uint32_t rx, acd3_global_cut *gc, size_t *cap) {
    size_t nv = m->nvertices, nf = m->ntriangles, ne = g->nedges, nr = ms->nregions, nch = cg->nchains;
    uint32_t ra = chain_other(cg, ach, rx);
    if (ra == UINT32_MAX || chain_other(cg, bch, rx) == UINT32_MAX) return 0;
    size_t *rrow = calloc(nr + 1, sizeof *rrow), *crow = calloc(nr + 1, sizeof *crow), *krow = calloc(nch + 1, sizeof *krow);
    uint32_t *rface = malloc((nf ? nf : 1) * sizeof *rface), *rchain = malloc((2 * nch + 1) * sizeof *rchain),
             *ckn = malloc((cg->nknots + 1) * sizeof *ckn), *pool = NULL;
    double *wc = malloc((ne ? ne : 1) * sizeof *wc);
    uint8_t *allowed = calloc(nv ? nv : 1, 1);
    ditem *it = NULL;
    size_t nitems = 0, capitems = 0, npool = 0, cappool = 0;
    acd_minheap heap = {0};
    pairset closed = {0};
    acd_sp_ws sp;
    memset(&sp, 0, sizeof sp);
    int res = -1;
    if (!rrow || !crow || !krow || !rface || !rchain || !ckn || !wc || !allowed || acd_sp_ws_init(&sp, nv, NULL) != ACD_OK) goto done;
    for (size_t f = 0; f < nf; f++) rrow[ms->face_region[f] + 1]++;
    for (size_t r = 0; r < nr; r++) rrow[r + 1] += rrow[r];
    for (size_t c = 0; c < nch; c++) crow[cg->chain_region[2 * c] + 1]++, crow[cg->chain_region[2 * c + 1] + 1]++;
    for (size_t r = 0; r < nr; r++) crow[r + 1] += crow[r];
    for (size_t k = 0; k < cg->nknots; k++) krow[cg->knot_chain[k] + 1]++;
    for (size_t c = 0; c < nch; c++) krow[c + 1] += krow[c];
    {
        size_t *fill = malloc((nr + nch + 1) * sizeof *fill);
        if (!fill) goto done;
        memcpy(fill, rrow, nr * sizeof *fill);
        for (size_t f = 0; f < nf; f++) rface[fill[ms->face_region[f]]++] = (uint32_t)f;
        memcpy(fill, crow, nr * sizeof *fill);
        for (size_t c = 0; c < nch; c++)
            for (int s2 = 0; s2 < 2; s2++) rchain[fill[cg->chain_region[2 * c + s2]]++] = (uint32_t)c;
        memcpy(fill, krow, nch * sizeof *fill);
        for (size_t k = 0; k < cg->nknots; k++) ckn[fill[cg->knot_chain[k]]++] = (uint32_t)k;
        free(fill);
    }
    for (size_t e = 0; e < ne; e++) wc[e] = acd3_valley_cost(g, ms->vconc, (uint32_t)e, o->tau);
    capitems = 1024;
    it = malloc(capitems * sizeof *it);
    if (!it) goto done;
    it[nitems] = (ditem){av, ra, ach, ak, UINT32_MAX, -1, 0, 0, 0};
    if (!acd_minheap_push(&heap, 0, (uint32_t)nitems++)) goto done;
    int32_t goal = -1;
    size_t runs = 0;
    uint32_t targets[1024];
    for (size_t pops = 0; heap.n && pops < CYCLE_MAX_EXPANSIONS; pops++) {
        acd_minheap_item top = acd_minheap_pop(&heap);
        ditem cur = it[top.id];
        if (cur.v == bv && cur.region == rx && cur.parent >= 0) {
            goal = (int32_t)top.id;
            break;
        }
        int added = pairset_add(&closed, cur.v, cur.region);
        if (added < 0) goto done;
        if (!added) continue;
        uint32_t p = cur.region;
        /* candidate moves: (vertex, chain, knot, cut or path) */
        /* 1. the cuts of G_K at a knot */
        if (cur.knot != UINT32_MAX)
            for (size_t q = cg->knot_row[cur.knot]; q < cg->knot_row[cur.knot + 1]; q++) {
                uint32_t c = cg->knot_cut[q];
                if (c == root || cg->cuts[c].region != p) continue;
                uint32_t k2 = cg->cuts[c].knot[0] == cur.knot ? cg->cuts[c].knot[1] : cg->cuts[c].knot[0];
                uint32_t n2 = beyond(cg, k2, p);
                if (n2 == UINT32_MAX) continue;
                if (n2 == rx) {
                    if (cg->knot_v[k2] != bv) continue;
                } else {
                    int visited = 0;
                    for (int32_t a = (int32_t)top.id; a >= 0 && !visited; a = it[a].parent) visited = it[a].region == n2;
                    if (visited) continue;
                }
                if (nitems == capitems) {
                    ditem *ni = realloc(it, 2 * capitems * sizeof *ni);
                    if (!ni) goto done;
                    it = ni, capitems *= 2;
                }
                double w = cur.w + cg->cuts[c].w;
                it[nitems] = (ditem){cg->knot_v[k2], n2, cg->knot_chain[k2], k2, c, (int32_t)top.id, 0, 0, w};
                if (!acd_minheap_push(&heap, w, (uint32_t)nitems++)) goto done;
            }
        /* 2. dynamic geodesic cuts inside p */
        if (runs >= DYNAMIC_MAX_RUNS) continue;
        runs++;
        for (size_t i = rrow[p]; i < rrow[p + 1]; i++)
            for (int k = 0; k < 3; k++) allowed[m->triangles[3 * (size_t)rface[i] + k]] = 1;
        acd_sp_limits lim = {.weights = wc, .vertex_allowed = allowed};
        int run_ok = acd_sp_ws_run(&sp, g, cur.v, &lim);
        for (size_t i = rrow[p]; i < rrow[p + 1]; i++)
            for (int k = 0; k < 3; k++) allowed[m->triangles[3 * (size_t)rface[i] + k]] = 0;
        if (!run_ok) goto done;
        for (size_t q = crow[p]; q < crow[p + 1]; q++) {
            uint32_t ch = rchain[q];
            if (ch == cur.chain || (q > crow[p] && rchain[q - 1] == ch)) continue; /* (a chain with p on both sides) */
            uint32_t n2 = chain_other(cg, ch, p);
            size_t nt = 0;
            uint32_t tknot[1024];
            if (n2 == rx) {
                if (ch != bch) continue;
                targets[nt] = bv, tknot[nt++] = UINT32_MAX;
                for (size_t j = krow[ch]; j < krow[ch + 1]; j++)
                    if (cg->knot_v[ckn[j]] == bv) tknot[0] = ckn[j];
            } else {
                int visited = 0;
                for (int32_t a = (int32_t)top.id; a >= 0 && !visited; a = it[a].parent) visited = it[a].region == n2;
                if (visited) continue;
                if (krow[ch + 1] > krow[ch]) {
                    if (cur.knot != UINT32_MAX) continue; /* knot to knot: the cuts of G_K */
                    for (size_t j = krow[ch]; j < krow[ch + 1] && nt < 1024; j++)
                        targets[nt] = cg->knot_v[ckn[j]], tknot[nt++] = ckn[j];
                } else {
                    uint32_t best = UINT32_MAX;
                    double bd = INFINITY;
                    for (size_t j = cg->chain_off[ch]; j < cg->chain_off[ch + 1]; j++) {
                        double d = acd_sp_ws_dist(&sp, cg->chain_v[j]);
                        if (d < bd || (d == bd && best != UINT32_MAX && cg->chain_v[j] < best)) bd = d, best = cg->chain_v[j];
                    }
                    if (best == UINT32_MAX) continue;
                    targets[nt] = best, tknot[nt++] = UINT32_MAX;
                }
            }
            for (size_t t = 0; t < nt; t++) {
                uint32_t tv = targets[t];
                if (!isfinite(acd_sp_ws_dist(&sp, tv))) continue;
                size_t n = 0;
                for (uint32_t v = tv; v != ACD_NO_VERTEX; v = sp.pred[v]) n++;
                if (npool + n > cappool) {
                    size_t nc = cappool ? 2 * cappool : 4096;
                    while (nc < npool + n) nc *= 2;
                    uint32_t *np2 = realloc(pool, nc * sizeof *np2);
                    if (!np2) goto done;
                    pool = np2, cappool = nc;
                }
                size_t i = npool + n;
                for (uint32_t v = tv; v != ACD_NO_VERTEX; v = sp.pred[v]) pool[--i] = v;
                double w = n > 1 ? acd3_cut_weight(m, g, cg->face_of, ms->vconc, pool + npool, n, o) : 0;
                if (nitems == capitems) {
                    ditem *ni = realloc(it, 2 * capitems * sizeof *ni);
                    if (!ni) goto done;
                    it = ni, capitems *= 2;
                }
                it[nitems] = (ditem){tv, n2, ch, tknot[t], UINT32_MAX, (int32_t)top.id, npool, n, cur.w + w};
                npool += n;
                if (!acd_minheap_push(&heap, cur.w + w, (uint32_t)nitems++)) goto done;
            }
        }
    }
    res = 0;
    if (goal >= 0) {
        /* the branch from bv back to av continues the root av -> bv */
        for (int32_t q = goal; it[q].parent >= 0; q = it[q].parent) {
            if (it[q].cut != UINT32_MAX) {
                if (!append_cut(gc, cap, cg, it[q].cut, it[q].knot)) goto oom;
            } else {
                for (size_t i = it[q].n; i-- > 0;)
                    if (!append(gc, cap, pool[it[q].off + i])) goto oom;
                gc->ncuts++;
                gc->weight += it[q].w - it[it[q].parent].w;
            }
        }
        res = 1;
    }
    goto done;
oom:
    res = -1;
done:
    free(rrow), free(crow), free(krow), free(rface), free(rchain), free(ckn), free(pool), free(wc), free(allowed);
    free(it), free(closed.a);
    acd_minheap_free(&heap);
    acd_sp_ws_free(&sp);
    return res;
}

/* Cup-shaped pocket rx: the cut u -> x -> w through the witness x. */
static int cup_cut(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms, const acd3_cut_graph *cg,
                   const acd3_gc_opts *o, uint32_t x, uint32_t rx, acd3_global_cut *gc, size_t *cap) {
    size_t nv = m->nvertices, ne = g->nedges;
    uint8_t *allowed = calloc(nv, 1), *onb = calloc(nv, 1);
    double *wc = malloc((ne ? ne : 1) * sizeof *wc);
    int res = 0;
    acd_sp_tree t;
    memset(&t, 0, sizeof t);
    if (!allowed || !onb || !wc) {
        res = -1;
        goto done;
    }
    for (size_t f = 0; f < m->ntriangles; f++)
        if (ms->face_region[f] == rx)
            for (int k = 0; k < 3; k++) allowed[m->triangles[3 * f + k]] = 1;
    size_t nb = 0;
    for (size_t c = 0; c < cg->nchains; c++)
        if (cg->chain_region[2 * c] == rx || cg->chain_region[2 * c + 1] == rx)
            for (size_t i = cg->chain_off[c]; i < cg->chain_off[c + 1]; i++) nb += !onb[cg->chain_v[i]], onb[cg->chain_v[i]] = 1;
    if (nb < 2) goto done;
    for (size_t e = 0; e < ne; e++) wc[e] = acd3_valley_cost(g, ms->vconc, (uint32_t)e, o->tau);
    acd_dijkstra_opts dop;
    memset(&dop, 0, sizeof dop);
    dop.weights = wc;
    dop.vertex_allowed = allowed;
    dop.target = ACD_NO_VERTEX;
    if (acd_dijkstra(g, &x, 1, &dop, &t, NULL) != ACD_OK) {
        res = -1;
        goto done;
    }
    uint32_t u = UINT32_MAX;
    for (size_t v = 0; v < nv; v++)
        if (onb[v] && v != x && isfinite(t.dist[v]) && (u == UINT32_MAX || t.dist[v] < t.dist[u])) u = (uint32_t)v;
    if (u == UINT32_MAX) goto done;
    const double *N = ms->patches.planes + 4 * (size_t)ms->region_patch[rx];
    const double *px = m->vertices + 3 * (size_t)x;
    double du[3];
    for (int k = 0; k < 3; k++) du[k] = m->vertices[3 * (size_t)u + k] - px[k];
    double s = du[0] * N[0] + du[1] * N[1] + du[2] * N[2];
    for (int k = 0; k < 3; k++) du[k] -= s * N[k];
    double lu = sqrt(du[0] * du[0] + du[1] * du[1] + du[2] * du[2]);
    /* a root for the dynamic cycle (witness_root): w off the chains through u, else the cycle
     * could only close along u's own chain */
    if (o->dynamic && o->witness_root)
        for (size_t c = 0; c < cg->nchains; c++) {
            if (cg->chain_region[2 * c] != rx && cg->chain_region[2 * c + 1] != rx) continue;
            int has = 0;
            for (size_t i = cg->chain_off[c]; i < cg->chain_off[c + 1] && !has; i++) has = cg->chain_v[i] == u;
            if (has)
                for (size_t i = cg->chain_off[c]; i < cg->chain_off[c + 1]; i++) onb[cg->chain_v[i]] = 2;
        }
    uint32_t w = UINT32_MAX;
    double best = -INFINITY;
    for (size_t v = 0; v < nv; v++) {
        if (onb[v] != 1 || v == u || v == x || !isfinite(t.dist[v])) continue;
        double dv[3];
        for (int k = 0; k < 3; k++) dv[k] = m->vertices[3 * v + k] - px[k];
        double sv = dv[0] * N[0] + dv[1] * N[1] + dv[2] * N[2];
        for (int k = 0; k < 3; k++) dv[k] -= sv * N[k];
        double lv = sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]);
        double score = lu > 0 && lv > 0 ? -(du[0] * dv[0] + du[1] * dv[1] + du[2] * dv[2]) / (lu * lv) : -1;
        if (score > best || (score == best && t.dist[v] < t.dist[w])) best = score, w = (uint32_t)v;
    }
    if (w == UINT32_MAX) goto done;
    /* u -> x (the tree path from x to u, walked from u), then x -> w */
    for (uint32_t v = u; v != ACD_NO_VERTEX; v = t.pred[v])
        if (!append(gc, cap, v)) {
            res = -1;
            goto done;
        }
    {
        size_t len = 0, i;
        for (uint32_t v = w; v != ACD_NO_VERTEX; v = t.pred[v]) len++;
        uint32_t *tmp = malloc(len * sizeof *tmp);
        if (!tmp) {
            res = -1;
            goto done;
        }
        i = len;
        for (uint32_t v = w; v != ACD_NO_VERTEX; v = t.pred[v]) tmp[--i] = v;
        for (i = 0; i < len; i++)
            if (!append(gc, cap, tmp[i])) {
                free(tmp);
                res = -1;
                goto done;
            }
        free(tmp);
    }
    gc->cup = 1;
    gc->ncuts = 1;
    gc->root_n = gc->n;
    gc->weight = acd3_cut_weight(m, g, cg->face_of, ms->vconc, gc->v, gc->n, o);
    res = 1;
done:
    acd_sp_tree_free(&t);
    free(allowed), free(onb), free(wc);
    return res;
}

acd_status acd3_global_cut_find(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms,
                                const acd3_cut_graph *cg, const acd3_gc_opts *o, acd3_global_cut *out,
                                acd_error *err) {
    memset(out, 0, sizeof *out);
    uint32_t x = ms->witness;
    if (x == UINT32_MAX || ms->hull.dim < 3) return ACD_OK;
    uint32_t rx = acd3_vertex_region(m, ms, cg, x);
    if (rx == UINT32_MAX) return ACD_OK;
    const double *px = m->vertices + 3 * (size_t)x;
    uint32_t root = UINT32_MAX;
    double bd = INFINITY;
    int near = 0;
    for (size_t c = 0; c < cg->ncuts; c++) {
        const acd3_pocket_cut *pc = &cg->cuts[c];
        if (pc->region != rx) continue;
        double d = INFINITY;
        for (size_t i = 0; i < pc->n; i++) {
            uint32_t v = cg->cut_v[pc->off + i];
            double dv = acd_dist3(m->vertices + 3 * (size_t)v, px);
            if (dv < d) d = dv;
            if (!near) near = v == x || acd_edge_graph_find(g, v, x) != ACD_NO_VERTEX;
        }
        if (root == UINT32_MAX || d < bd || (d == bd && pc->w < cg->cuts[root].w)) root = (uint32_t)c, bd = d;
    }
    double kmax = 0;
    for (size_t k = 0; k < cg->nknots; k++) {
        const uint32_t *cr = cg->chain_region + 2 * (size_t)cg->knot_chain[k];
        if ((cr[0] == rx || cr[1] == rx) && ms->vconc[cg->knot_v[k]] > kmax) kmax = ms->vconc[cg->knot_v[k]];
    }
    size_t cap = 0;
    int r;
    if (root == UINT32_MAX || (!near && kmax < ms->vconc[x] - o->delta) || (o->dynamic && o->witness_root)) {
        r = cup_cut(m, g, ms, cg, o, x, rx, out, &cap);
        out->plane_n = out->n;
        if (r > 0 && o->dynamic && out->n >= 2) {
            /* the cup cut ends on the pocket's boundary: the dynamic search closes it */
            uint32_t u = out->v[0], w = out->v[out->n - 1];
            uint32_t cu = chain_at(cg, u, rx), cw = chain_at(cg, w, rx);
            if (cu != UINT32_MAX && cw != UINT32_MAX) {
                r = grow_cycle_dynamic(m, g, ms, cg, o, UINT32_MAX, u, cu, UINT32_MAX, w, cw, rx, out, &cap);
                if (r > 0) out->closed = out->dynamic = 1;
                if (r == 0) r = 1;
            }
        }
    } else {
        r = append_cut(out, &cap, cg, root, cg->cuts[root].knot[0]) ? 1 : -1;
        out->root_n = out->n;
        if (r > 0) {
            r = grow_cycle(cg, root, rx, out, &cap);
            if (r > 0) out->closed = 1;
            out->plane_n = out->n;
            if (r == 0 && o->dynamic) {
                uint32_t a = cg->cuts[root].knot[0], b = cg->cuts[root].knot[1];
                r = grow_cycle_dynamic(m, g, ms, cg, o, root, cg->knot_v[a], cg->knot_chain[a], a, cg->knot_v[b],
                                       cg->knot_chain[b], rx, out, &cap);
                if (r > 0) out->closed = out->dynamic = 1;
            }
            if (r == 0) r = 1;
        }
    }
    if (r < 0) {
        acd3_global_cut_free(out);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory finding the global cut");
    }
    return ACD_OK;
}

/* Weighted fit about the weighted centroid (through == NULL) or about `through`. */
static int fit_plane(const double *pts, const double *w, size_t n, const double *through, double c[3],
                     double vals[3], double axes[3][3]) {
    double sw = 0;
    c[0] = c[1] = c[2] = 0;
    for (size_t i = 0; i < n; i++) {
        sw += w[i];
        for (int k = 0; k < 3; k++) c[k] += w[i] * pts[3 * i + k];
    }
    if (!(sw > 0)) return 0;
    for (int k = 0; k < 3; k++) c[k] = through ? through[k] : c[k] / sw;
    double a[3][3] = {{0}};
    for (size_t i = 0; i < n; i++) {
        double d[3] = {pts[3 * i] - c[0], pts[3 * i + 1] - c[1], pts[3 * i + 2] - c[2]};
        for (int r = 0; r < 3; r++)
            for (int s = r; s < 3; s++) a[r][s] += w[i] * d[r] * d[s];
    }
    for (int r = 0; r < 3; r++)
        for (int s = r; s < 3; s++) a[r][s] /= sw;
    acd_eigen_sym3(a, vals, axes);
    return 1;
}

int acd3_global_cut_plane(const acd_mesh *m, const acd3_measure *ms, const acd3_cut_graph *cg,
                          const acd3_global_cut *gc, const acd3_gc_opts *o, double point[3], double normal[3],
                          double fitted[3]) {
    size_t n = gc->plane_n && gc->plane_n <= gc->n ? gc->plane_n : gc->n;
    const uint32_t *cv = gc->v;
    if (n < 2) return 0;
    size_t ns = 3 * (n - 1);
    double *pts = malloc(3 * ns * sizeof *pts), *w = malloc(ns * sizeof *w), *mult = malloc(n * sizeof *mult);
    int ok = 0;
    if (!pts || !w || !mult) goto done;
    for (size_t i = 0; i < n; i++) mult[i] = 1;
    double total_len = 0;
    int any_conc = 0;
    for (size_t i = 0; i + 1 < n; i++) {
        const double *a = m->vertices + 3 * (size_t)cv[i], *b = m->vertices + 3 * (size_t)cv[i + 1];
        total_len += acd_dist3(a, b);
        any_conc |= ms->vconc[cv[i]] > 0 || ms->vconc[cv[i + 1]] > 0;
    }
    if (!(total_len > 0)) goto done;
    double theta = 2.0 * total_len / (double)(n - 1);
    if (o->tau > theta) theta = o->tau;
    double c[3], vals[3], axes[3][3];
    const double *through = NULL;
    for (int iter = 0;; iter++) {
        for (size_t i = 0; i + 1 < n; i++) {
            uint32_t va = cv[i], vb = cv[i + 1];
            const double *a = m->vertices + 3 * (size_t)va, *b = m->vertices + 3 * (size_t)vb;
            double len = acd_dist3(a, b), ca = any_conc ? ms->vconc[va] : 1, cb = any_conc ? ms->vconc[vb] : 1;
            for (int k = 0; k < 3; k++) {
                pts[9 * i + k] = a[k];
                pts[9 * i + 3 + k] = 0.5 * (a[k] + b[k]);
                pts[9 * i + 6 + k] = b[k];
            }
            w[3 * i] = len * ca * mult[i];
            w[3 * i + 1] = len * 0.5 * (ca * mult[i] + cb * mult[i + 1]);
            w[3 * i + 2] = len * cb * mult[i + 1];
        }
        if (!fit_plane(pts, w, ns, through, c, vals, axes)) goto done;
        if (!(vals[1] > CUT_PLANARITY * vals[2]) || !(vals[1] > 0)) {
            if (iter > 0) break; /* keep the last two-dimensional fit */
            /* a straight cut: the plane through its direction and the mean surface normal */
            double sn[3] = {0, 0, 0};
            for (size_t i = 0; i < n; i++)
                for (size_t q = cg->vf_row[cv[i]]; q < cg->vf_row[cv[i] + 1]; q++) {
                    const uint32_t *t = m->triangles + 3 * (size_t)cg->vf[q];
                    const double *p0 = m->vertices + 3 * (size_t)t[0], *p1 = m->vertices + 3 * (size_t)t[1],
                                 *p2 = m->vertices + 3 * (size_t)t[2];
                    double u[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, v[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
                    sn[0] += u[1] * v[2] - u[2] * v[1];
                    sn[1] += u[2] * v[0] - u[0] * v[2];
                    sn[2] += u[0] * v[1] - u[1] * v[0];
                }
            const double *d = axes[0];
            double nn[3] = {d[1] * sn[2] - d[2] * sn[1], d[2] * sn[0] - d[0] * sn[2], d[0] * sn[1] - d[1] * sn[0]};
            double l = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
            double ls = sqrt(sn[0] * sn[0] + sn[1] * sn[1] + sn[2] * sn[2]);
            if (!(l > 1e-9 * ls) || !(ls > 0)) goto done;
            for (int k = 0; k < 3; k++) axes[2][k] = nn[k] / l;
            break;
        }
        if (iter >= PUSH_ITERATIONS + 1) break;
        /* push toward the cut vertices the plane misses */
        size_t worst = SIZE_MAX;
        double wd = theta;
        for (size_t i = 0; i < n; i++) {
            const double *p = m->vertices + 3 * (size_t)cv[i];
            double dd = fabs((p[0] - c[0]) * axes[2][0] + (p[1] - c[1]) * axes[2][1] + (p[2] - c[2]) * axes[2][2]);
            if (dd > theta && ms->vconc[cv[i]] > 0) mult[i] *= 2;
            if (dd > wd) wd = dd, worst = i;
        }
        if (worst == SIZE_MAX) break;
        if (iter == PUSH_ITERATIONS) through = m->vertices + 3 * (size_t)cv[worst]; /* last: through the worst */
    }
    {
        double l = sqrt(axes[2][0] * axes[2][0] + axes[2][1] * axes[2][1] + axes[2][2] * axes[2][2]);
        if (!(l > 0)) goto done;
        for (int k = 0; k < 3; k++) normal[k] = axes[2][k] / l;
        /* the plane is moved parallel to itself through the witness: the cut must resolve the
         * most concave vertex (a cycle or root cut near but not through it would leave it) */
        const double *x = ms->witness != UINT32_MAX ? m->vertices + 3 * (size_t)ms->witness : c;
        for (int k = 0; k < 3; k++) point[k] = x[k];
        if (fitted) {
            double s = (x[0] - c[0]) * normal[0] + (x[1] - c[1]) * normal[1] + (x[2] - c[2]) * normal[2];
            for (int k = 0; k < 3; k++) fitted[k] = x[k] - s * normal[k];
        }
        ok = 1;
    }
done:
    free(pts), free(w), free(mult);
    return ok;
}

acd_status acd3_global_cut_at_witness(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms,
                                      const acd3_gc_opts *o, acd3_poll *poll, acd3_global_cut *gc, double point[3],
                                      double normal[3], int *has_plane, acd_error *err) {
    memset(gc, 0, sizeof *gc);
    *has_plane = 0;
    acd3_cut_graph cg;
    acd_status st = acd3_cut_graph_build(m, g, ms, o, poll, &cg, err);
    if (st != ACD_OK) return st;
    st = acd3_global_cut_find(m, g, ms, &cg, o, gc, err);
    if (st == ACD_OK && gc->n >= 2) *has_plane = acd3_global_cut_plane(m, ms, &cg, gc, o, point, normal, NULL);
    acd3_cut_graph_free(&cg);
    return st;
}
