/* acd3/surface_cut: face classes by a plane, pieces by flood fill; see surface_cut.h. */
#include "acd3/surface_cut.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd3/measure.h"
#include "core/error.h"
#include "core/union_find.h"

/* How many section strips, nearest first, are tried before the surface is left whole. */
#define ACD3_SURFACE_STRIPS 8

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

/* Labels the connected sets of faces across edges not blocked (blocked may be NULL): pieces
 * seeded from faces of class +1 first, then the others, each by lowest face. Returns the count. */
static uint32_t flood(const acd_mesh *m, const acd_edge_graph *g, const uint32_t *face_of, const int8_t *cls,
                      const uint8_t *blocked, uint32_t *piece, uint32_t *queue) {
    size_t nf = m->ntriangles;
    for (size_t f = 0; f < nf; f++) piece[f] = UINT32_MAX;
    uint32_t np = 0;
    for (int pass = 0; pass < 2; pass++)
        for (size_t s = 0; s < nf; s++) {
            if (piece[s] != UINT32_MAX || (pass == 0 && cls[s] != 1)) continue;
            size_t qh = 0, qt = 0;
            queue[qt++] = (uint32_t)s;
            piece[s] = np;
            while (qh < qt) {
                uint32_t f = queue[qh++];
                for (int k = 0; k < 3; k++) {
                    uint32_t e = acd_edge_graph_find(g, m->triangles[3 * f + k], m->triangles[3 * f + (k + 1) % 3]);
                    if (e == ACD_NO_VERTEX || (blocked && blocked[e])) continue;
                    for (int side = 0; side < 2; side++) {
                        uint32_t h = face_of[2 * (size_t)e + side];
                        if (h != UINT32_MAX && piece[h] == UINT32_MAX) {
                            piece[h] = np;
                            queue[qt++] = h;
                        }
                    }
                }
            }
            np++;
        }
    return np;
}

/* A piece made only of faces the plane crosses (in_strip) is an artefact of the jagged section
 * next to the mesh boundary (a face cut off by its crossing edges and a boundary edge), not a
 * side of the cut: it is joined to the neighbouring piece with which it shares the longest
 * blocked length (lowest piece on ties) by unblocking the edges between them. Returns the number
 * of pieces joined. */
static size_t join_strip_pieces(const acd_mesh *m, const acd_edge_graph *g, const uint32_t *face_of,
                                const uint8_t *in_strip, uint32_t np, const uint32_t *piece, uint8_t *blocked,
                                double *shared) {
    size_t nf = m->ntriangles, ne = g->nedges, joined = 0;
    uint8_t *only = malloc(np ? np : 1);
    if (!only) return 0;
    memset(only, 1, np);
    for (size_t f = 0; f < nf; f++)
        if (!in_strip[f]) only[piece[f]] = 0;
    for (uint32_t p = 0; p < np; p++) {
        if (!only[p]) continue;
        for (uint32_t q = 0; q < np; q++) shared[q] = 0;
        for (size_t e = 0; e < ne; e++) {
            uint32_t f0 = face_of[2 * e], f1 = face_of[2 * e + 1];
            if (!blocked[e] || f0 == UINT32_MAX || f1 == UINT32_MAX) continue;
            if (piece[f0] == p && piece[f1] != p) shared[piece[f1]] += g->length[e];
            if (piece[f1] == p && piece[f0] != p) shared[piece[f0]] += g->length[e];
        }
        uint32_t best = UINT32_MAX;
        for (uint32_t q = 0; q < np; q++)
            if (shared[q] > 0 && (best == UINT32_MAX || shared[q] > shared[best])) best = q;
        if (best == UINT32_MAX) continue;
        for (size_t e = 0; e < ne; e++) {
            uint32_t f0 = face_of[2 * e], f1 = face_of[2 * e + 1];
            if (!blocked[e] || f0 == UINT32_MAX || f1 == UINT32_MAX) continue;
            if ((piece[f0] == p && piece[f1] == best) || (piece[f1] == p && piece[f0] == best)) blocked[e] = 0;
        }
        joined++;
    }
    free(only);
    return joined;
}

/* Splits m along the blocked edges into pieces (see flood), joining strip-only pieces when
 * in_strip is given. */
static acd_status split_blocked(const acd_mesh *m, const acd_edge_graph *g, const uint32_t *face_of,
                                const int8_t *cls, uint8_t *blocked, const uint8_t *in_strip, acd_cut_result *out,
                                acd_error *err) {
    memset(out, 0, sizeof *out);
    size_t nf = m->ntriangles;
    uint32_t *piece = malloc((nf ? nf : 1) * sizeof *piece), *queue = malloc((nf ? nf : 1) * sizeof *queue);
    uint32_t *remap = malloc((m->nvertices ? m->nvertices : 1) * sizeof *remap);
    double *shared = NULL;
    acd_status st = ACD_OK;
    if (!piece || !queue || !remap) {
        st = ACD_ERR_NOMEM;
        goto done;
    }
    uint32_t np = flood(m, g, face_of, cls, blocked, piece, queue);
    if (in_strip && blocked && np > 1) {
        shared = malloc(np * sizeof *shared);
        if (!shared) {
            st = ACD_ERR_NOMEM;
            goto done;
        }
        if (join_strip_pieces(m, g, face_of, in_strip, np, piece, blocked, shared))
            np = flood(m, g, face_of, cls, blocked, piece, queue);
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
    free(piece), free(queue), free(remap), free(shared);
    if (st != ACD_OK) {
        acd_cut_result_free(out);
        if (st == ACD_ERR_NOMEM) return acd_fail(err, st, "out of memory splitting a surface of %zu faces", nf);
    }
    return st;
}

acd_status acd3_surface_cut(const acd_mesh *m, const acd_edge_graph *g, const acd_cut_plane *pl, const double *near,
                            acd_cut_result *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    size_t nf = m->ntriangles, ne = g->nedges, nv = m->nvertices;
    int8_t *cls = malloc(nf ? nf : 1), *vs = malloc(nv ? nv : 1);
    uint8_t *blocked = calloc(ne ? ne : 1, 1), *in_strip = malloc(nf ? nf : 1);
    uint32_t *face_of = NULL;
    size_t *par = NULL;
    double *sdist = NULL;
    uint8_t *strip = NULL;
    acd_status st = ACD_OK;
    if (!cls || !vs || !blocked || !in_strip) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory splitting a surface of %zu faces", nf);
        goto done;
    }
    st = acd3_edge_faces(m, g, &face_of, err);
    if (st != ACD_OK) goto done;
    /* vertex sides (exact; on the plane counts as +, a fixed rule), face side = the side of two
     * or three of its vertices: faces that meet across an edge whose ends are on one side are
     * on that side, so only edges crossing the plane separate faces of different sides */
    for (size_t v = 0; v < nv; v++) vs[v] = acd_cut_plane_side(pl, m->vertices + 3 * v) >= 0 ? 1 : -1;
    for (size_t f = 0; f < nf; f++) {
        int8_t a = vs[m->triangles[3 * f]], b = vs[m->triangles[3 * f + 1]], c = vs[m->triangles[3 * f + 2]];
        cls[f] = a + b + c > 0 ? 1 : -1;
        in_strip[f] = a != b || b != c;
    }
    if (!near) {
        for (size_t e = 0; e < ne; e++) {
            uint32_t f0 = face_of[2 * e], f1 = face_of[2 * e + 1];
            blocked[e] = f0 != UINT32_MAX && f1 != UINT32_MAX && cls[f0] != cls[f1];
        }
        st = split_blocked(m, g, face_of, cls, blocked, in_strip, out, err);
        goto done;
    }
    /* only the section strip nearest to `near` splits: the faces crossed by the plane, joined
     * across crossing edges, form strips (one per section loop, or an open chain ending on the
     * mesh boundary); the strip's crossing edges between faces of different sides are a chain
     * of mesh edges following the section, and the surface splits along it alone */
    par = malloc((nf ? nf : 1) * sizeof *par);
    sdist = malloc((nf ? nf : 1) * sizeof *sdist);
    strip = malloc(nf ? nf : 1);
    if (!par || !sdist || !strip) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory splitting a surface of %zu faces", nf);
        goto done;
    }
    for (size_t f = 0; f < nf; f++) par[f] = f, sdist[f] = INFINITY;
    for (size_t e = 0; e < ne; e++) {
        uint32_t f0 = face_of[2 * e], f1 = face_of[2 * e + 1];
        if (vs[g->edge_v[2 * e]] != vs[g->edge_v[2 * e + 1]] && f0 != UINT32_MAX && f1 != UINT32_MAX)
            acd_uf_union_z(par, f0, f1);
    }
    /* each strip's distance: its crossing edge nearest to `near` (by midpoint) */
    for (size_t e = 0; e < ne; e++) {
        uint32_t a = g->edge_v[2 * e], b = g->edge_v[2 * e + 1];
        uint32_t f0 = face_of[2 * e] != UINT32_MAX ? face_of[2 * e] : face_of[2 * e + 1];
        if (vs[a] == vs[b] || f0 == UINT32_MAX) continue;
        const double *p = m->vertices + 3 * (size_t)a, *q = m->vertices + 3 * (size_t)b;
        double d = 0;
        for (int k = 0; k < 3; k++) {
            double x = 0.5 * (p[k] + q[k]) - near[k];
            d += x * x;
        }
        size_t r = acd_uf_find_z(par, f0);
        if (d < sdist[r]) sdist[r] = d;
    }
    /* the strips by distance (then lowest root): the nearest one whose chain separates the
     * surface is used (a section loop around a handle, or one the joined artefacts close,
     * leaves it whole) */
    for (int attempt = 0; attempt < ACD3_SURFACE_STRIPS; attempt++) {
        size_t root = SIZE_MAX;
        for (size_t f = 0; f < nf; f++)
            if (par[f] == f && sdist[f] < INFINITY && (root == SIZE_MAX || sdist[f] < sdist[root])) root = f;
        if (root == SIZE_MAX) break;
        sdist[root] = INFINITY; /* not again */
        for (size_t e = 0; e < ne; e++) {
            uint32_t e0 = face_of[2 * e], e1 = face_of[2 * e + 1];
            blocked[e] = e0 != UINT32_MAX && e1 != UINT32_MAX && cls[e0] != cls[e1] && acd_uf_find_z(par, e0) == root;
        }
        for (size_t f = 0; f < nf; f++) strip[f] = in_strip[f] && acd_uf_find_z(par, f) == root;
        st = split_blocked(m, g, face_of, cls, blocked, strip, out, err);
        if (st != ACD_OK || out->npieces >= 2) goto done;
        acd_cut_result_free(out);
    }
    /* no strip separates: the surface, whole */
    st = split_blocked(m, g, face_of, cls, NULL, NULL, out, err);
done:
    free(cls), free(vs), free(blocked), free(in_strip), free(face_of), free(par), free(sdist), free(strip);
    return st;
}

acd_status acd3_surface_components(const acd_mesh *m, const acd_edge_graph *g, acd_cut_result *out, acd_error *err) {
    size_t nf = m->ntriangles;
    int8_t *cls = malloc(nf ? nf : 1);
    uint32_t *face_of = NULL;
    if (!cls) return acd_fail(err, ACD_ERR_NOMEM, "out of memory splitting a surface of %zu faces", nf);
    memset(cls, 1, nf);
    acd_status st = acd3_edge_faces(m, g, &face_of, err);
    if (st == ACD_OK) st = split_blocked(m, g, face_of, cls, NULL, NULL, out, err);
    free(cls);
    free(face_of);
    return st;
}
