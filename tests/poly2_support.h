/* Shared helpers of the exact2d / triangulation tests: random polygons with holes, reading
 * Lien's .poly files through the library reader, exact point-in-polygon, and (when
 * acd/exact2d.h is included first) an independent partition check. Header-only, static functions. */
#ifndef ACD_TESTS_POLY2_SUPPORT_H
#define ACD_TESTS_POLY2_SUPPORT_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/polygon.h"
#include "core/predicates.h"
#include "core/rng.h"

#define V2(p) ((const double *)(const void *)(p))

/* Star-shaped polygon around (cx, cy): n vertices at angles (i + u_i 0.8) 2 pi / n (so no gap
 * reaches 2 * 2 pi / n), radii in [rmin, rmax], counterclockwise. */
static inline void p2_random_star(acd_rng *g, acd_vec2 *out, size_t n, double cx, double cy, double rmin,
                                  double rmax) {
    for (size_t i = 0; i < n; i++) {
        double a = 6.283185307179586 * ((double)i + 0.8 * acd_rng_uniform(g)) / (double)n;
        double r = rmin + (rmax - rmin) * acd_rng_uniform(g);
        out[i].x = cx + r * cos(a);
        out[i].y = cy + r * sin(a);
    }
}

/* Random polygon with nholes holes: a star-shaped outer ring of max(n, 8) vertices (radius in
 * [0.8, 1], so it contains the disc of radius 0.56) and holes of 3..hv vertices in distinct cells of a grid inside radius 0.5. Rings are
 * randomly reversed when `mix_orientation` (the triangulator must cope). */
static inline int p2_random_polygon(acd_rng *g, acd_polygon *p, size_t n, size_t nholes, size_t hv,
                                    int mix_orientation) {
    size_t k = 1;
    while (k * k < nholes) k++;
    size_t nrings = 1 + nholes;
    acd_vec2 **rings = calloc(nrings, sizeof *rings);
    size_t *sizes = calloc(nrings, sizeof *sizes);
    if (nholes && n < 8) n = 8;
    sizes[0] = n;
    rings[0] = malloc(n * sizeof(acd_vec2));
    p2_random_star(g, rings[0], n, 0, 0, nholes ? 0.8 : 0.3, 1.0);
    double cell = 0.7 / (double)k;
    for (size_t h = 0; h < nholes; h++) {
        size_t m = 3 + (size_t)acd_rng_below(g, hv > 3 ? hv - 2 : 1);
        sizes[h + 1] = m;
        rings[h + 1] = malloc(m * sizeof(acd_vec2));
        double cx = -0.35 + cell * ((double)(h % k) + 0.5), cy = -0.35 + cell * ((double)(h / k) + 0.5);
        p2_random_star(g, rings[h + 1], m, cx, cy, cell * 0.15, cell * 0.45);
        /* holes clockwise */
        for (size_t i = 0; i < m / 2; i++) {
            acd_vec2 t = rings[h + 1][i];
            rings[h + 1][i] = rings[h + 1][m - 1 - i];
            rings[h + 1][m - 1 - i] = t;
        }
    }
    if (mix_orientation)
        for (size_t r = 0; r < nrings; r++)
            if (acd_rng_below(g, 2))
                for (size_t i = 0; i < sizes[r] / 2; i++) {
                    acd_vec2 t = rings[r][i];
                    rings[r][i] = rings[r][sizes[r] - 1 - i];
                    rings[r][sizes[r] - 1 - i] = t;
                }
    int ok = acd_polygon_from_rings(p, (const acd_vec2 *const *)rings, sizes, nrings, NULL) == ACD_OK;
    for (size_t r = 0; r < nrings; r++) free(rings[r]);
    free(rings);
    free(sizes);
    return ok;
}

/* |area| of the outer ring minus |area| of the holes, whatever the orientations. */
static inline double p2_region_area(const acd_vec2 *pts, const size_t *rs, size_t nrings) {
    double total = 0;
    for (size_t r = 0; r < nrings; r++) {
        double a = 0;
        size_t s = rs[r], n = rs[r + 1] - s;
        for (size_t i = 0; i < n; i++) {
            const acd_vec2 *p = &pts[s + i], *q = &pts[s + (i + 1) % n];
            a += p->x * q->y - q->x * p->y;
        }
        total += r == 0 ? fabs(a) / 2 : -fabs(a) / 2;
    }
    return total;
}

/* Exact even-odd test: 1 if q is strictly inside the region (0 on a boundary or outside). */
static inline int p2_point_inside(const acd_vec2 *pts, const size_t *rs, size_t nrings, const double q[2]) {
    int in = 0;
    for (size_t r = 0; r < nrings; r++) {
        size_t s = rs[r], n = rs[r + 1] - s;
        for (size_t i = 0; i < n; i++) {
            const double *a = V2(&pts[s + i]), *b = V2(&pts[s + (i + 1) % n]);
            if (acd_point_on_segment(q, a, b)) return 0;
            if ((a[1] <= q[1]) != (b[1] <= q[1])) {
                int o = acd_orient2d_sign(a, b, q);
                if ((b[1] > a[1] && o > 0) || (b[1] < a[1] && o < 0)) in ^= 1;
            }
        }
    }
    return in;
}

/* Reads a polygon file with the library reader (acd_polygon_set_read_file) into out[] (at most
 * cap polygons, copied). Returns the number of polygons, or -1 on an error (printed). */
static inline int p2_read_poly(const char *path, acd_polygon *out, int cap) {
    acd_polygon_set set;
    acd_error err;
    if (acd_polygon_set_read_file(&set, path, ACD_POLY_FORMAT_AUTO, NULL, &err) != ACD_OK) {
        printf("%s: %s\n", path, err.message);
        return -1;
    }
    int np = 0;
    for (size_t i = 0; i < set.count && np < cap; i++)
        if (acd_polygon_copy(&out[np], &set.polygons[i]) == ACD_OK) np++;
    acd_polygon_set_free(&set);
    return np;
}

#ifdef ACD_EXACT2D_H
/* Independent partition check of an exact decomposition: every piece made of input vertices,
 * counterclockwise and convex (exact), areas adding up to the region's (1e-9 relative), and the
 * centroid of every piece (sampled for big results) strictly inside the region and inside no other
 * piece (exact). Returns 1 when all hold, printing the first failure otherwise. */
static inline int p2_check_partition(const acd_polygon *p, const acd_exact2d_result *r) {
    size_t n = acd_polygon_num_points(p);
    double area = p2_region_area(p->points, p->ring_start, p->nrings), sum = 0;
    for (size_t i = 0; i < r->npieces; i++) {
        const acd_exact2d_piece *pc = &r->pieces[i];
        if (pc->npoints < 3) return printf("piece %zu: %zu vertices\n", i, pc->npoints), 0;
        double a = 0;
        int pos = 0;
        for (size_t k = 0; k < pc->npoints; k++) {
            if (pc->index[k] >= n || p->points[pc->index[k]].x != pc->points[k].x ||
                p->points[pc->index[k]].y != pc->points[k].y)
                return printf("piece %zu vertex %zu is not an input vertex\n", i, k), 0;
            const acd_vec2 *u = &pc->points[k], *w = &pc->points[(k + 1) % pc->npoints],
                           *x = &pc->points[(k + 2) % pc->npoints];
            int o = acd_orient2d_sign(V2(u), V2(w), V2(x));
            if (o < 0) return printf("piece %zu reflex at %zu\n", i, (k + 1) % pc->npoints), 0;
            pos |= o > 0;
            a += u->x * w->y - w->x * u->y;
        }
        if (!pos) return printf("piece %zu degenerate\n", i), 0;
        sum += a / 2;
    }
    if (fabs(sum - area) > 1e-9 * fabs(area)) return printf("areas %.17g vs %.17g\n", sum, area), 0;
    size_t stride = r->npieces / 400 + 1;
    for (size_t i = 0; i < r->npieces; i += stride) {
        const acd_exact2d_piece *pc = &r->pieces[i];
        /* a point strictly inside the convex piece i: the mean of its vertices */
        double q[2] = {0, 0};
        for (size_t k = 0; k < pc->npoints; k++) {
            q[0] += pc->points[k].x / (double)pc->npoints;
            q[1] += pc->points[k].y / (double)pc->npoints;
        }
        /* slivers: the rounded mean may miss the piece; only test points strictly inside it */
        int inside_own = 1;
        for (size_t k = 0; k < pc->npoints && inside_own; k++)
            if (acd_orient2d_sign(V2(&pc->points[k]), V2(&pc->points[(k + 1) % pc->npoints]), q) <= 0) inside_own = 0;
        if (!inside_own) continue;
        if (!p2_point_inside(p->points, p->ring_start, p->nrings, q))
            return printf("piece %zu centroid (%g, %g) outside the polygon\n", i, q[0], q[1]), 0;
        for (size_t o = 0; o < r->npieces; o++) {
            if (o == i) continue;
            const acd_exact2d_piece *pb = &r->pieces[o];
            int in = 1;
            for (size_t k = 0; k < pb->npoints && in; k++)
                if (acd_orient2d_sign(V2(&pb->points[k]), V2(&pb->points[(k + 1) % pb->npoints]), q) <= 0) in = 0;
            if (in) return printf("piece %zu centroid inside piece %zu\n", i, o), 0;
        }
    }
    return 1;
}
#endif

#endif /* ACD_TESTS_POLY2_SUPPORT_H */
