/* acd 2d INPUT: approximate convex decomposition of every polygon with holes in a file (Lien,
 * dissertation Ch. IV; docs/cli-2d.md). Reads .poly / GeoJSON / WKT, validates, decomposes,
 * optionally rechecks the result independently (--verify) and writes JSON, GeoJSON/.poly and SVG. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd2d.h"
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
            "Feature/FeatureCollection, or WKT) into components whose concavity is at most TAU.\n"
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
            "      --format F       input format: auto, poly, geojson, wkt (default auto)\n"
            "      --json FILE      write the report (components, hulls, cuts, tree, stats) as JSON;\n"
            "                       FILE '-' is standard output\n"
            "  -o FILE              write the components as GeoJSON (.geojson, .json) or .poly\n"
            "      --svg FILE       draw input, components, hulls and cuts\n"
            "      --verify         recheck the result independently (partition, areas, tau bound);\n"
            "                       exit 3 naming the failing component if it does not hold\n"
            "      --verify-tau F   with --verify, check the concavity bound against F instead of the\n"
            "                       decomposition's tau (model units)\n"
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

int acd_cmd_2d(int argc, char **argv) {
    acd2d_params prm = acd2d_default_params();
    const char *input = NULL, *json_path = NULL, *out_path = NULL, *svg_path = NULL;
    acd_polygon_format fmt = ACD_POLY_FORMAT_AUTO;
    int verify = 0, verbose = 0;
    double verify_tau = -1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *val;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return ACD_EXIT_OK;
        } else if (is_opt(a, "-t") || is_opt(a, "--tau")) {
            if (!(val = opt_value(argc, argv, &i, a[1] == '-' ? "--tau" : "-t"))) return ACD_EXIT_USAGE;
            if (!acd_cli_parse_double("2d", "--tau", val, &prm.tau)) return ACD_EXIT_USAGE;
            if (prm.tau < 0) {
                fprintf(stderr, "acd 2d: --tau must be >= 0, got %s\n", val);
                return ACD_EXIT_USAGE;
            }
        } else if (is_opt(a, "-m") || is_opt(a, "--measure")) {
            if (!(val = opt_value(argc, argv, &i, a[1] == '-' ? "--measure" : "-m"))) return ACD_EXIT_USAGE;
            if (!acd2d_measure_parse(val, &prm.measure)) {
                fprintf(stderr, "acd 2d: --measure must be sl, sp, h1 or h2, got '%s'\n", val);
                return ACD_EXIT_USAGE;
            }
        } else if (is_opt(a, "--sc")) {
            if (!(val = opt_value(argc, argv, &i, "--sc"))) return ACD_EXIT_USAGE;
            if (!acd_cli_parse_double("2d", "--sc", val, &prm.sc)) return ACD_EXIT_USAGE;
            if (prm.sc < 0) {
                fprintf(stderr, "acd 2d: --sc must be >= 0, got %s\n", val);
                return ACD_EXIT_USAGE;
            }
        } else if (is_opt(a, "--sd")) {
            if (!(val = opt_value(argc, argv, &i, "--sd"))) return ACD_EXIT_USAGE;
            if (!acd_cli_parse_double("2d", "--sd", val, &prm.sd)) return ACD_EXIT_USAGE;
            if (!(prm.sd > 0)) {
                fprintf(stderr, "acd 2d: --sd must be > 0, got %s\n", val);
                return ACD_EXIT_USAGE;
            }
        } else if (is_opt(a, "--notch-eps")) {
            if (!(val = opt_value(argc, argv, &i, "--notch-eps"))) return ACD_EXIT_USAGE;
            if (!acd_cli_parse_double("2d", "--notch-eps", val, &prm.notch_tolerance)) return ACD_EXIT_USAGE;
            if (prm.notch_tolerance < 0) {
                fprintf(stderr, "acd 2d: --notch-eps must be >= 0, got %s\n", val);
                return ACD_EXIT_USAGE;
            }
        } else if (is_opt(a, "--cut")) {
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
            else {
                fprintf(stderr, "acd 2d: --format must be auto, poly, geojson or wkt, got '%s'\n", val);
                return ACD_EXIT_USAGE;
            }
        } else if (!strcmp(a, "--normalize")) {
            prm.normalize = 1;
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
    /* the summary goes to stderr when the JSON report takes standard output */
    FILE *info = json_path && !strcmp(json_path, "-") ? stderr : stdout;

    acd_error err;
    acd_polygon_set set = {NULL, 0};
    acd_polygon_fixes fixes;
    memset(&fixes, 0, sizeof fixes);
    acd_status st = acd_polygon_set_read_file(&set, input, fmt, &fixes, &err);
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
    }

    /* outputs (also after a failed verification: they help to see what went wrong) */
    if (done == set.count) {
        if (json_path) {
            acd_json2d_doc doc = {&prm, set.polygons, res, done, verified, verified ? vmsg : NULL};
            acd_error werr;
            if (acd_json2d_write(json_path, &doc, &werr) != ACD_OK) {
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
        if (prm.normalize)
            snprintf(taubuf, sizeof taubuf, "tau %g x R (%g model units in polygon 0)", prm.tau, res[0].tau);
        else
            snprintf(taubuf, sizeof taubuf, "tau %g", prm.tau);
        fprintf(info,
                "%s: %zu polygon%s, %zu vertices, %zu notches, %zu holes; %s, measure %s: %zu components, "
                "max concavity %.6g, %.6f s\n",
                input, done, done == 1 ? "" : "s", nv, nr, nh, taubuf, measure_name(prm.measure), ncomp, maxc, secs);
        if (verified > 0) fprintf(info, "verify: passed: %s\n", vmsg);
    }
    if (verified < 0) fprintf(stderr, "acd 2d: verify failed: %s\n", vmsg);
    for (size_t i = 0; i < done; i++) acd2d_result_free(&res[i]);
    free(res);
    acd_polygon_set_free(&set);
    return code;
}
