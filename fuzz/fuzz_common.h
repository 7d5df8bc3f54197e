/* Shared body of the mesh reader fuzz targets: parse the input with one reader directly, and when
 * it is accepted, validate the mesh, write it in the same format and read it back: the same mesh
 * must come back (OBJ, OFF, PLY: every coordinate bit and every index; STL, a soup welded on
 * read: the triangle count, and each triangle's corners the originals, float-rounded in binary
 * STL); PLY and STL also in their ASCII forms. A refusal must say why, beginning with the file's
 * name, and a line or byte offset it names must lie within the input. Any crash, leak, hang,
 * sanitizer report or violation is a bug (abort). */
#ifndef ACD_FUZZ_COMMON_H
#define ACD_FUZZ_COMMON_H

#include <stdlib.h>
#include <string.h>

#include "acd/mesh.h"
#include "mesh/io_formats.h"
#include "fuzz_refusal.h"

/* Writes m in fmt and reads it back: the same mesh (STL: the same triangles' corners, float-rounded
 * in binary STL; a soup, so the vertex order may change). */
static void fuzz_roundtrip(const acd_mesh *m, acd_mesh_format fmt) {
    void *out = NULL;
    size_t n = 0;
    acd_error err;
    if (acd_mesh_write_memory(m, fmt, &out, &n, &err) != ACD_OK) return;
    acd_mesh back;
    if (acd_mesh_read_memory(out, n, fmt, "fuzz-rt", &back, &err) != ACD_OK) abort();
    if (back.ntriangles != m->ntriangles) abort();
    if (fmt != ACD_MESH_FORMAT_STL && fmt != ACD_MESH_FORMAT_STL_ASCII) {
        if (back.nvertices != m->nvertices) abort();
        if (m->nvertices && memcmp(back.vertices, m->vertices, 3 * m->nvertices * sizeof(double)) != 0) abort();
        if (m->ntriangles && memcmp(back.triangles, m->triangles, 3 * m->ntriangles * sizeof(uint32_t)) != 0) abort();
    } else {
        for (size_t t = 0; t < 3 * m->ntriangles; t++)
            for (int k = 0; k < 3; k++) {
                double want = m->vertices[3 * (size_t)m->triangles[t] + k];
                if (fmt == ACD_MESH_FORMAT_STL) want = (double)(float)want;
                if (back.vertices[3 * (size_t)back.triangles[t] + k] != want) abort();
            }
    }
    acd_mesh_free(&back);
    free(out);
}

typedef acd_status (*fuzz_reader)(const char *buf, size_t len, const char *name, acd_mesh_builder *b, acd_error *err);

static int fuzz_one(const uint8_t *data, size_t size, fuzz_reader read, acd_mesh_format fmt) {
    char *buf = malloc(size + 1);
    if (!buf) return 0;
    memcpy(buf, data, size);
    buf[size] = '\0';
    acd_mesh_builder b;
    memset(&b, 0, sizeof b);
    acd_error err;
    err.message[0] = '\0';
    acd_status s = read(buf, size, "fuzz", &b, &err);
    if (s != ACD_OK) fuzz_check_refusal(err.message, "fuzz", data, size, 0);
    free(buf);
    if (s != ACD_OK) {
        acd_builder_free(&b);
        return 0;
    }
    acd_mesh m;
    acd_builder_take_mesh(&b, &m);
    acd_builder_free(&b);
    acd_mesh_report r;
    if (acd_mesh_validate(&m, m.ntriangles <= 2000, &r, &err) == ACD_OK) acd_mesh_report_free(&r);
    fuzz_roundtrip(&m, fmt);
    if (fmt == ACD_MESH_FORMAT_PLY) fuzz_roundtrip(&m, ACD_MESH_FORMAT_PLY_ASCII);
    if (fmt == ACD_MESH_FORMAT_STL) fuzz_roundtrip(&m, ACD_MESH_FORMAT_STL_ASCII);
    acd_mesh_free(&m);
    return 0;
}

#endif
