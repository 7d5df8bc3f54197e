/* core/union_find: disjoint sets over indices with path halving. The smaller root always becomes
 * the parent, so a set's representative is its smallest member and results never depend on the
 * order of the unions. One version for uint32_t indices, one for size_t. */
#ifndef ACD_CORE_UNION_FIND_H
#define ACD_CORE_UNION_FIND_H

#include <stddef.h>
#include <stdint.h>

static inline uint32_t acd_uf_find(uint32_t *parent, uint32_t x) {
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

static inline void acd_uf_union(uint32_t *parent, uint32_t a, uint32_t b) {
    a = acd_uf_find(parent, a);
    b = acd_uf_find(parent, b);
    if (a < b) parent[b] = a;
    else if (b < a) parent[a] = b;
}

static inline size_t acd_uf_find_z(size_t *parent, size_t x) {
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

static inline void acd_uf_union_z(size_t *parent, size_t a, size_t b) {
    a = acd_uf_find_z(parent, a);
    b = acd_uf_find_z(parent, b);
    if (a < b) parent[b] = a;
    else if (b < a) parent[a] = b;
}

#endif
