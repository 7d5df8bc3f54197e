/* mesh/io_util: building blocks shared by the mesh readers and writers: a mesh builder with
 * growable arrays and o/g groups, a text cursor with line numbers and fast number parsing, and a
 * growable output buffer. Internal. */
#ifndef ACD_MESH_IO_UTIL_H
#define ACD_MESH_IO_UTIL_H

#include <stddef.h>
#include <stdint.h>

#include "acd/mesh.h"

/* A mesh under construction, with the triangle ranges of OBJ groups. */
typedef struct acd_mesh_group {
    char *name;
    size_t first_triangle;
} acd_mesh_group;

typedef struct acd_mesh_builder {
    double *v;
    size_t nv, vcap;        /* vertices (3 doubles each) */
    uint32_t *t;
    size_t nt, tcap;        /* triangles (3 indices each) */
    acd_mesh_group *groups; /* OBJ o/g statements, in file order */
    size_t ngroups, gcap;
    uint32_t *poly;         /* scratch polygon indices */
    size_t npoly, polycap;
    acd_warning_fn warn;    /* optional (acd_mesh_read_options): told what a reader skipped */
    void *warn_user;
} acd_mesh_builder;

void acd_builder_free(acd_mesh_builder *b);
/* Each returns 0 when out of memory (or beyond the 2^32-1 vertex limit). */
int acd_builder_vertex(acd_mesh_builder *b, double x, double y, double z);
int acd_builder_triangle(acd_mesh_builder *b, uint32_t a, uint32_t c, uint32_t d);
int acd_builder_group(acd_mesh_builder *b, const char *name, size_t len);
/* Pushes one polygon index to the scratch polygon; acd_builder_fan emits it as triangles and
 * clears it: a fan (v0, vi, vi+1) when the polygon is convex in its plane (or its vertices are
 * not read yet, or it is not simple in projection), ear clipping otherwise (no overlapping
 * triangles from a non-convex face). */
int acd_builder_poly_push(acd_mesh_builder *b, uint32_t i);
/* Non-convex polygons of more corners than this are refused (ear clipping is quadratic: 10000
 * corners take about 2 s, 200000 would take many minutes). */
#define ACD_MESH_EARCLIP_MAX_CORNERS 10000
/* 1 done, 0 out of memory, -1 a non-convex polygon beyond ACD_MESH_EARCLIP_MAX_CORNERS. */
int acd_builder_fan(acd_mesh_builder *b);
/* acd_builder_fan with the failures as messages ("NAME:LINE: ..."; line 0: no line). */
acd_status acd_builder_fan_or_fail(acd_mesh_builder *b, const char *name, size_t line, acd_error *err);
/* Moves the arrays into out (shrinks them); b is left empty except for groups. */
void acd_builder_take_mesh(acd_mesh_builder *b, acd_mesh *out);

/* Grows *p (elements of size elem) to hold at least need elements; 0 on failure. */
int acd_grow(void **p, size_t *cap, size_t need, size_t elem);

/* Text cursor: buf is NUL-terminated at end. */
typedef struct acd_text {
    const char *p, *end;
    size_t line;      /* 1-based line of p */
    const char *name; /* file name for messages */
} acd_text;

/* Skips spaces, tabs, \r, \f, \v (not newlines). */
static inline void acd_text_skip_blank(acd_text *t) {
    while (*t->p == ' ' || *t->p == '\t' || *t->p == '\r' || *t->p == '\f' || *t->p == '\v') t->p++;
}
/* Moves past the next newline (or to the end). */
void acd_text_next_line(acd_text *t);
/* Skips whitespace including newlines (counting lines) and '#' comments when comments != 0. */
void acd_text_skip_space(acd_text *t, int comments);
/* True at end of line (newline, NUL or, with comments, '#'), after skipping blanks. */
int acd_text_at_eol(acd_text *t, int comments);

/* Parses a decimal floating-point number at p (after optional blanks: space, tab, \r, \f, \v; never
 * a newline, so a number is never taken from the next line); returns the end of the number or NULL
 * if there is none. Correctly rounded (fast path for short decimals, strtod
 * otherwise). Accepts nan/inf spellings so the caller can reject them by name. */
const char *acd_parse_double(const char *p, double *out);
/* Parses an optionally signed decimal integer; NULL if none or it overflows int64. */
const char *acd_parse_int64(const char *p, int64_t *out);

/* Growable output buffer; on allocation failure it sets failed and drops further output. */
typedef struct acd_obuf {
    char *data;
    size_t len, cap;
    int failed;
} acd_obuf;
void acd_obuf_write(acd_obuf *o, const void *data, size_t n);
void acd_obuf_printf(acd_obuf *o, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Appends "%.17g" of v (shortest exact text is not attempted: 17 digits always round-trip). */
void acd_obuf_double(acd_obuf *o, double v);
void acd_obuf_u64(acd_obuf *o, uint64_t v);

#endif
