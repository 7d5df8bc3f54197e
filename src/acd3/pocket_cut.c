/* acd3/pocket_cut: boundary chains, knots, pocket cuts and the cut graph; see pocket_cut.h. */
#include "acd3/pocket_cut.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd3/knots.h"
#include "core/error.h"
#include "core/u32vec.h"

/* Hungarian costs standing for "no path". */
#define NO_PATH_COST 1e100
/* Guards of the cut weight: sum concavity + ETA_CONC * tau; gamma + ETA_CURV per edge (radians:
 * an edge turning less than about 3 degrees counts as flat, so that W = omega / gamma stays
 * finite on flat paths). */
#define ETA_CONC 1e-3
#define ETA_CURV 0.05
/* Valley path cost: |uv| / (VALLEY_ETA * tau + mean concavity). */
#define VALLEY_ETA 1e-3

void acd3_cut_graph_free(acd3_cut_graph *cg) {
    if (!cg) return;
    free(cg->chain_off), free(cg->chain_v), free(cg->chain_region), free(cg->chain_closed);
    free(cg->knot_v), free(cg->knot_chain);
    free(cg->cuts), free(cg->cut_v);
    free(cg->knot_row), free(cg->knot_cut);
    free(cg->face_of), free(cg->vf_row), free(cg->vf);
    memset(cg, 0, sizeof *cg);
}

static void tri_normal(const acd_mesh *m, uint32_t f, double n[3]) {
    const double *a = m->vertices + 3 * (size_t)m->triangles[3 * f], *b = m->vertices + 3 * (size_t)m->triangles[3 * f + 1],
                 *c = m->vertices + 3 * (size_t)m->triangles[3 * f + 2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (l > 0) n[0] /= l, n[1] /= l, n[2] /= l;
}

double acd3_valley_cost(const acd_edge_graph *g, const double *vconc, uint32_t e, double tau) {
    double c = 0.5 * (vconc[g->edge_v[2 * (size_t)e]] + vconc[g->edge_v[2 * (size_t)e + 1]]);
    double eta = VALLEY_ETA * tau;
    if (!(eta > 0)) eta = 1e-300;
    return g->length[e] / (eta + c);
}

double acd3_cut_weight(const acd_mesh *m, const acd_edge_graph *g, const uint32_t *face_of, const double *vconc,
                       const uint32_t *p, size_t n, const acd3_gc_opts *o) {
    double sc = 0, gamma = 0;
    for (size_t i = 0; i < n; i++) sc += vconc[p[i]];
    for (size_t i = 0; i + 1 < n; i++) {
        gamma += ETA_CURV;
        uint32_t e = acd_edge_graph_find(g, p[i], p[i + 1]);
        if (e == ACD_NO_VERTEX) continue;
        uint32_t f0 = face_of[2 * (size_t)e], f1 = face_of[2 * (size_t)e + 1];
        if (f0 == UINT32_MAX || f1 == UINT32_MAX) continue;
        double n0[3], n1[3];
        tri_normal(m, f0, n0);
        tri_normal(m, f1, n1);
        double c = n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2];
        if (c > 1) c = 1;
        if (c < -1) c = -1;
        gamma += acos(c);
    }
    double omega = (double)n / (sc + ETA_CONC * o->tau + 1e-300);
    return o->weight == ACD3D_WEIGHT_PRODUCT ? omega * gamma : omega / gamma;
}

uint32_t acd3_vertex_region(const acd_mesh *m, const acd3_measure *ms, const acd3_cut_graph *cg, uint32_t v) {
    uint32_t best = UINT32_MAX;
    double bd = -INFINITY;
    for (size_t k = cg->vf_row[v]; k < cg->vf_row[v + 1]; k++) {
        uint32_t r = ms->face_region[cg->vf[k]], p = ms->region_patch[r];
        if (p == UINT32_MAX) continue;
        double d = acd3_patch_depth(&ms->patches, p, m->vertices + 3 * (size_t)v);
        if (d > bd || (d == bd && r < best)) {
            bd = d;
            best = r;
        }
    }
    return best;
}

/* Minimum-cost assignment of the rows of c (n x mm, row-major, n <= mm) to distinct columns
 * (Hungarian method with potentials, O(n^2 mm)). row_col[i] = the column of row i. */
static int hungarian(const double *c, size_t n, size_t mm, size_t *row_col) {
    double *u = calloc(n + 1, sizeof *u), *v = calloc(mm + 1, sizeof *v), *minv = malloc((mm + 1) * sizeof *minv);
    size_t *p = calloc(mm + 1, sizeof *p), *way = calloc(mm + 1, sizeof *way);
    unsigned char *used = malloc(mm + 1);
    int ok = u && v && minv && p && way && used;
    for (size_t i = 1; ok && i <= n; i++) {
        p[0] = i;
        size_t j0 = 0;
        for (size_t j = 0; j <= mm; j++) minv[j] = INFINITY, used[j] = 0;
        do {
            used[j0] = 1;
            size_t i0 = p[j0], j1 = 0;
            double delta = INFINITY;
            for (size_t j = 1; j <= mm; j++) {
                if (used[j]) continue;
                double cur = c[(i0 - 1) * mm + (j - 1)] - u[i0] - v[j];
                if (cur < minv[j]) minv[j] = cur, way[j] = j0;
                if (minv[j] < delta) delta = minv[j], j1 = j;
            }
            for (size_t j = 0; j <= mm; j++)
                if (used[j]) u[p[j]] += delta, v[j] -= delta;
                else minv[j] -= delta;
            j0 = j1;
        } while (p[j0] != 0);
        do {
            size_t j1 = way[j0];
            p[j0] = p[j1];
            j0 = j1;
        } while (j0);
    }
    if (ok)
        for (size_t j = 1; j <= mm; j++)
            if (p[j]) row_col[p[j] - 1] = j - 1;
    free(u), free(v), free(minv), free(p), free(way), free(used);
    return ok;
}

/* A candidate cut during construction. */
typedef struct cand {
    uint32_t a, b; /* knot ids */
    size_t off, n; /* in the candidate pool */
    double w;
    int keep, crossed;
} cand;

typedef struct rk { /* (region, knot) */
    uint32_t region, knot;
} rk;

static int cmp_rk(const void *x, const void *y) {
    const rk *a = x, *b = y;
    if (a->region != b->region) return a->region < b->region ? -1 : 1;
    return (a->knot > b->knot) - (a->knot < b->knot);
}

/* Traces boundary chains from the barrier edges that separate two regions. */
static int trace_chains(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms, acd3_cut_graph *cg) {
    size_t nv = m->nvertices, ne = g->nedges;
    uint8_t *bnd = calloc(ne ? ne : 1, 1), *seen = calloc(ne ? ne : 1, 1);
    uint32_t *bdeg = calloc(nv ? nv : 1, sizeof *bdeg);
    acd_u32vec cv = {0}, off = {0}, creg = {0};
    int ok = bnd && seen && bdeg;
    if (!ok) goto done;
    for (size_t e = 0; e < ne; e++) {
        if (!ms->edge_barrier[e]) continue;
        uint32_t f0 = cg->face_of[2 * e], f1 = cg->face_of[2 * e + 1];
        if (f0 == UINT32_MAX || f1 == UINT32_MAX || ms->face_region[f0] == ms->face_region[f1]) continue;
        bnd[e] = 1;
        bdeg[g->edge_v[2 * e]]++;
        bdeg[g->edge_v[2 * e + 1]]++;
    }
    ok = acd_u32vec_push(&off, 0);
    for (int pass = 0; pass < 2 && ok; pass++) {
        /* pass 0: chains from branch points (vertices of boundary degree != 2); pass 1: loops */
        for (size_t s = 0; s < (pass ? ne : nv) && ok; s++) {
            uint32_t start;
            if (pass == 0) {
                if (bdeg[s] == 0 || bdeg[s] == 2) continue;
                start = (uint32_t)s;
            } else {
                if (!bnd[s] || seen[s]) continue;
                start = g->edge_v[2 * s];
            }
            for (size_t k = g->row[start]; k < g->row[start + 1] && ok; k++) {
                uint32_t e = g->adj_edge[k];
                if (!bnd[e] || seen[e]) continue;
                uint32_t f0 = cg->face_of[2 * (size_t)e], f1 = cg->face_of[2 * (size_t)e + 1];
                uint32_t r0 = ms->face_region[f0], r1 = ms->face_region[f1];
                if (r0 > r1) {
                    uint32_t t = r0;
                    r0 = r1, r1 = t;
                }
                ok = acd_u32vec_push(&cv, start);
                uint32_t cur = start;
                while (ok) {
                    seen[e] = 1;
                    uint32_t nx = g->edge_v[2 * (size_t)e] == cur ? g->edge_v[2 * (size_t)e + 1] : g->edge_v[2 * (size_t)e];
                    ok = acd_u32vec_push(&cv, nx);
                    if (nx == start || bdeg[nx] != 2) break;
                    uint32_t ne2 = ACD_NO_VERTEX;
                    for (size_t q = g->row[nx]; q < g->row[nx + 1]; q++) {
                        uint32_t e2 = g->adj_edge[q];
                        if (bnd[e2] && !seen[e2]) {
                            ne2 = e2;
                            break;
                        }
                    }
                    if (ne2 == ACD_NO_VERTEX) break;
                    e = ne2;
                    cur = nx;
                }
                ok = ok && acd_u32vec_push(&off, (uint32_t)cv.n) && acd_u32vec_push(&creg, r0) && acd_u32vec_push(&creg, r1);
                if (pass == 1) break; /* one loop per start */
            }
        }
    }
    if (!ok) goto done;
    cg->nchains = off.n - 1;
    cg->chain_off = malloc(off.n * sizeof *cg->chain_off);
    cg->chain_closed = malloc(cg->nchains ? cg->nchains : 1);
    ok = cg->chain_off && cg->chain_closed;
    if (!ok) goto done;
    for (size_t i = 0; i < off.n; i++) cg->chain_off[i] = off.a[i];
    for (size_t c = 0; c < cg->nchains; c++)
        cg->chain_closed[c] = cv.a[cg->chain_off[c]] == cv.a[cg->chain_off[c + 1] - 1];
    cg->chain_v = cv.a, cv.a = NULL;
    cg->chain_region = creg.a, creg.a = NULL;
done:
    free(bnd), free(seen), free(bdeg), free(cv.a), free(off.a), free(creg.a);
    return ok;
}

static int find_all_knots(const acd_mesh *m, const acd3_measure *ms, const acd3_gc_opts *o, acd3_cut_graph *cg) {
    size_t total = cg->chain_off[cg->nchains];
    double *pts = malloc(3 * (total ? total : 1) * sizeof *pts), *conc = malloc((total ? total : 1) * sizeof *conc);
    uint32_t *idx = malloc((total ? total : 1) * sizeof *idx);
    acd_u32vec kv = {0}, kc = {0};
    int ok = pts && conc && idx;
    for (size_t c = 0; ok && c < cg->nchains; c++) {
        size_t o0 = cg->chain_off[c], n = cg->chain_off[c + 1] - o0;
        if (n < 3) continue;
        double arc = 0;
        for (size_t i = 0; i < n; i++) {
            uint32_t v = cg->chain_v[o0 + i];
            memcpy(pts + 3 * i, m->vertices + 3 * (size_t)v, sizeof(double[3]));
            conc[i] = ms->vconc[v];
            if (i) {
                const double *a = pts + 3 * (i - 1), *b = pts + 3 * i;
                arc += sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
            }
        }
        const double *a = pts, *b = pts + 3 * (n - 1);
        double chord = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
        /* |e|: the hull edge's length, which the chord between the chain's hull vertices is;
         * the arc length for a loop */
        double len = cg->chain_closed[c] || chord < 0.5 * arc ? arc : chord;
        size_t nk = acd3_find_knots(pts, conc, n, len, o->delta, idx);
        if (nk == (size_t)-1) {
            ok = 0;
            break;
        }
        for (size_t i = 0; i < nk && ok; i++) ok = acd_u32vec_push(&kv, cg->chain_v[o0 + idx[i]]) && acd_u32vec_push(&kc, (uint32_t)c);
    }
    if (ok) {
        cg->nknots = kv.n;
        cg->knot_v = kv.a, kv.a = NULL;
        cg->knot_chain = kc.a, kc.a = NULL;
    }
    free(pts), free(conc), free(idx), free(kv.a), free(kc.a);
    return ok;
}

/* Flood-fills the faces of region r (listed in rf[0..nrf)) without crossing the edges marked in
 * cut_edge; label[f] = component (faces outside r keep UINT32_MAX). */
static void flood_split(const uint32_t *fe, const acd3_measure *ms, const acd3_cut_graph *cg,
                        uint32_t r, const uint32_t *rf, size_t nrf, const uint8_t *cut_edge, uint32_t *label,
                        uint32_t *queue) {
    for (size_t i = 0; i < nrf; i++) label[rf[i]] = UINT32_MAX;
    uint32_t nl = 0;
    for (size_t i = 0; i < nrf; i++) {
        if (label[rf[i]] != UINT32_MAX) continue;
        size_t qh = 0, qt = 0;
        queue[qt++] = rf[i];
        label[rf[i]] = nl;
        while (qh < qt) {
            uint32_t f = queue[qh++];
            for (int k = 0; k < 3; k++) {
                uint32_t e = fe[3 * (size_t)f + k];
                if (e == ACD_NO_VERTEX || cut_edge[e]) continue;
                for (int s = 0; s < 2; s++) {
                    uint32_t h = cg->face_of[2 * (size_t)e + s];
                    if (h != UINT32_MAX && ms->face_region[h] == r && label[h] == UINT32_MAX) {
                        label[h] = nl;
                        queue[qt++] = h;
                    }
                }
            }
        }
        nl++;
    }
}

acd_status acd3_cut_graph_build(const acd_mesh *m, const acd_edge_graph *g, const acd3_measure *ms,
                                const acd3_gc_opts *o, acd3_poll *poll, acd3_cut_graph *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    size_t nv = m->nvertices, nf = m->ntriangles, ne = g->nedges, nr = ms->nregions;
    acd_status st = ACD_OK;
    int cancelled = 0; /* poll said stop (ok = 0 too) */
    if (ms->face_of) { /* the measure's (the same graph and mesh) */
        out->face_of = malloc((2 * ne + 1) * sizeof *out->face_of);
        if (!out->face_of) return acd_fail(err, ACD_ERR_NOMEM, "out of memory for %zu edges", ne);
        memcpy(out->face_of, ms->face_of, 2 * ne * sizeof *out->face_of);
    } else {
        st = acd3_edge_faces(m, g, &out->face_of, err);
    }
    if (st != ACD_OK) return st;
    /* vertex -> faces */
    out->vf_row = calloc(nv + 1, sizeof *out->vf_row);
    out->vf = malloc((nf ? 3 * nf : 1) * sizeof *out->vf);
    if (!out->vf_row || !out->vf) goto nomem;
    for (size_t i = 0; i < 3 * nf; i++) out->vf_row[m->triangles[i] + 1]++;
    for (size_t v = 0; v < nv; v++) out->vf_row[v + 1] += out->vf_row[v];
    {
        size_t *fill = malloc((nv ? nv : 1) * sizeof *fill);
        if (!fill) goto nomem;
        memcpy(fill, out->vf_row, nv * sizeof *fill);
        for (size_t f = 0; f < nf; f++)
            for (int k = 0; k < 3; k++) out->vf[fill[m->triangles[3 * f + k]]++] = (uint32_t)f;
        free(fill);
    }
    if (ms->hull.dim < 3 || nr == 0) return ACD_OK;
    if (!trace_chains(m, g, ms, out) || !find_all_knots(m, ms, o, out)) goto nomem;

    /* (region, knot) incidences, by region */
    size_t nrk = 2 * out->nknots;
    rk *rks = malloc((nrk ? nrk : 1) * sizeof *rks);
    /* faces by region */
    size_t *rrow = calloc(nr + 1, sizeof *rrow);
    uint32_t *rface = malloc((nf ? nf : 1) * sizeof *rface), *label = malloc((nf ? nf : 1) * sizeof *label),
             *queue = malloc((nf ? nf : 1) * sizeof *queue),
             *fe = ms->face_edge ? NULL : malloc((nf ? 3 * nf : 1) * sizeof *fe);
    double *wcost = malloc((ne ? ne : 1) * sizeof *wcost);
    uint8_t *allowed = calloc(nv ? nv : 1, 1), *cut_edge = calloc(ne ? ne : 1, 1);
    uint8_t *on_cut = calloc(nv ? nv : 1, 1); /* the vertices of the kept cut being compared (below) */
    acd_u32vec pool = {0}, kept = {0};
    acd_sp_ws sp; /* the knot-to-knot searches, reused across sources */
    memset(&sp, 0, sizeof sp);
    cand *cands = NULL;
    size_t ncand = 0, capcand = 0;
    acd3_pocket_cut *cuts = NULL;
    size_t ncuts = 0, capcuts = 0, ncutv = 0;
    int ok = rks && rrow && rface && label && queue && (fe || ms->face_edge) && wcost && allowed && cut_edge && on_cut;
    if (!ok) goto build_done;
    /* fev: the edge of each face side (the measure's, or fe found once when first needed: the
     * floods below visit a region's faces per kept cut) */
    const uint32_t *fev = ms->face_edge;
    int fe_ready = fev != NULL;
    for (size_t k = 0; k < out->nknots; k++) {
        uint32_t c = out->knot_chain[k];
        rks[2 * k] = (rk){out->chain_region[2 * c], (uint32_t)k};
        rks[2 * k + 1] = (rk){out->chain_region[2 * c + 1], (uint32_t)k};
    }
    if (nrk) qsort(rks, nrk, sizeof *rks, cmp_rk);
    for (size_t f = 0; f < nf; f++) rrow[ms->face_region[f] + 1]++;
    for (size_t r = 0; r < nr; r++) rrow[r + 1] += rrow[r];
    {
        size_t *fill = malloc((nr ? nr : 1) * sizeof *fill);
        if (!fill) {
            ok = 0;
            goto build_done;
        }
        memcpy(fill, rrow, nr * sizeof *fill);
        for (size_t f = 0; f < nf; f++) rface[fill[ms->face_region[f]]++] = (uint32_t)f;
        free(fill);
    }
    for (size_t e = 0; e < ne; e++) wcost[e] = acd3_valley_cost(g, ms->vconc, (uint32_t)e, o->tau);
    int weights_ok = 1; /* (acd_dijkstra's check, once) */
    for (size_t e = 0; e < ne; e++)
        if (!(wcost[e] >= 0) || !isfinite(wcost[e])) weights_ok = 0;
    if (acd_sp_ws_init(&sp, nv, NULL) != ACD_OK) {
        ok = 0;
        goto build_done;
    }

    for (size_t i0 = 0; i0 < nrk && ok;) {
        size_t i1 = i0;
        uint32_t r = rks[i0].region;
        while (i1 < nrk && rks[i1].region == r) i1++;
        size_t K = i1 - i0;
        const rk *kr = rks + i0;
        i0 = i1;
        if (K < 2) continue;
        /* knots on at least two chains */
        int multi = 0;
        for (size_t i = 1; i < K; i++) multi |= out->knot_chain[kr[i].knot] != out->knot_chain[kr[0].knot];
        if (!multi) continue;
        const uint32_t *rf = rface + rrow[r];
        size_t nrf = rrow[r + 1] - rrow[r];
        for (size_t i = 0; i < nrf; i++)
            for (int k = 0; k < 3; k++) allowed[m->triangles[3 * rf[i] + k]] = 1;
        /* candidate cuts: cheapest valley path between every two knots on different chains */
        ncand = 0;
        pool.n = 0;
        double *wm = malloc(K * K * sizeof *wm);
        size_t *cid = malloc(K * K * sizeof *cid);
        uint32_t *tgt = malloc(K * sizeof *tgt);
        if (!wm || !cid || !tgt) {
            free(wm), free(cid), free(tgt);
            ok = 0;
            break;
        }
        for (size_t i = 0; i < K * K; i++) wm[i] = NO_PATH_COST, cid[i] = SIZE_MAX;
        for (size_t i = 0; i < K && ok; i++) {
            if (acd3_poll_stop(poll)) {
                cancelled = 1, ok = 0;
                break;
            }
            uint32_t src = out->knot_v[kr[i].knot];
            /* the search stops once the knots it pairs with (below) are settled */
            size_t nt = 0;
            for (size_t j = i + 1; j < K; j++)
                if (out->knot_chain[kr[j].knot] != out->knot_chain[kr[i].knot] && out->knot_v[kr[j].knot] != src)
                    tgt[nt++] = out->knot_v[kr[j].knot];
            acd_sp_limits lim = {.weights = wcost, .vertex_allowed = allowed, .targets = tgt, .ntargets = nt};
            if (!weights_ok || !acd_sp_ws_run(&sp, g, src, &lim)) {
                ok = 0;
                break;
            }
            for (size_t j = i + 1; j < K && ok; j++) {
                if (out->knot_chain[kr[j].knot] == out->knot_chain[kr[i].knot]) continue;
                uint32_t dst = out->knot_v[kr[j].knot];
                if (dst == src || !isfinite(acd_sp_ws_dist(&sp, dst))) continue;
                size_t off = pool.n, n = 0;
                for (uint32_t v = dst; v != ACD_NO_VERTEX; v = sp.pred[v]) {
                    ok = acd_u32vec_push(&pool, v);
                    if (!ok) break;
                    n++;
                }
                if (!ok) break;
                /* reverse: src first */
                for (size_t a = off, b = off + n - 1; a < b; a++, b--) {
                    uint32_t tmp = pool.a[a];
                    pool.a[a] = pool.a[b], pool.a[b] = tmp;
                }
                if (ncand == capcand) {
                    capcand = capcand ? 2 * capcand : 64;
                    cand *nc = realloc(cands, capcand * sizeof *nc);
                    if (!nc) {
                        ok = 0;
                        break;
                    }
                    cands = nc;
                }
                double w = acd3_cut_weight(m, g, out->face_of, ms->vconc, pool.a + off, n, o);
                cands[ncand] = (cand){kr[i].knot, kr[j].knot, off, n, w, 0, 0};
                wm[i * K + j] = wm[j * K + i] = w;
                cid[i * K + j] = cid[j * K + i] = ncand;
                ncand++;
            }
        }
        for (size_t i = 0; i < nrf; i++)
            for (int k = 0; k < 3; k++) allowed[m->triangles[3 * rf[i] + k]] = 0;
        /* per pair of chains: minimum-weight bipartite matching of their knots */
        for (size_t a = 0; a < K && ok; a++) {
            uint32_t ca = out->knot_chain[kr[a].knot];
            int first_a = 1;
            for (size_t q = 0; q < a; q++) first_a &= out->knot_chain[kr[q].knot] != ca;
            if (!first_a) continue;
            for (size_t b = 0; b < K && ok; b++) {
                uint32_t cb = out->knot_chain[kr[b].knot];
                if (cb <= ca) continue;
                int first_b = 1;
                for (size_t q = 0; q < b; q++) first_b &= out->knot_chain[kr[q].knot] != cb;
                if (!first_b) continue;
                size_t na = 0, nb = 0, ia[64], ib[64];
                for (size_t q = 0; q < K; q++) {
                    if (out->knot_chain[kr[q].knot] == ca && na < 64) ia[na++] = q;
                    if (out->knot_chain[kr[q].knot] == cb && nb < 64) ib[nb++] = q;
                }
                int tr = na > nb;
                size_t rows = tr ? nb : na, cols = tr ? na : nb;
                double *cm = malloc(rows * cols * sizeof *cm);
                size_t *rc = malloc(rows * sizeof *rc);
                if (!cm || !rc) {
                    free(cm), free(rc);
                    ok = 0;
                    break;
                }
                for (size_t x = 0; x < rows; x++)
                    for (size_t y = 0; y < cols; y++) {
                        size_t p = tr ? ib[x] : ia[x], q = tr ? ia[y] : ib[y];
                        cm[x * cols + y] = wm[p * K + q];
                    }
                ok = hungarian(cm, rows, cols, rc);
                for (size_t x = 0; ok && x < rows; x++) {
                    size_t p = tr ? ib[x] : ia[x], q = tr ? ia[rc[x]] : ib[rc[x]];
                    if (cid[p * K + q] != SIZE_MAX) cands[cid[p * K + q]].keep = 1;
                }
                free(cm), free(rc);
            }
        }
        free(wm), free(cid), free(tgt);
        if (!ok) break;
        /* crossing cuts deleted, heaviest first */
        kept.n = 0;
        for (size_t c = 0; c < ncand && ok; c++)
            if (cands[c].keep) ok = acd_u32vec_push(&kept, (uint32_t)c);
        if (!ok) break;
        size_t nk = kept.n;
        uint8_t *cross = calloc(nk * nk + 1, 1);
        if (!cross) {
            ok = 0;
            break;
        }
        /* (one kept cut crosses no other: no flood) */
        for (size_t i = 0; i < nk && nk > 1; i++) {
            if (acd3_poll_stop(poll)) { /* each flood covers the region */
                cancelled = 1, ok = 0;
                break;
            }
            const cand *ci = &cands[kept.a[i]];
            const uint32_t *p = pool.a + ci->off;
            for (size_t k = 0; k + 1 < ci->n; k++) {
                uint32_t e = acd_edge_graph_find(g, p[k], p[k + 1]);
                if (e != ACD_NO_VERTEX) cut_edge[e] = 1;
            }
            if (!fe_ready) {
                for (size_t f = 0; f < nf; f++)
                    for (int k = 0; k < 3; k++)
                        fe[3 * f + k] = acd_edge_graph_find(g, m->triangles[3 * f + k], m->triangles[3 * f + (k + 1) % 3]);
                fe_ready = 1;
                fev = fe;
            }
            flood_split(fev, ms, out, r, rf, nrf, cut_edge, label, queue);
            for (size_t k = 0; k + 1 < ci->n; k++) {
                uint32_t e = acd_edge_graph_find(g, p[k], p[k + 1]);
                if (e != ACD_NO_VERTEX) cut_edge[e] = 0;
            }
            for (size_t q = 0; q < ci->n; q++) on_cut[p[q]] = 1;
            for (size_t j = 0; j < nk; j++) {
                if (j == i) continue;
                const cand *cj = &cands[kept.a[j]];
                uint32_t side = UINT32_MAX;
                for (size_t k = 1; k + 1 < cj->n; k++) {
                    uint32_t v = pool.a[cj->off + k];
                    if (on_cut[v]) continue;
                    uint32_t l = UINT32_MAX;
                    for (size_t q = out->vf_row[v]; q < out->vf_row[v + 1] && l == UINT32_MAX; q++)
                        if (ms->face_region[out->vf[q]] == r) l = label[out->vf[q]];
                    if (l == UINT32_MAX) continue;
                    if (side == UINT32_MAX) side = l;
                    else if (l != side) {
                        cross[i * nk + j] = cross[j * nk + i] = 1;
                        break;
                    }
                }
            }
            for (size_t q = 0; q < ci->n; q++) on_cut[p[q]] = 0;
        }
        /* each kept cut's count of kept cuts it crosses, updated as cuts are deleted (recounting
         * them per deletion made this O(nk^3): half of the run on a 200-tooth gear) */
        size_t *ncross = calloc(nk + 1, sizeof *ncross);
        if (!ncross) {
            free(cross);
            ok = 0;
            break;
        }
        for (size_t i = 0; i < nk; i++)
            for (size_t j = 0; j < nk; j++) ncross[i] += cross[i * nk + j];
        for (;;) {
            /* the cut crossing the most others goes first, the heavier on ties */
            size_t worst = SIZE_MAX, wn = 0;
            for (size_t i = 0; i < nk; i++) {
                if (!cands[kept.a[i]].keep) continue;
                size_t any = ncross[i];
                if (any && (worst == SIZE_MAX || any > wn || (any == wn && cands[kept.a[i]].w > cands[kept.a[worst]].w)))
                    worst = i, wn = any;
            }
            if (worst == SIZE_MAX) break;
            cands[kept.a[worst]].keep = 0;
            cands[kept.a[worst]].crossed = 1;
            for (size_t j = 0; j < nk; j++)
                if (cross[worst * nk + j]) ncross[j]--;
        }
        free(ncross);
        free(cross);
        /* the kept cuts of r */
        for (size_t c = 0; c < ncand && ok; c++) {
            if (!cands[c].keep && !cands[c].crossed) continue;
            if (ncuts == capcuts) {
                capcuts = capcuts ? 2 * capcuts : 64;
                acd3_pocket_cut *nc = realloc(cuts, capcuts * sizeof *nc);
                if (!nc) {
                    ok = 0;
                    break;
                }
                cuts = nc;
            }
            cuts[ncuts] = (acd3_pocket_cut){{cands[c].a, cands[c].b}, r, 0, cands[c].n, cands[c].w, cands[c].crossed};
            /* vertices appended to the output pool */
            size_t base = ncutv;
            uint32_t *nv2 = realloc(out->cut_v, (base + cands[c].n) * sizeof *nv2);
            if (!nv2) {
                ok = 0;
                break;
            }
            out->cut_v = nv2;
            memcpy(out->cut_v + base, pool.a + cands[c].off, cands[c].n * sizeof *nv2);
            cuts[ncuts].off = base;
            ncutv = base + cands[c].n;
            ncuts++;
        }
    }
build_done:
    free(rks), free(rrow), free(rface), free(label), free(queue), free(fe), free(wcost), free(allowed), free(cut_edge);
    free(on_cut);
    free(pool.a), free(kept.a), free(cands);
    acd_sp_ws_free(&sp);
    out->cuts = cuts;
    out->ncuts = ncuts;
    if (!ok) goto nomem;
    /* knot -> cuts */
    out->knot_row = calloc(out->nknots + 1, sizeof *out->knot_row);
    out->knot_cut = malloc((ncuts ? 2 * ncuts : 1) * sizeof *out->knot_cut);
    if (!out->knot_row || !out->knot_cut) goto nomem;
    for (size_t c = 0; c < ncuts; c++) out->knot_row[cuts[c].knot[0] + 1]++, out->knot_row[cuts[c].knot[1] + 1]++;
    for (size_t k = 0; k < out->nknots; k++) out->knot_row[k + 1] += out->knot_row[k];
    {
        size_t *fill = malloc((out->nknots ? out->nknots : 1) * sizeof *fill);
        if (!fill) goto nomem;
        memcpy(fill, out->knot_row, out->nknots * sizeof *fill);
        for (size_t c = 0; c < ncuts; c++)
            for (int s = 0; s < 2; s++) out->knot_cut[fill[cuts[c].knot[s]]++] = (uint32_t)c;
        free(fill);
    }
    return ACD_OK;
nomem:
    acd3_cut_graph_free(out);
    if (cancelled) return acd_fail(err, ACD_ERR_CANCELLED, "cancelled building the cut graph (%zu vertices)", nv);
    return acd_fail(err, ACD_ERR_NOMEM, "out of memory building the cut graph (%zu vertices)", nv);
}
