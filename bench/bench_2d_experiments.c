/* bench_2d_experiments: the dissertation's 2D experiments (Lien, IV.D; spec
 * ../shared/spec/acd2d.md §7, §9), regenerated as machine-readable output. Not a test.
 *
 *   sweep:  every model x {sl, sp, h1, h2} x tau in {0, 0.001, 0.01, 0.05, 0.1, 0.2, 0.5, 1, 2, 5,
 *           10, 20, 40}: components, CPU seconds and the convexity of Eqn 4.4
 *           (sum of component areas / sum of their convex hulls' areas) -> OUT/sweep.csv
 *           (Figs. 25-28 panels b, c, d; Table 1 is the monkey1 rows at tau 40/20/10/1); the SL runs
 *           are rechecked by acd_verify2d_result (column verified: pass / FAIL / - when not checked)
 *   exact:  MCD (Keil-Snoeyink, no Steiner points) and Hertel-Mehlhorn of include/acd/exact2d.h on
 *           the hole-free models -> OUT/exact.csv (Table 3 with the sweep's tau 0 and 0.1 rows)
 *   polys:  each model's outer ring, counterclockwise, as OUT/polys/<model>.txt ("n" then n lines
 *           "x y"), the input of the peer harnesses in bench/peers/
 *
 *   bench_2d_experiments --check POLYFILE PIECESFILE
 *           reads a peer's pieces (first line: count; then one piece per line: "n x1 y1 ... xn yn")
 *           and prints one CSV line "pieces,input_area,pieces_area,covered,verify": covered = sum of
 *           the pieces' areas / input area, verify = the first check of acd_verify2d that fails
 *           (or "pass"), with the concavity check off (peers decompose exactly, tau = 0).
 *
 * usage: bench_2d_experiments [--data DIR] [--out DIR] [--reps N] [--mcd-max N]
 * Times are process CPU time (the machine is shared), best of N runs (default 3, 1 above 2000
 * vertices). The polygons are read from DIR (default ../shared/data/polygons-lien), never copied
 * into the repository. Driven by scripts/bench-2d-experiments.sh; see docs/experiments-2d.md. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "acd/acd2d.h"
#include "acd/exact2d.h"
#include "acd/polygon.h"
#include "acd/verify2d.h"

#include "bench_clock.h"

/* Shoelace area (positive for counterclockwise). */
static double ring_area(const acd_vec2 *p, size_t n) {
    double a = 0;
    for (size_t i = 0; i < n; i++) {
        const acd_vec2 *u = &p[i], *v = &p[(i + 1) % n];
        a += u->x * v->y - v->x * u->y;
    }
    return 0.5 * a;
}

static int load(const char *path, acd_polygon_set *set) {
    acd_error err;
    if (acd_polygon_set_read_file(set, path, ACD_POLY_FORMAT_AUTO, NULL, &err) != ACD_OK) {
        fprintf(stderr, "bench_2d_experiments: %s: %s\n", path, err.message);
        return 0;
    }
    for (size_t i = 0; i < set->count; i++)
        if (acd_polygon_validate(&set->polygons[i], i, &err) != ACD_OK) {
            fprintf(stderr, "bench_2d_experiments: %s: %s\n", path, err.message);
            acd_polygon_set_free(set);
            return 0;
        }
    if (set->count == 0) {
        fprintf(stderr, "bench_2d_experiments: %s: no polygon\n", path);
        acd_polygon_set_free(set);
        return 0;
    }
    return 1;
}

static const char *MODELS[][2] = {
    {"maze", "wierd2_n"},   {"monkey1", "nazca_nazca_monkey"}, {"monkey2", "nazca_nazca_monkey_2"},
    {"heron1", "nazca_nazca_heron"}, {"texas", "texas"},   {"bird", "bird"},
};
static const double TAUS[] = {0, 0.001, 0.01, 0.05, 0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 40};

/* One decomposition, best CPU time of reps. Returns 0 on failure (message printed). */
static int run_acd(const acd_polygon *p, acd2d_measure m, double tau, int reps, size_t *ncomp, double *sec,
                   double *convexity, double *maxconc, const char **verified) {
    acd2d_params prm = acd2d_default_params();
    prm.measure = m;
    prm.tau = tau;
    *sec = -1;
    for (int r = 0; r < reps; r++) {
        acd2d_result res;
        acd_error err;
        double c0 = bench_cpu();
        acd_status st = acd2d_decompose(p, &prm, &res, &err);
        double c = bench_cpu() - c0;
        if (st != ACD_OK) {
            fprintf(stderr, "bench_2d_experiments: %s tau %g: %s\n", acd2d_measure_name(m), tau, err.message);
            return 0;
        }
        if (*sec < 0 || c < *sec) *sec = c;
        if (r == 0) {
            double a = 0, h = 0;
            for (size_t i = 0; i < res.ncomponents; i++) {
                a += ring_area(res.components[i].points, res.components[i].npoints);
                h += ring_area(res.components[i].hull, res.components[i].nhull);
            }
            *ncomp = res.ncomponents;
            *convexity = h > 0 ? a / h : 1;
            *maxconc = res.max_concavity;
            *verified = "-";
            if (m == ACD2D_MEASURE_SL) { /* the verifier's SL is cheap; SP's recomputation is not */
                acd_verify2d_report rep;
                *verified = acd_verify2d_result(p, &res, &prm, 0, &rep, &err) == ACD_OK ? "pass" : "FAIL";
            }
        }
        acd2d_result_free(&res);
    }
    return 1;
}

static int run_exact(const acd_polygon *p, acd_exact2d_method m, int reps, size_t *npieces, double *sec,
                     int *verified) {
    *sec = -1;
    for (int r = 0; r < reps; r++) {
        acd_exact2d_result res;
        acd_error err;
        double c0 = bench_cpu();
        acd_status st = acd_exact2d_decompose(p, m, &res, &err);
        double c = bench_cpu() - c0;
        if (st != ACD_OK) {
            fprintf(stderr, "bench_2d_experiments: %s: %s\n", acd_exact2d_method_name(m), err.message);
            return 0;
        }
        if (*sec < 0 || c < *sec) *sec = c;
        if (r == 0) {
            *npieces = res.npieces;
            *verified = acd_exact2d_verify(p, &res, &err) == ACD_OK;
        }
        acd_exact2d_result_free(&res);
    }
    return 1;
}

static int write_outer(const char *path, const acd_polygon *p) {
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "bench_2d_experiments: cannot write %s: %s\n", path, strerror(errno));
        return 0;
    }
    size_t n = p->ring_start[1] - p->ring_start[0];
    fprintf(f, "%zu\n", n);
    for (size_t i = 0; i < n; i++) fprintf(f, "%.17g %.17g\n", p->points[i].x, p->points[i].y);
    int ok = fclose(f) == 0;
    return ok;
}

/* --check: area covered by a peer's pieces and the verifier's verdict. */
static int check(const char *polyfile, const char *piecesfile) {
    acd_polygon_set set;
    if (!load(polyfile, &set)) return 1;
    const acd_polygon *p = &set.polygons[0];
    FILE *f = fopen(piecesfile, "r");
    if (!f) {
        fprintf(stderr, "bench_2d_experiments: cannot read %s: %s\n", piecesfile, strerror(errno));
        acd_polygon_set_free(&set);
        return 1;
    }
    size_t count = 0;
    int rc = 1;
    acd_vec2 **pieces = NULL;
    size_t *sizes = NULL;
    if (fscanf(f, "%zu", &count) != 1 || count > 10000000) goto bad;
    pieces = calloc(count ? count : 1, sizeof *pieces);
    sizes = calloc(count ? count : 1, sizeof *sizes);
    if (!pieces || !sizes) goto bad;
    double parea = 0;
    for (size_t i = 0; i < count; i++) {
        if (fscanf(f, "%zu", &sizes[i]) != 1 || sizes[i] > 100000000) goto bad;
        pieces[i] = malloc((sizes[i] ? sizes[i] : 1) * sizeof **pieces);
        if (!pieces[i]) goto bad;
        for (size_t k = 0; k < sizes[i]; k++)
            if (fscanf(f, "%lf %lf", &pieces[i][k].x, &pieces[i][k].y) != 2) goto bad;
        double a = ring_area(pieces[i], sizes[i]);
        if (a < 0) { /* the verifier wants counterclockwise pieces */
            for (size_t k = 0; k < sizes[i] / 2; k++) {
                acd_vec2 t = pieces[i][k];
                pieces[i][k] = pieces[i][sizes[i] - 1 - k];
                pieces[i][sizes[i] - 1 - k] = t;
            }
            a = -a;
        }
        parea += a;
    }
    double iarea = 0;
    for (size_t r = 0; r < p->nrings; r++)
        iarea += ring_area(p->points + p->ring_start[r], p->ring_start[r + 1] - p->ring_start[r]);
    acd_verify2d_options opt = acd_verify2d_default_options();
    opt.check_concavity = 0;
    acd_verify2d_report rep;
    acd_error err;
    acd_status st = acd_verify2d(p, (const acd_vec2 *const *)pieces, sizes, count, &opt, &rep, &err);
    const char *verdict = st == ACD_OK ? "pass" : st == ACD_ERR_VERIFY ? acd_verify2d_check_name(rep.failed) : "error";
    printf("%zu,%.17g,%.17g,%.6f,%s\n", count, iarea, parea, iarea > 0 ? parea / iarea : 0, verdict);
    rc = 0;
    goto done;
bad:
    fprintf(stderr, "bench_2d_experiments: %s: malformed pieces file or out of memory\n", piecesfile);
done:
    if (pieces)
        for (size_t i = 0; i < count; i++) free(pieces[i]);
    free(pieces);
    free(sizes);
    fclose(f);
    acd_polygon_set_free(&set);
    return rc;
}

int main(int argc, char **argv) {
    const char *dir = ACD_SHARED_DATA "/polygons-lien";
    const char *out = "build/exper2d";
    int reps = 3;
    size_t mcd_max = 3000;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--check") && i + 2 < argc) return check(argv[i + 1], argv[i + 2]);
        else if (!strcmp(argv[i], "--data") && i + 1 < argc) dir = argv[++i];
        else if (!strcmp(argv[i], "--out") && i + 1 < argc) out = argv[++i];
        else if (!strcmp(argv[i], "--reps") && i + 1 < argc) reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--mcd-max") && i + 1 < argc) mcd_max = (size_t)atol(argv[++i]);
        else {
            fprintf(stderr,
                    "usage: bench_2d_experiments [--data DIR] [--out DIR] [--reps N] [--mcd-max N]\n"
                    "       bench_2d_experiments --check POLYFILE PIECESFILE\n");
            return 2;
        }
    }
    if (reps < 1) reps = 1;
    char path[4096];
    snprintf(path, sizeof path, "%s/polys", out);
    if ((mkdir(out, 0777) != 0 && errno != EEXIST) || (mkdir(path, 0777) != 0 && errno != EEXIST)) {
        fprintf(stderr, "bench_2d_experiments: cannot create %s: %s\n", path, strerror(errno));
        return 1;
    }
    snprintf(path, sizeof path, "%s/sweep.csv", out);
    FILE *sw = fopen(path, "w");
    snprintf(path, sizeof path, "%s/exact.csv", out);
    FILE *ex = fopen(path, "w");
    snprintf(path, sizeof path, "%s/models.csv", out);
    FILE *mo = fopen(path, "w");
    if (!sw || !ex || !mo) {
        fprintf(stderr, "bench_2d_experiments: cannot write into %s\n", out);
        return 1;
    }
    fprintf(sw, "model,measure,tau,components,cpu_s,convexity,max_concavity,verified\n");
    fprintf(ex, "model,method,pieces,cpu_s,verified\n");
    fprintf(mo, "model,file,vertices,notches,holes\n");
    int rc = 0;
    for (size_t k = 0; k < sizeof MODELS / sizeof *MODELS; k++) {
        const char *model = MODELS[k][0];
        snprintf(path, sizeof path, "%s/%s.poly", dir, MODELS[k][1]);
        acd_polygon_set set;
        if (!load(path, &set)) {
            rc = 1;
            continue;
        }
        const acd_polygon *p = &set.polygons[0];
        size_t n = acd_polygon_num_points(p);
        int r = n > 2000 ? 1 : reps;
        size_t notches = 0;
        for (int m = 0; m < 4; m++)
            for (size_t t = 0; t < sizeof TAUS / sizeof *TAUS; t++) {
                size_t nc = 0;
                double sec, conv = 0, mc = 0;
                const char *ver = "-";
                if (!run_acd(p, (acd2d_measure)m, TAUS[t], r, &nc, &sec, &conv, &mc, &ver)) {
                    fprintf(sw, "%s,%s,%g,,,,,error\n", model, acd2d_measure_name((acd2d_measure)m), TAUS[t]);
                    rc = 1;
                    continue;
                }
                fprintf(sw, "%s,%s,%g,%zu,%.6g,%.6f,%.6g,%s\n", model, acd2d_measure_name((acd2d_measure)m), TAUS[t],
                        nc, sec, conv, mc, ver);
                if (ver[0] == 'F') rc = 1;
            }
        {
            acd2d_params prm = acd2d_default_params();
            acd2d_result res;
            acd_error err;
            prm.tau = 1e300; /* only the input statistics are wanted */
            if (acd2d_decompose(p, &prm, &res, &err) == ACD_OK) {
                notches = res.input_notches;
                acd2d_result_free(&res);
            }
        }
        fprintf(mo, "%s,%s,%zu,%zu,%zu\n", model, MODELS[k][1], n, notches, p->nrings - 1);
        for (int m = 0; m < 2; m++) {
            acd_exact2d_method em = m == 0 ? ACD_EXACT2D_MCD : ACD_EXACT2D_HM;
            if (p->nrings > 1 || (em == ACD_EXACT2D_MCD && n > mcd_max)) {
                fprintf(ex, "%s,%s,,,skipped\n", model, acd_exact2d_method_name(em));
                continue;
            }
            size_t np = 0;
            double sec;
            int ver = 0;
            if (run_exact(p, em, r, &np, &sec, &ver))
                fprintf(ex, "%s,%s,%zu,%.6g,%s\n", model, acd_exact2d_method_name(em), np, sec, ver ? "pass" : "FAIL");
            else
                fprintf(ex, "%s,%s,,,error\n", model, acd_exact2d_method_name(em));
        }
        snprintf(path, sizeof path, "%s/polys/%s.txt", out, model);
        if (!write_outer(path, p)) rc = 1;
        fprintf(stderr, "bench_2d_experiments: %s done\n", model);
        fflush(sw);
        fflush(ex);
        acd_polygon_set_free(&set);
    }
    if (fclose(sw) != 0 || fclose(ex) != 0 || fclose(mo) != 0) rc = 1;
    return rc;
}
