/* bench_validate: time of acd_polygon_validate (sweep line) against the adaptive subdivision and
 * the O(n^2) brute force, on generated polygons and on Lien's largest files. Prints a markdown
 * table; each time is the best of 3 runs (the machine is shared).
 * Usage: bench_validate [max_n]   (default 100000; 1000000 adds the million-vertex rows) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "acd/polygon.h"
#include "core/rng.h"
#include "geom2/validate.h"

#include "bench_clock.h"

#define BV_PI 3.14159265358979323846

/* kind 0: circle with radius noise about the vertex spacing; kind 1: spiky comb (radius
 * 900..1000, spikes 1600 times longer than their spacing at n = 1e5); kind 2: circle plus a
 * grid of n/50 octagonal holes. */
static int make(acd_polygon *p, int kind, size_t n) {
    size_t nh = kind == 2 ? n / 50 : 0, hm = 8;
    size_t side = (size_t)ceil(sqrt((double)nh));
    acd_vec2 *pts = malloc((n + nh * hm) * sizeof *pts);
    const acd_vec2 **rings = malloc((nh + 1) * sizeof *rings);
    size_t *sizes = malloc((nh + 1) * sizeof *sizes);
    if (!pts || !rings || !sizes) return 0;
    acd_rng rng;
    acd_rng_seed(&rng, 42);
    double spacing = 2 * BV_PI * 1000 / (double)n;
    for (size_t i = 0; i < n; i++) {
        double a = 2 * BV_PI * (double)i / (double)n;
        double r = kind == 1 ? 900 + 100 * acd_rng_uniform(&rng) : 1000 + spacing * acd_rng_uniform(&rng);
        pts[i].x = r * cos(a);
        pts[i].y = r * sin(a);
    }
    rings[0] = pts;
    sizes[0] = n;
    double cell = side ? 1200.0 / (double)side : 1;
    for (size_t h = 0; h < nh; h++) {
        double cx = -600 + cell * ((double)(h % side) + 0.5), cy = -600 + cell * ((double)(h / side) + 0.5);
        rings[h + 1] = pts + n + h * hm;
        sizes[h + 1] = hm;
        for (size_t i = 0; i < hm; i++) {
            double a = -2 * BV_PI * (double)i / (double)hm;
            pts[n + h * hm + i].x = cx + 0.3 * cell * cos(a);
            pts[n + h * hm + i].y = cy + 0.3 * cell * sin(a);
        }
    }
    acd_error err;
    int ok = acd_polygon_from_rings(p, rings, sizes, nh + 1, &err) == ACD_OK;
    free(pts);
    free((void *)rings);
    free(sizes);
    return ok;
}

static void row(const char *name, const acd_polygon *p) {
    acd_error err;
    acd_status st = ACD_OK, sd = ACD_OK;
    double fast = 1e30, sub = 1e30;
    for (int rep = 0; rep < 3; rep++) {
        double t0 = bench_wall();
        st = acd_polygon_validate(p, 0, &err);
        fast = fmin(fast, bench_wall() - t0);
        t0 = bench_wall();
        sd = acd_polygon_validate_with(p, 0, ACD_VALIDATE_SUBDIV, NULL);
        sub = fmin(sub, bench_wall() - t0);
    }
    size_t n = acd_polygon_num_points(p);
    char brute[32] = "-";
    if (n <= 20000) {
        double t0 = bench_wall();
        acd_status sb = acd_polygon_validate_with(p, 0, ACD_VALIDATE_BRUTE, NULL);
        snprintf(brute, sizeof brute, "%.1f ms%s", 1000 * (bench_wall() - t0), sb == st ? "" : " (DISAGREES)");
    }
    printf("| %s | %zu | %zu | %s | %.2f ms | %.2f ms%s | %s |\n", name, n, p->nrings - 1,
           st == ACD_OK ? "valid" : "invalid", 1000 * fast, 1000 * sub, sd == st ? "" : " (DISAGREES)", brute);
}

int main(int argc, char **argv) {
    size_t max_n = argc > 1 ? (size_t)strtoull(argv[1], NULL, 10) : 100000;
    printf("| polygon | vertices | holes | result | sweep (default) | subdivision | brute force |\n|---|---|---|---|---|---|---|\n");
    static const char *const kinds[] = {"noisy circle", "spiky comb", "circle + holes"};
    for (int kind = 0; kind < 3; kind++)
        for (size_t n = 1000; n <= max_n; n *= 10) {
            acd_polygon p;
            if (!make(&p, kind, n)) return 1;
            row(kinds[kind], &p);
            acd_polygon_free(&p);
        }
    static const char *const files[] = {"nazca_nazca_monkey_2", "star_star6", "hole5", "wierd2_n"};
    for (size_t f = 0; f < sizeof files / sizeof *files; f++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/polygons-lien/%s.poly", ACD_SHARED_DATA, files[f]);
        acd_polygon_set s;
        acd_error err;
        if (acd_polygon_set_read_file(&s, path, ACD_POLY_FORMAT_AUTO, NULL, &err) != ACD_OK) continue;
        row(files[f], &s.polygons[0]);
        acd_polygon_set_free(&s);
    }
    return 0;
}
