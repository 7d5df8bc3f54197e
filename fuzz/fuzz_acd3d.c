/* fuzz/fuzz_acd3d: libFuzzer target for the 3D decomposition (solid and surface) and the hole
 * filling that solid mode relies on for open input.
 *
 * The input shapes a small closed mesh instead of being parsed (the readers have their own
 * targets): a UV sphere (FZ_RINGS latitude rings of FZ_SEGS vertices and two poles) whose vertices
 * are moved along their directions to radii taken from the bytes, on a coarse grid (quarter units,
 * 0 allowed), so coplanar faces, flat stretches, spikes and vertices pinched together at the
 * centre are frequent. With positive radii the mesh is a star-shaped simple polyhedron; radius 0
 * makes it touch itself at the centre. Header bytes pick the mode, tau, the stopping test, and
 * optionally faces to delete (holes, closed again through acd_mesh_repair as `acd 3d` does in solid
 * mode).
 *
 * Checked on every accepted run (any violation aborts):
 *  - a failure carries a message;
 *  - solid: every part closed and consistently oriented, part volumes add up to the input's,
 *    every part meets tau unless its leaf reason says why not (no_cut, depth, merged by
 *    max_hulls), every part inside
 *    its hull's planes, a part kept whole by the hull test (hull_distance) with every vertex within
 *    tau of its hull's boundary;
 *  - surface: the parts' faces add up to the input's;
 *  - the tree: every part's node is a leaf that points back to the part. */
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

#define FZ_RINGS 5
#define FZ_SEGS 8
#define FZ_NV (FZ_RINGS * FZ_SEGS + 2)
#define FZ_HEADER 3

static void check(const acd_mesh *in, const acd3d_params *p, const acd3d_result *r) {
    int solid = p->mode == ACD3D_SOLID;
    double sum = 0;
    size_t faces = 0;
    for (size_t i = 0; i < r->nparts; i++) {
        const acd3d_part *q = &r->parts[i];
        if (q->node < 0 || (size_t)q->node >= r->nnodes) abort();
        const acd3d_node *nd = &r->nodes[q->node];
        if (nd->part != (int)i || (nd->first_child != -1 && nd->leaf_reason != ACD3D_LEAF_MERGED)) abort();
        if (q->concavity > r->tau * (1 + 1e-9) + FZ_TAU_SLACK * r->scale && nd->leaf_reason != ACD3D_LEAF_NO_CUT &&
            nd->leaf_reason != ACD3D_LEAF_DEPTH && nd->leaf_reason != ACD3D_LEAF_MERGED)
            abort();
        faces += q->mesh.ntriangles;
        if (!solid) continue;
        sum += q->volume;
        acd_edge_map em;
        acd_error e;
        if (acd_edge_map_build(q->mesh.triangles, q->mesh.ntriangles, NULL, &em, &e) != ACD_OK) abort();
        if (q->mesh.ntriangles && acd_edge_map_check_closed(&em, q->mesh.triangles, q->mesh.ntriangles, &e) != ACD_OK)
            abort();
        acd_edge_map_free(&em);
        /* positive volume, and inside its hull: the hull rebuilt from its vertices (qhull's own
         * planes: a plane from a sliver triangle's cross product would be meaningless) */
        if (!(q->volume > 0)) abort();
        acd_hull h;
        if (acd_hull_compute(q->hull.vertices, q->hull.nvertices, &h, &e) != ACD_OK) abort();
        for (size_t v = 0; v < q->mesh.nvertices; v++) {
            double pd = acd_hull_plane_distance(&h, q->mesh.vertices + 3 * v);
            if (pd > 1e-9 * r->scale) abort();
            if (nd->leaf_reason == ACD3D_LEAF_HULL && -pd > r->tau * (1 + 1e-9) + FZ_TAU_SLACK * r->scale) abort();
        }
        acd_hull_free(&h);
    }
    if (solid && fabs(sum - r->input_volume) > 1e-9 * fabs(r->input_volume)) abort();
    if (!solid && faces != in->ntriangles) abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size < FZ_HEADER + FZ_NV) return 0;
    acd_mesh m;
    fz_build_sphere(data + FZ_HEADER, FZ_RINGS, FZ_SEGS, &m);
    acd3d_params p = acd3d_default_params();
    p.mode = (data[0] & 1) ? ACD3D_SURFACE : ACD3D_SOLID;
    p.threads = 1;
    static const double taus[8] = {0, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1};
    p.tau = taus[data[1] % 8];
    p.max_depth = 6; /* bounds the work per input (at most 64 parts) */
    if (data[0] & 2) p.max_hulls = 1 + data[2] % 4;
    if (data[0] & 8) p.stop = ACD3D_STOP_HULL;
    /* optional holes: the trailing bytes name faces to delete */
    if ((data[0] & 4) && size > FZ_HEADER + FZ_NV) {
        fz_delete_faces(&m, data + FZ_HEADER + FZ_NV, size - FZ_HEADER - FZ_NV);
    }
    acd3d_result r;
    acd_error err;
    acd_status s = fz_decompose_closing(&m, &p, &r, &err); /* as `acd 3d`: holes closed in solid mode */
    if (s != ACD_OK) {
        acd_mesh_free(&m);
        return 0;
    }
    if (p.mode == ACD3D_SOLID && fabs(r.input_volume - fz_mesh_volume(&m)) > 1e-9 * fabs(r.input_volume) + 1e-300)
        abort();
    check(&m, &p, &r);
    acd3d_result_free(&r);
    acd_mesh_free(&m);
    return 0;
}
