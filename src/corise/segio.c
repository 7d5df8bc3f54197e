/* corise/segio: .seg files of the Princeton Segmentation Benchmark (Chen, Golovinskiy,
 * Funkhouser, "A benchmark for 3D mesh segmentation", SIGGRAPH 2009, data format of its
 * distribution): one integer label per face, one per line, in face order. */
#include "corise/segio.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

static int is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

acd_status acd_seg_parse(const char *text, size_t len, const char *name, size_t expected, int **labels,
                         size_t *n, acd_error *err) {
    if (!labels || !n || (!text && len)) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "seg: NULL argument");
    *labels = NULL;
    *n = 0;
    if (!name) name = "<seg>";
    int *out = NULL;
    size_t cnt = 0, cap = 0, line = 1;
    const char *p = text, *end = text + len;
    while (p < end) {
        const char *eol = memchr(p, '\n', (size_t)(end - p));
        if (!eol) eol = end;
        const char *q = p;
        while (q < eol && is_blank(*q)) q++;
        const char *e = eol;
        while (e > q && is_blank(e[-1])) e--;
        if (q < e) {
            /* exactly one integer: optional sign, digits */
            const char *d = q;
            int neg = 0;
            if (*d == '+' || *d == '-') neg = *d++ == '-';
            const char *digits = d;
            long long v = 0;
            int overflow = 0;
            while (d < e && *d >= '0' && *d <= '9') {
                if (v > (LLONG_MAX - 9) / 10)
                    overflow = 1;
                else
                    v = 10 * v + (*d - '0');
                d++;
            }
            if (d == digits || d != e) {
                int shown = (int)(e - q < 40 ? e - q : 40);
                char buf[48];
                memcpy(buf, q, (size_t)shown);
                buf[shown] = '\0';
                for (int k = 0; k < shown; k++)
                    if ((unsigned char)buf[k] < 32 || (unsigned char)buf[k] > 126) buf[k] = '?';
                free(out);
                const char *why = (d == digits) ? "is not an integer label"
                                  : (memchr(d, ' ', (size_t)(e - d)) || memchr(d, '\t', (size_t)(e - d)))
                                      ? "holds more than one value (one label per line)"
                                      : "is not an integer label";
                return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: '%s' %s", name, line, buf, why);
            }
            if (neg) v = -v;
            if (overflow || v > INT_MAX || v < INT_MIN) {
                free(out);
                return acd_fail(err, ACD_ERR_PARSE, "%s:%zu: label '%.*s' is outside the range [%d, %d]", name, line,
                                (int)(e - q < 40 ? e - q : 40), q, INT_MIN, INT_MAX);
            }
            if (cnt == cap) {
                size_t nc = cap ? 2 * cap : 1024;
                int *np = realloc(out, nc * sizeof *np);
                if (!np) {
                    free(out);
                    return acd_fail(err, ACD_ERR_NOMEM, "%s:%zu: out of memory reading labels", name, line);
                }
                out = np;
                cap = nc;
            }
            out[cnt++] = (int)v;
        }
        p = eol < end ? eol + 1 : end;
        line++;
    }
    if (expected != ACD_SEG_ANY_COUNT && cnt != expected) {
        free(out);
        return acd_fail(err, ACD_ERR_INVALID_INPUT, "%s: %zu labels, but the mesh has %zu faces (one label per face)",
                        name, cnt, expected);
    }
    *labels = out;
    *n = cnt;
    return ACD_OK;
}

acd_status acd_seg_read(const char *path, size_t expected, int **labels, size_t *n, acd_error *err) {
    if (!path || !labels || !n) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "seg: NULL argument");
    *labels = NULL;
    *n = 0;
    FILE *f = fopen(path, "rb");
    if (!f) return acd_fail(err, ACD_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    char *buf = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (cap - len < 65536) {
            size_t nc = cap ? 2 * cap : 65536;
            char *nb = realloc(buf, nc);
            if (!nb) {
                free(buf);
                fclose(f);
                return acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory reading the file", path);
            }
            buf = nb;
            cap = nc;
        }
        size_t got = fread(buf + len, 1, cap - len, f);
        len += got;
        if (got == 0) break;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        return acd_fail(err, ACD_ERR_IO, "%s: read error", path);
    }
    acd_status s = acd_seg_parse(buf, len, path, expected, labels, n, err);
    free(buf);
    return s;
}

acd_status acd_seg_write(const char *path, const int *labels, size_t n, acd_error *err) {
    if (!path || (!labels && n)) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "seg: NULL argument");
    FILE *f = fopen(path, "wb");
    if (!f) return acd_fail(err, ACD_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
    for (size_t i = 0; i < n; i++)
        if (fprintf(f, "%d\n", labels[i]) < 0) break;
    int bad = ferror(f);
    if (fclose(f) != 0) bad = 1;
    if (bad) return acd_fail(err, ACD_ERR_IO, "%s: write error", path);
    return ACD_OK;
}
