/* bench_geom3: timings of the 3D kit: hull of random points (cube and sphere), plane cut of a torus,
 * Dijkstra on a torus's edge graph, minimum enclosing sphere, PCA. Results: docs/results/geom3.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "acd/hull.h"
#include "acd/mesh.h"
#include "core/rng.h"
#include "geom3/dijkstra.h"
#include "geom3/pca.h"
#include "geom3/plane_cut.h"
#include "geom3/sphere.h"

#include "bench_clock.h"

static void torus(double R, double r, int nu, int nv, acd_mesh *m) {
    m->nvertices = (size_t)nu * (size_t)nv;
    m->ntriangles = 2 * m->nvertices;
    m->vertices = malloc(3 * m->nvertices * sizeof(double));
    m->triangles = malloc(3 * m->ntriangles * sizeof(uint32_t));
    if (!m->vertices || !m->triangles) exit(5);
    const double tau = 6.283185307179586;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            double u = tau * i / nu, w = tau * j / nv, *p = m->vertices + 3 * ((size_t)i * nv + j);
            p[0] = (R + r * cos(w)) * cos(u);
            p[1] = (R + r * cos(w)) * sin(u);
            p[2] = r * sin(w);
        }
    size_t k = 0;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            uint32_t a = (uint32_t)(i * nv + j), b = (uint32_t)(((i + 1) % nu) * nv + j),
                     c = (uint32_t)(((i + 1) % nu) * nv + (j + 1) % nv), d = (uint32_t)(i * nv + (j + 1) % nv);
            uint32_t t[6] = {a, c, b, a, d, c};
            memcpy(m->triangles + 6 * k++, t, sizeof t);
        }
}

int main(void) {
    acd_rng r;
    acd_rng_seed(&r, 1);
    size_t sizes[] = {10000, 100000, 1000000};
    for (int s = 0; s < 3; s++) {
        size_t n = sizes[s];
        double *p = malloc(3 * n * sizeof *p);
        if (!p) return 5;
        for (int sphere = 0; sphere < 2; sphere++) {
            for (size_t i = 0; i < n; i++) {
                for (int k = 0; k < 3; k++) p[3 * i + k] = 2 * acd_rng_uniform(&r) - 1;
                if (sphere) {
                    double l = sqrt(p[3 * i] * p[3 * i] + p[3 * i + 1] * p[3 * i + 1] + p[3 * i + 2] * p[3 * i + 2]);
                    for (int k = 0; k < 3; k++) p[3 * i + k] /= l;
                }
            }
            acd_hull h;
            double t0 = bench_wall();
            if (acd_hull_compute(p, n, &h, NULL) != ACD_OK) return 5;
            double t1 = bench_wall();
            acd_sphere sp;
            if (acd_min_sphere(p, n, &sp, NULL) != ACD_OK) return 5;
            double t2 = bench_wall();
            acd_pca pc;
            if (acd_pca_points(p, n, NULL, &pc, NULL) != ACD_OK) return 5;
            double t3 = bench_wall();
            printf("%-7zu points %-6s hull %8.3f s (%zu facets)  min sphere %7.3f s  pca %7.3f s\n", n,
                   sphere ? "sphere" : "cube", t1 - t0, h.ntriangles, t2 - t1, t3 - t2);
            acd_hull_free(&h);
        }
        free(p);
    }
    int grids[][2] = {{100, 50}, {400, 200}, {1000, 500}};
    for (int g = 0; g < 3; g++) {
        acd_mesh m;
        torus(2, 0.7, grids[g][0], grids[g][1], &m);
        acd_cut_plane pl;
        double o[3] = {0.1, 0.2, 0.05}, nrm[3] = {0.3, 0.2, 1};
        if (acd_cut_plane_from_normal(o, nrm, 3, &pl, NULL) != ACD_OK) return 5;
        double t0 = bench_wall();
        acd_cut_result res;
        if (acd_plane_cut(&m, &pl, &res, NULL) != ACD_OK) return 5;
        double t1 = bench_wall();
        acd_edge_graph eg;
        if (acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &eg, NULL) != ACD_OK) return 5;
        double t2 = bench_wall();
        acd_sp_tree tr;
        uint32_t src = 0;
        if (acd_dijkstra(&eg, &src, 1, NULL, &tr, NULL) != ACD_OK) return 5;
        double t3 = bench_wall();
        printf("torus %7zu triangles: plane cut %7.3f s (%zu pieces, %zu loops)  edge graph %7.3f s  dijkstra %7.3f s\n",
               m.ntriangles, t1 - t0, res.npieces, res.nloops, t2 - t1, t3 - t2);
        acd_cut_result_free(&res);
        acd_sp_tree_free(&tr);
        acd_edge_graph_free(&eg);
        acd_mesh_free(&m);
    }
    return 0;
}
