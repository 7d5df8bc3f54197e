/* mesh/validate: the mesh report: counts, edges by valence, non-manifold vertices (fans),
 * components, orientability and orientation, genus per closed component, degenerate and
 * duplicate faces, volume, area and self-intersections.
 *
 * design:
 *  1. check indices and coordinates (data errors), bounding box;
 *  2. half-edge view (mesh/halfedge): edge valences give boundary and non-manifold edges;
 *  3. components: union-find of faces over shared edges;
 *  4. fans: union-find of face corners across manifold edges; a vertex with more than one fan is
 *     non-manifold; Euler characteristic per component chi = fans - edges + faces, so that a
 *     pinched vertex counts once per sheet and the genus is that of the unpinched surface;
 *  5. orientation: breadth-first propagation over manifold edges of a flip bit per face (the
 *     two faces of an edge must traverse it in opposite directions once flips are applied); a
 *     contradiction makes the component non-orientable;
 *  6. genus of a closed orientable component = (2 - chi) / 2 (Euler-Poincare);
 *  7. volume by the divergence theorem (sum of signed tetrahedra to the box centre), area;
 *  8. degenerate faces: repeated index, or all three coordinate projections collinear (exact);
 *     duplicates: sorted index triples compared after sorting;
 *  9. self-intersections (mesh/selfintersect) on request. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/mesh.h"
#include "core/error.h"
#include "core/tolerance.h"
#include "core/union_find.h"
#include "core/predicates.h"
#include "mesh/halfedge.h"

void acd_mesh_report_free(acd_mesh_report *r) {
    if (!r) return;
    free(r->component);
    r->component = NULL;
}

static int zero_area(const double *a, const double *b, const double *c) {
    for (int d = 0; d < 3; d++) {
        double pa[2] = {a[(d + 1) % 3], a[(d + 2) % 3]}, pb[2] = {b[(d + 1) % 3], b[(d + 2) % 3]},
               pc[2] = {c[(d + 1) % 3], c[(d + 2) % 3]};
        if (acd_orient2d_sign(pa, pb, pc) != 0) return 0;
    }
    return 1;
}

static int cmp_triple(const void *x, const void *y) {
    const uint32_t *a = x, *b = y;
    for (int k = 0; k < 3; k++)
        if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
    return 0;
}

static void sort3(uint32_t t[3]) {
    uint32_t x;
    if (t[0] > t[1]) { x = t[0]; t[0] = t[1]; t[1] = x; }
    if (t[1] > t[2]) { x = t[1]; t[1] = t[2]; t[2] = x; }
    if (t[0] > t[1]) { x = t[0]; t[0] = t[1]; t[1] = x; }
}

/* The corner of triangle t at vertex v. */
static uint32_t corner_of(const acd_mesh *m, uint32_t t, uint32_t v) {
    const uint32_t *i = m->triangles + 3 * (size_t)t;
    return 3 * t + (i[0] == v ? 0u : i[1] == v ? 1u : 2u);
}

acd_status acd_mesh_validate(const acd_mesh *m, int check_self_intersections, acd_mesh_report *r, acd_error *err) {
    if (!m || !r || (m->nvertices && !m->vertices) || (m->ntriangles && !m->triangles))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_validate: NULL argument");
    memset(r, 0, sizeof *r);
    if (acd_check_coordinates(m->vertices, m->nvertices, 3, err) != ACD_OK) return ACD_ERR_INVALID_INPUT;
    const size_t nt = m->ntriangles, nv = m->nvertices;
    r->vertices = nv;
    r->faces = nt;
    for (size_t i = 0; i < nv; i++)
        for (int k = 0; k < 3; k++) {
            double x = m->vertices[3 * i + (size_t)k];
            if (i == 0 || x < r->bbox_min[k]) r->bbox_min[k] = x;
            if (i == 0 || x > r->bbox_max[k]) r->bbox_max[k] = x;
        }
    acd_halfedges he;
    acd_status s = acd_halfedges_build(m, &he, err);
    if (s != ACD_OK) return s;
    r->edges = he.nedges;

    uint32_t *fparent = malloc((nt ? nt : 1) * sizeof *fparent);
    uint32_t *cparent = malloc((nt ? 3 * nt : 1) * sizeof *cparent);
    uint32_t *comp = malloc((nt ? nt : 1) * sizeof *comp);
    unsigned char *flip = calloc(nt ? nt : 1, 1), *seen = calloc(nt ? nt : 1, 1);
    uint32_t *queue = malloc((nt ? nt : 1) * sizeof *queue);
    uint32_t *vfans = calloc(nv ? nv : 1, sizeof *vfans);
    uint32_t *vstamp = malloc((nv ? nv : 1) * sizeof *vstamp);
    uint32_t *keys = malloc((nt ? 3 * nt : 1) * sizeof *keys);
    if (!fparent || !cparent || !comp || !flip || !seen || !queue || !vfans || !vstamp || !keys) {
        s = acd_fail(err, ACD_ERR_NOMEM, "out of memory validating %zu triangles", nt);
        goto done;
    }
    /* edges by valence; face components; corner fans */
    for (size_t t = 0; t < nt; t++) fparent[t] = (uint32_t)t;
    for (size_t c = 0; c < 3 * nt; c++) cparent[c] = (uint32_t)c;
    for (size_t e = 0; e < he.nedges; e++) {
        uint32_t n = acd_edge_valence(&he, (uint32_t)e);
        const uint32_t *hs = he.edge_he + he.edge_start[e];
        if (n == 1) r->boundary_edges++;
        if (n > 2) r->nonmanifold_edges++;
        for (uint32_t k = 1; k < n; k++) acd_uf_union(fparent, hs[0] / 3, hs[k] / 3);
        if (n == 2) {
            uint32_t h0 = hs[0], h1 = hs[1], a = acd_he_from(m, h0), b = acd_he_to(m, h0);
            if (acd_he_from(m, h1) == a) r->orientation_conflicts++;
            acd_uf_union(cparent, h0, corner_of(m, h1 / 3, a));
            acd_uf_union(cparent, acd_he_next(h0), corner_of(m, h1 / 3, b));
        }
    }
    /* component numbering by first face; faces repeating an index belong to none */
    for (size_t t = 0; t < nt; t++) {
        const uint32_t *i = m->triangles + 3 * t;
        if (i[0] == i[1] || i[1] == i[2] || i[0] == i[2]) {
            comp[t] = UINT32_MAX;
            continue;
        }
        uint32_t root = acd_uf_find(fparent, (uint32_t)t);
        comp[t] = root == t ? (uint32_t)r->components++ : comp[root];
    }
    r->component = calloc(r->components ? r->components : 1, sizeof *r->component);
    if (!r->component) {
        s = acd_fail(err, ACD_ERR_NOMEM, "out of memory for %zu components", r->components);
        goto done;
    }
    /* bounding box centre as the origin of the volume sum (smaller rounding) */
    double o[3];
    for (int k = 0; k < 3; k++) o[k] = nv ? 0.5 * (r->bbox_min[k] + r->bbox_max[k]) : 0;
    for (size_t t = 0; t < nt; t++) {
        const uint32_t *i = m->triangles + 3 * t;
        const double *a = m->vertices + 3 * (size_t)i[0], *b = m->vertices + 3 * (size_t)i[1],
                     *c = m->vertices + 3 * (size_t)i[2];
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
        double area = 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double pa[3] = {a[0] - o[0], a[1] - o[1], a[2] - o[2]}, pb[3] = {b[0] - o[0], b[1] - o[1], b[2] - o[2]},
               pc[3] = {c[0] - o[0], c[1] - o[1], c[2] - o[2]};
        double vol = (pa[0] * (pb[1] * pc[2] - pb[2] * pc[1]) - pa[1] * (pb[0] * pc[2] - pb[2] * pc[0]) +
                      pa[2] * (pb[0] * pc[1] - pb[1] * pc[0])) / 6.0;
        r->area += area;
        r->volume += vol;
        int topo = i[0] == i[1] || i[1] == i[2] || i[0] == i[2];
        if (topo || zero_area(a, b, c)) r->degenerate_faces++;
        if (comp[t] != UINT32_MAX) {
            acd_mesh_component *cp = &r->component[comp[t]];
            cp->faces++;
            cp->area += area;
            cp->volume += vol;
        }
        uint32_t k3[3] = {i[0], i[1], i[2]};
        sort3(k3);
        memcpy(keys + 3 * t, k3, sizeof k3);
    }
    qsort(keys, nt, 3 * sizeof *keys, cmp_triple);
    for (size_t t = 1; t < nt; t++)
        if (!cmp_triple(keys + 3 * t, keys + 3 * (t - 1))) r->duplicate_faces++;
    /* edges per component */
    for (size_t e = 0; e < he.nedges; e++) {
        uint32_t n = acd_edge_valence(&he, (uint32_t)e);
        acd_mesh_component *cp = &r->component[comp[he.edge_he[he.edge_start[e]] / 3]];
        cp->edges++;
        if (n == 1) cp->boundary_edges++;
        if (n > 2) cp->nonmanifold_edges++;
    }
    /* vertices: distinct per component, fans per vertex and per component */
    for (size_t i = 0; i < nv; i++) vstamp[i] = UINT32_MAX;
    long *cfans = calloc(r->components ? r->components : 1, sizeof *cfans);
    if (!cfans) {
        s = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
        goto done;
    }
    size_t used = 0;
    for (size_t c = 0; c < 3 * nt; c++) {
        uint32_t t = (uint32_t)(c / 3), v = m->triangles[c];
        if (comp[t] == UINT32_MAX) continue;
        if (vstamp[v] == UINT32_MAX) used++;
        if (vstamp[v] != comp[t]) {
            vstamp[v] = comp[t];
            r->component[comp[t]].vertices++;
        }
        if (acd_uf_find(cparent, (uint32_t)c) == c) {
            vfans[v]++;
            cfans[comp[t]]++;
        }
    }
    /* vertices used only by faces repeating an index still count as used */
    for (size_t c = 0; c < 3 * nt; c++)
        if (comp[c / 3] == UINT32_MAX && vstamp[m->triangles[c]] == UINT32_MAX) {
            vstamp[m->triangles[c]] = UINT32_MAX - 1;
            used++;
        }
    r->unused_vertices = nv - used;
    for (size_t i = 0; i < nv; i++) r->nonmanifold_vertices += vfans[i] > 1;
    /* orientation propagation per component */
    for (size_t c = 0; c < r->components; c++) {
        r->component[c].orientable = 1;
        r->component[c].oriented = 1;
    }
    for (size_t t0 = 0; t0 < nt; t0++) {
        if (seen[t0] || comp[t0] == UINT32_MAX) continue;
        acd_mesh_component *cp = &r->component[comp[t0]];
        size_t qh = 0, qt = 0;
        queue[qt++] = (uint32_t)t0;
        seen[t0] = 1;
        while (qh < qt) {
            uint32_t t = queue[qh++];
            for (uint32_t k = 0; k < 3; k++) {
                uint32_t h = 3 * t + k, g = he.twin[h];
                if (g == ACD_HE_NONE) continue;
                int same_dir = acd_he_from(m, g) == acd_he_from(m, h);
                if (same_dir) cp->oriented = 0;
                unsigned char want = (unsigned char)(flip[t] ^ same_dir);
                uint32_t u = g / 3;
                if (!seen[u]) {
                    seen[u] = 1;
                    flip[u] = want;
                    queue[qt++] = u;
                } else if (flip[u] != want) {
                    cp->orientable = 0;
                }
            }
        }
    }
    r->orientable = 1;
    r->oriented = r->orientation_conflicts == 0;
    for (size_t c = 0; c < r->components; c++) {
        acd_mesh_component *cp = &r->component[c];
        cp->closed = cp->boundary_edges == 0 && cp->nonmanifold_edges == 0;
        if (!cp->orientable) r->orientable = 0;
        long chi = cfans[c] - (long)cp->edges + (long)cp->faces;
        cp->genus = cp->closed && cp->orientable && chi % 2 == 0 ? (2 - chi) / 2 : -1;
        if (cp->closed) {
            r->closed_components++;
            if (cp->genus >= 0) r->genus += cp->genus;
            if (cp->volume < 0) r->inward_components++;
        }
    }
    free(cfans);
    r->closed = nt > 0 && r->boundary_edges == 0 && r->nonmanifold_edges == 0;
    if (check_self_intersections) {
        s = acd_mesh_self_intersections(m, &r->self_intersections, r->first_intersection, 1, err);
        if (s != ACD_OK) goto done;
        r->self_intersections_checked = 1;
    }
done:
    acd_halfedges_free(&he);
    free(fparent);
    free(cparent);
    free(comp);
    free(flip);
    free(seen);
    free(queue);
    free(vfans);
    free(vstamp);
    free(keys);
    if (s != ACD_OK) acd_mesh_report_free(r);
    return s;
}
