/* acd3/measure: bridges, pockets and SL concavity of a triangle mesh; see measure.h. */
#include "acd3/measure.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd3/handles.h"
#include "acd3/project.h"
#include "core/error.h"

/* acd3_edge_faces, and when fe is not NULL the edge of every face side (fe[3f + k]: the edge from
 * corner k to k + 1, ACD_NO_VERTEX when none), looked up once for the pocket flood. */
static acd_status edge_faces(const acd_mesh *m, const acd_edge_graph *g, uint32_t **face_of, uint32_t *fe,
                             acd_error *err) {
    uint32_t *fo = malloc((2 * g->nedges + 1) * sizeof *fo);
    if (!fo) return acd_fail(err, ACD_ERR_NOMEM, "out of memory for %zu edges", g->nedges);
    for (size_t i = 0; i < 2 * g->nedges; i++) fo[i] = UINT32_MAX;
    for (size_t f = 0; f < m->ntriangles; f++)
        for (int k = 0; k < 3; k++) {
            uint32_t u = m->triangles[3 * f + k], v = m->triangles[3 * f + (k + 1) % 3];
            uint32_t e = acd_edge_graph_find(g, u, v);
            if (fe) fe[3 * f + (size_t)k] = e;
            if (e == ACD_NO_VERTEX) continue;
            size_t slot = 2 * (size_t)e + (u > v);
            if (fo[slot] == UINT32_MAX) fo[slot] = (uint32_t)f;
        }
    *face_of = fo;
    return ACD_OK;
}

acd_status acd3_edge_faces(const acd_mesh *m, const acd_edge_graph *g, uint32_t **face_of, acd_error *err) {
    return edge_faces(m, g, face_of, NULL, err);
}

void acd3_measure_free(acd3_measure *ms) {
    if (!ms) return;
    free(ms->vconc);
    acd_hull_free(&ms->hull);
    acd3_patches_free(&ms->patches);
    free(ms->face_region);
    free(ms->region_patch);
    free(ms->edge_barrier);
    free(ms->edge_handle);
    acd3_handle_arcs_free(&ms->handle_arcs);
    free(ms->face_of);
    free(ms->face_edge);
    memset(ms, 0, sizeof *ms);
}

/* The open-surface rule (dissertation §V.B.1 "Polygonal surface ACD"; paper §4.1 Ext. 2; spec
 * §3.4). A hull vertex is concave when its outward normal on the hull and its normal on the
 * surface point in opposite directions (both area-weighted averages of the incident facets'
 * normals): the surface shows its inner side to the hull there. Only meshes with boundary edges
 * are concerned (on a closed outward surface every hull vertex is convex). */
typedef struct open_rule {
    uint8_t *concave;  /* per hull vertex; NULL: closed mesh (the rule does not apply) */
    acd_sp_tree to_open; /* shortest paths from the boundary vertices */
    int have_tree;
    uint32_t *path;    /* the last path to an opening */
} open_rule;

static void open_rule_free(open_rule *os) {
    free(os->concave);
    if (os->have_tree) acd_sp_tree_free(&os->to_open);
    free(os->path);
    memset(os, 0, sizeof *os);
}

static void tri_cross(const double *a, const double *b, const double *c, double n[3]) {
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
}

static acd_status open_surface_rule(const acd_mesh *m, const acd_edge_graph *g, const uint32_t *face_of,
                                    const acd_hull *h, open_rule *os, acd_error *err) {
    size_t nv = m->nvertices, nb = 0;
    uint32_t *bverts = NULL;
    uint8_t *isb = NULL;
    double *hn = NULL, *sn = NULL;
    uint32_t *hidx = NULL;
    acd_status st = ACD_OK;
    for (size_t e = 0; e < g->nedges && !nb; e++) nb = face_of[2 * e] == UINT32_MAX || face_of[2 * e + 1] == UINT32_MAX;
    if (!nb) return ACD_OK;
    nb = 0;
    os->concave = calloc(h->nvertices ? h->nvertices : 1, 1);
    hn = calloc(3 * (h->nvertices ? h->nvertices : 1), sizeof *hn);
    sn = calloc(3 * (h->nvertices ? h->nvertices : 1), sizeof *sn);
    hidx = malloc((nv ? nv : 1) * sizeof *hidx);
    isb = calloc(nv ? nv : 1, 1);
    bverts = malloc((nv ? nv : 1) * sizeof *bverts);
    os->path = malloc((nv ? nv : 1) * sizeof *os->path);
    if (!os->concave || !hn || !sn || !hidx || !isb || !bverts || !os->path) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory measuring an open surface of %zu vertices", nv);
        goto done;
    }
    for (size_t v = 0; v < nv; v++) hidx[v] = UINT32_MAX;
    for (size_t k = 0; k < h->nvertices; k++) hidx[h->source[k]] = (uint32_t)k;
    for (size_t t = 0; t < h->ntriangles; t++) {
        const uint32_t *tr = h->triangles + 3 * t;
        double n[3];
        tri_cross(h->vertices + 3 * (size_t)tr[0], h->vertices + 3 * (size_t)tr[1], h->vertices + 3 * (size_t)tr[2], n);
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++) hn[3 * (size_t)tr[k] + j] += n[j];
    }
    for (size_t f = 0; f < m->ntriangles; f++) {
        const uint32_t *tr = m->triangles + 3 * f;
        double n[3];
        tri_cross(m->vertices + 3 * (size_t)tr[0], m->vertices + 3 * (size_t)tr[1], m->vertices + 3 * (size_t)tr[2], n);
        for (int k = 0; k < 3; k++) {
            uint32_t hv = hidx[tr[k]];
            if (hv != UINT32_MAX)
                for (int j = 0; j < 3; j++) sn[3 * (size_t)hv + j] += n[j];
        }
    }
    for (size_t k = 0; k < h->nvertices; k++)
        os->concave[k] = hn[3 * k] * sn[3 * k] + hn[3 * k + 1] * sn[3 * k + 1] + hn[3 * k + 2] * sn[3 * k + 2] < 0;
    for (size_t e = 0; e < g->nedges; e++)
        if (face_of[2 * e] == UINT32_MAX || face_of[2 * e + 1] == UINT32_MAX)
            isb[g->edge_v[2 * e]] = isb[g->edge_v[2 * e + 1]] = 1;
    for (size_t v = 0; v < nv; v++)
        if (isb[v]) bverts[nb++] = (uint32_t)v;
    st = acd_dijkstra(g, bverts, nb, NULL, &os->to_open, err);
    if (st == ACD_OK) os->have_tree = 1;
done:
    free(hn), free(sn), free(hidx), free(isb), free(bverts);
    if (st != ACD_OK) open_rule_free(os);
    return st;
}

/* The path from v to its nearest opening into os->path (v first; reversed: v last). Returns its
 * vertex count (0 when no opening is reachable). */
static size_t open_path(open_rule *os, uint32_t v, int reversed) {
    if (!os->have_tree || os->to_open.pred == NULL || !isfinite(os->to_open.dist[v])) return 0;
    size_t n = 0;
    for (uint32_t x = v; x != ACD_NO_VERTEX && n < os->to_open.nvertices; x = os->to_open.pred[x]) os->path[n++] = x;
    if (reversed)
        for (size_t i = 0; i < n / 2; i++) {
            uint32_t t = os->path[i];
            os->path[i] = os->path[n - 1 - i], os->path[n - 1 - i] = t;
        }
    return n;
}

/* Regions: faces connected across non-barrier edges. Returns the count. */
static size_t flood_regions(const acd_mesh *m, const uint32_t *fe, const uint32_t *face_of, const uint8_t *barrier,
                            uint32_t *face_region, uint32_t *queue) {
    size_t nf = m->ntriangles, nr = 0;
    for (size_t f = 0; f < nf; f++) face_region[f] = UINT32_MAX;
    for (size_t s = 0; s < nf; s++) {
        if (face_region[s] != UINT32_MAX) continue;
        size_t qh = 0, qt = 0;
        queue[qt++] = (uint32_t)s;
        face_region[s] = (uint32_t)nr;
        while (qh < qt) {
            uint32_t f = queue[qh++];
            for (int k = 0; k < 3; k++) {
                uint32_t e = fe[3 * (size_t)f + (size_t)k];
                if (e == ACD_NO_VERTEX || barrier[e]) continue;
                for (int side = 0; side < 2; side++) {
                    uint32_t h = face_of[2 * (size_t)e + side];
                    if (h != UINT32_MAX && face_region[h] == UINT32_MAX) {
                        face_region[h] = (uint32_t)nr;
                        queue[qt++] = h;
                    }
                }
            }
        }
        nr++;
    }
    return nr;
}

acd_status acd3_measure_compute(const acd_mesh *m, const acd_edge_graph *g, double eps, double tol,
                                acd3_measure *out, acd_error *err) {
    return acd3_measure_compute_hull(m, g, NULL, eps, tol, NULL, out, err);
}

/* The projection polls every this many hull edges (each a shortest path over the part: some 2 ms
 * each at the root of an 832k-triangle mesh, docs/results/3d-large.md "Progress and cancellation"),
 * the open surfaces' bound every ACD3_MEASURE_POLL_VERTICES vertices (each against every patch). */
enum { ACD3_MEASURE_POLL_PATHS = 8, ACD3_MEASURE_POLL_VERTICES = 4096 };

acd_status acd3_measure_compute_hull(const acd_mesh *m, const acd_edge_graph *g, acd_hull *hull, double eps,
                                     double tol, acd3_poll *poll, acd3_measure *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    out->witness = UINT32_MAX;
    size_t nv = m->nvertices, nf = m->ntriangles;
    acd_status st;
    uint32_t *face_of = NULL, *queue = NULL, *fe = NULL;
    acd3_pathfinder pf;
    memset(&pf, 0, sizeof pf);
    open_rule os;
    memset(&os, 0, sizeof os);
    uint32_t *face_patch = NULL; /* shared pockets: per face, the nearest cap */
    out->vconc = calloc(nv ? nv : 1, sizeof *out->vconc);
    out->face_region = malloc((nf ? nf : 1) * sizeof *out->face_region);
    out->edge_barrier = calloc(g->nedges ? g->nedges : 1, 1);
    if (!out->vconc || !out->face_region || !out->edge_barrier) {
        if (hull) acd_hull_free(hull);
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory measuring a mesh of %zu vertices", nv);
        goto fail;
    }
    if (hull) { /* taken over */
        out->hull = acd_hull_take(hull);
    } else {
        st = acd_hull_compute(m->vertices, nv, &out->hull, err);
        if (st != ACD_OK) goto fail;
    }
    if (acd3_poll_stop(poll)) goto cancelled;
    if (out->hull.dim < 3) { /* flat: convex by definition (a planar patch or a degenerate solid) */
        for (size_t f = 0; f < nf; f++) out->face_region[f] = 0;
        out->nregions = nf ? 1 : 0;
        return ACD_OK;
    }
    st = acd3_patches_build(&out->hull, eps, tol, &out->patches, err);
    if (st != ACD_OK) goto fail;
    if (acd3_poll_stop(poll)) goto cancelled;
    fe = malloc((nf ? 3 * nf : 1) * sizeof *fe);
    if (!fe) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory measuring a mesh of %zu faces", nf);
        goto fail;
    }
    st = edge_faces(m, g, &face_of, fe, err);
    if (st != ACD_OK) goto fail;
    if (!acd3_pathfinder_init(&pf, g, m->vertices)) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory projecting hull edges");
        goto fail;
    }

    /* open surfaces (spec §3.4): which hull vertices are concave, and the way to the openings */
    const acd_hull *h = &out->hull;
    st = open_surface_rule(m, g, face_of, h, &os, err);
    if (st != ACD_OK) goto fail;
    if (acd3_poll_stop(poll)) goto cancelled;

    /* project the patch-boundary hull edges; collect votes (face, patch, weight) */
    const uint32_t *fp = out->patches.facet_patch;
    size_t nvote = 0, capvote = 0;
    acd3_claim *vl = NULL;
    size_t nsearched = 0;
    for (size_t t = 0; t < h->ntriangles; t++)
        for (int i = 0; i < 3; i++) {
            uint32_t nb = h->neighbors[3 * t + i];
            if (nb == ACD_HULL_NO_NEIGHBOR || fp[nb] == fp[t] || nb < t) continue;
            if (++nsearched % ACD3_MEASURE_POLL_PATHS == 0 && acd3_poll_stop(poll)) {
                free(vl);
                goto cancelled;
            }
            uint32_t ia = h->triangles[3 * t + i], ib = h->triangles[3 * t + (i + 1) % 3];
            uint32_t a = h->source[ia], b = h->source[ib];
            int ca = os.concave && os.concave[ia], cb = os.concave && os.concave[ib];
            const uint32_t *path;
            size_t len;
            if (ca == cb) {
                int found = acd3_shortest_path(&pf, a, b);
                if (found < 0) {
                    free(vl);
                    st = acd_fail(err, ACD_ERR_NOMEM, "out of memory projecting hull edges");
                    goto fail;
                }
                if (!found) continue; /* a and b on different connected components */
                path = pf.path;
                len = pf.path_len;
            } else {
                /* one end concave: the path from the convex end to the opening, directed like
                 * a -> b (from a to the opening, or from the opening to b) */
                len = open_path(&os, ca ? b : a, !ca);
                if (len < 2) continue;
                path = os.path;
            }
            /* both ends concave: the surface shows its inner side to this bridge, so its faces
             * are oriented against the hull there: the sides of the path swap */
            int swap = ca && cb;
            out->nprojected++;
            for (size_t k = 0; k + 1 < len; k++) {
                uint32_t u = path[k], v = path[k + 1];
                uint32_t e = acd_edge_graph_find(g, u, v);
                if (e == ACD_NO_VERTEX) continue;
                out->edge_barrier[e] = 1;
                /* the face holding half-edge u->v lies left of the path: the left patch fp[t] */
                uint32_t left = face_of[2 * (size_t)e + (u > v)], right = face_of[2 * (size_t)e + (v > u)];
                if (swap) {
                    uint32_t x = left;
                    left = right, right = x;
                }
                double w = g->length[e];
                if (nvote + 2 > capvote) {
                    capvote = capvote ? 2 * capvote : 1024;
                    acd3_claim *nvl = realloc(vl, capvote * sizeof *nvl);
                    if (!nvl) {
                        free(vl);
                        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory projecting hull edges");
                        goto fail;
                    }
                    vl = nvl;
                }
                if (left != UINT32_MAX) vl[nvote++] = (acd3_claim){left, fp[t], w, left, e};
                if (right != UINT32_MAX) vl[nvote++] = (acd3_claim){right, fp[nb], w, right, e};
            }
        }

    queue = malloc((nf ? nf : 1) * sizeof *queue);
    if (!queue) {
        free(vl);
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory labelling pockets");
        goto fail;
    }
    out->nregions = flood_regions(m, fe, face_of, out->edge_barrier, out->face_region, queue);
    if (acd3_poll_stop(poll)) {
        free(vl);
        goto cancelled;
    }
    size_t np = out->patches.npatches, nr = out->nregions;
    out->region_patch = malloc((nr ? nr : 1) * sizeof *out->region_patch);
    if (!out->region_patch) {
        free(vl);
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory labelling pockets");
        goto fail;
    }
    for (size_t r = 0; r < nr; r++) out->region_patch[r] = UINT32_MAX;
    {
        /* best patch per region: sort votes by (region, patch, weight) -- a total order, so the
         * sums below are bitwise reproducible -- and sum the runs */
        for (size_t i = 0; i < nvote; i++) vl[i].region = out->face_region[vl[i].face];
        acd3_claims_sort(vl, nvote);
        double *best = malloc((nr ? nr : 1) * sizeof *best);
        if (!best) {
            free(vl);
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory labelling pockets");
            goto fail;
        }
        for (size_t r = 0; r < nr; r++) best[r] = -1;
        for (size_t i = 0; i < nvote;) {
            size_t j = i;
            double s = 0;
            while (j < nvote && vl[j].region == vl[i].region && vl[j].patch == vl[i].patch) s += vl[j++].w;
            uint32_t r = vl[i].region;
            if (s > best[r]) {
                best[r] = s;
                out->region_patch[r] = vl[i].patch;
            }
            i = j;
        }
        /* handle caps (spec §6, decision A15): shared pockets cut by their caps' arcs, each face
         * measured against its nearest cap */
        acd3_handle_input hin = {m, g, face_of, out->face_region, nr, out->edge_barrier, vl, nvote, best};
        acd3_handle_result hr;
        st = acd3_handle_cuts(&hin, &hr, err);
        free(best);
        if (st != ACD_OK) {
            free(vl);
            goto fail;
        }
        out->edge_handle = hr.edge_arc, hr.edge_arc = NULL;
        out->handle_arcs = hr.arcs, memset(&hr.arcs, 0, sizeof hr.arcs);
        out->nhandle_pockets = hr.npockets;
        out->nhandle_candidates = hr.ncandidates;
        face_patch = hr.face_patch, hr.face_patch = NULL;
        acd3_handle_result_free(&hr);
    }
    free(vl);
    if (acd3_poll_stop(poll)) goto cancelled;
    /* regions without a projected path around them (open surfaces): the patch whose plane
     * they lie least deep below; one pass over those faces per patch */
    {
        size_t nunvoted = 0;
        for (size_t r = 0; r < nr; r++) nunvoted += out->region_patch[r] == UINT32_MAX;
        if (nunvoted) {
            double *bestd = malloc(nr * sizeof *bestd), *worst = malloc(nr * sizeof *worst);
            if (!bestd || !worst) {
                free(bestd);
                free(worst);
                st = acd_fail(err, ACD_ERR_NOMEM, "out of memory labelling pockets");
                goto fail;
            }
            /* voted regions are marked -INFINITY and left alone */
            for (size_t r = 0; r < nr; r++) bestd[r] = out->region_patch[r] == UINT32_MAX ? INFINITY : -INFINITY;
            for (size_t p = 0; p < np; p++) {
                if (acd3_poll_stop(poll)) {
                    free(bestd);
                    free(worst);
                    goto cancelled;
                }
                for (size_t r = 0; r < nr; r++) worst[r] = 0;
                for (size_t f = 0; f < nf; f++) {
                    uint32_t r = out->face_region[f];
                    if (bestd[r] == -INFINITY) continue;
                    for (int k = 0; k < 3; k++) {
                        double d = acd3_patch_depth(&out->patches, p, m->vertices + 3 * (size_t)m->triangles[3 * f + k]);
                        if (d > worst[r]) worst[r] = d;
                    }
                }
                for (size_t r = 0; r < nr; r++)
                    if (bestd[r] != -INFINITY && worst[r] < bestd[r]) {
                        bestd[r] = worst[r];
                        out->region_patch[r] = (uint32_t)p;
                    }
            }
            free(bestd);
            free(worst);
        }
    }
    /* concavity: depth below the patch plane of each incident face's region, the largest */
    for (size_t f = 0; f < nf; f++) {
        uint32_t p = face_patch && face_patch[f] != UINT32_MAX ? face_patch[f] : out->region_patch[out->face_region[f]];
        if (p == UINT32_MAX) continue;
        for (int k = 0; k < 3; k++) {
            uint32_t v = m->triangles[3 * f + k];
            double d = acd3_patch_depth(&out->patches, p, m->vertices + 3 * (size_t)v);
            if (d > out->vconc[v]) out->vconc[v] = d;
        }
    }
    /* open surfaces: a vertex's concavity is at most its distance to the hull's boundary (the
     * least depth below a patch plane). On an open piece both sides of the surface face hull
     * facets (thin pieces, rims), and the bridge a region is given by the sides of its paths can
     * be one it does not lie under; the bound keeps a patch that lies on its own hull (a convex
     * surface patch, Chazelle et al.) at concavity 0, up to eps. */
    if (os.concave)
        for (size_t v = 0; v < nv; v++) {
            if ((v + 1) % ACD3_MEASURE_POLL_VERTICES == 0 && acd3_poll_stop(poll)) goto cancelled;
            double mn = INFINITY;
            for (size_t p = 0; p < out->patches.npatches && mn > 0; p++) {
                double d = acd3_patch_depth(&out->patches, p, m->vertices + 3 * v);
                if (d < mn) mn = d;
            }
            if (mn < out->vconc[v]) out->vconc[v] = mn > 0 ? mn : 0;
        }
    out->concavity = 0;
    for (size_t v = 0; v < nv; v++)
        if (out->vconc[v] > out->concavity) {
            out->concavity = out->vconc[v];
            out->witness = (uint32_t)v;
        }
    out->face_of = face_of;
    out->face_edge = fe;
    free(queue);
    acd3_pathfinder_free(&pf);
    open_rule_free(&os);
    free(face_patch);
    return ACD_OK;
cancelled:
    st = acd_fail(err, ACD_ERR_CANCELLED, "cancelled measuring a part of %zu triangles", nf);
fail:
    free(face_of);
    free(fe);
    free(queue);
    acd3_pathfinder_free(&pf);
    open_rule_free(&os);
    free(face_patch);
    acd3_measure_free(out);
    return st;
}
