/* mesh/io_ply: PLY reader (ASCII, binary little- and big-endian) and writer.
 *
 * The header's elements are read in order. "vertex" needs properties x, y, z (any numeric type;
 * other properties skipped); "face" needs a list property vertex_indices (or vertex_index, or
 * else its first list), fanned into triangles; "tristrips" (the Stanford tools' triangle strips)
 * the same list, -1 ending a strip, its triangles in alternating order and those with a repeated
 * corner (strip joins) dropped; every other element is skipped by its declared layout, told to
 * the warning channel (acd_mesh_read_options) when it has records. Header lines with an unknown keyword are ignored like comments. Byte order is handled byte by byte, independent of the host. Writes binary
 * little-endian (double coordinates, uint32 indices: exact) or ASCII with %.17g. */
#include "mesh/io_formats.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

typedef enum ply_type { PT_NONE = 0, PT_I8, PT_U8, PT_I16, PT_U16, PT_I32, PT_U32, PT_F32, PT_F64 } ply_type;

static const struct {
    const char *name;
    ply_type type;
} type_names[] = {{"char", PT_I8},    {"int8", PT_I8},     {"uchar", PT_U8},   {"uint8", PT_U8},   {"short", PT_I16},
                  {"int16", PT_I16},  {"ushort", PT_U16},  {"uint16", PT_U16}, {"int", PT_I32},    {"int32", PT_I32},
                  {"uint", PT_U32},   {"uint32", PT_U32},  {"float", PT_F32},  {"float32", PT_F32}, {"double", PT_F64},
                  {"float64", PT_F64}};

static size_t type_size(ply_type t) {
    switch (t) {
    case PT_I8:
    case PT_U8: return 1;
    case PT_I16:
    case PT_U16: return 2;
    case PT_I32:
    case PT_U32:
    case PT_F32: return 4;
    case PT_F64: return 8;
    case PT_NONE: break;
    }
    return 0;
}

#define PLY_MAX_PROPS 64
#define PLY_MAX_ELEMS 32

typedef struct ply_prop {
    ply_type type;       /* scalar type, or item type of a list */
    ply_type count_type; /* PT_NONE for a scalar */
    char name[32];
} ply_prop;

typedef struct ply_elem {
    char name[32];
    uint64_t count;
    size_t line; /* of its header line */
    ply_prop props[PLY_MAX_PROPS];
    int nprops;
} ply_elem;

enum { PLY_ASCII, PLY_LE, PLY_BE };

/* The triangles of the strips in b's scratch polygon (UINT32_MAX ends a strip): triangle k of a
 * strip s is (s[k], s[k+1], s[k+2]), its first two corners swapped when k is odd, so that all face
 * one way; a triangle with a repeated corner (strips joined by repeating an index) is dropped. */
static acd_status strip_triangles(acd_mesh_builder *b, const char *name, acd_error *err) {
    size_t k = 0; /* position within the current strip */
    for (size_t i = 0; i < b->npoly; i++) {
        if (b->poly[i] == UINT32_MAX) {
            k = 0;
            continue;
        }
        if (++k < 3) continue;
        uint32_t a = b->poly[i - 2], c = b->poly[i - 1], d = b->poly[i];
        if (a == c || c == d || a == d) continue;
        if (!((k - 3) % 2 == 0 ? acd_builder_triangle(b, a, c, d) : acd_builder_triangle(b, c, a, d)))
            return acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory", name);
    }
    b->npoly = 0;
    return ACD_OK;
}

int acd_ply_sniff(const char *buf, size_t len) {
    return len >= 4 && !strncmp(buf, "ply", 3) && (buf[3] == '\n' || buf[3] == '\r');
}

static ply_type parse_type(const char *s, size_t n) {
    for (size_t i = 0; i < sizeof type_names / sizeof type_names[0]; i++)
        if (strlen(type_names[i].name) == n && !strncmp(type_names[i].name, s, n)) return type_names[i].type;
    return PT_NONE;
}

/* Next word on the current line: *w, length returned (0 at end of line). */
static size_t word(acd_text *t, const char **w) {
    acd_text_skip_blank(t);
    *w = t->p;
    while (*t->p && *t->p != ' ' && *t->p != '\t' && *t->p != '\r' && *t->p != '\n') t->p++;
    return (size_t)(t->p - *w);
}

static int word_is(const char *w, size_t n, const char *s) { return strlen(s) == n && !strncmp(w, s, n); }

static double type_min(ply_type t) {
    switch (t) {
    case PT_I8: return -128;
    case PT_I16: return -32768;
    case PT_I32: return -2147483648.0;
    default: return t == PT_F32 || t == PT_F64 ? -INFINITY : 0;
    }
}

static double type_max(ply_type t) {
    switch (t) {
    case PT_I8: return 127;
    case PT_U8: return 255;
    case PT_I16: return 32767;
    case PT_U16: return 65535;
    case PT_I32: return 2147483647.0;
    case PT_U32: return 4294967295.0;
    default: return INFINITY;
    }
}

static double decode(const unsigned char *p, ply_type t, int be) {
    unsigned char b[8];
    size_t n = type_size(t);
    for (size_t i = 0; i < n; i++) b[i] = be ? p[n - 1 - i] : p[i];
    uint64_t u = 0;
    for (size_t i = 0; i < n; i++) u |= (uint64_t)b[i] << (8 * i);
    switch (t) {
    case PT_I8: return (double)(int8_t)(uint8_t)u;
    case PT_U8: return (double)(uint8_t)u;
    case PT_I16: return (double)(int16_t)(uint16_t)u;
    case PT_U16: return (double)(uint16_t)u;
    case PT_I32: return (double)(int32_t)(uint32_t)u;
    case PT_U32: return (double)(uint32_t)u;
    case PT_F32: {
        uint32_t v = (uint32_t)u;
        float f;
        memcpy(&f, &v, 4);
        return (double)f;
    }
    case PT_F64: {
        double d;
        memcpy(&d, &u, 8);
        return d;
    }
    case PT_NONE: break;
    }
    return 0;
}

typedef struct ply_reader {
    const char *name;
    int format;
    acd_text t;                /* ASCII data cursor */
    const unsigned char *data; /* binary: whole buffer */
    size_t pos, len;           /* binary: current byte offset, buffer length */
} ply_reader;

/* Reads one value of type ty; *where gets a position description on failure. */
static acd_status read_value(ply_reader *r, ply_type ty, double *out, const char *what, uint64_t index,
                             acd_error *err) {
    if (r->format == PLY_ASCII) {
        acd_text_skip_space(&r->t, 0);
        const char *q = acd_parse_double(r->t.p, out);
        if (!q || (*q && *q != ' ' && *q != '\t' && *q != '\r' && *q != '\n'))
            return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: %s %llu: expected a number, found '%.12s'", r->name, r->t.line,
                            what, (unsigned long long)index, r->t.p);
        r->t.p = q;
        if (ty != PT_F32 && ty != PT_F64 && (*out != floor(*out) || *out < type_min(ty) || *out > type_max(ty)))
            return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: %s %llu: integer property has value %g (not an integer of its type)",
                            r->name, r->t.line, what, (unsigned long long)index, *out);
        return ACD_OK;
    }
    size_t n = type_size(ty);
    if (r->len - r->pos < n)
        return acd_fail(err, ACD_ERR_PARSE, "%s: byte offset %zu: file ends inside %s %llu", r->name, r->pos, what,
                        (unsigned long long)index);
    *out = decode(r->data + r->pos, ty, r->format == PLY_BE);
    r->pos += n;
    return ACD_OK;
}

static const char *where(ply_reader *r, char *buf, size_t n) {
    if (r->format == PLY_ASCII) snprintf(buf, n, "%s:%zu", r->name, r->t.line);
    else snprintf(buf, n, "%s: byte offset %zu", r->name, r->pos);
    return buf;
}

static acd_status parse_header(acd_text *t, int *format, ply_elem *elems, int *nelems, acd_error *err) {
    const char *w;
    size_t n;
    *nelems = 0;
    *format = -1;
    acd_text_next_line(t); /* "ply" */
    for (;;) {
        if (t->p >= t->end) return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: header has no end_header", t->name, t->line);
        n = word(t, &w);
        if (n == 0 || word_is(w, n, "comment") || word_is(w, n, "obj_info")) {
            acd_text_next_line(t);
            continue;
        }
        if (word_is(w, n, "end_header")) {
            /* data starts right after this line's newline */
            const char *q = t->p;
            while (*q == ' ' || *q == '\t' || *q == '\r') q++;
            if (*q != '\n') return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: end_header not followed by a newline", t->name, t->line);
            t->p = q + 1;
            t->line++;
            break;
        }
        if (word_is(w, n, "format")) {
            n = word(t, &w);
            if (word_is(w, n, "ascii")) *format = PLY_ASCII;
            else if (word_is(w, n, "binary_little_endian")) *format = PLY_LE;
            else if (word_is(w, n, "binary_big_endian")) *format = PLY_BE;
            else return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: unknown PLY format '%.*s'", t->name, t->line, (int)(n > 30 ? 30 : n), w);
            n = word(t, &w);
            if (!word_is(w, n, "1.0"))
                return acd_fail(err, ACD_ERR_UNSUPPORTED, "%s:%zu: PLY version '%.*s' (only 1.0)", t->name, t->line,
                                (int)(n > 30 ? 30 : n), w);
        } else if (word_is(w, n, "element")) {
            if (*nelems == PLY_MAX_ELEMS)
                return acd_fail(err, ACD_ERR_UNSUPPORTED, "%s:%zu: more than %d elements", t->name, t->line, PLY_MAX_ELEMS);
            ply_elem *e = &elems[(*nelems)++];
            memset(e, 0, sizeof *e);
            e->line = t->line;
            n = word(t, &w);
            if (n == 0) return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: element without a name", t->name, t->line);
            snprintf(e->name, sizeof e->name, "%.*s", (int)(n > 31 ? 31 : n), w);
            int64_t c;
            const char *q = acd_parse_int64(t->p, &c);
            if (!q || c < 0) return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: element '%s' has no valid count", t->name, t->line, e->name);
            t->p = q;
            e->count = (uint64_t)c;
        } else if (word_is(w, n, "property")) {
            if (*nelems == 0) return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: property before any element", t->name, t->line);
            ply_elem *e = &elems[*nelems - 1];
            if (e->nprops == PLY_MAX_PROPS)
                return acd_fail(err, ACD_ERR_UNSUPPORTED, "%s:%zu: more than %d properties", t->name, t->line, PLY_MAX_PROPS);
            ply_prop *p = &e->props[e->nprops++];
            n = word(t, &w);
            if (word_is(w, n, "list")) {
                n = word(t, &w);
                p->count_type = parse_type(w, n);
                n = word(t, &w);
                p->type = parse_type(w, n);
                if (!p->count_type || !p->type || p->count_type == PT_F32 || p->count_type == PT_F64)
                    return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: bad list property types", t->name, t->line);
            } else {
                p->type = parse_type(w, n);
                if (!p->type)
                    return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: unknown property type '%.*s'", t->name, t->line,
                                    (int)(n > 30 ? 30 : n), w);
            }
            n = word(t, &w);
            if (n == 0) return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: property without a name", t->name, t->line);
            snprintf(p->name, sizeof p->name, "%.*s", (int)(n > 31 ? 31 : n), w);
        }
        /* any other line: ignored like a comment (old Blender exporters wrote "Created by ..."
           without the comment keyword) */
        acd_text_next_line(t);
    }
    if (*format < 0) return acd_fail(err, ACD_ERR_PARSE, "%s: header has no format line", t->name);
    return ACD_OK;
}

acd_status acd_ply_read(const char *buf, size_t len, const char *name, acd_mesh_builder *b, acd_error *err) {
    if (!acd_ply_sniff(buf, len)) return acd_fail(err, ACD_ERR_PARSE, "%s:1: does not start with 'ply'", name);
    ply_elem *elems = malloc(PLY_MAX_ELEMS * sizeof *elems);
    if (!elems) return acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory", name);
    int nelems, format;
    ply_reader r;
    memset(&r, 0, sizeof r);
    r.t = (acd_text){buf, buf + len, 1, name};
    r.name = name;
    acd_status s = parse_header(&r.t, &format, elems, &nelems, err);
    if (s != ACD_OK) {
        free(elems);
        return s;
    }
    r.format = format;
    r.data = (const unsigned char *)buf;
    r.len = len;
    r.pos = (size_t)(r.t.p - buf);
    uint64_t nverts = 0;
    int have_vertex = 0, have_face = 0;
    for (int i = 0; i < nelems; i++)
        if (!strcmp(elems[i].name, "vertex")) {
            nverts = elems[i].count;
            have_vertex = 1;
        }
    if (nverts > UINT32_MAX) {
        free(elems);
        return acd_fail(err, ACD_ERR_UNSUPPORTED, "%s: %llu vertices (at most 2^32-1)", name, (unsigned long long)nverts);
    }
    const size_t v0 = b->nv;
    char pos[600];
    for (int ei = 0; ei < nelems && s == ACD_OK; ei++) {
        ply_elem *e = &elems[ei];
        int is_vertex = !strcmp(e->name, "vertex"), is_face = !strcmp(e->name, "face"),
            is_strip = !strcmp(e->name, "tristrips");
        if (e->count > 0 && !is_vertex && !is_face && !is_strip && b->warn) {
            char msg[ACD_ERROR_MESSAGE_SIZE];
            if (!strcmp(e->name, "edge"))
                snprintf(msg, sizeof msg,
                         "%s:%zu: %llu 'edge' element%s skipped (line segments): only faces and triangle strips are "
                         "read as geometry, so the mesh may be incomplete",
                         name, e->line, (unsigned long long)e->count, e->count == 1 ? "" : "s");
            else
                snprintf(msg, sizeof msg,
                         "%s:%zu: %llu '%s' element%s skipped: only vertex, face and tristrips elements are read", name,
                         e->line, (unsigned long long)e->count, e->name, e->count == 1 ? "" : "s");
            b->warn(b->warn_user, msg);
        }
        if (e->nprops == 0) continue;
        /* every record takes at least one byte: refuse counts the rest of the file cannot hold */
        size_t left = format == PLY_ASCII ? (size_t)(r.t.end - r.t.p) : r.len - r.pos;
        if (e->count > left / (format == PLY_ASCII ? 2 : 1) + 1) {
            s = acd_fail(err, ACD_ERR_PARSE, "%s: element '%s' count %llu exceeds what the file can hold", name, e->name,
                         (unsigned long long)e->count);
            break;
        }
        int px = -1, py = -1, pz = -1, plist = -1;
        for (int k = 0; k < e->nprops; k++) {
            const ply_prop *p = &e->props[k];
            if (p->count_type == PT_NONE) {
                if (!strcmp(p->name, "x")) px = k;
                if (!strcmp(p->name, "y")) py = k;
                if (!strcmp(p->name, "z")) pz = k;
            } else if (!strcmp(p->name, "vertex_indices") || !strcmp(p->name, "vertex_index") ||
                       (plist < 0 && (is_face || is_strip))) {
                if (plist < 0 || strcmp(e->props[plist].name, "vertex_indices") != 0) plist = k;
            }
        }
        if (is_vertex && (px < 0 || py < 0 || pz < 0)) {
            s = acd_fail(err, ACD_ERR_PARSE, "%s: element 'vertex' lacks property x, y or z", name);
            break;
        }
        if ((is_face || is_strip) && plist < 0) {
            s = acd_fail(err, ACD_ERR_PARSE, "%s: element '%s' has no list property vertex_indices", name, e->name);
            break;
        }
        have_face |= is_face;
        for (uint64_t i = 0; i < e->count && s == ACD_OK; i++) {
            double xyz[3] = {0, 0, 0};
            b->npoly = 0;
            for (int k = 0; k < e->nprops && s == ACD_OK; k++) {
                const ply_prop *p = &e->props[k];
                double v;
                if (p->count_type == PT_NONE) {
                    s = read_value(&r, p->type, &v, e->name, i, err);
                    if (s != ACD_OK) break;
                    if (is_vertex && (k == px || k == py || k == pz)) {
                        if (!isfinite(v)) {
                            s = acd_fail(err, ACD_ERR_PARSE, "%s: vertex %llu: coordinate %s is not finite",
                                         where(&r, pos, sizeof pos), (unsigned long long)i, p->name);
                            break;
                        }
                        xyz[k == px ? 0 : k == py ? 1 : 2] = v;
                    }
                    continue;
                }
                double c;
                s = read_value(&r, p->count_type, &c, e->name, i, err);
                if (s != ACD_OK) break;
                if (c < 0) {
                    s = acd_fail(err, ACD_ERR_PARSE, "%s: %s %llu: negative list length %g", where(&r, pos, sizeof pos),
                                 e->name, (unsigned long long)i, c);
                    break;
                }
                int take = (is_face || is_strip) && k == plist;
                if (take && is_face && c < 3) {
                    s = acd_fail(err, ACD_ERR_PARSE, "%s: face %llu has %g vertices (at least 3 needed)",
                                 where(&r, pos, sizeof pos), (unsigned long long)i, c);
                    break;
                }
                if (format != PLY_ASCII && !take) { /* skip the list in one step */
                    uint64_t bytes = (uint64_t)c * type_size(p->type);
                    if (bytes > r.len - r.pos) {
                        s = acd_fail(err, ACD_ERR_PARSE, "%s: byte offset %zu: file ends inside %s %llu", name, r.pos,
                                     e->name, (unsigned long long)i);
                        break;
                    }
                    r.pos += (size_t)bytes;
                    continue;
                }
                for (uint64_t j = 0; j < (uint64_t)c && s == ACD_OK; j++) {
                    s = read_value(&r, p->type, &v, e->name, i, err);
                    if (s != ACD_OK || !take) continue;
                    if (is_strip && v == -1) { /* the end of a strip */
                        if (!acd_builder_poly_push(b, UINT32_MAX))
                            s = acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory", name);
                        continue;
                    }
                    if (!(v >= 0 && v < (double)nverts)) {
                        s = acd_fail(err, ACD_ERR_PARSE, "%s: %s %llu: vertex index %g out of range (0..%llu%s)",
                                     where(&r, pos, sizeof pos), is_strip ? "strip" : "face", (unsigned long long)i, v,
                                     (unsigned long long)nverts - 1, is_strip ? ", or -1 ending a strip" : "");
                        break;
                    }
                    if (!acd_builder_poly_push(b, (uint32_t)(v0 + (size_t)v)))
                        s = acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory", name);
                }
            }
            if (s != ACD_OK) break;
            if (is_vertex && !acd_builder_vertex(b, xyz[0], xyz[1], xyz[2]))
                s = acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory", name);
            if (is_face) s = acd_builder_fan_or_fail(b, name, 0, err);
            if (is_strip) s = strip_triangles(b, name, err);
        }
    }
    free(elems);
    if (s == ACD_OK && !have_vertex) s = acd_fail(err, ACD_ERR_PARSE, "%s: no 'vertex' element", name);
    (void)have_face; /* a point cloud (no faces) is a mesh without triangles */
    return s;
}

static void put_u32le(acd_obuf *o, uint32_t u) {
    unsigned char b[4] = {(unsigned char)u, (unsigned char)(u >> 8), (unsigned char)(u >> 16), (unsigned char)(u >> 24)};
    acd_obuf_write(o, b, 4);
}

static void put_f64le(acd_obuf *o, double d) {
    uint64_t u;
    memcpy(&u, &d, 8);
    unsigned char b[8];
    for (int i = 0; i < 8; i++) b[i] = (unsigned char)(u >> (8 * i));
    acd_obuf_write(o, b, 8);
}

void acd_ply_write(acd_obuf *o, const acd_mesh *m, int ascii) {
    acd_obuf_printf(o,
                    "ply\nformat %s 1.0\ncomment written by acd %s\nelement vertex %zu\nproperty double x\n"
                    "property double y\nproperty double z\nelement face %zu\nproperty list uchar uint vertex_indices\n"
                    "end_header\n",
                    ascii ? "ascii" : "binary_little_endian", ACD_VERSION_STRING, m->nvertices, m->ntriangles);
    for (size_t i = 0; i < m->nvertices; i++) {
        const double *v = m->vertices + 3 * i;
        if (ascii) {
            acd_obuf_double(o, v[0]);
            acd_obuf_write(o, " ", 1);
            acd_obuf_double(o, v[1]);
            acd_obuf_write(o, " ", 1);
            acd_obuf_double(o, v[2]);
            acd_obuf_write(o, "\n", 1);
        } else {
            for (int k = 0; k < 3; k++) put_f64le(o, v[k]);
        }
    }
    for (size_t i = 0; i < m->ntriangles; i++) {
        const uint32_t *t = m->triangles + 3 * i;
        if (ascii) {
            acd_obuf_write(o, "3", 1);
            for (int k = 0; k < 3; k++) {
                acd_obuf_write(o, " ", 1);
                acd_obuf_u64(o, t[k]);
            }
            acd_obuf_write(o, "\n", 1);
        } else {
            acd_obuf_write(o, "\3", 1);
            for (int k = 0; k < 3; k++) put_u32le(o, t[k]);
        }
    }
}
