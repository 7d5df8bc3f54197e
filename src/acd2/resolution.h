/* acd2/resolution: can the input's coordinates resolve its features? (far-from-origin input)
 *
 * Cut end points on edges are computed in double precision and rounded to the spacing of doubles
 * at the input's coordinates, up to about DBL_EPSILON x the largest coordinate magnitude M. Near
 * the origin that is far below every tolerance; a polygon of extent 1 translated to 1e10 has a
 * spacing of 2e-6 between doubles. Cut ends are shared exactly between the pieces (decompose.c),
 * so only points on the input's edges stay off by the rounding; that is harmless unless a feature
 * of the input (a vertex near an edge that is not its own, a short edge) is that small. */
#ifndef ACD_ACD2_RESOLUTION_H
#define ACD_ACD2_RESOLUTION_H

#include "acd/base.h"
#include "acd/polygon.h"

/* A point computed on an edge and rounded lies within 0.71 DBL_EPSILON x M of it; a shared point
 * (decompose.c) thus kinks its neighbour's edge by less than ACD2_ROUND_ULPS x DBL_EPSILON x M,
 * which the decomposition (and its readout) take as no concavity. Input notches shallower than
 * that are not resolved far from the origin (the verifier allows 4 x as much). */
#define ACD2_ROUND_ULPS 1.0

/* Features are resolved when no edge is shorter than, and no vertex lies nearer than,
 * ACD2_RESOLVE_ULPS x DBL_EPSILON x M to an edge not incident to it. */
#define ACD2_RESOLVE_ULPS 64.0

/* ACD_OK, or ACD_ERR_DEGENERATE with a message naming the vertex, the edge, the distance and the
 * ratio to the rounding (and the coordinates' magnitude relative to the extent); ACD_ERR_NOMEM.
 * Checks nothing (ACD_OK, O(n)) when that distance is below ACD_TOL_REL_DIST x extent. */
acd_status acd2_check_resolution(const acd_polygon *p, acd_error *err);

#endif
