/* acd2/hybrid: hazard test of H1/H2 (Lien dissertation IV.A.1.c, Obs. A.5, Algs. 3-4, Fig. 18).
 *
 * The outward normal of a directed edge d is (d.y, -d.x); the dot product of two such normals
 * equals the dot product of the edge directions, so the test compares edge directions with the
 * bridge direction. This is a switch between two valid measures, not a topological decision;
 * it is evaluated in double precision on coordinate differences. */
#include "acd2/hybrid.h"

#include "acd2/ring.h"

int acd2_pocket_hazard(const acd_vec2 *p, size_t n, size_t a, size_t b) {
    double bx = p[b].x - p[a].x, by = p[b].y - p[a].y;
    for (size_t k = a; k != b; k = acd2_next(k, n)) {
        size_t k2 = acd2_next(k, n);
        double ex = p[k2].x - p[k].x, ey = p[k2].y - p[k].y;
        if (ex * bx + ey * by < 0) return 1;
    }
    return 0;
}
