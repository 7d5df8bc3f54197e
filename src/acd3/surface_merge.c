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

/* The welded union of the parts whose group (gof) is a or b (b may be a). */
static acd_status weld(const ctx *c, const uint32_t *gof, uint32_t a, uint32_t b, acd_mesh *out) {
    memset(out, 0, sizeof *out);
    size_t nv = 0, nt = 0;
    for (size_t p = 0; p < c->nparts; p++)
        if (gof[p] == a || gof[p] == b) nv += c->parts[p].nvertices, nt += c->parts[p].ntriangles;
    uint32_t *map = malloc((c->ngid ? c->ngid : 1) * sizeof *map);
    uint32_t *local = malloc((nv ? nv : 1) * sizeof *local);
    out->vertices = malloc(3 * (nv ? nv : 1) * sizeof(double));
    out->triangles = malloc(3 * (nt ? nt : 1) * sizeof(uint32_t));
    if (!map || !local || !out->vertices || !out->triangles || nv >= UINT32_MAX) {
        free(map), free(local);
        acd_mesh_free(out);
        return ACD_ERR_NOMEM;
    }
    for (size_t g = 0; g < c->ngid; g++) map[g] = UINT32_MAX;
    for (size_t p = 0; p < c->nparts; p++) {
        if (gof[p] != a && gof[p] != b) continue;
        const acd_mesh *m = &c->parts[p];
        for (size_t v = 0; v < m->nvertices; v++) {
            size_t i = c->off[p] + v;
            uint32_t g = c->gid[i], id;
            if (!c->dup[i] && map[g] != UINT32_MAX) {
                id = map[g];
            } else {
                id = (uint32_t)out->nvertices++;
                memcpy(out->vertices + 3 * (size_t)id, m->vertices + 3 * v, sizeof(double[3]));
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
    return ACD_OK;
}

static void score(const ctx *c, const uint32_t *gof, pair *pr) {
    acd_mesh u;
    pr->cost = INFINITY;
    pr->st = weld(c, gof, pr->a, pr->b, &u);
    if (pr->st != ACD_OK) return;
    acd_edge_graph g;
    acd_error err;
    acd_status st = acd_edge_graph_from_mesh(u.vertices, u.nvertices, u.triangles, u.ntriangles, &g, &err);
    if (st == ACD_OK) {
        acd3_measure ms;
        st = acd3_measure_compute(&u, &g, c->eps, c->tol, &ms, &err);
        if (st == ACD_OK) {
            pr->cost = ms.concavity;
            acd3_measure_free(&ms);
        }
        acd_edge_graph_free(&g);
    }
    if (st == ACD_ERR_NOMEM) pr->st = st; /* other failures: the pair is not joined */
    acd_mesh_free(&u);
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
                              acd3_surface_merge_result *out, acd_error *err) {
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
    acd_status st = ACD_OK;
    if (!off || !vk || !gid || !partof || !dup || !ek || !gof || !gconc || nv >= UINT32_MAX || nparts >= UINT32_MAX) {
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
    for (size_t p = 0; p < nparts; p++) gof[p] = (uint32_t)p;
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
        prs[npr++].st = ACD_OK;
    }
    st = score_all(&c, gof, prs, 0, npr, threads);
    if (st != ACD_OK) {
        st = acd_fail(err, st, "out of memory merging %zu surface parts", nparts);
        goto done;
    }
    for (;;) {
        size_t best = SIZE_MAX;
        for (size_t i = 0; i < npr; i++) {
            if (!prs[i].valid || !(prs[i].cost <= tau)) continue;
            if (best == SIZE_MAX || prs[i].cost < prs[best].cost ||
                (prs[i].cost == prs[best].cost &&
                 (prs[i].a < prs[best].a || (prs[i].a == prs[best].a && prs[i].b < prs[best].b))))
                best = i;
        }
        if (best == SIZE_MAX) break;
        uint32_t a = prs[best].a, b = prs[best].b;
        gconc[a] = prs[best].cost;
        for (size_t p = 0; p < nparts; p++)
            if (gof[p] == b) gof[p] = a;
        out->merges++;
        for (size_t i = 0; i < npr; i++)
            if (prs[i].a == a || prs[i].b == a || prs[i].a == b || prs[i].b == b) prs[i].valid = 0;
        /* the new group's neighbours (by their lowest parts), in order */
        size_t p0 = npr;
        for (size_t i = 0; i < nadj; i++) {
            uint32_t x = gof[adj[i] >> 32], y = gof[adj[i] & 0xffffffffu];
            if (x == y || (x != a && y != a)) continue;
            uint32_t h = x == a ? y : x, lo = a < h ? a : h, hi = a < h ? h : a;
            int seen = 0;
            for (size_t k = p0; k < npr && !seen; k++) seen = prs[k].a == lo && prs[k].b == hi;
            if (seen) continue;
            if (npr == cappr) {
                cappr *= 2;
                pair *np = realloc(prs, cappr * sizeof *np);
                if (!np) {
                    st = acd_fail(err, ACD_ERR_NOMEM, "out of memory merging %zu surface parts", nparts);
                    goto done;
                }
                prs = np;
            }
            prs[npr].a = lo, prs[npr].b = hi, prs[npr].valid = 1, prs[npr++].st = ACD_OK;
        }
        st = score_all(&c, gof, prs, p0, npr, threads);
        if (st != ACD_OK) {
            st = acd_fail(err, st, "out of memory merging %zu surface parts", nparts);
            goto done;
        }
        /* drop the invalid pairs now and then */
        if (npr > 4 * nadj + 64) {
            size_t u = 0;
            for (size_t i = 0; i < npr; i++)
                if (prs[i].valid) prs[u++] = prs[i];
            npr = u;
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
    if (st != ACD_OK) acd3_surface_merge_result_free(out);
    return st;
}
