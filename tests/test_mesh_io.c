/* Tests of the mesh readers and writers: exact round trips in every format (17 significant
 * digits), gzip, OBJ groups as parts, and a clear error (with line or byte offset) for every
 * malformed-file case. */
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

#include "acd/mesh.h"
#include "core/rng.h"

/* An octahedron with awkward coordinates (not short decimals) so that only 17 digits round-trip. */
static void make_octa(acd_mesh *m, uint64_t seed) {
    static const uint32_t tri[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                       {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    static const double dir[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    acd_rng r;
    acd_rng_seed(&r, seed);
    m->nvertices = 6;
    m->ntriangles = 8;
    m->vertices = malloc(18 * sizeof(double));
    m->triangles = malloc(24 * sizeof(uint32_t));
    assert_non_null(m->vertices);
    assert_non_null(m->triangles);
    for (int i = 0; i < 6; i++)
        for (int k = 0; k < 3; k++)
            m->vertices[3 * i + k] = dir[i][k] * (1.0 + acd_rng_uniform(&r) / 3.0) + acd_rng_uniform(&r) * 1e-7;
    memcpy(m->triangles, tri, sizeof tri);
}

/* Same mesh; with float_precision 1 (binary STL) or 2 (ASCII STL) (STL: a soup welded on read, so the vertex order follows the
 * triangles) the triangles' corners must have the float-rounded coordinates of the original. */
static void assert_same_mesh(const acd_mesh *a, const acd_mesh *b, int float_precision) {
    assert_int_equal(a->nvertices, b->nvertices);
    assert_int_equal(a->ntriangles, b->ntriangles);
    if (float_precision) {
        /* 1: rounded to float */
        for (size_t t = 0; t < a->ntriangles; t++)
            for (int c = 0; c < 3; c++)
                for (int k = 0; k < 3; k++) {
                    double expect = a->vertices[3 * a->triangles[3 * t + c] + k];
                    if (float_precision == 1) expect = (double)(float)expect;
                    double got = b->vertices[3 * b->triangles[3 * t + c] + k];
                    if (expect != got) fail_msg("triangle %zu corner %d: %.17g != %.17g", t, c, expect, got);
                }
        return;
    }
    for (size_t i = 0; i < 3 * a->nvertices; i++) {
        double expect = float_precision ? (double)(float)a->vertices[i] : a->vertices[i];
        if (expect != b->vertices[i]) fail_msg("coordinate %zu: %.17g != %.17g", i, expect, b->vertices[i]);
    }
    assert_memory_equal(a->triangles, b->triangles, 3 * a->ntriangles * sizeof(uint32_t));
}

static void roundtrip(acd_mesh_format fmt, int float_precision) {
    acd_mesh m, back;
    make_octa(&m, 7 + (uint64_t)fmt);
    void *data = NULL;
    size_t size = 0;
    acd_error err;
    assert_int_equal(acd_mesh_write_memory(&m, fmt, &data, &size, &err), ACD_OK);
    /* read back with no hint: the format must be recognised from the content */
    acd_status s = acd_mesh_read_memory(data, size, ACD_MESH_FORMAT_AUTO, "rt", &back, &err);
    if (s != ACD_OK) fail_msg("%s: %s", acd_mesh_format_name(fmt), err.message);
    assert_same_mesh(&m, &back, float_precision);
    free(data);
    acd_mesh_free(&back);
    acd_mesh_free(&m);
}

static void test_roundtrip_obj(void **state) { (void)state; roundtrip(ACD_MESH_FORMAT_OBJ, 0); }
static void test_roundtrip_off(void **state) { (void)state; roundtrip(ACD_MESH_FORMAT_OFF, 0); }
static void test_roundtrip_stl(void **state) { (void)state; roundtrip(ACD_MESH_FORMAT_STL, 1); }
static void test_roundtrip_stl_ascii(void **state) { (void)state; roundtrip(ACD_MESH_FORMAT_STL_ASCII, 2); }

static acd_status read_str(const char *text, acd_mesh_format hint, acd_mesh *m, acd_error *err) {
    return acd_mesh_read_memory(text, strlen(text), hint, "t", m, err);
}

static void test_roundtrip_ply(void **state) { (void)state; roundtrip(ACD_MESH_FORMAT_PLY, 0); }
static void test_roundtrip_ply_ascii(void **state) { (void)state; roundtrip(ACD_MESH_FORMAT_PLY_ASCII, 0); }

/* Appends v as n bytes in the given byte order. */
static size_t put(unsigned char *b, size_t at, uint64_t v, int n, int big) {
    for (int i = 0; i < n; i++) b[at + (size_t)i] = (unsigned char)(v >> (8 * (big ? n - 1 - i : i)));
    return at + (size_t)n;
}

static uint64_t f32bits(float f) {
    uint32_t u;
    memcpy(&u, &f, 4);
    return u;
}

/* A binary PLY in either byte order with extra properties, an extra element, a quad face and a
 * face property after the list; returns its size. */
static size_t make_binary_ply(unsigned char *b, int big) {
    int n = sprintf((char *)b,
                    "ply\nformat %s 1.0\ncomment test\nelement vertex 4\nproperty float x\nproperty uchar red\n"
                    "property float y\nproperty float z\nproperty double nx\nelement edge 1\nproperty list uchar int ids\n"
                    "element face 2\nproperty list uchar int vertex_indices\nproperty ushort flags\nend_header\n",
                    big ? "binary_big_endian" : "binary_little_endian");
    size_t at = (size_t)n;
    static const float xyz[4][3] = {{0, 0, 0}, {1.5f, 0, 0}, {1.5f, 1, 0}, {0, 1, -0.25f}};
    for (int i = 0; i < 4; i++) {
        at = put(b, at, f32bits(xyz[i][0]), 4, big);
        at = put(b, at, 200, 1, big);
        at = put(b, at, f32bits(xyz[i][1]), 4, big);
        at = put(b, at, f32bits(xyz[i][2]), 4, big);
        at = put(b, at, 0x3ff0000000000000ull, 8, big);
    }
    at = put(b, at, 2, 1, big); /* edge 0 1 */
    at = put(b, at, 0, 4, big);
    at = put(b, at, 1, 4, big);
    at = put(b, at, 4, 1, big); /* quad */
    for (int i = 0; i < 4; i++) at = put(b, at, (uint64_t)i, 4, big);
    at = put(b, at, 7, 2, big);
    at = put(b, at, 3, 1, big); /* triangle 0 2 1 */
    at = put(b, at, 0, 4, big);
    at = put(b, at, 2, 4, big);
    at = put(b, at, 1, 4, big);
    at = put(b, at, 7, 2, big);
    return at;
}

static void test_ply_binary_both_endians(void **state) {
    (void)state;
    for (int big = 0; big < 2; big++) {
        unsigned char b[2048];
        size_t n = make_binary_ply(b, big);
        acd_mesh m;
        acd_error err;
        acd_status s = acd_mesh_read_memory(b, n, ACD_MESH_FORMAT_AUTO, "be", &m, &err);
        if (s != ACD_OK) fail_msg("%s", err.message);
        assert_int_equal(m.nvertices, 4);
        assert_int_equal(m.ntriangles, 3);
        assert_true(m.vertices[3] == 1.5 && m.vertices[7] == 1.0 && m.vertices[11] == -0.25);
        const uint32_t expect[9] = {0, 1, 2, 0, 2, 3, 0, 2, 1};
        assert_memory_equal(m.triangles, expect, sizeof expect);
        acd_mesh_free(&m);
        /* every truncation is an error naming a byte offset (or the header) */
        for (size_t cut = 4; cut < n; cut += 3) {
            s = acd_mesh_read_memory(b, cut, ACD_MESH_FORMAT_AUTO, "cut", &m, &err);
            if (s == ACD_OK) fail_msg("cut at %zu of %zu read", cut, n);
            assert_true(strstr(err.message, "byte offset") || strstr(err.message, "header") ||
                        strstr(err.message, "cut:"));
        }
        /* index out of range */
        b[n - 2 - 4 - 1] = big ? 9 : 0;
        b[n - 2 - 4 - 4] = big ? 0 : 9;
        s = acd_mesh_read_memory(b, n, ACD_MESH_FORMAT_AUTO, "idx", &m, &err);
        assert_int_equal(s, ACD_ERR_PARSE);
        assert_non_null(strstr(err.message, "vertex index 9 out of range"));
    }
}

static void test_ply_ascii_features(void **state) {
    (void)state;
    const char *text = "ply\r\nformat ascii 1.0\r\ncomment x\r\nobj_info y\r\nelement vertex 3\r\nproperty double x\r\n"
                       "property double y\r\nproperty double z\r\nproperty uchar red\r\nelement face 1\r\n"
                       "property list uint8 int32 vertex_index\r\nend_header\r\n"
                       "0 0 0 1\r\n1e0 0 0 2\r\n0 0.5 0 3\r\n3 0 1 2\r\n";
    acd_mesh m;
    acd_error err;
    acd_status s = read_str(text, ACD_MESH_FORMAT_AUTO, &m, &err);
    if (s != ACD_OK) fail_msg("%s", err.message);
    assert_int_equal(m.nvertices, 3);
    assert_int_equal(m.ntriangles, 1);
    assert_true(m.vertices[7] == 0.5);
    acd_mesh_free(&m);
}

static void tmp_path(char *buf, size_t n, const char *suffix) {
    snprintf(buf, n, "/tmp/acd_test_mesh_io_%ld%s", (long)getpid(), suffix);
}

static void test_roundtrip_files_and_gzip(void **state) {
    (void)state;
    static const char *const suffixes[] = {".obj", ".off", ".stl", ".ply", ".obj.gz", ".off.gz", ".stl.gz", ".ply.gz"};
    for (size_t i = 0; i < sizeof suffixes / sizeof suffixes[0]; i++) {
        acd_mesh m, back;
        make_octa(&m, 100 + i);
        char path[256];
        tmp_path(path, sizeof path, suffixes[i]);
        acd_error err;
        assert_int_equal(acd_mesh_write(path, &m, ACD_MESH_FORMAT_AUTO, &err), ACD_OK);
        if (strstr(suffixes[i], ".gz")) { /* really compressed */
            size_t len;
            char *raw = tu_read_file(path, &len);
            assert_non_null(raw);
            assert_true(len > 2 && (unsigned char)raw[0] == 0x1f && (unsigned char)raw[1] == 0x8b);
            free(raw);
        }
        acd_status s = acd_mesh_read(path, &back, &err);
        if (s != ACD_OK) fail_msg("%s: %s", suffixes[i], err.message);
        assert_same_mesh(&m, &back, strstr(suffixes[i], ".stl") != NULL);
        unlink(path);
        acd_mesh_free(&m);
        acd_mesh_free(&back);
    }
}


static void test_obj_features(void **state) {
    (void)state;
    /* quads fanned, negative indices, v/vt/vn, comments, w coordinate, vertex colours */
    const char *text = "# a quad and a triangle\n"
                       "mtllib x.mtl\n"
                       "v 0 0 0 1\n"
                       "v 1 0 0 1 0.5 0.5\n"
                       "v 1 1 0\r\n"
                       "v 0 1 0\n"
                       "vt 0 0\nvn 0 0 1\n"
                       "usemtl a\ns off\n"
                       "f 1/1/1 2/1/1 3/1/1 4/1/1\n"
                       "v 0.5 0.5 1\n"
                       "f -5//1 -4//1 -1//1 # comment\n"
                       "l 1 2\n";
    acd_mesh m;
    acd_error err;
    acd_status s = read_str(text, ACD_MESH_FORMAT_AUTO, &m, &err);
    if (s != ACD_OK) fail_msg("%s", err.message);
    assert_int_equal(m.nvertices, 5);
    assert_int_equal(m.ntriangles, 3);
    const uint32_t expect[9] = {0, 1, 2, 0, 2, 3, 0, 1, 4};
    assert_memory_equal(m.triangles, expect, sizeof expect);
    assert_true(m.vertices[3 * 4 + 2] == 1.0);
    acd_mesh_free(&m);
}

/* Warnings collected by a read (acd_mesh_read_options.warning). */
typedef struct warn_log {
    char msg[16][ACD_ERROR_MESSAGE_SIZE];
    size_t n;
} warn_log;

static void log_warning(void *user, const char *message) {
    warn_log *l = user;
    assert_true(l->n < 16);
    assert_non_null(message);
    assert_true(strlen(message) < ACD_ERROR_MESSAGE_SIZE);
    snprintf(l->msg[l->n++], ACD_ERROR_MESSAGE_SIZE, "%s", message);
}

/* OBJ statements other than v, f, o, g (docs/mesh.md "OBJ statements"): those without geometry of
 * the surface are skipped silently, those with geometry the reader does not read (points, lines,
 * free-form curves and surfaces, superseded patches, calls) are skipped and reported, one warning
 * per keyword with the count and the first line, in the order of those lines; continuation lines
 * of a skipped statement are skipped with it; an unknown keyword is an error naming its line. */
static void test_obj_statements(void **state) {
    (void)state;
    const char *text = "# every statement of the format\n"                       /* 1 */
                       "mtllib a.mtl\nusemtl m\nmaplib x\nusemap y\n"            /* 2-5 */
                       "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"                    /* 6-9 */
                       "vt 0 0\nvn 0 0 1\nvp 0.5 0.5\n"                          /* 10-12 */
                       "s 1\nmg 1 0.5\nbevel off\nc_interp off\nd_interp off\n"  /* 13-17 */
                       "lod 1\nshadow_obj s.obj\ntrace_obj t.obj\n"              /* 18-20 */
                       "ctech cparm 1\nstech cparm 1\nres 4 4\nt crease 2/1/0 1 2 5\n" /* 21-24 */
                       "g a\nf 1 2 3\nf 1 3 4\n"                                 /* 25-27 */
                       "l 1 2\np 1\nl 2 3 \\\n  4\n"                             /* 28-31: l continued */
                       "cstype bspline\ndeg 3 3\nstep 1 1\nbmat u 1 0 0 1\n"     /* 32-35 */
                       "surf 0 1 0 1 1 2 \\\n 3 4\n"                             /* 36-37 */
                       "parm u 0 0 0 0 1 1 1 1\ntrim 0 1 1\nhole 0 1 1\nscrv 0 1 1\nsp 1\nend\n" /* 38-43 */
                       "con 1 0 1 1 2 0 1 1\ncurv 0 1 1 2 3 4\ncurv2 1 2 3\nsurf 0 1 0 1 1 2 3 4\n" /* 44-47 */
                       "bsp 1 2 3 4\nbzp 1 2 3 4\ncdc 1 2 3 4\ncdp 1 2 3 4\n"    /* 48-51 */
                       "call other.obj\ncsh ls\n"                                 /* 52-53 */
                       "o b\nf 1 4 2\n";                                          /* 54-55 */
    static const char *const expect[] = {
        "t:28: 2 'l' statements skipped (line elements; the first on this line)",
        "t:29: 1 'p' statement skipped (point elements;",
        "t:36: 2 'surf' statements skipped (free-form surfaces;",
        "t:45: 1 'curv' statement skipped (free-form curves;",
        "t:46: 1 'curv2' statement skipped (free-form curves on surfaces;",
        "t:48: 1 'bsp' statement skipped (B-spline patches;",
        "t:49: 1 'bzp' statement skipped (Bezier patches;",
        "t:50: 1 'cdc' statement skipped (Cardinal curves;",
        "t:51: 1 'cdp' statement skipped (Cardinal patches;",
        "t:52: 1 'call' statement skipped (calls of other OBJ files, not read;",
        "t:53: 1 'csh' statement skipped (shell commands, not run;",
    };
    static warn_log log;
    log.n = 0;
    acd_mesh_read_options o = acd_mesh_read_default_options();
    assert_null(o.warning);
    o.warning = log_warning;
    o.warning_user = &log;
    acd_mesh m;
    acd_error err;
    acd_status s = acd_mesh_read_memory_ex(text, strlen(text), ACD_MESH_FORMAT_OBJ, "t", &o, &m, &err);
    if (s != ACD_OK) fail_msg("%s", err.message);
    assert_int_equal(m.nvertices, 4);
    assert_int_equal(m.ntriangles, 3);
    const uint32_t tri[9] = {0, 1, 2, 0, 2, 3, 0, 3, 1};
    assert_memory_equal(m.triangles, tri, sizeof tri);
    acd_mesh_free(&m);
    size_t nexpect = sizeof expect / sizeof expect[0];
    assert_int_equal(log.n, nexpect);
    for (size_t i = 0; i < nexpect; i++) {
        if (strncmp(log.msg[i], expect[i], strlen(expect[i])) != 0) fail_msg("warning %zu: '%s'", i, log.msg[i]);
        assert_non_null(strstr(log.msg[i], "the mesh may be incomplete"));
    }
    /* the same warnings from the parts reader; none without a callback (the plain readers) */
    log.n = 0;
    acd_mesh_parts parts;
    assert_int_equal(acd_mesh_read_parts_memory_ex(text, strlen(text), ACD_MESH_FORMAT_OBJ, "t", &o, &parts, &err), ACD_OK);
    assert_int_equal(parts.count, 2);
    assert_int_equal(log.n, nexpect);
    for (size_t i = 0; i < nexpect; i++)
        if (strncmp(log.msg[i], expect[i], strlen(expect[i])) != 0) fail_msg("parts warning %zu: '%s'", i, log.msg[i]);
    acd_mesh_parts_free(&parts);
    assert_int_equal(acd_mesh_read_memory(text, strlen(text), ACD_MESH_FORMAT_OBJ, "t", &m, &err), ACD_OK);
    assert_int_equal(m.ntriangles, 3);
    acd_mesh_free(&m);
    /* a file without skipped geometry: no warning (attributes, free-form types and bodies alone) */
    log.n = 0;
    const char *quiet = "mtllib a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\ns off\nusemtl m\ncstype bezier\n"
                        "deg 1\nparm u 0 1\nend\nt crease 2/1/0 1 2 5\nf 1/1/1 2/1/1 3/1/1\n";
    assert_int_equal(acd_mesh_read_memory_ex(quiet, strlen(quiet), ACD_MESH_FORMAT_OBJ, "t", &o, &m, &err), ACD_OK);
    assert_int_equal(m.ntriangles, 1);
    assert_int_equal(log.n, 0);
    acd_mesh_free(&m);
    /* refused input: the error, no warning (the l before it is not reported) */
    static const struct {
        const char *text, *where;
    } bad[] = {
        {"v 0 0 0\nl 1 1\nfoo 1 2\n", "t:3: unknown statement 'foo'"},
        {"V 0 0 0\n", "t:1: unknown statement 'V'"},          /* keywords are lower case */
        {"v 0 0 0\nvertex 1 2 3\n", "t:2: unknown statement 'vertex'"},
        {"v 0 0 0\nv1 0 0\n", "t:2: unknown statement 'v1'"},
        {"v 0 0 0\nfo\x01o 1\n", "t:2: unknown statement 'fo?o'"},
        {"v 0 0 0\nl 1 1 \\\n 1\n2 3\n", "t:4: unexpected text"}, /* a continuation ends */
        {"v 0 0 0\nl 1 1\n1 1\n", "t:3: unexpected text"},        /* no continuation without '\\' */
        {"v 0 0 0\nl 1 1 # \\\n1 1\n", "t:3: unexpected text"},   /* a '\\' in a comment continues nothing */
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        log.n = 0;
        s = acd_mesh_read_memory_ex(bad[i].text, strlen(bad[i].text), ACD_MESH_FORMAT_OBJ, "t", &o, &m, &err);
        if (s != ACD_ERR_PARSE || !strstr(err.message, bad[i].where))
            fail_msg("bad %zu: status %d, '%s' (want '%s')", i, (int)s, s == ACD_OK ? "" : err.message, bad[i].where);
        assert_int_equal(log.n, 0);
        assert_null(m.vertices);
    }
}

/* PLY triangle strips (the Stanford tools' "tristrips": -1 ends a strip, alternate triangles
 * reversed, joins by a repeated index dropped) and the warnings for skipped elements */
static void test_ply_tristrips_and_skipped(void **state) {
    (void)state;
    /* a 3 x 2 grid of vertices in z = 0, ids 0 1 2 / 3 4 5; two strips: 0 3 1 4 (two triangles),
     * then 1 4 2 5 joined to a repeat of 5 (dropped) and ended with -1 */
    const char *text = "ply\nformat ascii 1.0\n"                                       /* 1-2 */
                       "element vertex 6\nproperty double x\nproperty double y\nproperty double z\n" /* 3-6 */
                       "element edge 2\nproperty int vertex1\nproperty int vertex2\n"  /* 7-9 */
                       "element tristrips 1\nproperty list int int vertex_indices\n"   /* 10-11 */
                       "element material 1\nproperty uchar red\n"                      /* 12-13 */
                       "end_header\n"
                       "0 1 0\n1 1 0\n2 1 0\n0 0 0\n1 0 0\n2 0 0\n"
                       "0 1\n1 2\n"
                       "10 0 3 1 4 -1 1 4 2 5 5\n"
                       "7\n";
    static warn_log log;
    log.n = 0;
    acd_mesh_read_options o = acd_mesh_read_default_options();
    o.warning = log_warning;
    o.warning_user = &log;
    acd_mesh m;
    acd_error err;
    acd_status s = acd_mesh_read_memory_ex(text, strlen(text), ACD_MESH_FORMAT_PLY, "p", &o, &m, &err);
    if (s != ACD_OK) fail_msg("%s", err.message);
    assert_int_equal(m.nvertices, 6);
    assert_int_equal(m.ntriangles, 4);
    const uint32_t tri[12] = {0, 3, 1, 1, 3, 4, 1, 4, 2, 2, 4, 5};
    assert_memory_equal(m.triangles, tri, sizeof tri);
    /* every triangle faces the first's way (+z): the strip's alternation is undone */
    for (size_t t = 0; t < m.ntriangles; t++) {
        const double *a = m.vertices + 3 * m.triangles[3 * t], *b = m.vertices + 3 * m.triangles[3 * t + 1],
                     *c = m.vertices + 3 * m.triangles[3 * t + 2];
        double nz = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if (!(nz > 0)) fail_msg("triangle %zu faces -z (%g)", t, nz);
    }
    acd_mesh_free(&m);
    assert_int_equal(log.n, 2);
    if (strncmp(log.msg[0], "p:7: 2 'edge' elements skipped (line segments)", 46) != 0) fail_msg("'%s'", log.msg[0]);
    assert_non_null(strstr(log.msg[0], "the mesh may be incomplete"));
    if (strncmp(log.msg[1], "p:12: 1 'material' element skipped", 34) != 0) fail_msg("'%s'", log.msg[1]);
    /* an index below -1 in a strip is refused with its place */
    const char *bad = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
                      "property double z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n"
                      "0 0 0\n1 0 0\n0 1 0\n4 0 1 -2 2\n";
    assert_int_equal(acd_mesh_read_memory(bad, strlen(bad), ACD_MESH_FORMAT_PLY, "q", &m, &err), ACD_ERR_PARSE);
    assert_non_null(strstr(err.message, "q:13: strip 0: vertex index -2 out of range (0..2, or -1 ending a strip)"));
    assert_int_equal(m.ntriangles, 0);
}

static void test_obj_groups(void **state) {
    (void)state;
    const char *text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 5 5 5\n"
                       "o first\nf 1 2 3\nf 1 2 4\n"
                       "o empty\n"
                       "g second part  \nf 5 2 3\n"
                       "o first\nf 4 3 2\n";
    acd_mesh_parts p;
    acd_error err;
    acd_status s = acd_mesh_read_parts_memory(text, strlen(text), ACD_MESH_FORMAT_AUTO, "groups", &p, &err);
    if (s != ACD_OK) fail_msg("%s", err.message);
    assert_int_equal(p.count, 3);
    assert_string_equal(p.parts[0].name, "first");
    assert_string_equal(p.parts[1].name, "second part");
    assert_string_equal(p.parts[2].name, "first");
    assert_int_equal(p.parts[0].mesh.nvertices, 4);
    assert_int_equal(p.parts[0].mesh.ntriangles, 2);
    assert_int_equal(p.parts[1].mesh.nvertices, 3);
    assert_int_equal(p.parts[1].mesh.ntriangles, 1);
    /* part vertices are the used ones, in order of first use */
    assert_true(p.parts[1].mesh.vertices[0] == 5.0);
    const uint32_t t1[3] = {0, 1, 2};
    assert_memory_equal(p.parts[1].mesh.triangles, t1, sizeof t1);
    assert_true(p.parts[2].mesh.vertices[0] == 0 && p.parts[2].mesh.vertices[2] == 1.0);

    /* written as parts and read back: same parts */
    char path[256];
    tmp_path(path, sizeof path, "_parts.obj");
    assert_int_equal(acd_mesh_write_obj_parts(path, &p, &err), ACD_OK);
    acd_mesh_parts q;
    s = acd_mesh_read_obj_groups(path, &q, &err);
    if (s != ACD_OK) fail_msg("%s", err.message);
    assert_int_equal(q.count, 3);
    for (size_t i = 0; i < 3; i++) {
        assert_string_equal(q.parts[i].name, p.parts[i].name);
        assert_same_mesh(&p.parts[i].mesh, &q.parts[i].mesh, 0);
    }
    /* a name with a newline is written on one line */
    char *old = p.parts[0].name;
    p.parts[0].name = (char *)"bad\nname";
    char path2[256];
    tmp_path(path2, sizeof path2, "_names.obj");
    assert_int_equal(acd_mesh_write_obj_parts(path2, &p, &err), ACD_OK);
    p.parts[0].name = old;
    acd_mesh_parts q2;
    assert_int_equal(acd_mesh_read_obj_groups(path2, &q2, &err), ACD_OK);
    assert_int_equal(q2.count, 3);
    assert_string_equal(q2.parts[0].name, "bad_name");
    acd_mesh_parts_free(&q2);
    unlink(path2);
    /* the whole file as one mesh: all 4 triangles */
    acd_mesh all;
    assert_int_equal(acd_mesh_read(path, &all, &err), ACD_OK);
    assert_int_equal(all.ntriangles, 4);
    acd_mesh_free(&all);
    unlink(path);
    acd_mesh_parts_free(&q);
    acd_mesh_parts_free(&p);

    /* no groups: one part named "" ; an OFF file is not OBJ for read_obj_groups */
    s = acd_mesh_read_parts_memory("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 32, ACD_MESH_FORMAT_AUTO, "x", &p, &err);
    assert_int_equal(s, ACD_OK);
    assert_int_equal(p.count, 1);
    assert_string_equal(p.parts[0].name, "");
    acd_mesh_parts_free(&p);
    tmp_path(path, sizeof path, "_parts.off");
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", f);
    fclose(f);
    assert_int_equal(acd_mesh_read_obj_groups(path, &p, &err), ACD_ERR_UNSUPPORTED);
    assert_int_equal(acd_mesh_read_parts(path, &p, &err), ACD_OK);
    assert_int_equal(p.count, 1);
    acd_mesh_parts_free(&p);
    unlink(path);
}

static void test_off_features(void **state) {
    (void)state;
    /* counts on the header line, comments, colours after vertices and faces, a quad */
    const char *text = "COFF 5 2 0 # header with counts\n"
                       "# comment\n"
                       "0 0 0 255 0 0 255\n1 0 0 255 0 0 255\n1 1 0 0 0 0 0\n0 1 0 1 1 1 1\n\n0.5 0.5 1 0 0 0 0\n"
                       "4 0 1 2 3 0.1 0.2 0.3\n3 0 1 4\n";
    acd_mesh m;
    acd_error err;
    acd_status s = read_str(text, ACD_MESH_FORMAT_AUTO, &m, &err);
    if (s != ACD_OK) fail_msg("%s", err.message);
    assert_int_equal(m.nvertices, 5);
    assert_int_equal(m.ntriangles, 3);
    acd_mesh_free(&m);
}

/* A non-convex polygon face is ear-clipped, not fanned (a fan from its first corner would cover
 * area outside it and overlap itself): an L-shaped prism written with two 6-gon caps whose first
 * corner sees not all of the L, read as OFF and OBJ: 20 triangles, closed, volume 3, no
 * self-intersection; a convex quad is still fanned from its first corner. */
static void test_nonconvex_polygon_faces(void **state) {
    (void)state;
    const char *off = "OFF 12 8 0\n"
                      "2 0 0\n2 1 0\n1 1 0\n1 2 0\n0 2 0\n0 0 0\n"
                      "2 0 1\n2 1 1\n1 1 1\n1 2 1\n0 2 1\n0 0 1\n"
                      "6 0 5 4 3 2 1\n6 6 7 8 9 10 11\n"
                      "4 0 1 7 6\n4 1 2 8 7\n4 2 3 9 8\n4 3 4 10 9\n4 4 5 11 10\n4 5 0 6 11\n";
    const char *obj = "v 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nv 0 0 0\n"
                      "v 2 0 1\nv 2 1 1\nv 1 1 1\nv 1 2 1\nv 0 2 1\nv 0 0 1\n"
                      "f 1 6 5 4 3 2\nf 7 8 9 10 11 12\n"
                      "f 1 2 8 7\nf 2 3 9 8\nf 3 4 10 9\nf 4 5 11 10\nf 5 6 12 11\nf 6 1 7 12\n";
    const char *texts[] = {off, obj};
    for (int i = 0; i < 2; i++) {
        acd_mesh m;
        acd_error err;
        acd_status s = read_str(texts[i], ACD_MESH_FORMAT_AUTO, &m, &err);
        if (s != ACD_OK) fail_msg("%s", err.message);
        assert_int_equal(m.ntriangles, 20);
        acd_mesh_report r;
        assert_int_equal(acd_mesh_validate(&m, 1, &r, &err), ACD_OK);
        assert_true(r.closed);
        assert_int_equal(r.self_intersections, 0);
        assert_true(fabs(r.volume - 3.0) < 1e-12);
        acd_mesh_report_free(&r);
        /* the side quads (convex) are fanned from their first corner: triangles (0 1 7), (0 7 6) */
        int found = 0;
        for (size_t t = 0; t < m.ntriangles; t++)
            found += m.triangles[3 * t] == 0 && m.triangles[3 * t + 1] == 1 && m.triangles[3 * t + 2] == 7;
        assert_int_equal(found, 1);
        acd_mesh_free(&m);
    }
}

static void test_stl_ascii_and_weld(void **state) {
    (void)state;
    const char *text = "solid t\n"
                       " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n  endloop\n endfacet\n"
                       " FACET NORMAL 0 0 1\n  OUTER LOOP\n   VERTEX 1 0 0\n   VERTEX 1 1 0\n   VERTEX -0 1 0\n  ENDLOOP\n ENDFACET\n"
                       "endsolid t\n";
    acd_mesh m;
    acd_error err;
    acd_status s = read_str(text, ACD_MESH_FORMAT_AUTO, &m, &err);
    if (s != ACD_OK) fail_msg("%s", err.message);
    assert_int_equal(m.ntriangles, 2);
    assert_int_equal(m.nvertices, 4); /* shared corners welded, -0 == 0 */
    acd_mesh_free(&m);

    /* a binary STL whose header starts with "solid" is still binary */
    acd_mesh o;
    make_octa(&o, 3);
    void *data;
    size_t size;
    assert_int_equal(acd_mesh_write_memory(&o, ACD_MESH_FORMAT_STL, &data, &size, &err), ACD_OK);
    memcpy(data, "solid fake", 10);
    s = acd_mesh_read_memory(data, size, ACD_MESH_FORMAT_AUTO, "b", &m, &err);
    if (s != ACD_OK) fail_msg("%s", err.message);
    assert_same_mesh(&o, &m, 1);
    acd_mesh_free(&m);
    /* truncated binary: error with byte offset (detected by the .stl hint) */
    s = acd_mesh_read_memory(data, size - 7, ACD_MESH_FORMAT_STL, "trunc.stl", &m, &err);
    assert_int_equal(s, ACD_ERR_PARSE);
    assert_non_null(strstr(err.message, "truncated"));
    assert_non_null(strstr(err.message, "byte offset"));
    /* NaN coordinate in binary: error with byte offset */
    float nan = NAN;
    memcpy((char *)data + 84 + 50 * 2 + 12 + 4 * 4, &nan, 4);
    s = acd_mesh_read_memory(data, size, ACD_MESH_FORMAT_AUTO, "nan.stl", &m, &err);
    assert_int_equal(s, ACD_ERR_PARSE);
    assert_non_null(strstr(err.message, "byte offset 212"));
    /* a count lower than the triangles the file holds (a streaming writer's unpatched 0, or a
     * lie): an error naming the count's offset, not a mesh missing its last triangles */
    memcpy((char *)data + 84 + 50 * 2 + 12 + 4 * 4, (char *)data + 84 + 50 * 2 + 12 + 4 * 3, 4);
    const unsigned char six[4] = {6, 0, 0, 0};
    memcpy((char *)data + 80, six, 4);
    s = acd_mesh_read_memory(data, size, ACD_MESH_FORMAT_STL, "low.stl", &m, &err);
    assert_int_equal(s, ACD_ERR_PARSE);
    assert_non_null(strstr(err.message, "header says 6 triangles"));
    assert_non_null(strstr(err.message, "room for 8"));
    /* a few trailing bytes (padding) are tolerated */
    memcpy((char *)data + 80, (const unsigned char[4]){8, 0, 0, 0}, 4);
    char *padded = malloc(size + 10);
    assert_non_null(padded);
    memcpy(padded, data, size);
    memset(padded + size, 0, 10);
    s = acd_mesh_read_memory(padded, size + 10, ACD_MESH_FORMAT_STL, "pad.stl", &m, &err);
    if (s != ACD_OK) fail_msg("%s", err.message);
    assert_int_equal(m.ntriangles, 8);
    acd_mesh_free(&m);
    free(padded);
    free(data);
    acd_mesh_free(&o);
}

/* Each malformed text must fail with the given status and a message containing `where`. */
typedef struct bad_case {
    const char *text;
    acd_mesh_format hint;
    acd_status status;
    const char *where;
} bad_case;

/* Each case must fail with its status, the message must contain its text, and the mesh must be
 * left empty. */
static void check_bad_cases(const bad_case *cases, size_t n) {
    for (size_t i = 0; i < n; i++) {
        acd_mesh m;
        acd_error err;
        acd_status s = read_str(cases[i].text, cases[i].hint, &m, &err);
        if (s != cases[i].status || !strstr(err.message, cases[i].where))
            fail_msg("case %zu: status %d (want %d), message '%s' (want '%s')", i, (int)s, (int)cases[i].status,
                     s == ACD_OK ? "" : err.message, cases[i].where);
        assert_null(m.vertices);
        assert_int_equal(m.ntriangles, 0);
    }
}

static void test_malformed(void **state) {
    (void)state;
    static const bad_case cases[] = {
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:4:"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:4: vertex index 0"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:4:"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:4: face with 2"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf\nf 1 2 3\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:4: face with 0"},
        {"v 1 2 3.1+e2\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:1: vertex needs 3 numbers (coordinate 3"},
        {"OFF\n3 1\n0 0 0\n0 1 0\n1 0 0\n0\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:6: face 0 has 0 vertices"},
        {"OFF\n3 1\n0 0 0\n0 1 0\n1 0 0\n999999 0 1 2\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "more than the file"},
        {"v 0 0\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:1: vertex needs 3"},
        {"v 0 0 nan\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:1: vertex coordinate 3 is not finite"},
        {"v 0 0 1e999\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "not finite"},
        {"v 0 0 0x\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:1:"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3x\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:4: face corner 3"},
        {"v 0 0 0\n1 2 3\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:2: unexpected text"},
        {"v 0 0 0\nf 1 2 99999999999\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:2:"},
        {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:6: face 0: vertex index 3"},
        {"OFF\n3 1 0\n0 0 0\n1 0\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:4: vertex 1: coordinate 3 is missing"},
        {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:6: face 0 has 2"},
        {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "face 0: vertex index 2"},
        {"OFF\nx 1 0\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:2: expected the number of vertices"},
        {"OFF\n3\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "number of faces"},
        {"OFF\n99999999 1 0\n0 0 0\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "exceed"},
        {"4OFF\n1 0 0\n0 0 0 0\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_UNSUPPORTED, "t:1:"},
        {"OFF BINARY\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_UNSUPPORTED, "binary OFF"},
        {"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n",
         ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:6: facet with 2"},
        {"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 q 0\n", ACD_MESH_FORMAT_AUTO,
         ACD_ERR_PARSE, "t:6: vertex coordinate 2"},
        {"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\n",
         ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:8: expected 'endfacet'"},
        {"solid x\nfacet normal 0 0 1\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "expected 'outer'"},
        {"solid x\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "no 'endsolid'"},
        {"", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "empty file"},
        {"hello world\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_UNSUPPORTED, "unrecognised"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "no end_header"},
        {"ply\nformat ascii 2.0\nend_header\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_UNSUPPORTED, "t:2: PLY version"},
        {"ply\nformat text 1.0\nend_header\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:2: unknown PLY format"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE,
         "t:4: unknown property type"},
        {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:3: property before"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
         ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "lacks property"},
        {"ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 1\n",
         ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "vertex 1: expected a number"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
         "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
         ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:13: face 0: vertex index 3 out of range"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
         "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
         ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "face 0 has 2 vertices"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 inf 0\n",
         ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:8: vertex 0: coordinate y is not finite"},
        {"ply\nformat ascii 1.0\nelement vertex 100000\nproperty float x\nend_header\n0\n", ACD_MESH_FORMAT_AUTO,
         ACD_ERR_PARSE, "exceeds"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty int x\nproperty int y\nproperty int z\nend_header\n0 0.5 0\n",
         ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "integer property"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
         "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n9e101 0 1 2\n",
         ACD_MESH_FORMAT_AUTO, ACD_ERR_PARSE, "t:13: face 0: integer property has value 9e+101"},
        {"short", ACD_MESH_FORMAT_STL, ACD_ERR_PARSE, "shorter than its 84-byte header"},
    };
    check_bad_cases(cases, sizeof cases / sizeof cases[0]);
}

/* A vertex short of a coordinate must be an error at its own line, never completed with the next
 * line's first number: the number parser fell back to strtod, which skips newlines, so OBJ
 * "v 0 0\n5" was the vertex (0, 0, 5) (the line "5" eaten), an OFF vertex line "0 0" took the next
 * vertex's x, and later errors named lines too early (fuzzrun3, docs/results/fuzz.md). */
static void test_coordinates_on_one_line(void **state) {
    (void)state;
    static const bad_case cases[] = {
        {"v 0 0\n5\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", ACD_MESH_FORMAT_OBJ, ACD_ERR_PARSE,
         "t:1: vertex needs 3 numbers (coordinate 3"},
        {"v 0 0 0\nv 1 0\r\n\n7\nf 1 2 3\n", ACD_MESH_FORMAT_OBJ, ACD_ERR_PARSE, "t:2: vertex needs 3 numbers (coordinate 3"},
        {"OFF\n4 1 0\n0 0\n0\n1 0 0\n0 1 0\n3 0 1 2\n", ACD_MESH_FORMAT_OFF, ACD_ERR_PARSE,
         "t:3: vertex 0: coordinate 3 is missing"},
        {"OFF\n3 1 0\n0 0\n\n\n0\n1 0 0\n0 1 0\n3 0 1 2\n", ACD_MESH_FORMAT_OFF, ACD_ERR_PARSE,
         "t:3: vertex 0: coordinate 3 is missing"},
        {"solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
         "endsolid\n",
         ACD_MESH_FORMAT_STL, ACD_ERR_PARSE, "t:4: vertex coordinate 3 is missing"},
    };
    check_bad_cases(cases, sizeof cases / sizeof cases[0]);
    /* blanks other than a newline still separate numbers on a line; inf and nan are still named */
    acd_mesh m;
    acd_error err;
    assert_int_equal(read_str("v 1\f2\v3 \r\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", ACD_MESH_FORMAT_OBJ, &m, &err), ACD_OK);
    assert_true(m.nvertices == 3 && m.vertices[0] == 1 && m.vertices[1] == 2 && m.vertices[2] == 3);
    acd_mesh_free(&m);
    assert_int_equal(read_str("v 0 -Infinity 0\n", ACD_MESH_FORMAT_OBJ, &m, &err), ACD_ERR_PARSE);
    assert_non_null(strstr(err.message, "t:1: vertex coordinate 2 is not finite"));
}

/* ASCII STL: a facet after endsolid was dropped without a word (other trailing text is tolerated
 * as padding); a NUL byte inside a solid was reported as the end of the file (fuzzrun3). */
static void test_stl_after_endsolid(void **state) {
    (void)state;
    static const char stl_after[] = "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                                    "endloop\nendfacet\nendsolid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 1\n"
                                    "vertex 1 0 1\nvertex 0 1 1\nendloop\nendfacet\nendsolid a\n";
    {
        acd_mesh m;
        acd_error err;
        assert_int_equal(read_str(stl_after, ACD_MESH_FORMAT_STL, &m, &err), ACD_ERR_PARSE);
        assert_non_null(strstr(err.message, "t:10: 'facet' after 'endsolid'"));
        /* the NUL beyond the first KiB (text there makes the file ASCII): 12 facets of 7 lines */
        char text[2048];
        size_t len = (size_t)snprintf(text, sizeof text, "solid a\n");
        for (int f = 0; f < 12; f++)
            len += (size_t)snprintf(text + len, sizeof text - len,
                                    "facet normal 0 0 1\nouter loop\nvertex %d 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                                    "endloop\nendfacet\n", f + 2);
        assert_true(len > 1024 && len + 16 < sizeof text);
        text[len++] = '\0';
        len += (size_t)snprintf(text + len, sizeof text - len, "endsolid\n");
        assert_int_equal(acd_mesh_read_memory(text, len, ACD_MESH_FORMAT_STL, "t", &m, &err), ACD_ERR_PARSE);
        if (!strstr(err.message, "t:86: NUL byte inside a solid")) fail_msg("NUL byte: '%s'", err.message);
    }
    {
        /* other text after the last endsolid is still read past (padding, a note) */
        static const char padded[] = "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                     "vertex 0 1 0\nendloop\nendfacet\nendsolid a\n   \n written by x\n";
        acd_mesh m;
        acd_error err;
        assert_int_equal(acd_mesh_read_memory(padded, sizeof padded - 1, ACD_MESH_FORMAT_STL, "t", &m, &err), ACD_OK);
        assert_int_equal(m.ntriangles, 1);
        acd_mesh_free(&m);
    }
}

static void test_text_encodings(void **state) {
    (void)state;
    /* UTF-16 (both byte orders, with BOM) and UTF-8 with BOM are read */
    const char *text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    size_t n = strlen(text);
    for (int be = 0; be < 2; be++) {
        unsigned char *u = malloc(2 * n + 2);
        assert_non_null(u);
        u[0] = be ? 0xfe : 0xff;
        u[1] = be ? 0xff : 0xfe;
        for (size_t i = 0; i < n; i++) {
            u[2 + 2 * i + (size_t)!be] = 0;
            u[2 + 2 * i + (size_t)be] = (unsigned char)text[i];
        }
        acd_mesh m;
        acd_error err;
        acd_status s = acd_mesh_read_memory(u, 2 * n + 2, ACD_MESH_FORMAT_AUTO, "u16", &m, &err);
        if (s != ACD_OK) fail_msg("%s", err.message);
        assert_int_equal(m.ntriangles, 1);
        acd_mesh_free(&m);
        free(u);
    }
    char b8[64] = "\xef\xbb\xbf";
    strcat(b8, text);
    acd_mesh m;
    acd_error err;
    assert_int_equal(acd_mesh_read_memory(b8, strlen(b8), ACD_MESH_FORMAT_AUTO, "u8", &m, &err), ACD_OK);
    assert_int_equal(m.ntriangles, 1);
    acd_mesh_free(&m);
    /* PLY header lines without a keyword (old Blender) are ignored */
    const char *ply = "ply\nformat ascii 1.0\nCreated by Blender3D 247\nelement vertex 3\nproperty float x\n"
                      "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                      "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    assert_int_equal(acd_mesh_read_memory(ply, strlen(ply), ACD_MESH_FORMAT_AUTO, "p", &m, &err), ACD_OK);
    assert_int_equal(m.ntriangles, 1);
    acd_mesh_free(&m);
}

static void test_gzip_errors(void **state) {
    (void)state;
    acd_mesh m;
    make_octa(&m, 1);
    char path[256];
    tmp_path(path, sizeof path, "_bad.obj.gz");
    acd_error err;
    assert_int_equal(acd_mesh_write(path, &m, ACD_MESH_FORMAT_AUTO, &err), ACD_OK);
    acd_mesh_free(&m);
    size_t len;
    char *raw = tu_read_file(path, &len);
    assert_non_null(raw);
    unlink(path);
    /* truncated compressed stream */
    acd_status s = acd_mesh_read_memory(raw, len / 2, ACD_MESH_FORMAT_AUTO, "half.gz", &m, &err);
    assert_int_equal(s, ACD_ERR_PARSE);
    assert_non_null(strstr(err.message, "gzip"));
    /* corrupt deflate data */
    for (size_t i = 12; i < len - 8; i++) raw[i] = (char)0xff;
    s = acd_mesh_read_memory(raw, len, ACD_MESH_FORMAT_AUTO, "corrupt.gz", &m, &err);
    assert_int_equal(s, ACD_ERR_PARSE);
    assert_non_null(strstr(err.message, "gzip"));
    free(raw);
    /* a gzip bomb (80 MiB of spaces in ~80 KB, a ratio near deflate's limit of 1032) is refused
     * with a message, before it expands to its full size */
    size_t bomb_out = (size_t)80 << 20, cap = 1 << 20, blen = 0;
    unsigned char *bomb = malloc(cap), *spaces = malloc(1 << 20);
    assert_non_null(bomb);
    assert_non_null(spaces);
    memset(spaces, ' ', 1 << 20);
    z_stream z;
    memset(&z, 0, sizeof z);
    assert_int_equal(deflateInit2(&z, 9, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY), Z_OK);
    for (size_t done = 0; done < bomb_out; done += 1 << 20) {
        z.next_in = spaces;
        z.avail_in = 1 << 20;
        int flush = done + (1 << 20) >= bomb_out ? Z_FINISH : Z_NO_FLUSH;
        do {
            z.next_out = bomb + blen;
            z.avail_out = (uInt)(cap - blen);
            deflate(&z, flush);
            blen = cap - z.avail_out;
        } while (z.avail_out == 0 && blen < cap);
        assert_true(blen < cap);
    }
    deflateEnd(&z);
    s = acd_mesh_read_memory(bomb, blen, ACD_MESH_FORMAT_OBJ, "bomb.obj.gz", &m, &err);
    assert_int_equal(s, ACD_ERR_PARSE);
    assert_non_null(strstr(err.message, "bomb.obj.gz"));
    assert_non_null(strstr(err.message, "gzip bomb"));
    free(bomb);
    free(spaces);
    /* a missing file is an I/O error naming the file */
    s = acd_mesh_read("/nonexistent/dir/x.obj", &m, &err);
    assert_int_equal(s, ACD_ERR_IO);
    assert_non_null(strstr(err.message, "/nonexistent/dir/x.obj"));
}

/* A face of n corners on a circle (alternate radii 1 and 1.5 when star: not convex), as OBJ. */
static char *big_face_obj(size_t n, int star) {
    size_t cap = n * 64 + 64, len = 0;
    char *s = malloc(cap);
    assert_non_null(s);
    for (size_t i = 0; i < n; i++) {
        double a = 2 * 3.14159265358979323846 * (double)i / (double)n, r = star && i % 2 ? 1.5 : 1;
        len += (size_t)snprintf(s + len, cap - len, "v %.9f %.9f 0\n", r * cos(a), r * sin(a));
    }
    len += (size_t)snprintf(s + len, cap - len, "f");
    for (size_t i = 0; i < n; i++) len += (size_t)snprintf(s + len, cap - len, " %zu", i + 1);
    snprintf(s + len, cap - len, "\n");
    return s;
}

/* A non-convex face of 200000 corners kept `acd info` busy for minutes (ear clipping is
 * quadratic); beyond 10000 corners it is refused with the line. A convex one of that size is still
 * fanned, and a small non-convex one ear-clipped. */
static void test_huge_nonconvex_face(void **state) {
    (void)state;
    acd_mesh m;
    acd_error err;
    char *s = big_face_obj(10001, 1);
    assert_int_equal(read_str(s, ACD_MESH_FORMAT_OBJ, &m, &err), ACD_ERR_UNSUPPORTED);
    assert_non_null(strstr(err.message, ":10002: a face of 10001 corners is not convex"));
    free(s);
    s = big_face_obj(20000, 0);
    acd_status st = read_str(s, ACD_MESH_FORMAT_OBJ, &m, &err);
    if (st != ACD_OK) fail_msg("%s", err.message);
    assert_int_equal(m.ntriangles, 19998);
    acd_mesh_free(&m);
    free(s);
    s = big_face_obj(100, 1);
    st = read_str(s, ACD_MESH_FORMAT_OBJ, &m, &err);
    if (st != ACD_OK) fail_msg("%s", err.message);
    assert_int_equal(m.ntriangles, 98);
    acd_mesh_free(&m);
    free(s);
}

static void test_write_checks(void **state) {
    (void)state;
    acd_mesh m;
    make_octa(&m, 2);
    void *data;
    size_t size;
    acd_error err;
    m.triangles[5] = 6;
    assert_int_equal(acd_mesh_write_memory(&m, ACD_MESH_FORMAT_OBJ, &data, &size, &err), ACD_ERR_INVALID_ARGUMENT);
    m.triangles[5] = 0;
    m.vertices[4] = NAN;
    assert_int_equal(acd_mesh_write_memory(&m, ACD_MESH_FORMAT_OFF, &data, &size, &err), ACD_ERR_INVALID_ARGUMENT);
    m.vertices[4] = 1e300;
    assert_int_equal(acd_mesh_write_memory(&m, ACD_MESH_FORMAT_STL, &data, &size, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_int_equal(acd_mesh_write_memory(&m, ACD_MESH_FORMAT_OBJ, &data, &size, &err), ACD_OK);
    free(data);
    assert_int_equal(acd_mesh_write("/tmp/x.unknown", &m, ACD_MESH_FORMAT_AUTO, &err), ACD_ERR_INVALID_ARGUMENT);
    acd_mesh_free(&m);
    assert_int_equal(acd_mesh_format_from_path("a/B.OBJ.gz"), ACD_MESH_FORMAT_OBJ);
    assert_int_equal(acd_mesh_format_from_path("x.stl"), ACD_MESH_FORMAT_STL);
    assert_int_equal(acd_mesh_format_from_path("x.txt"), ACD_MESH_FORMAT_AUTO);
}

static void test_number_parsing_exact(void **state) {
    (void)state;
    /* numbers the fast path and the strtod path both must get exactly right */
    static const char *const nums[] = {"0.1", "-2.5e-3", "123456789012345678", "1.7976931348623157e308",
                                       "4.9406564584124654e-324", "0.30000000000000004", "9007199254740993",
                                       "1e22", "1e23", "-0", "3.14159265358979323846264338327950288"};
    for (size_t i = 0; i < sizeof nums / sizeof nums[0]; i++) {
        char text[256];
        snprintf(text, sizeof text, "v %s 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n", nums[i]);
        acd_mesh m;
        acd_error err;
        assert_int_equal(read_str(text, ACD_MESH_FORMAT_AUTO, &m, &err), ACD_OK);
        double expect = strtod(nums[i], NULL);
        if (memcmp(&expect, &m.vertices[0], sizeof expect) != 0) fail_msg("%s read as %.17g", nums[i], m.vertices[0]);
        acd_mesh_free(&m);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_roundtrip_obj),
        cmocka_unit_test(test_roundtrip_off),
        cmocka_unit_test(test_roundtrip_stl),
        cmocka_unit_test(test_roundtrip_stl_ascii),
        cmocka_unit_test(test_roundtrip_ply),
        cmocka_unit_test(test_roundtrip_ply_ascii),
        cmocka_unit_test(test_ply_binary_both_endians),
        cmocka_unit_test(test_ply_ascii_features),
        cmocka_unit_test(test_roundtrip_files_and_gzip),
        cmocka_unit_test(test_obj_features),
        cmocka_unit_test(test_obj_statements),
        cmocka_unit_test(test_ply_tristrips_and_skipped),
        cmocka_unit_test(test_obj_groups),
        cmocka_unit_test(test_off_features),
        cmocka_unit_test(test_nonconvex_polygon_faces),
        cmocka_unit_test(test_stl_ascii_and_weld),
        cmocka_unit_test(test_malformed),
        cmocka_unit_test(test_text_encodings),
        cmocka_unit_test(test_gzip_errors),
        cmocka_unit_test(test_huge_nonconvex_face),
        cmocka_unit_test(test_write_checks),
        cmocka_unit_test(test_number_parsing_exact),
        cmocka_unit_test(test_coordinates_on_one_line),
        cmocka_unit_test(test_stl_after_endsolid),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
