/* mesh/io_obj: Wavefront OBJ reader and writer.
 *
 * Reads v (extra w or colour values ignored), f (v, v/vt, v//vn, v/vt/vn; negative indices
 * relative to the vertices read so far; polygons fanned from their first vertex), o and g
 * (group starts, kept for acd_mesh_read_parts). Every other statement of the format (Wavefront's
 * "Object Files (.obj)", Advanced Visualizer 3.0 manual, appendix B1, and the statements it
 * supersedes) is skipped, with its '\' continuation lines: silently when it carries no geometry
 * of the surface (texture and normal data, smoothing groups, materials, display attributes, the
 * body statements of free-form elements), told to the builder's warning channel when it is
 * geometry this reader does not read (points, lines, free-form curves and surfaces, calls of
 * other files), so that the caller knows the mesh may be incomplete. A statement that is not an
 * OBJ keyword is an error with its line. Positive indices may refer to vertices defined later in
 * the file (checked at the end). Writes %.17g coordinates, which round-trip exactly. */
#include "mesh/io_formats.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"

/* The OBJ statements other than v, f, o and g. what: NULL for those skipped silently; for those
 * reported, what the skipped statements are (plural, the warning's words). */
typedef struct obj_keyword {
    const char *kw, *what;
} obj_keyword;

static const obj_keyword obj_keywords[] = {
    /* vertex data: texture, normal and parameter-space vertices, free-form curve/surface types */
    {"vt", NULL}, {"vn", NULL}, {"vp", NULL}, {"cstype", NULL}, {"deg", NULL}, {"bmat", NULL}, {"step", NULL},
    /* elements other than faces: geometry this reader does not read */
    {"p", "point elements"}, {"l", "line elements"}, {"curv", "free-form curves"},
    {"curv2", "free-form curves on surfaces"}, {"surf", "free-form surfaces"},
    /* body statements of free-form elements (the element itself is reported), connectivity */
    {"parm", NULL}, {"trim", NULL}, {"hole", NULL}, {"scrv", NULL}, {"sp", NULL}, {"end", NULL}, {"con", NULL},
    /* grouping, display and rendering attributes */
    {"s", NULL}, {"mg", NULL}, {"usemtl", NULL}, {"mtllib", NULL}, {"usemap", NULL}, {"maplib", NULL},
    {"bevel", NULL}, {"c_interp", NULL}, {"d_interp", NULL}, {"lod", NULL}, {"shadow_obj", NULL},
    {"trace_obj", NULL}, {"ctech", NULL}, {"stech", NULL},
    /* superseded by curv/surf (older versions of the format): patches and curves; their resolution */
    {"bsp", "B-spline patches"}, {"bzp", "Bezier patches"}, {"cdc", "Cardinal curves"}, {"cdp", "Cardinal patches"},
    {"res", NULL},
    /* general statements: another file's geometry, a shell command */
    {"call", "calls of other OBJ files, not read"}, {"csh", "shell commands, not run"},
    /* extension (OpenSubdiv, tinyobjloader): subdivision tags such as creases */
    {"t", NULL},
};
#define OBJ_NKEYWORDS (sizeof obj_keywords / sizeof obj_keywords[0])

/* Index of the keyword kw[0..n) in obj_keywords, or -1. */
static int obj_keyword_find(const char *kw, size_t n) {
    for (size_t k = 0; k < OBJ_NKEYWORDS; k++)
        if (strlen(obj_keywords[k].kw) == n && !memcmp(obj_keywords[k].kw, kw, n)) return (int)k;
    return -1;
}

static int is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
static int is_eol(char c) { return c == '\n' || c == '\0' || c == '#'; }
static int is_alpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }

/* Moves past the statement at t->p and its continuation lines (a line whose last character before
 * a comment or the newline, blanks aside, is a backslash continues on the next line). */
static void obj_skip_statement(acd_text *t) {
    for (;;) {
        const char *p = t->p, *c = NULL;
        while (*p != '\n' && *p != '\0') {
            if (*p == '#' && !c) c = p;
            p++;
        }
        const char *e = c ? c : p;
        while (e > t->p && is_blank(e[-1])) e--;
        int more = e > t->p && e[-1] == '\\' && *p == '\n';
        acd_text_next_line(t);
        if (!more || t->p >= t->end) return;
    }
}

int acd_obj_sniff(const char *buf, size_t len) {
    /* the first statement line begins with a known OBJ keyword */
    acd_text t = {buf, buf + len, 1, NULL};
    for (int lines = 0; lines < 200 && t.p < t.end; lines++) {
        acd_text_skip_blank(&t);
        const char *p = t.p;
        if (*p == '#' || *p == '\n') {
            acd_text_next_line(&t);
            continue;
        }
        static const char *const kw[] = {"v", "vt", "vn", "vp", "f", "o", "g", "s", "l", "p", "usemtl", "mtllib"};
        for (size_t k = 0; k < sizeof kw / sizeof kw[0]; k++) {
            size_t n = strlen(kw[k]);
            if (!strncmp(p, kw[k], n) && (is_blank(p[n]) || p[n] == '\n' || p[n] == '\0')) return 1;
        }
        return 0;
    }
    return 0;
}

acd_status acd_obj_read(const char *buf, size_t len, const char *name, acd_mesh_builder *b, acd_error *err) {
    acd_text t = {buf, buf + len, 1, name};
    int64_t max_index = 0;
    size_t max_line = 0;
    const size_t v0 = b->nv;
    size_t skipped[OBJ_NKEYWORDS] = {0}, first_line[OBJ_NKEYWORDS] = {0}; /* reported statements */
    while (t.p < t.end) {
        acd_text_skip_blank(&t);
        const char *p = t.p;
        char c = p[0];
        if (c == '\n' || c == '#' || c == '\0') {
            if (c == '\0' && p < t.end)
                return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: NUL byte in an OBJ file (binary data?)", name, t.line);
            acd_text_next_line(&t);
            continue;
        }
        size_t kwlen = 0; /* the statement's keyword: up to a blank, a comment or the end of the line */
        while (!is_blank(p[kwlen]) && !is_eol(p[kwlen])) kwlen++;
        if (c == 'v' && kwlen == 1) {
            double x[3];
            p += 1;
            for (int k = 0; k < 3; k++) {
                const char *q = acd_parse_double(p, &x[k]);
                if (!q || !(is_blank(*q) || *q == '\n' || *q == '\0' || *q == '#'))
                    return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: vertex needs 3 numbers (coordinate %d is missing or malformed)",
                                    name, t.line, k + 1);
                if (!isfinite(x[k]))
                    return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: vertex coordinate %d is not finite", name, t.line, k + 1);
                p = q;
            }
            if (!acd_builder_vertex(b, x[0], x[1], x[2]))
                return acd_fail(err, ACD_ERR_NOMEM, "%s:%zu: out of memory (or more than 2^32-1 vertices)", name, t.line);
            t.p = p;
            acd_text_next_line(&t);
            continue;
        }
        if (c == 'f' && kwlen == 1) {
            p += 1;
            b->npoly = 0;
            for (;;) {
                while (is_blank(*p)) p++;
                if (is_eol(*p)) break;
                if (*p == '\\' && (p[1] == '\n' || (p[1] == '\r' && p[2] == '\n'))) {
                    /* line continuation */
                    p += p[1] == '\n' ? 2 : 3;
                    t.line++;
                    continue;
                }
                int64_t idx;
                const char *q = acd_parse_int64(p, &idx);
                if (!q)
                    return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: face corner %zu: expected a vertex index, found '%.12s'",
                                    name, t.line, b->npoly + 1, p);
                /* skip /vt, /vt/vn, //vn */
                for (int k = 0; k < 2 && *q == '/'; k++) {
                    q++;
                    int64_t dummy;
                    const char *r = acd_parse_int64(q, &dummy);
                    if (r) q = r;
                }
                if (!(is_blank(*q) || is_eol(*q) || *q == '\\'))
                    return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: face corner %zu: malformed index '%.12s'", name, t.line,
                                    b->npoly + 1, p);
                int64_t nv = (int64_t)(b->nv - v0);
                int64_t r;
                if (idx > 0) {
                    r = idx - 1;
                    if (idx > max_index) {
                        max_index = idx;
                        max_line = t.line;
                    }
                } else if (idx < 0) {
                    if (-idx > nv)
                        return acd_fail(err, ACD_ERR_PARSE,
                                        "%s:%zu: relative vertex index %lld refers before the first vertex (%lld read so far)",
                                        name, t.line, (long long)idx, (long long)nv);
                    r = nv + idx;
                } else {
                    return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: vertex index 0 (OBJ indices start at 1)", name, t.line);
                }
                if (r >= (int64_t)UINT32_MAX)
                    return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: vertex index %lld too large", name, t.line, (long long)idx);
                if (!acd_builder_poly_push(b, (uint32_t)(r + (int64_t)v0)))
                    return acd_fail(err, ACD_ERR_NOMEM, "%s:%zu: out of memory", name, t.line);
                p = q;
            }
            if (b->npoly < 3)
                return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: face with %zu vertices (at least 3 needed)", name, t.line,
                                b->npoly);
            acd_status fs = acd_builder_fan_or_fail(b, name, t.line, err);
            if (fs != ACD_OK) return fs;
            t.p = p;
            acd_text_next_line(&t);
            continue;
        }
        if ((c == 'o' || c == 'g') && kwlen == 1) {
            p += 1;
            while (is_blank(*p)) p++;
            const char *e = p;
            while (*e != '\n' && *e != '\0') e++;
            while (e > p && is_blank(e[-1])) e--;
            if (!acd_builder_group(b, p, (size_t)(e - p)))
                return acd_fail(err, ACD_ERR_NOMEM, "%s:%zu: out of memory", name, t.line);
            acd_text_next_line(&t);
            continue;
        }
        int k = obj_keyword_find(p, kwlen);
        if (k >= 0) {
            if (obj_keywords[k].what && !skipped[k]++) first_line[k] = t.line;
            obj_skip_statement(&t);
            continue;
        }
        if (is_alpha(c)) {
            char kw[25]; /* printable ASCII only in the message */
            size_t n = 0;
            for (; n < kwlen && n + 1 < sizeof kw; n++) kw[n] = p[n] > ' ' && p[n] < 127 ? p[n] : '?';
            kw[n] = '\0';
            return acd_fail(err, ACD_ERR_PARSE,
                            "%s:%zu: unknown statement '%s%s' (not an OBJ keyword; docs/mesh.md lists those read and "
                            "those skipped)",
                            name, t.line, kw, n < kwlen ? "..." : "");
        }
        return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: unexpected text '%.16s' (not an OBJ statement)", name, t.line, p);
    }
    if (max_index > (int64_t)(b->nv - v0))
        return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: vertex index %lld out of range (the file has %zu vertices)", name,
                        max_line, (long long)max_index, b->nv - v0);
    /* the skipped geometry, one warning per keyword, in the order of their first lines */
    for (size_t done = 0; b->warn;) {
        int next = -1;
        for (size_t k = 0; k < OBJ_NKEYWORDS; k++)
            if (skipped[k] && first_line[k] > done && (next < 0 || first_line[k] < first_line[next])) next = (int)k;
        if (next < 0) break;
        char msg[ACD_ERROR_MESSAGE_SIZE];
        snprintf(msg, sizeof msg,
                 "%s:%zu: %zu '%s' statement%s skipped (%s; the first on this line): only faces (f) are read as "
                 "geometry, so the mesh may be incomplete",
                 name, first_line[next], skipped[next], obj_keywords[next].kw, skipped[next] == 1 ? "" : "s",
                 obj_keywords[next].what);
        b->warn(b->warn_user, msg);
        done = first_line[next];
    }
    return ACD_OK;
}

static void write_vertices(acd_obuf *o, const acd_mesh *m) {
    for (size_t i = 0; i < m->nvertices; i++) {
        const double *v = m->vertices + 3 * i;
        acd_obuf_write(o, "v ", 2);
        acd_obuf_double(o, v[0]);
        acd_obuf_write(o, " ", 1);
        acd_obuf_double(o, v[1]);
        acd_obuf_write(o, " ", 1);
        acd_obuf_double(o, v[2]);
        acd_obuf_write(o, "\n", 1);
    }
}

static void write_faces(acd_obuf *o, const acd_mesh *m, uint64_t base) {
    for (size_t i = 0; i < m->ntriangles; i++) {
        const uint32_t *t = m->triangles + 3 * i;
        acd_obuf_write(o, "f", 1);
        for (int k = 0; k < 3; k++) {
            acd_obuf_write(o, " ", 1);
            acd_obuf_u64(o, base + t[k] + 1);
        }
        acd_obuf_write(o, "\n", 1);
    }
}

void acd_obj_write(acd_obuf *o, const acd_mesh *m) {
    acd_obuf_printf(o, "# acd %s: %zu vertices, %zu triangles\n", ACD_VERSION_STRING, m->nvertices, m->ntriangles);
    write_vertices(o, m);
    write_faces(o, m, 0);
}

void acd_obj_write_parts(acd_obuf *o, const acd_mesh_parts *p) {
    acd_obuf_printf(o, "# acd %s: %zu parts\n", ACD_VERSION_STRING, p->count);
    uint64_t base = 0;
    for (size_t i = 0; i < p->count; i++) {
        const char *nm = p->parts[i].name;
        acd_obuf_write(o, "o ", 2);
        if (!nm || !nm[0]) nm = "part";
        for (const char *c = nm; *c; c++) /* one line: control characters become '_' */
            acd_obuf_write(o, (unsigned char)*c < 0x20 ? "_" : c, 1);
        acd_obuf_write(o, "\n", 1);
        write_vertices(o, &p->parts[i].mesh);
        write_faces(o, &p->parts[i].mesh, base);
        base += p->parts[i].mesh.nvertices;
    }
}
