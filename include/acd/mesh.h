/* acd/mesh.h: indexed triangle meshes. I/O, validation and repair are declared here as they
 * are built (see src/mesh/). */
#ifndef ACD_MESH_H
#define ACD_MESH_H

#include "acd/base.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct acd_mesh {
    double *vertices;     /* 3 * nvertices */
    size_t nvertices;
    uint32_t *triangles;  /* 3 * ntriangles, counterclockwise seen from outside */
    size_t ntriangles;
} acd_mesh;

void acd_mesh_free(acd_mesh *m);

#ifdef __cplusplus
}
#endif
#endif
