/* acd3/knots: Douglas-Peucker in concavity space and knot extraction; see knots.h. */
#include "acd3/knots.h"

#include <math.h>
#include <stdlib.h>

#include "core/predicates.h"

/* Distance from (px,py) to the segment (ax,ay)-(bx,by). */
static double seg_dist(double px, double py, double ax, double ay, double bx, double by) {
    double dx = bx - ax, dy = by - ay;
    double l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / l2 : 0.0;
    if (t < 0) t = 0;
    if (t > 1) t = 1;
    double qx = ax + t * dx - px, qy = ay + t * dy - py;
    return sqrt(qx * qx + qy * qy);
}

int acd3_douglas_peucker(const double *x, const double *y, size_t m, double delta, unsigned char *keep) {
    for (size_t i = 0; i < m; i++) keep[i] = 0;
    if (m == 0) return 1;
    keep[0] = keep[m - 1] = 1;
    if (m < 3) return 1;
    size_t *stack = malloc(2 * m * sizeof *stack);
    if (!stack) return 0;
    size_t sp = 0;
    stack[sp++] = 0;
    stack[sp++] = m - 1;
    while (sp) {
        size_t j = stack[--sp], i = stack[--sp];
        if (j <= i + 1) continue;
        size_t best = i;
        double bd = -1.0;
        for (size_t k = i + 1; k < j; k++) {
            double d = seg_dist(x[k], y[k], x[i], y[i], x[j], y[j]);
            if (d > bd) {
                bd = d;
                best = k;
            }
        }
        if (bd > delta) {
            keep[best] = 1;
            stack[sp++] = i;
            stack[sp++] = best;
            stack[sp++] = best;
            stack[sp++] = j;
        }
    }
    free(stack);
    return 1;
}

size_t acd3_find_knots(const double *pts, const double *conc, size_t m, double edge_length, double delta,
                       uint32_t *knots) {
    if (m < 3) return 0;
    double *x = malloc(m * sizeof *x);
    unsigned char *keep = malloc(m);
    if (!x || !keep) {
        free(x), free(keep);
        return (size_t)-1;
    }
    /* normalized cumulative arc length times |e| */
    x[0] = 0.0;
    for (size_t i = 1; i < m; i++) {
        const double *a = pts + 3 * (i - 1), *b = pts + 3 * i;
        double d0 = b[0] - a[0], d1 = b[1] - a[1], d2 = b[2] - a[2];
        x[i] = x[i - 1] + sqrt(d0 * d0 + d1 * d1 + d2 * d2);
    }
    double total = x[m - 1];
    for (size_t i = 0; i < m; i++) x[i] = total > 0 ? x[i] / total * edge_length : 0.0;
    size_t nk = 0;
    if (!acd3_douglas_peucker(x, conc, m, delta, keep)) {
        nk = (size_t)-1;
        goto done;
    }
    size_t prev = 0;
    for (size_t i = 1; i + 1 < m; i++) {
        if (!keep[i]) continue;
        size_t next = i + 1;
        while (!keep[next]) next++;
        double a[2] = {x[prev], conc[prev]}, v[2] = {x[i], conc[i]}, b[2] = {x[next], conc[next]};
        if (conc[i] > delta && acd_orient2d_sign(a, v, b) < 0) knots[nk++] = (uint32_t)i;
        prev = i;
    }
done:
    free(x), free(keep);
    return nk;
}
