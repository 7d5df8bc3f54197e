/* acd3/handles: handle caps, shortest cap-to-cap arcs and the G_h forest; see handles.h. */
#include "acd3/handles.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/u32vec.h"
#include "core/union_find.h"

#define NONE UINT32_MAX
#define MULTI (UINT32_MAX - 1) /* a vertex on two cap loops */

static int cmp_claim(const void *a, const void *b) {
    const acd3_claim *x = a, *y = b;
    if (x->region != y->region) return x->region < y->region ? -1 : 1;
    if (x->patch != y->patch) return x->patch < y->patch ? -1 : 1;
    if (x->w != y->w) return (x->w > y->w) - (x->w < y->w);
    if (x->face != y->face) return x->face < y->face ? -1 : 1;
    return (x->edge > y->edge) - (x->edge < y->edge);
}

void acd3_claims_sort(acd3_claim *c, size_t n) {
    if (n) qsort(c, n, sizeof *c, cmp_claim);
}

void acd3_handle_arcs_free(acd3_handle_arcs *h) {
    free(h->vert), free(h->off), free(h->region), free(h->a), free(h->b), free(h->length);
    memset(h, 0, sizeof *h);
}

void acd3_handle_result_free(acd3_handle_result *r) {
    free(r->edge_arc);
    free(r->face_patch);
    acd3_handle_arcs_free(&r->arcs);
    memset(r, 0, sizeof *r);
}

/* a candidate arc: the shortest through edge `edge` between cap loops a < b */
typedef struct cand_arc {
    uint32_t a, b, edge;
    double len;
} cand_arc;

static int cmp_pair(const void *p, const void *q) {
    const cand_arc *x = p, *y = q;
    if (x->a != y->a) return x->a < y->a ? -1 : 1;
    if (x->b != y->b) return x->b < y->b ? -1 : 1;
    if (x->len != y->len) return x->len < y->len ? -1 : 1;
    return (x->edge > y->edge) - (x->edge < y->edge);
}

static int cmp_len(const void *p, const void *q) {
    const cand_arc *x = p, *y = q;
    if (x->len != y->len) return x->len < y->len ? -1 : 1;
    return (x->edge > y->edge) - (x->edge < y->edge);
}

/* the edge of face f at vertex v other than e (fe: the face's three edge ids); NONE when absent */
static uint32_t other_edge_at(const acd_edge_graph *g, const uint32_t *fe, uint32_t f, uint32_t v, uint32_t e) {
    for (int k = 0; k < 3; k++) {
        uint32_t x = fe[3 * (size_t)f + k];
        if (x == NONE || x == e) continue;
        if (g->edge_v[2 * (size_t)x] == v || g->edge_v[2 * (size_t)x + 1] == v) return x;
    }
    return NONE;
}

/* arcs: appends one (vertex list, region, loops, length); 0 on allocation failure */
static int arcs_push(acd3_handle_arcs *h, size_t *cap, acd_u32vec *verts, const uint32_t *seq, size_t len, uint32_t r,
                     uint32_t a, uint32_t b, double length) {
    if (h->narcs == *cap) {
        size_t nc = *cap ? 2 * *cap : 8;
        size_t *no = realloc(h->off, (nc + 1) * sizeof *no);
        if (!no) return 0;
        h->off = no;
        uint32_t *nr = realloc(h->region, nc * sizeof *nr);
        if (!nr) return 0;
        h->region = nr;
        uint32_t *na = realloc(h->a, nc * sizeof *na);
        if (!na) return 0;
        h->a = na;
        uint32_t *nb = realloc(h->b, nc * sizeof *nb);
        if (!nb) return 0;
        h->b = nb;
        double *nl = realloc(h->length, nc * sizeof *nl);
        if (!nl) return 0;
        h->length = nl;
        *cap = nc;
    }
    if (h->narcs == 0) h->off[0] = 0;
    for (size_t i = 0; i < len; i++)
        if (!acd_u32vec_push(verts, seq[i])) return 0;
    h->region[h->narcs] = r, h->a[h->narcs] = a, h->b[h->narcs] = b, h->length[h->narcs] = length;
    h->narcs++;
    h->off[h->narcs] = verts->n;
    return 1;
}

long acd3_handles_genus(const acd_mesh *m, const acd_edge_graph *g, const uint32_t *face_of) {
    size_t nv = m->nvertices, nf = m->ntriangles;
    uint32_t *comp = malloc((nv ? nv : 1) * sizeof *comp), *loop = malloc((nv ? nv : 1) * sizeof *loop);
    uint8_t *used = calloc(nv ? nv : 1, 1), *onb = calloc(nv ? nv : 1, 1);
    long genus = -1;
    if (comp && loop && used && onb) {
        for (size_t v = 0; v < nv; v++) comp[v] = loop[v] = (uint32_t)v;
        long V = 0, E = 0, c = 0, b = 0;
        for (size_t f = 0; f < nf; f++)
            for (int k = 0; k < 3; k++) {
                used[m->triangles[3 * f + k]] = 1;
                acd_uf_union(comp, m->triangles[3 * f + k], m->triangles[3 * f + (k + 1) % 3]);
            }
        for (size_t e = 0; e < g->nedges; e++) {
            int n = (face_of[2 * e] != NONE) + (face_of[2 * e + 1] != NONE);
            E += n > 0;
            if (n == 1) {
                onb[g->edge_v[2 * e]] = onb[g->edge_v[2 * e + 1]] = 1;
                acd_uf_union(loop, g->edge_v[2 * e], g->edge_v[2 * e + 1]);
            }
        }
        for (size_t v = 0; v < nv; v++)
            if (used[v]) {
                V++;
                c += acd_uf_find(comp, (uint32_t)v) == v;
                b += onb[v] && acd_uf_find(loop, (uint32_t)v) == v;
            }
        genus = (2 * c - (V - E + (long)nf) - b) / 2;
        /* Euler's formula holds for a 2-manifold; where the surface is not one (vertices where
         * sheets touch, edges of three faces: soups and CAD files in surface mode) it can come
         * out negative, and such a surface is taken as having no handles (not as a failure: -1
         * is kept for out of memory) */
        if (genus < 0) genus = 0;
    }
    free(comp), free(loop), free(used), free(onb);
    return genus;
}

acd_status acd3_handle_cuts(const acd3_handle_input *in, acd3_handle_result *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    const acd_mesh *m = in->m;
    const acd_edge_graph *g = in->g;
    const uint32_t *face_of = in->face_of, *freg = in->face_region;
    size_t nr = in->nregions, nf = m->ntriangles, nv = m->nvertices, ne = g->nedges;
    acd_status st = ACD_OK;
    uint8_t *cand = NULL, *allowed = NULL, *blocked = NULL;
    uint32_t *nloops = NULL, *frow = NULL, *fl = NULL, *srow = NULL, *sl = NULL, *parent = NULL, *loopid = NULL;
    uint32_t *label = NULL, *estamp = NULL, *lpar = NULL, *seq = NULL, *fe = NULL;
    uint8_t *issrc = NULL;
    acd_u32vec srcs = {0}, srcl = {0}, verts = {0};
    cand_arc *ca = NULL;
    size_t arccap = 0, capca = 0;
    out->edge_arc = calloc(ne ? ne : 1, 1);
    cand = calloc(nr ? nr : 1, 1);
    if (!out->edge_arc || !cand) goto nomem;

    /* regions with two or more substantial claimants */
    size_t ncand = 0;
    for (size_t i = 0; i < in->nclaims;) {
        size_t j = i, k = 0;
        uint32_t r = in->claims[i].region;
        while (j < in->nclaims && in->claims[j].region == r) {
            size_t q = j;
            double sum = 0;
            while (q < in->nclaims && in->claims[q].region == r && in->claims[q].patch == in->claims[j].patch)
                sum += in->claims[q++].w;
            k += sum >= ACD3_HANDLE_VOTE_SHARE * in->best[r];
            j = q;
        }
        if (k >= 2) cand[r] = 1, ncand++;
        i = j;
    }
    if (!ncand) goto done;
    /* a surface without handles has no handle caps (an annulus among its regions comes from paths
     * that encircle another region, which is not what the caps are about) */
    long genus = acd3_handles_genus(m, g, face_of);
    if (genus < 0) goto nomem;
    out->genus = genus;
    if (genus == 0) goto done;

    /* faces and boundary sides of the candidate regions, by region (CSR) */
    frow = calloc(nr + 1, sizeof *frow);
    srow = calloc(nr + 1, sizeof *srow);
    if (!frow || !srow) goto nomem;
    for (size_t f = 0; f < nf; f++)
        if (cand[freg[f]]) frow[freg[f] + 1]++;
    for (size_t s = 0; s < 2 * ne; s++) {
        uint32_t f = face_of[s];
        if (f == NONE || !cand[freg[f]]) continue;
        if (in->edge_path[s / 2] || face_of[s ^ 1] == NONE) srow[freg[f] + 1]++;
    }
    for (size_t r = 0; r < nr; r++) frow[r + 1] += frow[r], srow[r + 1] += srow[r];
    fl = malloc((frow[nr] ? frow[nr] : 1) * sizeof *fl);
    sl = malloc((srow[nr] ? srow[nr] : 1) * sizeof *sl);
    parent = malloc((ne ? 2 * ne : 1) * sizeof *parent);
    loopid = malloc((ne ? 2 * ne : 1) * sizeof *loopid);
    nloops = calloc(nr, sizeof *nloops);
    if (!fl || !sl || !parent || !loopid || !nloops) goto nomem;
    {
        uint32_t *fill = malloc((nr ? nr : 1) * sizeof *fill);
        if (!fill) goto nomem;
        memcpy(fill, frow, nr * sizeof *fill);
        for (size_t f = 0; f < nf; f++)
            if (cand[freg[f]]) fl[fill[freg[f]]++] = (uint32_t)f;
        memcpy(fill, srow, nr * sizeof *fill);
        for (size_t s = 0; s < 2 * ne; s++) {
            uint32_t f = face_of[s];
            if (f == NONE || !cand[freg[f]]) continue;
            if (in->edge_path[s / 2] || face_of[s ^ 1] == NONE) sl[fill[freg[f]]++] = (uint32_t)s;
        }
        free(fill);
    }
    /* the edge ids of the candidate regions' faces (the wedge walks and the arcs look them up) */
    fe = malloc((nf ? 3 * nf : 1) * sizeof *fe);
    if (!fe) goto nomem;
    for (size_t i = 0; i < frow[nr]; i++) {
        const uint32_t *t = m->triangles + 3 * (size_t)fl[i];
        for (int k = 0; k < 3; k++) fe[3 * (size_t)fl[i] + k] = acd_edge_graph_find(g, t[k], t[(k + 1) % 3]);
    }

    /* boundary loops of the regions cut open along the barriers: join the two barrier sides of
     * every wedge (the region's faces around a vertex between two barriers) */
    for (size_t s = 0; s < 2 * ne; s++) parent[s] = (uint32_t)s, loopid[s] = NONE;
    for (size_t i = 0; i < srow[nr]; i++) {
        uint32_t s = sl[i], e = s / 2, f0 = face_of[s];
        for (int end = 0; end < 2; end++) {
            uint32_t v = g->edge_v[2 * (size_t)e + end], f = f0, ce = e;
            size_t steps = 0, maxsteps = g->row[v + 1] - g->row[v] + 2;
            while (steps++ < maxsteps) {
                uint32_t e2 = other_edge_at(g, fe, f, v, ce);
                if (e2 == NONE) break;
                uint32_t s2 = face_of[2 * (size_t)e2] == f ? 2 * e2 : face_of[2 * (size_t)e2 + 1] == f ? 2 * e2 + 1 : NONE;
                if (s2 == NONE) break; /* non-manifold */
                if (in->edge_path[e2] || face_of[s2 ^ 1] == NONE) {
                    acd_uf_union(parent, s, s2);
                    break;
                }
                f = face_of[s2 ^ 1], ce = e2;
            }
        }
    }
    /* cap loops (with a projected path on them), numbered per region in order of their first side */
    size_t nshared = 0;
    for (size_t r = 0; r < nr; r++) {
        for (size_t i = srow[r]; i < srow[r + 1]; i++) {
            uint32_t s = sl[i];
            if (!in->edge_path[s / 2]) continue;
            uint32_t root = acd_uf_find(parent, s);
            if (loopid[root] == NONE) loopid[root] = nloops[r]++;
        }
        nshared += cand[r] && nloops[r] >= 2;
    }
    out->npockets = nshared;
    if (!nshared) goto done;

    label = malloc((nv ? nv : 1) * sizeof *label);
    issrc = calloc(nv ? nv : 1, 1);
    allowed = calloc(nv ? nv : 1, 1);
    estamp = malloc((ne ? ne : 1) * sizeof *estamp);
    if (!label || !issrc || !allowed || !estamp) goto nomem;
    for (size_t v = 0; v < nv; v++) label[v] = NONE;
    for (size_t e = 0; e < ne; e++) estamp[e] = NONE;

    /* arcs, region by region */
    for (size_t r = 0; r < nr; r++) {
        if (!cand[r] || nloops[r] < 2) continue;
        srcs.n = 0;
        for (size_t i = srow[r]; i < srow[r + 1]; i++) {
            uint32_t s = sl[i], e = s / 2;
            if (!in->edge_path[e]) continue;
            uint32_t L = loopid[acd_uf_find(parent, s)];
            for (int end = 0; end < 2; end++) {
                uint32_t v = g->edge_v[2 * (size_t)e + end];
                if (label[v] == NONE) {
                    if (!acd_u32vec_push(&srcs, v)) goto nomem;
                    issrc[v] = 1;
                    label[v] = L;
                } else if (label[v] != L) {
                    label[v] = MULTI;
                }
            }
        }
        /* the arcs run through the region's inner vertices between vertices of one cap loop
         * each: a vertex on two loops (two bridges' paths meeting) is two vertices of the region
         * cut open, and an arc from it could leave from the wrong copy and cut the region apart;
         * vertices on the openings only are left out too */
        for (size_t i = frow[r]; i < frow[r + 1]; i++)
            for (int k = 0; k < 3; k++) allowed[m->triangles[3 * (size_t)fl[i] + k]] = 1;
        for (size_t i = srow[r]; i < srow[r + 1]; i++)
            for (int end = 0; end < 2; end++) {
                uint32_t v = g->edge_v[2 * (size_t)(sl[i] / 2) + end];
                if (label[v] == NONE || label[v] == MULTI) allowed[v] = 0;
            }
        acd_dijkstra_opts o;
        memset(&o, 0, sizeof o);
        o.edge_blocked = in->edge_path;
        o.vertex_allowed = allowed;
        o.target = ACD_NO_VERTEX;
        acd_sp_tree tree;
        st = acd_dijkstra(g, srcs.a, srcs.n, &o, &tree, err);
        if (st != ACD_OK) goto done;
        /* candidate arcs through the region's edges whose ends were reached from different loops */
        size_t nca = 0;
        for (size_t i = frow[r]; i < frow[r + 1]; i++) {
            for (int k = 0; k < 3; k++) {
                uint32_t e = fe[3 * (size_t)fl[i] + k];
                if (e == NONE || estamp[e] == r || in->edge_path[e]) continue;
                estamp[e] = (uint32_t)r;
                uint32_t u = g->edge_v[2 * (size_t)e], v = g->edge_v[2 * (size_t)e + 1];
                if (tree.origin[u] == NONE || tree.origin[v] == NONE) continue;
                uint32_t la = label[srcs.a[tree.origin[u]]], lb = label[srcs.a[tree.origin[v]]];
                if (la == lb) continue;
                if (nca == capca) {
                    size_t nc = capca ? 2 * capca : 64;
                    cand_arc *n2 = realloc(ca, nc * sizeof *n2);
                    if (!n2) {
                        acd_sp_tree_free(&tree);
                        goto nomem;
                    }
                    ca = n2, capca = nc;
                }
                ca[nca++] = (cand_arc){la < lb ? la : lb, la < lb ? lb : la, e, tree.dist[u] + g->length[e] + tree.dist[v]};
            }
        }
        /* the shortest per pair of loops, then Kruskal: shortest first, never closing a cycle */
        if (nca) qsort(ca, nca, sizeof *ca, cmp_pair);
        size_t nuniq = 0;
        for (size_t i = 0; i < nca; i++)
            if (!nuniq || ca[i].a != ca[nuniq - 1].a || ca[i].b != ca[nuniq - 1].b) ca[nuniq++] = ca[i];
        out->ncandidates += nuniq;
        if (nuniq) qsort(ca, nuniq, sizeof *ca, cmp_len);
        uint32_t *lp = realloc(lpar, nloops[r] * sizeof *lp);
        uint32_t *sq = realloc(seq, (nv ? nv : 1) * sizeof *sq);
        if (lp) lpar = lp;
        if (sq) seq = sq;
        if (!lp || !sq) {
            acd_sp_tree_free(&tree);
            goto nomem;
        }
        for (uint32_t l = 0; l < nloops[r]; l++) lpar[l] = l;
        for (size_t i = 0; i < nuniq; i++) {
            if (acd_uf_find(lpar, ca[i].a) == acd_uf_find(lpar, ca[i].b)) continue;
            acd_uf_union(lpar, ca[i].a, ca[i].b);
            uint32_t u = g->edge_v[2 * (size_t)ca[i].edge], v = g->edge_v[2 * (size_t)ca[i].edge + 1];
            if (label[srcs.a[tree.origin[u]]] != ca[i].a) {
                uint32_t x = u;
                u = v, v = x;
            }
            /* loop a's source ... u, then v ... loop b's source */
            size_t n = 0;
            for (uint32_t x = u;; x = tree.pred[x]) {
                seq[n++] = x;
                if (issrc[x] || tree.pred[x] == NONE || n >= nv) break;
            }
            for (size_t p = 0; p < n / 2; p++) {
                uint32_t x = seq[p];
                seq[p] = seq[n - 1 - p], seq[n - 1 - p] = x;
            }
            for (uint32_t x = v;; x = tree.pred[x]) {
                seq[n++] = x;
                if (issrc[x] || tree.pred[x] == NONE || n >= nv) break;
            }
            for (size_t p = 0; p + 1 < n; p++) {
                uint32_t e = acd_edge_graph_find(g, seq[p], seq[p + 1]);
                if (e != ACD_NO_VERTEX) out->edge_arc[e] = 1;
            }
            if (!arcs_push(&out->arcs, &arccap, &verts, seq, n, (uint32_t)r, ca[i].a, ca[i].b, ca[i].len)) {
                acd_sp_tree_free(&tree);
                goto nomem;
            }
        }
        acd_sp_tree_free(&tree);
        for (size_t i = 0; i < srcs.n; i++) label[srcs.a[i]] = NONE, issrc[srcs.a[i]] = 0;
        for (size_t i = frow[r]; i < frow[r + 1]; i++)
            for (int k = 0; k < 3; k++) allowed[m->triangles[3 * (size_t)fl[i] + k]] = 0;
    }
    out->arcs.vert = verts.a, verts.a = NULL;

    /* every face of a shared pocket measured against its nearest cap (the cap of its vertex
     * nearest to one): flood from the paths of the substantial claimants, across no path and no
     * arc */
    out->face_patch = malloc((nf ? nf : 1) * sizeof *out->face_patch);
    blocked = malloc(ne ? ne : 1);
    if (!out->face_patch || !blocked) goto nomem;
    for (size_t f = 0; f < nf; f++) out->face_patch[f] = NONE;
    for (size_t e = 0; e < ne; e++) blocked[e] = in->edge_path[e] | out->edge_arc[e];
    for (size_t i = 0; i < in->nclaims;) {
        uint32_t r = in->claims[i].region;
        size_t j = i;
        while (j < in->nclaims && in->claims[j].region == r) j++;
        if (!cand[r] || nloops[r] < 2) {
            i = j;
            continue;
        }
        srcs.n = srcl.n = 0;
        for (size_t q = i; q < j;) {
            size_t t = q;
            double sum = 0;
            while (t < j && in->claims[t].patch == in->claims[q].patch) sum += in->claims[t++].w;
            if (sum >= ACD3_HANDLE_VOTE_SHARE * in->best[r])
                for (size_t u = q; u < t; u++)
                    for (int end = 0; end < 2; end++)
                        if (!acd_u32vec_push(&srcs, g->edge_v[2 * (size_t)in->claims[u].edge + end]) ||
                            !acd_u32vec_push(&srcl, in->claims[u].patch))
                            goto nomem;
            q = t;
        }
        for (size_t k = frow[r]; k < frow[r + 1]; k++)
            for (int c = 0; c < 3; c++) allowed[m->triangles[3 * (size_t)fl[k] + c]] = 1;
        acd_dijkstra_opts o;
        memset(&o, 0, sizeof o);
        o.edge_blocked = blocked;
        o.vertex_allowed = allowed;
        o.target = ACD_NO_VERTEX;
        acd_sp_tree tree;
        st = acd_dijkstra(g, srcs.a, srcs.n, &o, &tree, err);
        if (st != ACD_OK) goto done;
        for (size_t k = frow[r]; k < frow[r + 1]; k++) {
            uint32_t f = fl[k], bestv = NONE;
            for (int c = 0; c < 3; c++) {
                uint32_t v = m->triangles[3 * (size_t)f + c];
                if (!isfinite(tree.dist[v])) continue;
                if (bestv == NONE || tree.dist[v] < tree.dist[bestv] || (tree.dist[v] == tree.dist[bestv] && v < bestv))
                    bestv = v;
            }
            if (bestv != NONE) out->face_patch[f] = srcl.a[tree.origin[bestv]];
        }
        acd_sp_tree_free(&tree);
        for (size_t k = frow[r]; k < frow[r + 1]; k++)
            for (int c = 0; c < 3; c++) allowed[m->triangles[3 * (size_t)fl[k] + c]] = 0;
        i = j;
    }
    goto done;
nomem:
    st = acd_fail(err, ACD_ERR_NOMEM, "out of memory cutting the handles of a mesh of %zu faces", nf);
done:
    free(cand), free(allowed), free(blocked), free(nloops), free(frow), free(fl), free(srow), free(sl);
    free(parent), free(loopid), free(label), free(estamp), free(lpar), free(seq), free(issrc), free(fe);
    free(srcs.a), free(srcl.a), free(verts.a), free(ca);
    if (st != ACD_OK) acd3_handle_result_free(out);
    else if (!out->npockets) {
        free(out->face_patch);
        out->face_patch = NULL;
    }
    return st;
}
