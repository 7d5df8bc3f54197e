/* bench_eval: time of `acd eval` (default parameters: 10^6 volume samples, 2 x 200000 surface
 * samples) on a 69 696-triangle torus cut into K angular sectors (their hulls are the parts), and
 * on a mesh given on the command line (bench_eval MESH DECOMP.obj). Results: docs/results/eval.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "acd/eval.h"
#include "acd/hull.h"
#include "acd/mesh.h"

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
            uint32_t t[6] = {a, b, c, a, c, d};
            memcpy(m->triangles + 6 * k++, t, sizeof t);
        }
}

static void report(const char *name, const acd_eval_report *r) {
    printf("%-28s parts %3zu  iou %.4f  cov %.4f  exc %.4f  m->h max %.4f mean %.5f  h->m max %.4f mean %.5f"
           "  inexact %zu  %.3f s\n",
           name, r->parts, r->iou, r->coverage, r->excess, r->mesh_to_hulls_max, r->mesh_to_hulls_mean,
           r->hulls_to_mesh_max, r->hulls_to_mesh_mean, r->inexact_distances, r->seconds);
}

int main(int argc, char **argv) {
    acd_error err;
    acd_eval_params prm = acd_eval_default_params();
    acd_eval_report rep;
    if (argc == 3) {
        acd_mesh m;
        acd_mesh_parts parts;
        if (acd_mesh_read(argv[1], &m, &err) != ACD_OK || acd_mesh_read_parts(argv[2], &parts, &err) != ACD_OK) {
            fprintf(stderr, "bench_eval: %s\n", err.message);
            return 1;
        }
        if (acd_eval_parts(&m, &parts, &prm, &rep, &err) != ACD_OK) {
            fprintf(stderr, "bench_eval: %s\n", err.message);
            return 1;
        }
        printf("%s: %zu triangles\n", argv[1], m.ntriangles);
        report(argv[2], &rep);
        acd_mesh_free(&m);
        acd_mesh_parts_free(&parts);
        return 0;
    }
    acd_mesh m;
    torus(1.0, 0.35, 264, 132, &m);
    printf("torus: %zu triangles, %zu vertices\n", m.ntriangles, m.nvertices);
    int ks[] = {4, 8, 24};
    for (size_t q = 0; q < sizeof ks / sizeof *ks; q++) {
        int K = ks[q];
        acd_hull *h = calloc((size_t)K, sizeof *h);
        double *pts = malloc(3 * m.nvertices * sizeof(double));
        if (!h || !pts) return 5;
        for (int s = 0; s < K; s++) {
            /* the vertices of sector s (angles [s, s+1] * 2 pi / K, ends included) */
            size_t n = 0;
            for (size_t v = 0; v < m.nvertices; v++) {
                double a = atan2(m.vertices[3 * v + 1], m.vertices[3 * v]);
                if (a < 0) a += 6.283185307179586;
                double lo = 6.283185307179586 * s / K, hi = 6.283185307179586 * (s + 1) / K;
                if ((a >= lo - 1e-9 && a <= hi + 1e-9) || (s == K - 1 && a < 1e-9)) memcpy(pts + 3 * n++, m.vertices + 3 * v, 3 * sizeof(double));
            }
            if (acd_hull_compute(pts, n, &h[s], &err) != ACD_OK) {
                fprintf(stderr, "bench_eval: hull: %s\n", err.message);
                return 1;
            }
        }
        clock_t c0 = clock();
        if (acd_eval_hulls(&m, h, (size_t)K, &prm, &rep, &err) != ACD_OK) {
            fprintf(stderr, "bench_eval: %s\n", err.message);
            return 1;
        }
        char name[64];
        double cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
        snprintf(name, sizeof name, "torus, %d sectors", K);
        printf("  (cpu time of all threads: %.3f s)\n", cpu);
        report(name, &rep);
        for (int s = 0; s < K; s++) acd_hull_free(&h[s]);
        free(h);
        free(pts);
    }
    acd_mesh_free(&m);
    return 0;
}
