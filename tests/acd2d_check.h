/* Shared checks for the acd2d tests (included by tests/test_acd2d_*.c; header-only, static). */
#ifndef ACD_TESTS_ACD2D_CHECK_H
#define ACD_TESTS_ACD2D_CHECK_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "acd/acd2d.h"
#include "core/predicates.h"

static double ck_ring_area(const acd_vec2 *p, size_t n) {
    double s = 0;
    for (size_t i = 1; i + 1 < n; i++)
        s += (p[i].x - p[0].x) * (p[i + 1].y - p[0].y) - (p[i].y - p[0].y) * (p[i + 1].x - p[0].x);
    return 0.5 * s;
}

/* simple: no two non-adjacent edges meet, adjacent edges meet only at their shared vertex */
static int ck_simple(const acd_vec2 *p, size_t n) {
    if (n < 3) return 0;
    for (size_t i = 0; i < n; i++) {
        const double a0[2] = {p[i].x, p[i].y}, a1[2] = {p[(i + 1) % n].x, p[(i + 1) % n].y};
        if (a0[0] == a1[0] && a0[1] == a1[1]) return 0;
        for (size_t j = i + 1; j < n; j++) {
            const double b0[2] = {p[j].x, p[j].y}, b1[2] = {p[(j + 1) % n].x, p[(j + 1) % n].y};
            acd_seg_relation rel = acd_segments_relation(a0, a1, b0, b1);
            int adjacent = (j == i + 1) || (i == 0 && j == n - 1);
            if (adjacent) {
                if (rel == ACD_SEG_OVERLAP || rel == ACD_SEG_PROPER) return 0;
                if (n == 3) continue;
                /* the far endpoints must not touch the other edge */
                const double *far = (j == i + 1) ? b1 : b0;
                const double *far2 = (j == i + 1) ? a0 : a1;
                if (acd_point_on_segment(far, a0, a1) || acd_point_on_segment(far2, b0, b1)) return 0;
            } else if (rel != ACD_SEG_DISJOINT) {
                return 0;
            }
        }
    }
    return 1;
}

/* Checks a result: every component CCW simple with concavity <= tau (recomputed), areas add up,
 * hulls contain their components. Returns 0 when all holds, else prints and returns 1. */
static int ck_result(const acd2d_result *res, const acd2d_params *prm, double poly_area, int check_simple) {
    double sum = 0;
    acd2d_params p2 = *prm;
    p2.normalize = 0;
    p2.tau = res->tau;
    for (size_t i = 0; i < res->ncomponents; i++) {
        const acd2d_component *c = &res->components[i];
        double a = ck_ring_area(c->points, c->npoints);
        if (!(a > 0)) { printf("component %zu: area %g not positive\n", i, a); return 1; }
        if (check_simple && !ck_simple(c->points, c->npoints)) { printf("component %zu not simple\n", i); return 1; }
        double cc = acd2d_concavity_params(c->points, c->npoints, &p2, NULL);
        if (cc > res->tau + 1e-9 * (1 + res->tau)) {
            printf("component %zu: concavity %.17g > tau %g\n", i, cc, res->tau);
            return 1;
        }
        if (fabs(cc - c->concavity) > 1e-9 * (1 + cc)) {
            printf("component %zu: stored concavity %.17g, recomputed %.17g\n", i, c->concavity, cc);
            return 1;
        }
        for (size_t k = 0; k < c->npoints; k++)
            for (size_t h = 0; h < c->nhull; h++) {
                const double A[2] = {c->hull[h].x, c->hull[h].y};
                const double B[2] = {c->hull[(h + 1) % c->nhull].x, c->hull[(h + 1) % c->nhull].y};
                const double P[2] = {c->points[k].x, c->points[k].y};
                if (acd_orient2d_sign(A, B, P) < 0) { printf("component %zu: point outside hull\n", i); return 1; }
            }
        sum += a;
    }
    if (fabs(sum - poly_area) > 1e-9 * fabs(poly_area)) {
        printf("areas: components %.17g, polygon %.17g\n", sum, poly_area);
        return 1;
    }
    return 0;
}

#endif
