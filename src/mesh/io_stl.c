/* mesh/io_stl: STL reader (ASCII and binary) and writer.
 *
 * Binary: 80-byte header, uint32 little-endian triangle count, 50 bytes per triangle (normal,
 * three float32 vertices, uint16 attribute). A file is binary when its size is exactly
 * 84 + 50 * count, whatever its header says (many binary files start with "solid"); room for
 * more triangles than the count is an error (up to 49 trailing bytes are tolerated).
 * ASCII: solid / facet normal / outer loop / vertex x y z (3 or more, fanned) / endloop /
 * endfacet / endsolid, keywords case-insensitive, several solids allowed; other text after the
 * last endsolid is ignored (padding), a facet there refused (it would be lost).
 * STL stores a triangle soup; the reader welds it on exact coordinates. */
#include "mesh/io_formats.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "mesh/weld.h"

static uint32_t rd_u32le(const unsigned char *p) {
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static float rd_f32le(const unsigned char *p) {
    uint32_t u = rd_u32le(p);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

int acd_stl_is_binary(const unsigned char *buf, size_t len) {
    if (len < 84) return 0;
    uint64_t n = rd_u32le(buf + 80);
    return (uint64_t)len == 84 + 50 * n;
}

static int is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

static int keyword_ci(const char *p, const char *kw) {
    size_t n = strlen(kw);
    for (size_t i = 0; i < n; i++) {
        char c = p[i];
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != kw[i]) return 0;
    }
    return p[n] == '\0' || is_space(p[n]);
}

int acd_stl_is_ascii(const char *buf, size_t len) {
    /* "solid" and text bytes only in the first KiB (a binary header may also say "solid") */
    for (size_t i = 0; i < len && i < 1024; i++) {
        unsigned char c = (unsigned char)buf[i];
        if (c >= 0x80 || (c < 0x20 && !is_space((char)c))) return 0;
    }
    acd_text t = {buf, buf + len, 1, NULL};
    acd_text_skip_space(&t, 0);
    return keyword_ci(t.p, "solid");
}

/* Welds the soup in b (3 vertices per triangle, triangles already 0,1,2,3,...). */
static acd_status weld_soup(acd_mesh_builder *b, const char *name, acd_error *err) {
    if (!b->nv) return ACD_OK;
    uint32_t *remap = malloc(b->nv * sizeof *remap);
    size_t u;
    if (!remap || !acd_weld_exact(b->v, b->nv, remap, &u)) {
        free(remap);
        return acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory welding %zu STL vertices", name, b->nv);
    }
    for (size_t i = 0; i < 3 * b->nt; i++) b->t[i] = remap[b->t[i]];
    acd_weld_compact(b->v, b->nv, remap);
    b->nv = u;
    free(remap);
    return ACD_OK;
}

static acd_status read_binary(const unsigned char *buf, size_t len, const char *name, acd_mesh_builder *b,
                              acd_error *err) {
    if (len < 84)
        return acd_fail(err, ACD_ERR_PARSE, "%s: binary STL shorter than its 84-byte header (%zu bytes)", name, len);
    uint64_t n = rd_u32le(buf + 80);
    if ((uint64_t)len < 84 + 50 * n)
        return acd_fail(err, ACD_ERR_PARSE,
                        "%s: binary STL truncated: header says %llu triangles (%llu bytes), file has %zu bytes (triangle "
                        "%llu cut at byte offset %zu)",
                        name, (unsigned long long)n, (unsigned long long)(84 + 50 * n), len,
                        (unsigned long long)((len - 84) / 50), 84 + (len - 84) / 50 * 50);
    /* more whole triangles than the count: a count left unpatched (0 by streaming writers) or
     * lowered; reading only the first n would silently drop the rest */
    if ((uint64_t)len - (84 + 50 * n) >= 50)
        return acd_fail(err, ACD_ERR_PARSE,
                        "%s: binary STL: header says %llu triangles (%llu bytes) but the file has %zu bytes, room for "
                        "%llu triangles: the count at byte offset 80 is wrong or other data follows the triangles",
                        name, (unsigned long long)n, (unsigned long long)(84 + 50 * n), len,
                        (unsigned long long)((len - 84) / 50));
    if (b->nv + 3 * n > UINT32_MAX) return acd_fail(err, ACD_ERR_UNSUPPORTED, "%s: more than 2^32-1 vertices", name);
    if (!acd_grow((void **)&b->v, &b->vcap, b->nv + 3 * n, 3 * sizeof(double)) ||
        !acd_grow((void **)&b->t, &b->tcap, b->nt + n, 3 * sizeof(uint32_t)))
        return acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory for %llu triangles", name, (unsigned long long)n);
    for (uint64_t i = 0; i < n; i++) {
        const unsigned char *r = buf + 84 + 50 * i + 12;
        for (int k = 0; k < 9; k++) {
            float f = rd_f32le(r + 4 * k);
            if (!isfinite(f))
                return acd_fail(err, ACD_ERR_PARSE, "%s: byte offset %llu: triangle %llu, vertex %d: coordinate is not finite",
                                name, (unsigned long long)(84 + 50 * i + 12 + 4 * (uint64_t)k), (unsigned long long)i,
                                k / 3);
            b->v[3 * b->nv + (size_t)k] = (double)f;
        }
        uint32_t *t = b->t + 3 * b->nt;
        t[0] = (uint32_t)b->nv;
        t[1] = (uint32_t)b->nv + 1;
        t[2] = (uint32_t)b->nv + 2;
        b->nv += 3;
        b->nt++;
    }
    return ACD_OK;
}

/* Next whitespace-separated token of t (skipping space), or "" at the end. */
static const char *token(acd_text *t) {
    acd_text_skip_space(t, 0);
    return t->p;
}

static void skip_token(acd_text *t) {
    while (*t->p && !is_space(*t->p)) t->p++;
}

static acd_status expect(acd_text *t, const char *kw, acd_error *err) {
    const char *p = token(t);
    if (!keyword_ci(p, kw))
        return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: expected '%s', found '%.16s'", t->name, t->line, kw, p);
    t->p += strlen(kw);
    return ACD_OK;
}

static acd_status read_ascii(const char *buf, size_t len, const char *name, acd_mesh_builder *b, acd_error *err) {
    acd_text t = {buf, buf + len, 1, name};
    acd_status s;
    int solids = 0;
    for (;;) {
        const char *p = token(&t);
        if (!*p && t.p >= t.end) break;
        if (!keyword_ci(p, "solid")) {
            /* facets after an endsolid would be dropped without a word: refused */
            if (solids && keyword_ci(p, "facet"))
                return acd_fail(err, ACD_ERR_PARSE,
                                "%s:%zu: 'facet' after 'endsolid' (facets must come between 'solid' and 'endsolid')",
                                name, t.line);
            if (solids) break; /* other trailing junk after endsolid: tolerated (some exporters pad) */
            return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: expected 'solid', found '%.16s'", name, t.line, p);
        }
        solids++;
        acd_text_next_line(&t); /* the solid's name */
        for (;;) {
            p = token(&t);
            if (keyword_ci(p, "endsolid")) {
                acd_text_next_line(&t);
                break;
            }
            if (!*p && t.p < t.end)
                return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: NUL byte inside a solid (binary data in an ASCII STL?)",
                                name, t.line);
            if (!*p) return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: end of file inside a solid (no 'endsolid')", name, t.line);
            if ((s = expect(&t, "facet", err)) != ACD_OK) return s;
            acd_text_next_line(&t); /* the normal is recomputed from the vertices */
            if ((s = expect(&t, "outer", err)) != ACD_OK) return s;
            if ((s = expect(&t, "loop", err)) != ACD_OK) return s;
            b->npoly = 0;
            for (;;) {
                p = token(&t);
                if (keyword_ci(p, "endloop")) {
                    skip_token(&t);
                    break;
                }
                if (!keyword_ci(p, "vertex"))
                    return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: expected 'vertex' or 'endloop', found '%.16s'", name,
                                    t.line, p);
                t.p += 6;
                double x[3];
                for (int k = 0; k < 3; k++) {
                    acd_text_skip_blank(&t);
                    const char *q = acd_parse_double(t.p, &x[k]);
                    if (!q || (*q && !is_space(*q)))
                        return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: vertex coordinate %d is missing or malformed ('%.12s')",
                                        name, t.line, k + 1, t.p);
                    if (!isfinite(x[k]))
                        return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: vertex coordinate %d is not finite", name, t.line, k + 1);
                    t.p = q;
                }
                if (!acd_builder_vertex(b, x[0], x[1], x[2]) || !acd_builder_poly_push(b, (uint32_t)(b->nv - 1)))
                    return acd_fail(err, ACD_ERR_NOMEM, "%s:%zu: out of memory (or more than 2^32-1 vertices)", name,
                                    t.line);
            }
            if (b->npoly < 3)
                return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: facet with %zu vertices (at least 3 needed)", name, t.line,
                                b->npoly);
            if ((s = acd_builder_fan_or_fail(b, name, t.line, err)) != ACD_OK) return s;
            if ((s = expect(&t, "endfacet", err)) != ACD_OK) return s;
        }
    }
    return ACD_OK;
}

acd_status acd_stl_read(const char *buf, size_t len, const char *name, acd_mesh_builder *b, acd_error *err) {
    acd_status s;
    size_t v0 = b->nv;
    if (v0 != 0) return acd_fail(err, ACD_ERR_INTERNAL, "%s: STL reader needs an empty builder", name);
    if (acd_stl_is_binary((const unsigned char *)buf, len) || !acd_stl_is_ascii(buf, len))
        s = read_binary((const unsigned char *)buf, len, name, b, err);
    else
        s = read_ascii(buf, len, name, b, err);
    if (s != ACD_OK) return s;
    return weld_soup(b, name, err);
}

static void wr_f32le(acd_obuf *o, float f) {
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    unsigned char b[4] = {(unsigned char)u, (unsigned char)(u >> 8), (unsigned char)(u >> 16), (unsigned char)(u >> 24)};
    acd_obuf_write(o, b, 4);
}

static void normal_of(const double *a, const double *b, const double *c, float nf[3]) {
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++) nf[k] = l > 0 && isfinite(l) ? (float)(n[k] / l) : 0.0f;
}

void acd_stl_write(acd_obuf *o, const acd_mesh *m, int ascii) {
    if (ascii) {
        acd_obuf_printf(o, "solid acd\n");
        for (size_t i = 0; i < m->ntriangles; i++) {
            const uint32_t *t = m->triangles + 3 * i;
            float n[3];
            normal_of(m->vertices + 3 * t[0], m->vertices + 3 * t[1], m->vertices + 3 * t[2], n);
            acd_obuf_printf(o, "  facet normal %.9g %.9g %.9g\n    outer loop\n", n[0], n[1], n[2]);
            for (int k = 0; k < 3; k++) {
                const double *v = m->vertices + 3 * t[k];
                acd_obuf_printf(o, "      vertex %.17g %.17g %.17g\n", v[0], v[1], v[2]);
            }
            acd_obuf_printf(o, "    endloop\n  endfacet\n");
        }
        acd_obuf_printf(o, "endsolid acd\n");
        return;
    }
    char header[80];
    memset(header, 0, sizeof header);
    snprintf(header, sizeof header, "binary STL written by acd %s", ACD_VERSION_STRING);
    acd_obuf_write(o, header, 80);
    uint32_t n = m->ntriangles > UINT32_MAX ? UINT32_MAX : (uint32_t)m->ntriangles;
    unsigned char nb[4] = {(unsigned char)n, (unsigned char)(n >> 8), (unsigned char)(n >> 16), (unsigned char)(n >> 24)};
    acd_obuf_write(o, nb, 4);
    for (size_t i = 0; i < n; i++) {
        const uint32_t *t = m->triangles + 3 * i;
        float nf[3];
        normal_of(m->vertices + 3 * t[0], m->vertices + 3 * t[1], m->vertices + 3 * t[2], nf);
        for (int k = 0; k < 3; k++) wr_f32le(o, nf[k]);
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < 3; k++) wr_f32le(o, (float)m->vertices[3 * t[c] + (size_t)k]);
        acd_obuf_write(o, "\0\0", 2);
    }
}
