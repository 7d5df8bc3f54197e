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
