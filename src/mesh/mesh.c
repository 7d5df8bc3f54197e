/* mesh/mesh: the indexed triangle mesh value type. */
#include "acd/mesh.h"

#include <stdlib.h>

void acd_mesh_free(acd_mesh *m) {
    if (!m) return;
    free(m->vertices);
    free(m->triangles);
    m->vertices = NULL;
    m->triangles = NULL;
    m->nvertices = m->ntriangles = 0;
}

#include <string.h>

#include "core/error.h"

acd_status acd_mesh_copy(acd_mesh *dst, const acd_mesh *src, acd_error *err) {
    if (!dst || !src) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_copy: NULL argument");
    memset(dst, 0, sizeof *dst);
    dst->vertices = malloc((src->nvertices ? src->nvertices : 1) * 3 * sizeof(double));
    dst->triangles = malloc((src->ntriangles ? src->ntriangles : 1) * 3 * sizeof(uint32_t));
    if (!dst->vertices || !dst->triangles) {
        acd_mesh_free(dst);
        return acd_fail(err, ACD_ERR_NOMEM, "acd_mesh_copy: out of memory (%zu vertices, %zu triangles)",
                        src->nvertices, src->ntriangles);
    }
    if (src->nvertices) memcpy(dst->vertices, src->vertices, src->nvertices * 3 * sizeof(double));
    if (src->ntriangles) memcpy(dst->triangles, src->triangles, src->ntriangles * 3 * sizeof(uint32_t));
    dst->nvertices = src->nvertices;
    dst->ntriangles = src->ntriangles;
    return ACD_OK;
}
