/* geom2/feature_select: which GeoJSON Features / TopoJSON geometries a selector keeps. */
#include "geom2/feature_select.h"

#include <stdlib.h>
#include <string.h>

/* value v equals the text s[0..n) */
static int value_equals(const cJSON *v, const char *s, size_t n) {
    if (!v) return 0;
    if (cJSON_IsString(v) && v->valuestring) return strlen(v->valuestring) == n && memcmp(v->valuestring, s, n) == 0;
    if (cJSON_IsNumber(v) && n > 0 && n < 64) {
        char buf[64];
        memcpy(buf, s, n);
        buf[n] = '\0';
        char *end = NULL;
        double d = strtod(buf, &end);
        return end && *end == '\0' && end != buf && d == v->valuedouble;
    }
    return 0;
}

int acd_feature_matches(const cJSON *obj, const char *sel) {
    if (!sel) return 1;
    if (!cJSON_IsObject(obj)) return 0;
    const cJSON *props = cJSON_GetObjectItemCaseSensitive(obj, "properties");
    if (!cJSON_IsObject(props)) props = NULL;
    const char *eq = strchr(sel, '=');
    if (eq) {
        size_t klen = (size_t)(eq - sel);
        const char *val = eq + 1;
        size_t vlen = strlen(val);
        if (klen == 2 && memcmp(sel, "id", 2) == 0 &&
            value_equals(cJSON_GetObjectItemCaseSensitive(obj, "id"), val, vlen))
            return 1;
        if (props)
            for (const cJSON *p = props->child; p; p = p->next)
                if (p->string && strlen(p->string) == klen && memcmp(p->string, sel, klen) == 0 &&
                    value_equals(p, val, vlen))
                    return 1;
        /* fall through: a value may itself contain '=' */
    }
    size_t n = strlen(sel);
    if (value_equals(cJSON_GetObjectItemCaseSensitive(obj, "id"), sel, n)) return 1;
    if (props)
        for (const cJSON *p = props->child; p; p = p->next)
            if (value_equals(p, sel, n)) return 1;
    return 0;
}
