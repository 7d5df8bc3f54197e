/* Shared by the 3D fuzz targets: a small closed mesh shaped by the fuzz input instead of parsed
 * (the readers have their own targets). A UV sphere of `rings` latitude rings of `segs` vertices
 * and two poles (rings * segs + 2 vertices, one radius byte each) whose vertices are moved along
 * their directions to radii taken from the bytes, on a coarse grid (quarter units, 0 allowed), so
 * coplanar faces, flat stretches, spikes and vertices pinched together at the centre are
 * frequent. With positive radii the mesh is a star-shaped simple polyhedron; radius 0 makes it
 * touch itself at the centre. Outward (counterclockwise) triangles. */
#ifndef ACD_FUZZ_SPHERE_H
#define ACD_FUZZ_SPHERE_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd/mesh.h"
#include "core/tolerance.h"

/* The slack of the tau checks, relative to r->scale (the enclosing sphere's radius): the library
 * takes a part within tau up to ACD_TOL_REL_DIST of the bounding box's diagonal (decompose.c:
 * "tau = 0: up to rounding"), and that diagonal is at most 2 sqrt(3) radii. (It was 1e-12: a part
 * at tau = 0 with concavity 5.2e-11 x the radius, accepted by the library, aborted the harness:
 * corpus acd3d/tau0_rounding.) */
#define FZ_TAU_SLACK (ACD_TOL_REL_DIST * 2 * 1.7320508075688772)

static void fz_build_sphere(const uint8_t *r, int rings, int segs, acd_mesh *m) {
    const double pi = 3.14159265358979323846;
    int nv = rings * segs + 2;
    m->nvertices = (size_t)nv;
    m->ntriangles = 2 * (size_t)segs * (size_t)rings;
    m->vertices = malloc((size_t)nv * 3 * sizeof(double));
    m->triangles = malloc(m->ntriangles * 3 * sizeof(uint32_t));
    if (!m->vertices || !m->triangles) abort();
    for (int v = 0; v < nv; v++) {
        double theta, phi;
        if (v < rings * segs) {
            theta = pi * (v / segs + 1) / (rings + 1);
            phi = 2 * pi * (v % segs) / segs;
        } else {
            theta = v == nv - 2 ? 0 : pi;
            phi = 0;
        }
        double rad = 0.25 * (r[v] % 16);
        /* directions rounded to a 1/64 grid: exact coplanarities are common */
        double d[3] = {sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta)};
        for (int k = 0; k < 3; k++) m->vertices[3 * v + k] = rad * round(64 * d[k]) / 64;
    }
    size_t t = 0;
    uint32_t north = (uint32_t)nv - 2, south = (uint32_t)nv - 1;
    for (int s = 0; s < segs; s++) {
        uint32_t a = (uint32_t)s, b = (uint32_t)((s + 1) % segs);
        uint32_t tn[3] = {north, a, b};
        memcpy(m->triangles + 3 * t++, tn, sizeof tn);
        uint32_t la = (uint32_t)((rings - 1) * segs) + a, lb = (uint32_t)((rings - 1) * segs) + b;
        uint32_t ts[3] = {south, lb, la};
        memcpy(m->triangles + 3 * t++, ts, sizeof ts);
    }
    for (int i = 0; i + 1 < rings; i++)
        for (int s = 0; s < segs; s++) {
            uint32_t a = (uint32_t)(i * segs + s), b = (uint32_t)(i * segs + (s + 1) % segs);
            uint32_t c = a + (uint32_t)segs, d = b + (uint32_t)segs;
            uint32_t t1[3] = {a, c, d}, t2[3] = {a, d, b};
            memcpy(m->triangles + 3 * t++, t1, sizeof t1);
            memcpy(m->triangles + 3 * t++, t2, sizeof t2);
        }
    m->ntriangles = t;
}

static double fz_mesh_volume(const acd_mesh *m) {
    double v = 0;
    for (size_t t = 0; t < m->ntriangles; t++) {
        const double *a = m->vertices + 3 * (size_t)m->triangles[3 * t];
        const double *b = m->vertices + 3 * (size_t)m->triangles[3 * t + 1];
        const double *c = m->vertices + 3 * (size_t)m->triangles[3 * t + 2];
        v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return v / 6;
}

/* Deletes the faces named by the bytes del[0 .. n-1] (each modulo the face count): holes. */
static void fz_delete_faces(acd_mesh *m, const uint8_t *del, size_t n) {
    if (!n || !m->ntriangles) return;
    uint8_t *mark = calloc(m->ntriangles, 1);
    if (!mark) abort();
    for (size_t i = 0; i < n; i++) mark[del[i] % m->ntriangles] = 1;
    size_t k = 0;
    for (size_t t = 0; t < m->ntriangles; t++)
        if (!mark[t]) memmove(m->triangles + 3 * k++, m->triangles + 3 * t, 3 * sizeof(uint32_t));
    m->ntriangles = k;
    free(mark);
}

/* acd3d_decompose as `acd 3d` runs it: when solid mode refuses the mesh as not closed (holes deleted
 * by the input), weld, orient and close the holes (acd_mesh_repair), then decompose the closed mesh.
 * A repair that fails returns its status; every failure must carry a message (abort otherwise). */
static inline acd_status fz_decompose_closing(acd_mesh *m, const acd3d_params *p, acd3d_result *r, acd_error *err) {
    err->message[0] = '\0';
    acd_status s = acd3d_decompose(m, p, r, err);
    if (s == ACD_ERR_NON_MANIFOLD && p->mode == ACD3D_SOLID) {
        acd_repair_options ro = acd_repair_default_options();
        ro.fill_holes_max_edges = SIZE_MAX;
        acd_repair_stats rs;
        err->message[0] = '\0';
        s = acd_mesh_repair(m, &ro, &rs, err);
        if (s == ACD_OK) {
            err->message[0] = '\0';
            s = acd3d_decompose(m, p, r, err);
        }
    }
    if (s != ACD_OK && !err->message[0]) abort(); /* every failure must say why */
    return s;
}

#endif
