/* geom3/frame: a local frame for input far from the origin; see frame.h. */
#include "geom3/frame.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void acd_geom3_frame_of(const double *pts, size_t n, acd_frame *f) {
    memset(f, 0, sizeof *f);
    if (!pts || n == 0) return;
    double lo[3], hi[3], big = -1;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            double x = pts[3 * i + k];
            if (!isfinite(x)) return;
            if (i == 0 || x < lo[k]) lo[k] = x;
            if (i == 0 || x > hi[k]) hi[k] = x;
            if (fabs(x) > big) big = fabs(x), f->far_vertex = i;
        }
    double e = 0;
    for (int k = 0; k < 3; k++) e = fmax(e, hi[k] - lo[k]);
    f->extent = e;
    /* the spacing of doubles at the largest magnitude (one ulp; the smallest subnormal at 0) */
    f->spacing = nextafter(big, INFINITY) - big;
    if (!(e > 0) || !isfinite(e)) return;
    int ex;
    (void)frexp(e, &ex);          /* e < 2^ex */
    const double P = ldexp(1.0, ex); /* the power of two above E (E < P <= 2E) */
    for (int k = 0; k < 3; k++) {
        double m = lo[k] + 0.5 * (hi[k] - lo[k]);
        if (!(fabs(m) > ACD_FRAME_NEAR * P)) continue;
        double c = P * nearbyint(m / P); /* m / P and the product are exact (powers of two) */
        /* Sterbenz: x - c exact for every x of the box when c/2 <= x <= 2c (same sign); true by the
         * rule (frame.h), checked rather than assumed */
        int exact = c > 0 ? (lo[k] >= 0.5 * c && hi[k] <= 2 * c) : (hi[k] <= 0.5 * c && lo[k] >= 2 * c);
        if (!exact) continue;
        f->c[k] = c;
        f->moved = 1;
    }
}

acd_status acd_geom3_frame_check(const acd_frame *f, const double *pts, const char *what, acd_error *err) {
    if (!(f->extent > 0) || f->extent >= ACD_FRAME_MIN_STEPS * f->spacing) return ACD_OK;
    const double *v = pts + 3 * f->far_vertex;
    return acd_fail(err, ACD_ERR_INVALID_INPUT,
                    "%s: the coordinates cannot resolve the input's extent: vertex %zu (%.17g, %.17g, %.17g) is "
                    "so far from the origin that neighbouring doubles there are %.3g apart, and the extent %.3g "
                    "spans only %.3g such steps (at least %.0f needed, so that results written in these "
                    "coordinates keep the shape); translate the mesh nearer the origin",
                    what, f->far_vertex, v[0], v[1], v[2], f->spacing, f->extent, f->extent / f->spacing,
                    ACD_FRAME_MIN_STEPS);
}

void acd_geom3_frame_to_local(const acd_frame *f, double *pts, size_t n) {
    if (!f->moved) return;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) pts[3 * i + k] -= f->c[k];
}

void acd_geom3_frame_to_model(const acd_frame *f, double *pts, size_t n) {
    if (!f->moved) return;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) pts[3 * i + k] += f->c[k];
}

void acd_geom3_frame_plane_to_model(const acd_frame *f, double plane[4]) {
    if (!f->moved) return;
    plane[3] -= plane[0] * f->c[0] + plane[1] * f->c[1] + plane[2] * f->c[2];
}

acd_status acd_geom3_frame_mesh_view(const acd_frame *f, const acd_mesh *m, acd_mesh *out, acd_error *err) {
    *out = *m;
    out->vertices = malloc((m->nvertices ? 3 * m->nvertices : 3) * sizeof *out->vertices);
    if (!out->vertices) return acd_fail(err, ACD_ERR_NOMEM, "out of memory for a mesh of %zu vertices", m->nvertices);
    if (m->nvertices) memcpy(out->vertices, m->vertices, 3 * m->nvertices * sizeof *out->vertices);
    acd_geom3_frame_to_local(f, out->vertices, m->nvertices);
    return ACD_OK;
}

acd_status acd_geom3_frame_hull_view(const acd_frame *f, const acd_hull *h, acd_hull *out, acd_error *err) {
    *out = *h;
    out->vertices = malloc((h->nvertices ? 3 * h->nvertices : 3) * sizeof *out->vertices);
    out->planes = malloc((h->ntriangles ? 4 * h->ntriangles : 4) * sizeof *out->planes);
    if (!out->vertices || !out->planes) {
        free(out->vertices), free(out->planes);
        out->vertices = out->planes = NULL;
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for a hull of %zu vertices", h->nvertices);
    }
    if (h->nvertices) memcpy(out->vertices, h->vertices, 3 * h->nvertices * sizeof *out->vertices);
    acd_geom3_frame_to_local(f, out->vertices, h->nvertices);
    for (size_t t = 0; t < h->ntriangles && h->planes; t++) {
        const double *q = h->planes + 4 * t;
        double *o = out->planes + 4 * t;
        o[0] = q[0], o[1] = q[1], o[2] = q[2];
        o[3] = q[3] + q[0] * f->c[0] + q[1] * f->c[1] + q[2] * f->c[2];
    }
    return ACD_OK;
}

void acd_geom3_frame_view_free(acd_mesh *m, acd_hull *h) {
    if (m) free(m->vertices), m->vertices = NULL;
    if (h) free(h->vertices), free(h->planes), h->vertices = h->planes = NULL;
}
