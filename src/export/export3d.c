/* export/export3d: writers of a 3D decomposition (issue "3D mesh foundation", item 7): OBJ with one
 * group per hull, one file per hull or part, JSON summary, URDF and MuJoCo MJCF collision models.
 * Meshes go through the mesh writers (src/mesh, %.17g); the XML and JSON are written here. */
#include "export/export3d.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>

#include <cjson/cJSON.h>

#include "core/error.h"
#include "geom3/hull_simplify.h"

acd_export_options acd_export_default_options(void) {
    acd_export_options o;
    memset(&o, 0, sizeof o);
    o.name = "acd";
    o.hull_stem = "hull";
    o.part_stem = "part";
    o.mesh_ext = "obj";
    o.max_hull_vertices = 0;
    return o;
}

static acd_export_options fill(const acd_export_options *o) {
    acd_export_options d = acd_export_default_options();
    if (!o) return d;
    acd_export_options r = *o;
    if (!r.name || !*r.name) r.name = d.name;
    if (!r.hull_stem || !*r.hull_stem) r.hull_stem = d.hull_stem;
    if (!r.part_stem || !*r.part_stem) r.part_stem = d.part_stem;
    if (!r.mesh_ext || !*r.mesh_ext) r.mesh_ext = d.mesh_ext;
    return r;
}

static int ext_ok(const char *ext) {
    return !strcmp(ext, "obj") || !strcmp(ext, "stl") || !strcmp(ext, "off") || !strcmp(ext, "ply");
}

/* A name safe in file names and XML: letters, digits, '_', '-', '.'; anything else becomes '_'. */
static int name_ok(const char *s) {
    if (!*s) return 0;
    for (; *s; s++)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9') || *s == '_' ||
              *s == '-' || *s == '.'))
            return 0;
    return 1;
}

static acd_status check_options(const acd_export_options *o, acd_error *err) {
    if (!ext_ok(o->mesh_ext))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "export: mesh extension '%s' is not one of obj, stl, off, ply",
                        o->mesh_ext);
    if (!name_ok(o->name) || !name_ok(o->hull_stem) || !name_ok(o->part_stem))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT,
                        "export: names may hold only letters, digits, '_', '-' and '.' (name '%s', stems '%s', '%s')",
                        o->name, o->hull_stem, o->part_stem);
    return ACD_OK;
}

static acd_status make_dir(const char *dir, acd_error *err) {
    if (!dir || !*dir) return ACD_OK;
    if (mkdir(dir, 0777) == 0 || errno == EEXIST) {
        struct stat st;
        if (stat(dir, &st) == 0 && S_ISDIR(st.st_mode)) return ACD_OK;
        return acd_fail(err, ACD_ERR_IO, "export: '%s' exists and is not a directory", dir);
    }
    return acd_fail(err, ACD_ERR_IO, "export: cannot create directory '%s': %s", dir, strerror(errno));
}

static acd_status join(char *buf, size_t size, const char *dir, const char *name, acd_error *err) {
    int n = (dir && *dir) ? snprintf(buf, size, "%s/%s", dir, name) : snprintf(buf, size, "%s", name);
    if (n < 0 || (size_t)n >= size) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "export: path too long ('%s/%s')", dir, name);
    return ACD_OK;
}

/* The hull as a mesh view (no copy). */
static acd_mesh hull_mesh(const acd_hull *h) {
    acd_mesh m = {h->vertices, h->nvertices, h->triangles, h->ntriangles};
    return m;
}

acd_status acd_export_simplify_hulls(const acd_hull *hulls, size_t n, size_t max_vertices, acd_hull *out,
                                     acd_error *err) {
    memset(out, 0, n * sizeof *out);
    for (size_t i = 0; i < n; i++) {
        acd_error e2;
        acd_status st = acd_hull_simplify(hulls[i].vertices, hulls[i].nvertices, max_vertices, &out[i], &e2);
        if (st != ACD_OK) {
            for (size_t j = 0; j < i; j++) acd_hull_free(&out[j]);
            return acd_fail(err, st, "export: hull %zu: %s", i, e2.message);
        }
    }
    return ACD_OK;
}

acd_status acd_export_hulls_obj(const char *path, const acd_hull *hulls, size_t n, const acd_export_options *opt,
                                acd_error *err) {
    acd_export_options o = fill(opt);
    acd_status st = check_options(&o, err);
    if (st != ACD_OK) return st;
    acd_mesh_part *p = calloc(n ? n : 1, sizeof *p);
    char *names = malloc((n ? n : 1) * 96);
    if (!p || !names) {
        free(p);
        free(names);
        return acd_fail(err, ACD_ERR_NOMEM, "export: out of memory for %zu hulls", n);
    }
    for (size_t i = 0; i < n; i++) {
        snprintf(names + 96 * i, 96, "%.60s_%03zu", o.hull_stem, i);
        p[i].name = names + 96 * i;
        p[i].mesh = hull_mesh(&hulls[i]);
    }
    acd_mesh_parts ps = {p, n};
    st = acd_mesh_write_obj_parts(path, &ps, err);
    free(p);
    free(names);
    return st;
}

static acd_status write_mesh_file(const char *dir, const char *stem, size_t i, const char *ext, const acd_mesh *m,
                                  acd_error *err) {
    char name[128], path[4096];
    snprintf(name, sizeof name, "%.60s_%03zu.%s", stem, i, ext);
    acd_status st = join(path, sizeof path, dir, name, err);
    if (st != ACD_OK) return st;
    return acd_mesh_write(path, m, ACD_MESH_FORMAT_AUTO, err);
}

acd_status acd_export_hull_files(const char *dir, const acd_hull *hulls, size_t n, const acd_export_options *opt,
                                 acd_error *err) {
    acd_export_options o = fill(opt);
    acd_status st = check_options(&o, err);
    if (st == ACD_OK) st = make_dir(dir, err);
    for (size_t i = 0; i < n && st == ACD_OK; i++) {
        acd_mesh m = hull_mesh(&hulls[i]);
        st = write_mesh_file(dir, o.hull_stem, i, o.mesh_ext, &m, err);
    }
    return st;
}

acd_status acd_export_part_files(const char *dir, const acd_mesh_parts *parts, const acd_export_options *opt,
                                 acd_error *err) {
    acd_export_options o = fill(opt);
    acd_status st = check_options(&o, err);
    if (st == ACD_OK) st = make_dir(dir, err);
    for (size_t i = 0; parts && i < parts->count && st == ACD_OK; i++)
        st = write_mesh_file(dir, o.part_stem, i, o.mesh_ext, &parts->parts[i].mesh, err);
    return st;
}

static cJSON *vec3(const double v[3]) {
    double w[3] = {v[0], v[1], v[2]};
    return cJSON_CreateDoubleArray(w, 3);
}

static acd_status write_text(const char *path, const char *text, acd_error *err) {
    FILE *f = fopen(path, "w");
    if (!f) return acd_fail(err, ACD_ERR_IO, "export: cannot open '%s' for writing: %s", path, strerror(errno));
    int bad = fputs(text, f) < 0;
    bad |= fclose(f) != 0;
    if (bad) return acd_fail(err, ACD_ERR_IO, "export: writing '%s' failed", path);
    return ACD_OK;
}

acd_status acd_export_summary_json(const char *path, const acd_mesh_parts *parts, const acd_hull *hulls, size_t n,
                                   const acd_eval_report *rep, const acd_export_options *opt, acd_error *err) {
    acd_export_options o = fill(opt);
    acd_status st = check_options(&o, err);
    if (st != ACD_OK) return st;
    cJSON *root = cJSON_CreateObject(), *arr = cJSON_CreateArray();
    if (!root || !arr) {
        cJSON_Delete(root);
        cJSON_Delete(arr);
        return acd_fail(err, ACD_ERR_NOMEM, "export: out of memory for the summary");
    }
    cJSON_AddStringToObject(root, "name", o.name);
    cJSON_AddNumberToObject(root, "hulls", (double)n);
    double vsum = 0;
    size_t vtot = 0;
    for (size_t i = 0; i < n; i++) {
        const acd_hull *h = &hulls[i];
        cJSON *e = cJSON_CreateObject();
        if (!e) break;
        char fname[128];
        snprintf(fname, sizeof fname, "%.60s_%03zu.%s", o.hull_stem, i, o.mesh_ext);
        cJSON_AddNumberToObject(e, "index", (double)i);
        cJSON_AddStringToObject(e, "file", fname);
        if (parts && i < parts->count) {
            cJSON_AddStringToObject(e, "part", parts->parts[i].name ? parts->parts[i].name : "");
            cJSON_AddNumberToObject(e, "part_vertices", (double)parts->parts[i].mesh.nvertices);
            cJSON_AddNumberToObject(e, "part_triangles", (double)parts->parts[i].mesh.ntriangles);
        }
        cJSON_AddNumberToObject(e, "dim", h->dim);
        cJSON_AddNumberToObject(e, "vertices", (double)h->nvertices);
        cJSON_AddNumberToObject(e, "triangles", (double)h->ntriangles);
        cJSON_AddNumberToObject(e, "volume", h->volume);
        cJSON_AddNumberToObject(e, "area", h->area);
        double c[3] = {0, 0, 0}, lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
        for (size_t v = 0; v < h->nvertices; v++)
            for (int k = 0; k < 3; k++) {
                double x = h->vertices[3 * v + k];
                c[k] += x / (double)h->nvertices;
                if (v == 0 || x < lo[k]) lo[k] = x;
                if (v == 0 || x > hi[k]) hi[k] = x;
            }
        cJSON_AddItemToObject(e, "vertex_centroid", vec3(c));
        cJSON_AddItemToObject(e, "bbox_min", vec3(lo));
        cJSON_AddItemToObject(e, "bbox_max", vec3(hi));
        cJSON_AddItemToArray(arr, e);
        vsum += h->volume;
        vtot += h->nvertices;
    }
    cJSON_AddNumberToObject(root, "hull_vertices", (double)vtot);
    cJSON_AddNumberToObject(root, "hull_volume_sum", vsum);
    cJSON_AddItemToObject(root, "hull_list", arr);
    if (rep) {
        char *js = NULL;
        if (acd_eval_report_json(rep, &js, NULL) == ACD_OK) {
            cJSON *ev = cJSON_Parse(js);
            if (ev) cJSON_AddItemToObject(root, "eval", ev);
            free(js);
        }
    }
    char *text = cJSON_Print(root);
    cJSON_Delete(root);
    if (!text) return acd_fail(err, ACD_ERR_NOMEM, "export: out of memory for the summary");
    size_t len = strlen(text);
    char *t2 = realloc(text, len + 2);
    if (!t2) {
        free(text);
        return acd_fail(err, ACD_ERR_NOMEM, "export: out of memory for the summary");
    }
    t2[len] = '\n';
    t2[len + 1] = '\0';
    st = write_text(path, t2, err);
    free(t2);
    return st;
}

/* Growing text buffer for the XML writers. */
typedef struct sbuf {
    char *s;
    size_t n, cap;
    int failed;
} sbuf;

static void sb_printf(sbuf *b, const char *fmt, ...) ACD_PRINTF(2, 3);
static void sb_printf(sbuf *b, const char *fmt, ...) {
    if (b->failed) return;
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        int k = vsnprintf(b->s ? b->s + b->n : NULL, b->s ? b->cap - b->n : 0, fmt, ap);
        va_end(ap);
        if (k < 0) {
            b->failed = 1;
            return;
        }
        if (b->s && b->n + (size_t)k < b->cap) {
            b->n += (size_t)k;
            return;
        }
        size_t cap = b->cap ? 2 * b->cap : 4096;
        while (cap <= b->n + (size_t)k) cap *= 2;
        char *s = realloc(b->s, cap);
        if (!s) {
            b->failed = 1;
            return;
        }
        b->s = s;
        b->cap = cap;
    }
}

static acd_status sb_write(sbuf *b, const char *path, acd_error *err) {
    acd_status st = b->failed ? acd_fail(err, ACD_ERR_NOMEM, "export: out of memory writing '%s'", path)
                              : write_text(path, b->s ? b->s : "", err);
    free(b->s);
    return st;
}

static void mesh_ref(char *buf, size_t size, const char *mesh_dir, const acd_export_options *o, size_t i) {
    if (mesh_dir && *mesh_dir)
        snprintf(buf, size, "%s/%.60s_%03zu.%s", mesh_dir, o->hull_stem, i, o->mesh_ext);
    else
        snprintf(buf, size, "%.60s_%03zu.%s", o->hull_stem, i, o->mesh_ext);
}

/* mesh_dir goes into an XML attribute: refuse the characters that would need escaping. */
static acd_status check_dir_attr(const char *mesh_dir, acd_error *err) {
    for (const char *s = mesh_dir ? mesh_dir : ""; *s; s++)
        if (*s == '"' || *s == '<' || *s == '>' || *s == '&' || *s == '\'')
            return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "export: mesh directory '%s' holds a character (%c) not allowed "
                            "in the XML", mesh_dir, *s);
    return ACD_OK;
}

acd_status acd_export_urdf(const char *path, const char *mesh_dir, size_t n, const acd_export_options *opt,
                           acd_error *err) {
    acd_export_options o = fill(opt);
    acd_status st = check_options(&o, err);
    if (st == ACD_OK) st = check_dir_attr(mesh_dir, err);
    if (st != ACD_OK) return st;
    sbuf b = {0};
    sb_printf(&b, "<?xml version=\"1.0\"?>\n<!-- written by acd %s: one collision element per convex hull -->\n",
              ACD_VERSION_STRING);
    sb_printf(&b, "<robot name=\"%s\">\n  <link name=\"%s_link\">\n", o.name, o.name);
    for (size_t i = 0; i < n; i++) {
        char ref[4200];
        mesh_ref(ref, sizeof ref, mesh_dir, &o, i);
        sb_printf(&b,
                  "    <collision name=\"%s_%03zu\">\n      <origin xyz=\"0 0 0\" rpy=\"0 0 0\"/>\n"
                  "      <geometry>\n        <mesh filename=\"%s\"/>\n      </geometry>\n    </collision>\n",
                  o.hull_stem, i, ref);
    }
    sb_printf(&b, "  </link>\n</robot>\n");
    return sb_write(&b, path, err);
}

acd_status acd_export_mjcf(const char *path, const char *mesh_dir, size_t n, const acd_export_options *opt,
                           acd_error *err) {
    acd_export_options o = fill(opt);
    acd_status st = check_options(&o, err);
    if (st == ACD_OK) st = check_dir_attr(mesh_dir, err);
    if (st != ACD_OK) return st;
    sbuf b = {0};
    sb_printf(&b, "<!-- written by acd %s: one mesh asset and one geom per convex hull -->\n", ACD_VERSION_STRING);
    sb_printf(&b, "<mujoco model=\"%s\">\n  <asset>\n", o.name);
    for (size_t i = 0; i < n; i++) {
        char ref[4200];
        mesh_ref(ref, sizeof ref, mesh_dir, &o, i);
        sb_printf(&b, "    <mesh name=\"%s_%03zu\" file=\"%s\"/>\n", o.hull_stem, i, ref);
    }
    sb_printf(&b, "  </asset>\n  <worldbody>\n    <body name=\"%s\">\n", o.name);
    for (size_t i = 0; i < n; i++)
        sb_printf(&b, "      <geom name=\"%s_%03zu\" type=\"mesh\" mesh=\"%s_%03zu\"/>\n", o.hull_stem, i, o.hull_stem, i);
    sb_printf(&b, "    </body>\n  </worldbody>\n</mujoco>\n");
    return sb_write(&b, path, err);
}

acd_status acd_export_all(const char *dir, const acd_mesh_parts *parts, const acd_hull *hulls, size_t n,
                          const acd_eval_report *rep, const acd_export_options *opt, acd_error *err) {
    acd_export_options o = fill(opt);
    acd_status st = check_options(&o, err);
    if (st != ACD_OK) return st;
    if (o.max_hull_vertices && o.max_hull_vertices < 4)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "export: a hull needs at least 4 vertices, not %zu",
                        o.max_hull_vertices);
    st = make_dir(dir, err);
    if (st != ACD_OK) return st;
    acd_hull *simp = NULL;
    const acd_hull *hs = hulls;
    if (o.max_hull_vertices) {
        simp = calloc(n ? n : 1, sizeof *simp);
        if (!simp) return acd_fail(err, ACD_ERR_NOMEM, "export: out of memory for %zu hulls", n);
        st = acd_export_simplify_hulls(hulls, n, o.max_hull_vertices, simp, err);
        if (st != ACD_OK) {
            free(simp);
            return st;
        }
        hs = simp;
    }
    char path[4096], sub[4096], name[256];
    if (st == ACD_OK) st = join(path, sizeof path, dir, "decomposition.obj", err);
    if (st == ACD_OK) st = acd_export_hulls_obj(path, hs, n, &o, err);
    if (st == ACD_OK) st = join(sub, sizeof sub, dir, "hulls", err);
    if (st == ACD_OK) st = acd_export_hull_files(sub, hs, n, &o, err);
    if (st == ACD_OK && parts) st = join(sub, sizeof sub, dir, "parts", err);
    if (st == ACD_OK && parts) st = acd_export_part_files(sub, parts, &o, err);
    if (st == ACD_OK) st = join(path, sizeof path, dir, "summary.json", err);
    if (st == ACD_OK) st = acd_export_summary_json(path, parts, hs, n, rep, &o, err);
    snprintf(name, sizeof name, "%.200s.urdf", o.name);
    if (st == ACD_OK) st = join(path, sizeof path, dir, name, err);
    if (st == ACD_OK) st = acd_export_urdf(path, "hulls", n, &o, err);
    snprintf(name, sizeof name, "%.200s.xml", o.name);
    if (st == ACD_OK) st = join(path, sizeof path, dir, name, err);
    if (st == ACD_OK) st = acd_export_mjcf(path, "hulls", n, &o, err);
    if (simp) {
        for (size_t i = 0; i < n; i++) acd_hull_free(&simp[i]);
        free(simp);
    }
    return st;
}
