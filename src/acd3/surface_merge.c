/* acd3/surface_merge: joining adjacent surface parts measured within tau; see surface_merge.h. */
#include "acd3/surface_merge.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "acd3/measure.h"
#include "core/error.h"
#include "geom3/dijkstra.h"

/* Pairs measured at once when the cheapest bound is not measured yet (lazy joins). */
#define ACD3_SURFACE_MERGE_BATCH 4
/* Rounds of moves (refine) between rounds of joins. */
#define ACD3_SURFACE_MERGE_ROUNDS 8
/* Parts tried per nearly joinable pair (the witness's first). */
#define ACD3_SURFACE_MERGE_TRIES 12
/* A pair whose union measures within this many tau is nearly joinable: refine tries to move the
 * part holding its witness to a third group. */
#define ACD3_SURFACE_MERGE_NEAR 1.6

typedef struct vkey {
    double p[3];
    uint32_t idx; /* into the concatenation of the parts' vertices */
} vkey;

static int cmp_vkey(const void *a, const void *b) {
    const vkey *x = a, *y = b;
    for (int k = 0; k < 3; k++)
        if (x->p[k] != y->p[k]) return x->p[k] < y->p[k] ? -1 : 1;
    return x->idx < y->idx ? -1 : x->idx > y->idx;
}

typedef struct ekey {
    uint32_t a, b, part;
} ekey;

static int cmp_ekey(const void *a, const void *b) {
    const ekey *x = a, *y = b;
    if (x->a != y->a) return x->a < y->a ? -1 : 1;
    if (x->b != y->b) return x->b < y->b ? -1 : 1;
    return x->part < y->part ? -1 : x->part > y->part;
}

typedef struct pair {
    uint32_t a, b; /* groups (their lowest parts), a < b */
    double cost;   /* the union's concavity; INFINITY when it could not be measured */
    int valid;
    uint32_t wpart; /* the part holding the union's witness */
    int stale;      /* cost is a lower bound (the cost of a pair it grew from), not measured yet */
    acd_status st;
} pair;

static int cmp_u64(const void *a, const void *b) {
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

typedef struct ctx {
    const acd_mesh *parts;
    size_t nparts;
    const size_t *off;    /* per part: its first vertex in the concatenation */
    const uint32_t *gid;  /* per concatenated vertex: its position's id */
    const uint8_t *dup;   /* per concatenated vertex: its position occurs again in its part */
    size_t ngid;
    double eps, tol;
} ctx;

/* The welded union of the parts p with sel[p]; vpart (NULL: not wanted) receives per vertex of
 * the union its part (the first part holding it), allocated here. */
static acd_status weld_sel(const ctx *c, const uint8_t *sel, acd_mesh *out, uint32_t **vpart) {
    memset(out, 0, sizeof *out);
    if (vpart) *vpart = NULL;
    size_t nv = 0, nt = 0;
    for (size_t p = 0; p < c->nparts; p++)
        if (sel[p]) nv += c->parts[p].nvertices, nt += c->parts[p].ntriangles;
    uint32_t *map = malloc((c->ngid ? c->ngid : 1) * sizeof *map);
    uint32_t *local = malloc((nv ? nv : 1) * sizeof *local);
    out->vertices = malloc(3 * (nv ? nv : 1) * sizeof(double));
    out->triangles = malloc(3 * (nt ? nt : 1) * sizeof(uint32_t));
    uint32_t *vp = vpart ? malloc((nv ? nv : 1) * sizeof *vp) : NULL;
    if (!map || !local || !out->vertices || !out->triangles || nv >= UINT32_MAX || (vpart && !vp)) {
        free(map), free(local), free(vp);
        acd_mesh_free(out);
        return ACD_ERR_NOMEM;
    }
    for (size_t g = 0; g < c->ngid; g++) map[g] = UINT32_MAX;
    for (size_t p = 0; p < c->nparts; p++) {
        if (!sel[p]) continue;
        const acd_mesh *m = &c->parts[p];
        for (size_t v = 0; v < m->nvertices; v++) {
            size_t i = c->off[p] + v;
            uint32_t g = c->gid[i], id;
            if (!c->dup[i] && map[g] != UINT32_MAX) {
                id = map[g];
            } else {
                id = (uint32_t)out->nvertices++;
                memcpy(out->vertices + 3 * (size_t)id, m->vertices + 3 * v, sizeof(double[3]));
                if (vp) vp[id] = (uint32_t)p;
                if (!c->dup[i]) map[g] = id;
            }
            local[v] = id;
        }
        for (size_t t = 0; t < m->ntriangles; t++) {
            uint32_t x = local[m->triangles[3 * t]], y = local[m->triangles[3 * t + 1]], z = local[m->triangles[3 * t + 2]];
            uint32_t *q = out->triangles + 3 * out->ntriangles++;
            q[0] = x, q[1] = y, q[2] = z;
        }
    }
    free(map), free(local);
    if (vpart) *vpart = vp;
    return ACD_OK;
}

/* The selection of the parts whose group (gof) is a or b (b may be a), allocated; NULL out of
 * memory. */
static uint8_t *group_sel(const ctx *c, const uint32_t *gof, uint32_t a, uint32_t b) {
    uint8_t *sel = malloc(c->nparts ? c->nparts : 1);
    if (sel)
        for (size_t p = 0; p < c->nparts; p++) sel[p] = gof[p] == a || gof[p] == b;
    return sel;
}

/* The welded union of the parts whose group (gof) is a or b (b may be a). */
static acd_status weld(const ctx *c, const uint32_t *gof, uint32_t a, uint32_t b, acd_mesh *out) {
    uint8_t *sel = group_sel(c, gof, a, b);
    if (!sel) {
        memset(out, 0, sizeof *out);
        return ACD_ERR_NOMEM;
    }
    acd_status st = weld_sel(c, sel, out, NULL);
    free(sel);
    return st;
}

/* The concavity of the welded union of the parts p with sel[p] (INFINITY when it cannot be
 * measured) and the part holding its witness (*wpart; UINT32_MAX when none). */
static acd_status measure_sel(const ctx *c, const uint8_t *sel, double *conc, uint32_t *wpart) {
    acd_mesh u;
    uint32_t *vp = NULL;
    *conc = INFINITY;
    if (wpart) *wpart = UINT32_MAX;
    acd_status st = weld_sel(c, sel, &u, wpart ? &vp : NULL);
    if (st != ACD_OK) return st;
    acd_edge_graph g;
    acd_error err;
    st = acd_edge_graph_from_mesh(u.vertices, u.nvertices, u.triangles, u.ntriangles, &g, &err);
    if (st == ACD_OK) {
        acd3_measure ms;
        st = acd3_measure_compute(&u, &g, c->eps, c->tol, &ms, &err);
        if (st == ACD_OK) {
            *conc = ms.concavity;
            if (wpart && ms.witness != UINT32_MAX) *wpart = vp[ms.witness];
            acd3_measure_free(&ms);
        }
        acd_edge_graph_free(&g);
    }
    free(vp);
    acd_mesh_free(&u);
    return st == ACD_ERR_NOMEM ? st : ACD_OK; /* other failures: INFINITY */
}

static void score(const ctx *c, const uint32_t *gof, pair *pr) {
    pr->cost = INFINITY;
    pr->wpart = UINT32_MAX;
    uint8_t *sel = group_sel(c, gof, pr->a, pr->b);
    if (!sel) {
        pr->st = ACD_ERR_NOMEM;
        return;
    }
    pr->st = measure_sel(c, sel, &pr->cost, &pr->wpart);
    free(sel);
}

static acd_status score_all(const ctx *c, const uint32_t *gof, pair *prs, size_t p0, size_t p1, int threads) {
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && p1 - p0 > 1)
#endif
    for (long i = (long)p0; i < (long)p1; i++) score(c, gof, &prs[i]);
    (void)threads;
    for (size_t i = p0; i < p1; i++)
        if (prs[i].st != ACD_OK) return prs[i].st;
    return ACD_OK;
}

/* The order of the joins: cost, then the groups' ids. */
static int pair_less(const pair *p, const pair *q) {
    return p->cost < q->cost || (p->cost == q->cost && (p->a < q->a || (p->a == q->a && p->b < q->b)));
}

/* Measures the stale pairs among the valid ones with cost <= bound: the `batch` of smallest (cost,
 * then ids) when batch > 0, else all. Returns how many were measured via *n. */
static acd_status score_stale(const ctx *c, const uint32_t *gof, pair *prs, size_t npr, double bound, size_t batch,
                              int threads, size_t *n) {
    size_t *idx = malloc((npr ? npr : 1) * sizeof *idx), k = 0;
    if (!idx) return ACD_ERR_NOMEM;
    for (size_t i = 0; i < npr; i++) {
        if (!prs[i].valid || !prs[i].stale || !(prs[i].cost <= bound)) continue;
        size_t j = k++;
        /* insertion by (cost, a, b); only the batch is kept */
        while (j > 0 && pair_less(&prs[i], &prs[idx[j - 1]])) {
            if (!batch || j < batch) idx[j] = idx[j - 1];
            j--;
        }
        if (!batch || j < batch) idx[j] = i;
        if (batch && k > batch) k = batch;
    }
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && k > 1)
#endif
    for (long i = 0; i < (long)k; i++) score(c, gof, &prs[idx[i]]);
    (void)threads;
    acd_status st = ACD_OK;
    for (size_t i = 0; i < k; i++) {
        prs[idx[i]].stale = 0;
        if (prs[idx[i]].st != ACD_OK) st = prs[idx[i]].st;
    }
    free(idx);
    *n = k;
    return st;
}

/* Appends the pairs of group a with each neighbouring group (adj: the adjacent parts), by the
 * neighbours' lowest parts, each once (those already appended by this call). 0: out of memory. */
static int add_pairs(const uint32_t *gof, const uint64_t *adj, size_t nadj, uint32_t a, pair **prs, size_t *npr,
                     size_t *cappr) {
    size_t p0 = *npr;
    for (size_t i = 0; i < nadj; i++) {
        uint32_t x = gof[adj[i] >> 32], y = gof[adj[i] & 0xffffffffu];
        if (x == y || (x != a && y != a)) continue;
        uint32_t h = x == a ? y : x, lo = a < h ? a : h, hi = a < h ? h : a;
        int seen = 0;
        for (size_t k = p0; k < *npr && !seen; k++) seen = (*prs)[k].a == lo && (*prs)[k].b == hi;
        if (seen) continue;
        if (*npr == *cappr) {
            size_t nc = *cappr ? 2 * *cappr : 64;
            pair *np = realloc(*prs, nc * sizeof *np);
            if (!np) return 0;
            *prs = np, *cappr = nc;
        }
        pair *q = &(*prs)[(*npr)++];
        q->a = lo, q->b = hi, q->valid = 1, q->st = ACD_OK, q->wpart = UINT32_MAX, q->stale = 0;
    }
    return 1;
}

typedef struct refine_cand {
    size_t pr;
    double cost;
    uint32_t a, b;
} refine_cand;

static int cmp_refine_cand(const void *x, const void *y) {
    const refine_cand *p = x, *q = y;
    if (p->cost != q->cost) return p->cost < q->cost ? -1 : 1;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    return p->b < q->b ? -1 : p->b > q->b;
}

/* Whether part l of the pair of groups (a, b) can move to a third group C next to it (not touched
 * this round): (A u B) \ l is connected and measures within tau, and C u l measures within tau
 * (the cheapest C, then the lowest). Reads the groups only. */
typedef struct move_eval {
    int ok;
    uint32_t to;        /* C */
    double conc_to, conc_rest; /* C u l, (A u B) minus l */
    acd_status st;
} move_eval;

static void eval_move(const ctx *c, const uint32_t *gof, const size_t *nbo, const uint32_t *nb, uint32_t a, uint32_t b,
                      uint32_t l, double tau, const uint8_t *touched, move_eval *r) {
    size_t np = c->nparts;
    memset(r, 0, sizeof *r);
    r->st = ACD_OK;
    uint8_t *sel = malloc(np ? np : 1);
    uint32_t *queue = malloc((np ? np : 1) * sizeof *queue), *cs = malloc((np ? np : 1) * sizeof *cs);
    if (!sel || !queue || !cs) {
        r->st = ACD_ERR_NOMEM;
        goto out;
    }
    /* l is not its group's only part; (A u B) \ l connected */
    size_t in_u = 0, in_l = 0;
    for (size_t p = 0; p < np; p++) {
        sel[p] = (gof[p] == a || gof[p] == b) && p != l;
        in_u += sel[p];
        in_l += gof[p] == gof[l];
    }
    if (in_l < 2 || in_u < 2) goto out;
    {
        size_t qh = 0, qt = 0, s0 = 0;
        while (!sel[s0]) s0++;
        sel[s0] = 2, queue[qt++] = (uint32_t)s0;
        while (qh < qt) {
            uint32_t p = queue[qh++];
            for (size_t j = nbo[p]; j < nbo[p + 1]; j++)
                if (sel[nb[j]] == 1) sel[nb[j]] = 2, queue[qt++] = nb[j];
        }
        if (qt != in_u) goto out;
    }
    /* the groups C next to l, ascending */
    size_t ncs = 0;
    for (size_t j = nbo[l]; j < nbo[l + 1]; j++) {
        uint32_t g = gof[nb[j]];
        if (g == a || g == b || touched[g]) continue;
        int seen = 0;
        for (size_t i = 0; i < ncs && !seen; i++) seen = cs[i] == g;
        if (!seen) cs[ncs++] = g;
    }
    for (size_t i = 1; i < ncs; i++)
        for (size_t j = i; j > 0 && cs[j - 1] > cs[j]; j--) {
            uint32_t t = cs[j];
            cs[j] = cs[j - 1], cs[j - 1] = t;
        }
    double bestc = INFINITY, cu;
    uint32_t bestg = UINT32_MAX;
    for (size_t i = 0; i < ncs; i++) {
        for (size_t p = 0; p < np; p++) sel[p] = gof[p] == cs[i] || p == l;
        double cc;
        r->st = measure_sel(c, sel, &cc, NULL);
        if (r->st != ACD_OK) goto out;
        if (cc <= tau && cc < bestc) bestc = cc, bestg = cs[i];
    }
    if (bestg == UINT32_MAX) goto out;
    for (size_t p = 0; p < np; p++) sel[p] = (gof[p] == a || gof[p] == b) && p != l;
    r->st = measure_sel(c, sel, &cu, NULL);
    if (r->st != ACD_OK || !(cu <= tau)) goto out;
    r->ok = 1, r->to = bestg, r->conc_to = bestc, r->conc_rest = cu;
out:
    free(sel), free(queue), free(cs);
}

/* Makes the move eval_move found: the groups' new ids are their lowest parts. */
static void commit_move(size_t np, uint32_t *gof, double *gconc, uint8_t *touched, uint32_t a, uint32_t b, uint32_t l,
                        const move_eval *r) {
    uint32_t nu = UINT32_MAX, ncg = r->to < l ? r->to : l;
    for (size_t p = 0; p < np && nu == UINT32_MAX; p++)
        if ((gof[p] == a || gof[p] == b) && p != l) nu = (uint32_t)p;
    for (size_t p = 0; p < np; p++) {
        if (p == l || gof[p] == r->to) gof[p] = ncg;
        else if (gof[p] == a || gof[p] == b) gof[p] = nu;
    }
    gconc[nu] = r->conc_rest, gconc[ncg] = r->conc_to;
    touched[a] = touched[b] = touched[r->to] = touched[nu] = touched[ncg] = 1;
}

/* One round of moves. A pair of groups (A, B) whose union measures above tau but within
 * ACD3_SURFACE_MERGE_NEAR x tau (cheapest first) is joined when one of its parts l can go to a
 * third group C adjacent to it (eval_move): one group fewer. The parts tried, at most
 * ACD3_SURFACE_MERGE_TRIES: the one holding the union's witness, then those of A u B next to a
 * third group, ascending; the first that can move is moved. Groups touched by a move wait for the next round (touched[group id] = 1, old and new
 * ids). nbo/nb: the parts' neighbours (CSR). Sequential, so the same for any thread count. */
static acd_status refine(const ctx *c, uint32_t *gof, double *gconc, const size_t *nbo, const uint32_t *nb,
                         const pair *prs, size_t npr, double tau, uint8_t *touched, size_t *moved) {
    size_t np = c->nparts, nc = 0;
    refine_cand *cand = malloc((npr ? npr : 1) * sizeof *cand);
    uint32_t ls[ACD3_SURFACE_MERGE_TRIES];
    acd_status st = ACD_OK;
    if (!cand) {
        st = ACD_ERR_NOMEM;
        goto out;
    }
    for (size_t i = 0; i < npr; i++)
        if (prs[i].valid && !prs[i].stale && prs[i].cost > tau && prs[i].cost <= ACD3_SURFACE_MERGE_NEAR * tau &&
            prs[i].wpart != UINT32_MAX)
            cand[nc++] = (refine_cand){i, prs[i].cost, prs[i].a, prs[i].b};
    qsort(cand, nc, sizeof *cand, cmp_refine_cand);
    for (size_t k = 0; k < nc; k++) {
        const pair *pr = &prs[cand[k].pr];
        uint32_t a = pr->a, b = pr->b;
        if (touched[a] || touched[b] || (gof[pr->wpart] != a && gof[pr->wpart] != b)) continue;
        /* the parts to try: the witness's, then the parts of A u B next to a third group, ascending */
        size_t nls = 0;
        ls[nls++] = pr->wpart;
        for (size_t p = 0; p < np && nls < ACD3_SURFACE_MERGE_TRIES; p++) {
            if ((gof[p] != a && gof[p] != b) || p == pr->wpart) continue;
            int third = 0;
            for (size_t j = nbo[p]; j < nbo[p + 1] && !third; j++) third = gof[nb[j]] != a && gof[nb[j]] != b && !touched[gof[nb[j]]];
            if (third) ls[nls++] = (uint32_t)p;
        }
        for (size_t li = 0; li < nls; li++) {
            move_eval r;
            eval_move(c, gof, nbo, nb, a, b, ls[li], tau, touched, &r);
            if (r.st != ACD_OK) {
                st = r.st;
                goto out;
            }
            if (r.ok) {
                commit_move(np, gof, gconc, touched, a, b, ls[li], &r);
                (*moved)++;
                break;
            }
        }
    }
out:
    free(cand);
    return st;
}

void acd3_surface_merge_result_free(acd3_surface_merge_result *r) {
    if (!r) return;
    if (r->meshes)
        for (size_t g = 0; g < r->ngroups; g++) acd_mesh_free(&r->meshes[g]);
    free(r->meshes);
    free(r->group_of);
    free(r->group_size);
    free(r->concavity);
    memset(r, 0, sizeof *r);
}

acd_status acd3_surface_merge(const acd_mesh *parts, size_t nparts, double eps, double tau, double tol, int threads,
                              acd_progress_fn progress, void *progress_user, acd3_surface_merge_result *out,
                              acd_error *err) {
    memset(out, 0, sizeof *out);
    size_t nv = 0, ne = 0;
    for (size_t p = 0; p < nparts; p++) nv += parts[p].nvertices, ne += 3 * parts[p].ntriangles;
    size_t *off = malloc((nparts ? nparts : 1) * sizeof *off);
    vkey *vk = malloc((nv ? nv : 1) * sizeof *vk);
    uint32_t *gid = malloc((nv ? nv : 1) * sizeof *gid), *partof = malloc((nv ? nv : 1) * sizeof *partof);
    uint8_t *dup = calloc(nv ? nv : 1, 1);
    ekey *ek = malloc((ne ? ne : 1) * sizeof *ek);
    uint64_t *adj = NULL;
    uint32_t *gof = malloc((nparts ? nparts : 1) * sizeof *gof);
    double *gconc = calloc(nparts ? nparts : 1, sizeof *gconc);
    pair *prs = NULL;
    size_t npr = 0, cappr = 0, nadj = 0;
    size_t *nbo = calloc(nparts + 1, sizeof *nbo);
    uint32_t *nb = NULL;
    uint8_t *touched = calloc(nparts ? nparts : 1, 1);
    double *lb = malloc((nparts ? nparts : 1) * sizeof *lb);
    acd_status st = ACD_OK;
    if (!off || !vk || !gid || !partof || !dup || !ek || !gof || !gconc || !nbo || !touched || !lb || nv >= UINT32_MAX ||
        nparts >= UINT32_MAX) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory merging %zu surface parts", nparts);
        goto done;
    }
    /* position ids */
    nv = 0;
    for (size_t p = 0; p < nparts; p++) {
        off[p] = nv;
        for (size_t v = 0; v < parts[p].nvertices; v++, nv++) {
            memcpy(vk[nv].p, parts[p].vertices + 3 * v, sizeof(double[3]));
            vk[nv].idx = (uint32_t)nv;
            partof[nv] = (uint32_t)p;
        }
    }
    qsort(vk, nv, sizeof *vk, cmp_vkey);
    size_t ngid = 0;
    for (size_t i = 0; i < nv;) {
        size_t j = i;
        while (j < nv && memcmp(vk[j].p, vk[i].p, sizeof vk[i].p) == 0) j++;
        /* a part holding the position twice: those copies are not welded (sorted by index, so a
         * part's copies are next to each other) */
        for (size_t k = i; k < j; k++) {
            gid[vk[k].idx] = (uint32_t)ngid;
            if (k > i && partof[vk[k].idx] == partof[vk[k - 1].idx]) dup[vk[k].idx] = dup[vk[k - 1].idx] = 1;
        }
        ngid++;
        i = j;
    }
    /* adjacency: a shared edge */
    ne = 0;
    for (size_t p = 0; p < nparts; p++)
        for (size_t t = 0; t < parts[p].ntriangles; t++)
            for (int k = 0; k < 3; k++) {
                uint32_t x = gid[off[p] + parts[p].triangles[3 * t + k]], y = gid[off[p] + parts[p].triangles[3 * t + (k + 1) % 3]];
                ek[ne].a = x < y ? x : y;
                ek[ne].b = x < y ? y : x;
                ek[ne++].part = (uint32_t)p;
            }
    qsort(ek, ne, sizeof *ek, cmp_ekey);
    size_t capadj = 0;
    for (size_t i = 0; i < ne;) {
        size_t j = i;
        while (j < ne && ek[j].a == ek[i].a && ek[j].b == ek[i].b) j++;
        for (size_t x = i; x < j; x++)
            for (size_t y = x + 1; y < j; y++) {
                if (ek[x].part == ek[y].part) continue;
                if (nadj == capadj) {
                    capadj = capadj ? 2 * capadj : 256;
                    uint64_t *na = realloc(adj, capadj * sizeof *na);
                    if (!na) {
                        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory merging %zu surface parts", nparts);
                        goto done;
                    }
                    adj = na;
                }
                adj[nadj++] = ((uint64_t)ek[x].part << 32) | ek[y].part; /* x < y: part order */
            }
        i = j;
    }
    if (nadj) qsort(adj, nadj, sizeof *adj, cmp_u64);
    {
        size_t u = 0;
        for (size_t i = 0; i < nadj; i++)
            if (u == 0 || adj[i] != adj[u - 1]) adj[u++] = adj[i];
        nadj = u;
    }
    free(vk), vk = NULL;
    free(ek), ek = NULL;
    /* the parts' neighbours (CSR, ascending) */
    nb = malloc((nadj ? 2 * nadj : 1) * sizeof *nb);
    if (!nb) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory merging %zu surface parts", nparts);
        goto done;
    }
    for (size_t i = 0; i < nadj; i++) nbo[(adj[i] >> 32) + 1]++, nbo[(adj[i] & 0xffffffffu) + 1]++;
    for (size_t p = 0; p < nparts; p++) nbo[p + 1] += nbo[p];
    {
        size_t *fill = malloc((nparts ? nparts : 1) * sizeof *fill);
        if (!fill) {
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory merging %zu surface parts", nparts);
            goto done;
        }
        memcpy(fill, nbo, nparts * sizeof *fill);
        for (size_t i = 0; i < nadj; i++) { /* adj sorted by (x, y): each list ends up ascending */
            uint32_t x = (uint32_t)(adj[i] >> 32), y = (uint32_t)(adj[i] & 0xffffffffu);
            nb[fill[x]++] = y;
        }
        for (size_t i = 0; i < nadj; i++) {
            uint32_t x = (uint32_t)(adj[i] >> 32), y = (uint32_t)(adj[i] & 0xffffffffu);
            nb[fill[y]++] = x;
        }
        free(fill);
    }
    for (size_t p = 0; p < nparts; p++) gof[p] = (uint32_t)p, lb[p] = -1;
    const ctx c = {parts, nparts, off, gid, dup, ngid, eps, tol};
    /* the pairs of adjacent parts */
    cappr = nadj + 16;
    prs = malloc(cappr * sizeof *prs);
    if (!prs) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory merging %zu surface parts", nparts);
        goto done;
    }
    for (size_t i = 0; i < nadj; i++) {
        prs[npr].a = (uint32_t)(adj[i] >> 32);
        prs[npr].b = (uint32_t)(adj[i] & 0xffffffffu);
        prs[npr].valid = 1;
        prs[npr].wpart = UINT32_MAX;
        prs[npr].stale = 0;
        prs[npr++].st = ACD_OK;
    }
    st = score_all(&c, gof, prs, 0, npr, threads);
    if (st != ACD_OK) {
        st = acd_fail(err, st, "out of memory merging %zu surface parts", nparts);
        goto done;
    }
    for (int round = 0;; round++) {
        for (;;) {
            if (progress && progress(progress_user, -1.0, "merge: joining surface parts")) {
                st = acd_fail(err, ACD_ERR_CANCELLED, "cancelled (merge: joining surface parts, %zu joins made)",
                              out->merges);
                goto done;
            }
            size_t best = SIZE_MAX;
            for (size_t i = 0; i < npr; i++) {
                if (!prs[i].valid || !(prs[i].cost <= tau)) continue;
                if (best == SIZE_MAX || pair_less(&prs[i], &prs[best])) best = i;
            }
            if (best == SIZE_MAX) break;
            if (prs[best].stale) { /* the smallest bounds measured, a fixed batch (any thread count) */
                size_t n;
                st = score_stale(&c, gof, prs, npr, tau, ACD3_SURFACE_MERGE_BATCH, threads, &n);
                if (st != ACD_OK) {
                    st = acd_fail(err, st, "out of memory merging %zu surface parts", nparts);
                    goto done;
                }
                continue;
            }
            uint32_t a = prs[best].a, b = prs[best].b;
            gconc[a] = prs[best].cost;
            for (size_t p = 0; p < nparts; p++)
                if (gof[p] == b) gof[p] = a;
            out->merges++;
            /* the joined group's pair with a neighbour N is at least as concave as the pairs (A, N)
             * and (B, N) were (their largest cost is its bound until it is measured) */
            for (size_t i = 0; i < npr; i++)
                if (prs[i].valid && (prs[i].a == a || prs[i].b == a || prs[i].a == b || prs[i].b == b)) {
                    uint32_t o = prs[i].a == a || prs[i].a == b ? prs[i].b : prs[i].a;
                    if (o != a && o != b && (lb[o] < 0 || prs[i].cost > lb[o])) lb[o] = prs[i].cost;
                    prs[i].valid = 0;
                }
            size_t p0 = npr;
            if (!add_pairs(gof, adj, nadj, a, &prs, &npr, &cappr)) {
                st = acd_fail(err, ACD_ERR_NOMEM, "out of memory merging %zu surface parts", nparts);
                goto done;
            }
            for (size_t i = p0; i < npr; i++) {
                uint32_t o = prs[i].a == a ? prs[i].b : prs[i].a;
                if (lb[o] >= 0) prs[i].stale = 1, prs[i].cost = lb[o];
            }
            for (size_t i = p0; i < npr; i++) lb[prs[i].a] = lb[prs[i].b] = -1;
            for (size_t i = p0; i < npr; i++) /* (none without a bound: every adjacent pair has a pair) */
                if (!prs[i].stale) prs[i].stale = 1, prs[i].cost = 0;
            /* drop the invalid pairs now and then */
            if (npr > 4 * nadj + 64) {
                size_t u = 0;
                for (size_t i = 0; i < npr; i++)
                    if (prs[i].valid) prs[u++] = prs[i];
                npr = u;
            }
        }
        /* no pair joinable: move a part out of a pair that is nearly joinable (refine), then join again */
        if (round >= ACD3_SURFACE_MERGE_ROUNDS) break;
        {
            size_t n;
            st = score_stale(&c, gof, prs, npr, ACD3_SURFACE_MERGE_NEAR * tau, 0, threads, &n);
            if (st != ACD_OK) {
                st = acd_fail(err, st, "out of memory merging %zu surface parts", nparts);
                goto done;
            }
        }
        size_t moved = 0;
        st = refine(&c, gof, gconc, nbo, nb, prs, npr, tau, touched, &moved);
        if (st != ACD_OK) {
            st = acd_fail(err, st, "out of memory merging %zu surface parts", nparts);
            goto done;
        }
        if (!moved) break;
        out->moves += moved;
        for (size_t i = 0; i < npr; i++)
            if (touched[prs[i].a] || touched[prs[i].b]) prs[i].valid = 0;
        size_t p0 = npr;
        for (size_t g = 0; g < nparts; g++)
            if (touched[g] && gof[g] == g && !add_pairs(gof, adj, nadj, (uint32_t)g, &prs, &npr, &cappr)) {
                st = acd_fail(err, ACD_ERR_NOMEM, "out of memory merging %zu surface parts", nparts);
                goto done;
            }
        memset(touched, 0, nparts);
        st = score_all(&c, gof, prs, p0, npr, threads);
        if (st != ACD_OK) {
            st = acd_fail(err, st, "out of memory merging %zu surface parts", nparts);
            goto done;
        }
    }
    /* groups numbered by their lowest part */
    out->group_of = malloc((nparts ? nparts : 1) * sizeof *out->group_of);
    uint32_t *num = malloc((nparts ? nparts : 1) * sizeof *num);
    if (!out->group_of || !num) {
        free(num);
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory merging %zu surface parts", nparts);
        goto done;
    }
    for (size_t p = 0; p < nparts; p++) num[p] = UINT32_MAX;
    for (size_t p = 0; p < nparts; p++) {
        if (num[gof[p]] == UINT32_MAX) num[gof[p]] = (uint32_t)out->ngroups++;
        out->group_of[p] = num[gof[p]];
    }
    out->group_size = calloc(out->ngroups ? out->ngroups : 1, sizeof *out->group_size);
    out->concavity = calloc(out->ngroups ? out->ngroups : 1, sizeof *out->concavity);
    out->meshes = calloc(out->ngroups ? out->ngroups : 1, sizeof *out->meshes);
    if (!out->group_size || !out->concavity || !out->meshes) {
        free(num);
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory merging %zu surface parts", nparts);
        goto done;
    }
    for (size_t p = 0; p < nparts; p++) out->group_size[out->group_of[p]]++;
    for (size_t p = 0; p < nparts && st == ACD_OK; p++) {
        if (gof[p] != p) continue; /* p is its group's lowest part */
        uint32_t g = num[p];
        if (out->group_size[g] < 2) continue;
        out->concavity[g] = gconc[p];
        if (weld(&c, gof, (uint32_t)p, (uint32_t)p, &out->meshes[g]) != ACD_OK)
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory merging %zu surface parts", nparts);
    }
    free(num);
done:
    free(off), free(vk), free(gid), free(partof), free(dup), free(ek), free(adj), free(gof), free(gconc), free(prs);
    free(nbo), free(nb), free(touched), free(lb);
    if (st != ACD_OK) acd3_surface_merge_result_free(out);
    return st;
}
