/* libFuzzer target for the OBJ reader (see fuzz_common.h). Also the o/g groups as parts
 * (acd_mesh_read_parts_memory, `acd hull` and `acd eval` read decompositions so): the parts must
 * hold the whole mesh's triangles, in order, with the same corners. */
#include <stddef.h>
#include <stdint.h>

#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void fuzz_parts(const uint8_t *data, size_t size) {
    acd_mesh m;
    acd_mesh_parts parts;
    acd_error err;
    acd_status a = acd_mesh_read_memory(data, size, ACD_MESH_FORMAT_OBJ, "fuzz", &m, &err);
    acd_status b = acd_mesh_read_parts_memory(data, size, ACD_MESH_FORMAT_OBJ, "fuzz", &parts, &err);
    if (a != b) abort();
    if (a != ACD_OK) return;
    size_t t = 0;
    for (size_t i = 0; i < parts.count; i++) {
        const acd_mesh *p = &parts.parts[i].mesh;
        if (!p->ntriangles || !parts.parts[i].name) abort(); /* empty groups are dropped */
        for (size_t j = 0; j < 3 * p->ntriangles; j++, t++) {
            if (t >= 3 * m.ntriangles || p->triangles[j] >= p->nvertices) abort();
            if (memcmp(p->vertices + 3 * (size_t)p->triangles[j], m.vertices + 3 * (size_t)m.triangles[t],
                       3 * sizeof(double)) != 0)
                abort();
        }
    }
    if (t != 3 * m.ntriangles) abort();
    acd_mesh_parts_free(&parts);
    acd_mesh_free(&m);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fuzz_parts(data, size);
    return fuzz_one(data, size, acd_obj_read, ACD_MESH_FORMAT_OBJ);
}
