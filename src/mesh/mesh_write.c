/* mesh/mesh_write: writing a mesh in one of the formats, to memory or to a file (gzip when the
 * name ends in .gz). The mesh is checked first: finite coordinates, indices in range, and for
 * STL coordinates that fit a float. */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "core/error.h"
#include "mesh/io_formats.h"

static acd_status check_mesh(const acd_mesh *m, int need_float, const char *what, acd_error *err) {
    if (!m || (m->nvertices && !m->vertices) || (m->ntriangles && !m->triangles))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "%s: NULL mesh or arrays", what);
    for (size_t i = 0; i < 3 * m->nvertices; i++) {
        double v = m->vertices[i];
        if (!isfinite(v))
            return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "%s: vertex %zu has a non-finite coordinate", what, i / 3);
        if (need_float && fabs(v) > FLT_MAX)
            return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "%s: vertex %zu coordinate %g does not fit STL's float32",
                            what, i / 3, v);
    }
    for (size_t i = 0; i < 3 * m->ntriangles; i++)
        if (m->triangles[i] >= m->nvertices)
            return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "%s: triangle %zu refers to vertex %u of %zu", what, i / 3,
                            m->triangles[i], m->nvertices);
    if (need_float && m->ntriangles > UINT32_MAX)
        return acd_fail(err, ACD_ERR_UNSUPPORTED, "%s: binary STL holds at most 2^32-1 triangles", what);
    return ACD_OK;
}

static acd_status encode(const acd_mesh *m, acd_mesh_format fmt, acd_obuf *o, const char *what, acd_error *err) {
    int stl = fmt == ACD_MESH_FORMAT_STL || fmt == ACD_MESH_FORMAT_STL_ASCII;
    acd_status s = check_mesh(m, stl, what, err);
    if (s != ACD_OK) return s;
    switch (fmt) {
    case ACD_MESH_FORMAT_OBJ: acd_obj_write(o, m); break;
    case ACD_MESH_FORMAT_OFF: acd_off_write(o, m); break;
    case ACD_MESH_FORMAT_PLY: acd_ply_write(o, m, 0); break;
    case ACD_MESH_FORMAT_PLY_ASCII: acd_ply_write(o, m, 1); break;
    case ACD_MESH_FORMAT_STL: acd_stl_write(o, m, 0); break;
    case ACD_MESH_FORMAT_STL_ASCII: acd_stl_write(o, m, 1); break;
    case ACD_MESH_FORMAT_AUTO:
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "%s: no output format (unknown extension; use .obj, .off, .ply or .stl)",
                        what);
    }
    if (o->failed) return acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory while encoding", what);
    return ACD_OK;
}

acd_status acd_mesh_write_memory(const acd_mesh *m, acd_mesh_format fmt, void **data, size_t *size, acd_error *err) {
    if (!data || !size) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_write_memory: NULL output");
    acd_obuf o = {0};
    acd_status s = encode(m, fmt, &o, "acd_mesh_write_memory", err);
    if (s != ACD_OK) {
        free(o.data);
        return s;
    }
    *data = o.data;
    *size = o.len;
    return ACD_OK;
}

static acd_status save(const char *path, const acd_obuf *o, acd_error *err) {
    size_t n = strlen(path);
    if (n >= 3 && (!strcmp(path + n - 3, ".gz") || !strcmp(path + n - 3, ".GZ"))) {
        gzFile g = gzopen(path, "wb");
        if (!g) return acd_fail(err, ACD_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
        size_t done = 0;
        while (done < o->len) {
            unsigned chunk = o->len - done > (1u << 30) ? (1u << 30) : (unsigned)(o->len - done);
            int w = gzwrite(g, o->data + done, chunk);
            if (w <= 0) {
                gzclose(g);
                return acd_fail(err, ACD_ERR_IO, "%s: write error after %zu bytes", path, done);
            }
            done += (size_t)w;
        }
        if (gzclose(g) != Z_OK) return acd_fail(err, ACD_ERR_IO, "%s: error closing the gzip file", path);
        return ACD_OK;
    }
    FILE *f = fopen(path, "wb");
    if (!f) return acd_fail(err, ACD_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
    size_t w = o->len ? fwrite(o->data, 1, o->len, f) : 0;
    int bad = w != o->len || ferror(f);
    if (fclose(f) != 0) bad = 1;
    if (bad) return acd_fail(err, ACD_ERR_IO, "%s: write error: %s", path, strerror(errno));
    return ACD_OK;
}

acd_status acd_mesh_write(const char *path, const acd_mesh *m, acd_mesh_format fmt, acd_error *err) {
    if (!path) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_write: NULL path");
    if (fmt == ACD_MESH_FORMAT_AUTO) fmt = acd_mesh_format_from_path(path);
    acd_obuf o = {0};
    acd_status s = encode(m, fmt, &o, path, err);
    if (s == ACD_OK) s = save(path, &o, err);
    free(o.data);
    return s;
}

acd_status acd_mesh_write_obj_parts(const char *path, const acd_mesh_parts *parts, acd_error *err) {
    if (!path || !parts || (parts->count && !parts->parts))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_write_obj_parts: NULL argument");
    for (size_t i = 0; i < parts->count; i++) {
        char what[64];
        snprintf(what, sizeof what, "part %zu", i);
        acd_status s = check_mesh(&parts->parts[i].mesh, 0, what, err);
        if (s != ACD_OK) return s;
    }
    acd_obuf o = {0};
    acd_obj_write_parts(&o, parts);
    acd_status s = o.failed ? acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory while encoding", path) : save(path, &o, err);
    free(o.data);
    return s;
}
