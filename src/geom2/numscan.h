/* geom2/numscan: strict decimal number scanning for the 2D text readers (.poly, WKT).
 *
 * Numbers are scanned strtod-style (the longest prefix that forms a number), so run-together
 * tokens such as "-6.64248.788605" read as -6.64248 then .788605, as Lien's .poly files need.
 * Only plain decimal syntax is accepted: [+-] digits [. digits] [(e|E) [+-] digits], with at
 * least one mantissa digit. "nan", "inf", hexadecimal floats and locale decimal commas are not
 * numbers here; values that overflow to infinity are reported as out of range. */
#ifndef ACD_GEOM2_NUMSCAN_H
#define ACD_GEOM2_NUMSCAN_H

#include <stddef.h>

/* A cursor over text of known length (the text need not be NUL-terminated). */
typedef struct acd_scan {
    const char *text;
    size_t len;
    size_t pos;
    size_t line; /* 1-based line of pos */
} acd_scan;

void acd_scan_init(acd_scan *s, const char *text, size_t len);

/* Skips spaces, tabs, CR, LF, and (if hash_comments) '#' comments to the end of the line. */
void acd_scan_skip_space(acd_scan *s, int hash_comments);

/* Results of acd_scan_number. */
typedef enum acd_scan_result {
    ACD_SCAN_OK = 0,
    ACD_SCAN_NONE,     /* no number at the cursor (cursor unchanged) */
    ACD_SCAN_RANGE,    /* syntactically a number but not finite as a double (cursor unchanged) */
    ACD_SCAN_TOO_LONG  /* a number of more than ACD_SCAN_MAX_DIGITS characters (cursor unchanged) */
} acd_scan_result;

#define ACD_SCAN_MAX_DIGITS 400

/* Reads one decimal number at the cursor (no leading space skipping). */
acd_scan_result acd_scan_number(acd_scan *s, double *value);

/* Reads an unsigned decimal integer (digits only, optional '+'), at most max_value. Returns
 * ACD_SCAN_NONE if there are no digits and ACD_SCAN_RANGE if the value exceeds max_value
 * or is followed by '.', 'e' or 'E' (not an integer); the cursor is then unchanged. */
acd_scan_result acd_scan_uint(acd_scan *s, size_t max_value, size_t *value);

/* Copies up to 24 printable characters at the cursor into buf (for "found '...'" messages);
 * "end of input" at the end. buf must hold at least 32 bytes. */
const char *acd_scan_excerpt(const acd_scan *s, char *buf, size_t size);

static inline int acd_scan_eof(const acd_scan *s) {
    return s->pos >= s->len;
}
static inline int acd_scan_peek(const acd_scan *s) {
    return s->pos < s->len ? (unsigned char)s->text[s->pos] : -1;
}

#endif
