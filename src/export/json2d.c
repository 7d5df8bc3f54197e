/* export/json2d: JSON report of a 2D decomposition, built with cJSON (format in json2d.h). */
#include "export/json2d.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

static const char *measure_name(acd2d_measure m) {
    switch (m) {
    case ACD2D_MEASURE_SL: return "sl";
    case ACD2D_MEASURE_SP: return "sp";
    case ACD2D_MEASURE_H1: return "h1";
    case ACD2D_MEASURE_H2: return "h2";
    }
    return "?";
}

/* Building state: ok drops to 0 at the first allocation failure. */
typedef struct jb {
    int ok;
} jb;

static cJSON *add(jb *b, cJSON *parent, const char *key, cJSON *item) {
    if (!item) {
        b->ok = 0;
        return NULL;
    }
    if (!parent) {
        cJSON_Delete(item);
        b->ok = 0;
        return NULL;
    }
    int r = key ? cJSON_AddItemToObject(parent, key, item) : cJSON_AddItemToArray(parent, item);
    if (!r) {
        cJSON_Delete(item);
        b->ok = 0;
        return NULL;
    }
    return item;
}

/* A number printed with the fewest of 15, 16, 17 significant digits that read back exactly
 * (cJSON's own printer may drop the last ulp); null for a non-finite value. */
static cJSON *num(double v) {
    char buf[40];
    if (!isfinite(v)) return cJSON_CreateNull();
    for (int digits = 15; digits <= 17; digits++) {
        snprintf(buf, sizeof buf, "%.*g", digits, v);
        if (strtod(buf, NULL) == v) break;
    }
    return cJSON_CreateRaw(buf);
}

static cJSON *point(acd_vec2 p) {
    cJSON *a = cJSON_CreateArray();
    if (!a) return NULL;
    cJSON *x = num(p.x), *y = num(p.y);
    if (!x || !y) {
        cJSON_Delete(x);
        cJSON_Delete(y);
        cJSON_Delete(a);
        return NULL;
    }
    cJSON_AddItemToArray(a, x);
    cJSON_AddItemToArray(a, y);
    return a;
}

static cJSON *point_list(jb *b, const acd_vec2 *p, size_t n) {
    cJSON *a = cJSON_CreateArray();
    for (size_t i = 0; a && i < n; i++) add(b, a, NULL, point(p[i]));
    return a;
}

static cJSON *build(const acd_json2d_doc *d) {
    jb b = {1};
    cJSON *root = cJSON_CreateObject();
    if (!root) return NULL;
    const acd2d_result *r0 = d->count ? &d->results[0] : NULL;
    double tau = r0 ? r0->tau : (d->params ? d->params->tau : 0);
    acd2d_measure m = r0 ? r0->measure : (d->params ? d->params->measure : ACD2D_MEASURE_SL);
    add(&b, root, "tau", num(tau));
    add(&b, root, "measure", cJSON_CreateString(measure_name(m)));
    if (d->params) {
        cJSON *p = add(&b, root, "params", cJSON_CreateObject());
        add(&b, p, "tau", num(d->params->tau));
        add(&b, p, "sc", num(d->params->sc));
        add(&b, p, "sd", num(d->params->sd));
        add(&b, p, "cut", cJSON_CreateString(d->params->cut == ACD2D_CUT_DIAGONAL ? "diagonal" : "ray"));
        add(&b, p, "normalize", cJSON_CreateBool(d->params->normalize != 0));
        add(&b, p, "notch_tolerance", num(d->params->notch_tolerance));
    }
    size_t nv = 0, nr = 0, nh = 0, nc = 0;
    double area = 0, maxc = 0, secs = 0;
    for (size_t i = 0; i < d->count; i++) {
        nv += d->results[i].input_vertices;
        nr += d->results[i].input_notches;
        nh += d->results[i].input_holes;
        nc += d->results[i].ncomponents;
        area += acd_polygon_area(&d->inputs[i]);
        if (d->results[i].max_concavity > maxc) maxc = d->results[i].max_concavity;
        secs += d->results[i].seconds;
    }
    cJSON *in = add(&b, root, "input", cJSON_CreateObject());
    add(&b, in, "polygons", num((double)d->count));
    add(&b, in, "vertices", num((double)nv));
    add(&b, in, "notches", num((double)nr));
    add(&b, in, "holes", num((double)nh));
    add(&b, in, "area", num(area));

    cJSON *comps = add(&b, root, "components", cJSON_CreateArray());
    cJSON *hulls = add(&b, root, "hulls", cJSON_CreateArray());
    cJSON *concs = add(&b, root, "concavities", cJSON_CreateArray());
    cJSON *cuts = add(&b, root, "cuts", cJSON_CreateArray());
    cJSON *polys = add(&b, root, "polygons", cJSON_CreateArray());
    cJSON *trees = add(&b, root, "tree", cJSON_CreateArray());
    size_t first = 0;
    for (size_t i = 0; i < d->count && b.ok; i++) {
        const acd2d_result *r = &d->results[i];
        for (size_t c = 0; c < r->ncomponents && b.ok; c++) {
            add(&b, comps, NULL, point_list(&b, r->components[c].points, r->components[c].npoints));
            add(&b, hulls, NULL, point_list(&b, r->components[c].hull, r->components[c].nhull));
            add(&b, concs, NULL, num(r->components[c].concavity));
        }
        for (size_t c = 0; c < r->ncuts && b.ok; c++) add(&b, cuts, NULL, point_list(&b, r->cuts[c], 2));
        cJSON *p = add(&b, polys, NULL, cJSON_CreateObject());
        add(&b, p, "vertices", num((double)r->input_vertices));
        add(&b, p, "notches", num((double)r->input_notches));
        add(&b, p, "holes", num((double)r->input_holes));
        add(&b, p, "first_component", num((double)first));
        add(&b, p, "components", num((double)r->ncomponents));
        add(&b, p, "cuts", num((double)r->ncuts));
        add(&b, p, "max_concavity", num(r->max_concavity));
        add(&b, p, "seconds", num(r->seconds));
        /* the tree: leaves point at their component (global index) */
        cJSON *t = add(&b, trees, NULL, cJSON_CreateArray());
        long *leaf = malloc((r->nnodes ? r->nnodes : 1) * sizeof *leaf);
        if (!leaf) b.ok = 0;
        for (size_t k = 0; leaf && k < r->nnodes; k++) leaf[k] = -1;
        for (size_t c = 0; leaf && c < r->ncomponents; c++)
            if (r->components[c].node >= 0 && (size_t)r->components[c].node < r->nnodes)
                leaf[r->components[c].node] = (long)(first + c);
        for (size_t k = 0; k < r->nnodes && b.ok; k++) {
            const acd2d_node *nd = &r->nodes[k];
            cJSON *o = add(&b, t, NULL, cJSON_CreateObject());
            add(&b, o, "id", num((double)k));
            add(&b, o, "parent", num(nd->parent));
            cJSON *ch = add(&b, o, "children", cJSON_CreateArray());
            for (int j = 0; j < 2; j++)
                if (nd->child[j] >= 0) add(&b, ch, NULL, num(nd->child[j]));
            add(&b, o, "concavity", num(nd->concavity));
            if (nd->child[0] >= 0 || nd->child[1] >= 0) {
                add(&b, o, "cut", point_list(&b, nd->cut, 2));
                add(&b, o, "hole_merge", cJSON_CreateBool(nd->is_hole_merge != 0));
            }
            add(&b, o, "component", num((double)leaf[k]));
        }
        free(leaf);
        first += r->ncomponents;
    }
    cJSON *st = add(&b, root, "stats", cJSON_CreateObject());
    add(&b, st, "components", num((double)nc));
    add(&b, st, "max_concavity", num(maxc));
    add(&b, st, "seconds", num(secs));
    if (d->verified) {
        cJSON *v = add(&b, root, "verify", cJSON_CreateObject());
        add(&b, v, "passed", cJSON_CreateBool(d->verified > 0));
        if (d->verify_message) add(&b, v, "message", cJSON_CreateString(d->verify_message));
    }
    if (!b.ok) {
        cJSON_Delete(root);
        return NULL;
    }
    return root;
}

char *acd_json2d_string(const acd_json2d_doc *doc) {
    cJSON *root = build(doc);
    if (!root) return NULL;
    char *s = cJSON_PrintUnformatted(root);
    cJSON_Delete(root);
    return s;
}

acd_status acd_json2d_write(const char *path, const acd_json2d_doc *doc, acd_error *err) {
    char *s = acd_json2d_string(doc);
    if (!s) return acd_fail(err, ACD_ERR_NOMEM, "out of memory while building the JSON report");
    int to_stdout = !strcmp(path, "-");
    FILE *f = to_stdout ? stdout : fopen(path, "w");
    if (!f) {
        int e = errno;
        free(s);
        return acd_fail(err, ACD_ERR_IO, "cannot write the JSON report '%s': %s", path, strerror(e));
    }
    size_t len = strlen(s);
    int bad = fwrite(s, 1, len, f) != len || fputc('\n', f) == EOF;
    if (to_stdout)
        bad |= fflush(f) != 0;
    else
        bad |= fclose(f) != 0;
    free(s);
    if (bad) return acd_fail(err, ACD_ERR_IO, "error writing the JSON report '%s'", path);
    return ACD_OK;
}
