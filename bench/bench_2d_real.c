/* bench_2d_real: real-world polygons beyond the dissertation's (countries with enclaves from npm
 * world-atlas TopoJSON, CGAL's straight-skeleton samples with 20 and 11 holes, DejaVu glyphs with
 * holes), decomposed by ACD (SL at tau = 0 and at tau = 0.01 R, 0.05 R, R the radius of
 * --normalize), Hertel-Mehlhorn and, without holes, MCD. Not a test. Driven by
 * scripts/bench-2d-experiments.sh (see docs/experiments-2d.md); the data come from
 * scripts/fetch-data.sh (data/2d, docs/data.md).
 *
 * usage: bench_2d_real --data DIR --out DIR [--reps N] [--mcd-max N]
 * Writes OUT/real/models.csv (name,source,vertices,holes,notches), OUT/real/results.csv
 * (name,method,tau_rel,pieces,cpu_s,convexity,verified), each polygon used as
 * OUT/real/<name>.poly (for the pictures drawn by `acd 2d`) and, without holes, its ring as
 * OUT/polys/<name>.txt for the peer harnesses. A polygon whose file is missing is skipped with a
 * message. When a selection holds several polygons (a country's islands) the largest by area
 * is taken. Times: process CPU time of the decomposition call, best of N (default 3; 1 above
 * 2000 vertices). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "acd/acd2d.h"
#include "acd/exact2d.h"
#include "acd/polygon.h"
#include "acd/verify2d.h"

#include "bench_clock.h"

static double ring_area(const acd_vec2 *p, size_t n) {
    double a = 0;
    for (size_t i = 0; i < n; i++) a += p[i].x * p[(i + 1) % n].y - p[(i + 1) % n].x * p[i].y;
    return 0.5 * a;
}

typedef struct real_model {
    const char *name, *file, *feature, *source;
} real_model;

static const real_model MODELS[] = {
    {"south-africa-50m", "world-atlas/countries-50m.json", "South Africa", "world-atlas 50m (Lesotho as hole)"},
    {"south-africa-10m", "world-atlas/countries-10m.json", "South Africa", "world-atlas 10m (Lesotho as hole)"},
    {"italy-50m", "world-atlas/countries-50m.json", "name=Italy", "world-atlas 50m (San Marino and Vatican as holes)"},
    {"kyrgyzstan-50m", "world-atlas/countries-50m.json", "Kyrgyzstan", "world-atlas 50m (exclaves of Uzbekistan and Tajikistan as holes)"},
    {"norway-50m", "world-atlas/countries-50m.json", "Norway", "world-atlas 50m (mainland with fjords)"},
    {"cgal-skeleton-1", "cgal/straight_skeleton_sample_1.poly", NULL, "CGAL Straight_skeleton_2 sample_1.dat"},
    {"cgal-skeleton-2", "cgal/straight_skeleton_sample_2.poly", NULL, "CGAL Straight_skeleton_2 sample_2.dat"},
    {"cgal-skeleton-3", "cgal/straight_skeleton_sample_3.poly", NULL, "CGAL Straight_skeleton_2 sample_3.dat"},
    {"glyph-B", "glyphs/dejavu-sans-B.poly", NULL, "DejaVu Sans 'B'"},
    {"glyph-8", "glyphs/dejavu-sans-8.poly", NULL, "DejaVu Sans '8'"},
    {"glyph-at", "glyphs/dejavu-sans-at.poly", NULL, "DejaVu Sans '@'"},
};
static const double TAU_REL[] = {0, 0.01, 0.05};

/* The largest polygon (by area) of the file's selection, validated, into *out. */
static int load(const char *path, const char *feature, acd_polygon *out) {
    acd_polygon_read_options o;
    memset(&o, 0, sizeof o);
    o.feature = feature;
    acd_polygon_set set;
    acd_error err;
    if (acd_polygon_set_read_file_opts(&set, path, &o, NULL, &err) != ACD_OK) {
        fprintf(stderr, "bench_2d_real: %s\n", err.message);
        return 0;
    }
    size_t best = 0;
    for (size_t i = 1; i < set.count; i++)
        if (acd_polygon_area(&set.polygons[i]) > acd_polygon_area(&set.polygons[best])) best = i;
    int ok = acd_polygon_validate(&set.polygons[best], best, &err) == ACD_OK;
    if (!ok)
        fprintf(stderr, "bench_2d_real: %s: %s\n", path, err.message);
    else
        ok = acd_polygon_copy(out, &set.polygons[best]) == ACD_OK;
    acd_polygon_set_free(&set);
    return ok;
}

static int run_acd(const acd_polygon *p, double tau_rel, int reps, FILE *res, const char *name, size_t *notches) {
    acd2d_params prm = acd2d_default_params();
    prm.tau = tau_rel;
    prm.normalize = 1;
    double best = -1, conv = 1;
    size_t nc = 0;
    const char *ver = "-";
    for (int r = 0; r < reps; r++) {
        acd2d_result out;
        acd_error err;
        double c0 = bench_cpu();
        acd_status st = acd2d_decompose(p, &prm, &out, &err);
        double c = bench_cpu() - c0;
        if (st != ACD_OK) {
            fprintf(stderr, "bench_2d_real: %s acd tau %g R: %s\n", name, tau_rel, err.message);
            fprintf(res, "%s,acd-sl,%g,,,,error\n", name, tau_rel);
            return 0;
        }
        if (best < 0 || c < best) best = c;
        if (r == 0) {
            double a = 0, h = 0;
            for (size_t i = 0; i < out.ncomponents; i++) {
                a += ring_area(out.components[i].points, out.components[i].npoints);
                h += ring_area(out.components[i].hull, out.components[i].nhull);
            }
            conv = h > 0 ? a / h : 1;
            nc = out.ncomponents;
            *notches = out.input_notches;
            acd_verify2d_report rep;
            ver = acd_verify2d_result(p, &out, &prm, 0, &rep, &err) == ACD_OK ? "pass" : "FAIL";
        }
        acd2d_result_free(&out);
    }
    fprintf(res, "%s,acd-sl,%g,%zu,%.6g,%.6f,%s\n", name, tau_rel, nc, best, conv, ver);
    return ver[0] == 'p';
}

static int run_exact(const acd_polygon *p, acd_exact2d_method m, int reps, FILE *res, const char *name) {
    double best = -1;
    size_t np = 0;
    int ver = 0;
    for (int r = 0; r < reps; r++) {
        acd_exact2d_result out;
        acd_error err;
        double c0 = bench_cpu();
        acd_status st = acd_exact2d_decompose(p, m, &out, &err);
        double c = bench_cpu() - c0;
        if (st != ACD_OK) {
            fprintf(stderr, "bench_2d_real: %s %s: %s\n", name, acd_exact2d_method_name(m), err.message);
            fprintf(res, "%s,%s,0,,,,error\n", name, acd_exact2d_method_name(m));
            return 0;
        }
        if (best < 0 || c < best) best = c;
        if (r == 0) {
            np = out.npieces;
            ver = acd_exact2d_verify(p, &out, &err) == ACD_OK;
        }
        acd_exact2d_result_free(&out);
    }
    fprintf(res, "%s,%s,0,%zu,%.6g,1,%s\n", name, acd_exact2d_method_name(m), np, best, ver ? "pass" : "FAIL");
    return ver;
}

static int write_outer(const char *path, const acd_polygon *p) {
    FILE *f = fopen(path, "w");
    if (!f) return 0;
    size_t n = acd_polygon_ring_size(p, 0);
    fprintf(f, "%zu\n", n);
    for (size_t i = 0; i < n; i++) fprintf(f, "%.17g %.17g\n", p->points[i].x, p->points[i].y);
    return fclose(f) == 0;
}

int main(int argc, char **argv) {
    const char *dir = "data/2d", *out = "build/exper2d";
    int reps = 3;
    size_t mcd_max = 3000;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--data") && i + 1 < argc) dir = argv[++i];
        else if (!strcmp(argv[i], "--out") && i + 1 < argc) out = argv[++i];
        else if (!strcmp(argv[i], "--reps") && i + 1 < argc) reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--mcd-max") && i + 1 < argc) mcd_max = (size_t)atol(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_2d_real --data DIR --out DIR [--reps N] [--mcd-max N]\n");
            return 2;
        }
    }
    if (reps < 1) reps = 1;
    char path[4096];
    const char *subs[] = {"", "/real", "/polys"};
    for (int k = 0; k < 3; k++) {
        snprintf(path, sizeof path, "%s%s", out, subs[k]);
        if (mkdir(path, 0777) != 0 && errno != EEXIST) {
            fprintf(stderr, "bench_2d_real: cannot create %s: %s\n", path, strerror(errno));
            return 1;
        }
    }
    snprintf(path, sizeof path, "%s/real/models.csv", out);
    FILE *mo = fopen(path, "w");
    snprintf(path, sizeof path, "%s/real/results.csv", out);
    FILE *res = fopen(path, "w");
    if (!mo || !res) {
        fprintf(stderr, "bench_2d_real: cannot write into %s/real\n", out);
        return 1;
    }
    fprintf(mo, "name,source,vertices,holes,notches\n");
    fprintf(res, "name,method,tau_rel,pieces,cpu_s,convexity,verified\n");
    int rc = 0;
    for (size_t k = 0; k < sizeof MODELS / sizeof *MODELS; k++) {
        const real_model *m = &MODELS[k];
        snprintf(path, sizeof path, "%s/%s", dir, m->file);
        if (access(path, R_OK) != 0) {
            fprintf(stderr, "bench_2d_real: %s missing (scripts/fetch-data.sh): %s skipped\n", path, m->name);
            continue;
        }
        acd_polygon p;
        if (!load(path, m->feature, &p)) {
            rc = 1;
            continue;
        }
        size_t n = acd_polygon_num_points(&p), holes = p.nrings - 1, notches = 0;
        int r = n > 2000 ? 1 : reps;
        for (size_t t = 0; t < sizeof TAU_REL / sizeof *TAU_REL; t++)
            if (!run_acd(&p, TAU_REL[t], r, res, m->name, &notches)) rc = 1;
        if (!run_exact(&p, ACD_EXACT2D_HM, r, res, m->name)) rc = 1;
        if (holes == 0 && n <= mcd_max) {
            if (!run_exact(&p, ACD_EXACT2D_MCD, r, res, m->name)) rc = 1;
        } else {
            fprintf(res, "%s,mcd,0,,,,%s\n", m->name, holes ? "holes" : "skipped");
        }
        fprintf(mo, "%s,%s,%zu,%zu,%zu\n", m->name, m->source, n, holes, notches);
        acd_polygon_set one = {&p, 1};
        acd_error err;
        snprintf(path, sizeof path, "%s/real/%s.poly", out, m->name);
        if (acd_polygon_set_write_poly(&one, path, &err) != ACD_OK) {
            fprintf(stderr, "bench_2d_real: %s\n", err.message);
            rc = 1;
        }
        if (holes == 0) {
            snprintf(path, sizeof path, "%s/polys/%s.txt", out, m->name);
            if (!write_outer(path, &p)) rc = 1;
        }
        fprintf(stderr, "bench_2d_real: %s done (%zu vertices, %zu holes)\n", m->name, n, holes);
        fflush(res);
        acd_polygon_free(&p);
    }
    if (fclose(mo) != 0 || fclose(res) != 0) rc = 1;
    return rc;
}
