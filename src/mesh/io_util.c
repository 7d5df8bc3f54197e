/* mesh/io_util: mesh builder, text cursor with fast number parsing, output buffer. */
#include "mesh/io_util.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/predicates.h"
#include "geom2/triangulate.h"

int acd_grow(void **p, size_t *cap, size_t need, size_t elem) {
    if (need <= *cap) return 1;
    size_t n = *cap ? *cap : 16;
    while (n < need) {
        if (n > SIZE_MAX / 2) return 0;
        n *= 2;
    }
    if (n > SIZE_MAX / elem) return 0;
    void *q = realloc(*p, n * elem);
    if (!q) return 0;
    *p = q;
    *cap = n;
    return 1;
}

void acd_builder_free(acd_mesh_builder *b) {
    free(b->v);
    free(b->t);
    for (size_t i = 0; i < b->ngroups; i++) free(b->groups[i].name);
    free(b->groups);
    free(b->poly);
    memset(b, 0, sizeof *b);
}

int acd_builder_vertex(acd_mesh_builder *b, double x, double y, double z) {
    if (b->nv >= UINT32_MAX) return 0;
    if (b->nv == b->vcap && !acd_grow((void **)&b->v, &b->vcap, b->nv + 1, 3 * sizeof(double))) return 0;
    double *d = b->v + 3 * b->nv++;
    d[0] = x;
    d[1] = y;
    d[2] = z;
    return 1;
}

int acd_builder_triangle(acd_mesh_builder *b, uint32_t a, uint32_t c, uint32_t d) {
    if (b->nt == b->tcap && !acd_grow((void **)&b->t, &b->tcap, b->nt + 1, 3 * sizeof(uint32_t))) return 0;
    uint32_t *t = b->t + 3 * b->nt++;
    t[0] = a;
    t[1] = c;
    t[2] = d;
    return 1;
}

int acd_builder_group(acd_mesh_builder *b, const char *name, size_t len) {
    if (!acd_grow((void **)&b->groups, &b->gcap, b->ngroups + 1, sizeof *b->groups)) return 0;
    char *s = malloc(len + 1);
    if (!s) return 0;
    memcpy(s, name, len);
    s[len] = '\0';
    b->groups[b->ngroups].name = s;
    b->groups[b->ngroups].first_triangle = b->nt;
    b->ngroups++;
    return 1;
}

int acd_builder_poly_push(acd_mesh_builder *b, uint32_t i) {
    if (b->npoly == b->polycap && !acd_grow((void **)&b->poly, &b->polycap, b->npoly + 1, sizeof(uint32_t)))
        return 0;
    b->poly[b->npoly++] = i;
    return 1;
}

/* A polygon of more than three corners that is not convex in its own plane cannot be fanned:
 * the fan's triangles would overlap (a self-intersecting mesh from a valid file, as in CGAL's
 * corner_poly.off and mpi.off). It is projected on the coordinate plane its Newell normal is
 * most perpendicular to and ear-clipped (geom2/triangulate, exact predicates); each triangle
 * keeps the polygon's orientation. Returns 1 if emitted that way, 0 to fan instead (convex, or
 * not a simple polygon in projection: the fan is then as good as anything), -1 out of memory, 2
 * when not convex and larger than ACD_MESH_EARCLIP_MAX_CORNERS. */
static int builder_ear_clip(acd_mesh_builder *b) {
    const size_t n = b->npoly;
    for (size_t i = 0; i < n; i++)
        if (b->poly[i] >= b->nv) return 0; /* indices are checked by the reader */
    double N[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++) {
        const double *p = b->v + 3 * (size_t)b->poly[i], *q = b->v + 3 * (size_t)b->poly[(i + 1) % n];
        N[0] += (p[1] - q[1]) * (p[2] + q[2]);
        N[1] += (p[2] - q[2]) * (p[0] + q[0]);
        N[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    int k = fabs(N[0]) >= fabs(N[1]) && fabs(N[0]) >= fabs(N[2]) ? 0 : fabs(N[1]) >= fabs(N[2]) ? 1 : 2;
    if (!(N[k] != 0)) return 0;
    const int ax = (k + 1) % 3, ay = (k + 2) % 3;
    acd_vec2 *pts = malloc(n * sizeof *pts);
    if (!pts) return -1;
    for (size_t i = 0; i < n; i++) {
        pts[i].x = b->v[3 * (size_t)b->poly[i] + ax];
        pts[i].y = b->v[3 * (size_t)b->poly[i] + ay];
    }
    /* convex (every turn the same way or straight): the fan is right */
    int pos = 0, neg = 0;
    for (size_t i = 0; i < n; i++) {
        const acd_vec2 *a = &pts[(i + n - 1) % n], *c = &pts[i], *d = &pts[(i + 1) % n];
        int o = acd_orient2d_sign((const double[2]){a->x, a->y}, (const double[2]){c->x, c->y},
                                  (const double[2]){d->x, d->y});
        pos += o > 0;
        neg += o < 0;
    }
    if (!pos || !neg) {
        free(pts);
        return 0;
    }
    if (n > ACD_MESH_EARCLIP_MAX_CORNERS) { /* ear clipping is quadratic: refused, not a hang */
        free(pts);
        return 2;
    }
    const size_t ring[2] = {0, n};
    size_t *tris = NULL, ntris = 0;
    acd_status st = acd_triangulate_rings(pts, ring, 1, 0, &tris, &ntris, NULL, NULL, NULL);
    int ccw = st == ACD_OK ? acd_ring_is_ccw(pts, n) : 0;
    free(pts);
    if (st == ACD_ERR_NOMEM) return -1;
    if (st != ACD_OK) return 0;
    for (size_t t = 0; t < ntris; t++) {
        uint32_t i0 = b->poly[tris[3 * t]], i1 = b->poly[tris[3 * t + 1]], i2 = b->poly[tris[3 * t + 2]];
        if (!(ccw ? acd_builder_triangle(b, i0, i1, i2) : acd_builder_triangle(b, i0, i2, i1))) {
            free(tris);
            return -1;
        }
    }
    free(tris);
    return 1;
}

int acd_builder_fan(acd_mesh_builder *b) {
    if (b->npoly > 3) {
        int r = builder_ear_clip(b);
        if (r == 2) return -1;
        if (r < 0) return 0;
        if (r > 0) {
            b->npoly = 0;
            return 1;
        }
    }
    for (size_t i = 1; i + 1 < b->npoly; i++)
        if (!acd_builder_triangle(b, b->poly[0], b->poly[i], b->poly[i + 1])) return 0;
    b->npoly = 0;
    return 1;
}

void acd_builder_take_mesh(acd_mesh_builder *b, acd_mesh *out) {
    out->nvertices = b->nv;
    out->ntriangles = b->nt;
    out->vertices = b->v;
    out->triangles = b->t;
    if (b->nv && b->nv < b->vcap) {
        double *v = realloc(b->v, b->nv * 3 * sizeof(double));
        if (v) out->vertices = v;
    }
    if (b->nt && b->nt < b->tcap) {
        uint32_t *t = realloc(b->t, b->nt * 3 * sizeof(uint32_t));
        if (t) out->triangles = t;
    }
    b->v = NULL;
    b->t = NULL;
    b->nv = b->vcap = b->nt = b->tcap = 0;
}

/* ---------------------------------------------------------------------------------------- */

void acd_text_next_line(acd_text *t) {
    const char *q = memchr(t->p, '\n', (size_t)(t->end - t->p));
    if (q) {
        t->p = q + 1;
        t->line++;
    } else {
        t->p = t->end;
    }
}

void acd_text_skip_space(acd_text *t, int comments) {
    for (;;) {
        char c = *t->p;
        if (c == '\n') {
            t->line++;
            t->p++;
        } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
            t->p++;
        } else if (comments && c == '#') {
            acd_text_next_line(t);
        } else {
            return;
        }
    }
}

int acd_text_at_eol(acd_text *t, int comments) {
    acd_text_skip_blank(t);
    char c = *t->p;
    return c == '\n' || c == '\0' || (comments && c == '#');
}

static const double pow10_exact[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                       1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

const char *acd_parse_double(const char *p, double *out) {
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\f' || *p == '\v') p++;
    const char *start = p, *s = p;
    int neg = 0;
    if (*s == '+' || *s == '-') neg = *s++ == '-';
    uint64_t m = 0;
    int nd = 0, any = 0, exact = 1;
    long e10 = 0;
    while (*s >= '0' && *s <= '9') {
        unsigned d = (unsigned)(*s - '0');
        if (nd < 19) {
            if (m || d) nd++;
            m = m * 10 + d;
        } else {
            exact = 0;
        }
        any = 1;
        s++;
    }
    if (*s == '.') {
        s++;
        while (*s >= '0' && *s <= '9') {
            unsigned d = (unsigned)(*s - '0');
            if (nd < 19) {
                if (m || d) nd++;
                m = m * 10 + d;
                e10--;
            } else {
                exact = 0;
            }
            any = 1;
            s++;
        }
    }
    if (!any) {
        /* nan, inf, infinity (so that callers can reject them by name), or nothing. strtod only
         * for those: it would skip a newline (or \r, \f, \v) and take the next line's first number
         * as this one, reading "v 1 2\n3 ..." as the vertex (1, 2, 3) without an error. */
        if (*s != 'i' && *s != 'I' && *s != 'n' && *s != 'N') return NULL;
        char *end = NULL;
        double v = strtod(start, &end);
        if (end == start) return NULL;
        *out = v;
        return end;
    }
    if (*s == 'e' || *s == 'E') {
        const char *q = s + 1;
        int eneg = 0;
        if (*q == '+' || *q == '-') eneg = *q++ == '-';
        if (*q >= '0' && *q <= '9') {
            long ev = 0;
            while (*q >= '0' && *q <= '9') {
                if (ev < 100000) ev = ev * 10 + (*q - '0');
                q++;
            }
            e10 += eneg ? -ev : ev;
            s = q;
        }
    }
    if (m == 0) {
        *out = neg ? -0.0 : 0.0;
        return s;
    }
    if (exact && m <= (1ull << 53) && e10 >= -22 && e10 <= 22) {
        /* Clinger's fast path: m and 10^|e10| are exact doubles, one rounding. */
        double v = (double)m;
        v = e10 < 0 ? v / pow10_exact[-e10] : v * pow10_exact[e10];
        *out = neg ? -v : v;
        return s;
    }
    char *end = NULL;
    *out = strtod(start, &end);
    return end > start ? end : NULL;
}

const char *acd_parse_int64(const char *p, int64_t *out) {
    while (*p == ' ' || *p == '\t') p++;
    int neg = 0;
    if (*p == '+' || *p == '-') neg = *p++ == '-';
    if (!(*p >= '0' && *p <= '9')) return NULL;
    uint64_t v = 0;
    while (*p >= '0' && *p <= '9') {
        unsigned d = (unsigned)(*p - '0');
        if (v > (UINT64_C(9223372036854775807) - d) / 10) return NULL;
        v = v * 10 + d;
        p++;
    }
    *out = neg ? -(int64_t)v : (int64_t)v;
    return p;
}

/* ---------------------------------------------------------------------------------------- */

void acd_obuf_write(acd_obuf *o, const void *data, size_t n) {
    if (o->failed) return;
    if (o->len + n + 1 > o->cap) {
        size_t cap = o->cap;
        if (!acd_grow((void **)&o->data, &cap, o->len + n + 1, 1)) {
            o->failed = 1;
            return;
        }
        o->cap = cap;
    }
    memcpy(o->data + o->len, data, n);
    o->len += n;
}

void acd_obuf_printf(acd_obuf *o, const char *fmt, ...) {
    char small[256];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(small, sizeof small, fmt, ap);
    va_end(ap);
    if (n < 0) {
        o->failed = 1;
        return;
    }
    if ((size_t)n < sizeof small) {
        acd_obuf_write(o, small, (size_t)n);
        return;
    }
    char *big = malloc((size_t)n + 1);
    if (!big) {
        o->failed = 1;
        return;
    }
    va_start(ap, fmt);
    vsnprintf(big, (size_t)n + 1, fmt, ap);
    va_end(ap);
    acd_obuf_write(o, big, (size_t)n);
    free(big);
}

void acd_obuf_double(acd_obuf *o, double v) {
    char s[40];
    int n = snprintf(s, sizeof s, "%.17g", v);
    acd_obuf_write(o, s, (size_t)n);
}

void acd_obuf_u64(acd_obuf *o, uint64_t v) {
    char s[24];
    int i = 24;
    do {
        s[--i] = (char)('0' + v % 10);
        v /= 10;
    } while (v);
    acd_obuf_write(o, s + i, (size_t)(24 - i));
}

acd_status acd_builder_fan_or_fail(acd_mesh_builder *b, const char *name, size_t line, acd_error *err) {
    size_t n = b->npoly;
    int r = acd_builder_fan(b);
    if (r > 0) return ACD_OK;
    if (r == 0) {
        if (line) return acd_fail(err, ACD_ERR_NOMEM, "%s:%zu: out of memory", name, line);
        return acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory", name);
    }
    b->npoly = 0;
    if (line)
        return acd_fail(err, ACD_ERR_UNSUPPORTED,
                        "%s:%zu: a face of %zu corners is not convex and too large to triangulate (ear clipping, "
                        "quadratic in time, is limited to %d corners): split it into smaller faces",
                        name, line, n, ACD_MESH_EARCLIP_MAX_CORNERS);
    return acd_fail(err, ACD_ERR_UNSUPPORTED,
                    "%s: a face of %zu corners is not convex and too large to triangulate (ear clipping, quadratic in "
                    "time, is limited to %d corners): split it into smaller faces",
                    name, n, ACD_MESH_EARCLIP_MAX_CORNERS);
}
