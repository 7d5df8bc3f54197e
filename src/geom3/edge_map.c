/* geom3/edge_map: half-edge lookup by sorted 64-bit keys (deterministic, no hashing). */
#include "geom3/edge_map.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"

typedef struct kv {
    uint64_t k;
    uint32_t h;
} kv;

static int cmp_kv(const void *x, const void *y) {
    const kv *a = x, *b = y;
    if (a->k != b->k) return a->k < b->k ? -1 : 1;
    return a->h < b->h ? -1 : (a->h > b->h);
}

acd_status acd_edge_map_build(const uint32_t *triangles, size_t ntriangles, const uint8_t *keep, acd_edge_map *m,
                              acd_error *err) {
    memset(m, 0, sizeof *m);
    if (ntriangles > (size_t)UINT32_MAX / 3)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "edge map: %zu triangles too many", ntriangles);
    size_t n = 0;
    for (size_t t = 0; t < ntriangles; t++)
        if (!keep || keep[t]) n += 3;
    kv *tmp = malloc((n ? n : 1) * sizeof *tmp);
    m->key = malloc((n ? n : 1) * sizeof *m->key);
    m->half = malloc((n ? n : 1) * sizeof *m->half);
    if (!tmp || !m->key || !m->half) {
        free(tmp);
        acd_edge_map_free(m);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for the half-edges of %zu triangles", ntriangles);
    }
    size_t k = 0;
    for (size_t t = 0; t < ntriangles; t++) {
        if (keep && !keep[t]) continue;
        for (int i = 0; i < 3; i++) {
            uint32_t a = triangles[3 * t + i], b = triangles[3 * t + (i + 1) % 3];
            tmp[k].k = ((uint64_t)a << 32) | b;
            tmp[k].h = (uint32_t)(3 * t + (size_t)i);
            k++;
        }
    }
    qsort(tmp, n, sizeof *tmp, cmp_kv);
    for (size_t i = 0; i < n; i++) {
        m->key[i] = tmp[i].k;
        m->half[i] = tmp[i].h;
    }
    m->n = n;
    free(tmp);
    return ACD_OK;
}

void acd_edge_map_free(acd_edge_map *m) {
    if (!m) return;
    free(m->key);
    free(m->half);
    memset(m, 0, sizeof *m);
}

/* First index with key >= k. */
static size_t lower_bound(const acd_edge_map *m, uint64_t k) {
    size_t lo = 0, hi = m->n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (m->key[mid] < k)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

uint32_t acd_edge_map_find(const acd_edge_map *m, uint32_t a, uint32_t b) {
    uint64_t k = ((uint64_t)a << 32) | b;
    size_t i = lower_bound(m, k);
    return i < m->n && m->key[i] == k ? m->half[i] : ACD_EDGE_NONE;
}

size_t acd_edge_map_count(const acd_edge_map *m, uint32_t a, uint32_t b) {
    uint64_t k = ((uint64_t)a << 32) | b;
    size_t i = lower_bound(m, k), c = 0;
    while (i + c < m->n && m->key[i + c] == k) c++;
    return c;
}

acd_status acd_edge_map_check_closed(const acd_edge_map *m, const uint32_t *triangles, size_t ntriangles,
                                     acd_error *err) {
    for (size_t t = 0; t < ntriangles; t++) {
        const uint32_t *q = triangles + 3 * t;
        if (q[0] == q[1] || q[1] == q[2] || q[2] == q[0])
            return acd_fail(err, ACD_ERR_NON_MANIFOLD, "triangle %zu (%u, %u, %u) repeats a vertex", t, q[0], q[1], q[2]);
    }
    for (size_t i = 0; i < m->n; i++) {
        uint32_t a = (uint32_t)(m->key[i] >> 32), b = (uint32_t)m->key[i];
        size_t t = m->half[i] / 3;
        if (i + 1 < m->n && m->key[i + 1] == m->key[i])
            return acd_fail(err, ACD_ERR_NON_MANIFOLD,
                            "edge (%u, %u) is used in the same direction by triangles %zu and %u (not a consistently "
                            "oriented manifold)",
                            a, b, t, m->half[i + 1] / 3);
        if (acd_edge_map_find(m, b, a) == ACD_EDGE_NONE)
            return acd_fail(err, ACD_ERR_NON_MANIFOLD, "edge (%u, %u) of triangle %zu has no opposite edge (mesh not closed)",
                            a, b, t);
    }
    (void)triangles;
    return ACD_OK;
}
