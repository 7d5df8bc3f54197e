/* Closed test meshes for the CoRiSe tests: a box whose top is a height field z = top(x, y)
 * sampled on an (nx+1) x (ny+1) grid, with a flat bottom z = 0 and vertical side walls (all
 * triangles oriented outward). Header-only. */
#ifndef ACD_TEST_CORISE_MESHES_H
#define ACD_TEST_CORISE_MESHES_H

#include <stdint.h>
#include <stdlib.h>

#include "acd/mesh.h"

typedef double (*cm_height_fn)(double x, double y, const void *user);

static void cm_tri(acd_mesh *m, size_t *t, uint32_t a, uint32_t b, uint32_t c, const double out[3]) {
    const double *p = m->vertices + 3 * a, *q = m->vertices + 3 * b, *r = m->vertices + 3 * c;
    double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    uint32_t *T = m->triangles + 3 * (*t)++;
    if (n[0] * out[0] + n[1] * out[1] + n[2] * out[2] >= 0)
        T[0] = a, T[1] = b, T[2] = c;
    else
        T[0] = a, T[1] = c, T[2] = b;
}

/* Box [0,lx] x [0,ly] with the given top, walls split into nz rows. Vertex ids: top grid
 * (j*(nx+1)+i), then the bottom grid (same + n), then the inner wall vertices. */
static void cm_heightfield_box(acd_mesh *m, size_t nx, size_t ny, size_t nz, double lx, double ly, cm_height_fn top,
                               const void *user) {
    size_t w = nx + 1, n = w * (ny + 1), np = 2 * (nx + ny);
    m->nvertices = 2 * n + np * (nz - 1);
    m->vertices = malloc(3 * m->nvertices * sizeof(double));
    for (size_t j = 0; j <= ny; j++)
        for (size_t i = 0; i <= nx; i++) {
            double x = lx * (double)i / (double)nx, y = ly * (double)j / (double)ny;
            double *p = m->vertices + 3 * (j * w + i), *q = m->vertices + 3 * (n + j * w + i);
            p[0] = q[0] = x;
            p[1] = q[1] = y;
            p[2] = top(x, y, user);
            q[2] = 0;
        }
    /* perimeter of the grid, counterclockwise from (0,0) */
    uint32_t *per = malloc(np * sizeof *per);
    size_t k = 0;
    for (size_t i = 0; i < nx; i++) per[k++] = (uint32_t)i;
    for (size_t j = 0; j < ny; j++) per[k++] = (uint32_t)(j * w + nx);
    for (size_t i = nx; i > 0; i--) per[k++] = (uint32_t)(ny * w + i);
    for (size_t j = ny; j > 0; j--) per[k++] = (uint32_t)(j * w);
    /* column vertex of perimeter point p at level l (0 = bottom, nz = top) */
#define CM_COL(p, l) ((l) == 0 ? per[p] + (uint32_t)n : (l) == nz ? per[p] : (uint32_t)(2 * n + (p) * (nz - 1) + (l) - 1))
    for (size_t p = 0; p < np; p++)
        for (size_t l = 1; l < nz; l++) {
            double *v = m->vertices + 3 * CM_COL(p, l);
            const double *t = m->vertices + 3 * per[p];
            v[0] = t[0];
            v[1] = t[1];
            v[2] = t[2] * (double)l / (double)nz;
        }
    m->ntriangles = 4 * nx * ny + 2 * np * nz;
    m->triangles = malloc(3 * m->ntriangles * sizeof(uint32_t));
    size_t t = 0;
    const double up[3] = {0, 0, 1}, down[3] = {0, 0, -1};
    for (size_t j = 0; j < ny; j++)
        for (size_t i = 0; i < nx; i++) {
            uint32_t a = (uint32_t)(j * w + i), b = a + 1, c = (uint32_t)(a + w + 1), d = (uint32_t)(a + w);
            cm_tri(m, &t, a, b, c, up);
            cm_tri(m, &t, a, c, d, up);
            cm_tri(m, &t, a + (uint32_t)n, b + (uint32_t)n, c + (uint32_t)n, down);
            cm_tri(m, &t, a + (uint32_t)n, c + (uint32_t)n, d + (uint32_t)n, down);
        }
    for (size_t p = 0; p < np; p++) {
        size_t q = (p + 1) % np;
        const double *A = m->vertices + 3 * per[p], *B = m->vertices + 3 * per[q];
        double out[3] = {0.5 * (A[0] + B[0]) - 0.5 * lx, 0.5 * (A[1] + B[1]) - 0.5 * ly, 0};
        for (size_t l = 0; l < nz; l++) {
            cm_tri(m, &t, CM_COL(p, l), CM_COL(q, l), CM_COL(q, l + 1), out);
            cm_tri(m, &t, CM_COL(p, l), CM_COL(q, l + 1), CM_COL(p, l + 1), out);
        }
    }
#undef CM_COL
    free(per);
}

#endif
