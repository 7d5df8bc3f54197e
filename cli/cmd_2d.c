/* acd 2d INPUT: approximate convex decomposition of every polygon with holes in a file (Lien,
 * dissertation Ch. IV; docs/cli-2d.md). Reads .poly / GeoJSON / WKT, validates, decomposes,
 * optionally rechecks the result independently (--verify) and writes JSON, GeoJSON/.poly and SVG.
 * With --exact mcd|hm the exact baselines of Ch. IV.D (Table 3; include/acd/exact2d.h) replace
 * ACD; their pieces are converted to an acd2d_result (tau 0, each piece its own hull, the
 * diagonals as cuts, no tree) so that every output and the verifier work unchanged. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd2d.h"
#include "acd/exact2d.h"
#include "acd/polygon.h"
#include "acd/verify2d.h"
#include "cli.h"
#include "core/error.h"
#include "export/json2d.h"
#include "export/svg2d.h"

static void usage(FILE *f) {
    fprintf(f,
            "usage: acd 2d INPUT [options]\n"
            "\n"
            "Decomposes every polygon (with its holes) in INPUT (.poly, GeoJSON Polygon/MultiPolygon/\n"
            "Feature/FeatureCollection, TopoJSON, or WKT) into components whose concavity is at most TAU.\n"
            "\n"
            "options:\n"
            "  -t, --tau F          concavity tolerance, model units (relative to R with --normalize;\n"
            "                       default 0: exact convex decomposition)\n"
            "  -m, --measure M      concavity measure: sl, sp, h1, h2 (default sl)\n"
            "      --sc F           weight of concavity in the cut choice, Eqn 4.3 (default 0.1)\n"
            "      --sd F           weight of distance in the cut choice, Eqn 4.3 (default 1)\n"
            "      --cut MODE       ray (cuts may end on an edge; default) or diagonal (vertex to vertex)\n"
            "      --normalize      tau is relative to R, the largest distance of an outer vertex from\n"
            "                       the outer vertices' mean\n"
            "      --notch-eps F    a vertex is a notch when (v-u)x(w-v) < -F (default 1e-5; 0 = exact)\n"
            "      --format F       input format: auto, poly, geojson, topojson, wkt (default auto)\n"
            "      --feature SEL    GeoJSON/TopoJSON: only the features whose id or a property equals\n"
            "                       SEL (e.g. \"South Africa\"), or with SEL = KEY=VALUE property KEY\n"
            "      --object NAME    TopoJSON: only this member of \"objects\" (e.g. countries)\n"
            "      --json FILE      write the report (components, hulls, cuts, tree, stats) as JSON;\n"
            "                       FILE '-' is standard output\n"
            "  -o FILE              write the components as GeoJSON (.geojson, .json) or .poly\n"
            "      --svg FILE       draw input, components, hulls and cuts\n"
            "      --verify         recheck the result independently (partition, areas, tau bound);\n"
            "                       exit 3 naming the failing component if it does not hold\n"
            "      --verify-tau F   with --verify, check the concavity bound against F instead of the\n"
            "                       decomposition's tau (model units)\n"
            "      --exact M        exact convex decomposition instead of ACD: mcd (minimum, Keil &\n"
            "                       Snoeyink; polygons without holes only) or hm (Hertel-Mehlhorn,\n"
            "                       at most 4 x minimum; holes allowed). Not with -t, -m, --sc, --sd,\n"
            "                       --cut, --normalize, --notch-eps\n"
            "  -v, --verbose        report normalization fixes and per-polygon statistics\n"
            "  -h, --help           this text\n"
            "\n"
            "exit codes: 0 ok, 1 bad command line, 2 bad input, 3 verification failed, 4 I/O error,\n"
            "5 internal error.\n");
}

static const char *measure_name(acd2d_measure m) {
    switch (m) {
    case ACD2D_MEASURE_SL: return "sl";
    case ACD2D_MEASURE_SP: return "sp";
    case ACD2D_MEASURE_H1: return "h1";
    case ACD2D_MEASURE_H2: return "h2";
    }
    return "?";
}

static int ends_with(const char *s, const char *suffix) {
    size_t n = strlen(s), m = strlen(suffix);
    if (m > n) return 0;
    for (size_t i = 0; i < m; i++) {
        char a = s[n - m + i], b = suffix[i];
        if (a >= 'A' && a <= 'Z') a = (char)(a - 'A' + 'a');
        if (a != b) return 0;
    }
    return 1;
}

/* Option value: "--opt VALUE" or "--opt=VALUE". Returns NULL (after a message) when missing. */
static const char *opt_value(int argc, char **argv, int *i, const char *name) {
    const char *a = argv[*i];
    size_t n = strlen(name);
    if (!strncmp(a, name, n) && a[n] == '=') return a + n + 1;
    if (*i + 1 >= argc) {
        fprintf(stderr, "acd 2d: option %s needs a value\n", name);
        return NULL;
    }
    return argv[++*i];
}

/* Is argv[i] the option `name` (alone or as "name=...")? */
static int is_opt(const char *a, const char *name) {
    size_t n = strlen(name);
    return !strncmp(a, name, n) && (a[n] == '\0' || (name[1] == '-' && a[n] == '='));
}

/* Writes the components of all results as a polygon set (one polygon per component). */
static acd_status write_components(const char *path, const acd2d_result *res, size_t count, acd_error *err) {
    size_t total = 0;
    for (size_t i = 0; i < count; i++) total += res[i].ncomponents;
    acd_polygon_set set;
    set.count = 0;
    set.polygons = calloc(total ? total : 1, sizeof *set.polygons);
    if (!set.polygons) return acd_fail(err, ACD_ERR_NOMEM, "out of memory for %zu components", total);
    acd_status st = ACD_OK;
    for (size_t i = 0; i < count && st == ACD_OK; i++)
        for (size_t c = 0; c < res[i].ncomponents && st == ACD_OK; c++) {
            const acd_vec2 *ring = res[i].components[c].points;
            size_t n = res[i].components[c].npoints;
            st = acd_polygon_from_rings(&set.polygons[set.count], &ring, &n, 1, err);
            if (st == ACD_OK) set.count++;
        }
    if (st == ACD_OK) {
        if (ends_with(path, ".poly"))
            st = acd_polygon_set_write_poly(&set, path, err);
        else
            st = acd_polygon_set_write_geojson(&set, path, err);
    }
    acd_polygon_set_free(&set);
    return st;
}

static acd_vec2 *copy_points(const acd_vec2 *p, size_t n) {
    acd_vec2 *q = malloc((n ? n : 1) * sizeof *q);
    if (q && n) memcpy(q, p, n * sizeof *q);
    return q;
}

/* An exact decomposition of poly as an acd2d_result (freed with acd2d_result_free): the pieces
 * are the components and, being convex, their own hulls (concavity 0); the diagonals are the
 * cuts; tau 0, measure SL (the verifier's measure); no tree (nnodes 0). */
static acd_status exact_to_result(const acd_polygon *poly, const acd_exact2d_result *ex, acd2d_result *out,
                                  acd_error *err) {
    memset(out, 0, sizeof *out);
    out->tau = 0;
    out->measure = ACD2D_MEASURE_SL;
    out->input_vertices = ex->input_vertices;
    out->input_notches = ex->input_notches;
    out->input_holes = ex->input_holes;
    out->seconds = ex->seconds;
    out->max_concavity = 0;
    out->components = calloc(ex->npieces ? ex->npieces : 1, sizeof *out->components);
    out->cuts = malloc((ex->ndiagonals ? ex->ndiagonals : 1) * sizeof *out->cuts);
    if (!out->components || !out->cuts) goto nomem;
    for (size_t i = 0; i < ex->npieces; i++) {
        acd2d_component *c = &out->components[out->ncomponents];
        c->points = copy_points(ex->pieces[i].points, ex->pieces[i].npoints);
        c->hull = copy_points(ex->pieces[i].points, ex->pieces[i].npoints);
        out->ncomponents++; /* counted before the check so that acd2d_result_free frees both */
        if (!c->points || !c->hull) goto nomem;
        c->npoints = c->nhull = ex->pieces[i].npoints;
        c->concavity = 0;
        c->node = -1;
    }
    size_t npts = poly->nrings ? poly->ring_start[poly->nrings] : 0;
    for (size_t d = 0; d < ex->ndiagonals; d++) {
        size_t a = ex->diagonals[d][0], b = ex->diagonals[d][1];
        if (a >= npts || b >= npts) {
            acd2d_result_free(out);
            return acd_fail(err, ACD_ERR_INTERNAL, "exact decomposition: diagonal %zu joins point %zu and %zu, "
                                                   "but the polygon has %zu points", d, a, b, npts);
        }
        out->cuts[d][0] = poly->points[a];
        out->cuts[d][1] = poly->points[b];
        out->ncuts++;
    }
    return ACD_OK;
nomem:
    acd2d_result_free(out);
    return acd_fail(err, ACD_ERR_NOMEM, "out of memory converting %zu exact pieces", ex->npieces);
}

/* Decomposes poly by the exact method (rechecked by acd_exact2d_verify when verify is set) into
 * an acd2d_result. */
static acd_status exact_decompose(const acd_polygon *poly, acd_exact2d_method m, int verify, acd2d_result *out,
                                  acd_error *err) {
    acd_exact2d_result ex;
    memset(out, 0, sizeof *out);
    acd_status st = acd_exact2d_decompose(poly, m, &ex, err);
    if (st != ACD_OK) return st;
    if (verify) st = acd_exact2d_verify(poly, &ex, err);
    if (st == ACD_OK) st = exact_to_result(poly, &ex, out, err);
    acd_exact2d_result_free(&ex);
    return st;
}

/* The JSON report of an exact decomposition: the ACD report (written without params) with
 * "measure" replaced by "exact-<method>", followed by "params": {"exact": "<method>"} and a note
 * on the empty trees. Returns 0 when out of memory or when the report does not start as expected. */
static int write_exact_json(const char *path, const acd_json2d_doc *doc, acd_exact2d_method m, acd_error *err) {
    char *s = acd_json2d_string(doc);
    if (!s) {
        acd_fail(err, ACD_ERR_NOMEM, "out of memory while building the JSON report");
        return 0;
    }
    static const char key[] = "\"measure\":\"sl\"";
    char *at = strstr(s, key);
    if (!at || at - s > 40) {
        free(s);
        acd_fail(err, ACD_ERR_INTERNAL, "the JSON report does not start with tau and measure");
        return 0;
    }
    const char *name = acd_exact2d_method_name(m);
    int to_stdout = !strcmp(path, "-");
    FILE *f = to_stdout ? stdout : fopen(path, "w");
    if (!f) {
        acd_fail(err, ACD_ERR_IO, "cannot write the JSON report '%s': %s", path, strerror(errno));
        free(s);
        return 0;
    }
    int bad = fwrite(s, 1, (size_t)(at - s), f) != (size_t)(at - s);
    bad |= fprintf(f,
                   "\"measure\":\"exact-%s\",\"params\":{\"exact\":\"%s\"},\"note\":\"exact convex "
                   "decomposition (%s): every component is convex and is its own hull, the cuts are the "
                   "diagonals, there is no decomposition tree\"",
                   name, name, m == ACD_EXACT2D_MCD ? "minimum, Keil-Snoeyink" : "Hertel-Mehlhorn") < 0;
    const char *rest = at + strlen(key);
    size_t len = strlen(rest);
    bad |= fwrite(rest, 1, len, f) != len || fputc('\n', f) == EOF;
    if (to_stdout)
        bad |= fflush(f) != 0;
    else
        bad |= fclose(f) != 0;
    free(s);
    if (bad) {
        acd_fail(err, ACD_ERR_IO, "error writing the JSON report '%s'", path);
        return 0;
    }
    return 1;
}

int acd_cmd_2d(int argc, char **argv) {
    acd2d_params prm = acd2d_default_params();
    const char *input = NULL, *json_path = NULL, *out_path = NULL, *svg_path = NULL;
    acd_polygon_format fmt = ACD_POLY_FORMAT_AUTO;
    const char *feature = NULL, *object = NULL; /* --feature, --object */
    int verify = 0, verbose = 0;
    double verify_tau = -1;
    const char *exact_name = NULL; /* --exact value */
    const char *acd_only = NULL;   /* the first option given that only applies to ACD */
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *val;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return ACD_EXIT_OK;
        } else if (is_opt(a, "-t") || is_opt(a, "--tau")) {
            if (!acd_only) acd_only = a[1] == '-' ? "--tau" : "-t";
            if (!(val = opt_value(argc, argv, &i, a[1] == '-' ? "--tau" : "-t"))) return ACD_EXIT_USAGE;
            if (!acd_cli_parse_double("2d", "--tau", val, &prm.tau)) return ACD_EXIT_USAGE;
            if (prm.tau < 0) {
                fprintf(stderr, "acd 2d: --tau must be >= 0, got %s\n", val);
                return ACD_EXIT_USAGE;
            }
        } else if (is_opt(a, "-m") || is_opt(a, "--measure")) {
            if (!acd_only) acd_only = a[1] == '-' ? "--measure" : "-m";
            if (!(val = opt_value(argc, argv, &i, a[1] == '-' ? "--measure" : "-m"))) return ACD_EXIT_USAGE;
            if (!acd2d_measure_parse(val, &prm.measure)) {
                fprintf(stderr, "acd 2d: --measure must be sl, sp, h1 or h2, got '%s'\n", val);
                return ACD_EXIT_USAGE;
            }
        } else if (is_opt(a, "--sc")) {
            if (!acd_only) acd_only = "--sc";
            if (!(val = opt_value(argc, argv, &i, "--sc"))) return ACD_EXIT_USAGE;
            if (!acd_cli_parse_double("2d", "--sc", val, &prm.sc)) return ACD_EXIT_USAGE;
            if (prm.sc < 0) {
                fprintf(stderr, "acd 2d: --sc must be >= 0, got %s\n", val);
                return ACD_EXIT_USAGE;
            }
        } else if (is_opt(a, "--sd")) {
            if (!acd_only) acd_only = "--sd";
            if (!(val = opt_value(argc, argv, &i, "--sd"))) return ACD_EXIT_USAGE;
            if (!acd_cli_parse_double("2d", "--sd", val, &prm.sd)) return ACD_EXIT_USAGE;
            if (!(prm.sd > 0)) {
                fprintf(stderr, "acd 2d: --sd must be > 0, got %s\n", val);
                return ACD_EXIT_USAGE;
            }
        } else if (is_opt(a, "--notch-eps")) {
            if (!acd_only) acd_only = "--notch-eps";
            if (!(val = opt_value(argc, argv, &i, "--notch-eps"))) return ACD_EXIT_USAGE;
            if (!acd_cli_parse_double("2d", "--notch-eps", val, &prm.notch_tolerance)) return ACD_EXIT_USAGE;
            if (prm.notch_tolerance < 0) {
                fprintf(stderr, "acd 2d: --notch-eps must be >= 0, got %s\n", val);
                return ACD_EXIT_USAGE;
            }
        } else if (is_opt(a, "--cut")) {
            if (!acd_only) acd_only = "--cut";
            if (!(val = opt_value(argc, argv, &i, "--cut"))) return ACD_EXIT_USAGE;
            if (!strcmp(val, "ray"))
                prm.cut = ACD2D_CUT_RAY;
            else if (!strcmp(val, "diagonal"))
                prm.cut = ACD2D_CUT_DIAGONAL;
            else {
                fprintf(stderr, "acd 2d: --cut must be ray or diagonal, got '%s'\n", val);
                return ACD_EXIT_USAGE;
            }
        } else if (is_opt(a, "--format")) {
            if (!(val = opt_value(argc, argv, &i, "--format"))) return ACD_EXIT_USAGE;
            if (!strcmp(val, "auto"))
                fmt = ACD_POLY_FORMAT_AUTO;
            else if (!strcmp(val, "poly"))
                fmt = ACD_POLY_FORMAT_POLY;
            else if (!strcmp(val, "geojson"))
                fmt = ACD_POLY_FORMAT_GEOJSON;
            else if (!strcmp(val, "wkt"))
                fmt = ACD_POLY_FORMAT_WKT;
            else if (!strcmp(val, "topojson"))
                fmt = ACD_POLY_FORMAT_TOPOJSON;
            else {
                fprintf(stderr, "acd 2d: --format must be auto, poly, geojson, topojson or wkt, got '%s'\n", val);
                return ACD_EXIT_USAGE;
            }
        } else if (is_opt(a, "--feature")) {
            if (!(feature = opt_value(argc, argv, &i, "--feature"))) return ACD_EXIT_USAGE;
        } else if (is_opt(a, "--object")) {
            if (!(object = opt_value(argc, argv, &i, "--object"))) return ACD_EXIT_USAGE;
        } else if (!strcmp(a, "--normalize")) {
            prm.normalize = 1;
            if (!acd_only) acd_only = "--normalize";
        } else if (is_opt(a, "--exact")) {
            if (!(exact_name = opt_value(argc, argv, &i, "--exact"))) return ACD_EXIT_USAGE;
        } else if (is_opt(a, "--json")) {
            if (!(json_path = opt_value(argc, argv, &i, "--json"))) return ACD_EXIT_USAGE;
        } else if (is_opt(a, "-o") || is_opt(a, "--output")) {
            if (!(out_path = opt_value(argc, argv, &i, a[1] == '-' ? "--output" : "-o"))) return ACD_EXIT_USAGE;
            if (!ends_with(out_path, ".geojson") && !ends_with(out_path, ".json") && !ends_with(out_path, ".poly")) {
                fprintf(stderr, "acd 2d: -o needs a .geojson, .json or .poly file name, got '%s'\n", out_path);
                return ACD_EXIT_USAGE;
            }
        } else if (is_opt(a, "--svg")) {
            if (!(svg_path = opt_value(argc, argv, &i, "--svg"))) return ACD_EXIT_USAGE;
        } else if (is_opt(a, "--verify-tau")) {
            if (!(val = opt_value(argc, argv, &i, "--verify-tau"))) return ACD_EXIT_USAGE;
            if (!acd_cli_parse_double("2d", "--verify-tau", val, &verify_tau)) return ACD_EXIT_USAGE;
            if (verify_tau < 0) {
                fprintf(stderr, "acd 2d: --verify-tau must be >= 0, got %s\n", val);
                return ACD_EXIT_USAGE;
            }
            verify = 1;
        } else if (!strcmp(a, "--verify")) {
            verify = 1;
        } else if (!strcmp(a, "-v") || !strcmp(a, "--verbose")) {
            verbose = 1;
        } else if (a[0] == '-' && a[1] != '\0') {
            fprintf(stderr, "acd 2d: unknown option '%s' (see acd 2d --help)\n", a);
            return ACD_EXIT_USAGE;
        } else if (!input) {
            input = a;
        } else {
            fprintf(stderr, "acd 2d: one input file expected, got '%s' and '%s'\n", input, a);
            return ACD_EXIT_USAGE;
        }
    }
    if (!input) {
        usage(stderr);
        return ACD_EXIT_USAGE;
    }
    acd_exact2d_method exact_m = ACD_EXACT2D_MCD;
    if (exact_name) {
        if (!acd_exact2d_method_parse(exact_name, &exact_m)) {
            fprintf(stderr, "acd 2d: --exact takes mcd or hm, got '%s'\n", exact_name);
            return ACD_EXIT_USAGE;
        }
        if (acd_only) {
            fprintf(stderr, "acd 2d: %s applies to the approximate decomposition only; it cannot be combined "
                            "with --exact %s\n", acd_only, exact_name);
            return ACD_EXIT_USAGE;
        }
        /* the verifier checks the exact pieces at tau 0 with exact notches */
        prm.notch_tolerance = 0;
    }
    /* the summary goes to stderr when the JSON report takes standard output */
    FILE *info = json_path && !strcmp(json_path, "-") ? stderr : stdout;

    acd_error err;
    acd_polygon_set set = {NULL, 0};
    acd_polygon_fixes fixes;
    memset(&fixes, 0, sizeof fixes);
    acd_polygon_read_options ropt;
    memset(&ropt, 0, sizeof ropt);
    ropt.format = fmt;
    ropt.feature = feature;
    ropt.object = object;
    acd_status st = acd_polygon_set_read_file_opts(&set, input, &ropt, &fixes, &err);
    if (st != ACD_OK) return acd_cli_report("2d", &err);
    if (set.count == 0) {
        fprintf(stderr, "acd 2d: %s: %s: no polygon in the file\n", acd_status_string(ACD_ERR_INVALID_INPUT), input);
        acd_polygon_set_free(&set);
        return ACD_EXIT_BAD_INPUT;
    }
    if (verbose) {
        fprintf(stderr, "acd 2d: read %s: %zu polygon%s; normalization dropped %zu repeated vertices, reversed %zu rings",
                input, set.count, set.count == 1 ? "" : "s", fixes.repeated_dropped, fixes.rings_reversed);
        if (fixes.chains_ignored) fprintf(stderr, ", ignored %zu chains beyond the declared count", fixes.chains_ignored);
        fprintf(stderr, "\n");
    }
    for (size_t i = 0; i < set.count; i++) {
        st = acd_polygon_validate(&set.polygons[i], i, &err);
        if (st != ACD_OK) {
            fprintf(stderr, "acd 2d: %s: %s: %s\n", acd_status_string(st), input, err.message);
            acd_polygon_set_free(&set);
            return acd_cli_exit_code(st);
        }
    }

    acd2d_result *res = calloc(set.count, sizeof *res);
    if (!res) {
        fprintf(stderr, "acd 2d: out of memory\n");
        acd_polygon_set_free(&set);
        return ACD_EXIT_INTERNAL;
    }
    size_t done = 0;
    int code = ACD_EXIT_OK;
    for (; done < set.count; done++) {
        if (exact_name)
            st = exact_decompose(&set.polygons[done], exact_m, verify, &res[done], &err);
        else
            st = acd2d_decompose(&set.polygons[done], &prm, &res[done], &err);
        if (st != ACD_OK) {
            fprintf(stderr, "acd 2d: %s: %s: polygon %zu: %s\n", acd_status_string(st), input, done, err.message);
            code = acd_cli_exit_code(st);
            break;
        }
    }

    size_t ncomp = 0, nv = 0, nr = 0, nh = 0;
    double maxc = 0, secs = 0;
    for (size_t i = 0; i < done; i++) {
        ncomp += res[i].ncomponents;
        nv += res[i].input_vertices;
        nr += res[i].input_notches;
        nh += res[i].input_holes;
        secs += res[i].seconds;
        if (res[i].max_concavity > maxc) maxc = res[i].max_concavity;
    }

    /* independent recheck */
    int verified = 0;
    char vmsg[ACD_ERROR_MESSAGE_SIZE + 64] = "";
    if (code == ACD_EXIT_OK && verify) {
        verified = 1;
        size_t base = 0;
        for (size_t i = 0; i < done; i++) {
            acd_verify2d_report rep;
            acd2d_result r = res[i]; /* shallow copy: only the bound to check may differ */
            if (verify_tau >= 0) r.tau = verify_tau;
            st = acd_verify2d_result(&set.polygons[i], &r, &prm, base, &rep, &err);
            if (st != ACD_OK) {
                snprintf(vmsg, sizeof vmsg, "polygon %zu: %s", i, err.message);
                verified = -1;
                code = acd_cli_exit_code(st);
                break;
            }
            base += res[i].ncomponents;
        }
        if (verified > 0)
            snprintf(vmsg, sizeof vmsg, "%zu components: interior-disjoint, inside the input, areas add up, "
                                        "concavity <= %g (%s)", ncomp, verify_tau >= 0 ? verify_tau : res[0].tau,
                     measure_name(prm.measure));
        if (verified > 0 && exact_name && verify_tau < 0)
            snprintf(vmsg, sizeof vmsg, "%zu components: interior-disjoint, inside the input, areas add up, "
                                        "convex (concavity 0, exact notches, sl)", ncomp);
    }

    /* outputs (also after a failed verification: they help to see what went wrong) */
    if (done == set.count) {
        if (json_path) {
            acd_json2d_doc doc = {exact_name ? NULL : &prm, set.polygons, res, done, verified, verified ? vmsg : NULL};
            acd_error werr;
            int ok = exact_name ? write_exact_json(json_path, &doc, exact_m, &werr)
                                : acd_json2d_write(json_path, &doc, &werr) == ACD_OK;
            if (!ok) {
                fprintf(stderr, "acd 2d: %s: %s\n", acd_status_string(werr.status), werr.message);
                if (code == ACD_EXIT_OK) code = acd_cli_exit_code(werr.status);
            }
        }
        if (out_path) {
            acd_error werr;
            if (write_components(out_path, res, done, &werr) != ACD_OK) {
                fprintf(stderr, "acd 2d: %s: %s\n", acd_status_string(werr.status), werr.message);
                if (code == ACD_EXIT_OK) code = acd_cli_exit_code(werr.status);
            }
        }
        if (svg_path) {
            acd_svg2d_options so = acd_svg2d_default_options();
            char title[256];
            if (exact_name)
                snprintf(title, sizeof title, "%s: exact %s, %zu components", input, exact_name, ncomp);
            else
                snprintf(title, sizeof title, "%s: tau %g (%s), %zu components", input, res[0].tau,
                         measure_name(prm.measure), ncomp);
            so.title = title;
            acd_error werr;
            if (acd_svg2d_write(svg_path, set.polygons, res, done, &so, &werr) != ACD_OK) {
                fprintf(stderr, "acd 2d: %s: %s\n", acd_status_string(werr.status), werr.message);
                if (code == ACD_EXIT_OK) code = acd_cli_exit_code(werr.status);
            }
        }
        if (verbose)
            for (size_t i = 0; i < done; i++)
                fprintf(stderr,
                        "acd 2d: polygon %zu: %zu vertices, %zu notches, %zu holes -> %zu components, %zu cuts, "
                        "max concavity %.6g, %.6f s\n",
                        i, res[i].input_vertices, res[i].input_notches, res[i].input_holes, res[i].ncomponents,
                        res[i].ncuts, res[i].max_concavity, res[i].seconds);
        char taubuf[96];
        if (exact_name)
            snprintf(taubuf, sizeof taubuf, "exact %s", exact_name);
        else if (prm.normalize)
            snprintf(taubuf, sizeof taubuf, "tau %g x R (%g model units in polygon 0)", prm.tau, res[0].tau);
        else
            snprintf(taubuf, sizeof taubuf, "tau %g", prm.tau);
        fprintf(info,
                "%s: %zu polygon%s, %zu vertices, %zu notches, %zu holes; %s%s%s: %zu components, "
                "max concavity %.6g, %.6f s\n",
                input, done, done == 1 ? "" : "s", nv, nr, nh, taubuf, exact_name ? "" : ", measure ",
                exact_name ? "" : measure_name(prm.measure), ncomp, maxc, secs);
        if (verified > 0) fprintf(info, "verify: passed: %s\n", vmsg);
    }
    if (verified < 0) fprintf(stderr, "acd 2d: verify failed: %s\n", vmsg);
    for (size_t i = 0; i < done; i++) acd2d_result_free(&res[i]);
    free(res);
    acd_polygon_set_free(&set);
    return code;
}
