/* acd segment: nearly convex segmentation of a triangle mesh (CoRiSe, acd/segment.h): labels per
 * face (.seg), the parts and their convex hulls as OBJ groups, a JSON summary, and --verify. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "acd/cage.h"
#include "acd/mesh.h"
#include "acd/segment.h"
#include "cli.h"
#include "core/error.h"
#include "corise/corise.h"
#include "corise/segio.h"

static void usage(FILE *f) {
    fprintf(f,
            "usage: acd segment MESH [-t TAU] [--seg LABELS.seg] [--parts PARTS.obj] [-o HULLS.obj]\n"
            "                        [--json FILE] [--clamp-hull-depth 0|1] [--threads N] [--verify] [-v]\n"
            "                        [--cage CAGE.obj [--cage-offset D] [--cage-vertices N]]\n"
            "\n"
            "Segments MESH (OBJ, OFF, PLY or STL) into nearly convex parts by convex ridge separation\n"
            "(CoRiSe; docs/corise.md).\n"
            "\n"
            "  -t, --tau TAU        valley concavity tolerance, relative to the bounding sphere's radius\n"
            "                       (default 0.1)\n"
            "  --seg FILE           one label per face, in face order (0 .. parts-1)\n"
            "  --parts FILE         the parts as OBJ groups (o part_K)\n"
            "  -o FILE              the parts' convex hulls as OBJ groups (o hull_K; flat parts have none)\n"
            "  --json FILE          summary: parts, seconds, per-part concavity, hull/mesh volume ratio\n"
            "  --clamp-hull-depth B cap valley concavity by the depth below the hull (default 1)\n"
            "  --threads N          worker threads (default 1; 0: all cores); the output is the same for any N\n"
            "  --verify             check: every face labelled, every part connected, no part has a\n"
            "                       valley deeper than tau (exit 3 naming the part otherwise)\n"
            "  --cage FILE          a cage for deformation (paper, section 7.2): the parts' hulls expanded,\n"
            "                       simplified and unioned into one closed mesh (docs/corise.md, Cages)\n"
            "  --cage-offset D      outward offset of the hulls, relative to the bounding-box diagonal\n"
            "                       (default 0.01)\n"
            "  --cage-vertices N    simplify each hull to at most N vertices (>= 4; 0: no simplification;\n"
            "                       default 32)\n"
            "  -v, --verbose        progress and details on stderr\n");
}

typedef struct progress_state {
    int verbose;
    double last; /* seconds of the last line */
} progress_state;

/* -v: the loop's milestones (stage "corise": each wave, each final part) as they come, the polls
 * within its steps and the preparation (tens of thousands on a large mesh) at most once a second */
static int on_progress(void *user, double fraction, const char *stage) {
    progress_state *ps = user;
    if (!ps->verbose) return 0;
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    double now = (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
    if (strcmp(stage, "corise") && now - ps->last < 1.0) return 0;
    ps->last = now;
    fprintf(stderr, "acd segment: %s %.0f%%\n", stage, 100 * fraction);
    return 0;
}

static uint32_t uf_find(uint32_t *p, uint32_t x) {
    while (p[x] != x) x = p[x] = p[p[x]];
    return x;
}

typedef struct half {
    uint32_t lo, hi, face;
} half;

static int cmp_half(const void *x, const void *y) {
    const half *a = x, *b = y;
    if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
    if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
    return (a->face > b->face) - (a->face < b->face);
}

/* --verify: labels in range and every part non-empty, every part edge-connected, every part's
 * valleys within tau (the library's valley test re-run per part). */
static acd_status verify(const acd_mesh *m, const acd_segment_params *p, const acd_segment_result *r, acd_error *err) {
    size_t nt = m->ntriangles;
    if (r->nfaces != nt) return acd_fail(err, ACD_ERR_VERIFY, "%zu labels for %zu faces", r->nfaces, nt);
    size_t *count = calloc(r->nparts ? r->nparts : 1, sizeof *count);
    uint32_t *uf = malloc((nt ? nt : 1) * sizeof *uf), *root = malloc((r->nparts ? r->nparts : 1) * sizeof *root);
    half *h = malloc((nt ? 3 * nt : 1) * sizeof *h);
    double *conc = malloc((r->nparts ? r->nparts : 1) * sizeof *conc);
    acd_status st = ACD_OK;
    if (!count || !uf || !root || !h || !conc) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory verifying %zu faces", nt);
        goto done;
    }
    for (size_t f = 0; f < nt; f++) {
        if (r->labels[f] >= r->nparts) {
            st = acd_fail(err, ACD_ERR_VERIFY, "face %zu has label %u, but there are %zu parts", f, r->labels[f], r->nparts);
            goto done;
        }
        count[r->labels[f]]++;
        uf[f] = (uint32_t)f;
        for (int k = 0; k < 3; k++) {
            uint32_t u = m->triangles[3 * f + k], v = m->triangles[3 * f + (k + 1) % 3];
            h[3 * f + k] = (half){u < v ? u : v, u < v ? v : u, (uint32_t)f};
        }
    }
    for (size_t k = 0; k < r->nparts; k++)
        if (!count[k]) {
            st = acd_fail(err, ACD_ERR_VERIFY, "part %zu has no face", k);
            goto done;
        }
    qsort(h, 3 * nt, sizeof *h, cmp_half);
    for (size_t i = 0; i + 1 < 3 * nt; i++) {
        size_t j = i + 1;
        for (; j < 3 * nt && h[j].lo == h[i].lo && h[j].hi == h[i].hi; j++)
            if (r->labels[h[j].face] == r->labels[h[i].face]) {
                uint32_t a = uf_find(uf, h[i].face), b = uf_find(uf, h[j].face);
                if (a != b) uf[a > b ? a : b] = a < b ? a : b;
            }
    }
    for (size_t k = 0; k < r->nparts; k++) root[k] = UINT32_MAX;
    for (size_t f = 0; f < nt; f++) {
        uint32_t k = r->labels[f], a = uf_find(uf, (uint32_t)f);
        if (root[k] == UINT32_MAX) root[k] = a;
        else if (root[k] != a) {
            st = acd_fail(err, ACD_ERR_VERIFY, "part %u is not connected: face %zu is not edge-connected to its first face", k, f);
            goto done;
        }
    }
    acd_corise_params c = acd_corise_default_params();
    c.tau = p->tau;
    c.clamp_hull_depth = p->clamp_hull_depth;
    if ((st = acd_corise_parts_concavity(m, &c, r->labels, r->nparts, conc, err)) != ACD_OK) goto done;
    for (size_t k = 0; k < r->nparts; k++)
        if (conc[k] > p->tau) {
            st = acd_fail(err, ACD_ERR_VERIFY, "part %zu (%zu faces) has a valley of concavity %.6g > tau %.6g", k, count[k],
                          conc[k], p->tau);
            goto done;
        }
done:
    free(count);
    free(uf);
    free(root);
    free(h);
    free(conc);
    return st;
}

/* Parts (hulls = 0) or hulls (hulls = 1) as OBJ groups. */
static acd_status write_groups(const char *path, const acd_mesh *m, const acd_segment_result *r, int hulls,
                               acd_error *err) {
    acd_mesh_parts mp = {calloc(r->nparts ? r->nparts : 1, sizeof(acd_mesh_part)), 0};
    uint32_t *map = malloc((m->nvertices ? m->nvertices : 1) * sizeof *map);
    acd_status st = ACD_OK;
    if (!mp.parts || !map) goto nomem;
    for (size_t k = 0; k < r->nparts; k++) {
        acd_mesh_part *q = &mp.parts[mp.count];
        char name[32];
        snprintf(name, sizeof name, "%s_%zu", hulls ? "hull" : "part", k);
        if (hulls) {
            if (r->parts[k].hull.ntriangles == 0) continue;
            if (acd_mesh_copy(&q->mesh, &r->parts[k].hull, err) != ACD_OK) goto fail;
        } else {
            size_t nf = r->parts[k].nfaces, nv = 0;
            q->mesh.triangles = malloc(3 * nf * sizeof *q->mesh.triangles);
            q->mesh.vertices = malloc(9 * nf * sizeof *q->mesh.vertices);
            if (!q->mesh.triangles || !q->mesh.vertices) {
                acd_mesh_free(&q->mesh);
                goto nomem;
            }
            for (size_t v = 0; v < m->nvertices; v++) map[v] = UINT32_MAX;
            for (size_t f = 0; f < m->ntriangles; f++) {
                if (r->labels[f] != k) continue;
                for (int c = 0; c < 3; c++) {
                    uint32_t v = m->triangles[3 * f + c];
                    if (map[v] == UINT32_MAX) {
                        memcpy(q->mesh.vertices + 3 * nv, m->vertices + 3 * (size_t)v, 3 * sizeof(double));
                        map[v] = (uint32_t)nv++;
                    }
                    q->mesh.triangles[3 * q->mesh.ntriangles + c] = map[v];
                }
                q->mesh.ntriangles++;
            }
            q->mesh.nvertices = nv;
        }
        q->name = malloc(strlen(name) + 1);
        mp.count++;
        if (!q->name) goto nomem;
        strcpy(q->name, name);
    }
    st = acd_mesh_write_obj_parts(path, &mp, err);
    goto out;
nomem:
    st = acd_fail(err, ACD_ERR_NOMEM, "out of memory writing %s", path);
    goto out;
fail:
    st = err ? err->status : ACD_ERR_INTERNAL;
out:
    acd_mesh_parts_free(&mp);
    free(map);
    return st;
}

static cJSON *result_json(const char *input, const acd_segment_result *r, const acd_segment_params *p) {
    cJSON *o = cJSON_CreateObject();
    if (!o) return NULL;
    cJSON_AddStringToObject(o, "file", input);
    cJSON_AddNumberToObject(o, "faces", (double)r->nfaces);
    cJSON_AddNumberToObject(o, "tau", p->tau);
    cJSON_AddBoolToObject(o, "clamp_hull_depth", p->clamp_hull_depth != 0);
    cJSON_AddNumberToObject(o, "scale", r->scale);
    cJSON_AddNumberToObject(o, "parts", (double)r->nparts);
    cJSON_AddNumberToObject(o, "seconds", r->seconds);
    cJSON_AddNumberToObject(o, "cuts", (double)r->cuts);
    cJSON_AddNumberToObject(o, "depth", (double)r->depth);
    cJSON_AddNumberToObject(o, "unresolved", (double)r->unresolved);
    cJSON_AddNumberToObject(o, "mesh_volume", r->mesh_volume);
    cJSON_AddNumberToObject(o, "hull_volume", r->hull_volume);
    if (r->mesh_volume > 0) cJSON_AddNumberToObject(o, "volume_ratio", r->hull_volume / r->mesh_volume);
    else cJSON_AddNullToObject(o, "volume_ratio");
    cJSON *a = cJSON_AddArrayToObject(o, "part");
    for (size_t k = 0; a && k < r->nparts; k++) {
        cJSON *q = cJSON_CreateObject();
        if (!q) break;
        cJSON_AddNumberToObject(q, "faces", (double)r->parts[k].nfaces);
        cJSON_AddNumberToObject(q, "concavity", r->parts[k].concavity);
        cJSON_AddNumberToObject(q, "concavity_rel", r->parts[k].concavity_rel);
        cJSON_AddNumberToObject(q, "area", r->parts[k].area);
        cJSON_AddNumberToObject(q, "hull_volume", r->parts[k].hull_volume);
        cJSON_AddItemToArray(a, q);
    }
    return o;
}

int acd_cmd_segment(int argc, char **argv) {
    const char *input = NULL, *seg_path = NULL, *parts_path = NULL, *hulls_path = NULL, *json_path = NULL;
    const char *cage_path = NULL;
    int do_verify = 0, verbose = 0;
    acd_segment_params p = acd_segment_default_params();
    acd_cage_params cp = acd_cage_default_params();
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return ACD_EXIT_OK;
        } else if (!strcmp(a, "-t") || !strcmp(a, "--tau")) {
            if (!acd_cli_parse_double("segment", a, val, &p.tau)) return ACD_EXIT_USAGE;
            if (p.tau < 0) {
                fprintf(stderr, "acd segment: %s needs a number >= 0\n", a);
                return ACD_EXIT_USAGE;
            }
            i++;
        } else if (!strcmp(a, "--clamp-hull-depth")) {
            if (!val || (strcmp(val, "0") && strcmp(val, "1"))) {
                fprintf(stderr, "acd segment: --clamp-hull-depth takes 0 or 1\n");
                return ACD_EXIT_USAGE;
            }
            p.clamp_hull_depth = val[0] == '1';
            i++;
        } else if (!strcmp(a, "--threads")) {
            size_t n;
            if (!acd_cli_parse_size("segment", a, val, &n)) return ACD_EXIT_USAGE;
            if (n > 1024) {
                fprintf(stderr, "acd segment: %s takes 0 (all cores) to 1024\n", a);
                return ACD_EXIT_USAGE;
            }
            p.threads = (int)n; /* the output never depends on it */
            i++;
        } else if (!strcmp(a, "--cage-offset")) {
            if (!acd_cli_parse_double("segment", a, val, &cp.offset)) return ACD_EXIT_USAGE;
            if (!(cp.offset >= 0)) {
                fprintf(stderr, "acd segment: %s needs a number >= 0\n", a);
                return ACD_EXIT_USAGE;
            }
            i++;
        } else if (!strcmp(a, "--cage-vertices")) {
            double nv;
            if (!acd_cli_parse_double("segment", a, val, &nv)) return ACD_EXIT_USAGE;
            if (!(nv == 0 || (nv >= 4 && nv <= 1e6 && nv == floor(nv)))) {
                fprintf(stderr, "acd segment: %s needs 0 or a whole number >= 4\n", a);
                return ACD_EXIT_USAGE;
            }
            cp.max_vertices = (size_t)nv;
            i++;
        } else if (!strcmp(a, "--seg") || !strcmp(a, "--parts") || !strcmp(a, "-o") || !strcmp(a, "--json") ||
                   !strcmp(a, "--cage")) {
            if (!val) {
                fprintf(stderr, "acd segment: option %s needs a file name\n", a);
                return ACD_EXIT_USAGE;
            }
            const char **dst = !strcmp(a, "--seg")     ? &seg_path
                               : !strcmp(a, "--parts") ? &parts_path
                               : !strcmp(a, "-o")      ? &hulls_path
                               : !strcmp(a, "--cage")  ? &cage_path
                                                       : &json_path;
            *dst = argv[++i];
        } else if (!strcmp(a, "--verify")) {
            do_verify = 1;
        } else if (!strcmp(a, "-v") || !strcmp(a, "--verbose")) {
            verbose = 1;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "acd segment: unknown option '%s'\n", a);
            usage(stderr);
            return ACD_EXIT_USAGE;
        } else if (!input) {
            input = a;
        } else {
            fprintf(stderr, "acd segment: more than one input ('%s' and '%s')\n", input, a);
            return ACD_EXIT_USAGE;
        }
    }
    if (!input) {
        usage(stderr);
        return ACD_EXIT_USAGE;
    }
    acd_error err;
    acd_error_clear(&err);
    acd_mesh mesh;
    if (acd_cli_read_mesh("segment", input, &mesh, &err) != ACD_OK) return acd_cli_report("segment", &err);
    {
        int ec = acd_cli_check_extent("segment", &mesh);
        if (ec) {
            acd_mesh_free(&mesh);
            return ec;
        }
    }
    progress_state ps = {verbose, 0};
    {
        struct timespec ts;
        clock_gettime(CLOCK_MONOTONIC, &ts);
        ps.last = (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec; /* the first poll line after a second */
    }
    p.progress = on_progress;
    p.progress_user = &ps;
    acd_segment_result r;
    acd_status st = acd_segment(&mesh, &p, &r, &err);
    acd_mesh_free(&mesh);
    if (st != ACD_OK) return acd_cli_report("segment", &err);
    /* the library welds and orients the input (docs/corise.md, "Input preparation"); the mesh it
     * segmented is r.mesh, which the outputs below use */
    if (r.vertices_merged > 0)
        fprintf(stderr,
                "acd segment: %zu vertices at the same coordinates as others merged (a triangle soup or split "
                "vertices): faces are joined there\n",
                r.vertices_merged);
    if (r.faces_flipped > 0)
        fprintf(stderr,
                "acd segment: %zu of %zu faces flipped to orient the mesh consistently, closed parts outward (it "
                "was %s)\n",
                r.faces_flipped, r.nfaces, r.faces_flipped == r.nfaces ? "inside out" : "not consistently oriented");
    const acd_mesh *sm = &r.mesh;
    int code = ACD_EXIT_OK;
    printf("%zu parts, %zu cuts, %zu unresolved, hull/mesh volume %.6g, %.3f s\n", r.nparts, r.cuts, r.unresolved,
           r.mesh_volume > 0 ? r.hull_volume / r.mesh_volume : 0.0, r.seconds);
    if (verbose)
        for (size_t k = 0; k < r.nparts; k++)
            fprintf(stderr, "acd segment: part %zu: %zu faces, concavity %.6g (%.4g x radius), hull volume %.6g\n", k,
                    r.parts[k].nfaces, r.parts[k].concavity, r.parts[k].concavity_rel, r.parts[k].hull_volume);
    if (seg_path) {
        int *lab = malloc((r.nfaces ? r.nfaces : 1) * sizeof *lab);
        if (!lab) {
            acd_fail(&err, ACD_ERR_NOMEM, "out of memory writing %s", seg_path);
            code = acd_cli_report("segment", &err);
        } else {
            for (size_t f = 0; f < r.nfaces; f++) lab[f] = (int)r.labels[f];
            if (acd_seg_write(seg_path, lab, r.nfaces, &err) != ACD_OK) code = acd_cli_report("segment", &err);
            free(lab);
        }
    }
    if (!code && parts_path && write_groups(parts_path, sm, &r, 0, &err) != ACD_OK)
        code = acd_cli_report("segment", &err);
    if (!code && hulls_path && write_groups(hulls_path, sm, &r, 1, &err) != ACD_OK)
        code = acd_cli_report("segment", &err);
    if (!code && cage_path) {
        acd_cage_result cr;
        if (acd_cage_from_segment(sm, &r, &cp, &cr, &err) != ACD_OK) {
            code = acd_cli_report("segment", &err);
        } else {
            printf("cage: %zu hulls (%zu corners chosen, %zu after quantization), %zu vertices, %zu triangles, volume/mesh %.6g, "
                   "%zu of %zu vertices outside, %.3f s\n",
                   cr.hulls, cr.chosen_corners, cr.corners, cr.cage.nvertices, cr.cage.ntriangles,
                   r.mesh_volume > 0 ? cr.volume / r.mesh_volume : 0.0, cr.outside_vertices, cr.checked_vertices,
                   cr.seconds);
            if (acd_mesh_write(cage_path, &cr.cage, acd_mesh_format_from_path(cage_path), &err) != ACD_OK)
                code = acd_cli_report("segment", &err);
            else if (cr.outside_vertices) {
                acd_fail(&err, ACD_ERR_VERIFY, "cage: %zu mesh vertices lie outside the cage", cr.outside_vertices);
                code = acd_cli_report("segment", &err);
            }
            acd_cage_result_free(&cr);
        }
    }
    if (!code && json_path) {
        cJSON *j = result_json(input, &r, &p);
        char *txt = j ? cJSON_Print(j) : NULL;
        FILE *f = txt ? fopen(json_path, "w") : NULL;
        int bad = !f;
        if (f) {
            bad = fputs(txt, f) < 0;
            bad |= fclose(f) != 0;
        }
        if (!txt) {
            acd_fail(&err, ACD_ERR_NOMEM, "out of memory writing JSON");
            code = acd_cli_report("segment", &err);
        } else if (bad) {
            acd_fail(&err, ACD_ERR_IO, "cannot write %s", json_path);
            code = acd_cli_report("segment", &err);
        }
        free(txt);
        cJSON_Delete(j);
    }
    if (!code && do_verify) {
        if (verify(sm, &p, &r, &err) != ACD_OK) code = acd_cli_report("segment", &err);
        else if (verbose) fprintf(stderr, "acd segment: verified: every face labelled, parts connected, parts within tau\n");
    }
    acd_segment_result_free(&r); /* and r.mesh */
    return code;
}
