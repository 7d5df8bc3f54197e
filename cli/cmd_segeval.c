/* acd segeval MESH A.seg B.seg...: the segmentation benchmark metrics of Chen, Golovinskiy and
 * Funkhouser 2009 between a segmentation A and one or more reference segmentations B (files, or
 * a directory whose *.seg files are all used, as the benchmark's human segmentations of one model
 * are stored). docs/segeval.md. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <cjson/cJSON.h>

#include "acd/mesh.h"
#include "acd/segment.h"
#include "cli.h"
#include "corise/segio.h"

static void usage(FILE *f) {
    fprintf(f,
            "usage: acd segeval MESH A.seg B.seg [B2.seg ...] [options]\n"
            "\n"
            "Compares the face segmentation A.seg of MESH with each reference B (a .seg file, or a\n"
            "directory: all its *.seg files in name order) by the metrics of Chen, Golovinskiy and\n"
            "Funkhouser 2009: Rand index (and 1 - RI), Hamming distance with missing rate Rm and\n"
            "false-alarm rate Rf, global and local consistency error, and cut discrepancy (geodesic\n"
            "along the mesh edges, divided by the mesh's average radius). With several references\n"
            "the mean over them is reported too (CD over those where it is defined).\n"
            ".seg files hold one integer label per face, in the mesh's face order.\n"
            "\n"
            "options:\n"
            "  --json             print the report as JSON\n"
            "  --weights W        area (default: faces weighted by their area) or faces (counts)\n"
            "  -h, --help         this text\n");
}

typedef struct ref_list {
    char **paths;
    size_t n, cap;
} ref_list;

static int ref_push(ref_list *l, const char *p) {
    if (l->n == l->cap) {
        size_t nc = l->cap ? 2 * l->cap : 8;
        char **np = realloc(l->paths, nc * sizeof *np);
        if (!np) return 0;
        l->paths = np;
        l->cap = nc;
    }
    size_t len = strlen(p);
    char *s = malloc(len + 1);
    if (!s) return 0;
    memcpy(s, p, len + 1);
    l->paths[l->n++] = s;
    return 1;
}

static void ref_free(ref_list *l) {
    for (size_t i = 0; i < l->n; i++) free(l->paths[i]);
    free(l->paths);
}

static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* Adds path, or the *.seg files of the directory path in name order. Returns an exit code. */
static int add_reference(ref_list *l, const char *path) {
    struct stat st;
    if (stat(path, &st) != 0 || !S_ISDIR(st.st_mode)) return ref_push(l, path) ? ACD_EXIT_OK : ACD_EXIT_INTERNAL;
    DIR *d = opendir(path);
    if (!d) {
        fprintf(stderr, "acd segeval: %s: cannot open directory '%s'\n", acd_status_string(ACD_ERR_IO), path);
        return ACD_EXIT_IO;
    }
    size_t first = l->n;
    struct dirent *e;
    while ((e = readdir(d))) {
        size_t len = strlen(e->d_name);
        if (len < 5 || strcmp(e->d_name + len - 4, ".seg") != 0) continue;
        size_t plen = strlen(path) + len + 2;
        char *full = malloc(plen);
        if (!full) {
            closedir(d);
            return ACD_EXIT_INTERNAL;
        }
        snprintf(full, plen, "%s/%s", path, e->d_name);
        int ok = ref_push(l, full);
        free(full);
        if (!ok) {
            closedir(d);
            return ACD_EXIT_INTERNAL;
        }
    }
    closedir(d);
    if (l->n == first) {
        fprintf(stderr, "acd segeval: %s: directory '%s' holds no .seg file\n", acd_status_string(ACD_ERR_INVALID_INPUT),
                path);
        return ACD_EXIT_BAD_INPUT;
    }
    qsort(l->paths + first, l->n - first, sizeof *l->paths, cmp_str);
    return ACD_EXIT_OK;
}

static void print_text(FILE *f, const char *name, const acd_segeval_result *r) {
    fprintf(f, "reference          %s\n", name);
    fprintf(f, "segments           %zu (A), %zu (B), %zu faces\n", r->nsegments_a, r->nsegments_b, r->nfaces);
    fprintf(f, "rand index         %.6f   (1 - RI = %.6f)\n", r->rand_index, 1.0 - r->rand_index);
    fprintf(f, "hamming            %.6f   (Rm %.6f, Rf %.6f)\n", r->hamming, r->hamming_rm, r->hamming_rf);
    fprintf(f, "gce                %.6f\n", r->gce);
    fprintf(f, "lce                %.6f\n", r->lce);
    if (r->cd_defined)
        fprintf(f, "cut discrepancy    %.6f   (pooled %.6f; DCD A->B %.6g, B->A %.6g; avg radius %.6g)\n",
                r->cut_discrepancy, r->cut_discrepancy_pooled, r->dcd_ab, r->dcd_ba, r->avg_radius);
    else
        fprintf(f, "cut discrepancy    undefined (cut vertices: %zu in A, %zu in B)\n", r->ncut_a, r->ncut_b);
    if (r->cd_unreachable)
        fprintf(f, "                   %zu cut vertices cannot reach the other cut (left out)\n", r->cd_unreachable);
}

static cJSON *num_or_null(double v, int defined) { return defined ? cJSON_CreateNumber(v) : cJSON_CreateNull(); }

static cJSON *result_json(const char *name, const acd_segeval_result *r) {
    cJSON *o = cJSON_CreateObject();
    if (!o) return NULL;
    if (name) cJSON_AddStringToObject(o, "reference", name);
    cJSON_AddNumberToObject(o, "faces", (double)r->nfaces);
    cJSON_AddNumberToObject(o, "segments_a", (double)r->nsegments_a);
    cJSON_AddNumberToObject(o, "segments_b", (double)r->nsegments_b);
    cJSON_AddNumberToObject(o, "rand_index", r->rand_index);
    cJSON_AddNumberToObject(o, "one_minus_rand_index", 1.0 - r->rand_index);
    cJSON_AddNumberToObject(o, "hamming", r->hamming);
    cJSON_AddNumberToObject(o, "hamming_rm", r->hamming_rm);
    cJSON_AddNumberToObject(o, "hamming_rf", r->hamming_rf);
    cJSON_AddNumberToObject(o, "gce", r->gce);
    cJSON_AddNumberToObject(o, "lce", r->lce);
    cJSON_AddItemToObject(o, "cut_discrepancy", num_or_null(r->cut_discrepancy, r->cd_defined));
    cJSON_AddItemToObject(o, "cut_discrepancy_pooled", num_or_null(r->cut_discrepancy_pooled, r->cd_defined));
    cJSON_AddItemToObject(o, "dcd_ab", num_or_null(r->dcd_ab, r->cd_defined));
    cJSON_AddItemToObject(o, "dcd_ba", num_or_null(r->dcd_ba, r->cd_defined));
    cJSON_AddNumberToObject(o, "avg_radius", r->avg_radius);
    cJSON_AddNumberToObject(o, "cut_vertices_a", (double)r->ncut_a);
    cJSON_AddNumberToObject(o, "cut_vertices_b", (double)r->ncut_b);
    cJSON_AddNumberToObject(o, "cd_unreachable", (double)r->cd_unreachable);
    return o;
}

int acd_cmd_segeval(int argc, char **argv) {
    const char *mesh_path = NULL, *a_path = NULL;
    int json = 0;
    acd_segeval_options opts = acd_segeval_default_options();
    ref_list refs = {0};
    int rc = ACD_EXIT_OK;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            ref_free(&refs);
            return ACD_EXIT_OK;
        } else if (!strcmp(a, "--json")) {
            json = 1;
        } else if (!strcmp(a, "--weights")) {
            const char *v = i + 1 < argc ? argv[++i] : NULL;
            if (v && !strcmp(v, "area"))
                opts.weighting = ACD_SEGEVAL_WEIGHT_AREA;
            else if (v && !strcmp(v, "faces"))
                opts.weighting = ACD_SEGEVAL_WEIGHT_FACES;
            else {
                fprintf(stderr, "acd segeval: option --weights needs 'area' or 'faces', got '%s'\n", v ? v : "");
                ref_free(&refs);
                return ACD_EXIT_USAGE;
            }
        } else if (a[0] == '-' && a[1] != '\0') {
            fprintf(stderr, "acd segeval: unknown option '%s'\n", a);
            usage(stderr);
            ref_free(&refs);
            return ACD_EXIT_USAGE;
        } else if (!mesh_path) {
            mesh_path = a;
        } else if (!a_path) {
            a_path = a;
        } else if ((rc = add_reference(&refs, a)) != ACD_EXIT_OK) {
            ref_free(&refs);
            return rc;
        }
    }
    if (!mesh_path || !a_path || refs.n == 0) {
        fprintf(stderr, "acd segeval: needs MESH, A.seg and at least one reference B.seg\n");
        usage(stderr);
        ref_free(&refs);
        return ACD_EXIT_USAGE;
    }
    acd_error err;
    acd_mesh mesh = {0};
    int *la = NULL, *lb = NULL;
    size_t n = 0;
    acd_segeval_result *res = NULL;
    cJSON *root = NULL;
    if (acd_cli_read_mesh("segeval", mesh_path, &mesh, &err) != ACD_OK) {
        rc = acd_cli_report("segeval", &err);
        goto done;
    }
    if (acd_seg_read(a_path, mesh.ntriangles, &la, &n, &err) != ACD_OK) {
        rc = acd_cli_report("segeval", &err);
        goto done;
    }
    res = calloc(refs.n, sizeof *res);
    if (!res) {
        fprintf(stderr, "acd segeval: %s\n", acd_status_string(ACD_ERR_NOMEM));
        rc = ACD_EXIT_INTERNAL;
        goto done;
    }
    for (size_t k = 0; k < refs.n; k++) {
        if (acd_seg_read(refs.paths[k], mesh.ntriangles, &lb, &n, &err) != ACD_OK ||
            acd_segeval(&mesh, la, lb, &opts, &res[k], &err) != ACD_OK) {
            rc = acd_cli_report("segeval", &err);
            goto done;
        }
        free(lb);
        lb = NULL;
    }
    /* mean over the references (CD over those where it is defined) */
    acd_segeval_result mean;
    memset(&mean, 0, sizeof mean);
    size_t ncd = 0;
    for (size_t k = 0; k < refs.n; k++) {
        const acd_segeval_result *r = &res[k];
        mean.rand_index += r->rand_index;
        mean.hamming += r->hamming;
        mean.hamming_rm += r->hamming_rm;
        mean.hamming_rf += r->hamming_rf;
        mean.gce += r->gce;
        mean.lce += r->lce;
        if (r->cd_defined) {
            mean.cut_discrepancy += r->cut_discrepancy;
            mean.cut_discrepancy_pooled += r->cut_discrepancy_pooled;
            ncd++;
        }
    }
    double inv = 1.0 / (double)refs.n;
    mean.rand_index *= inv;
    mean.hamming *= inv;
    mean.hamming_rm *= inv;
    mean.hamming_rf *= inv;
    mean.gce *= inv;
    mean.lce *= inv;
    if (ncd) {
        mean.cut_discrepancy /= (double)ncd;
        mean.cut_discrepancy_pooled /= (double)ncd;
    }
    const char *wname = opts.weighting == ACD_SEGEVAL_WEIGHT_AREA ? "area" : "faces";
    if (json) {
        root = cJSON_CreateObject();
        cJSON *arr = root ? cJSON_AddArrayToObject(root, "references") : NULL;
        if (!root || !arr) goto nomem;
        cJSON_AddStringToObject(root, "mesh", mesh_path);
        cJSON_AddStringToObject(root, "segmentation", a_path);
        cJSON_AddStringToObject(root, "weights", wname);
        cJSON_AddNumberToObject(root, "faces", (double)mesh.ntriangles);
        for (size_t k = 0; k < refs.n; k++) {
            cJSON *o = result_json(refs.paths[k], &res[k]);
            if (!o) goto nomem;
            cJSON_AddItemToArray(arr, o);
        }
        cJSON *m = cJSON_CreateObject();
        if (!m) goto nomem;
        cJSON_AddNumberToObject(m, "references", (double)refs.n);
        cJSON_AddNumberToObject(m, "rand_index", mean.rand_index);
        cJSON_AddNumberToObject(m, "one_minus_rand_index", 1.0 - mean.rand_index);
        cJSON_AddNumberToObject(m, "hamming", mean.hamming);
        cJSON_AddNumberToObject(m, "hamming_rm", mean.hamming_rm);
        cJSON_AddNumberToObject(m, "hamming_rf", mean.hamming_rf);
        cJSON_AddNumberToObject(m, "gce", mean.gce);
        cJSON_AddNumberToObject(m, "lce", mean.lce);
        cJSON_AddItemToObject(m, "cut_discrepancy", num_or_null(mean.cut_discrepancy, ncd > 0));
        cJSON_AddItemToObject(m, "cut_discrepancy_pooled", num_or_null(mean.cut_discrepancy_pooled, ncd > 0));
        cJSON_AddNumberToObject(m, "cd_references", (double)ncd);
        cJSON_AddItemToObject(root, "mean", m);
        char *s = cJSON_Print(root);
        if (!s) goto nomem;
        printf("%s\n", s);
        cJSON_free(s);
    } else {
        printf("mesh               %s (%zu faces)\nsegmentation       %s\nweights            %s\n", mesh_path,
               mesh.ntriangles, a_path, wname);
        for (size_t k = 0; k < refs.n; k++) {
            printf("\n");
            print_text(stdout, refs.paths[k], &res[k]);
        }
        if (refs.n > 1) {
            printf("\nmean over %zu references\n", refs.n);
            printf("rand index         %.6f   (1 - RI = %.6f)\n", mean.rand_index, 1.0 - mean.rand_index);
            printf("hamming            %.6f   (Rm %.6f, Rf %.6f)\n", mean.hamming, mean.hamming_rm, mean.hamming_rf);
            printf("gce                %.6f\nlce                %.6f\n", mean.gce, mean.lce);
            if (ncd)
                printf("cut discrepancy    %.6f   (pooled %.6f; over %zu references)\n", mean.cut_discrepancy,
                       mean.cut_discrepancy_pooled, ncd);
            else
                printf("cut discrepancy    undefined\n");
        }
    }
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "acd segeval: %s: writing the report failed\n", acd_status_string(ACD_ERR_IO));
        rc = ACD_EXIT_IO;
    }
    goto done;
nomem:
    fprintf(stderr, "acd segeval: %s\n", acd_status_string(ACD_ERR_NOMEM));
    rc = ACD_EXIT_INTERNAL;
done:
    cJSON_Delete(root);
    free(res);
    free(la);
    free(lb);
    acd_mesh_free(&mesh);
    ref_free(&refs);
    return rc;
}
