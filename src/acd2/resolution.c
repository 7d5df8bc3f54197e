/* acd2/resolution: refusing far-from-origin input whose coordinates cannot resolve its features
 * (see resolution.h). A sweep over x with the edges' boxes grown by the distance sought. */
#include "acd2/resolution.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/error.h"
#include "core/tolerance.h"
#include "geom2/seg_dist.h"

typedef struct edge_ref {
    double x0, x1;
    size_t a, b; /* point indices */
} edge_ref;

static int cmp_edge(const void *p, const void *q) {
    const edge_ref *a = p, *b = q;
    return (a->x0 > b->x0) - (a->x0 < b->x0);
}

typedef struct vertex_ref {
    double x;
    size_t i;
} vertex_ref;

static int cmp_vertex(const void *p, const void *q) {
    const vertex_ref *a = p, *b = q;
    if (a->x != b->x) return (a->x > b->x) - (a->x < b->x);
    return (a->i > b->i) - (a->i < b->i);
}

static size_t ring_of(const acd_polygon *p, size_t i) {
    size_t r = 0;
    while (r + 1 < p->nrings && p->ring_start[r + 1] <= i) r++;
    return r;
}

acd_status acd2_check_resolution(const acd_polygon *p, acd_error *err) {
    size_t n = acd_polygon_num_points(p);
    if (n == 0) return ACD_OK;
    double m = 0;
    for (size_t i = 0; i < n; i++) m = fmax(m, fmax(fabs(p->points[i].x), fabs(p->points[i].y)));
    acd_scale sc = acd_scale_of_points(&p->points[0].x, n, 2);
    double D = ACD2_RESOLVE_ULPS * DBL_EPSILON * m;
    if (D <= sc.dist) return ACD_OK;
    edge_ref *es = malloc(n * sizeof *es);
    vertex_ref *vs = malloc(n * sizeof *vs);
    size_t *act = malloc(n * sizeof *act);
    if (!es || !vs || !act) {
        free(es); free(vs); free(act);
        return acd_fail(err, ACD_ERR_NOMEM, "acd2d: out of memory checking the coordinates' resolution");
    }
    acd_status st = ACD_OK;
    size_t bad_v = SIZE_MAX, bad_a = 0, bad_b = 0;
    int short_edge = 0;
    double bad_d = 0;
    for (size_t r = 0; r < p->nrings && bad_v == SIZE_MAX; r++) {
        size_t s = p->ring_start[r], e = p->ring_start[r + 1];
        for (size_t i = s; i < e; i++) {
            size_t j = i + 1 == e ? s : i + 1;
            acd_vec2 a = p->points[i], b = p->points[j];
            es[i] = (edge_ref){fmin(a.x, b.x) - D, fmax(a.x, b.x) + D, i, j};
            double l = hypot(b.x - a.x, b.y - a.y);
            if (l < D && bad_v == SIZE_MAX) {
                bad_v = j; bad_a = i; bad_b = j; bad_d = l;
                short_edge = 1;
            }
        }
    }
    if (bad_v == SIZE_MAX) {
        qsort(es, n, sizeof *es, cmp_edge);
        for (size_t i = 0; i < n; i++) vs[i] = (vertex_ref){p->points[i].x, i};
        qsort(vs, n, sizeof *vs, cmp_vertex);
        size_t next = 0, na = 0;
        for (size_t k = 0; k < n && bad_v == SIZE_MAX; k++) {
            size_t v = vs[k].i;
            acd_vec2 q = p->points[v];
            while (next < n && es[next].x0 <= q.x) act[na++] = next++;
            for (size_t t = 0; t < na && bad_v == SIZE_MAX;) {
                const edge_ref *ed = &es[act[t]];
                if (ed->x1 < q.x) { act[t] = act[--na]; continue; }
                t++;
                if (ed->a == v || ed->b == v) continue;
                acd_vec2 a = p->points[ed->a], b = p->points[ed->b];
                if (q.y < fmin(a.y, b.y) - D || q.y > fmax(a.y, b.y) + D) continue;
                double d = acd_seg_dist2(q, a, b);
                if (d < D) {
                    bad_v = v; bad_a = ed->a; bad_b = ed->b; bad_d = d;
                }
            }
        }
    }
    if (bad_v != SIZE_MAX) {
        size_t rv = ring_of(p, bad_v), re = ring_of(p, bad_a);
        acd_vec2 q = p->points[bad_v];
        double ulp = DBL_EPSILON * m;
        char what[200];
        if (short_edge)
            snprintf(what, sizeof what, "edge %zu-%zu of chain %zu, ending at (%.17g, %.17g), is %.3g long",
                     bad_a - p->ring_start[re], bad_b - p->ring_start[re], re, q.x, q.y, bad_d);
        else
            snprintf(what, sizeof what, "vertex %zu of chain %zu (%.17g, %.17g) is %.3g from edge %zu-%zu of chain %zu",
                     bad_v - p->ring_start[rv], rv, q.x, q.y, bad_d, bad_a - p->ring_start[re],
                     bad_b - p->ring_start[re], re);
        st = acd_fail(err, ACD_ERR_DEGENERATE,
                      "acd2d: the coordinates cannot resolve a feature: %s, only %.3g times the rounding %.3g of "
                      "coordinates of magnitude %.3g (%.3g times the polygon's extent %.3g; at least %g times is "
                      "needed): cut points would be rounded across it. Translate the polygon nearer the origin",
                      what, bad_d / ulp, ulp, m, m / sc.extent, sc.extent, ACD2_RESOLVE_ULPS);
    }
    free(es);
    free(vs);
    free(act);
    return st;
}
