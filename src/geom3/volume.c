/* geom3/volume: volumes of closed triangle meshes; see volume.h. */
#include "geom3/volume.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "acd/mesh.h"
#include "geom3/frame.h"
#include "geom3/vec3.h"

/* the centre of m's bounding box (m has vertices) */
static void box_centre(const acd_mesh *m, double o[3]) {
    double lo[3], hi[3];
    for (size_t v = 0; v < m->nvertices; v++)
        for (int k = 0; k < 3; k++) {
            double x = m->vertices[3 * v + k];
            if (v == 0 || x < lo[k]) lo[k] = x;
            if (v == 0 || x > hi[k]) hi[k] = x;
        }
    for (int k = 0; k < 3; k++) o[k] = lo[k] + 0.5 * (hi[k] - lo[k]);
}

double acd_geom3_signed_volume(const acd_mesh *m) {
    if (m->nvertices == 0) return 0;
    double o[3];
    box_centre(m, o);
    double vol = 0;
    for (size_t t = 0; t < m->ntriangles; t++) {
        const double *p[3];
        for (int i = 0; i < 3; i++) p[i] = m->vertices + 3 * (size_t)m->triangles[3 * t + i];
        double a[3], b[3], c[3], bc[3];
        for (int k = 0; k < 3; k++) a[k] = p[0][k] - o[k], b[k] = p[1][k] - o[k], c[k] = p[2][k] - o[k];
        acd_cross3(b, c, bc);
        vol += a[0] * bc[0] + a[1] * bc[1] + a[2] * bc[2];
    }
    return vol / 6.0;
}

double acd_geom3_triangle_volume_beyond(const double a[3], const double b[3], const double c[3], const double n[3],
                                        double off, const double apex[3]) {
    const double *const p[3] = {a, b, c};
    double s[3];
    int nbeyond = 0;
    for (int k = 0; k < 3; k++) {
        s[k] = n[0] * p[k][0] + n[1] * p[k][1] + n[2] * p[k][2] - off;
        nbeyond += s[k] > 0;
    }
    return nbeyond == 0 ? 0 : acd_geom3_clipped_cone_volume(p, s, apex);
}

/* Far from the origin (geom3/frame) the mesh and the plane are taken in the local frame: the
 * plane's offset d + n.c rounded once (a plane within half a spacing of the model coordinates of the
 * given one, which is as precisely as that offset is known), the sides and the section points then
 * to the rounding of the local coordinates; in model coordinates the sides carried that rounding
 * afresh at every vertex and the clipped points the model coordinates' spacing. Near the origin
 * the computation is the one it always was. */
double acd_mesh_volume_beyond(const acd_mesh *m, const double plane[4]) {
    if (!m || m->nvertices == 0 || m->ntriangles == 0) return 0;
    double nn = plane[0] * plane[0] + plane[1] * plane[1] + plane[2] * plane[2];
    if (!(nn > 0) || !isfinite(nn) || !isfinite(plane[3])) return NAN;
    /* the apex: the bounding-box centre projected onto the plane (near the mesh, for rounding) */
    double o[3];
    box_centre(m, o);
    acd_frame fr;
    acd_geom3_frame_of(m->vertices, m->nvertices, &fr);
    if (fr.moved) { /* far from the origin: in the local frame (geom3/frame), see below */
        double q[4] = {plane[0], plane[1], plane[2], plane[3] + plane[0] * fr.c[0] + plane[1] * fr.c[1] + plane[2] * fr.c[2]};
        for (int k = 0; k < 3; k++) o[k] -= fr.c[k];
        double s = (q[0] * o[0] + q[1] * o[1] + q[2] * o[2] + q[3]) / nn;
        for (int k = 0; k < 3; k++) o[k] -= s * q[k];
        double vol = 0;
        for (size_t t = 0; t < m->ntriangles; t++) {
            const uint32_t *tr = m->triangles + 3 * t;
            double p[3][3];
            for (int i = 0; i < 3; i++)
                for (int k = 0; k < 3; k++) p[i][k] = m->vertices[3 * (size_t)tr[i] + k] - fr.c[k];
            vol += acd_geom3_triangle_volume_beyond(p[0], p[1], p[2], q, -q[3], o);
        }
        return vol;
    }
    double s = (plane[0] * o[0] + plane[1] * o[1] + plane[2] * o[2] + plane[3]) / nn;
    for (int k = 0; k < 3; k++) o[k] -= s * plane[k];
    double vol = 0;
    for (size_t t = 0; t < m->ntriangles; t++) {
        const uint32_t *tr = m->triangles + 3 * t;
        vol += acd_geom3_triangle_volume_beyond(m->vertices + 3 * (size_t)tr[0], m->vertices + 3 * (size_t)tr[1],
                                                m->vertices + 3 * (size_t)tr[2], plane, -plane[3], o);
    }
    return vol;
}

static double volume_outside_bound(const acd_hull *h, const acd_mesh *m, double tol, double tol_scale);

/* Far from the origin, in the local frame (geom3/frame) as acd_hull_volume_outside. */
double acd_hull_volume_outside_bound(const acd_hull *h, const acd_mesh *m, double tol, double tol_scale) {
    if (h->dim != 3 || m->nvertices == 0) return 0;
    acd_frame fr;
    acd_geom3_frame_of(m->vertices, m->nvertices, &fr);
    if (!fr.moved) return volume_outside_bound(h, m, tol, tol_scale);
    acd_mesh lm;
    acd_hull lh;
    if (acd_geom3_frame_mesh_view(&fr, m, &lm, NULL) != ACD_OK) return NAN;
    double v = acd_geom3_frame_hull_view(&fr, h, &lh, NULL) == ACD_OK ? volume_outside_bound(&lh, &lm, tol, tol_scale) : NAN;
    acd_geom3_frame_view_free(&lm, &lh);
    return v;
}

static double volume_outside_bound(const acd_hull *h, const acd_mesh *m, double tol, double tol_scale) {
    double *seen = NULL, sum = 0;
    size_t nseen = 0;
    for (size_t f = 0; f < h->ntriangles; f++) {
        const double *q = h->planes + 4 * f;
        double w = -INFINITY;
        for (size_t k = 0; k < m->nvertices; k++) {
            const double *v = m->vertices + 3 * k;
            w = fmax(w, q[0] * v[0] + q[1] * v[1] + q[2] * v[2] + q[3]);
        }
        if (!(w > tol)) continue;
        int dup = 0;
        for (size_t j = 0; j < nseen && !dup; j++)
            dup = fabs(seen[4 * j] - q[0]) <= 1e-9 && fabs(seen[4 * j + 1] - q[1]) <= 1e-9 &&
                  fabs(seen[4 * j + 2] - q[2]) <= 1e-9 && fabs(seen[4 * j + 3] - q[3]) <= 1e-9 * tol_scale;
        if (dup) continue;
        if (!seen) {
            seen = malloc(4 * h->ntriangles * sizeof *seen);
            if (!seen) return NAN;
        }
        memcpy(seen + 4 * nseen++, q, 4 * sizeof *seen);
        sum += fmax(0.0, acd_mesh_volume_beyond(m, q));
    }
    free(seen);
    return sum;
}
