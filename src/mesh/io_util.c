/* mesh/io_util: mesh builder, text cursor with fast number parsing, output buffer. */
#include "mesh/io_util.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

int acd_builder_fan(acd_mesh_builder *b) {
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
    while (*p == ' ' || *p == '\t') p++;
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
        /* nan, inf, infinity (so that callers can reject them by name), or nothing */
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
