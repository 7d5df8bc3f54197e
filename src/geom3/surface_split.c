/* geom3/surface_split: cutting a surface along edge paths (Lien D §V.B, surface ACD's resolution;
 * spec acd3d.md §5.1). Corners (triangle, vertex) are united across every uncut edge they share;
 * each class of corners becomes one output vertex, and faces are flood-filled (united) across uncut
 * edges into patches. Purely combinatorial: no geometric decision is made. */
#include "geom3/surface_split.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/union_find.h"
#include "geom3/edge_map.h"

#define NONE UINT32_MAX

static int cmp_u64(const void *x, const void *y) {
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return (a > b) - (a < b);
}

void acd_split_result_free(acd_split_result *r) {
    if (!r) return;
    for (size_t i = 0; i < r->npatches; i++) {
        acd_mesh_free(&r->patches[i].mesh);
        free(r->patches[i].source_vertex);
        free(r->patches[i].source_face);
    }
    free(r->patches);
    free(r->face_patch);
    memset(r, 0, sizeof *r);
}

static int is_cut(const uint64_t *cut, size_t ncut, uint32_t a, uint32_t b) {
    uint64_t k = a < b ? ((uint64_t)a << 32) | b : ((uint64_t)b << 32) | a;
    return bsearch(&k, cut, ncut, sizeof *cut, cmp_u64) != NULL;
}

acd_status acd_surface_split_edges(const acd_mesh *m, const uint32_t *edges, size_t nedges, acd_split_result *out,
                                   acd_error *err) {
    memset(out, 0, sizeof *out);
    size_t nt = m->ntriangles, nv = m->nvertices;
    if (nt >= UINT32_MAX / 3 || nv >= UINT32_MAX)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "surface split: mesh too large");
    for (size_t i = 0; i < 3 * nt; i++)
        if (m->triangles[i] >= nv)
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "surface split: triangle %zu uses vertex %u of %zu", i / 3,
                            m->triangles[i], nv);
    acd_edge_map em;
    acd_status st = acd_edge_map_build(m->triangles, nt, NULL, &em, err);
    if (st != ACD_OK) return st;
    for (size_t i = 0; i + 1 < em.n; i++)
        if (em.key[i] == em.key[i + 1]) {
            st = acd_fail(err, ACD_ERR_NON_MANIFOLD,
                          "surface split: edge (%u, %u) is used in the same direction by triangles %u and %u",
                          (uint32_t)(em.key[i] >> 32), (uint32_t)em.key[i], em.half[i] / 3, em.half[i + 1] / 3);
            acd_edge_map_free(&em);
            return st;
        }
    uint64_t *cut = malloc((nedges ? nedges : 1) * sizeof *cut);
    uint32_t *corner = malloc((nt ? nt : 1) * 3 * sizeof *corner);
    uint32_t *face = malloc((nt ? nt : 1) * sizeof *face);
    uint32_t *cid = malloc((nt ? nt : 1) * 3 * sizeof *cid);
    uint32_t *pid = malloc((nt ? nt : 1) * sizeof *pid);
    size_t *pcount = NULL;
    if (!cut || !corner || !face || !cid || !pid) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory splitting a surface of %zu triangles", nt);
        goto done;
    }
    for (size_t i = 0; i < nedges; i++) {
        uint32_t a = edges[2 * i], b = edges[2 * i + 1];
        if (a >= nv || b >= nv || a == b ||
            (acd_edge_map_find(&em, a, b) == ACD_EDGE_NONE && acd_edge_map_find(&em, b, a) == ACD_EDGE_NONE)) {
            st = acd_fail(err, ACD_ERR_INVALID_INPUT, "surface split: cut edge %zu (%u, %u) is not an edge of the mesh", i,
                          a, b);
            goto done;
        }
        cut[i] = a < b ? ((uint64_t)a << 32) | b : ((uint64_t)b << 32) | a;
    }
    qsort(cut, nedges, sizeof *cut, cmp_u64);
    size_t ncut = 0;
    for (size_t i = 0; i < nedges; i++)
        if (ncut == 0 || cut[i] != cut[ncut - 1]) cut[ncut++] = cut[i];
    out->cut_edges = ncut;
    for (size_t i = 0; i < 3 * nt; i++) corner[i] = (uint32_t)i;
    for (size_t t = 0; t < nt; t++) face[t] = (uint32_t)t;
    /* across every uncut interior edge: unite the faces and the corners of the shared vertices */
    for (size_t t = 0; t < nt; t++)
        for (int i = 0; i < 3; i++) {
            uint32_t a = m->triangles[3 * t + i], b = m->triangles[3 * t + (i + 1) % 3];
            uint32_t h = acd_edge_map_find(&em, b, a);
            if (h == ACD_EDGE_NONE || is_cut(cut, ncut, a, b)) continue;
            uint32_t u = h / 3, j = h % 3; /* in u, corner j is b, corner j+1 is a */
            acd_uf_union(face, (uint32_t)t, u);
            acd_uf_union(corner, (uint32_t)(3 * t + (size_t)i), 3 * u + (j + 1) % 3);
            acd_uf_union(corner, (uint32_t)(3 * t + (size_t)(i + 1) % 3), 3 * u + j);
        }
    /* patches in order of their lowest triangle; vertices in order of first use within a patch */
    size_t np = 0;
    for (size_t t = 0; t < nt; t++) pid[t] = acd_uf_find(face, (uint32_t)t) == t ? (uint32_t)np++ : NONE;
    out->face_patch = malloc((nt ? nt : 1) * sizeof *out->face_patch);
    out->patches = calloc(np ? np : 1, sizeof *out->patches);
    pcount = calloc(np ? np : 1, sizeof *pcount);
    if (!out->face_patch || !out->patches || !pcount) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for %zu patches", np);
        goto done;
    }
    out->npatches = np;
    for (size_t t = 0; t < nt; t++) {
        out->face_patch[t] = pid[acd_uf_find(face, (uint32_t)t)];
        pcount[out->face_patch[t]]++;
    }
    for (size_t p = 0; p < np; p++) {
        acd_patch *pc = &out->patches[p];
        pc->mesh.triangles = malloc((pcount[p] ? pcount[p] : 1) * 3 * sizeof *pc->mesh.triangles);
        pc->source_face = malloc((pcount[p] ? pcount[p] : 1) * sizeof *pc->source_face);
        pc->source_vertex = malloc((pcount[p] ? 3 * pcount[p] : 1) * sizeof *pc->source_vertex);
        pc->mesh.vertices = malloc((pcount[p] ? 3 * pcount[p] : 1) * 3 * sizeof *pc->mesh.vertices);
        if (!pc->mesh.triangles || !pc->source_face || !pc->source_vertex || !pc->mesh.vertices) {
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for a patch of %zu triangles", pcount[p]);
            goto done;
        }
    }
    for (size_t i = 0; i < 3 * nt; i++) cid[i] = NONE; /* corner class root -> vertex id in its patch */
    for (size_t t = 0; t < nt; t++) {
        acd_patch *pc = &out->patches[out->face_patch[t]];
        size_t k = pc->mesh.ntriangles++;
        pc->source_face[k] = (uint32_t)t;
        for (int i = 0; i < 3; i++) {
            uint32_t r = acd_uf_find(corner, (uint32_t)(3 * t + (size_t)i));
            if (cid[r] == NONE) {
                uint32_t v = m->triangles[3 * t + i];
                cid[r] = (uint32_t)pc->mesh.nvertices++;
                pc->source_vertex[cid[r]] = v;
                memcpy(pc->mesh.vertices + 3 * (size_t)cid[r], m->vertices + 3 * (size_t)v, 3 * sizeof(double));
            }
            pc->mesh.triangles[3 * k + i] = cid[r];
        }
    }
    for (size_t p = 0; p < np; p++) { /* trim to size */
        acd_patch *pc = &out->patches[p];
        size_t n = pc->mesh.nvertices ? pc->mesh.nvertices : 1;
        double *v = realloc(pc->mesh.vertices, n * 3 * sizeof *v);
        uint32_t *s = realloc(pc->source_vertex, n * sizeof *s);
        if (v) pc->mesh.vertices = v;
        if (s) pc->source_vertex = s;
    }
done:
    acd_edge_map_free(&em);
    free(cut);
    free(corner);
    free(face);
    free(cid);
    free(pid);
    free(pcount);
    if (st != ACD_OK) acd_split_result_free(out);
    return st;
}

acd_status acd_surface_split_path(const acd_mesh *m, const uint32_t *path, size_t n, int closed,
                                  acd_split_result *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    size_t ne = n < 2 ? 0 : (closed && n > 2 ? n : n - 1);
    uint32_t *e = malloc((ne ? ne : 1) * 2 * sizeof *e);
    if (!e) return acd_fail(err, ACD_ERR_NOMEM, "out of memory for a path of %zu vertices", n);
    for (size_t i = 0; i < ne; i++) {
        e[2 * i] = path[i];
        e[2 * i + 1] = path[(i + 1) % n];
    }
    acd_status st = acd_surface_split_edges(m, e, ne, out, err);
    free(e);
    return st;
}
