/* acd/exact2d.h: exact convex decompositions of polygons, the baselines the dissertation compares
 * ACD against (Lien, Ch. IV.D, Table 3; spec ../shared/spec/acd2d.md §7).
 *
 *   ACD_EXACT2D_MCD  minimum convex decomposition without Steiner points (Keil & Snoeyink,
 *                    "On the time bound for convex decomposition of simple polygons", 2002):
 *                    polygons without holes only.
 *   ACD_EXACT2D_HM   Hertel-Mehlhorn: triangulate, then drop every diagonal whose removal keeps
 *                    both merged pieces convex; at most 4 times the minimum; works with holes.
 *
 * Usage:
 *   acd_exact2d_result res;
 *   if (acd_exact2d_decompose(&poly, ACD_EXACT2D_MCD, &res, &err) == ACD_OK) {
 *       for (size_t i = 0; i < res.npieces; i++) use(res.pieces[i].points, res.pieces[i].npoints);
 *       acd_exact2d_result_free(&res);
 *   }
 */
#ifndef ACD_EXACT2D_H
#define ACD_EXACT2D_H

#include "acd/base.h"
#include "acd/polygon.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum acd_exact2d_method {
    ACD_EXACT2D_MCD = 0, /* minimum convex decomposition, no Steiner points, no holes */
    ACD_EXACT2D_HM = 1   /* Hertel-Mehlhorn over an ear-clipping triangulation, holes allowed */
} acd_exact2d_method;

/* One convex piece: a counterclockwise polygon whose vertices are input vertices (no Steiner
 * points). Collinear input vertices may appear as 180-degree vertices of a piece. */
typedef struct acd_exact2d_piece {
    acd_vec2 *points; /* npoints points, counterclockwise, first not repeated */
    size_t *index;    /* index of each point in the input polygon's point array */
    size_t npoints;
} acd_exact2d_piece;

typedef struct acd_exact2d_result {
    acd_exact2d_method method;
    size_t input_vertices, input_notches, input_holes; /* notches: reflex vertices, exact orient2d */
    acd_exact2d_piece *pieces;
    size_t npieces;
    size_t (*diagonals)[2]; /* the cuts, as pairs of input point indices */
    size_t ndiagonals;      /* = npieces - 1 + input_holes */
    double seconds;         /* wall time of the decomposition */
} acd_exact2d_result;

/* "mcd" / "hm"; acd_exact2d_method_parse returns 1 on success. */
const char *acd_exact2d_method_name(acd_exact2d_method m);
int acd_exact2d_method_parse(const char *name, acd_exact2d_method *out);

/* Decomposes one polygon (it should pass acd_polygon_validate; the rings may have either
 * orientation). The result is checked before it is returned (pieces convex by exact orient2d,
 * areas adding up to the polygon's): input that is not a simple polygon with holes yields an error,
 * never a silently wrong partition. Errors: ACD_ERR_UNSUPPORTED (MCD on a polygon with holes),
 * ACD_ERR_DEGENERATE, ACD_ERR_INVALID_INPUT, ACD_ERR_VERIFY, ACD_ERR_NOMEM. On error *out is
 * zeroed and needs no free. Free a successful result with acd_exact2d_result_free. */
acd_status acd_exact2d_decompose(const acd_polygon *poly, acd_exact2d_method m, acd_exact2d_result *out,
                                 acd_error *err);

void acd_exact2d_result_free(acd_exact2d_result *r);

/* The --verify checks on a result for poly: every piece has >= 3 vertices, all input vertices
 * (index and coordinates agree), is convex (no clockwise turn, exact orient2d, and not all
 * collinear), and the piece areas add up to the polygon's area (relative tolerance
 * ACD_TOL_REL_MEASURE); every diagonal joins two input vertices. ACD_ERR_VERIFY with a message naming
 * the piece and vertex otherwise. */
acd_status acd_exact2d_verify(const acd_polygon *poly, const acd_exact2d_result *r, acd_error *err);

#ifdef __cplusplus
}
#endif
#endif
