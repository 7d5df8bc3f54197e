/* mesh/io_off: Geomview OFF reader and writer.
 *
 * Reads OFF with the optional ST, C and N prefixes (texture coordinates, colours and normals
 * after a vertex's coordinates are skipped, as is a face's colour after its indices), '#'
 * comments anywhere, and the counts on the header line or the next. A face of n >= 3 vertices
 * is fanned. A vertex's coordinates and a face's indices must be on one line (what makes the
 * trailing colours skippable), blank and comment lines may come between. 4OFF/nOFF (other dimensions) and binary OFF are refused as unsupported. */
#include "mesh/io_formats.h"

#include <math.h>
#include <string.h>

#include "core/error.h"

static int is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

/* Length of the header keyword at p if it is [ST][C][N][4][n]OFF, else 0. */
static size_t header_len(const char *p, int *dim_other) {
    size_t n = 0;
    *dim_other = 0;
    if (p[n] == 'S' && p[n + 1] == 'T') n += 2;
    if (p[n] == 'C') n++;
    if (p[n] == 'N') n++;
    if (p[n] == '4') {
        *dim_other = 1;
        n++;
    }
    if (p[n] == 'n') {
        *dim_other = 1;
        n++;
    }
    if (strncmp(p + n, "OFF", 3) != 0) return 0;
    n += 3;
    if (p[n] && !is_space(p[n]) && p[n] != '#') return 0;
    return n;
}

int acd_off_sniff(const char *buf, size_t len) {
    acd_text t = {buf, buf + len, 1, NULL};
    acd_text_skip_space(&t, 1);
    int other;
    return header_len(t.p, &other) > 0;
}

static acd_status read_count(acd_text *t, const char *what, int64_t *out, acd_error *err) {
    acd_text_skip_space(t, 1);
    const char *q = acd_parse_int64(t->p, out);
    if (!q || (*q && !is_space(*q) && *q != '#') || *out < 0)
        return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: expected the number of %s, found '%.12s'", t->name, t->line, what,
                        t->p);
    t->p = q;
    return ACD_OK;
}

acd_status acd_off_read(const char *buf, size_t len, const char *name, acd_mesh_builder *b, acd_error *err) {
    acd_text t = {buf, buf + len, 1, name};
    acd_text_skip_space(&t, 1);
    int other;
    size_t hl = header_len(t.p, &other);
    if (!hl) return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: expected the OFF header keyword", name, t.line);
    if (other)
        return acd_fail(err, ACD_ERR_UNSUPPORTED, "%s:%zu: '%.*s' (not 3-dimensional) is not supported", name, t.line,
                        (int)hl, t.p);
    t.p += hl;
    acd_text_skip_blank(&t);
    if (!strncmp(t.p, "BINARY", 6))
        return acd_fail(err, ACD_ERR_UNSUPPORTED, "%s:%zu: binary OFF is not supported", name, t.line);
    int64_t nv, nf, ne = 0;
    acd_status s;
    if ((s = read_count(&t, "vertices", &nv, err)) != ACD_OK) return s;
    if ((s = read_count(&t, "faces", &nf, err)) != ACD_OK) return s;
    if (!acd_text_at_eol(&t, 1) && (s = read_count(&t, "edges", &ne, err)) != ACD_OK) return s;
    /* each vertex takes at least 6 bytes ("0 0 0\n"), each face 8: refuse counts the file cannot hold */
    if ((uint64_t)nv > len / 6 + 1 || (uint64_t)nf > len / 8 + 1 || nv > (int64_t)UINT32_MAX)
        return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: counts (%lld vertices, %lld faces) exceed what the file can hold",
                        name, t.line, (long long)nv, (long long)nf);
    acd_text_next_line(&t);
    size_t v0 = b->nv;
    for (int64_t i = 0; i < nv; i++) {
        double x[3];
        for (int k = 0; k < 3; k++) {
            /* blank and comment lines may come before a vertex; its coordinates share one line */
            if (k == 0) acd_text_skip_space(&t, 1);
            else acd_text_skip_blank(&t);
            const char *q = acd_parse_double(t.p, &x[k]);
            if (!q || (*q && !is_space(*q) && *q != '#'))
                return acd_fail(err, ACD_ERR_PARSE,
                                "%s:%zu: vertex %lld: coordinate %d is missing or malformed ('%.12s'; a vertex's "
                                "coordinates must be on one line)",
                                name, t.line, (long long)i, k + 1, t.p);
            if (!isfinite(x[k]))
                return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: vertex %lld: coordinate %d is not finite", name, t.line,
                                (long long)i, k + 1);
            t.p = q;
        }
        if (!acd_builder_vertex(b, x[0], x[1], x[2]))
            return acd_fail(err, ACD_ERR_NOMEM, "%s:%zu: out of memory", name, t.line);
        acd_text_next_line(&t);
    }
    for (int64_t f = 0; f < nf; f++) {
        int64_t n;
        acd_text_skip_space(&t, 1);
        const char *q = acd_parse_int64(t.p, &n);
        if (!q || (*q && !is_space(*q) && *q != '#'))
            return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: face %lld: expected its number of vertices, found '%.12s'", name,
                            t.line, (long long)f, t.p);
        if (n < 3)
            return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: face %lld has %lld vertices (at least 3 needed)", name, t.line,
                            (long long)f, (long long)n);
        if (n > (int64_t)(len - (size_t)(t.p - buf)))
            return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: face %lld claims %lld vertices, more than the file can hold",
                            name, t.line, (long long)f, (long long)n);
        t.p = q;
        b->npoly = 0;
        for (int64_t k = 0; k < n; k++) {
            int64_t idx;
            acd_text_skip_blank(&t); /* a face's indices share its line */
            q = acd_parse_int64(t.p, &idx);
            if (!q || (*q && !is_space(*q) && *q != '#'))
                return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: face %lld: vertex index %lld is missing or malformed", name,
                                t.line, (long long)f, (long long)k);
            if (idx < 0 || idx >= nv)
                return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: face %lld: vertex index %lld out of range (0..%lld)", name,
                                t.line, (long long)f, (long long)idx, (long long)nv - 1);
            if (!acd_builder_poly_push(b, (uint32_t)(v0 + (size_t)idx)))
                return acd_fail(err, ACD_ERR_NOMEM, "%s:%zu: out of memory", name, t.line);
            t.p = q;
        }
        if ((s = acd_builder_fan_or_fail(b, name, t.line, err)) != ACD_OK) return s;
        acd_text_next_line(&t); /* a face colour may follow */
    }
    return ACD_OK;
}

void acd_off_write(acd_obuf *o, const acd_mesh *m) {
    acd_obuf_printf(o, "OFF\n%zu %zu 0\n", m->nvertices, m->ntriangles);
    for (size_t i = 0; i < m->nvertices; i++) {
        const double *v = m->vertices + 3 * i;
        acd_obuf_double(o, v[0]);
        acd_obuf_write(o, " ", 1);
        acd_obuf_double(o, v[1]);
        acd_obuf_write(o, " ", 1);
        acd_obuf_double(o, v[2]);
        acd_obuf_write(o, "\n", 1);
    }
    for (size_t i = 0; i < m->ntriangles; i++) {
        const uint32_t *t = m->triangles + 3 * i;
        acd_obuf_write(o, "3", 1);
        for (int k = 0; k < 3; k++) {
            acd_obuf_write(o, " ", 1);
            acd_obuf_u64(o, t[k]);
        }
        acd_obuf_write(o, "\n", 1);
    }
}
