/* acd info: the mesh report (topology, genus, orientation, defects, volume, area,
 * self-intersections) as text or JSON. See docs/mesh.md for the definitions. */
#include <cjson/cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/mesh.h"
#include "cli.h"

static void usage(FILE *f) {
    fprintf(f,
            "usage: acd info MESH [--json] [--no-self-intersections] [--components]\n"
            "                     [--repair OUT [--weld-tolerance T] [--fill-holes N]]\n"
            "\n"
            "Reads MESH (OBJ, OFF, PLY or STL, optionally gzip-compressed; format from the content) and\n"
            "reports its vertices, faces, edges, boundary and non-manifold edges and vertices, connected\n"
            "components, genus (sum over closed components), orientation, degenerate and duplicate faces,\n"
            "volume, area and self-intersecting face pairs.\n"
            "\n"
            "  --json                    print the report as one JSON object\n"
            "  --no-self-intersections   skip the self-intersection test (the slowest part)\n"
            "  --components              also list every connected component\n"
            "  --repair OUT              repair the mesh (weld, drop degenerate and duplicate faces, orient\n"
            "                            consistently, closed parts outward), write it to OUT (format from\n"
            "                            the extension, .gz compresses) and report on the repaired mesh\n"
            "  --weld-tolerance T        with --repair: weld vertices within T times the bounding-box\n"
            "                            diagonal (default 0: equal coordinates only)\n"
            "  --fill-holes N            with --repair: fill boundary loops of at most N edges (default 0)\n");
}

static cJSON *report_json(const char *path, const acd_mesh_report *r, int list_components,
                          const acd_repair_stats *st) {
    cJSON *o = cJSON_CreateObject();
    if (!o) return NULL;
    if (st) {
        cJSON *rp = cJSON_AddObjectToObject(o, "repair");
        if (rp) {
            cJSON_AddNumberToObject(rp, "vertices_merged", (double)st->vertices_merged);
            cJSON_AddNumberToObject(rp, "degenerate_dropped", (double)st->degenerate_dropped);
            cJSON_AddNumberToObject(rp, "duplicates_dropped", (double)st->duplicates_dropped);
            cJSON_AddNumberToObject(rp, "faces_flipped", (double)st->faces_flipped);
            cJSON_AddNumberToObject(rp, "nonorientable_parts", (double)st->nonorientable_parts);
            cJSON_AddNumberToObject(rp, "holes_filled", (double)st->holes_filled);
            cJSON_AddNumberToObject(rp, "hole_faces_added", (double)st->hole_faces_added);
            cJSON_AddNumberToObject(rp, "hole_vertices_added", (double)st->hole_vertices_added);
            cJSON_AddNumberToObject(rp, "unused_vertices_dropped", (double)st->unused_vertices_dropped);
            cJSON_AddNumberToObject(rp, "cavities", (double)st->cavities);
            cJSON_AddNumberToObject(rp, "nonmanifold_edges_split", (double)st->nonmanifold_edges_split);
            cJSON_AddNumberToObject(rp, "vertices_split", (double)st->vertices_split);
        }
    }
    cJSON_AddStringToObject(o, "file", path);
    cJSON_AddNumberToObject(o, "vertices", (double)r->vertices);
    cJSON_AddNumberToObject(o, "faces", (double)r->faces);
    cJSON_AddNumberToObject(o, "edges", (double)r->edges);
    cJSON_AddNumberToObject(o, "unused_vertices", (double)r->unused_vertices);
    cJSON_AddNumberToObject(o, "boundary_edges", (double)r->boundary_edges);
    cJSON_AddNumberToObject(o, "nonmanifold_edges", (double)r->nonmanifold_edges);
    cJSON_AddNumberToObject(o, "nonmanifold_vertices", (double)r->nonmanifold_vertices);
    cJSON_AddNumberToObject(o, "components", (double)r->components);
    cJSON_AddNumberToObject(o, "closed_components", (double)r->closed_components);
    cJSON_AddNumberToObject(o, "genus", (double)r->genus);
    cJSON_AddBoolToObject(o, "closed", r->closed);
    cJSON_AddBoolToObject(o, "orientable", r->orientable);
    cJSON_AddBoolToObject(o, "oriented", r->oriented);
    cJSON_AddNumberToObject(o, "orientation_conflicts", (double)r->orientation_conflicts);
    cJSON_AddNumberToObject(o, "inward_components", (double)r->inward_components);
    cJSON_AddNumberToObject(o, "degenerate_faces", (double)r->degenerate_faces);
    cJSON_AddNumberToObject(o, "duplicate_faces", (double)r->duplicate_faces);
    cJSON_AddNumberToObject(o, "volume", r->volume);
    cJSON_AddNumberToObject(o, "area", r->area);
    if (r->self_intersections_checked) cJSON_AddNumberToObject(o, "self_intersections", (double)r->self_intersections);
    else cJSON_AddNullToObject(o, "self_intersections");
    cJSON *lo = cJSON_CreateDoubleArray(r->bbox_min, 3), *hi = cJSON_CreateDoubleArray(r->bbox_max, 3);
    cJSON *bb = cJSON_AddObjectToObject(o, "bbox");
    if (bb && lo && hi) {
        cJSON_AddItemToObject(bb, "min", lo);
        cJSON_AddItemToObject(bb, "max", hi);
    } else {
        cJSON_Delete(lo);
        cJSON_Delete(hi);
    }
    if (list_components) {
        cJSON *arr = cJSON_AddArrayToObject(o, "component_list");
        for (size_t i = 0; arr && i < r->components; i++) {
            const acd_mesh_component *c = &r->component[i];
            cJSON *e = cJSON_CreateObject();
            if (!e) break;
            cJSON_AddNumberToObject(e, "faces", (double)c->faces);
            cJSON_AddNumberToObject(e, "vertices", (double)c->vertices);
            cJSON_AddNumberToObject(e, "edges", (double)c->edges);
            cJSON_AddNumberToObject(e, "boundary_edges", (double)c->boundary_edges);
            cJSON_AddNumberToObject(e, "nonmanifold_edges", (double)c->nonmanifold_edges);
            cJSON_AddBoolToObject(e, "closed", c->closed);
            cJSON_AddBoolToObject(e, "orientable", c->orientable);
            cJSON_AddBoolToObject(e, "oriented", c->oriented);
            if (c->genus >= 0) cJSON_AddNumberToObject(e, "genus", (double)c->genus);
            else cJSON_AddNullToObject(e, "genus");
            cJSON_AddNumberToObject(e, "volume", c->volume);
            cJSON_AddNumberToObject(e, "area", c->area);
            cJSON_AddItemToArray(arr, e);
        }
    }
    return o;
}

static void print_text(const char *path, const acd_mesh_report *r, int list_components,
                       const acd_repair_stats *st) {
    if (st)
        printf("repair                %zu vertices merged, %zu degenerate and %zu duplicate faces dropped, %zu faces "
               "flipped, %zu holes filled (%zu faces, %zu new vertices), %zu unused vertices dropped%s\n",
               st->vertices_merged, st->degenerate_dropped, st->duplicates_dropped, st->faces_flipped, st->holes_filled,
               st->hole_faces_added, st->hole_vertices_added, st->unused_vertices_dropped,
               st->nonorientable_parts ? " (some parts are not orientable)" : "");
    if (st && st->cavities)
        printf("repair                %zu closed part(s) inside an odd number of others: oriented inward (cavities)\n",
               st->cavities);
    if (st && st->vertices_split)
        printf("repair                %zu non-manifold edge(s) paired by angle, %zu vertex copies: bodies touching "
               "along an edge or at a point separated\n",
               st->nonmanifold_edges_split, st->vertices_split);
    printf("file                  %s\n", path);
    printf("vertices              %zu (%zu unused)\n", r->vertices, r->unused_vertices);
    printf("faces                 %zu\n", r->faces);
    printf("edges                 %zu\n", r->edges);
    printf("boundary edges        %zu\n", r->boundary_edges);
    printf("non-manifold edges    %zu\n", r->nonmanifold_edges);
    printf("non-manifold vertices %zu\n", r->nonmanifold_vertices);
    printf("components            %zu (%zu closed)\n", r->components, r->closed_components);
    printf("genus                 %ld (sum over closed components)\n", r->genus);
    printf("closed                %s\n", r->closed ? "yes" : "no");
    printf("orientable            %s\n", r->orientable ? "yes" : "no");
    printf("oriented              %s (%zu conflicting edges, %zu closed components inside out)\n",
           r->oriented ? "yes" : "no", r->orientation_conflicts, r->inward_components);
    printf("degenerate faces      %zu\n", r->degenerate_faces);
    printf("duplicate faces       %zu\n", r->duplicate_faces);
    printf("volume                %.17g\n", r->volume);
    printf("area                  %.17g\n", r->area);
    printf("bounding box          [%.17g %.17g %.17g] - [%.17g %.17g %.17g]\n", r->bbox_min[0], r->bbox_min[1],
           r->bbox_min[2], r->bbox_max[0], r->bbox_max[1], r->bbox_max[2]);
    if (!r->self_intersections_checked) printf("self-intersections    not checked\n");
    else if (r->self_intersections)
        printf("self-intersections    %zu face pairs (first: faces %u and %u)\n", r->self_intersections,
               r->first_intersection[0], r->first_intersection[1]);
    else printf("self-intersections    0\n");
    if (list_components)
        for (size_t i = 0; i < r->components; i++) {
            const acd_mesh_component *c = &r->component[i];
            printf("component %zu: %zu faces, %zu vertices, %s, %s, genus ", i, c->faces, c->vertices,
                   c->closed ? "closed" : "open", c->oriented ? "oriented" : c->orientable ? "orientable" : "non-orientable");
            if (c->genus >= 0) printf("%ld", c->genus);
            else printf("-");
            printf(", volume %.17g, area %.17g\n", c->volume, c->area);
        }
}

int acd_cmd_info(int argc, char **argv) {
    const char *path = NULL, *repair_out = NULL;
    int json = 0, selfx = 1, comps = 0;
    acd_repair_options ro = acd_repair_default_options();
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            usage(stdout);
            return ACD_EXIT_OK;
        } else if (!strcmp(argv[i], "--json")) {
            json = 1;
        } else if (!strcmp(argv[i], "--no-self-intersections")) {
            selfx = 0;
        } else if (!strcmp(argv[i], "--components")) {
            comps = 1;
        } else if (!strcmp(argv[i], "--repair") || !strcmp(argv[i], "--weld-tolerance") ||
                   !strcmp(argv[i], "--fill-holes")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "acd info: option %s needs a value\n", argv[i]);
                return ACD_EXIT_USAGE;
            }
            const char *opt = argv[i++];
            if (!strcmp(opt, "--repair")) repair_out = argv[i];
            else if (!strcmp(opt, "--weld-tolerance")) {
                if (!acd_cli_parse_double("info", opt, argv[i], &ro.weld_tolerance)) return ACD_EXIT_USAGE;
                if (ro.weld_tolerance < 0) {
                    fprintf(stderr, "acd info: --weld-tolerance must be >= 0\n");
                    return ACD_EXIT_USAGE;
                }
            } else if (!acd_cli_parse_size("info", opt, argv[i], &ro.fill_holes_max_edges)) {
                return ACD_EXIT_USAGE;
            }
        } else if (argv[i][0] == '-' && argv[i][1]) {
            fprintf(stderr, "acd info: unknown option '%s'\n", argv[i]);
            usage(stderr);
            return ACD_EXIT_USAGE;
        } else if (!path) {
            path = argv[i];
        } else {
            fprintf(stderr, "acd info: one mesh file expected, got '%s' too\n", argv[i]);
            return ACD_EXIT_USAGE;
        }
    }
    if (!path) {
        usage(stderr);
        return ACD_EXIT_USAGE;
    }
    acd_error err;
    acd_mesh m;
    if (acd_cli_read_mesh("info", path, &m, &err) != ACD_OK) return acd_cli_report("info", &err);
    acd_repair_stats st;
    if (repair_out) {
        if (acd_mesh_repair(&m, &ro, &st, &err) != ACD_OK || acd_mesh_write(repair_out, &m, ACD_MESH_FORMAT_AUTO, &err) != ACD_OK) {
            acd_mesh_free(&m);
            return acd_cli_report("info", &err);
        }
    }
    acd_mesh_report r;
    acd_status s = acd_mesh_validate(&m, selfx, &r, &err);
    acd_mesh_free(&m);
    if (s != ACD_OK) return acd_cli_report("info", &err);
    int rc = ACD_EXIT_OK;
    if (json) {
        cJSON *o = report_json(path, &r, comps, repair_out ? &st : NULL);
        char *text = o ? cJSON_Print(o) : NULL;
        if (text) printf("%s\n", text);
        else {
            fprintf(stderr, "acd info: out of memory printing JSON\n");
            rc = ACD_EXIT_INTERNAL;
        }
        free(text);
        cJSON_Delete(o);
    } else {
        print_text(path, &r, comps, repair_out ? &st : NULL);
    }
    acd_mesh_report_free(&r);
    return rc;
}
