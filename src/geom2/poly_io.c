/* geom2/poly_io: reader of Lien's .poly files (spec acd2d.md §8; format of jmlien/acd2d
 * test_env, see shared/data/polygons-lien/POLY_FORMAT.txt). */
#include "geom2/poly_io.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "geom2/numscan.h"
#include "geom2/polygon_build.h"

/* Fails with "name:line: message (found '...')". */
#define POLY_FAIL(st, fmt, ...)                                                                      \
    do {                                                                                             \
        char ex_[40];                                                                                \
        status = acd_fail(err, (st), "%s:%zu: " fmt " (found %s)", name, s.line, __VA_ARGS__,        \
                          acd_scan_excerpt(&s, ex_, sizeof ex_));                                    \
        goto done;                                                                                   \
    } while (0)

/* Reads the word at the cursor (letters only) into w; returns its length (0 if none). */
static size_t read_word(acd_scan *s, char *w, size_t size) {
    size_t k = 0;
    while (!acd_scan_eof(s)) {
        int c = acd_scan_peek(s);
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'))) break;
        if (k + 1 < size) w[k] = (char)(c | 0x20);
        k++;
        s->pos++;
    }
    w[k + 1 < size ? k : size - 1] = '\0';
    return k;
}

static const char *scan_problem(acd_scan_result r) {
    switch (r) {
    case ACD_SCAN_RANGE: return ", got a number out of the range of double";
    case ACD_SCAN_TOO_LONG: return ", got a number that is too long";
    default: return " (a decimal number)";
    }
}

acd_status acd_poly_parse(acd_polygon_set *out, const char *text, size_t len, const char *name,
                          size_t *chains_ignored, acd_error *err) {
    acd_status status = ACD_OK;
    acd_pbuild b, extra;
    acd_scan s;
    size_t *perm = NULL;
    unsigned char *seen = NULL;
    acd_vec2 *tmp = NULL;
    memset(out, 0, sizeof *out);
    acd_pbuild_init(&b);
    acd_pbuild_init(&extra);
    if (chains_ignored) *chains_ignored = 0;
    acd_scan_init(&s, text, len);
    if (!name) name = "<input>";

    acd_scan_skip_space(&s, 1);
    size_t nchains = 0;
    acd_scan_result r = acd_scan_uint(&s, SIZE_MAX / 2, &nchains);
    if (r != ACD_SCAN_OK) POLY_FAIL(ACD_ERR_PARSE, "expected the number of chains (a non-negative integer)%s", "");
    if (nchains == 0) POLY_FAIL(ACD_ERR_PARSE, "the file declares 0 chains; at least one 'out' chain is needed%s", "");

    /* Well-formed chains after the declared number are read (so garbage is still an error) and
     * then ignored, as the reference reader does: simple5.poly declares 1 chain and holds 4. */
    for (size_t c = 0;; c++) {
        acd_scan_skip_space(&s, 1);
        if (c >= nchains && acd_scan_eof(&s)) break;
        acd_pbuild *dst = c < nchains ? &b : &extra;
        if (c >= nchains && chains_ignored) (*chains_ignored)++;
        if (acd_scan_eof(&s))
            POLY_FAIL(ACD_ERR_PARSE, "file ends after %zu of the %zu declared chains; expected chain %zu header 'N out|in'",
                      c, nchains, c);
        size_t n = 0;
        r = acd_scan_uint(&s, SIZE_MAX / 2, &n);
        if (r != ACD_SCAN_OK)
            POLY_FAIL(ACD_ERR_PARSE, "chain %zu: expected a header 'N out' or 'N in' with N the number of points", c);
        acd_scan_skip_space(&s, 0);
        char word[8];
        size_t wl = read_word(&s, word, sizeof word);
        int hole;
        if (wl == 3 && strcmp(word, "out") == 0) hole = 0;
        else if (wl == 2 && strcmp(word, "in") == 0) hole = 1;
        else POLY_FAIL(ACD_ERR_PARSE, "chain %zu: expected 'out' or 'in' after the point count %zu", c, n);
        if (n == 0) POLY_FAIL(ACD_ERR_PARSE, "chain %zu declares 0 points%s", c, "");
        /* Each point needs at least 2 number characters and one order entry with a separator,
         * so a count larger than the remaining bytes / 3 cannot be satisfied: refuse it before
         * anything is allocated. */
        size_t remaining = s.len - s.pos;
        if (n > remaining / 3)
            POLY_FAIL(ACD_ERR_PARSE, "chain %zu declares %zu points but only %zu bytes remain in the file", c, n,
                      remaining);
        if (hole && !b.open)
            POLY_FAIL(ACD_ERR_PARSE, "chain %zu is a hole ('in') but no 'out' chain precedes it%s", c, "");
        if (!hole || !dst->open) {
            status = acd_pbuild_begin_polygon(dst, err);
            if (status != ACD_OK) goto done;
        }
        status = acd_pbuild_begin_ring(dst, err);
        if (status != ACD_OK) goto done;
        for (size_t i = 0; i < n; i++) {
            double xy[2];
            for (int k = 0; k < 2; k++) {
                acd_scan_skip_space(&s, 1);
                r = acd_scan_number(&s, &xy[k]);
                if (r != ACD_SCAN_OK)
                    POLY_FAIL(ACD_ERR_PARSE, "chain %zu, point %zu of %zu: expected the %s coordinate%s", c, i + 1, n,
                              k ? "y" : "x", scan_problem(r));
            }
            status = acd_pbuild_add_point(dst, xy[0], xy[1], err);
            if (status != ACD_OK) goto done;
        }
        /* The vertex order: a permutation of 1..n. The points are there, so n is real. */
        free(perm);
        free(seen);
        perm = malloc(n * sizeof *perm);
        seen = calloc(n, 1);
        if (!perm || !seen) {
            status = acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory for the vertex order of chain %zu (%zu points)", name, c, n);
            goto done;
        }
        for (size_t i = 0; i < n; i++) {
            acd_scan_skip_space(&s, 1);
            size_t v = 0, at = s.pos;
            r = acd_scan_uint(&s, SIZE_MAX / 2, &v);
            if (r == ACD_SCAN_OK && (v < 1 || v > n || seen[v - 1])) s.pos = at; /* show the entry */
            if (r != ACD_SCAN_OK || v < 1 || v > n)
                POLY_FAIL(ACD_ERR_PARSE,
                          "chain %zu: vertex order entry %zu of %zu must be an integer in 1..%zu (the order line is a permutation of the point numbers)",
                          c, i + 1, n, n);
            if (seen[v - 1])
                POLY_FAIL(ACD_ERR_PARSE, "chain %zu: vertex order entry %zu repeats point %zu; the order must be a permutation of 1..%zu", c,
                          i + 1, v, n);
            seen[v - 1] = 1;
            perm[i] = v - 1;
        }
        size_t rn = 0;
        acd_vec2 *ring = acd_pbuild_ring(dst, &rn);
        free(tmp);
        tmp = malloc(rn * sizeof *tmp);
        if (!tmp) {
            status = acd_fail(err, ACD_ERR_NOMEM, "%s: out of memory for chain %zu (%zu points)", name, c, n);
            goto done;
        }
        memcpy(tmp, ring, rn * sizeof *tmp);
        for (size_t i = 0; i < rn; i++) ring[i] = tmp[perm[i]];
    }
    status = acd_pbuild_take(&b, out, err);

done:
    free(perm);
    free(seen);
    free(tmp);
    acd_pbuild_free(&b);
    acd_pbuild_free(&extra);
    if (status != ACD_OK) acd_polygon_set_free(out);
    return status;
}
