#include "shapes.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

double mg_bumpy_r(double theta, double phi, void *user) {
    (void)user;
    return 1 + 0.25 * sin(3 * theta) * cos(4 * phi) + 0.1 * cos(5 * theta);
}

int mg_radial(acd_mesh *m, int nu, int nv, mg_radius_fn r, void *user) {
    memset(m, 0, sizeof *m);
    size_t nvert = (size_t)nu * (size_t)(nv - 1) + 2;
    size_t ntri = 2 * (size_t)nu * (size_t)(nv - 1);
    m->vertices = malloc(3 * nvert * sizeof *m->vertices);
    m->triangles = malloc(3 * ntri * sizeof *m->triangles);
    if (!m->vertices || !m->triangles) return 0;
    const double pi = 3.14159265358979323846;
    size_t k = 0;
    double rn = r(0, 0, user), rs = r(pi, 0, user);
    m->vertices[k++] = 0, m->vertices[k++] = 0, m->vertices[k++] = rn; /* north pole: 0 */
    for (int j = 1; j < nv; j++) {
        double th = pi * j / nv;
        for (int i = 0; i < nu; i++) {
            double ph = 2 * pi * i / nu;
            double rr = r(th, ph, user);
            m->vertices[k++] = rr * sin(th) * cos(ph);
            m->vertices[k++] = rr * sin(th) * sin(ph);
            m->vertices[k++] = rr * cos(th);
        }
    }
    m->vertices[k++] = 0, m->vertices[k++] = 0, m->vertices[k++] = -rs; /* south pole */
    m->nvertices = nvert;
    uint32_t S = (uint32_t)(nvert - 1);
#define V(j, i) ((uint32_t)(1 + ((j) - 1) * nu + ((i) % nu)))
    size_t t = 0;
    for (int i = 0; i < nu; i++) {
        uint32_t *q = m->triangles + 3 * t++;
        q[0] = 0, q[1] = V(1, i), q[2] = V(1, i + 1);
    }
    for (int j = 1; j < nv - 1; j++)
        for (int i = 0; i < nu; i++) {
            uint32_t a = V(j, i), b = V(j + 1, i), c = V(j + 1, i + 1), d = V(j, i + 1);
            uint32_t *q = m->triangles + 3 * t++;
            q[0] = a, q[1] = b, q[2] = c;
            q = m->triangles + 3 * t++;
            q[0] = a, q[1] = c, q[2] = d;
        }
    for (int i = 0; i < nu; i++) {
        uint32_t *q = m->triangles + 3 * t++;
        q[0] = S, q[1] = V(nv - 1, i + 1), q[2] = V(nv - 1, i);
    }
#undef V
    m->ntriangles = t;
    return 1;
}

int mg_torus(acd_mesh *m, int nu, int nv, double R, double r) {
    memset(m, 0, sizeof *m);
    size_t nvert = (size_t)nu * (size_t)nv, ntri = 2 * nvert;
    m->vertices = malloc(3 * nvert * sizeof *m->vertices);
    m->triangles = malloc(3 * ntri * sizeof *m->triangles);
    if (!m->vertices || !m->triangles) return 0;
    const double pi = 3.14159265358979323846;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            double u = 2 * pi * i / nu, v = 2 * pi * j / nv;
            double *p = m->vertices + 3 * ((size_t)i * nv + j);
            p[0] = (R + r * cos(v)) * cos(u);
            p[1] = (R + r * cos(v)) * sin(u);
            p[2] = r * sin(v);
        }
    size_t t = 0;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            uint32_t a = (uint32_t)(i * nv + j), b = (uint32_t)(((i + 1) % nu) * nv + j);
            uint32_t c = (uint32_t)(((i + 1) % nu) * nv + (j + 1) % nv), d = (uint32_t)(i * nv + (j + 1) % nv);
            uint32_t *q = m->triangles + 3 * t++;
            q[0] = a, q[1] = b, q[2] = c;
            q = m->triangles + 3 * t++;
            q[0] = a, q[1] = c, q[2] = d;
        }
    m->nvertices = nvert;
    m->ntriangles = t;
    return 1;
}

int mg_voxels(acd_mesh *m, const unsigned char *occ, int nx, int ny, int nz) {
    memset(m, 0, sizeof *m);
    int gx = nx + 1, gy = ny + 1, gz = nz + 1;
    size_t ngrid = (size_t)gx * gy * gz;
    int32_t *id = malloc(ngrid * sizeof *id);
    size_t cap = 1024;
    m->triangles = malloc(3 * cap * sizeof *m->triangles);
    if (!id || !m->triangles) { free(id); return 0; }
    for (size_t i = 0; i < ngrid; i++) id[i] = -1;
#define OCC(x, y, z) ((x) >= 0 && (y) >= 0 && (z) >= 0 && (x) < nx && (y) < ny && (z) < nz && occ[((size_t)(z) * ny + (y)) * nx + (x)])
    size_t nt = 0, nvtx = 0;
    double *verts = NULL;
    size_t vcap = 0;
    for (int z = 0; z < nz; z++)
        for (int y = 0; y < ny; y++)
            for (int x = 0; x < nx; x++) {
                if (!OCC(x, y, z)) continue;
                for (int dir = 0; dir < 6; dir++) {
                    int ax = dir / 2, sgn = dir % 2 ? 1 : -1;
                    int d[3] = {0, 0, 0};
                    d[ax] = sgn;
                    if (OCC(x + d[0], y + d[1], z + d[2])) continue;
                    /* quad on the face of the cell in direction d, counterclockwise seen from outside */
                    int u = (ax + 1) % 3, w = (ax + 2) % 3;
                    int base[3] = {x, y, z};
                    if (sgn > 0) base[ax] += 1;
                    int c[4][3];
                    for (int q = 0; q < 4; q++) memcpy(c[q], base, sizeof base);
                    c[1][u] += 1;
                    c[2][u] += 1, c[2][w] += 1;
                    c[3][w] += 1;
                    uint32_t vi[4];
                    for (int q = 0; q < 4; q++) {
                        size_t g = ((size_t)c[q][2] * gy + c[q][1]) * gx + c[q][0];
                        if (id[g] < 0) {
                            if (nvtx == vcap) {
                                vcap = vcap ? 2 * vcap : 1024;
                                double *nvv = realloc(verts, 3 * vcap * sizeof *nvv);
                                if (!nvv) { free(id); free(verts); return 0; }
                                verts = nvv;
                            }
                            verts[3 * nvtx] = c[q][0], verts[3 * nvtx + 1] = c[q][1], verts[3 * nvtx + 2] = c[q][2];
                            id[g] = (int32_t)nvtx++;
                        }
                        vi[q] = (uint32_t)id[g];
                    }
                    if (nt + 2 > cap) {
                        cap *= 2;
                        uint32_t *nn = realloc(m->triangles, 3 * cap * sizeof *nn);
                        if (!nn) { free(id); free(verts); return 0; }
                        m->triangles = nn;
                    }
                    /* (u, w) x order gives normal +ax; flip for the negative side */
                    uint32_t *t0 = m->triangles + 3 * nt++, *t1 = m->triangles + 3 * nt++;
                    if (sgn > 0) {
                        t0[0] = vi[0], t0[1] = vi[1], t0[2] = vi[2];
                        t1[0] = vi[0], t1[1] = vi[2], t1[2] = vi[3];
                    } else {
                        t0[0] = vi[0], t0[1] = vi[2], t0[2] = vi[1];
                        t1[0] = vi[0], t1[1] = vi[3], t1[2] = vi[2];
                    }
                }
            }
#undef OCC
    free(id);
    m->vertices = verts;
    m->nvertices = nvtx;
    m->ntriangles = nt;
    return 1;
}

double mg_volume(const acd_mesh *m) {
    double v = 0;
    for (size_t t = 0; t < m->ntriangles; t++) {
        const double *a = m->vertices + 3 * m->triangles[3 * t], *b = m->vertices + 3 * m->triangles[3 * t + 1],
                     *c = m->vertices + 3 * m->triangles[3 * t + 2];
        v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return v / 6.0;
}
