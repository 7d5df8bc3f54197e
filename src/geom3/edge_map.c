/* geom3/edge_map: half-edge lookup by sorted 64-bit keys (radix sorted; deterministic, no hashing). */
#include "geom3/edge_map.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"

#define RADIX_BITS 11
#define RADIX_BUCKETS (1u << RADIX_BITS)

#define INSERTION_MAX 48 /* up to this many keys: an insertion sort */

/* Sorts keys[0..n) = (a << 32) | b (a, b <= maxid) carrying vals, stably (equal keys keep their
 * input order: every path gives the same order). Up to INSERTION_MAX keys by insertion; with
 * dense ids (maxid < 2n, as a mesh's half-edges) by two counting passes, on b then on a (a
 * bucket per vertex, all counts taken in one read); else the pair is packed as a * (maxid + 1) + b,
 * which orders the same, and sorted by an LSD radix sort on 11-bit digits of that (all digit
 * counts taken in one read; a pass whose digits are all equal is skipped). tk, tv: scratch of n
 * entries (unused up to INSERTION_MAX). Returns 0 when out of memory. */

static int radix_sort(uint64_t *keys, uint32_t *vals, uint64_t *tk, uint32_t *tv, size_t n, uint32_t maxid) {
    if (n <= INSERTION_MAX) { /* the same order: both are stable sorts by key */
        for (size_t i = 1; i < n; i++) {
            uint64_t k = keys[i];
            uint32_t v = vals[i];
            size_t j = i;
            for (; j > 0 && keys[j - 1] > k; j--) keys[j] = keys[j - 1], vals[j] = vals[j - 1];
            keys[j] = k, vals[j] = v;
        }
        return 1;
    }
    if ((uint64_t)maxid < 2 * (uint64_t)n) { /* dense ids: two counting passes, a digit per vertex */
        size_t nb = (size_t)maxid + 1;
        size_t *cb = calloc(2 * (nb + 1), sizeof *cb), *ca = cb ? cb + nb + 1 : NULL;
        if (!cb) return 0;
        for (size_t i = 0; i < n; i++) {
            ca[(keys[i] >> 32) + 1]++;
            cb[(uint32_t)keys[i] + 1]++;
        }
        for (size_t v = 0; v < nb; v++) ca[v + 1] += ca[v], cb[v + 1] += cb[v];
        for (size_t i = 0; i < n; i++) { /* by b, stable */
            size_t j = cb[(uint32_t)keys[i]]++;
            tk[j] = keys[i];
            tv[j] = vals[i];
        }
        for (size_t i = 0; i < n; i++) { /* then by a, stable */
            size_t j = ca[tk[i] >> 32]++;
            keys[j] = tk[i];
            vals[j] = tv[i];
        }
        free(cb);
        return 1;
    }
    uint64_t n1 = (uint64_t)maxid + 1;
    int bits = 64;
    if (n1 <= (1ull << 31)) {
        uint64_t top = n1 * n1 - 1;
        bits = 1;
        while (bits < 64 && (top >> bits)) bits++;
    }
    int passes = (bits + RADIX_BITS - 1) / RADIX_BITS;
    size_t *cnt = calloc((size_t)passes * RADIX_BUCKETS, sizeof *cnt);
    if (!cnt) return 0;
    for (size_t i = 0; i < n; i++) {
        uint64_t c = (keys[i] >> 32) * n1 + (keys[i] & 0xffffffffu);
        tk[i] = c;
        for (int p = 0; p < passes; p++) cnt[(size_t)p * RADIX_BUCKETS + ((c >> (RADIX_BITS * p)) & (RADIX_BUCKETS - 1))]++;
    }
    memcpy(tv, vals, n * sizeof *vals);
    uint64_t *k0 = tk, *k1 = keys;
    uint32_t *v0 = tv, *v1 = vals;
    for (int p = 0; p < passes; p++) {
        size_t *c = cnt + (size_t)p * RADIX_BUCKETS;
        int shift = RADIX_BITS * p;
        if (n == 0 || c[(k0[0] >> shift) & (RADIX_BUCKETS - 1)] == n) continue; /* one digit: nothing moves */
        size_t sum = 0;
        for (unsigned d = 0; d < RADIX_BUCKETS; d++) {
            size_t x = c[d];
            c[d] = sum;
            sum += x;
        }
        for (size_t i = 0; i < n; i++) {
            size_t j = c[(k0[i] >> shift) & (RADIX_BUCKETS - 1)]++;
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
    free(cnt);
    for (size_t i = 0; i < n; i++) keys[i] = ((k0[i] / n1) << 32) | (k0[i] % n1);
    if (v0 != vals) memcpy(vals, v0, n * sizeof *vals);
    return 1;
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
            if (b > maxid) maxid = b;
            m->key[k] = ((uint64_t)a << 32) | b;
            m->half[k] = (uint32_t)(3 * t + (size_t)i);
            k++;
        }
    }
    /* sorted by (key, half): half increases with k, and the sort is stable */
    int ok = radix_sort(m->key, m->half, tk, tv, n, maxid);
    m->n = n;
    free(tk);
    free(tv);
    if (!ok) {
        acd_edge_map_free(m);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory sorting the half-edges of %zu triangles", ntriangles);
    }
    return ACD_OK;
}

/* The largest vertex id in m's keys (0 when empty). */
static uint32_t keys_max_id(const acd_edge_map *m) {
    uint32_t maxid = 0;
    for (size_t i = 0; i < m->n; i++) {
        uint32_t a = (uint32_t)(m->key[i] >> 32), b = (uint32_t)m->key[i];
        if (a > maxid) maxid = a;
        if (b > maxid) maxid = b;
    }
    return maxid;
}

acd_status acd_edge_map_sort(acd_edge_map *m, acd_error *err) {
    size_t n = m->n;
    uint32_t maxid = keys_max_id(m);
    uint64_t *tk = NULL;
    uint32_t *tv = NULL;
    if (n > INSERTION_MAX) {
        tk = malloc(n * sizeof *tk);
        tv = malloc(n * sizeof *tv);
    }
    int ok = (n <= INSERTION_MAX || (tk && tv)) && radix_sort(m->key, m->half, tk, tv, n, maxid);
    free(tk);
    free(tv);
    return ok ? ACD_OK : acd_fail(err, ACD_ERR_NOMEM, "out of memory sorting %zu half-edges", n);
}

static size_t lower_bound(const acd_edge_map *m, uint64_t k);

/* Up to this many entries, the twins by a binary search each (no sort's fixed cost). */
#define TWINS_SEARCH_MAX 1024

acd_status acd_edge_map_twins(const acd_edge_map *m, uint32_t **twin, acd_error *err) {
    size_t n = m->n;
    if (n <= TWINS_SEARCH_MAX) { /* the first entry of the key b -> a, as the merge walk finds it */
        uint32_t *tw = malloc((n ? n : 1) * sizeof *tw);
        if (!tw) return acd_fail(err, ACD_ERR_NOMEM, "out of memory for the twins of %zu half-edges", n);
        for (size_t i = 0; i < n; i++) {
            uint64_t r = (m->key[i] << 32) | (m->key[i] >> 32);
            size_t p = lower_bound(m, r);
            tw[i] = p < n && m->key[p] == r ? m->half[p] : ACD_EDGE_NONE;
        }
        *twin = tw;
        return ACD_OK;
    }
    uint32_t maxid = keys_max_id(m);
    /* the reversed keys (b, a) in order, with their entries ri: the map is sorted by (a, b), so a
     * stable counting sort by b (one pass, a bucket per vertex: a transpose) sorts them, in the
     * order a stable sort of the reversed keys in entry order gives; with ids much sparser than
     * the entries, the radix sort does it */
    int transpose = (uint64_t)maxid < 2 * (uint64_t)n;
    uint64_t *rk = malloc((n ? n : 1) * sizeof *rk), *tk = transpose ? NULL : malloc((n ? n : 1) * sizeof *tk);
    uint32_t *ri = malloc((n ? n : 1) * sizeof *ri), *tv = transpose ? NULL : malloc((n ? n : 1) * sizeof *tv);
    uint32_t *tw = malloc((n ? n : 1) * sizeof *tw);
    size_t *pos = transpose ? calloc((size_t)maxid + 2, sizeof *pos) : NULL;
    int ok = rk && ri && tw && (transpose ? pos != NULL : tk && tv);
    if (ok && transpose) {
        for (size_t i = 0; i < n; i++) pos[(uint32_t)m->key[i] + 1]++;
        for (size_t v = 0; v <= maxid; v++) pos[v + 1] += pos[v];
        for (size_t i = 0; i < n; i++) {
            uint64_t k = m->key[i];
            size_t j = pos[(uint32_t)k]++;
            rk[j] = (k << 32) | (k >> 32);
            ri[j] = (uint32_t)i;
        }
    } else if (ok) {
        for (size_t i = 0; i < n; i++) {
            rk[i] = (m->key[i] << 32) | (m->key[i] >> 32);
            ri[i] = (uint32_t)i;
        }
        ok = radix_sort(rk, ri, tk, tv, n, maxid);
    }
    if (ok) { /* merge walk: the first index p with key[p] == rk[j] */
        size_t p = 0;
        for (size_t j = 0; j < n; j++) {
            while (p < n && m->key[p] < rk[j]) p++;
            tw[ri[j]] = p < n && m->key[p] == rk[j] ? m->half[p] : ACD_EDGE_NONE;
        }
    }
    free(rk);
    free(tk);
    free(ri);
    free(tv);
    free(pos);
    if (!ok) {
        free(tw);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for the twins of %zu half-edges", n);
    }
    *twin = tw;
    return ACD_OK;
}

void acd_edge_map_free(acd_edge_map *m) {
    if (!m) return;
    free(m->key);
    free(m->half);
    free(m->twin);
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

/* acd_edge_map_check_closed; when closed and tw_out is not NULL, *tw_out: the twins by entry. */
static acd_status check_closed(const acd_edge_map *m, const uint32_t *triangles, size_t ntriangles, uint32_t **tw_out,
                               acd_error *err) {
    for (size_t t = 0; t < ntriangles; t++) {
        const uint32_t *q = triangles + 3 * t;
        if (!acd_edge_map_triangle_proper(q))
            return acd_fail(err, ACD_ERR_NON_MANIFOLD, "triangle %zu (%u, %u, %u) repeats a vertex", t, q[0], q[1], q[2]);
    }
    uint32_t *tw = NULL;
    acd_status st = acd_edge_map_twins(m, &tw, err);
    if (st != ACD_OK) return st;
    for (size_t i = 0; i < m->n; i++) {
        if (acd_edge_map_entry_closed(m, tw, i)) continue;
        uint32_t a = (uint32_t)(m->key[i] >> 32), b = (uint32_t)m->key[i];
        size_t t = m->half[i] / 3;
        if (acd_edge_map_repeated(m, i))
            st = acd_fail(err, ACD_ERR_NON_MANIFOLD,
                          "edge (%u, %u) is used in the same direction by triangles %zu and %u (not a consistently "
                          "oriented manifold)",
                          a, b, t, m->half[i + 1] / 3);
        else
            st = acd_fail(err, ACD_ERR_NON_MANIFOLD, "edge (%u, %u) of triangle %zu has no opposite edge (mesh not closed)",
                          a, b, t);
        break;
    }
    if (st == ACD_OK && tw_out)
        *tw_out = tw;
    else
        free(tw);
    return st;
}

acd_status acd_edge_map_check_closed(const acd_edge_map *m, const uint32_t *triangles, size_t ntriangles,
                                     acd_error *err) {
    return check_closed(m, triangles, ntriangles, NULL, err);
}

acd_status acd_edge_map_closed(const uint32_t *triangles, size_t ntriangles, acd_edge_map *map, acd_error *err) {
    acd_edge_map m;
    acd_status st = acd_edge_map_build(triangles, ntriangles, NULL, &m, err);
    if (st != ACD_OK) return st;
    uint32_t *tw = NULL;
    st = check_closed(&m, triangles, ntriangles, map ? &tw : NULL, err);
    if (st == ACD_OK && map) {
        /* closed: every half-edge is in the map once, its twin by entry turned into one by half-edge */
        m.twin = malloc((m.n ? m.n : 1) * sizeof *m.twin);
        if (!m.twin) {
            free(tw);
            acd_edge_map_free(&m);
            return acd_fail(err, ACD_ERR_NOMEM, "out of memory for the twins of %zu half-edges", m.n);
        }
        for (size_t i = 0; i < m.n; i++) m.twin[m.half[i]] = tw[i];
        free(tw);
        *map = m;
    } else {
        acd_edge_map_free(&m);
    }
    return st;
}
