/* geom2/numscan: strict decimal number scanning (see numscan.h). */
#include "geom2/numscan.h"

#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

void acd_scan_init(acd_scan *s, const char *text, size_t len) {
    s->text = text;
    s->len = len;
    s->pos = 0;
    s->line = 1;
}

void acd_scan_skip_space(acd_scan *s, int hash_comments) {
    while (s->pos < s->len) {
        char c = s->text[s->pos];
        if (c == '\n') {
            s->line++;
            s->pos++;
        } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
            s->pos++;
        } else if (c == '#' && hash_comments) {
            while (s->pos < s->len && s->text[s->pos] != '\n') s->pos++;
        } else {
            break;
        }
    }
}

static int is_digit(int c) {
    return c >= '0' && c <= '9';
}

acd_scan_result acd_scan_number(acd_scan *s, double *value) {
    size_t p = s->pos, n = s->len;
    const char *t = s->text;
    if (p < n && (t[p] == '+' || t[p] == '-')) p++;
    size_t digits = 0;
    while (p < n && is_digit(t[p])) p++, digits++;
    if (p < n && t[p] == '.') {
        p++;
        while (p < n && is_digit(t[p])) p++, digits++;
    }
    if (digits == 0) return ACD_SCAN_NONE;
    if (p < n && (t[p] == 'e' || t[p] == 'E')) {
        size_t q = p + 1;
        if (q < n && (t[q] == '+' || t[q] == '-')) q++;
        if (q < n && is_digit(t[q])) {
            while (q < n && is_digit(t[q])) q++;
            p = q;
        }
        /* else: the 'e' is not part of the number (strtod behaves the same) */
    }
    size_t tl = p - s->pos;
    if (tl > ACD_SCAN_MAX_DIGITS) return ACD_SCAN_TOO_LONG;
    char buf[ACD_SCAN_MAX_DIGITS + 1];
    memcpy(buf, t + s->pos, tl);
    buf[tl] = '\0';
    double v = strtod(buf, NULL);
    if (!isfinite(v)) return ACD_SCAN_RANGE;
    *value = v;
    s->pos = p;
    return ACD_SCAN_OK;
}

acd_scan_result acd_scan_uint(acd_scan *s, size_t max_value, size_t *value) {
    size_t p = s->pos, n = s->len;
    const char *t = s->text;
    if (p < n && t[p] == '+') p++;
    if (p >= n || !is_digit(t[p])) return ACD_SCAN_NONE;
    size_t v = 0;
    int over = 0;
    while (p < n && is_digit(t[p])) {
        size_t d = (size_t)(t[p] - '0');
        if (d > max_value || v > (max_value - d) / 10) over = 1;
        else v = v * 10 + d;
        p++;
    }
    if (over) return ACD_SCAN_RANGE;
    if (p < n && (t[p] == '.' || t[p] == 'e' || t[p] == 'E')) return ACD_SCAN_RANGE;
    *value = v;
    s->pos = p;
    return ACD_SCAN_OK;
}

const char *acd_scan_excerpt(const acd_scan *s, char *buf, size_t size) {
    if (s->pos >= s->len) {
        snprintf(buf, size, "end of input");
        return buf;
    }
    size_t k = 0;
    buf[k++] = '\'';
    for (size_t p = s->pos; p < s->len && k + 6 < size && p - s->pos < 24; p++) {
        unsigned char c = (unsigned char)s->text[p];
        if (c == '\n' || c == '\r') break;
        buf[k++] = (c >= 32 && c < 127) ? (char)c : '?';
    }
    buf[k++] = '\'';
    buf[k] = '\0';
    return buf;
}
