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

/* Extracts the faces with piece label `label` into a new mesh with its own vertices: one per
 * corner class (corner = 3 f + k; see corner_classes), so the piece is cut open along blocked
 * edges even where they do not separate it. remap: 3 * ntriangles entries, all UINT32_MAX on
 * entry and on return. */
static acd_status extract(const acd_mesh *m, const uint32_t *piece, uint32_t label, const size_t *corner,
                          uint32_t *remap, acd_cut_piece *out) {
    memset(out, 0, sizeof *out);
    size_t nt = 0, nv = 0;
    for (size_t f = 0; f < m->ntriangles; f++)
        if (piece[f] == label) {
            nt++;
            for (int k = 0; k < 3; k++) {
                size_t c = corner[3 * f + k];
                if (remap[c] == UINT32_MAX) remap[c] = (uint32_t)nv++;
            }
        }
    out->mesh.vertices = malloc(3 * (nv ? nv : 1) * sizeof *out->mesh.vertices);
    out->mesh.triangles = malloc(3 * (nt ? nt : 1) * sizeof *out->mesh.triangles);
    out->source = malloc((nv ? nv : 1) * sizeof *out->source);
    out->is_cap = calloc(nt ? nt : 1, 1);
    acd_status st = ACD_OK;
    if (!out->mesh.vertices || !out->mesh.triangles || !out->source || !out->is_cap) st = ACD_ERR_NOMEM;
    size_t t = 0;
    for (size_t f = 0; f < m->ntriangles; f++)
        if (piece[f] == label) {
            for (int k = 0; k < 3; k++) {
                uint32_t v = m->triangles[3 * f + k], nvid = remap[corner[3 * f + k]];
                if (st == ACD_OK) {
                    memcpy(out->mesh.vertices + 3 * (size_t)nvid, m->vertices + 3 * (size_t)v, sizeof(double[3]));
                    out->source[nvid] = v;
                    out->mesh.triangles[3 * t + k] = nvid;
                }
            }
            t++;
        }
    for (size_t f = 0; f < m->ntriangles; f++)
        if (piece[f] == label)
            for (int k = 0; k < 3; k++) remap[corner[3 * f + k]] = UINT32_MAX;
    out->mesh.nvertices = nv;
    out->mesh.ntriangles = nt;
    return st;
}

/* Corner classes: the corners of a vertex (corner 3 f + k holds triangles[3 f + k]) are one
 * class unless the vertex is an end of a blocked edge; then its corners are grouped into the fans
 * of faces joined across its edges that are not blocked, and each fan becomes its own vertex.
 * corner[c] receives the class (a representative corner). Scratch: first (nv entries), cut (nv). */
static void corner_classes(const acd_mesh *m, const acd_edge_graph *g, const uint32_t *face_of, const uint8_t *blocked,
                           size_t *corner, size_t *first, uint8_t *cut) {
    size_t nf = m->ntriangles, nv = m->nvertices;
    for (size_t c = 0; c < 3 * nf; c++) corner[c] = c;
    memset(cut, 0, nv ? nv : 1);
    for (size_t e = 0; blocked && e < g->nedges; e++)
        if (blocked[e]) cut[g->edge_v[2 * e]] = cut[g->edge_v[2 * e + 1]] = 1;
    /* fans: at each end of an unblocked edge, the corners of its two faces */
    for (size_t e = 0; e < g->nedges; e++) {
        uint32_t f0 = face_of[2 * e], f1 = face_of[2 * e + 1];
        if (f0 == UINT32_MAX || f1 == UINT32_MAX || (blocked && blocked[e])) continue;
        for (int end = 0; end < 2; end++) {
            uint32_t v = g->edge_v[2 * e + end];
            if (!cut[v]) continue;
            size_t c0 = SIZE_MAX, c1 = SIZE_MAX;
            for (int k = 0; k < 3; k++) {
                if (m->triangles[3 * (size_t)f0 + k] == v) c0 = 3 * (size_t)f0 + k;
                if (m->triangles[3 * (size_t)f1 + k] == v) c1 = 3 * (size_t)f1 + k;
            }
            if (c0 != SIZE_MAX && c1 != SIZE_MAX) acd_uf_union_z(corner, c0, c1);
        }
    }
    /* the other vertices: all their corners one class */
    for (size_t v = 0; v < nv; v++) first[v] = SIZE_MAX;
    for (size_t c = 0; c < 3 * nf; c++) {
        uint32_t v = m->triangles[c];
        if (cut[v]) continue;
        if (first[v] == SIZE_MAX) first[v] = c;
        else acd_uf_union_z(corner, first[v], c);
    }
    for (size_t c = 0; c < 3 * nf; c++) corner[c] = acd_uf_find_z(corner, c);
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
static size_t join_pieces(const acd_mesh *m, const acd_edge_graph *g, const uint32_t *face_of, const uint8_t *only,
                          uint32_t np, const uint32_t *piece, uint8_t *blocked, double *shared) {
    size_t ne = g->nedges, joined = 0;
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
    return joined;
}

static size_t join_strip_pieces(const acd_mesh *m, const acd_edge_graph *g, const uint32_t *face_of,
                                const uint8_t *in_strip, uint32_t np, const uint32_t *piece, uint8_t *blocked,
                                double *shared) {
    uint8_t *only = malloc(np ? np : 1);
    if (!only) return 0;
    memset(only, 1, np);
    for (size_t f = 0; f < m->ntriangles; f++)
        if (!in_strip[f]) only[piece[f]] = 0;
    size_t joined = join_pieces(m, g, face_of, only, np, piece, blocked, shared);
    free(only);
    return joined;
}

static double face_area(const acd_mesh *m, size_t f) {
    const double *a = m->vertices + 3 * (size_t)m->triangles[3 * f], *b = m->vertices + 3 * (size_t)m->triangles[3 * f + 1],
                 *c = m->vertices + 3 * (size_t)m->triangles[3 * f + 2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/* One strip's chain is one loop (or one chain from boundary to boundary): it has two sides. Where
 * it runs along the mesh boundary it crosses it again and again and cuts off teeth between itself
 * and the boundary (one or two faces each); those are not sides of the cut. All pieces but the
 * two of largest area (lowest piece on ties) are joined to the neighbour they share most chain
 * length with (join_pieces). Returns the number joined. */
static size_t join_teeth(const acd_mesh *m, const acd_edge_graph *g, const uint32_t *face_of, uint32_t np,
                         const uint32_t *piece, uint8_t *blocked, double *shared) {
    if (np <= 2) return 0;
    double *area = calloc(np, sizeof *area);
    uint8_t *only = malloc(np);
    size_t joined = 0;
    if (area && only) {
        for (size_t f = 0; f < m->ntriangles; f++) area[piece[f]] += face_area(m, f);
        uint32_t a = UINT32_MAX, b = UINT32_MAX;
        for (uint32_t p = 0; p < np; p++) {
            if (a == UINT32_MAX || area[p] > area[a]) b = a, a = p;
            else if (b == UINT32_MAX || area[p] > area[b]) b = p;
        }
        for (uint32_t p = 0; p < np; p++) only[p] = p != a && p != b;
        joined = join_pieces(m, g, face_of, only, np, piece, blocked, shared);
    }
    free(area);
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
    size_t nv = m->nvertices;
    uint32_t *piece = malloc((nf ? nf : 1) * sizeof *piece), *queue = malloc((nf ? nf : 1) * sizeof *queue);
    uint32_t *remap = malloc(3 * (nf ? nf : 1) * sizeof *remap);
    size_t *corner = malloc(3 * (nf ? nf : 1) * sizeof *corner), *first = malloc((nv ? nv : 1) * sizeof *first);
    uint8_t *cut = malloc(nv ? nv : 1);
    double *shared = NULL;
    acd_status st = ACD_OK;
    if (!piece || !queue || !remap || !corner || !first || !cut) {
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
        /* teeth: joined until two pieces are left (each round joins every tooth to a neighbour,
         * so the count falls every round) */
        while (np > 2 && join_teeth(m, g, face_of, np, piece, blocked, shared))
            np = flood(m, g, face_of, cls, blocked, piece, queue);
    }
    corner_classes(m, g, face_of, blocked, corner, first, cut);
    for (size_t c = 0; c < 3 * nf; c++) remap[c] = UINT32_MAX;
    out->pieces = calloc(np ? np : 1, sizeof *out->pieces);
    if (!out->pieces) {
        st = ACD_ERR_NOMEM;
        goto done;
    }
    for (uint32_t p = 0; p < np; p++) {
        out->npieces = p + 1;
        st = extract(m, piece, p, corner, remap, &out->pieces[p]);
        if (st != ACD_OK) goto done;
        /* the side of the piece: the class of its first face */
        for (size_t f = 0; f < nf; f++)
            if (piece[f] == p) {
                out->pieces[p].side = cls[f];
                break;
            }
    }
done:
    free(piece), free(queue), free(remap), free(shared), free(corner), free(first), free(cut);
    if (st != ACD_OK) {
        acd_cut_result_free(out);
        if (st == ACD_ERR_NOMEM) return acd_fail(err, st, "out of memory splitting a surface of %zu faces", nf);
    }
    return st;
}

/* The blocked edges and strip faces of the strip with union-find root `root`. */
static void mark_strip(const acd_mesh *m, const acd_edge_graph *g, const uint32_t *face_of, const int8_t *cls,
                       const uint8_t *in_strip, size_t *par, size_t root, uint8_t *blocked, uint8_t *strip) {
    for (size_t e = 0; e < g->nedges; e++) {
        uint32_t e0 = face_of[2 * e], e1 = face_of[2 * e + 1];
        blocked[e] = e0 != UINT32_MAX && e1 != UINT32_MAX && cls[e0] != cls[e1] && acd_uf_find_z(par, e0) == root;
    }
    for (size_t f = 0; f < m->ntriangles; f++) strip[f] = in_strip[f] && acd_uf_find_z(par, f) == root;
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
    /* each strip's distance: its crossing edge nearest to `near` (by midpoint); strips with no
     * edge to cut along (a face whose crossing edges are on the mesh boundary) are not tried */
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
    for (size_t f = 0; f < nf; f++) strip[f] = 0; /* here: the strip has a chain */
    for (size_t e = 0; e < ne; e++) {
        uint32_t e0 = face_of[2 * e], e1 = face_of[2 * e + 1];
        if (e0 != UINT32_MAX && e1 != UINT32_MAX && cls[e0] != cls[e1]) strip[acd_uf_find_z(par, e0)] = 1;
    }
    for (size_t f = 0; f < nf; f++)
        if (par[f] == f && !strip[f]) sdist[f] = INFINITY;
    /* the strips by distance (then lowest root): the nearest one whose chain separates the
     * surface is used (a section loop around a handle, or one the joined artefacts close,
     * leaves it whole) */
    size_t slit = SIZE_MAX; /* the nearest strip that cuts without separating */
    for (int attempt = 0; attempt < ACD3_SURFACE_STRIPS; attempt++) {
        size_t root = SIZE_MAX;
        for (size_t f = 0; f < nf; f++)
            if (par[f] == f && sdist[f] < INFINITY && (root == SIZE_MAX || sdist[f] < sdist[root])) root = f;
        if (root == SIZE_MAX) break;
        sdist[root] = INFINITY; /* not again */
        mark_strip(m, g, face_of, cls, in_strip, par, root, blocked, strip);
        st = split_blocked(m, g, face_of, cls, blocked, strip, out, err);
        if (st != ACD_OK || out->npieces >= 2) goto done;
        if (slit == SIZE_MAX && out->npieces == 1 && out->pieces[0].mesh.nvertices > nv) slit = root;
        acd_cut_result_free(out);
    }
    /* no strip separates: the surface is cut open along the nearest strip that cuts at all (a
     * loop around a handle: the genus drops, spec §5.3 step 6), or else left whole */
    if (slit != SIZE_MAX) {
        mark_strip(m, g, face_of, cls, in_strip, par, slit, blocked, strip);
        st = split_blocked(m, g, face_of, cls, blocked, strip, out, err);
    } else {
        st = split_blocked(m, g, face_of, cls, NULL, NULL, out, err);
    }
done:
    free(cls), free(vs), free(blocked), free(in_strip), free(face_of), free(par), free(sdist), free(strip);
    return st;
}

acd_status acd3_surface_cut_chain(const acd_mesh *m, const acd_edge_graph *g, const uint32_t *v, size_t n,
                                  acd_cut_result *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    size_t nf = m->ntriangles, ne = g->nedges;
    int8_t *cls = malloc(nf ? nf : 1);
    uint8_t *blocked = calloc(ne ? ne : 1, 1), *near = calloc(nf ? nf : 1, 1);
    uint32_t *face_of = NULL;
    acd_status st = ACD_OK;
    if (!cls || !blocked || !near) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory splitting a surface of %zu faces", nf);
        goto done;
    }
    st = acd3_edge_faces(m, g, &face_of, err);
    if (st != ACD_OK) goto done;
    memset(cls, 1, nf ? nf : 1);
    /* the chain's edges (an edge of the mesh boundary separates nothing), and the faces along
     * them: a piece made only of those is a sliver between two stretches of the chain */
    for (size_t i = 0; i + 1 < n; i++) {
        uint32_t e = acd_edge_graph_find(g, v[i], v[i + 1]);
        if (e == ACD_NO_VERTEX) continue;
        uint32_t f0 = face_of[2 * (size_t)e], f1 = face_of[2 * (size_t)e + 1];
        if (f0 == UINT32_MAX || f1 == UINT32_MAX) continue;
        blocked[e] = 1;
        near[f0] = near[f1] = 1;
    }
    st = split_blocked(m, g, face_of, cls, blocked, near, out, err);
done:
    free(cls), free(blocked), free(near), free(face_of);
    return st;
}

acd_status acd3_surface_cut_deep(const acd_mesh *m, const acd_edge_graph *g, const double *level, double thr,
                                 uint32_t seed, acd_cut_result *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    size_t nf = m->ntriangles, ne = g->nedges;
    int8_t *cls = malloc(nf ? nf : 1);
    uint8_t *deep = malloc(nf ? nf : 1), *blocked = calloc(ne ? ne : 1, 1);
    uint32_t *queue = malloc((nf ? nf : 1) * sizeof *queue), *face_of = NULL;
    acd_status st = ACD_OK;
    if (!cls || !deep || !blocked || !queue) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory splitting a surface of %zu faces", nf);
        goto done;
    }
    st = acd3_edge_faces(m, g, &face_of, err);
    if (st != ACD_OK) goto done;
    /* the faces with a deep vertex; the component of the seed's faces across edges between two
     * of them (then every vertex on its border with the rest is not deep) */
    size_t qt = 0;
    for (size_t f = 0; f < nf; f++) {
        deep[f] = 0;
        cls[f] = -1;
        for (int k = 0; k < 3; k++) deep[f] |= level[m->triangles[3 * f + k]] >= thr;
        int at_seed = m->triangles[3 * f] == seed || m->triangles[3 * f + 1] == seed || m->triangles[3 * f + 2] == seed;
        if (at_seed && deep[f]) cls[f] = 1, queue[qt++] = (uint32_t)f;
    }
    for (size_t qh = 0; qh < qt; qh++) {
        uint32_t f = queue[qh];
        for (int k = 0; k < 3; k++) {
            uint32_t e = acd_edge_graph_find(g, m->triangles[3 * f + k], m->triangles[3 * f + (k + 1) % 3]);
            if (e == ACD_NO_VERTEX) continue;
            for (int side = 0; side < 2; side++) {
                uint32_t h = face_of[2 * (size_t)e + side];
                if (h != UINT32_MAX && deep[h] && cls[h] != 1) cls[h] = 1, queue[qt++] = h;
            }
        }
    }
    for (size_t e = 0; e < ne; e++) {
        uint32_t f0 = face_of[2 * e], f1 = face_of[2 * e + 1];
        blocked[e] = f0 != UINT32_MAX && f1 != UINT32_MAX && cls[f0] != cls[f1];
    }
    st = split_blocked(m, g, face_of, cls, blocked, NULL, out, err);
done:
    free(cls), free(deep), free(blocked), free(queue), free(face_of);
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
