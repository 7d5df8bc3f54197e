/* corise/segio: reading and writing face segmentations in the Princeton Segmentation Benchmark's
 * .seg format (Chen, Golovinskiy, Funkhouser 2009): one integer label per face, in the mesh's
 * face order, one per line. Labels are arbitrary integers (any value in int range, negatives
 * allowed): they name segments, their values carry no meaning.
 *
 * Accepted: leading/trailing blanks on a line, CRLF line ends, blank lines (skipped), a missing
 * final newline. Refused with the file name and line number: anything that is not exactly one
 * decimal integer on a line (e.g. "1.5", "x", "1 2"), values outside int range, and (when a
 * face count is expected) a label count that differs from it. */
#ifndef ACD_CORISE_SEGIO_H
#define ACD_CORISE_SEGIO_H

#include <stddef.h>

#include "acd/base.h"

/* Pass as `expected` when any number of labels is acceptable. */
#define ACD_SEG_ANY_COUNT ((size_t)-1)

/* Parses .seg text (len bytes, need not be NUL-terminated; NUL bytes are an error). name is used
 * in messages (NULL: "<seg>"). *labels is malloc'd (caller frees; NULL when *n == 0). */
acd_status acd_seg_parse(const char *text, size_t len, const char *name, size_t expected, int **labels,
                         size_t *n, acd_error *err);

/* Reads a .seg file (see acd_seg_parse). An unreadable file is ACD_ERR_IO. */
acd_status acd_seg_read(const char *path, size_t expected, int **labels, size_t *n, acd_error *err);

/* Writes labels[0..n) as a .seg file, one per line. */
acd_status acd_seg_write(const char *path, const int *labels, size_t n, acd_error *err);

#endif
