/* Small closed meshes made in code for the 3D tests (header-only: static functions).
 * Every mesh is outward oriented (counterclockwise seen from outside). */
#ifndef ACD_TEST_MESHGEN_H
#define ACD_TEST_MESHGEN_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct tm_mesh {
    double *v;
    uint32_t *t;
    size_t nv, nt;
} tm_mesh;

static inline void tm_free(tm_mesh *m) {
    free(m->v);
    free(m->t);
    memset(m, 0, sizeof *m);
}

/* Axis-aligned box [lo, hi] with 8 vertices and 12 triangles. */
static inline tm_mesh tm_box(const double lo[3], const double hi[3]) {
    static const uint32_t T[36] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                   2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6, 5, 0, 4, 7, 0, 7, 3};
    tm_mesh m;
    m.nv = 8;
    m.nt = 12;
    m.v = malloc(24 * sizeof(double));
    m.t = malloc(36 * sizeof(uint32_t));
    if (!m.v || !m.t) abort();
    for (int i = 0; i < 8; i++) {
        m.v[3 * i + 0] = (i == 1 || i == 2 || i == 5 || i == 6) ? hi[0] : lo[0];
        m.v[3 * i + 1] = (i == 2 || i == 3 || i == 6 || i == 7) ? hi[1] : lo[1];
        m.v[3 * i + 2] = i >= 4 ? hi[2] : lo[2];
    }
    memcpy(m.t, T, sizeof T);
    return m;
}

/* Torus around z: major radius R, minor r, nu x nv quads split in two. */
static inline tm_mesh tm_torus(double R, double r, int nu, int nvv) {
    tm_mesh m;
    m.nv = (size_t)nu * (size_t)nvv;
    m.nt = 2 * m.nv;
    m.v = malloc(3 * m.nv * sizeof(double));
    m.t = malloc(3 * m.nt * sizeof(uint32_t));
    if (!m.v || !m.t) abort();
    const double tau = 6.283185307179586;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nvv; j++) {
            double u = tau * i / nu, w = tau * j / nvv;
            double *p = m.v + 3 * ((size_t)i * nvv + j);
            p[0] = (R + r * cos(w)) * cos(u);
            p[1] = (R + r * cos(w)) * sin(u);
            p[2] = r * sin(w);
        }
    size_t k = 0;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nvv; j++) {
            uint32_t a = (uint32_t)(i * nvv + j), b = (uint32_t)(((i + 1) % nu) * nvv + j),
                     c = (uint32_t)(((i + 1) % nu) * nvv + (j + 1) % nvv), d = (uint32_t)(i * nvv + (j + 1) % nvv);
            uint32_t tri[6] = {a, b, c, a, c, d};
            memcpy(m.t + 6 * k, tri, sizeof tri);
            k++;
        }
    return m;
}

/* Octahedron with vertices at +-1 on the axes (rays from the origin along an axis hit a vertex). */
static inline tm_mesh tm_octahedron(void) {
    static const double V[18] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
    static const uint32_t T[24] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    tm_mesh m;
    m.nv = 6;
    m.nt = 8;
    m.v = malloc(sizeof V);
    m.t = malloc(sizeof T);
    if (!m.v || !m.t) abort();
    memcpy(m.v, V, sizeof V);
    memcpy(m.t, T, sizeof T);
    return m;
}

/* Prism: the counterclockwise polygon (n points, 2 doubles each) between z0 and z1. The caps are
 * fanned from polygon vertex `fan` (the polygon must be star-shaped from it). */
static inline tm_mesh tm_prism(const double *poly, size_t n, size_t fan, double z0, double z1) {
    tm_mesh m;
    m.nv = 2 * n;
    m.nt = 2 * (n - 2) + 2 * n;
    m.v = malloc(3 * m.nv * sizeof(double));
    m.t = malloc(3 * m.nt * sizeof(uint32_t));
    if (!m.v || !m.t) abort();
    for (size_t i = 0; i < n; i++) {
        m.v[3 * i] = m.v[3 * (n + i)] = poly[2 * i];
        m.v[3 * i + 1] = m.v[3 * (n + i) + 1] = poly[2 * i + 1];
        m.v[3 * i + 2] = z0;
        m.v[3 * (n + i) + 2] = z1;
    }
    size_t k = 0;
    for (size_t j = 1; j + 1 < n; j++) {
        uint32_t a = (uint32_t)fan, b = (uint32_t)((fan + j) % n), c = (uint32_t)((fan + j + 1) % n);
        uint32_t bot[3] = {a, c, b}, top[3] = {(uint32_t)n + a, (uint32_t)n + b, (uint32_t)n + c};
        memcpy(m.t + 3 * k++, bot, sizeof bot);
        memcpy(m.t + 3 * k++, top, sizeof top);
    }
    for (size_t i = 0; i < n; i++) {
        uint32_t a = (uint32_t)i, b = (uint32_t)((i + 1) % n);
        uint32_t t1[3] = {a, b, (uint32_t)n + b}, t2[3] = {a, (uint32_t)n + b, (uint32_t)n + a};
        memcpy(m.t + 3 * k++, t1, sizeof t1);
        memcpy(m.t + 3 * k++, t2, sizeof t2);
    }
    return m;
}

#endif
