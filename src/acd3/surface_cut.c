/* acd3/surface_cut: face classes by a plane, pieces by flood fill; see surface_cut.h. */
#include "acd3/surface_cut.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd3/measure.h"
#include "core/error.h"
#include "core/union_find.h"

/* Extracts the faces with piece label `label` into a new mesh with its own vertices. */
static acd_status extract(const acd_mesh *m, const uint32_t *piece, uint32_t label, uint32_t *remap,
                          acd_cut_piece *out) {
    memset(out, 0, sizeof *out);
    size_t nt = 0, nv = 0;
    for (size_t f = 0; f < m->ntriangles; f++) nt += piece[f] == label;
    for (size_t v = 0; v < m->nvertices; v++) remap[v] = UINT32_MAX;
    for (size_t f = 0; f < m->ntriangles; f++)
        if (piece[f] == label)
            for (int k = 0; k < 3; k++) {
                uint32_t v = m->triangles[3 * f + k];
                if (remap[v] == UINT32_MAX) remap[v] = (uint32_t)nv++;
            }
    out->mesh.vertices = malloc(3 * (nv ? nv : 1) * sizeof *out->mesh.vertices);
    out->mesh.triangles = malloc(3 * (nt ? nt : 1) * sizeof *out->mesh.triangles);
    out->source = malloc((nv ? nv : 1) * sizeof *out->source);
    out->is_cap = calloc(nt ? nt : 1, 1);
    if (!out->mesh.vertices || !out->mesh.triangles || !out->source || !out->is_cap) return ACD_ERR_NOMEM;
    for (size_t v = 0; v < m->nvertices; v++)
        if (remap[v] != UINT32_MAX) {
            memcpy(out->mesh.vertices + 3 * (size_t)remap[v], m->vertices + 3 * v, sizeof(double[3]));
            out->source[remap[v]] = (uint32_t)v;
        }
    size_t t = 0;
    for (size_t f = 0; f < m->ntriangles; f++)
        if (piece[f] == label) {
            for (int k = 0; k < 3; k++) out->mesh.triangles[3 * t + k] = remap[m->triangles[3 * f + k]];
            t++;
        }
    out->mesh.nvertices = nv;
    out->mesh.ntriangles = nt;
    return ACD_OK;
}

/* Pieces = connected sets of faces with equal class across shared edges. */
static acd_status split_by_class(const acd_mesh *m, const acd_edge_graph *g, const int8_t *cls,
                                 const uint8_t *blocked, acd_cut_result *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    size_t nf = m->ntriangles;
    uint32_t *face_of = NULL, *piece = malloc((nf ? nf : 1) * sizeof *piece), *queue = malloc((nf ? nf : 1) * sizeof *queue);
    uint32_t *remap = malloc((m->nvertices ? m->nvertices : 1) * sizeof *remap);
    acd_status st = ACD_OK;
    if (!piece || !queue || !remap) {
        st = ACD_ERR_NOMEM;
        goto done;
    }
    st = acd3_edge_faces(m, g, &face_of, err);
    if (st != ACD_OK) goto done;
    for (size_t f = 0; f < nf; f++) piece[f] = UINT32_MAX;
    uint32_t np = 0;
    /* + side pieces first, each side by lowest face */
    for (int pass = 0; pass < 2; pass++) {
        int8_t want = pass == 0 ? 1 : -1;
        for (size_t s = 0; s < nf; s++) {
            if (piece[s] != UINT32_MAX || (!blocked && cls[s] != want) || (blocked && pass == 1)) continue;
            size_t qh = 0, qt = 0;
            queue[qt++] = (uint32_t)s;
            piece[s] = np;
            while (qh < qt) {
                uint32_t f = queue[qh++];
                for (int k = 0; k < 3; k++) {
                    uint32_t u = m->triangles[3 * f + k], v = m->triangles[3 * f + (k + 1) % 3];
                    uint32_t e = acd_edge_graph_find(g, u, v);
                    if (e == ACD_NO_VERTEX || (blocked && blocked[e])) continue;
                    for (int side = 0; side < 2; side++) {
                        uint32_t h = face_of[2 * (size_t)e + side];
                        if (h != UINT32_MAX && piece[h] == UINT32_MAX && (blocked || cls[h] == want)) {
                            piece[h] = np;
                            queue[qt++] = h;
                        }
                    }
                }
            }
            np++;
        }
    }
    out->pieces = calloc(np ? np : 1, sizeof *out->pieces);
    if (!out->pieces) {
        st = ACD_ERR_NOMEM;
        goto done;
    }
    for (uint32_t p = 0; p < np; p++) {
        out->npieces = p + 1;
        st = extract(m, piece, p, remap, &out->pieces[p]);
        if (st != ACD_OK) goto done;
        /* the side of the piece: the class of its first face */
        for (size_t f = 0; f < nf; f++)
            if (piece[f] == p) {
                out->pieces[p].side = cls[f];
                break;
            }
    }
done:
    free(face_of), free(piece), free(queue), free(remap);
    if (st != ACD_OK) {
        acd_cut_result_free(out);
        if (st == ACD_ERR_NOMEM) return acd_fail(err, st, "out of memory splitting a surface of %zu faces", nf);
    }
    return st;
}

acd_status acd3_surface_cut(const acd_mesh *m, const acd_edge_graph *g, const acd_cut_plane *pl, const double *near,
                            acd_cut_result *out, acd_error *err) {
    size_t nf = m->ntriangles, ne = g->nedges, nv = m->nvertices;
    int8_t *cls = malloc(nf ? nf : 1);
    uint8_t *blocked = NULL;
    uint32_t *face_of = NULL;
    size_t *par = NULL;
    acd_status st = ACD_OK;
    if (!cls) return acd_fail(err, ACD_ERR_NOMEM, "out of memory splitting a surface of %zu faces", nf);
    for (size_t f = 0; f < nf; f++) {
        double c[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++) c[j] += m->vertices[3 * (size_t)m->triangles[3 * f + k] + j] / 3.0;
        cls[f] = acd_cut_plane_side(pl, c) > 0 ? 1 : -1; /* on the plane counts as - (a fixed rule) */
    }
    if (!near) {
        st = split_by_class(m, g, cls, NULL, out, err);
        free(cls);
        return st;
    }
    /* only the loop of class-boundary edges nearest to `near` splits */
    blocked = calloc(ne ? ne : 1, 1);
    par = malloc((nv ? nv : 1) * sizeof *par);
    if (!blocked || !par) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory splitting a surface of %zu faces", nf);
        goto done;
    }
    st = acd3_edge_faces(m, g, &face_of, err);
    if (st != ACD_OK) goto done;
    for (size_t v = 0; v < nv; v++) par[v] = v;
    size_t best_e = SIZE_MAX;
    double best_d = INFINITY;
    for (size_t e = 0; e < ne; e++) {
        uint32_t f0 = face_of[2 * e], f1 = face_of[2 * e + 1];
        if (f0 == UINT32_MAX || f1 == UINT32_MAX || cls[f0] == cls[f1]) continue;
        blocked[e] = 1;
        acd_uf_union_z(par, g->edge_v[2 * e], g->edge_v[2 * e + 1]);
        const double *p = m->vertices + 3 * (size_t)g->edge_v[2 * e], *q = m->vertices + 3 * (size_t)g->edge_v[2 * e + 1];
        double d = 0;
        for (int k = 0; k < 3; k++) {
            double x = 0.5 * (p[k] + q[k]) - near[k];
            d += x * x;
        }
        if (d < best_d) {
            best_d = d;
            best_e = e;
        }
    }
    if (best_e != SIZE_MAX) {
        size_t root = acd_uf_find_z(par, g->edge_v[2 * best_e]);
        for (size_t e = 0; e < ne; e++)
            if (blocked[e] && acd_uf_find_z(par, g->edge_v[2 * e]) != root) blocked[e] = 0;
    }
    st = split_by_class(m, g, cls, blocked, out, err);
done:
    free(cls), free(blocked), free(face_of), free(par);
    return st;
}

acd_status acd3_surface_components(const acd_mesh *m, const acd_edge_graph *g, acd_cut_result *out, acd_error *err) {
    size_t nf = m->ntriangles;
    int8_t *cls = malloc(nf ? nf : 1);
    if (!cls) return acd_fail(err, ACD_ERR_NOMEM, "out of memory splitting a surface of %zu faces", nf);
    memset(cls, 1, nf);
    acd_status st = split_by_class(m, g, cls, NULL, out, err);
    free(cls);
    return st;
}
