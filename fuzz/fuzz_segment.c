/* fuzz/fuzz_segment: libFuzzer target for CoRiSe segmentation (acd_segment, include/acd/segment.h)
 * on small star-shaped spheres (fuzz_sphere.h; 5 rings of 8), closed or with holes.
 *
 * Header: data[0] bits 0-2 tau, bits 3-4 alpha, bits 5-6 concave_weight, bit 7 clamp_hull_depth;
 * data[1] bits 0-1 max_depth (1, 2, 4, 64), bit 2 holes (the trailing bytes name faces to delete).
 *
 * Checked on every accepted run (any violation aborts):
 *  - a failure carries a message;
 *  - one label per face, every label < nparts, every part non-empty and edge-connected, parts
 *    numbered by their smallest face;
 *  - each part's face count and area from the labels, the areas adding up to the mesh's; the
 *    mesh volume and the sum of the hull volumes as reported;
 *  - a part whose hull is solid (hull_dim 3) has every corner of its faces inside the hull and a
 *    hull with positive volume; a flat one (hull_dim < 3) an empty hull and volume 0;
 *  - concavity = concavity_rel x scale; every part deeper than tau counted as unresolved;
 *  - the mesh segmented (result.mesh: the input welded and oriented first) has the input's faces
 *    in order with the same corners, reversed only for the faces counted as flipped; the checks
 *    above are made on it. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "acd/mesh.h"
#include "acd/segment.h"
#include "fuzz_sphere.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define FZ_RINGS 5
#define FZ_SEGS 8
#define FZ_NV (FZ_RINGS * FZ_SEGS + 2)
#define FZ_HEADER 2

static uint32_t find(uint32_t *uf, uint32_t x) {
    while (uf[x] != x) x = uf[x] = uf[uf[x]];
    return x;
}

static double tri_area(const acd_mesh *m, size_t f) {
    const uint32_t *T = m->triangles + 3 * f;
    const double *a = m->vertices + 3 * (size_t)T[0], *b = m->vertices + 3 * (size_t)T[1], *c = m->vertices + 3 * (size_t)T[2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double x[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    return 0.5 * sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
}

static void check(const acd_mesh *m, const acd_segment_result *r) {
    size_t nf = m->ntriangles, np = r->nparts;
    if (r->nfaces != nf || !np || np > nf) abort();
    /* labels in range, numbered by first face */
    uint32_t next = 0;
    for (size_t f = 0; f < nf; f++) {
        if (r->labels[f] >= np) abort();
        if (r->labels[f] > next) abort();
        if (r->labels[f] == next) next++;
    }
    if (next != np) abort();
    /* edge-connected: faces sharing an edge (by vertex indices) with the same label joined */
    uint32_t *uf = malloc(nf * sizeof *uf);
    if (!uf) abort();
    for (size_t f = 0; f < nf; f++) uf[f] = (uint32_t)f;
    for (size_t f = 0; f < nf; f++)
        for (size_t g = f + 1; g < nf; g++) {
            if (r->labels[f] != r->labels[g]) continue;
            int shared = 0;
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) shared += m->triangles[3 * f + i] == m->triangles[3 * g + j];
            if (shared >= 2) uf[find(uf, (uint32_t)f)] = find(uf, (uint32_t)g);
        }
    uint32_t *root = malloc(np * sizeof *root);
    size_t *count = calloc(np, sizeof *count);
    double *area = calloc(np, sizeof *area);
    if (!root || !count || !area) abort();
    for (size_t k = 0; k < np; k++) root[k] = UINT32_MAX;
    double total = 0;
    for (size_t f = 0; f < nf; f++) {
        uint32_t k = r->labels[f], rt = find(uf, (uint32_t)f);
        if (root[k] == UINT32_MAX) root[k] = rt;
        else if (root[k] != rt) abort(); /* a part in two pieces */
        count[k]++;
        double a = tri_area(m, f);
        area[k] += a;
        total += a;
    }
    double hv = 0, asum = 0;
    for (size_t k = 0; k < np; k++) {
        const acd_segment_part *p = &r->parts[k];
        if (p->nfaces != count[k] || !p->nfaces) abort();
        if (fabs(p->area - area[k]) > 1e-9 * (total + 1e-300)) abort();
        asum += p->area;
        hv += p->hull_volume;
        if (p->concavity != p->concavity_rel * r->scale) abort();
        if (!(p->concavity_rel >= 0) || !isfinite(p->concavity_rel)) abort();
        if (p->hull_dim == 3) {
            if (!(p->hull_volume > 0) || p->hull.ntriangles < 4) abort();
            acd_hull h;
            acd_error e;
            if (acd_hull_compute(p->hull.vertices, p->hull.nvertices, &h, &e) != ACD_OK) abort();
            for (size_t f = 0; f < nf; f++) {
                if (r->labels[f] != k) continue;
                for (int c = 0; c < 3; c++)
                    if (acd_hull_plane_distance(&h, m->vertices + 3 * (size_t)m->triangles[3 * f + c]) > 1e-9 * r->scale)
                        abort();
            }
            acd_hull_free(&h);
        } else {
            if (p->hull_dim > 3 || p->hull_volume != 0 || p->hull.ntriangles) abort();
        }
    }
    if (fabs(asum - total) > 1e-9 * (total + 1e-300)) abort();
    if (fabs(hv - r->hull_volume) > 1e-12 * (hv + 1e-300)) abort();
    if (fabs(r->mesh_volume - fz_mesh_volume(m)) > 1e-9 * (fabs(r->mesh_volume) + r->scale * r->scale * r->scale)) abort();
    size_t deep = 0;
    for (size_t k = 0; k < np; k++) deep += r->parts[k].concavity_rel > r->tau * (1 + 1e-9) + 1e-12;
    if (deep > r->unresolved) abort();
    free(uf);
    free(root);
    free(count);
    free(area);
}

/* The input preparation (params.prepare, docs/corise.md): the mesh segmented has the input's faces
 * in order, each with the same corners in the same or the reversed cyclic order (by index when
 * nothing was welded, else by position: the weld merges equal positions, -0 = +0), the reversed
 * ones counted in faces_flipped (a face whose corners repeat reads both ways: either count), and
 * vertices_merged fewer vertices. */
static int eq3(const double *a, const double *b) {
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

static int corner_eq(const acd_mesh *in, const acd_mesh *sm, int welded, uint32_t u, uint32_t v) {
    return welded ? eq3(sm->vertices + 3 * (size_t)u, in->vertices + 3 * (size_t)v) : u == v;
}

static void check_prepared(const acd_mesh *in, const acd_segment_result *r) {
    const acd_mesh *sm = &r->mesh;
    if (sm->ntriangles != in->ntriangles || sm->nvertices + r->vertices_merged != in->nvertices) abort();
    int welded = r->vertices_merged > 0;
    size_t flipped = 0, either = 0;
    for (size_t f = 0; f < in->ntriangles; f++) {
        const uint32_t *a = in->triangles + 3 * f, *b = sm->triangles + 3 * f;
        int same = 0, reversed = 0;
        for (int k = 0; k < 3; k++) {
            int s1 = 1, s2 = 1;
            for (int c = 0; c < 3; c++) {
                s1 &= corner_eq(in, sm, welded, b[c], a[(k + c) % 3]);
                s2 &= corner_eq(in, sm, welded, b[c], a[(k + 3 - c) % 3]);
            }
            same |= s1;
            reversed |= s2;
        }
        if (!same && !reversed) abort();
        flipped += !same;
        either += same && reversed;
    }
    if (r->faces_flipped < flipped || r->faces_flipped > flipped + either) abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size < FZ_HEADER + FZ_NV) return 0;
    acd_mesh m;
    fz_build_sphere(data + FZ_HEADER, FZ_RINGS, FZ_SEGS, &m);
    if ((data[1] & 4) && size > FZ_HEADER + FZ_NV) fz_delete_faces(&m, data + FZ_HEADER + FZ_NV, size - FZ_HEADER - FZ_NV);
    acd_segment_params p = acd_segment_default_params();
    static const double taus[8] = {0, 0.01, 0.02, 0.05, 0.1, 0.2, 0.4, 1};
    static const double alphas[4] = {0, 0.5, 0.8, 1};
    static const double weights[4] = {0.1, 0.3, 1, 3};
    static const size_t depths[4] = {1, 2, 4, 64};
    p.tau = taus[data[0] & 7];
    p.alpha = alphas[(data[0] >> 3) & 3];
    p.concave_weight = weights[(data[0] >> 5) & 3];
    p.clamp_hull_depth = data[0] >> 7;
    p.max_depth = depths[data[1] & 3];
    p.threads = 1;
    acd_segment_result r;
    acd_error err;
    err.message[0] = '\0';
    acd_status s = acd_segment(&m, &p, &r, &err);
    if (s != ACD_OK) {
        if (!err.message[0]) abort(); /* every failure must say why */
        acd_segment_result_free(&r);
        acd_mesh_free(&m);
        return 0;
    }
    check_prepared(&m, &r);
    check(&r.mesh, &r);
    acd_segment_result_free(&r);
    acd_mesh_free(&m);
    return 0;
}
