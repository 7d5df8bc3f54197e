/* acd eval MESH DECOMP.obj: scores a 3D decomposition (ours or a peer's: one part per OBJ o/g
 * group, as V-HACD and CoACD write them) against its mesh. docs/eval.md. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/eval.h"
#include "acd/export.h"
#include "acd/hull.h"
#include "acd/mesh.h"
#include "cli.h"

static void usage(FILE *f) {
    fprintf(f,
            "usage: acd eval MESH DECOMP.obj [options]\n"
            "\n"
            "Scores the decomposition DECOMP.obj (one part per o/g group; the convex hull of each\n"
            "part is taken) against MESH: volumes, IoU, coverage, excess (stratified Monte Carlo) and\n"
            "the two-sided distance between the mesh surface and the boundary of the union of hulls,\n"
            "divided by the mesh's bounding-box diagonal. Deterministic for a given seed.\n"
            "\n"
            "options:\n"
            "  --json                 print the report as JSON\n"
            "  --samples N            volume samples (default 1000000)\n"
            "  --surface-samples N    surface samples, each way (default 200000)\n"
            "  --seed S               random seed (default 1)\n"
            "  -o FILE                write the report to FILE instead of stdout\n"
            "  --export DIR           also write the decomposition's hulls for other tools: one OBJ with\n"
            "                         a group per hull, one file per hull and part, summary.json, URDF\n"
            "                         and MuJoCo MJCF (docs/eval.md, Exports)\n"
            "  --max-hull-vertices N  with --export: simplify each hull to at most N (>= 4) vertices,\n"
            "                         still enclosing it\n"
            "  --name NAME            with --export: model name (default acd)\n"
            "  -h, --help             this text\n");
}

static void print_text(FILE *f, const acd_eval_report *r) {
    fprintf(f, "parts              %zu", r->parts);
    if (r->degenerate_parts) fprintf(f, " (%zu flat, left out)", r->degenerate_parts);
    fprintf(f, "\n");
    fprintf(f, "hull vertices      %zu\n", r->hull_vertices);
    fprintf(f, "mesh volume        %.10g%s\n", r->mesh_volume, r->mesh_closed ? "" : " (open mesh: generalized winding number)");
    fprintf(f, "hull volume sum    %.10g\n", r->hull_volume_sum);
    fprintf(f, "union volume       %.10g\n", r->union_volume);
    fprintf(f, "iou                %.6f\n", r->iou);
    fprintf(f, "coverage           %.6f\n", r->coverage);
    fprintf(f, "excess             %.6f\n", r->excess);
    fprintf(f, "mesh -> hulls      max %.6g  mean %.6g\n", r->mesh_to_hulls_max, r->mesh_to_hulls_mean);
    fprintf(f, "hulls -> mesh      max %.6g  mean %.6g\n", r->hulls_to_mesh_max, r->hulls_to_mesh_mean);
    fprintf(f, "concavity max      %.6g   (distances / diagonal %.6g)\n", r->concavity_max, r->diagonal);
    fprintf(f, "samples            %zu volume, %zu surface, %zu on the union's boundary, seed %llu\n", r->samples,
            r->surface_samples, r->boundary_samples, (unsigned long long)r->seed);
    fprintf(f, "seconds            %.3f\n", r->seconds);
}

int acd_cmd_eval(int argc, char **argv) {
    const char *paths[2] = {NULL, NULL}, *outpath = NULL, *export_dir = NULL;
    acd_export_options xo = acd_export_default_options();
    int npaths = 0, json = 0;
    acd_eval_params prm = acd_eval_default_params();
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return ACD_EXIT_OK;
        } else if (!strcmp(a, "--json")) {
            json = 1;
        } else if (!strcmp(a, "--samples") || !strcmp(a, "--surface-samples") || !strcmp(a, "--seed") ||
                   !strcmp(a, "-o") || !strcmp(a, "--export") || !strcmp(a, "--max-hull-vertices") ||
                   !strcmp(a, "--name")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "acd eval: option %s needs a value\n", a);
                return ACD_EXIT_USAGE;
            }
            const char *v = argv[++i];
            size_t n;
            if (!strcmp(a, "-o")) {
                outpath = v;
            } else if (!strcmp(a, "--export")) {
                export_dir = v;
            } else if (!strcmp(a, "--name")) {
                xo.name = v;
            } else if (!strcmp(a, "--max-hull-vertices")) {
                if (!acd_cli_parse_size("eval", a, v, &n)) return ACD_EXIT_USAGE;
                if (n < 4) {
                    fprintf(stderr, "acd eval: option %s needs at least 4, got '%s'\n", a, v);
                    return ACD_EXIT_USAGE;
                }
                xo.max_hull_vertices = n;
            } else {
                if (!acd_cli_parse_size("eval", a, v, &n)) return ACD_EXIT_USAGE;
                if (!strcmp(a, "--seed")) {
                    prm.seed = (uint64_t)n;
                } else if (n < 1) {
                    fprintf(stderr, "acd eval: option %s needs at least 1, got '%s'\n", a, v);
                    return ACD_EXIT_USAGE;
                } else if (!strcmp(a, "--samples")) {
                    prm.samples = n;
                } else {
                    prm.surface_samples = n;
                }
            }
        } else if (a[0] == '-' && a[1] != '\0') {
            fprintf(stderr, "acd eval: unknown option '%s'\n", a);
            usage(stderr);
            return ACD_EXIT_USAGE;
        } else if (npaths < 2) {
            paths[npaths++] = a;
        } else {
            fprintf(stderr, "acd eval: too many arguments ('%s')\n", a);
            return ACD_EXIT_USAGE;
        }
    }
    if (npaths != 2) {
        fprintf(stderr, "acd eval: needs MESH and DECOMP.obj\n");
        usage(stderr);
        return ACD_EXIT_USAGE;
    }
    acd_error err;
    acd_mesh mesh = {0};
    acd_mesh_parts parts = {0};
    if (acd_cli_read_mesh("eval", paths[0], &mesh, &err) != ACD_OK) return acd_cli_report("eval", &err);
    if (acd_cli_read_parts("eval", paths[1], &parts, &err) != ACD_OK) {
        acd_mesh_free(&mesh);
        return acd_cli_report("eval", &err);
    }
    acd_eval_report rep;
    acd_hull *hulls = calloc(parts.count ? parts.count : 1, sizeof *hulls);
    acd_status st = ACD_OK;
    if (!hulls) {
        st = err.status = ACD_ERR_NOMEM;
        snprintf(err.message, sizeof err.message, "out of memory for %zu hulls", parts.count);
    }
    for (size_t i = 0; i < parts.count && st == ACD_OK; i++) {
        const acd_mesh *pm = &parts.parts[i].mesh;
        acd_error e2;
        st = acd_hull_compute(pm->vertices, pm->nvertices, &hulls[i], &e2);
        if (st != ACD_OK) {
            err.status = st;
            snprintf(err.message, sizeof err.message, "%s: hull of part %zu ('%.100s'): %.300s", paths[1], i,
                     parts.parts[i].name ? parts.parts[i].name : "", e2.message);
        }
    }
    if (st == ACD_OK) st = acd_eval_hulls(&mesh, hulls, parts.count, &prm, &rep, &err);
    if (st == ACD_OK && export_dir) st = acd_export_all(export_dir, &parts, hulls, parts.count, &rep, &xo, &err);
    for (size_t i = 0; hulls && i < parts.count; i++) acd_hull_free(&hulls[i]);
    free(hulls);
    acd_mesh_free(&mesh);
    acd_mesh_parts_free(&parts);
    if (st != ACD_OK) return acd_cli_report("eval", &err);
    FILE *f = stdout;
    if (outpath && !(f = fopen(outpath, "w"))) {
        fprintf(stderr, "acd eval: %s: cannot open '%s' for writing\n", acd_status_string(ACD_ERR_IO), outpath);
        return ACD_EXIT_IO;
    }
    if (json) {
        char *js;
        if (acd_eval_report_json(&rep, &js, &err) != ACD_OK) {
            if (f != stdout) fclose(f);
            return acd_cli_report("eval", &err);
        }
        fprintf(f, "%s\n", js);
        free(js);
    } else {
        print_text(f, &rep);
    }
    int bad = ferror(f);
    if (f != stdout) bad |= fclose(f) != 0;
    if (bad) {
        fprintf(stderr, "acd eval: %s: writing the report failed\n", acd_status_string(ACD_ERR_IO));
        return ACD_EXIT_IO;
    }
    return ACD_EXIT_OK;
}
