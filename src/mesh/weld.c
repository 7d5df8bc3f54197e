/* mesh/weld: vertex welding by hashing coordinates.
 *
 * Exact: an open-addressing hash table keyed on the coordinates' bit patterns (-0 mapped to +0).
 * Tolerance: points are hashed into a grid of cell size tol; each point is compared with the
 * points already seen in the 27 surrounding cells and joined (union-find) with those within tol
 * in every coordinate; a cluster takes the index and position of its first point. Both are
 * deterministic: indices follow first occurrence, independent of addresses or threads. */
#include "mesh/weld.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "core/union_find.h"

static uint64_t bits_of(double d) {
    if (d == 0) d = 0; /* -0 -> +0 */
    uint64_t u;
    memcpy(&u, &d, sizeof u);
    return u;
}

static uint64_t mix64(uint64_t h) {
    h ^= h >> 33;
    h *= UINT64_C(0xff51afd7ed558ccd);
    h ^= h >> 33;
    h *= UINT64_C(0xc4ceb9fe1a85ec53);
    h ^= h >> 33;
    return h;
}

static uint64_t hash3(uint64_t a, uint64_t b, uint64_t c) {
    return mix64(a * UINT64_C(0x9e3779b97f4a7c15) ^ mix64(b + UINT64_C(0x632be59bd9b4e019)) ^
                 (c * UINT64_C(0xbf58476d1ce4e5b9) + (c >> 29)));
}

static size_t table_size(size_t n) {
    size_t s = 64;
    while (s < 2 * n) s *= 2;
    return s;
}

int acd_weld_exact(const double *v, size_t n, uint32_t *remap, size_t *nunique) {
    size_t cap = table_size(n), mask = cap - 1;
    uint32_t *table = malloc(cap * sizeof *table); /* point index + 1, 0 = empty */
    if (!table) return 0;
    memset(table, 0, cap * sizeof *table);
    size_t u = 0;
    for (size_t i = 0; i < n; i++) {
        const double *p = v + 3 * i;
        uint64_t bx = bits_of(p[0]), by = bits_of(p[1]), bz = bits_of(p[2]);
        size_t h = (size_t)hash3(bx, by, bz) & mask;
        for (;;) {
            uint32_t e = table[h];
            if (!e) {
                table[h] = (uint32_t)(i + 1);
                remap[i] = (uint32_t)u++;
                break;
            }
            const double *q = v + 3 * (e - 1);
            if (bits_of(q[0]) == bx && bits_of(q[1]) == by && bits_of(q[2]) == bz) {
                remap[i] = remap[e - 1];
                break;
            }
            h = (h + 1) & mask;
        }
    }
    free(table);
    *nunique = u;
    return 1;
}

int acd_weld_tolerance(const double *v, size_t n, double tol, uint32_t *remap, size_t *nunique) {
    if (!(tol > 0) || !isfinite(tol)) return acd_weld_exact(v, n, remap, nunique);
    size_t cap = table_size(n), mask = cap - 1;
    /* grid cell -> chain of points in that cell (head[slot], next[point]); slots keyed on cell */
    int64_t *keys = malloc(cap * 3 * sizeof *keys);
    uint32_t *head = malloc(cap * sizeof *head);
    uint32_t *next = malloc((n ? n : 1) * sizeof *next);
    uint32_t *parent = malloc((n ? n : 1) * sizeof *parent);
    if (!keys || !head || !next || !parent) {
        free(keys);
        free(head);
        free(next);
        free(parent);
        return 0;
    }
    for (size_t i = 0; i < cap; i++) head[i] = UINT32_MAX;
    for (size_t i = 0; i < n; i++) parent[i] = (uint32_t)i;
    for (size_t i = 0; i < n; i++) {
        const double *p = v + 3 * i;
        int64_t c[3];
        for (int k = 0; k < 3; k++) {
            double f = floor(p[k] / tol);
            /* coordinates far beyond 2^62 cells all share one clamped cell: still correct, only slower */
            c[k] = f > 4e18 ? (int64_t)4e18 : f < -4e18 ? (int64_t)-4e18 : (int64_t)f;
        }
        for (int dx = -1; dx <= 1; dx++)
            for (int dy = -1; dy <= 1; dy++)
                for (int dz = -1; dz <= 1; dz++) {
                    int64_t q[3] = {c[0] + dx, c[1] + dy, c[2] + dz};
                    size_t h = (size_t)hash3((uint64_t)q[0], (uint64_t)q[1], (uint64_t)q[2]) & mask;
                    while (head[h] != UINT32_MAX) {
                        if (keys[3 * h] == q[0] && keys[3 * h + 1] == q[1] && keys[3 * h + 2] == q[2]) break;
                        h = (h + 1) & mask;
                    }
                    for (uint32_t j = head[h]; j != UINT32_MAX; j = next[j]) {
                        const double *r = v + 3 * j;
                        if (fabs(r[0] - p[0]) <= tol && fabs(r[1] - p[1]) <= tol && fabs(r[2] - p[2]) <= tol) {
                            uint32_t a = acd_uf_find(parent, (uint32_t)i), b = acd_uf_find(parent, j);
                            if (a != b) {
                                if (a < b) parent[b] = a;
                                else parent[a] = b;
                            }
                        }
                    }
                }
        size_t h = (size_t)hash3((uint64_t)c[0], (uint64_t)c[1], (uint64_t)c[2]) & mask;
        while (head[h] != UINT32_MAX) {
            if (keys[3 * h] == c[0] && keys[3 * h + 1] == c[1] && keys[3 * h + 2] == c[2]) break;
            h = (h + 1) & mask;
        }
        if (head[h] == UINT32_MAX) {
            keys[3 * h] = c[0];
            keys[3 * h + 1] = c[1];
            keys[3 * h + 2] = c[2];
        }
        next[i] = head[h];
        head[h] = (uint32_t)i;
    }
    /* number clusters by their smallest member (the root, since roots are minimal) */
    size_t u = 0;
    for (size_t i = 0; i < n; i++) {
        uint32_t r = acd_uf_find(parent, (uint32_t)i);
        remap[i] = r == i ? (uint32_t)u++ : remap[r];
    }
    free(keys);
    free(head);
    free(next);
    free(parent);
    *nunique = u;
    return 1;
}

void acd_weld_compact(double *v, size_t n, const uint32_t *remap) {
    size_t u = 0;
    for (size_t i = 0; i < n; i++)
        if (remap[i] == u) { /* first occurrence (remap[i] <= i, increasing for firsts) */
            if (u != i) memcpy(v + 3 * u, v + 3 * i, 3 * sizeof(double));
            u++;
        }
}
