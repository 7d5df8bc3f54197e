/* mesh/mesh_read: reading a mesh file: gzip decompression (zlib), format detection from the
 * content, dispatch to the per-format reader, and splitting OBJ groups into parts.
 *
 * Detection order: gzip magic (1f 8b) -> decompress and detect again; "ply" -> PLY; an OFF
 * header keyword -> OFF; a binary STL whose size is exactly 84 + 50 * count -> STL; "solid" ->
 * ASCII STL; a first statement that is an OBJ keyword -> OBJ; otherwise the hint (the file's
 * extension) decides, so that e.g. a truncated binary STL gets an STL error message. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <zlib.h>

#include "core/error.h"
#include "mesh/io_formats.h"

const char *acd_mesh_format_name(acd_mesh_format f) {
    switch (f) {
    case ACD_MESH_FORMAT_AUTO: return "auto";
    case ACD_MESH_FORMAT_OBJ: return "obj";
    case ACD_MESH_FORMAT_OFF: return "off";
    case ACD_MESH_FORMAT_PLY: return "ply";
    case ACD_MESH_FORMAT_PLY_ASCII: return "ply-ascii";
    case ACD_MESH_FORMAT_STL: return "stl";
    case ACD_MESH_FORMAT_STL_ASCII: return "stl-ascii";
    }
    return "unknown";
}

static int ends_with_ci(const char *s, size_t n, const char *suffix) {
    size_t m = strlen(suffix);
    if (n < m) return 0;
    for (size_t i = 0; i < m; i++) {
        char c = s[n - m + i];
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != suffix[i]) return 0;
    }
    return 1;
}

acd_mesh_format acd_mesh_format_from_path(const char *path) {
    if (!path) return ACD_MESH_FORMAT_AUTO;
    size_t n = strlen(path);
    if (ends_with_ci(path, n, ".gz")) n -= 3;
    if (ends_with_ci(path, n, ".obj")) return ACD_MESH_FORMAT_OBJ;
    if (ends_with_ci(path, n, ".off")) return ACD_MESH_FORMAT_OFF;
    if (ends_with_ci(path, n, ".ply")) return ACD_MESH_FORMAT_PLY;
    if (ends_with_ci(path, n, ".stl")) return ACD_MESH_FORMAT_STL;
    return ACD_MESH_FORMAT_AUTO;
}

/* A gzip bomb guard: decompressed data larger than ACD_GZIP_BOMB_MIN_BYTES that is more than
 * ACD_GZIP_MAX_RATIO times the compressed size is refused. Mesh files compress by 2-10 (binary
 * coordinates less, text more); deflate's limit is about 1032, reached only by long runs of one
 * byte or pattern, which no real mesh consists of. The output never grows past that limit (a file
 * of a few MB would otherwise expand to many GB and be killed by the OOM killer). */
#define ACD_GZIP_MAX_RATIO 100
#define ACD_GZIP_BOMB_MIN_BYTES ((size_t)64 << 20)

/* Decompresses a gzip buffer into a malloc'd, NUL-terminated buffer. */
static acd_status gunzip(const unsigned char *in, size_t n, const char *name, char **out, size_t *outlen,
                         acd_error *err) {
    z_stream z;
    memset(&z, 0, sizeof z);
    if (inflateInit2(&z, 15 + 32) != Z_OK) return acd_fail(err, ACD_ERR_NOMEM, "%s: zlib initialisation failed", name);
    size_t cap = n * 4 + 1024, len = 0;
    char *buf = malloc(cap);
    if (!buf) {
        inflateEnd(&z);
        return acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory decompressing", name);
    }
    size_t consumed = 0;
    size_t limit = n > SIZE_MAX / ACD_GZIP_MAX_RATIO ? SIZE_MAX - 1 : n * ACD_GZIP_MAX_RATIO;
    if (limit < ACD_GZIP_BOMB_MIN_BYTES) limit = ACD_GZIP_BOMB_MIN_BYTES;
    int ret = Z_OK;
    while (ret != Z_STREAM_END) {
        if (len > limit) {
            free(buf);
            inflateEnd(&z);
            return acd_fail(err, ACD_ERR_PARSE,
                            "%s: gzip data expands more than %d times (%zu compressed bytes gave over %zu bytes by "
                            "compressed byte offset %zu): refused as a likely gzip bomb, not a mesh",
                            name, ACD_GZIP_MAX_RATIO, n, limit, consumed);
        }
        if (cap - len < 2) {
            size_t c2 = cap;
            if (!acd_grow((void **)&buf, &c2, cap + 1, 1)) {
                free(buf);
                inflateEnd(&z);
                return acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory decompressing (%zu bytes so far)", name, len);
            }
            cap = c2;
        }
        size_t chunk_in = n - consumed > (1u << 30) ? (1u << 30) : n - consumed;
        size_t chunk_out = cap - len - 1 > (1u << 30) ? (1u << 30) : cap - len - 1;
        if (chunk_out > limit + 1 - len) chunk_out = limit + 1 - len; /* one byte past: refused above */
        z.next_in = (unsigned char *)(uintptr_t)(in + consumed);
        z.avail_in = (uInt)chunk_in;
        z.next_out = (unsigned char *)buf + len;
        z.avail_out = (uInt)chunk_out;
        ret = inflate(&z, Z_NO_FLUSH);
        consumed += chunk_in - z.avail_in;
        len += chunk_out - z.avail_out;
        if (ret == Z_STREAM_END) {
            /* concatenated gzip members: continue with the next one */
            if (consumed < n && n - consumed >= 2 && in[consumed] == 0x1f && in[consumed + 1] == 0x8b) {
                inflateReset(&z);
                ret = Z_OK;
            }
            continue;
        }
        if (ret == Z_BUF_ERROR && z.avail_in == 0 && consumed == n) {
            free(buf);
            inflateEnd(&z);
            return acd_fail(err, ACD_ERR_PARSE, "%s: gzip data truncated (compressed byte offset %zu)", name, consumed);
        }
        if (ret != Z_OK && ret != Z_BUF_ERROR) {
            free(buf);
            inflateEnd(&z);
            return acd_fail(err, ACD_ERR_PARSE, "%s: corrupt gzip data at compressed byte offset %zu: %s", name, consumed,
                            z.msg ? z.msg : "inflate error");
        }
    }
    inflateEnd(&z);
    buf[len] = '\0';
    *out = buf;
    *outlen = len;
    return ACD_OK;
}

/* UTF-16 text (with a byte-order mark) to 8-bit: ASCII kept, anything else becomes '?'. Some
 * Windows tools write OBJ that way. */
static acd_status from_utf16(char **buf, size_t *len, const char *name, acd_error *err) {
    const unsigned char *u = (const unsigned char *)*buf;
    int be = u[0] == 0xfe;
    size_t n = (*len - 2) / 2;
    char *out = malloc(n + 1);
    if (!out) return acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory converting UTF-16", name);
    for (size_t i = 0; i < n; i++) {
        unsigned c = be ? (unsigned)u[2 + 2 * i] << 8 | u[3 + 2 * i] : (unsigned)u[3 + 2 * i] << 8 | u[2 + 2 * i];
        out[i] = c < 0x80 && c != 0 ? (char)c : '?';
    }
    out[n] = '\0';
    free(*buf);
    *buf = out;
    *len = n;
    return ACD_OK;
}

static acd_mesh_format detect(const char *buf, size_t len, acd_mesh_format hint) {
    if (acd_ply_sniff(buf, len)) return ACD_MESH_FORMAT_PLY;
    if (acd_off_sniff(buf, len)) return ACD_MESH_FORMAT_OFF;
    if (acd_stl_is_binary((const unsigned char *)buf, len)) return ACD_MESH_FORMAT_STL;
    if (acd_stl_is_ascii(buf, len)) return ACD_MESH_FORMAT_STL;
    if (acd_obj_sniff(buf, len)) return ACD_MESH_FORMAT_OBJ;
    if (hint == ACD_MESH_FORMAT_PLY_ASCII) return ACD_MESH_FORMAT_PLY;
    if (hint == ACD_MESH_FORMAT_STL_ASCII) return ACD_MESH_FORMAT_STL;
    return hint;
}

/* Reads buf (NUL-terminated at len) into the builder. */
static acd_status parse(const char *buf, size_t len, acd_mesh_format hint, const char *name, acd_mesh_builder *b,
                        acd_mesh_format *used, acd_error *err) {
    acd_mesh_format f = detect(buf, len, hint);
    if (used) *used = f;
    switch (f) {
    case ACD_MESH_FORMAT_OBJ: return acd_obj_read(buf, len, name, b, err);
    case ACD_MESH_FORMAT_OFF: return acd_off_read(buf, len, name, b, err);
    case ACD_MESH_FORMAT_PLY:
    case ACD_MESH_FORMAT_PLY_ASCII: return acd_ply_read(buf, len, name, b, err);
    case ACD_MESH_FORMAT_STL:
    case ACD_MESH_FORMAT_STL_ASCII: return acd_stl_read(buf, len, name, b, err);
    case ACD_MESH_FORMAT_AUTO: break;
    }
    if (len == 0) return acd_fail(err, ACD_ERR_PARSE, "%s: empty file", name);
    return acd_fail(err, ACD_ERR_UNSUPPORTED,
                    "%s: unrecognised mesh format (not OBJ, OFF, PLY or STL, judging by the first bytes '%.8s')", name,
                    buf);
}

/* Reads a memory image (possibly gzip) into the builder. */
static acd_status parse_memory(const void *data, size_t size, acd_mesh_format hint, const char *name,
                               acd_mesh_builder *b, acd_mesh_format *used, acd_error *err) {
    if (!name) name = "<memory>";
    const unsigned char *d = data;
    char *buf = NULL;
    size_t len = 0;
    acd_status s;
    if (size >= 2 && d[0] == 0x1f && d[1] == 0x8b) {
        if ((s = gunzip(d, size, name, &buf, &len, err)) != ACD_OK) return s;
    } else {
        buf = malloc(size + 1);
        if (!buf) return acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory (%zu bytes)", name, size);
        if (size) memcpy(buf, data, size);
        buf[size] = '\0';
        len = size;
    }
    if (len >= 2 && (((unsigned char)buf[0] == 0xfe && (unsigned char)buf[1] == 0xff) ||
                     ((unsigned char)buf[0] == 0xff && (unsigned char)buf[1] == 0xfe))) {
        if ((s = from_utf16(&buf, &len, name, err)) != ACD_OK) {
            free(buf);
            return s;
        }
    }
    if (len == 0) {
        free(buf);
        return acd_fail(err, ACD_ERR_PARSE, "%s: empty file", name);
    }
    const char *text = buf;
    if (len >= 3 && !memcmp(buf, "\xef\xbb\xbf", 3)) { /* UTF-8 byte-order mark */
        text += 3;
        len -= 3;
    }
    s = parse(text, len, hint, name, b, used, err);
    free(buf);
    return s;
}

static acd_status load_file(const char *path, unsigned char **data, size_t *size, acd_error *err) {
    FILE *f = fopen(path, "rb");
    if (!f) return acd_fail(err, ACD_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    size_t cap = 1 << 16, len = 0;
    unsigned char *buf = NULL;
    struct stat st;
    if (fstat(fileno(f), &st) == 0) {
        if (S_ISDIR(st.st_mode)) {
            fclose(f);
            return acd_fail(err, ACD_ERR_IO, "%s: is a directory, not a mesh file", path);
        }
        if (S_ISREG(st.st_mode) && st.st_size > 0) cap = (size_t)st.st_size + 1;
    }
    buf = malloc(cap);
    if (!buf) {
        fclose(f);
        return acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory (%zu bytes)", path, cap);
    }
    for (;;) {
        if (len == cap) {
            size_t c2 = cap;
            if (!acd_grow((void **)&buf, &c2, cap + 1, 1)) {
                free(buf);
                fclose(f);
                return acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory (%zu bytes)", path, cap);
            }
            cap = c2;
        }
        size_t r = fread(buf + len, 1, cap - len, f);
        len += r;
        if (r == 0) break;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        return acd_fail(err, ACD_ERR_IO, "%s: read error after %zu bytes: %s", path, len, strerror(errno));
    }
    *data = buf;
    *size = len;
    return ACD_OK;
}

static acd_status parse_file(const char *path, acd_mesh_builder *b, acd_mesh_format *used, acd_error *err) {
    unsigned char *data = NULL;
    size_t size = 0;
    acd_status s = load_file(path, &data, &size, err);
    if (s != ACD_OK) return s;
    s = parse_memory(data, size, acd_mesh_format_from_path(path), path, b, used, err);
    free(data);
    return s;
}

static acd_status finish_mesh(acd_mesh_builder *b, acd_status s, acd_mesh *out) {
    memset(out, 0, sizeof *out);
    if (s == ACD_OK) acd_builder_take_mesh(b, out);
    acd_builder_free(b);
    return s;
}

acd_mesh_read_options acd_mesh_read_default_options(void) {
    acd_mesh_read_options o;
    memset(&o, 0, sizeof o);
    return o;
}

/* An empty builder with the options' warning channel. */
static void builder_init(acd_mesh_builder *b, const acd_mesh_read_options *opt) {
    memset(b, 0, sizeof *b);
    if (opt) {
        b->warn = opt->warning;
        b->warn_user = opt->warning_user;
    }
}

acd_status acd_mesh_read_memory_ex(const void *data, size_t size, acd_mesh_format hint, const char *name,
                                   const acd_mesh_read_options *opt, acd_mesh *out, acd_error *err) {
    if (!out || (!data && size)) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_read_memory: NULL argument");
    acd_error_clear(err);
    acd_mesh_builder b;
    builder_init(&b, opt);
    return finish_mesh(&b, parse_memory(data, size, hint, name, &b, NULL, err), out);
}

acd_status acd_mesh_read_memory(const void *data, size_t size, acd_mesh_format hint, const char *name,
                                acd_mesh *out, acd_error *err) {
    return acd_mesh_read_memory_ex(data, size, hint, name, NULL, out, err);
}

acd_status acd_mesh_read_ex(const char *path, const acd_mesh_read_options *opt, acd_mesh *out, acd_error *err) {
    if (!out || !path) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_read: NULL argument");
    acd_error_clear(err);
    acd_mesh_builder b;
    builder_init(&b, opt);
    return finish_mesh(&b, parse_file(path, &b, NULL, err), out);
}

acd_status acd_mesh_read(const char *path, acd_mesh *out, acd_error *err) {
    return acd_mesh_read_ex(path, NULL, out, err);
}

void acd_mesh_parts_free(acd_mesh_parts *p) {
    if (!p) return;
    for (size_t i = 0; i < p->count; i++) {
        free(p->parts[i].name);
        acd_mesh_free(&p->parts[i].mesh);
    }
    free(p->parts);
    p->parts = NULL;
    p->count = 0;
}

/* Splits the builder's triangles into parts at the group starts; each part keeps the vertices it
 * uses, in order of first use. */
static acd_status split_parts(acd_mesh_builder *b, const char *name, acd_mesh_parts *out, acd_error *err) {
    size_t nranges = b->ngroups + 1;
    out->parts = calloc(nranges, sizeof *out->parts);
    uint32_t *stamp = malloc((b->nv ? b->nv : 1) * sizeof *stamp);
    uint32_t *newidx = malloc((b->nv ? b->nv : 1) * sizeof *newidx);
    if (!out->parts || !stamp || !newidx) {
        free(stamp);
        free(newidx);
        free(out->parts);
        out->parts = NULL;
        return acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory splitting parts", name);
    }
    for (size_t i = 0; i < b->nv; i++) stamp[i] = UINT32_MAX;
    acd_status s = ACD_OK;
    for (size_t g = 0; g < nranges && s == ACD_OK; g++) {
        size_t t0 = g == 0 ? 0 : b->groups[g - 1].first_triangle;
        size_t t1 = g < b->ngroups ? b->groups[g].first_triangle : b->nt;
        if (t1 <= t0) continue;
        const char *gname = g == 0 ? "" : b->groups[g - 1].name;
        acd_mesh_part *part = &out->parts[out->count];
        part->name = malloc(strlen(gname) + 1);
        size_t nv = 0;
        for (size_t i = 3 * t0; i < 3 * t1; i++)
            if (stamp[b->t[i]] != (uint32_t)g) {
                stamp[b->t[i]] = (uint32_t)g;
                newidx[b->t[i]] = (uint32_t)nv++;
            }
        part->mesh.vertices = malloc(nv * 3 * sizeof(double));
        part->mesh.triangles = malloc((t1 - t0) * 3 * sizeof(uint32_t));
        out->count++;
        if (!part->name || !part->mesh.vertices || !part->mesh.triangles) {
            s = acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory for part %zu", name, out->count - 1);
            break;
        }
        strcpy(part->name, gname);
        part->mesh.nvertices = nv;
        part->mesh.ntriangles = t1 - t0;
        for (size_t i = 3 * t0; i < 3 * t1; i++) {
            uint32_t v = b->t[i], k = newidx[v];
            part->mesh.triangles[i - 3 * t0] = k;
            memcpy(part->mesh.vertices + 3 * (size_t)k, b->v + 3 * (size_t)v, 3 * sizeof(double));
        }
    }
    free(stamp);
    free(newidx);
    if (s != ACD_OK) acd_mesh_parts_free(out);
    return s;
}

static acd_status finish_parts(acd_mesh_builder *b, acd_status s, const char *name, acd_mesh_format used,
                               int obj_only, acd_mesh_parts *out, acd_error *err) {
    if (s == ACD_OK && obj_only && used != ACD_MESH_FORMAT_OBJ)
        s = acd_fail(err, ACD_ERR_UNSUPPORTED, "%s: not an OBJ file (detected %s): no o/g groups to read", name,
                     acd_mesh_format_name(used));
    if (s == ACD_OK) s = split_parts(b, name, out, err);
    acd_builder_free(b);
    return s;
}

acd_status acd_mesh_read_parts_memory_ex(const void *data, size_t size, acd_mesh_format hint, const char *name,
                                         const acd_mesh_read_options *opt, acd_mesh_parts *out, acd_error *err) {
    if (!out || (!data && size))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_read_parts_memory: NULL argument");
    acd_error_clear(err);
    out->parts = NULL;
    out->count = 0;
    acd_mesh_builder b;
    builder_init(&b, opt);
    acd_mesh_format used = ACD_MESH_FORMAT_AUTO;
    acd_status s = parse_memory(data, size, hint, name, &b, &used, err);
    return finish_parts(&b, s, name ? name : "<memory>", used, 0, out, err);
}

acd_status acd_mesh_read_parts_memory(const void *data, size_t size, acd_mesh_format hint, const char *name,
                                      acd_mesh_parts *out, acd_error *err) {
    return acd_mesh_read_parts_memory_ex(data, size, hint, name, NULL, out, err);
}

static acd_status read_parts(const char *path, const acd_mesh_read_options *opt, acd_mesh_parts *out, int obj_only,
                             acd_error *err) {
    if (!out || !path) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_read_parts: NULL argument");
    acd_error_clear(err);
    out->parts = NULL;
    out->count = 0;
    acd_mesh_builder b;
    builder_init(&b, opt);
    acd_mesh_format used = ACD_MESH_FORMAT_AUTO;
    acd_status s = parse_file(path, &b, &used, err);
    return finish_parts(&b, s, path, used, obj_only, out, err);
}

acd_status acd_mesh_read_parts_ex(const char *path, const acd_mesh_read_options *opt, acd_mesh_parts *out,
                                  acd_error *err) {
    return read_parts(path, opt, out, 0, err);
}

acd_status acd_mesh_read_parts(const char *path, acd_mesh_parts *out, acd_error *err) {
    return read_parts(path, NULL, out, 0, err);
}

acd_status acd_mesh_read_obj_groups(const char *path, acd_mesh_parts *out, acd_error *err) {
    return read_parts(path, NULL, out, 1, err);
}
