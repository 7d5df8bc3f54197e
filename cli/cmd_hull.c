/* acd hull: convex hull of a mesh's vertices (or of each o/g part), written as a mesh file with
 * full precision. See docs/geom3.md. */
#include <cjson/cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "acd/mesh.h"
#include "cli.h"

static void usage(FILE *f) {
    fprintf(f,
            "usage: acd hull MESH [-o HULL] [--parts] [--json]\n"
            "\n"
            "Computes the convex hull of all vertices of MESH (OBJ, OFF, PLY or STL, optionally\n"
            "gzip-compressed) with qhull. Degenerate inputs have a defined hull: coplanar points give a\n"
            "convex polygon (dimension 2, one-sided triangles), collinear points a segment and a single\n"
            "point a point (written as vertices only).\n"
            "\n"
            "  -o HULL     write the hull (format from the extension: .obj .off .ply .stl, .gz; OBJ and\n"
            "              ASCII formats with %%.17g coordinates); with --parts one OBJ with an o group\n"
            "              per part\n"
            "  --parts     one hull per o/g group of an OBJ file (other formats: one part)\n"
            "  --json      print the summary (dimension, vertices, triangles, volume, area) as JSON\n");
}

typedef struct hull_summary {
    const char *name;
    int dim;
    size_t vertices, triangles;
    double volume, area;
} hull_summary;

static acd_mesh hull_as_mesh(const acd_hull *h) {
    acd_mesh m;
    m.vertices = h->vertices;
    m.nvertices = h->nvertices;
    m.triangles = h->triangles;
    m.ntriangles = h->ntriangles;
    return m;
}

static int print_summary(const hull_summary *s, size_t n, int json) {
    if (!json) {
        for (size_t i = 0; i < n; i++) {
            if (n > 1 || s[i].name[0]) printf("part %s: ", s[i].name[0] ? s[i].name : "(unnamed)");
            printf("dimension %d, %zu vertices, %zu triangles, volume %.17g, area %.17g\n", s[i].dim, s[i].vertices,
                   s[i].triangles, s[i].volume, s[i].area);
        }
        return ACD_EXIT_OK;
    }
    cJSON *root = cJSON_CreateObject(), *arr = root ? cJSON_AddArrayToObject(root, "hulls") : NULL;
    double vsum = 0;
    for (size_t i = 0; arr && i < n; i++) {
        cJSON *o = cJSON_CreateObject();
        if (!o) break;
        cJSON_AddStringToObject(o, "name", s[i].name);
        cJSON_AddNumberToObject(o, "dimension", s[i].dim);
        cJSON_AddNumberToObject(o, "vertices", (double)s[i].vertices);
        cJSON_AddNumberToObject(o, "triangles", (double)s[i].triangles);
        cJSON_AddNumberToObject(o, "volume", s[i].volume);
        cJSON_AddNumberToObject(o, "area", s[i].area);
        cJSON_AddItemToArray(arr, o);
        vsum += s[i].volume;
    }
    if (root) {
        cJSON_AddNumberToObject(root, "parts", (double)n);
        cJSON_AddNumberToObject(root, "volume_sum", vsum);
    }
    char *text = root ? cJSON_Print(root) : NULL;
    int rc = ACD_EXIT_OK;
    if (text)
        printf("%s\n", text);
    else {
        fprintf(stderr, "acd hull: out of memory printing JSON\n");
        rc = ACD_EXIT_INTERNAL;
    }
    free(text);
    cJSON_Delete(root);
    return rc;
}

int acd_cmd_hull(int argc, char **argv) {
    const char *in = NULL, *out = NULL;
    int json = 0, parts = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            usage(stdout);
            return ACD_EXIT_OK;
        } else if (!strcmp(argv[i], "-o") || !strcmp(argv[i], "--output")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "acd hull: option %s needs a file name\n", argv[i]);
                return ACD_EXIT_USAGE;
            }
            out = argv[++i];
        } else if (!strcmp(argv[i], "--json")) {
            json = 1;
        } else if (!strcmp(argv[i], "--parts")) {
            parts = 1;
        } else if (argv[i][0] == '-' && argv[i][1]) {
            fprintf(stderr, "acd hull: unknown option '%s'\n", argv[i]);
            usage(stderr);
            return ACD_EXIT_USAGE;
        } else if (!in) {
            in = argv[i];
        } else {
            fprintf(stderr, "acd hull: one mesh file expected, got '%s' too\n", argv[i]);
            return ACD_EXIT_USAGE;
        }
    }
    if (!in) {
        usage(stderr);
        return ACD_EXIT_USAGE;
    }
    acd_error err;
    acd_mesh_parts src;
    memset(&src, 0, sizeof src);
    if (parts) {
        if (acd_cli_read_parts("hull", in, &src, &err) != ACD_OK) return acd_cli_report("hull", &err);
    } else {
        src.parts = calloc(1, sizeof *src.parts);
        if (!src.parts) {
            fprintf(stderr, "acd hull: out of memory\n");
            return ACD_EXIT_INTERNAL;
        }
        src.count = 1;
        src.parts[0].name = NULL;
        if (acd_cli_read_mesh("hull", in, &src.parts[0].mesh, &err) != ACD_OK) {
            acd_mesh_parts_free(&src);
            return acd_cli_report("hull", &err);
        }
    }
    size_t n = src.count;
    acd_hull *hulls = calloc(n ? n : 1, sizeof *hulls);
    hull_summary *sum = calloc(n ? n : 1, sizeof *sum);
    acd_mesh_parts outp;
    outp.count = n;
    outp.parts = calloc(n ? n : 1, sizeof *outp.parts);
    int rc = ACD_EXIT_OK;
    if (!hulls || !sum || !outp.parts) {
        fprintf(stderr, "acd hull: out of memory\n");
        rc = ACD_EXIT_INTERNAL;
        goto done;
    }
    for (size_t i = 0; i < n; i++) {
        const acd_mesh *m = &src.parts[i].mesh;
        if (acd_hull_compute(m->vertices, m->nvertices, &hulls[i], &err) != ACD_OK) {
            rc = acd_cli_report("hull", &err);
            goto done;
        }
        sum[i].name = src.parts[i].name ? src.parts[i].name : "";
        sum[i].dim = hulls[i].dim;
        sum[i].vertices = hulls[i].nvertices;
        sum[i].triangles = hulls[i].ntriangles;
        sum[i].volume = hulls[i].volume;
        sum[i].area = hulls[i].area;
        outp.parts[i].name = (char *)(uintptr_t)sum[i].name; /* borrowed, never freed through outp */
        outp.parts[i].mesh = hull_as_mesh(&hulls[i]);
    }
    if (out) {
        acd_status st = parts ? acd_mesh_write_obj_parts(out, &outp, &err)
                              : acd_mesh_write(out, &outp.parts[0].mesh, ACD_MESH_FORMAT_AUTO, &err);
        if (st != ACD_OK) {
            rc = acd_cli_report("hull", &err);
            goto done;
        }
    }
    rc = print_summary(sum, n, json);
done:
    if (hulls)
        for (size_t i = 0; i < n; i++) acd_hull_free(&hulls[i]);
    free(hulls);
    free(sum);
    free(outp.parts);
    acd_mesh_parts_free(&src);
    return rc;
}
