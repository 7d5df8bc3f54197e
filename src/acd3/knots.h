/* acd3/knots: knots of a projected hull edge, found by Douglas-Peucker simplification in
 * concavity space (dissertation §V.B.2.b, Alg. 7, Eqn 5.1, Fig. 40; paper §4.2.1, Eqn 3;
 * spec acd3d.md §4.2).
 *
 * A projected edge p_0..p_m (p_0, p_m hull vertices) maps to the polyline
 * (d_i, concavity(p_i)) with d_i the normalized cumulative arc length times the hull edge's
 * length |e|. The polyline is simplified by Douglas-Peucker at threshold delta; a knot is a kept
 * interior vertex where the simplified chain turns clockwise (a peak of concavity, like a
 * reflex vertex of a 2D pocket) and whose concavity exceeds delta. */
#ifndef ACD_ACD3_KNOTS_H
#define ACD_ACD3_KNOTS_H

#include <stddef.h>
#include <stdint.h>

/* pts: m points (3 doubles each) of the path; conc: their concavities; edge_length: |e|.
 * Writes the indices of the knots (increasing) to knots (capacity m) and returns their count,
 * or (size_t)-1 on allocation failure. */
size_t acd3_find_knots(const double *pts, const double *conc, size_t m, double edge_length, double delta,
                       uint32_t *knots);

/* Douglas-Peucker on a 2D polyline (x_i, y_i), i < m: keep[i] = 1 for the kept vertices
 * (endpoints always). Iterative (no recursion depth limit). Returns 0 on allocation failure. */
int acd3_douglas_peucker(const double *x, const double *y, size_t m, double delta, unsigned char *keep);

#endif
