/* geom3/edge_map: half-edge lookup by sorted 64-bit keys (deterministic, no hashing). */
#include "geom3/edge_map.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"

/* Stable LSD radix sort of keys[0..n) carrying vals, by bytes 0..nbytes-1 of the low word and
 * then of the high word (the key's halves are vertex ids below 2^(8 nbytes)). Stable: equal
 * keys keep their input order. tk, tv: scratch of n entries. */
static void radix_sort(uint64_t *keys, uint32_t *vals, uint64_t *tk, uint32_t *tv, size_t n, int nbytes) {
    size_t cnt[256];
    uint64_t *k0 = keys, *k1 = tk;
    uint32_t *v0 = vals, *v1 = tv;
    for (int half = 0; half < 2; half++)
        for (int byte = 0; byte < nbytes; byte++) {
            int shift = 32 * half + 8 * byte;
            memset(cnt, 0, sizeof cnt);
            for (size_t i = 0; i < n; i++) cnt[(k0[i] >> shift) & 0xff]++;
            if (n == 0 || cnt[(k0[0] >> shift) & 0xff] == n) continue; /* one digit: nothing moves */
            size_t sum = 0;
            for (int d = 0; d < 256; d++) {
                size_t c = cnt[d];
                cnt[d] = sum;
                sum += c;
            }
            for (size_t i = 0; i < n; i++) {
                size_t j = cnt[(k0[i] >> shift) & 0xff]++;
                k1[j] = k0[i];
                v1[j] = v0[i];
            }
            uint64_t *tk_ = k0;
            k0 = k1;
            k1 = tk_;
            uint32_t *tv_ = v0;
            v0 = v1;
            v1 = tv_;
        }
    if (k0 != keys) {
        memcpy(keys, k0, n * sizeof *keys);
        memcpy(vals, v0, n * sizeof *vals);
    }
}

static int id_bytes(uint32_t maxid) {
    int b = 1;
    while (b < 4 && (maxid >> (8 * b))) b++;
    return b;
}

acd_status acd_edge_map_build(const uint32_t *triangles, size_t ntriangles, const uint8_t *keep, acd_edge_map *m,
                              acd_error *err) {
    memset(m, 0, sizeof *m);
    if (ntriangles > (size_t)UINT32_MAX / 3)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "edge map: %zu triangles too many", ntriangles);
    size_t n = 0;
    for (size_t t = 0; t < ntriangles; t++)
        if (!keep || keep[t]) n += 3;
    uint64_t *tk = malloc((n ? n : 1) * sizeof *tk);
    uint32_t *tv = malloc((n ? n : 1) * sizeof *tv);
    m->key = malloc((n ? n : 1) * sizeof *m->key);
    m->half = malloc((n ? n : 1) * sizeof *m->half);
    if (!tk || !tv || !m->key || !m->half) {
        free(tk);
        free(tv);
        acd_edge_map_free(m);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for the half-edges of %zu triangles", ntriangles);
    }
    size_t k = 0;
    uint32_t maxid = 0;
    for (size_t t = 0; t < ntriangles; t++) {
        if (keep && !keep[t]) continue;
        for (int i = 0; i < 3; i++) {
            uint32_t a = triangles[3 * t + i], b = triangles[3 * t + (i + 1) % 3];
            if (a > maxid) maxid = a;
            m->key[k] = ((uint64_t)a << 32) | b;
            m->half[k] = (uint32_t)(3 * t + (size_t)i);
            k++;
        }
    }
    /* sorted by (key, half): half increases with k, and the sort is stable */
    radix_sort(m->key, m->half, tk, tv, n, id_bytes(maxid));
    m->n = n;
    free(tk);
    free(tv);
    return ACD_OK;
}

acd_status acd_edge_map_twins(const acd_edge_map *m, uint32_t **twin, acd_error *err) {
    size_t n = m->n;
    uint64_t *rk = malloc((n ? n : 1) * sizeof *rk), *tk = malloc((n ? n : 1) * sizeof *tk);
    uint32_t *ri = malloc((n ? n : 1) * sizeof *ri), *tv = malloc((n ? n : 1) * sizeof *tv);
    uint32_t *tw = malloc((n ? n : 1) * sizeof *tw);
    if (!rk || !tk || !ri || !tv || !tw) {
        free(rk);
        free(tk);
        free(ri);
        free(tv);
        free(tw);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for the twins of %zu half-edges", n);
    }
    uint32_t maxid = 0;
    for (size_t i = 0; i < n; i++) {
        uint32_t a = (uint32_t)(m->key[i] >> 32), b = (uint32_t)m->key[i];
        if (a > maxid) maxid = a;
        rk[i] = ((uint64_t)b << 32) | a;
        ri[i] = (uint32_t)i;
    }
    radix_sort(rk, ri, tk, tv, n, id_bytes(maxid));
    /* merge walk: the first index p with key[p] == rk[j] */
    size_t p = 0;
    for (size_t j = 0; j < n; j++) {
        while (p < n && m->key[p] < rk[j]) p++;
        tw[ri[j]] = p < n && m->key[p] == rk[j] ? m->half[p] : ACD_EDGE_NONE;
    }
    free(rk);
    free(tk);
    free(ri);
    free(tv);
    *twin = tw;
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
    uint32_t *tw = NULL;
    acd_status st = acd_edge_map_twins(m, &tw, err);
    if (st != ACD_OK) return st;
    for (size_t i = 0; i < m->n; i++) {
        uint32_t a = (uint32_t)(m->key[i] >> 32), b = (uint32_t)m->key[i];
        size_t t = m->half[i] / 3;
        if (i + 1 < m->n && m->key[i + 1] == m->key[i]) {
            free(tw);
            return acd_fail(err, ACD_ERR_NON_MANIFOLD,
                            "edge (%u, %u) is used in the same direction by triangles %zu and %u (not a consistently "
                            "oriented manifold)",
                            a, b, t, m->half[i + 1] / 3);
        }
        if (tw[i] == ACD_EDGE_NONE) {
            free(tw);
            return acd_fail(err, ACD_ERR_NON_MANIFOLD, "edge (%u, %u) of triangle %zu has no opposite edge (mesh not closed)",
                            a, b, t);
        }
    }
    free(tw);
    (void)triangles;
    return ACD_OK;
}
