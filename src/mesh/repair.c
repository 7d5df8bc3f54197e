/* mesh/repair: welding, removal of degenerate and duplicate faces, consistent orientation
 * (closed parts outward), filling of small holes, removal of unused vertices.
 *
 * design (acd_mesh_repair):
 *  1. weld (mesh/weld: exact hashing or a tolerance grid);
 *  2. drop faces that repeat a vertex or have zero area (exact: all three coordinate projections
 *     collinear by acd_orient2d), then faces whose sorted vertex triple was seen before;
 *  3. orient: breadth-first over manifold edges from each part's first face, flipping a face
 *     when it traverses the shared edge in the same direction as its neighbour; a part all of
 *     whose edges are manifold (closed) is reversed if its signed volume is negative, an open
 *     part is reversed if that flips fewer faces (majority orientation kept);
 *  4. fill holes: boundary loops traced along boundary half-edges; a loop of at most
 *     fill_holes_max_edges edges is closed by a fan from its first vertex, oriented against the
 *     loop (so the new faces agree with their neighbours); then orient again;
 *  5. drop unused vertices. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/mesh.h"
#include "core/error.h"
#include "core/predicates.h"
#include "core/tolerance.h"
#include "mesh/halfedge.h"
#include "mesh/weld.h"

acd_repair_options acd_repair_default_options(void) {
    acd_repair_options o;
    o.weld = 1;
    o.weld_tolerance = 0;
    o.drop_degenerate = 1;
    o.drop_duplicates = 1;
    o.orient = 1;
    o.fill_holes_max_edges = 0;
    o.drop_unused_vertices = 1;
    return o;
}

acd_status acd_mesh_weld(acd_mesh *m, double tol_rel, size_t *merged, acd_error *err) {
    if (!m || (m->nvertices && !m->vertices)) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_weld: NULL mesh");
    if (!(tol_rel >= 0) || !isfinite(tol_rel))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_weld: tolerance %g is not a finite number >= 0", tol_rel);
    for (size_t i = 0; i < 3 * m->ntriangles; i++)
        if (m->triangles[i] >= m->nvertices)
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "triangle %zu refers to vertex %u of %zu", i / 3, m->triangles[i],
                            m->nvertices);
    if (merged) *merged = 0;
    if (m->nvertices == 0) return ACD_OK;
    uint32_t *remap = malloc(m->nvertices * sizeof *remap);
    if (!remap) return acd_fail(err, ACD_ERR_NOMEM, "out of memory welding %zu vertices", m->nvertices);
    size_t u;
    int ok;
    if (tol_rel > 0) {
        acd_scale sc = acd_scale_of_points(m->vertices, m->nvertices, 3);
        ok = acd_weld_tolerance(m->vertices, m->nvertices, tol_rel * sc.extent, remap, &u);
    } else {
        ok = acd_weld_exact(m->vertices, m->nvertices, remap, &u);
    }
    if (!ok) {
        free(remap);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory welding %zu vertices", m->nvertices);
    }
    for (size_t i = 0; i < 3 * m->ntriangles; i++) m->triangles[i] = remap[m->triangles[i]];
    acd_weld_compact(m->vertices, m->nvertices, remap);
    if (merged) *merged = m->nvertices - u;
    m->nvertices = u;
    free(remap);
    return ACD_OK;
}

static int zero_area(const double *a, const double *b, const double *c) {
    for (int d = 0; d < 3; d++) {
        double pa[2] = {a[(d + 1) % 3], a[(d + 2) % 3]}, pb[2] = {b[(d + 1) % 3], b[(d + 2) % 3]},
               pc[2] = {c[(d + 1) % 3], c[(d + 2) % 3]};
        if (acd_orient2d_sign(pa, pb, pc) != 0) return 0;
    }
    return 1;
}

/* Keeps the faces with keep[t] != 0, in order. */
static void filter_faces(acd_mesh *m, const unsigned char *keep) {
    size_t n = 0;
    for (size_t t = 0; t < m->ntriangles; t++)
        if (keep[t]) {
            if (n != t) memmove(m->triangles + 3 * n, m->triangles + 3 * t, 3 * sizeof(uint32_t));
            n++;
        }
    m->ntriangles = n;
}

typedef struct tri_key {
    uint32_t v[3];
    uint32_t t;
} tri_key;

static int cmp_key(const void *x, const void *y) {
    const tri_key *a = x, *b = y;
    for (int k = 0; k < 3; k++)
        if (a->v[k] != b->v[k]) return a->v[k] < b->v[k] ? -1 : 1;
    return a->t < b->t ? -1 : a->t > b->t;
}

static acd_status drop_faces(acd_mesh *m, int degenerate, int duplicates, acd_repair_stats *st, acd_error *err) {
    size_t nt = m->ntriangles;
    if (!nt) return ACD_OK;
    unsigned char *keep = malloc(nt);
    tri_key *keys = duplicates ? malloc(nt * sizeof *keys) : NULL;
    if (!keep || (duplicates && !keys)) {
        free(keep);
        free(keys);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory repairing %zu faces", nt);
    }
    for (size_t t = 0; t < nt; t++) {
        const uint32_t *i = m->triangles + 3 * t;
        keep[t] = 1;
        if (degenerate && (i[0] == i[1] || i[1] == i[2] || i[0] == i[2] ||
                           zero_area(m->vertices + 3 * (size_t)i[0], m->vertices + 3 * (size_t)i[1],
                                     m->vertices + 3 * (size_t)i[2]))) {
            keep[t] = 0;
            st->degenerate_dropped++;
        }
    }
    if (duplicates) {
        size_t n = 0;
        for (size_t t = 0; t < nt; t++) {
            if (!keep[t]) continue;
            uint32_t a = m->triangles[3 * t], b = m->triangles[3 * t + 1], c = m->triangles[3 * t + 2], x;
            if (a > b) { x = a; a = b; b = x; }
            if (b > c) { x = b; b = c; c = x; }
            if (a > b) { x = a; a = b; b = x; }
            keys[n].v[0] = a;
            keys[n].v[1] = b;
            keys[n].v[2] = c;
            keys[n].t = (uint32_t)t;
            n++;
        }
        qsort(keys, n, sizeof *keys, cmp_key);
        for (size_t i = 1; i < n; i++)
            if (!memcmp(keys[i].v, keys[i - 1].v, sizeof keys[i].v)) {
                keep[keys[i].t] = 0; /* the first face (lowest index) of each group stays */
                st->duplicates_dropped++;
            }
    }
    filter_faces(m, keep);
    free(keep);
    free(keys);
    return ACD_OK;
}

static double tet_volume(const acd_mesh *m, size_t t, const double o[3]) {
    const uint32_t *i = m->triangles + 3 * t;
    const double *a = m->vertices + 3 * (size_t)i[0], *b = m->vertices + 3 * (size_t)i[1],
                 *c = m->vertices + 3 * (size_t)i[2];
    double pa[3] = {a[0] - o[0], a[1] - o[1], a[2] - o[2]}, pb[3] = {b[0] - o[0], b[1] - o[1], b[2] - o[2]},
           pc[3] = {c[0] - o[0], c[1] - o[1], c[2] - o[2]};
    return (pa[0] * (pb[1] * pc[2] - pb[2] * pc[1]) - pa[1] * (pb[0] * pc[2] - pb[2] * pc[0]) +
            pa[2] * (pb[0] * pc[1] - pb[1] * pc[0])) / 6.0;
}

static void flip_face(acd_mesh *m, size_t t) {
    uint32_t x = m->triangles[3 * t + 1];
    m->triangles[3 * t + 1] = m->triangles[3 * t + 2];
    m->triangles[3 * t + 2] = x;
}

static acd_status orient(acd_mesh *m, acd_repair_stats *st, int count_nonorientable, acd_error *err) {
    size_t nt = m->ntriangles;
    if (!nt) return ACD_OK;
    acd_halfedges he;
    acd_status s = acd_halfedges_build(m, &he, err);
    if (s != ACD_OK) return s;
    unsigned char *flip = calloc(nt, 1), *seen = calloc(nt, 1);
    uint32_t *queue = malloc(nt * sizeof *queue);
    if (!flip || !seen || !queue) {
        s = acd_fail(err, ACD_ERR_NOMEM, "out of memory orienting %zu faces", nt);
        goto done;
    }
    double o[3] = {0, 0, 0};
    if (m->nvertices) memcpy(o, m->vertices, sizeof o); /* any fixed origin: volumes of closed parts do not depend on it */
    for (size_t t0 = 0; t0 < nt; t0++) {
        if (seen[t0]) continue;
        size_t qh = 0, qt = 0, nflip = 0;
        int closed = 1, orientable = 1;
        queue[qt++] = (uint32_t)t0;
        seen[t0] = 1;
        while (qh < qt) {
            uint32_t t = queue[qh++];
            for (uint32_t k = 0; k < 3; k++) {
                uint32_t h = 3 * t + k, g = he.twin[h];
                if (g == ACD_HE_NONE) {
                    closed = 0;
                    continue;
                }
                unsigned char want = (unsigned char)(flip[t] ^ (acd_he_from(m, g) == acd_he_from(m, h)));
                uint32_t u = g / 3;
                if (!seen[u]) {
                    seen[u] = 1;
                    flip[u] = want;
                    nflip += want;
                    queue[qt++] = u;
                } else if (flip[u] != want) {
                    orientable = 0;
                }
            }
        }
        if (!orientable && count_nonorientable) st->nonorientable_parts++;
        int reverse;
        if (closed && orientable) {
            double vol = 0;
            for (size_t i = 0; i < qt; i++) {
                double v = tet_volume(m, queue[i], o);
                vol += flip[queue[i]] ? -v : v;
            }
            reverse = vol < 0;
        } else {
            reverse = 2 * nflip > qt;
        }
        for (size_t i = 0; i < qt; i++) {
            uint32_t t = queue[i];
            if (flip[t] ^ (unsigned char)reverse) {
                flip_face(m, t);
                st->faces_flipped++;
            }
        }
    }
done:
    free(flip);
    free(seen);
    free(queue);
    acd_halfedges_free(&he);
    return s;
}

static acd_status fill_holes(acd_mesh *m, size_t max_edges, acd_repair_stats *st, acd_error *err) {
    if (!max_edges || !m->ntriangles) return ACD_OK;
    acd_halfedges he;
    acd_status s = acd_halfedges_build(m, &he, err);
    if (s != ACD_OK) return s;
    size_t nh = he.nhalfedges;
    /* boundary half-edges by their start vertex (CSR over vertices) */
    uint32_t *start = calloc(m->nvertices + 1, sizeof *start);
    uint32_t *list = malloc((nh ? nh : 1) * sizeof *list);
    unsigned char *used = calloc(nh ? nh : 1, 1);
    uint32_t *loop = malloc((max_edges + 1) * sizeof *loop);
    uint32_t *loopv = malloc((max_edges + 1) * sizeof *loopv);
    uint32_t *added = NULL;
    size_t nadded = 0, cap = 0;
    if (!start || !list || !used || !loop || !loopv) {
        s = acd_fail(err, ACD_ERR_NOMEM, "out of memory filling holes");
        goto done;
    }
    for (size_t h = 0; h < nh; h++)
        if (he.edge[h] != ACD_HE_NONE && acd_edge_valence(&he, he.edge[h]) == 1) start[acd_he_from(m, (uint32_t)h) + 1]++;
    for (size_t v = 0; v < m->nvertices; v++) start[v + 1] += start[v];
    {
        uint32_t *fillp = malloc((m->nvertices ? m->nvertices : 1) * sizeof *fillp);
        if (!fillp) {
            s = acd_fail(err, ACD_ERR_NOMEM, "out of memory filling holes");
            goto done;
        }
        memcpy(fillp, start, m->nvertices * sizeof *fillp);
        for (size_t h = 0; h < nh; h++)
            if (he.edge[h] != ACD_HE_NONE && acd_edge_valence(&he, he.edge[h]) == 1)
                list[fillp[acd_he_from(m, (uint32_t)h)]++] = (uint32_t)h;
        free(fillp);
    }
    for (size_t v0 = 0; v0 < m->nvertices; v0++)
        for (uint32_t i = start[v0]; i < start[v0 + 1]; i++) {
            uint32_t h = list[i];
            if (used[h]) continue;
            /* trace the loop from h; give up (leave it open) when it is longer than max_edges */
            size_t n = 0;
            int closed = 0;
            uint32_t cur = h;
            while (n <= max_edges) {
                loop[n] = cur;
                loopv[n] = acd_he_from(m, cur);
                n++;
                uint32_t w = acd_he_to(m, cur), next = ACD_HE_NONE;
                for (uint32_t j = start[w]; j < start[w + 1]; j++)
                    if (!used[list[j]] && list[j] != cur) {
                        int in_loop = 0;
                        for (size_t q = 1; q < n; q++) in_loop |= loop[q] == list[j];
                        if (!in_loop) {
                            next = list[j];
                            break;
                        }
                    }
                if (w == loopv[0]) {
                    closed = 1;
                    break;
                }
                if (next == ACD_HE_NONE) break;
                cur = next;
            }
            if (!closed || n < 3 || n > max_edges) {
                for (size_t q = 0; q < n && q <= max_edges; q++) used[loop[q]] = 1;
                continue;
            }
            for (size_t q = 0; q < n; q++) used[loop[q]] = 1;
            /* the loop runs v0 -> v1 -> ... ; the filling faces run against it */
            for (size_t q = 1; q + 1 < n; q++) {
                if (nadded == cap) {
                    size_t c2 = cap ? 2 * cap : 64;
                    uint32_t *a2 = realloc(added, c2 * 3 * sizeof *a2);
                    if (!a2) {
                        s = acd_fail(err, ACD_ERR_NOMEM, "out of memory filling holes");
                        goto done;
                    }
                    added = a2;
                    cap = c2;
                }
                added[3 * nadded] = loopv[0];
                added[3 * nadded + 1] = loopv[q + 1];
                added[3 * nadded + 2] = loopv[q];
                nadded++;
            }
            st->holes_filled++;
        }
    if (nadded) {
        uint32_t *t2 = realloc(m->triangles, (m->ntriangles + nadded) * 3 * sizeof *t2);
        if (!t2) {
            s = acd_fail(err, ACD_ERR_NOMEM, "out of memory filling holes");
            goto done;
        }
        m->triangles = t2;
        memcpy(m->triangles + 3 * m->ntriangles, added, nadded * 3 * sizeof *added);
        m->ntriangles += nadded;
        st->hole_faces_added += nadded;
    }
done:
    free(start);
    free(list);
    free(used);
    free(loop);
    free(loopv);
    free(added);
    acd_halfedges_free(&he);
    return s;
}

static acd_status drop_unused(acd_mesh *m, acd_repair_stats *st, acd_error *err) {
    if (!m->nvertices) return ACD_OK;
    uint32_t *remap = malloc(m->nvertices * sizeof *remap);
    if (!remap) return acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < m->nvertices; i++) remap[i] = UINT32_MAX;
    for (size_t i = 0; i < 3 * m->ntriangles; i++) remap[m->triangles[i]] = 0;
    size_t n = 0;
    for (size_t i = 0; i < m->nvertices; i++)
        if (remap[i] == 0) {
            remap[i] = (uint32_t)n;
            if (n != i) memcpy(m->vertices + 3 * n, m->vertices + 3 * i, 3 * sizeof(double));
            n++;
        }
    for (size_t i = 0; i < 3 * m->ntriangles; i++) m->triangles[i] = remap[m->triangles[i]];
    st->unused_vertices_dropped += m->nvertices - n;
    m->nvertices = n;
    free(remap);
    return ACD_OK;
}

acd_status acd_mesh_repair(acd_mesh *m, const acd_repair_options *opt, acd_repair_stats *stats, acd_error *err) {
    acd_repair_stats local;
    acd_repair_stats *st = stats ? stats : &local;
    memset(st, 0, sizeof *st);
    if (!m || !opt || (m->nvertices && !m->vertices) || (m->ntriangles && !m->triangles))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_repair: NULL argument");
    for (size_t i = 0; i < 3 * m->nvertices; i++)
        if (!isfinite(m->vertices[i]))
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "vertex %zu has a non-finite coordinate", i / 3);
    for (size_t i = 0; i < 3 * m->ntriangles; i++)
        if (m->triangles[i] >= m->nvertices)
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "triangle %zu refers to vertex %u of %zu", i / 3, m->triangles[i],
                            m->nvertices);
    acd_status s;
    if (opt->weld && (s = acd_mesh_weld(m, opt->weld_tolerance, &st->vertices_merged, err)) != ACD_OK) return s;
    if ((opt->drop_degenerate || opt->drop_duplicates) &&
        (s = drop_faces(m, opt->drop_degenerate, opt->drop_duplicates, st, err)) != ACD_OK)
        return s;
    if (opt->orient && (s = orient(m, st, opt->fill_holes_max_edges == 0, err)) != ACD_OK) return s;
    if (opt->fill_holes_max_edges) {
        if ((s = fill_holes(m, opt->fill_holes_max_edges, st, err)) != ACD_OK) return s;
        if (opt->orient && (s = orient(m, st, 1, err)) != ACD_OK) return s;
    }
    if (opt->drop_unused_vertices && (s = drop_unused(m, st, err)) != ACD_OK) return s;
    return ACD_OK;
}
