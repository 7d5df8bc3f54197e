/* bench_2d_far_xform IN OUT off|scale K [FEATURE]: writes IN (any 2D format; FEATURE selects
 * GeoJSON/TopoJSON features, e.g. "name=Italy") as .poly with every coordinate translated by
 * K x the set's extent on both axes (off) or multiplied by K (scale), in double precision as a
 * user's georeferenced copy would be. Used by bench/bench_2d_far.py (docs/results/2d-far.md). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include "acd/polygon.h"
int main(int argc, char **argv) {
    if (argc < 5) { fprintf(stderr, "usage\n"); return 1; }
    acd_polygon_set s; acd_error err; memset(&err, 0, sizeof err);
    acd_polygon_read_options o; memset(&o, 0, sizeof o);
    if (argc > 5) o.feature = argv[5];
    if (argc > 6) o.object = argv[6];
    if (acd_polygon_set_read_file_opts(&s, argv[1], &o, NULL, &err) != ACD_OK) { fprintf(stderr, "read: %s\n", err.message); return 2; }
    double K = atof(argv[4]);
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (size_t i = 0; i < s.count; i++) {
        acd_polygon *p = &s.polygons[i];
        for (size_t k = 0; k < acd_polygon_num_points(p); k++) {
            x0 = fmin(x0, p->points[k].x); x1 = fmax(x1, p->points[k].x);
            y0 = fmin(y0, p->points[k].y); y1 = fmax(y1, p->points[k].y);
        }
    }
    double ext = hypot(x1 - x0, y1 - y0);
    int off = strcmp(argv[3], "off") == 0;
    double d = K * ext;
    for (size_t i = 0; i < s.count; i++) {
        acd_polygon *p = &s.polygons[i];
        for (size_t k = 0; k < acd_polygon_num_points(p); k++) {
            if (off) { p->points[k].x += d; p->points[k].y += d; }
            else { p->points[k].x *= K; p->points[k].y *= K; }
        }
    }
    if (acd_polygon_set_write_poly(&s, argv[2], &err) != ACD_OK) { fprintf(stderr, "write: %s\n", err.message); return 4; }
    acd_polygon_set_free(&s);
    return 0;
}
