/* fuzz/fuzz_eval: libFuzzer target for the 3D decomposition yardstick (`acd eval`,
 * acd_eval_parts in include/acd/eval.h): a small star-shaped sphere (fuzz_sphere.h; 4 rings of 6),
 * closed or with holes, scored against fuzzed parts: each part a subset of the sphere's vertices
 * (a bit mask) scaled about its centroid (so parts stick out, fall short, overlap, are flat or
 * empty), few samples so that one input is fast.
 *
 * Layout: data[0] bits 0-1 parts - 1, bit 2 holes (the bytes after the parts name faces to
 * delete), bit 3 add a part holding every vertex; data[1 .. 26] radii; then per part 4 mask bytes
 * and a scale byte (0.5 .. 1.5).
 *
 * Checked on every accepted run (any violation aborts):
 *  - a failure carries a message;
 *  - every figure finite; 0 <= coverage <= 1, 0 <= iou <= coverage, excess >= 0, and
 *    iou = coverage / (1 + excess) (the same counts);
 *  - the means at most the maxima, concavity_max the larger maximum;
 *  - parts, degenerate parts, hull vertices and the sum of hull volumes as the hulls give them;
 *    mesh volume |signed volume| (closed mesh);
 *  - with a part holding every vertex of a closed mesh: coverage 1 (every sample inside the mesh is
 *    inside its hull). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "acd/eval.h"
#include "acd/hull.h"
#include "acd/mesh.h"
#include "fuzz_sphere.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define FZ_RINGS 4
#define FZ_SEGS 6
#define FZ_NV (FZ_RINGS * FZ_SEGS + 2)
#define FZ_PART 5

static int finite_report(const acd_eval_report *r) {
    const double v[] = {r->mesh_volume,       r->hull_volume_sum,    r->union_volume,      r->iou,
                        r->coverage,          r->excess,             r->mesh_to_hulls_max, r->mesh_to_hulls_mean,
                        r->hulls_to_mesh_max, r->hulls_to_mesh_mean, r->concavity_max,     r->diagonal,
                        r->boundary_spacing};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
        if (!isfinite(v[i]) || v[i] < 0) return 0;
    return 1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    size_t nparts = 1 + (data[0] & 3);
    int whole = (data[0] >> 3) & 1;
    if (size < 1 + FZ_NV + FZ_PART * nparts) return 0;
    acd_mesh m;
    fz_build_sphere(data + 1, FZ_RINGS, FZ_SEGS, &m);
    size_t tail = 1 + FZ_NV + FZ_PART * nparts;
    if ((data[0] & 4) && size > tail) fz_delete_faces(&m, data + tail, size - tail);
    size_t np = nparts + (size_t)whole;
    acd_mesh_parts parts;
    parts.count = np;
    parts.parts = calloc(np, sizeof *parts.parts);
    if (!parts.parts) abort();
    for (size_t i = 0; i < np; i++) {
        acd_mesh *pm = &parts.parts[i].mesh;
        pm->vertices = malloc(FZ_NV * 3 * sizeof(double));
        if (!pm->vertices) abort();
        if (i == nparts) { /* every vertex */
            memcpy(pm->vertices, m.vertices, FZ_NV * 3 * sizeof(double));
            pm->nvertices = FZ_NV;
            continue;
        }
        const uint8_t *d = data + 1 + FZ_NV + FZ_PART * i;
        uint32_t mask = (uint32_t)d[0] | (uint32_t)d[1] << 8 | (uint32_t)d[2] << 16 | (uint32_t)d[3] << 24;
        double scale = 0.5 + d[4] / 255.0, c[3] = {0, 0, 0};
        size_t n = 0;
        for (int v = 0; v < FZ_NV; v++)
            if (mask >> (v % 32) & 1) {
                memcpy(pm->vertices + 3 * n++, m.vertices + 3 * v, 3 * sizeof(double));
                for (int k = 0; k < 3; k++) c[k] += m.vertices[3 * v + k];
            }
        for (size_t j = 0; j < n; j++)
            for (int k = 0; k < 3; k++) pm->vertices[3 * j + k] = c[k] / (double)n + scale * (pm->vertices[3 * j + k] - c[k] / (double)n);
        pm->nvertices = n;
    }
    acd_eval_params prm = acd_eval_default_params();
    prm.samples = 2000;
    prm.surface_samples = 300;
    acd_eval_report r;
    acd_error err;
    err.message[0] = '\0';
    acd_status s = acd_eval_parts(&m, &parts, &prm, &r, &err);
    if (s != ACD_OK) {
        if (!err.message[0]) abort(); /* every failure must say why */
    } else {
        if (!finite_report(&r)) abort();
        if (r.coverage > 1 || r.iou > r.coverage * (1 + 1e-12)) abort();
        if (fabs(r.iou - r.coverage / (1 + r.excess)) > 1e-9) abort();
        if (r.mesh_to_hulls_mean > r.mesh_to_hulls_max * (1 + 1e-9) + 1e-300 ||
            r.hulls_to_mesh_mean > r.hulls_to_mesh_max * (1 + 1e-9) + 1e-300)
            abort();
        if (r.concavity_max != fmax(r.mesh_to_hulls_max, r.hulls_to_mesh_max)) abort();
        if (r.parts != np || !r.samples) abort();
        size_t degenerate = 0, hv = 0;
        double vol = 0;
        for (size_t i = 0; i < np; i++) {
            acd_hull h;
            if (acd_hull_compute(parts.parts[i].mesh.vertices, parts.parts[i].mesh.nvertices, &h, &err) != ACD_OK) abort();
            if (h.dim != 3) degenerate++;
            else vol += h.volume;
            hv += h.nvertices;
            acd_hull_free(&h);
        }
        if (degenerate != r.degenerate_parts || hv != r.hull_vertices) abort();
        if (fabs(vol - r.hull_volume_sum) > 1e-12 * vol) abort();
        if (r.mesh_closed &&
            fabs(r.mesh_volume - fabs(fz_mesh_volume(&m))) > 1e-9 * (r.mesh_volume + r.diagonal * r.diagonal * r.diagonal))
            abort();
        if (whole && r.mesh_closed && r.coverage != 1) abort();
    }
    for (size_t i = 0; i < np; i++) free(parts.parts[i].mesh.vertices);
    free(parts.parts);
    acd_mesh_free(&m);
    return 0;
}
