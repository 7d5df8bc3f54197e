/* Benchmark of the mesh readers and writers on a 1M-triangle torus (1000 x 500 quads): write
 * each format to a temporary file, then read it back (best of 3), printing seconds per format.
 * Usage: bench_mesh_io [TMPDIR]   Results: docs/results/mesh-io.md */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "acd/mesh.h"

#include "bench_clock.h"

int main(int argc, char **argv) {
    const char *dir = argc > 1 ? argv[1] : "/tmp";
    const int n = 1000, mm = 500;
    acd_mesh m;
    m.nvertices = (size_t)n * mm;
    m.ntriangles = 2 * m.nvertices;
    m.vertices = malloc(m.nvertices * 3 * sizeof(double));
    m.triangles = malloc(m.ntriangles * 3 * sizeof(uint32_t));
    if (!m.vertices || !m.triangles) return 1;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < mm; j++) {
            double u = 6.283185307179586 * i / n, w = 6.283185307179586 * j / mm;
            double *v = m.vertices + 3 * ((size_t)i * mm + j);
            v[0] = (2 + 0.5 * cos(w)) * cos(u);
            v[1] = (2 + 0.5 * cos(w)) * sin(u);
            v[2] = 0.5 * sin(w);
        }
    size_t t = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < mm; j++) {
            uint32_t a = (uint32_t)(i * mm + j), b = (uint32_t)(((i + 1) % n) * mm + j),
                     c = (uint32_t)(((i + 1) % n) * mm + (j + 1) % mm), d = (uint32_t)(i * mm + (j + 1) % mm);
            uint32_t q[6] = {a, b, c, a, c, d};
            memcpy(m.triangles + 3 * t, q, sizeof q);
            t += 2;
        }
    static const struct {
        const char *ext;
        acd_mesh_format fmt;
    } fmts[] = {{"stl", ACD_MESH_FORMAT_STL},       {"ply", ACD_MESH_FORMAT_PLY}, {"obj", ACD_MESH_FORMAT_OBJ},
                {"off", ACD_MESH_FORMAT_OFF},       {"ascii.ply", ACD_MESH_FORMAT_PLY_ASCII},
                {"ascii.stl", ACD_MESH_FORMAT_STL_ASCII}, {"obj.gz", ACD_MESH_FORMAT_OBJ}};
    printf("mesh: %zu vertices, %zu triangles\n", m.nvertices, m.ntriangles);
    printf("%-10s %12s %10s %10s\n", "format", "bytes", "write s", "read s");
    acd_error err;
    for (size_t k = 0; k < sizeof fmts / sizeof fmts[0]; k++) {
        char path[512];
        snprintf(path, sizeof path, "%s/acd_bench_mesh_io_%ld.%s", dir, (long)getpid(), fmts[k].ext);
        double t0 = bench_wall();
        if (acd_mesh_write(path, &m, fmts[k].fmt, &err) != ACD_OK) {
            fprintf(stderr, "%s\n", err.message);
            return 1;
        }
        double tw = bench_wall() - t0, best = INFINITY;
        FILE *f = fopen(path, "rb");
        long bytes = 0;
        if (f) {
            fseek(f, 0, SEEK_END);
            bytes = ftell(f);
            fclose(f);
        }
        for (int rep = 0; rep < 3; rep++) {
            acd_mesh back;
            t0 = bench_wall();
            if (acd_mesh_read(path, &back, &err) != ACD_OK) {
                fprintf(stderr, "%s\n", err.message);
                return 1;
            }
            double tr = bench_wall() - t0;
            if (tr < best) best = tr;
            if (back.ntriangles != m.ntriangles || back.nvertices != m.nvertices) {
                fprintf(stderr, "%s: read %zu vertices %zu triangles\n", fmts[k].ext, back.nvertices, back.ntriangles);
                return 1;
            }
            acd_mesh_free(&back);
        }
        printf("%-10s %12ld %10.3f %10.3f\n", fmts[k].ext, bytes, tw, best);
        unlink(path);
    }
    double t0 = bench_wall();
    acd_mesh_report r;
    if (acd_mesh_validate(&m, 0, &r, &err) != ACD_OK) return 1;
    double tv = bench_wall() - t0;
    printf("validate (no self-intersections): %.3f s (genus %ld)\n", tv, r.genus);
    acd_mesh_report_free(&r);
    t0 = bench_wall();
    if (acd_mesh_validate(&m, 1, &r, &err) != ACD_OK) return 1;
    printf("validate with self-intersections: %.3f s (%zu pairs)\n", bench_wall() - t0, r.self_intersections);
    acd_mesh_report_free(&r);
    acd_mesh_free(&m);
    return 0;
}
