/* core/minheap: a growable binary min-heap of (key, id, tie) items ordered by key, then id, then tie,
 * so that equal keys pop in a fixed order (deterministic shortest paths and best-first searches).
 * Used by acd3/project (A*), acd3/pocket_cut (region Dijkstra), acd3/global_cut (cycle growth) and
 * acd3/patches (VSA flooding, by (error, facet, proxy)). */
#ifndef ACD_CORE_MINHEAP_H
#define ACD_CORE_MINHEAP_H

#include <stddef.h>
#include <stdint.h>

typedef struct acd_minheap_item {
    double key;
    uint32_t id;
    uint32_t tie; /* the last tie-break (0 from acd_minheap_push); it fills what would be padding */
} acd_minheap_item;

typedef struct acd_minheap {
    acd_minheap_item *a;
    size_t n, cap;
} acd_minheap;

/* Whether a precedes b: by key, then id, then tie. The keys' order is evaluated without a branch
 * (it is unpredictable in a heap); equal keys, which are rare, take a branch to the rest. */
static inline int acd_minheap_less(acd_minheap_item a, acd_minheap_item b) {
    int r = a.key < b.key;
    if (a.key == b.key) r = (a.id < b.id) | ((a.id == b.id) & (a.tie < b.tie));
    return r;
}

/* Adds x; returns 0 when out of memory (the heap is unchanged). */
int acd_minheap_push_item(acd_minheap *h, acd_minheap_item x);
/* Adds (key, id) (tie 0); the same. */
int acd_minheap_push(acd_minheap *h, double key, uint32_t id);
/* Removes and returns the smallest item; h->n must be > 0. */
acd_minheap_item acd_minheap_pop(acd_minheap *h);
/* Adds x and removes the smallest item (x itself when it precedes every queued one), returning
 * it: push then pop in one pass, without allocating. */
acd_minheap_item acd_minheap_pushpop(acd_minheap *h, acd_minheap_item x);
/* A search's item held outside the heap: *held, when *have, is the smallest item offered since the
 * search last took one (the next to take is the smaller of it and the top: acd_minheap_pushpop). x
 * offered: held if none is, else the larger of x and the held one pushed. 0 when out of memory. */
static inline int acd_minheap_offer(acd_minheap *h, acd_minheap_item *held, int *have, acd_minheap_item x) {
    if (!*have) {
        *held = x;
        *have = 1;
        return 1;
    }
    if (acd_minheap_less(x, *held)) {
        acd_minheap_item y = *held;
        *held = x;
        x = y;
    }
    return acd_minheap_push_item(h, x);
}
/* Frees the storage and zeroes h. */
void acd_minheap_free(acd_minheap *h);

#endif
