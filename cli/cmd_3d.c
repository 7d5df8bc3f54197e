/* acd 3d: approximate convex decomposition of a polyhedron (solid mode), writing the convex
 * hulls (one OBJ group each), the parts, and a JSON summary with the tree. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "acd/acd3d.h"
#include "acd/export.h"
#include "acd/hull.h"
#include "acd/mesh.h"
#include "acd/verify3d.h"
#include "cli.h"
#include "core/error.h"
#include "geom3/volume.h"

static void usage(FILE *f) {
    fprintf(f,
            "usage: acd 3d INPUT [--budget N] [-t TAU] [--tau-abs] [-o HULLS.obj] [--parts PARTS.obj] [--json FILE]\n"
            "              [--mode solid|surface] [--max-hulls N] [--max-hull-vertices N] [--threads N] [--region-cuts]\n"
            "              [--no-merge] [--merge-tau T] [--merge-tau-diag F] [--merge-order bound|volume]\n"
            "              [--trim-coverage F]\n"
            "              [--merge-parts N] [--merge-refine N]\n"
            "              [--cut-choice concavity|volume|band] [--no-close-holes] [--resolver global|witness|notch]\n"
            "              [--cut-weight ratio|product] [--surface-cut strip|cycle|cycle-witness] [--eps-ratio R]\n"
            "              [--no-feature-grouping] [--stop measure|hull] [--verify] [-v]\n"
            "\n"
            "Decomposes a triangle mesh (closed for solid mode; OBJ, OFF, PLY, STL, optionally gzip-compressed) into parts\n"
            "whose concavity is at most TAU, and outputs their convex hulls.\n"
            "\n"
            "  --budget N          the tightest hulls at N parts (solid mode): after the decomposition the\n"
            "                      parts are split further, best first by the hull volume a plane cut saves,\n"
            "                      until N parts exist, and every part until it is within the merge\n"
            "                      tolerance of its hull both ways; then the merge pass (default 0: off).\n"
            "                      It implies, for the options not given: -t 10 (no tau-driven split: the\n"
            "                      input alone is split) --merge-tau-diag 0.0195 (joined parts within 0.0195\n"
            "                      of the bounding-box diagonal) --cut-choice volume --merge-order volume\n"
            "                      --merge-parts N --merge-refine 40 (with --no-merge only the first three).\n"
            "                      The settings that ran are printed and in --json (\"settings\")\n"
            "  -t TAU              concavity tolerance, relative to the radius of the minimum enclosing\n"
            "                      sphere (default 0.05); with --tau-abs in model units\n"
            "  --mode solid        parts are closed solids, cut by planes with capped sections (default)\n"
            "  --mode surface      parts are surface patches split along cut loops (open meshes welcome)\n"
            "  -o HULLS.obj        the convex hulls, one 'o hull_N' group each, full precision\n"
            "  --parts PARTS.obj   the parts themselves, one group each\n"
            "  --resolver global   solid mode: cut first by the plane of the global cut (knots, pocket cuts,\n"
            "                      minimum-weight cycle of the cut graph), then by planes through the most\n"
            "                      concave vertex (default)\n"
            "  --resolver witness  only the planes through the most concave vertex\n"
            "  --resolver notch    only the plane bisecting the most reflex edge at the most concave vertex\n"
            "                      (notch cutting; the witness planes when that vertex has no reflex edge)\n"
            "  --eps-ratio R       bridge clustering threshold eps = R * TAU (default 0.5; 0: none)\n"
            "  --no-feature-grouping  the variant without feature grouping (spec A14): --eps-ratio 0\n"
            "                      --resolver notch --region-cuts\n"
            "  --cut-weight ratio  global cut weight W = omega/gamma (paper Eqn 4, default); 'product':\n"
            "                      W = omega*gamma (dissertation Eqn 5.2)\n"
            "  --region-cuts       cut only the section region at the most concave vertex (spec A13)\n"
            "  --surface-cut strip surface mode: split along a cut plane's section strip (default);\n"
            "                      'cycle': first along the global cut's cycle of pocket cuts when it\n"
            "                      separates the part; 'cycle-witness': the cycle through the witness\n"
            "  --json FILE         summary: per part concavity, volume, hull volume; the tree\n"
            "  --export DIR        for other tools: decomposition.obj, hulls/, parts/, summary.json,\n"
            "                      NAME.urdf (one collision per hull), NAME.xml (MuJoCo); --name NAME\n"
            "  --max-hulls N       merge the cheapest adjacent parts (undo the splits of least concavity)\n"
            "                      until at most N remain; the concavity reached is reported\n"
            "  --no-merge          keep every part of the decomposition (by default adjacent parts are\n"
            "                      joined while the result stays within tau: solid, the joined hull\n"
            "                      within tau of the joined part; surface, the welded patch's concavity)\n"
            "  --merge-tau T       the merge pass's tolerance, in the units of TAU (default: TAU)\n"
            "  --merge-tau-diag F  the merge pass's tolerance as a fraction F of the bounding-box diagonal\n"
            "                      (instead of --merge-tau)\n"
            "  --merge-order bound solid merge pass: the joinable pair of smallest bound first (default);\n"
            "                      'volume': the pair whose joined hull adds the least volume first\n"
            "  --merge-parts N     solid merge pass: stop as soon as at most N parts remain (default: join\n"
            "                      while a pair is joinable)\n"
            "  --merge-refine N    with --merge-parts: up to N refinement steps after the joins, each a cut\n"
            "                      of the part whose volume plane saves the most hull volume and a join of\n"
            "                      the cheapest pair, while the hulls' volume falls (default 0)\n"
            "  --cut-choice concavity  solid mode: the candidate cut of least piece concavity (default);\n"
            "                      'volume': planes chosen for tight hulls join the candidates, and the\n"
            "                      smallest sum of the pieces' hull volumes wins within a band of concavity;\n"
            "                      'band': that rule on the default's candidates (no extra cost)\n"
            "  --stop measure      a part is a leaf when its measure (depth below its bridge patch's plane,\n"
            "                      the paper's) is at most TAU (default)\n"
            "  --stop hull         also when its surface and its hull's boundary are within TAU of each\n"
            "                      other both ways (upper bounds; leaf reason \"hull_distance\")\n"
            "  --max-hull-vertices N  each hull replaced by an enclosing one of at most N (>= 4) vertices\n"
            "  --trim-coverage F   solid mode: trim the hulls where they are mostly air over the parts' relief\n"
            "                      (caps cut off by planes), leaving at most F (<= 0.01) of the input's volume\n"
            "                      outside the union of hulls; the hulls stay convex. Off by default: every\n"
            "                      hull then encloses its part\n"
            "  --threads N         worker threads (default: all cores); the output is the same for any N\n"
            "  --no-close-holes    solid mode refuses an open mesh instead of closing its holes (by default\n"
            "                      an open or unoriented input is welded, oriented and its holes closed)\n"
            "  --verify            check: part volumes add up to the input's, every part meets tau (or says\n"
            "                      why not), every part lies inside its hull (with --trim-coverage: the parts'\n"
            "                      volume outside their hulls, measured by cutting each part with its hull's\n"
            "                      planes, is within F of the input's); exit 3 otherwise\n"
            "  -v                  report progress and statistics on stderr\n");
}

typedef struct progress_state {
    struct timespec start, last;
    int verbose;
} progress_state;

static double since(const struct timespec *a, const struct timespec *b) {
    return (double)(b->tv_sec - a->tv_sec) + 1e-9 * (double)(b->tv_nsec - a->tv_nsec);
}

static int on_progress(void *user, double fraction, const char *stage) {
    progress_state *ps = user;
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    if (since(&ps->start, &now) > 1.0 && since(&ps->last, &now) > 1.0) {
        if (fraction >= 0) fprintf(stderr, "acd 3d: %s %.0f%% (%.1f s)\n", stage, 100 * fraction, since(&ps->start, &now));
        else fprintf(stderr, "acd 3d: %s (%.1f s)\n", stage, since(&ps->start, &now));
        ps->last = now;
    }
    return 0;
}

static const char *cut_choice_name(acd3d_cut_choice c) {
    return c == ACD3D_CHOICE_VOLUME ? "volume" : c == ACD3D_CHOICE_BAND ? "band" : "concavity";
}

static const char *merge_order_name(acd3d_merge_order o) { return o == ACD3D_MERGE_VOLUME ? "volume" : "bound"; }

/* The settings that ran, when --budget implied some (or --merge-tau-diag was given): as options on
 * stdout, with the merge tolerance in TAU's units at full precision (the command line that gives the
 * same run), and as the JSON's "settings". Not written for other command lines, whose output stays
 * as it was. */
static void print_settings(const acd3d_result *r, const acd3d_params *p) {
    printf("settings:");
    if (p->budget_parts > 0) printf(" --budget %zu", p->budget_parts);
    printf(" -t %.17g%s --merge-tau %.17g", p->tau, p->tau_absolute ? " --tau-abs" : "",
           p->tau_absolute ? r->merge_tau : r->merge_tau_relative);
    if (p->merge_tau == 0 && p->merge_tau_diag > 0) printf(" (%.6g x diagonal)", p->merge_tau_diag);
    printf(" --cut-choice %s", cut_choice_name(p->cut_choice));
    if (!p->merge) printf(" --no-merge");
    else {
        printf(" --merge-order %s", merge_order_name(p->merge_order));
        if (p->merge_parts > 0) printf(" --merge-parts %zu", p->merge_parts);
        if (p->merge_refine > 0) printf(" --merge-refine %zu", p->merge_refine);
    }
    printf("\n");
}

static void settings_json(cJSON *o, const acd3d_result *r, const acd3d_params *p, const char *const *implied,
                          size_t nimplied) {
    cJSON *q = cJSON_AddObjectToObject(o, "settings");
    if (!q) return;
    cJSON_AddNumberToObject(q, "budget", (double)p->budget_parts);
    cJSON_AddNumberToObject(q, "tau", r->tau);
    cJSON_AddNumberToObject(q, "tau_relative", r->scale > 0 ? r->tau / r->scale : 0);
    cJSON_AddNumberToObject(q, "merge_tau", r->merge_tau);
    cJSON_AddNumberToObject(q, "merge_tau_relative", r->merge_tau_relative);
    if (p->merge_tau == 0 && p->merge_tau_diag > 0) cJSON_AddNumberToObject(q, "merge_tau_diag", p->merge_tau_diag);
    cJSON_AddStringToObject(q, "cut_choice", cut_choice_name(p->cut_choice));
    cJSON_AddBoolToObject(q, "merge", p->merge != 0);
    cJSON_AddStringToObject(q, "merge_order", merge_order_name(p->merge_order));
    cJSON_AddNumberToObject(q, "merge_parts", (double)p->merge_parts);
    cJSON_AddNumberToObject(q, "merge_refine", (double)p->merge_refine);
    cJSON *imp = cJSON_AddArrayToObject(q, "implied");
    for (size_t i = 0; imp && i < nimplied; i++) cJSON_AddItemToArray(imp, cJSON_CreateString(implied[i]));
}

static int write_parts(const char *path, const acd3d_result *r, int hulls, acd_error *err) {
    acd_mesh_parts parts = {0};
    char(*names)[32] = malloc((r->nparts ? r->nparts : 1) * sizeof *names);
    parts.parts = calloc(r->nparts ? r->nparts : 1, sizeof *parts.parts);
    acd_status st;
    if (!names || !parts.parts) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    } else {
        parts.count = r->nparts;
        for (size_t i = 0; i < r->nparts; i++) {
            snprintf(names[i], sizeof names[i], "%s_%zu", hulls ? "hull" : "part", i);
            parts.parts[i].name = names[i]; /* borrowed: the writer only reads */
            parts.parts[i].mesh = hulls ? r->parts[i].hull : r->parts[i].mesh;
        }
        st = acd_mesh_write_obj_parts(path, &parts, err);
    }
    free(names);
    free(parts.parts);
    return st;
}

/* --export DIR: the hulls for other tools (OBJ groups, one file per hull, the parts, summary.json,
 * URDF and MJCF), through the library's exporter. */
static int export_dir(const char *dir, const char *name, const acd3d_result *r, acd_error *err) {
    acd_hull *hulls = calloc(r->nparts ? r->nparts : 1, sizeof *hulls);
    acd_mesh_parts parts = {0};
    char(*names)[32] = malloc((r->nparts ? r->nparts : 1) * sizeof *names);
    parts.parts = calloc(r->nparts ? r->nparts : 1, sizeof *parts.parts);
    acd_status st = ACD_OK;
    if (!hulls || !names || !parts.parts) st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    size_t made = 0;
    for (size_t i = 0; st == ACD_OK && i < r->nparts; i++, made++) {
        st = acd_hull_compute(r->parts[i].hull.vertices, r->parts[i].hull.nvertices, &hulls[i], err);
        snprintf(names[i], sizeof names[i], "part_%zu", i);
        parts.parts[i].name = names[i]; /* borrowed: the exporter only reads */
        parts.parts[i].mesh = r->parts[i].mesh;
    }
    parts.count = r->nparts;
    if (st == ACD_OK) {
        acd_export_options xo = acd_export_default_options();
        if (name) xo.name = name;
        st = acd_export_all(dir, &parts, hulls, r->nparts, NULL, &xo, err);
    }
    for (size_t i = 0; i < made; i++) acd_hull_free(&hulls[i]);
    free(hulls), free(names), free(parts.parts);
    return st;
}

static cJSON *result_json(const char *input, const acd3d_result *r, const acd3d_params *p) {
    cJSON *o = cJSON_CreateObject();
    if (!o) return NULL;
    cJSON_AddStringToObject(o, "input", input);
    cJSON_AddStringToObject(o, "mode", p->mode == ACD3D_SOLID ? "solid" : "surface");
    cJSON_AddNumberToObject(o, "tau", r->tau);
    cJSON_AddNumberToObject(o, "tau_relative", r->scale > 0 ? r->tau / r->scale : 0);
    cJSON_AddNumberToObject(o, "scale", r->scale);
    cJSON_AddNumberToObject(o, "tol", r->tol);
    cJSON_AddNumberToObject(o, "input_volume", r->input_volume);
    if (p->trim_coverage > 0) { /* only with --trim-coverage: other runs' JSON unchanged */
        cJSON *t = cJSON_AddObjectToObject(o, "trim");
        cJSON_AddNumberToObject(t, "coverage", p->trim_coverage);
        cJSON_AddNumberToObject(t, "cuts", (double)r->trim_cuts);
        cJSON_AddNumberToObject(t, "trimmed_volume", r->trimmed_volume);
        cJSON_AddNumberToObject(t, "depth_max", r->trim_depth_max);
        cJSON_AddNumberToObject(t, "parts_left_whole", (double)r->trim_skipped);
        cJSON_AddNumberToObject(t, "distance_bound", r->trim_distance_bound);
        cJSON_AddNumberToObject(t, "refused_by_distance", (double)r->trim_refused_far);
    }
    if (p->budget_parts > 0) { /* only with --budget: other runs' JSON unchanged */
        cJSON *b = cJSON_AddObjectToObject(o, "budget");
        cJSON_AddNumberToObject(b, "cuts", (double)r->budget_cuts);
        cJSON_AddNumberToObject(b, "phase1_cuts", (double)r->budget_phase1_cuts);
        cJSON_AddNumberToObject(b, "parts_over", (double)r->budget_over);
        if (r->budget_stop) cJSON_AddStringToObject(b, "stop", r->budget_stop);
        else cJSON_AddNullToObject(b, "stop");
    }
    cJSON *parts = cJSON_AddArrayToObject(o, "parts");
    for (size_t i = 0; i < r->nparts; i++) {
        cJSON *q = cJSON_CreateObject();
        cJSON_AddNumberToObject(q, "concavity", r->parts[i].concavity);
        cJSON_AddNumberToObject(q, "volume", r->parts[i].volume);
        cJSON_AddNumberToObject(q, "hull_volume", r->parts[i].hull_volume);
        if (p->trim_coverage > 0) cJSON_AddNumberToObject(q, "trimmed_volume", r->parts[i].trimmed_volume);
        cJSON_AddNumberToObject(q, "vertices", (double)r->parts[i].mesh.nvertices);
        cJSON_AddNumberToObject(q, "hull_vertices", (double)r->parts[i].hull.nvertices);
        cJSON_AddNumberToObject(q, "node", r->parts[i].node);
        cJSON_AddNumberToObject(q, "genus", (double)r->parts[i].genus);
        cJSON_AddNumberToObject(q, "boundary_loops", (double)r->parts[i].boundary_loops);
        cJSON_AddStringToObject(q, "leaf_reason", acd3d_leaf_reason_name(r->nodes[r->parts[i].node].leaf_reason));
        cJSON_AddItemToArray(parts, q);
    }
    cJSON *tree = cJSON_AddArrayToObject(o, "tree");
    for (size_t i = 0; i < r->nnodes; i++) {
        const acd3d_node *n = &r->nodes[i];
        cJSON *q = cJSON_CreateObject();
        cJSON_AddNumberToObject(q, "parent", n->parent);
        cJSON *ch = cJSON_AddArrayToObject(q, "children");
        for (int k = 0; k < n->nchildren; k++) cJSON_AddItemToArray(ch, cJSON_CreateNumber(n->first_child + k));
        cJSON_AddNumberToObject(q, "concavity", n->concavity);
        cJSON_AddNumberToObject(q, "volume", n->volume);
        if (n->bodies) cJSON_AddTrueToObject(q, "bodies"); /* split into its bodies: no plane */
        else if (n->first_child >= 0) {
            cJSON *pl = cJSON_AddArrayToObject(q, "cut_plane");
            for (int k = 0; k < 4; k++) cJSON_AddItemToArray(pl, cJSON_CreateNumber(n->cut_plane[k]));
        }
        if (n->part >= 0) cJSON_AddNumberToObject(q, "part", n->part);
        if (n->merged_into >= 0) cJSON_AddNumberToObject(q, "merged_into", n->merged_into);
        if (n->first_child < 0 || n->leaf_reason == ACD3D_LEAF_MERGED)
            cJSON_AddStringToObject(q, "leaf_reason", acd3d_leaf_reason_name(n->leaf_reason));
        cJSON_AddItemToArray(tree, q);
    }
    cJSON *stats = cJSON_AddObjectToObject(o, "stats");
    double hv = 0;
    for (size_t i = 0; i < r->nparts; i++) hv += r->parts[i].hull_volume;
    cJSON_AddNumberToObject(stats, "parts", (double)r->nparts);
    cJSON_AddNumberToObject(stats, "max_concavity", r->max_concavity);
    cJSON_AddNumberToObject(stats, "hull_volume_sum", hv);
    cJSON_AddNumberToObject(stats, "seconds", r->seconds);
    return o;
}

/* The mesh's self-intersecting face pairs: *npairs, the first in pair; 0 when the test fails. Run
 * again only while none was found (the caller keeps npairs and pair between calls). */
static int self_crossing(const acd_mesh *mesh, size_t *npairs, uint32_t pair[2]) {
    if (*npairs > 0) return 1;
    acd_error serr;
    return acd_mesh_self_intersections(mesh, npairs, pair, 1, &serr) == ACD_OK;
}

int acd_cmd_3d(int argc, char **argv) {
    const char *input = NULL, *hulls_path = NULL, *parts_path = NULL, *json_path = NULL, *export_path = NULL,
               *model_name = NULL;
    int do_verify = 0, verbose = 0, close_holes = 1;
    /* the options --budget implies when they are not given */
    int got_tau = 0, got_merge_tau = 0, got_merge_tau_diag = 0, got_cut_choice = 0, got_merge_order = 0,
        got_merge_parts = 0, got_merge_refine = 0;
    acd3d_params p = acd3d_default_params();
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return ACD_EXIT_OK;
        } else if (!strcmp(a, "-t") || !strcmp(a, "--tau")) {
            if (!acd_cli_parse_double("3d", a, val, &p.tau) || p.tau < 0) {
                fprintf(stderr, "acd 3d: %s needs a number >= 0\n", a);
                return ACD_EXIT_USAGE;
            }
            got_tau = 1;
            i++;
        } else if (!strcmp(a, "--tau-abs")) {
            p.tau_absolute = 1;
        } else if (!strcmp(a, "--mode")) {
            if (val && !strcmp(val, "solid")) p.mode = ACD3D_SOLID;
            else if (val && !strcmp(val, "surface")) p.mode = ACD3D_SURFACE;
            else {
                fprintf(stderr, "acd 3d: --mode takes solid or surface\n");
                return ACD_EXIT_USAGE;
            }
            i++;
        } else if (!strcmp(a, "--resolver")) {
            if (val && !strcmp(val, "global")) p.resolver = ACD3D_RESOLVER_GLOBAL;
            else if (val && !strcmp(val, "witness")) p.resolver = ACD3D_RESOLVER_WITNESS;
            else if (val && !strcmp(val, "notch")) p.resolver = ACD3D_RESOLVER_NOTCH;
            else {
                fprintf(stderr, "acd 3d: --resolver takes global, witness or notch\n");
                return ACD_EXIT_USAGE;
            }
            i++;
        } else if (!strcmp(a, "--merge-order")) {
            if (val && !strcmp(val, "bound")) p.merge_order = ACD3D_MERGE_BOUND;
            else if (val && !strcmp(val, "volume")) p.merge_order = ACD3D_MERGE_VOLUME;
            else {
                fprintf(stderr, "acd 3d: --merge-order takes bound or volume\n");
                return ACD_EXIT_USAGE;
            }
            got_merge_order = 1;
            i++;
        } else if (!strcmp(a, "--merge-parts")) {
            if (!acd_cli_parse_size("3d", a, val, &p.merge_parts)) return ACD_EXIT_USAGE;
            got_merge_parts = 1;
            i++;
        } else if (!strcmp(a, "--budget")) {
            if (!acd_cli_parse_size("3d", a, val, &p.budget_parts)) return ACD_EXIT_USAGE;
            i++;
        } else if (!strcmp(a, "--merge-refine")) {
            if (!acd_cli_parse_size("3d", a, val, &p.merge_refine)) return ACD_EXIT_USAGE;
            got_merge_refine = 1;
            i++;
        } else if (!strcmp(a, "--cut-choice")) {
            if (val && !strcmp(val, "concavity")) p.cut_choice = ACD3D_CHOICE_CONCAVITY;
            else if (val && !strcmp(val, "volume")) p.cut_choice = ACD3D_CHOICE_VOLUME;
            else if (val && !strcmp(val, "band")) p.cut_choice = ACD3D_CHOICE_BAND;
            else {
                fprintf(stderr, "acd 3d: --cut-choice takes concavity, volume or band\n");
                return ACD_EXIT_USAGE;
            }
            got_cut_choice = 1;
            i++;
        } else if (!strcmp(a, "--stop")) {
            if (val && !strcmp(val, "measure")) p.stop = ACD3D_STOP_MEASURE;
            else if (val && !strcmp(val, "hull")) p.stop = ACD3D_STOP_HULL;
            else {
                fprintf(stderr, "acd 3d: --stop takes measure or hull\n");
                return ACD_EXIT_USAGE;
            }
            i++;
        } else if (!strcmp(a, "--surface-cut")) {
            if (val && !strcmp(val, "strip")) p.surface_cut = ACD3D_SURFACE_STRIP;
            else if (val && !strcmp(val, "cycle")) p.surface_cut = ACD3D_SURFACE_CYCLE;
            else if (val && !strcmp(val, "cycle-witness")) p.surface_cut = ACD3D_SURFACE_CYCLE_WITNESS;
            else {
                fprintf(stderr, "acd 3d: --surface-cut takes strip, cycle or cycle-witness\n");
                return ACD_EXIT_USAGE;
            }
            i++;
        } else if (!strcmp(a, "--cut-weight")) {
            if (val && !strcmp(val, "ratio")) p.weight = ACD3D_WEIGHT_RATIO;
            else if (val && !strcmp(val, "product")) p.weight = ACD3D_WEIGHT_PRODUCT;
            else {
                fprintf(stderr, "acd 3d: --cut-weight takes ratio or product\n");
                return ACD_EXIT_USAGE;
            }
            i++;
        } else if (!strcmp(a, "-o")) {
            if (!val) break;
            hulls_path = argv[++i];
        } else if (!strcmp(a, "--parts")) {
            if (!val) break;
            parts_path = argv[++i];
        } else if (!strcmp(a, "--json")) {
            if (!val) break;
            json_path = argv[++i];
        } else if (!strcmp(a, "--export")) {
            if (!val) break;
            export_path = argv[++i];
        } else if (!strcmp(a, "--name")) {
            if (!val) break;
            model_name = argv[++i];
        } else if (!strcmp(a, "--max-hulls")) {
            if (!acd_cli_parse_size("3d", a, val, &p.max_hulls)) return ACD_EXIT_USAGE;
            i++;
        } else if (!strcmp(a, "--max-hull-vertices")) {
            if (!acd_cli_parse_size("3d", a, val, &p.max_hull_vertices)) return ACD_EXIT_USAGE;
            if (p.max_hull_vertices > 0 && p.max_hull_vertices < 4) {
                fprintf(stderr, "acd 3d: --max-hull-vertices needs at least 4\n");
                return ACD_EXIT_USAGE;
            }
            i++;
        } else if (!strcmp(a, "--threads")) {
            size_t n;
            if (!acd_cli_parse_size("3d", a, val, &n)) return ACD_EXIT_USAGE;
            if (n > 1024) { /* as acd segment: --threads 100000 crashed inside libgomp */
                fprintf(stderr, "acd 3d: %s takes 0 (all cores) to 1024\n", a);
                return ACD_EXIT_USAGE;
            }
            p.threads = (int)n; /* results never depend on it */
            i++;
        } else if (!strcmp(a, "--merge-tau")) {
            if (!acd_cli_parse_double("3d", a, val, &p.merge_tau) || p.merge_tau < 0) {
                fprintf(stderr, "acd 3d: %s needs a number >= 0\n", a);
                return ACD_EXIT_USAGE;
            }
            got_merge_tau = 1;
            i++;
        } else if (!strcmp(a, "--merge-tau-diag")) {
            if (!acd_cli_parse_double("3d", a, val, &p.merge_tau_diag) || !(p.merge_tau_diag > 0)) {
                fprintf(stderr, "acd 3d: %s needs a number > 0\n", a);
                return ACD_EXIT_USAGE;
            }
            got_merge_tau_diag = 1;
            i++;
        } else if (!strcmp(a, "--trim-coverage")) {
            if (!acd_cli_parse_double("3d", a, val, &p.trim_coverage) ||
                !(p.trim_coverage >= 0 && p.trim_coverage <= ACD3D_TRIM_COVERAGE_MAX)) {
                fprintf(stderr, "acd 3d: %s needs a number in [0, %g] (the fraction of the input's volume the hulls "
                                "may leave out)\n", a, ACD3D_TRIM_COVERAGE_MAX);
                return ACD_EXIT_USAGE;
            }
            i++;
        } else if (!strcmp(a, "--no-merge")) {
            p.merge = 0;
        } else if (!strcmp(a, "--region-cuts")) {
            p.region_cuts = 1;
        } else if (!strcmp(a, "--eps-ratio")) {
            if (!acd_cli_parse_double("3d", a, val, &p.eps_ratio) || p.eps_ratio < 0) {
                fprintf(stderr, "acd 3d: %s needs a number >= 0\n", a);
                return ACD_EXIT_USAGE;
            }
            i++;
        } else if (!strcmp(a, "--no-feature-grouping")) {
            /* spec §5.4, decision A14: no bridge clustering, notch cutting in the witness's region */
            p.eps_ratio = 0;
            p.resolver = ACD3D_RESOLVER_NOTCH;
            p.region_cuts = 1;
        } else if (!strcmp(a, "--no-close-holes")) {
            close_holes = 0;
        } else if (!strcmp(a, "--verify")) {
            do_verify = 1;
        } else if (!strcmp(a, "-v") || !strcmp(a, "--verbose")) {
            verbose = 1;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "acd 3d: unknown option '%s'\n", a);
            usage(stderr);
            return ACD_EXIT_USAGE;
        } else if (!input) {
            input = a;
        } else {
            fprintf(stderr, "acd 3d: more than one input ('%s' and '%s')\n", input, a);
            return ACD_EXIT_USAGE;
        }
        if ((!strcmp(a, "-o") || !strcmp(a, "--parts") || !strcmp(a, "--json") || !strcmp(a, "--export") ||
             !strcmp(a, "--name")) &&
            !val)
            break;
    }
    for (int i = 1; i < argc; i++)
        if ((!strcmp(argv[i], "-o") || !strcmp(argv[i], "--parts") || !strcmp(argv[i], "--json") ||
             !strcmp(argv[i], "--export") || !strcmp(argv[i], "--name")) &&
            i + 1 >= argc) {
            fprintf(stderr, "acd 3d: option %s needs a file name\n", argv[i]);
            return ACD_EXIT_USAGE;
        }
    if (!input) {
        usage(stderr);
        return ACD_EXIT_USAGE;
    }
    /* options that would otherwise be ignored: a usage error rather than a silent no-op */
    if (got_merge_tau && got_merge_tau_diag) {
        fprintf(stderr, "acd 3d: --merge-tau and --merge-tau-diag both set the merge tolerance: give one\n");
        return ACD_EXIT_USAGE;
    }
    /* --budget N: the budget pipeline's settings (acd3d_budget_params) for the options not given; not
     * where the library refuses --budget (surface mode, --max-hulls), so that its message stays about
     * --budget; with --no-merge not the merge pass's */
    const char *implied[8];
    size_t nimplied = 0;
    if (p.budget_parts > 0 && p.mode == ACD3D_SOLID && p.max_hulls == 0) {
        const acd3d_params b = acd3d_budget_params(p.budget_parts);
        if (!got_tau && p.tau_absolute) {
            fprintf(stderr, "acd 3d: --tau-abs with --budget needs -t (the -t 10 --budget implies is relative to the "
                            "radius)\n");
            return ACD_EXIT_USAGE;
        }
        if (!got_tau) {
            p.tau = b.tau;
            implied[nimplied++] = "-t";
        }
        if (!got_merge_tau && !got_merge_tau_diag) {
            p.merge_tau_diag = b.merge_tau_diag;
            implied[nimplied++] = "--merge-tau-diag";
        }
        if (!got_cut_choice) {
            p.cut_choice = b.cut_choice;
            implied[nimplied++] = "--cut-choice";
        }
        if (p.merge && !got_merge_order) {
            p.merge_order = b.merge_order;
            implied[nimplied++] = "--merge-order";
        }
        if (p.merge && !got_merge_parts) {
            p.merge_parts = b.merge_parts;
            implied[nimplied++] = "--merge-parts";
        }
        if (p.merge && !got_merge_refine && p.merge_parts > 0) {
            p.merge_refine = b.merge_refine;
            implied[nimplied++] = "--merge-refine";
        }
    }
    const int show_settings = nimplied > 0 || p.merge_tau_diag > 0;
    if (p.merge_refine > 0 && p.merge_parts == 0) {
        fprintf(stderr, "acd 3d: --merge-refine needs --merge-parts (the part count it refines at)\n");
        return ACD_EXIT_USAGE;
    }
    if (!p.merge && (p.merge_parts > 0 || p.merge_order != ACD3D_MERGE_BOUND)) {
        fprintf(stderr, "acd 3d: --no-merge with --merge-parts or --merge-order: the merge pass is off\n");
        return ACD_EXIT_USAGE;
    }
    acd_error err;
    acd_error_clear(&err);
    acd_mesh mesh;
    if (acd_cli_read_mesh("3d", input, &mesh, &err) != ACD_OK) return acd_cli_report("3d", &err);
    {
        int ec = acd_cli_check_extent("3d", &mesh);
        if (ec) {
            acd_mesh_free(&mesh);
            return ec;
        }
    }
    progress_state ps = {.verbose = verbose};
    clock_gettime(CLOCK_MONOTONIC, &ps.start);
    ps.last = ps.start;
    p.progress = on_progress;
    p.progress_user = &ps;
    acd3d_result r;
    int repaired = 0;
    acd_status st = acd3d_decompose(&mesh, &p, &r, &err);
    /* a closed mesh facing inward as a whole (negative volume: a mirrored export, or every face
     * reversed) is repaired like an unoriented one: its closed parts turned outward (cavities,
     * parts inside an odd number of others, inward) */
    double inside_out_volume = 0;
    if (st == ACD_ERR_DEGENERATE && p.mode == ACD3D_SOLID && close_holes) inside_out_volume = acd_geom3_signed_volume(&mesh);
    if ((st == ACD_ERR_NON_MANIFOLD || inside_out_volume < 0) && p.mode == ACD3D_SOLID && close_holes) {
        repaired = 1;
        /* solid mode on an open or unoriented mesh: weld, orient and close every hole, then
         * decompose the closed mesh (the parts' volumes then add up to the closed volume) */
        acd_error first = err;
        acd_repair_options ro = acd_repair_default_options();
        ro.fill_holes_max_edges = SIZE_MAX;
        ro.progress = on_progress; /* the repair's steps on stderr too (a second at 832k faces) */
        ro.progress_user = &ps;
        acd_repair_stats rs;
        acd_error_clear(&err);
        if (acd_mesh_repair(&mesh, &ro, &rs, &err) != ACD_OK) {
            acd_mesh_free(&mesh);
            return acd_cli_report("3d", &err);
        }
        if (verbose) fprintf(stderr, "acd 3d: %s\n", first.message);
        char what[96];
        if (inside_out_volume < 0)
            snprintf(what, sizeof what, "is inside out (signed volume %.6g)", inside_out_volume);
        else
            snprintf(what, sizeof what, "is not a closed, consistently oriented mesh");
        char cav[224] = "";
        int nc = 0;
        if (rs.cavities) nc = snprintf(cav, sizeof cav, " (%zu closed part(s) inside others kept as cavities)", rs.cavities);
        if (rs.vertices_split && nc >= 0 && (size_t)nc < sizeof cav)
            snprintf(cav + nc, sizeof cav - (size_t)nc,
                     ", %zu non-manifold edge(s) and vertices split into separate bodies (%zu vertex copies)",
                     rs.nonmanifold_edges_split, rs.vertices_split);
        fprintf(stderr,
                "acd 3d: the input %s; repaired for solid mode: %zu "
                "vertices merged, %zu degenerate and %zu duplicate faces dropped, %zu faces flipped%s, %zu holes "
                "closed with %zu faces (%zu new vertices) (--no-close-holes refuses instead; --mode surface keeps "
                "it open)\n",
                what, rs.vertices_merged, rs.degenerate_dropped, rs.duplicates_dropped, rs.faces_flipped, cav,
                rs.holes_filled, rs.hole_faces_added, rs.hole_vertices_added);
        st = acd3d_decompose(&mesh, &p, &r, &err);
        if (st == ACD_ERR_NON_MANIFOLD) {
            char why[sizeof err.message];
            snprintf(why, sizeof why, "%s", err.message);
            acd_fail(&err, st, "the mesh could not be closed for solid mode: after repair, %.400s", why);
        }
    }
    if (st != ACD_OK) {
        acd_mesh_free(&mesh);
        return acd_cli_report("3d", &err);
    }
    int code = ACD_EXIT_OK;
    if (!repaired && p.mode == ACD3D_SOLID) {
        /* closed and consistently oriented, positive volume: but a closed shell inside another
         * facing outward is a solid inside a solid (its volume counted twice, hulls over what was
         * likely meant as a cavity). Orienting a copy by nesting (acd_mesh_repair's orientation
         * step) tells: any face it flips disagrees with the shells' nesting */
        acd_mesh c;
        acd_error ce;
        if (acd_mesh_copy(&c, &mesh, &ce) == ACD_OK) {
            acd_repair_options ro = acd_repair_default_options();
            ro.weld = 0;
            ro.drop_degenerate = 0;
            ro.drop_duplicates = 0;
            ro.drop_unused_vertices = 0;
            ro.split_nonmanifold = 0;
            ro.progress = on_progress;
            ro.progress_user = &ps;
            acd_repair_stats rs;
            if (acd_mesh_repair(&c, &ro, &rs, &ce) == ACD_OK && rs.faces_flipped > 0)
                fprintf(stderr,
                        "acd 3d: warning: %zu faces are oriented against the nesting of the closed shells (a shell inside "
                        "another facing outward is taken as a solid inside a solid, its volume counted twice; a "
                        "cavity faces inward): decomposed as given; 'acd info --repair' orients shells by nesting\n",
                        rs.faces_flipped);
            acd_mesh_free(&c);
        }
    }
    acd_error selfx = {0}; /* set when parts stay above tau because the solid crosses itself: bad input */
    size_t stuck = 0;
    for (size_t i = 0; i < r.nparts; i++) stuck += r.nodes[r.parts[i].node].leaf_reason == ACD3D_LEAF_NO_CUT ||
                                                   r.nodes[r.parts[i].node].leaf_reason == ACD3D_LEAF_DEPTH;
    printf("%zu parts, max concavity %.6g (tau %.6g = %.4g x radius %.6g), %.3f s\n", r.nparts, r.max_concavity, r.tau,
           r.scale > 0 ? r.tau / r.scale : 0.0, r.scale, r.seconds);
    if (show_settings) print_settings(&r, &p);
    if (p.budget_parts > 0 && r.budget_over > 0)
        printf("budget: the pass left %zu part(s) above the merge tolerance after %zu cuts (%zu past the budget): %s\n",
               r.budget_over, r.budget_cuts, r.budget_phase1_cuts, r.budget_stop ? r.budget_stop : "?");
    if (p.trim_coverage > 0 && r.trim_skipped > 0)
        fprintf(stderr,
                "acd 3d: warning: %zu part(s) intersect themselves (the %smesh crosses itself): their hulls are "
                "left whole (--trim-coverage accounts in volumes such a part does not have)\n",
                r.trim_skipped, repaired ? "repaired " : "");
    if (p.trim_coverage > 0)
        printf("trimmed hulls: %zu caps cut off, at most %.3g of the input's volume outside the hulls (limit %g), "
               "deepest cut %.3g (%.3g of the radius); every part within %.3g of its trimmed hull (%zu cap(s) refused "
               "by that bound)\n",
               r.trim_cuts, r.input_volume > 0 ? r.trimmed_volume / r.input_volume : 0.0, p.trim_coverage,
               r.trim_depth_max, r.scale > 0 ? r.trim_depth_max / r.scale : 0.0, r.trim_distance_bound,
               r.trim_refused_far);
    {
        size_t handled = 0;
        long gmax = 0;
        for (size_t i = 0; i < r.nparts; i++) {
            handled += r.parts[i].genus > 0;
            if (r.parts[i].genus > gmax) gmax = r.parts[i].genus;
        }
        if (handled)
            printf("genus of the parts: %zu of %zu have handles (at most %ld)\n", handled, r.nparts, gmax);
        else
            printf("genus of the parts: 0 (all %zu)\n", r.nparts);
    }
    /* the tolerance stuck parts stay above: in a budget run the merge tolerance (the budget pass
     * brings every part within it when a cut can) */
    const char *lim = p.budget_parts > 0 ? "the merge tolerance" : "tau";
    size_t npairs = 0; /* the (repaired) mesh's self-intersections, computed once when needed */
    uint32_t pair[2] = {0, 0};
    if (stuck) {
        fprintf(stderr, "acd 3d: %zu part(s) stayed above %s: no cut could split them further (see leaf_reason)\n",
                stuck, lim);
        /* the usual cause in solid mode: the surface crosses itself, so a plane cut cannot give
         * closed, outward pieces (often a scan whose holes were closed by caps that cross it) */
        if (p.mode == ACD3D_SOLID && self_crossing(&mesh, &npairs, pair) && npairs > 0)
            acd_fail(&selfx, ACD_ERR_INVALID_INPUT,
                     "the %smesh intersects itself (%zu face pairs, first: faces %u and %u), so %zu part(s) stay "
                     "above %s: solid mode cannot cut through crossing sheets; fix the mesh or use --mode surface "
                     "(the outputs are written, they do not meet %s)",
                     repaired ? "repaired " : "", npairs, pair[0], pair[1], stuck, lim, lim);
    }
    /* parts of no positive volume (not flat ones): in solid mode the mark of a solid that crosses
     * itself (the merge pass's joins of such parts came out inverted on the budget sweep's open
     * patches closed by crossing caps); refused as bad input as above */
    size_t inverted = 0;
    for (size_t i = 0; p.mode == ACD3D_SOLID && i < r.nparts; i++)
        inverted += !(r.parts[i].volume > 0) && r.nodes[r.parts[i].node].leaf_reason != ACD3D_LEAF_FLAT;
    if (inverted && selfx.status == ACD_OK && self_crossing(&mesh, &npairs, pair) && npairs > 0)
        acd_fail(&selfx, ACD_ERR_INVALID_INPUT,
                 "the %smesh intersects itself (%zu face pairs, first: faces %u and %u), so %zu part(s) have no "
                 "positive volume: solid mode cannot cut through crossing sheets; fix the mesh or use --mode surface "
                 "(the outputs are written, they are not valid parts)",
                 repaired ? "repaired " : "", npairs, pair[0], pair[1], inverted);
    if (hulls_path && (st = write_parts(hulls_path, &r, 1, &err)) != ACD_OK) code = acd_cli_report("3d", &err);
    if (!code && parts_path && (st = write_parts(parts_path, &r, 0, &err)) != ACD_OK) code = acd_cli_report("3d", &err);
    if (!code && export_path && (st = export_dir(export_path, model_name, &r, &err)) != ACD_OK)
        code = acd_cli_report("3d", &err);
    if (!code && json_path) {
        cJSON *j = result_json(input, &r, &p);
        if (j && show_settings) settings_json(j, &r, &p, implied, nimplied);
        char *txt = j ? cJSON_Print(j) : NULL;
        FILE *f = txt ? fopen(json_path, "w") : NULL;
        if (!txt) {
            acd_fail(&err, ACD_ERR_NOMEM, "out of memory writing JSON");
            code = acd_cli_report("3d", &err);
        } else if (!f || fputs(txt, f) < 0 || fclose(f) != 0) {
            acd_fail(&err, ACD_ERR_IO, "cannot write %s", json_path);
            code = acd_cli_report("3d", &err);
        }
        free(txt);
        cJSON_Delete(j);
    }
    /* a result that cannot meet tau because the input is not a valid solid is refused as bad input
     * (exit 2) after its outputs are written, with or without --verify */
    if (!code && selfx.status != ACD_OK) code = acd_cli_report("3d", &selfx);
    if (!code && do_verify) {
        double outside = 0;
        size_t nbound = 0;
        struct timespec v0, v1;
        clock_gettime(CLOCK_MONOTONIC, &v0);
        acd3d_verify_report vr;
        st = acd3d_verify(&mesh, &p, &r, &vr, &err);
        outside = vr.outside, nbound = vr.nbound;
        clock_gettime(CLOCK_MONOTONIC, &v1);
        if (verbose) fprintf(stderr, "acd 3d: --verify took %.3f s\n", since(&v0, &v1));
        /* a solid-mode result that fails on a mesh crossing itself: the input's fault (exit 2), the
         * verification's message kept */
        if (st != ACD_OK && p.mode == ACD3D_SOLID && self_crossing(&mesh, &npairs, pair) && npairs > 0) {
            acd_error v = err;
            acd_fail(&err, ACD_ERR_INVALID_INPUT,
                     "the %smesh intersects itself (%zu face pairs, first: faces %u and %u), and the result fails "
                     "verification (%.300s): solid mode cannot cut through crossing sheets; fix the mesh or use "
                     "--mode surface",
                     repaired ? "repaired " : "", npairs, pair[0], pair[1], v.message);
        }
        if (st != ACD_OK) code = acd_cli_report("3d", &err);
        else if (verbose && p.trim_coverage > 0 && nbound == 0)
            fprintf(stderr, "acd 3d: verified: volumes add up, parts meet tau, %.3g of the input's volume outside the "
                            "trimmed hulls (exact; limit %g)\n", r.input_volume > 0 ? outside / r.input_volume : 0.0,
                    p.trim_coverage);
        else if (verbose && p.trim_coverage > 0)
            fprintf(stderr, "acd 3d: verified: volumes add up, parts meet tau, at most %.3g of the input's volume "
                            "outside the trimmed hulls (exact but on %zu part(s) where the cut failed, an upper bound; "
                            "limit %g)\n", r.input_volume > 0 ? outside / r.input_volume : 0.0, nbound, p.trim_coverage);
        else if (verbose)
            fprintf(stderr, p.mode == ACD3D_SOLID ? "acd 3d: verified: volumes add up, parts meet tau, parts inside hulls\n"
                                                  : "acd 3d: verified: the parts tile the surface and meet tau\n");
    }
    acd3d_result_free(&r);
    acd_mesh_free(&mesh);
    return code;
}
