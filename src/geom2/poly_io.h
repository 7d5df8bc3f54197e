/* geom2/poly_io: reader of J.-M. Lien's ".poly" polygon files (the acd2d test_env format,
 * spec acd2d.md §8).
 *
 *   <number of chains>
 *   <N> out|in          one header per chain
 *   x y                 N points (numbers scanned strtod-style: "-6.64248.788605" is two numbers)
 *   p1 p2 ... pN        the vertex order, a permutation of 1..N
 *
 * '#' starts a comment anywhere. An "in" chain is a hole of the most recent "out" chain; every
 * "out" chain starts a new polygon. Well-formed chains beyond the declared number are read
 * and ignored (counted in *chains_ignored), as the reference reader does. */
#ifndef ACD_GEOM2_POLY_IO_H
#define ACD_GEOM2_POLY_IO_H

#include "acd/polygon.h"

/* Parses len bytes of .poly text into out (not normalized). `name` prefixes messages, which
 * name the line, the chain and the point. */
acd_status acd_poly_parse(acd_polygon_set *out, const char *text, size_t len, const char *name,
                          size_t *chains_ignored, acd_error *err);

#endif
