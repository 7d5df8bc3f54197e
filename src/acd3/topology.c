/* acd3/topology: Euler characteristic, boundary loops and genus of a mesh; see topology.h. */
#include "acd3/topology.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/union_find.h"
#include "geom3/dijkstra.h"

acd_status acd3_topology_of(const acd_mesh *m, acd3_topology *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    size_t nv = m->nvertices, nf = m->ntriangles;
    acd_edge_graph g;
    acd_status st = acd_edge_graph_from_mesh(m->vertices, nv, m->triangles, nf, &g, err);
    if (st != ACD_OK) return st;
    uint32_t *nface = calloc(g.nedges ? g.nedges : 1, sizeof *nface);
    uint8_t *used = calloc(nv ? nv : 1, 1);
    size_t *comp = malloc((nv ? nv : 1) * sizeof *comp), *loop = malloc((nv ? nv : 1) * sizeof *loop);
    uint8_t *onb = calloc(nv ? nv : 1, 1);
    if (!nface || !used || !comp || !loop || !onb) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for the topology of %zu vertices", nv);
        goto done;
    }
    for (size_t v = 0; v < nv; v++) comp[v] = loop[v] = v;
    for (size_t f = 0; f < nf; f++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = m->triangles[3 * f + k], b = m->triangles[3 * f + (k + 1) % 3];
            used[a] = 1;
            uint32_t e = acd_edge_graph_find(&g, a, b);
            if (e != ACD_NO_VERTEX) nface[e]++;
            acd_uf_union_z(comp, a, b);
        }
    size_t V = 0, ncomp = 0, nloops = 0;
    for (size_t v = 0; v < nv; v++)
        if (used[v]) {
            V++;
            ncomp += acd_uf_find_z(comp, v) == v;
        }
    for (size_t e = 0; e < g.nedges; e++)
        if (nface[e] == 1) {
            uint32_t a = g.edge_v[2 * e], b = g.edge_v[2 * e + 1];
            onb[a] = onb[b] = 1;
            acd_uf_union_z(loop, a, b);
        }
    for (size_t v = 0; v < nv; v++) nloops += onb[v] && acd_uf_find_z(loop, v) == v;
    out->components = ncomp;
    out->boundary_loops = nloops;
    out->euler = (long)V - (long)g.nedges + (long)nf;
    out->genus = ((long)(2 * ncomp) - out->euler - (long)nloops) / 2;
    /* negative only where the part is not a 2-manifold (shells touching at a vertex: a cavity
     * that touches the outer surface at one point, as a join of cheese's parts gave): no
     * handles; the Euler characteristic is reported as computed */
    if (out->genus < 0) out->genus = 0;
done:
    free(nface), free(used), free(comp), free(loop), free(onb);
    acd_edge_graph_free(&g);
    return st;
}
