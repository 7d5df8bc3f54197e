/* fuzz/fuzz_acd3d_tight: libFuzzer target for the solid-mode options fuzz_acd3d leaves at their
 * defaults: the cut choice (volume, band), the merge order by volume, merge_parts, merge_refine,
 * merge_tau, max_hulls and max_hull_vertices (the "tight" pipeline of docs/acd3d.md "Hull
 * tightness", and its neighbours), and that the output does not depend on the thread count.
 *
 * The input shapes a small star-shaped sphere (fuzz_sphere.h; 4 rings of 6) after a header:
 *   data[0]: bits 0-1 cut choice (concavity, volume, band, band), bit 2 merge order volume,
 *            bit 3 stop hull, bit 4 holes (trailing bytes name faces to delete; closed again by
 *            acd_mesh_repair as `acd 3d` does), bit 5 max_hulls, bit 6 no merge pass;
 *   data[1]: tau; data[2]: merge_parts (bits 0-2), merge_refine (bits 3-4), max_hull_vertices
 *            (bits 5-7: none, 4 .. 10); data[3]: max_hulls (bits 0-1, 1 .. 4), budget_parts (bits
 *            2-3: off, off, 2, 4), merge_tau (bits 4-5), trim_coverage (bits 6-7: off, 0.001, 0.005,
 *            0.01).
 *
 * Checked on every accepted run (any violation aborts):
 *  - a failure carries a message;
 *  - every part closed, with positive volume, the volumes adding up to the input's;
 *  - every part inside its hull (the hull's own planes, rebuilt by qhull from its vertices), at
 *    most max_hull_vertices hull vertices, the hull's volume at least the part's; with
 *    trim_coverage: the part's volume outside its trimmed hull (acd_hull_volume_outside, exact; not
 *    checked where it fails) at most its trimmed_volume (a part with none may still stick out by a fin of no volume), the hull's volume at least the part's less that, the trimmed volumes
 *    adding up to the result's, within trim_coverage of the input's volume;
 *  - every part meets tau unless its leaf reason says why not (no_cut, depth, merged by
 *    max_hulls, budget: its bound is merge_tau's unless no cut could split it); joined and refined
 *    parts meet merge_tau; max_concavity is the parts' maximum;
 *  - at most max_hulls parts;
 *  - the tree: every part's node points back to it, merged_into points to a joined node.
 * (Not the thread count: OpenMP's waits on a loaded machine made single inputs take seconds.) */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd/hull.h"
#include "acd/mesh.h"
#include "fuzz_sphere.h"
#include "geom3/edge_map.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define FZ_RINGS 4
#define FZ_SEGS 6
#define FZ_NV (FZ_RINGS * FZ_SEGS + 2)
#define FZ_HEADER 4

static void check(const acd3d_params *p, const acd3d_result *r) {
    double sum = 0, maxc = 0, trimmed = 0;
    if (p->max_hulls && r->nparts > p->max_hulls) abort();
    for (size_t i = 0; i < r->nparts; i++) {
        const acd3d_part *q = &r->parts[i];
        if (q->node < 0 || (size_t)q->node >= r->nnodes) abort();
        const acd3d_node *nd = &r->nodes[q->node];
        if (nd->part != (int)i || nd->merged_into != -1) abort();
        if (nd->first_child != -1 && nd->leaf_reason != ACD3D_LEAF_MERGED) abort();
        if (q->concavity > maxc) maxc = q->concavity;
        double slack = FZ_TAU_SLACK * r->scale;
        if (nd->leaf_reason == ACD3D_LEAF_JOINED) {
            if (q->concavity > r->merge_tau * (1 + 1e-9) + slack) abort();
        } else if (q->concavity > r->tau * (1 + 1e-9) + slack && nd->leaf_reason != ACD3D_LEAF_NO_CUT &&
                   nd->leaf_reason != ACD3D_LEAF_DEPTH && nd->leaf_reason != ACD3D_LEAF_MERGED &&
                   nd->leaf_reason != ACD3D_LEAF_BUDGET) {
            abort();
        }
        sum += q->volume;
        acd_edge_map em;
        acd_error e;
        if (acd_edge_map_build(q->mesh.triangles, q->mesh.ntriangles, NULL, &em, &e) != ACD_OK) abort();
        if (!q->mesh.ntriangles || acd_edge_map_check_closed(&em, q->mesh.triangles, q->mesh.ntriangles, &e) != ACD_OK)
            abort();
        acd_edge_map_free(&em);
        if (!(q->volume > 0)) abort();
        if (fabs(q->volume - fz_mesh_volume(&q->mesh)) > 1e-9 * (fabs(q->volume) + r->input_volume)) abort();
        if (p->max_hull_vertices && q->hull.nvertices > p->max_hull_vertices) abort();
        if (!(q->trimmed_volume >= 0) || (p->trim_coverage == 0 && q->trimmed_volume != 0)) abort();
        trimmed += q->trimmed_volume;
        if (!(q->hull_volume >= q->volume * (1 - 1e-9) - q->trimmed_volume - 1e-12 * r->input_volume)) abort();
        acd_hull h;
        if (acd_hull_compute(q->hull.vertices, q->hull.nvertices, &h, &e) != ACD_OK) abort();
        if (p->trim_coverage > 0) { /* (a part may stick out of its trimmed hull by a flat fin: no volume) */
            /* exactly (the trim charges each cut exactly since 17a04ab: the bound, which counts a
             * region beyond two planes twice, can exceed the charge); where the exact cut fails
             * (NaN), no check of this part */
            double out = NAN;
            if (acd_hull_volume_outside(&h, &q->mesh, 1e-9 * r->scale, r->scale, &out, &e) != ACD_OK) out = NAN;
            if (out == out && !(out <= q->trimmed_volume * (1 + 1e-6) + 1e-9 * r->input_volume)) abort();
        } else {
            for (size_t v = 0; v < q->mesh.nvertices; v++)
                if (acd_hull_plane_distance(&h, q->mesh.vertices + 3 * v) > 1e-9 * r->scale) abort();
        }
        acd_hull_free(&h);
    }
    if (maxc != r->max_concavity) abort();
    if (fabs(trimmed - r->trimmed_volume) > 1e-9 * r->input_volume) abort();
    if (!(r->trimmed_volume <= p->trim_coverage * r->input_volume * (1 + 1e-12))) abort();
    if (fabs(sum - r->input_volume) > 1e-9 * fabs(r->input_volume)) abort();
    for (size_t n = 0; n < r->nnodes; n++) {
        const acd3d_node *nd = &r->nodes[n];
        if (nd->part >= 0 && ((size_t)nd->part >= r->nparts || r->parts[nd->part].node != (int)n)) abort();
        if (nd->merged_into >= 0 &&
            ((size_t)nd->merged_into >= r->nnodes || r->nodes[nd->merged_into].leaf_reason != ACD3D_LEAF_JOINED))
            abort();
        if (nd->leaf_reason == ACD3D_LEAF_REFINED && nd->merged_into < 0) abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size < FZ_HEADER + FZ_NV) return 0;
    acd_mesh m;
    fz_build_sphere(data + FZ_HEADER, FZ_RINGS, FZ_SEGS, &m);
    acd3d_params p = acd3d_default_params();
    p.mode = ACD3D_SOLID;
    p.threads = 1;
    /* no tau below 0.02 (fuzz_acd3d has them): 0.01 took half of the time per input */
    static const double taus[8] = {0.15, 0.02, 0.03, 0.05, 0.1, 0.2, 0.5, 1};
    p.tau = taus[data[1] % 8];
    p.max_depth = 5; /* bounds the work per input (at most 32 parts) */
    static const acd3d_cut_choice choices[4] = {ACD3D_CHOICE_CONCAVITY, ACD3D_CHOICE_VOLUME, ACD3D_CHOICE_BAND,
                                                ACD3D_CHOICE_BAND};
    p.cut_choice = choices[data[0] & 3];
    if (data[0] & 4) p.merge_order = ACD3D_MERGE_VOLUME;
    if (data[0] & 8) p.stop = ACD3D_STOP_HULL;
    if (data[0] & 32) p.max_hulls = 1 + (data[3] & 3);
    if (data[0] & 64) p.merge = 0;
    p.merge_parts = data[2] & 7;
    p.merge_refine = (data[2] >> 3) & 3;
    p.max_hull_vertices = (data[2] >> 5) ? 3 + (size_t)(data[2] >> 5) : 0;
    static const double mtaus[4] = {0, 0.5, 2, 4}; /* in units of tau; 0: tau */
    p.merge_tau = mtaus[(data[3] >> 4) & 3] * p.tau;
    static const size_t budgets[4] = {0, 0, 2, 4}; /* 8 took 5 s under ASan on a seed */
    p.budget_parts = budgets[(data[3] >> 2) & 3];
    static const double trims[4] = {0, 0.001, 0.005, 0.01};
    p.trim_coverage = trims[data[3] >> 6];
    if ((data[0] & 16) && size > FZ_HEADER + FZ_NV) fz_delete_faces(&m, data + FZ_HEADER + FZ_NV, size - FZ_HEADER - FZ_NV);
    acd3d_result r;
    acd_error err;
    acd_status s = fz_decompose_closing(&m, &p, &r, &err); /* as `acd 3d`: holes closed in solid mode */
    if (s != ACD_OK) {
        acd_mesh_free(&m);
        return 0;
    }
    if (fabs(r.input_volume - fz_mesh_volume(&m)) > 1e-9 * fabs(r.input_volume) + 1e-300) abort();
    check(&p, &r);
    acd3d_result_free(&r);
    acd_mesh_free(&m);
    return 0;
}
