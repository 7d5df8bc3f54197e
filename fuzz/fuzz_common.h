/* Shared body of the mesh reader fuzz targets: parse the input with one reader directly, and when
 * it is accepted, validate the mesh, write it in the same format and read it back (the counts
 * must survive). Any crash, leak, hang or sanitizer report is a bug. */
#ifndef ACD_FUZZ_COMMON_H
#define ACD_FUZZ_COMMON_H

#include <stdlib.h>
#include <string.h>

#include "acd/mesh.h"
#include "mesh/io_formats.h"

typedef acd_status (*fuzz_reader)(const char *buf, size_t len, const char *name, acd_mesh_builder *b, acd_error *err);

static int fuzz_one(const uint8_t *data, size_t size, fuzz_reader read, acd_mesh_format fmt) {
    char *buf = malloc(size + 1);
    if (!buf) return 0;
    memcpy(buf, data, size);
    buf[size] = '\0';
    acd_mesh_builder b;
    memset(&b, 0, sizeof b);
    acd_error err;
    acd_status s = read(buf, size, "fuzz", &b, &err);
    free(buf);
    if (s != ACD_OK) {
        if (!err.message[0]) abort(); /* every failure must say why */
        acd_builder_free(&b);
        return 0;
    }
    acd_mesh m;
    acd_builder_take_mesh(&b, &m);
    acd_builder_free(&b);
    acd_mesh_report r;
    if (acd_mesh_validate(&m, m.ntriangles <= 2000, &r, &err) == ACD_OK) acd_mesh_report_free(&r);
    void *out = NULL;
    size_t n = 0;
    if (acd_mesh_write_memory(&m, fmt, &out, &n, &err) == ACD_OK) {
        acd_mesh back;
        if (acd_mesh_read_memory(out, n, fmt, "fuzz-rt", &back, &err) != ACD_OK) abort();
        if (back.ntriangles != m.ntriangles) abort();
        if (fmt != ACD_MESH_FORMAT_STL && back.nvertices != m.nvertices) abort();
        acd_mesh_free(&back);
        free(out);
    }
    acd_mesh_free(&m);
    return 0;
}

#endif
