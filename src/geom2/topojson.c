/* geom2/topojson: TopoJSON (topojson-specification 1.0) polygon reader, with cJSON.
 *
 * A Topology stores shared boundary pieces once: "arcs" is a list of arcs (position lists); a
 * geometry's ring is a list of arc indices, index i meaning arc i and ~i (= -i-1) arc i
 * reversed. Consecutive arcs of a ring share their end point, which is kept once. With a
 * "transform" the topology is quantized: each arc's positions are delta-encoded integers
 * (position j is the sum of the first j+1 entries) mapped by x = sum * scale[0] + translate[0]
 * (likewise y). Every Polygon and every polygon of a MultiPolygon in the named objects (or in all
 * of them) becomes one polygon; Point/LineString types and "type": null are skipped. Errors name
 * the JSON path, e.g. "objects.countries.geometries[4].arcs[0][2]: arc index 812 out of range". */
#include "geom2/topojson.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "geom2/feature_select.h"
#include "geom2/geojson.h"
#include "geom2/polygon_build.h"

#define TJ_MAX_DEPTH 64
#define TJ_PATH 256
/* Rings copy the arcs they reference, so a small file can expand without bound (64 KB: one arc of
 * 2,700 positions referenced 24,000 times is 65 million points, over 2 GB). A topology uses an arc
 * on both sides of a shared boundary, once more per object that covers it again (world-atlas'
 * "land" beside "countries": at most 3); the positions the rings expand to are limited to
 * TJ_MAX_EXPANSION times the arcs' positions, and at least TJ_MIN_EXPANDED. */
#define TJ_MAX_EXPANSION 16
#define TJ_MIN_EXPANDED ((size_t)1 << 16)

typedef struct tj {
    acd_pbuild b;
    const char *name;
    acd_error *err;
    const char *feature; /* selector (NULL = every polygon) */
    size_t features;     /* geometries looked at */
    size_t matched;      /* geometries the selector kept */
    acd_vec2 *pts;       /* decoded arcs, one after the other */
    size_t *arc_start;   /* arc a is pts[arc_start[a] .. arc_start[a+1]-1]; narcs+1 entries */
    size_t narcs;
    size_t expanded;     /* positions the rings have copied from the arcs so far */
} tj;

static void path_index(char *dst, size_t size, const char *base, size_t i) {
    if (snprintf(dst, size, "%s[%zu]", base, i) >= (int)size) dst[size - 1] = '\0';
}

static void path_field(char *dst, size_t size, const char *base, const char *field) {
    if (snprintf(dst, size, "%s%s%s", base, *base ? "." : "", field) >= (int)size) dst[size - 1] = '\0';
}

/* a pair [a, b] of finite numbers */
static int number_pair(const cJSON *v, double *a, double *b) {
    const cJSON *x = cJSON_IsArray(v) ? v->child : NULL, *y = x ? x->next : NULL;
    if (!x || !y || !cJSON_IsNumber(x) || !cJSON_IsNumber(y)) return 0;
    if (!isfinite(x->valuedouble) || !isfinite(y->valuedouble)) return 0;
    *a = x->valuedouble;
    *b = y->valuedouble;
    return 1;
}

static acd_status decode_arcs(tj *t, const cJSON *root) {
    const cJSON *tr = cJSON_GetObjectItemCaseSensitive(root, "transform");
    int quantized = tr && !cJSON_IsNull(tr);
    double sx = 1, sy = 1, tx = 0, ty = 0;
    if (quantized) {
        if (!cJSON_IsObject(tr))
            return acd_fail(t->err, ACD_ERR_PARSE, "%s: transform: expected an object with \"scale\" and \"translate\"",
                            t->name);
        const cJSON *sc = cJSON_GetObjectItemCaseSensitive(tr, "scale");
        const cJSON *tl = cJSON_GetObjectItemCaseSensitive(tr, "translate");
        if (!sc || !number_pair(sc, &sx, &sy))
            return acd_fail(t->err, ACD_ERR_PARSE, "%s: transform.scale: %s", t->name,
                            sc ? "expected [sx, sy], two finite numbers" : "missing (a transform needs a scale)");
        if (!tl || !number_pair(tl, &tx, &ty))
            return acd_fail(t->err, ACD_ERR_PARSE, "%s: transform.translate: %s", t->name,
                            tl ? "expected [tx, ty], two finite numbers"
                               : "missing (a transform needs a translate)");
    }
    const cJSON *arcs = cJSON_GetObjectItemCaseSensitive(root, "arcs");
    if (!arcs)
        return acd_fail(t->err, ACD_ERR_PARSE, "%s: missing \"arcs\" (every Topology has an arc list, maybe empty)",
                        t->name);
    if (!cJSON_IsArray(arcs))
        return acd_fail(t->err, ACD_ERR_PARSE, "%s: arcs: expected an array of arcs", t->name);
    /* sizes first: the JSON is in memory already, so counting bounds the allocation */
    size_t narcs = 0, npts = 0;
    for (const cJSON *a = arcs->child; a; a = a->next, narcs++) {
        if (!cJSON_IsArray(a) || !a->child)
            return acd_fail(t->err, ACD_ERR_PARSE, "%s: arcs[%zu]: expected an arc (a non-empty array of positions)",
                            t->name, narcs);
        for (const cJSON *p = a->child; p; p = p->next) npts++;
    }
    t->arc_start = malloc((narcs + 1) * sizeof *t->arc_start);
    t->pts = malloc((npts ? npts : 1) * sizeof *t->pts);
    if (!t->arc_start || !t->pts)
        return acd_fail(t->err, ACD_ERR_NOMEM, "%s: out of memory for %zu arc positions", t->name, npts);
    t->narcs = narcs;
    size_t k = 0, ai = 0;
    for (const cJSON *a = arcs->child; a; a = a->next, ai++) {
        t->arc_start[ai] = k;
        double x = 0, y = 0;
        size_t j = 0;
        for (const cJSON *p = a->child; p; p = p->next, j++) {
            double u, v;
            if (!number_pair(p, &u, &v))
                return acd_fail(t->err, ACD_ERR_PARSE, "%s: arcs[%zu][%zu]: expected a position [x, y] of two finite numbers",
                                t->name, ai, j);
            if (quantized) {
                x += u; /* delta-encoded */
                y += v;
                u = x * sx + tx;
                v = y * sy + ty;
                if (!isfinite(u) || !isfinite(v))
                    return acd_fail(t->err, ACD_ERR_PARSE,
                                    "%s: arcs[%zu][%zu]: decoded coordinate out of the range of double", t->name, ai, j);
            }
            t->pts[k].x = u;
            t->pts[k].y = v;
            k++;
        }
    }
    t->arc_start[narcs] = k;
    return ACD_OK;
}

/* One ring: an array of arc indices. */
static acd_status read_ring(tj *t, const cJSON *ring, const char *path) {
    if (!cJSON_IsArray(ring) || !ring->child)
        return acd_fail(t->err, ACD_ERR_PARSE, "%s: %s: expected a ring (a non-empty array of arc indices)", t->name,
                        path);
    acd_status st = acd_pbuild_begin_ring(&t->b, t->err);
    size_t i = 0;
    for (const cJSON *ix = ring->child; ix && st == ACD_OK; ix = ix->next, i++) {
        double d = cJSON_IsNumber(ix) ? ix->valuedouble : NAN;
        if (!(d == floor(d)) || fabs(d) > 1e15)
            return acd_fail(t->err, ACD_ERR_PARSE, "%s: %s[%zu]: expected an arc index (an integer; ~i = -i-1 is arc i reversed)",
                            t->name, path, i);
        long long v = (long long)d;
        int reversed = v < 0;
        long long a = reversed ? -v - 1 : v;
        if (a >= (long long)t->narcs)
            return acd_fail(t->err, ACD_ERR_PARSE,
                            "%s: %s[%zu]: arc index %lld out of range (the topology has %zu arcs; ~i = -i-1 is arc i "
                            "reversed)",
                            t->name, path, i, v, t->narcs);
        size_t s = t->arc_start[a], e = t->arc_start[a + 1];
        size_t npts = t->arc_start[t->narcs], limit = npts > TJ_MIN_EXPANDED / TJ_MAX_EXPANSION
                                                          ? npts * TJ_MAX_EXPANSION
                                                          : TJ_MIN_EXPANDED;
        if (e - s > limit - t->expanded)
            return acd_fail(t->err, ACD_ERR_INVALID_INPUT,
                            "%s: %s[%zu]: the rings' arc references expand to more than %zu positions (%d times the "
                            "arcs' %zu): refused (arcs referenced that often are no topology's shared boundaries)",
                            t->name, path, i, limit, TJ_MAX_EXPANSION, npts);
        t->expanded += e - s;
        size_t have;
        acd_vec2 *cur = acd_pbuild_ring(&t->b, &have);
        for (size_t q = 0; q < e - s && st == ACD_OK; q++) {
            acd_vec2 p = t->pts[reversed ? e - 1 - q : s + q];
            /* consecutive arcs share their end point: keep it once */
            if (q == 0 && have > 0 && cur[have - 1].x == p.x && cur[have - 1].y == p.y) continue;
            st = acd_pbuild_add_point(&t->b, p.x, p.y, t->err);
        }
    }
    return st;
}

/* One Polygon's "arcs": an array of rings. */
static acd_status read_polygon(tj *t, const cJSON *rings, const char *path) {
    if (!cJSON_IsArray(rings))
        return acd_fail(t->err, ACD_ERR_PARSE, "%s: %s: expected an array of rings (arrays of arc indices)", t->name,
                        path);
    if (!rings->child) return ACD_OK; /* empty polygon */
    acd_status st = acd_pbuild_begin_polygon(&t->b, t->err);
    size_t r = 0;
    char rp[TJ_PATH];
    for (const cJSON *ring = rings->child; ring && st == ACD_OK; ring = ring->next, r++) {
        path_index(rp, sizeof rp, path, r);
        st = read_ring(t, ring, rp);
    }
    if (st == ACD_OK) st = acd_pbuild_end_polygon(&t->b, t->err);
    return st;
}

static acd_status walk(tj *t, const cJSON *g, const char *path, int depth, int keep) {
    if (depth > TJ_MAX_DEPTH)
        return acd_fail(t->err, ACD_ERR_PARSE, "%s: %s: geometry collections nested more than %d deep", t->name, path,
                        TJ_MAX_DEPTH);
    if (!cJSON_IsObject(g))
        return acd_fail(t->err, ACD_ERR_PARSE, "%s: %s: expected a TopoJSON geometry object", t->name, path);
    const cJSON *type = cJSON_GetObjectItemCaseSensitive(g, "type");
    if (cJSON_IsNull(type)) return ACD_OK; /* a null geometry */
    if (!cJSON_IsString(type) || !type->valuestring)
        return acd_fail(t->err, ACD_ERR_PARSE, "%s: %s: expected a \"type\" member (a string or null)", t->name, path);
    t->features++;
    if (!keep && acd_feature_matches(g, t->feature)) {
        keep = 1;
        t->matched++;
    }
    const char *ty = type->valuestring;
    char fp[TJ_PATH], ip[TJ_PATH];
    if (strcmp(ty, "GeometryCollection") == 0) {
        const cJSON *gs = cJSON_GetObjectItemCaseSensitive(g, "geometries");
        path_field(fp, sizeof fp, path, "geometries");
        if (!cJSON_IsArray(gs))
            return acd_fail(t->err, ACD_ERR_PARSE, "%s: %s: expected an array of geometries", t->name, fp);
        size_t i = 0;
        for (const cJSON *it = gs->child; it; it = it->next, i++) {
            path_index(ip, sizeof ip, fp, i);
            acd_status st = walk(t, it, ip, depth + 1, keep);
            if (st != ACD_OK) return st;
        }
        return ACD_OK;
    }
    if (strcmp(ty, "Polygon") == 0 || strcmp(ty, "MultiPolygon") == 0) {
        const cJSON *arcs = cJSON_GetObjectItemCaseSensitive(g, "arcs");
        path_field(fp, sizeof fp, path, "arcs");
        if (!arcs)
            return acd_fail(t->err, ACD_ERR_PARSE, "%s: %s: missing \"arcs\" (the rings as arc indices)", t->name, path);
        if (!keep) return ACD_OK;
        if (ty[0] == 'P') return read_polygon(t, arcs, fp);
        if (!cJSON_IsArray(arcs))
            return acd_fail(t->err, ACD_ERR_PARSE, "%s: %s: expected an array of polygons", t->name, fp);
        size_t i = 0;
        for (const cJSON *pc = arcs->child; pc; pc = pc->next, i++) {
            path_index(ip, sizeof ip, fp, i);
            acd_status st = read_polygon(t, pc, ip);
            if (st != ACD_OK) return st;
        }
        return ACD_OK;
    }
    if (strcmp(ty, "Point") == 0 || strcmp(ty, "MultiPoint") == 0 || strcmp(ty, "LineString") == 0 ||
        strcmp(ty, "MultiLineString") == 0)
        return ACD_OK; /* not polygonal: skipped */
    return acd_fail(t->err, ACD_ERR_PARSE, "%s: %s: unknown TopoJSON geometry type \"%.40s\"", t->name, path, ty);
}

acd_status acd_topojson_from_json(acd_polygon_set *out, const cJSON *root, const char *name, const char *object,
                                  const char *feature, acd_error *err) {
    memset(out, 0, sizeof *out);
    tj t;
    memset(&t, 0, sizeof t);
    acd_pbuild_init(&t.b);
    t.name = name ? name : "<input>";
    t.err = err;
    t.feature = feature;
    acd_status st = ACD_OK;
    if (!acd_json_is_topology(root)) {
        st = acd_fail(err, ACD_ERR_PARSE, "%s: not TopoJSON: expected an object with \"type\": \"Topology\"", t.name);
        goto done;
    }
    const cJSON *objects = cJSON_GetObjectItemCaseSensitive(root, "objects");
    if (!cJSON_IsObject(objects)) {
        st = acd_fail(err, ACD_ERR_PARSE, "%s: objects: %s", t.name,
                      objects ? "expected an object mapping names to geometries"
                              : "missing (a Topology names its geometries in \"objects\")");
        goto done;
    }
    st = decode_arcs(&t, root);
    if (st != ACD_OK) goto done;
    size_t seen = 0;
    char path[TJ_PATH];
    for (const cJSON *o = objects->child; o && st == ACD_OK; o = o->next) {
        if (object && (!o->string || strcmp(o->string, object) != 0)) continue;
        seen++;
        path_field(path, sizeof path, "objects", o->string ? o->string : "?");
        st = walk(&t, o, path, 0, feature == NULL);
    }
    if (st != ACD_OK) goto done;
    if (object && !seen) {
        char names[160] = "";
        size_t used = 0;
        for (const cJSON *o = objects->child; o && o->string && used + 4 < sizeof names; o = o->next) {
            int w = snprintf(names + used, sizeof names - used, "%s'%s'", used ? ", " : "", o->string);
            if (w < 0 || (size_t)w >= sizeof names - used) {
                names[used] = '\0';
                break;
            }
            used += (size_t)w;
        }
        st = acd_fail(err, ACD_ERR_INVALID_INPUT, "%s: no object named '%.60s' in objects (it has %s)", t.name, object,
                      used ? names : "none");
        goto done;
    }
    if (feature && t.matched == 0) {
        st = acd_fail(err, ACD_ERR_INVALID_INPUT,
                      "%s: no geometry matches the selector '%.80s' (%zu geometries looked at; a selector 'VALUE' "
                      "matches the id or any property, 'KEY=VALUE' one property)",
                      t.name, feature, t.features);
        goto done;
    }
    st = acd_pbuild_take(&t.b, out, err);
done:
    acd_pbuild_free(&t.b);
    free(t.pts);
    free(t.arc_start);
    return st;
}

acd_status acd_topojson_parse(acd_polygon_set *out, const char *text, size_t len, const char *name, acd_error *err) {
    memset(out, 0, sizeof *out);
    cJSON *root = acd_json_parse(text, len, name ? name : "<input>", err);
    if (!root) return ACD_ERR_PARSE;
    acd_status st = acd_topojson_from_json(out, root, name, NULL, NULL, err);
    cJSON_Delete(root);
    return st;
}
