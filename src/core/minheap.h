/* core/minheap: a growable binary min-heap of (key, id) pairs ordered by key, then id, so that
 * equal keys pop in a fixed order (deterministic shortest paths and best-first searches). Used by
 * acd3/project (A*), acd3/pocket_cut (region Dijkstra) and acd3/global_cut (cycle growth). */
#ifndef ACD_CORE_MINHEAP_H
#define ACD_CORE_MINHEAP_H

#include <stddef.h>
#include <stdint.h>

typedef struct acd_minheap_item {
    double key;
    uint32_t id;
} acd_minheap_item;

typedef struct acd_minheap {
    acd_minheap_item *a;
    size_t n, cap;
} acd_minheap;

/* Adds (key, id); returns 0 when out of memory (the heap is unchanged). */
int acd_minheap_push(acd_minheap *h, double key, uint32_t id);
/* Removes and returns the smallest item; h->n must be > 0. */
acd_minheap_item acd_minheap_pop(acd_minheap *h);
/* Frees the storage and zeroes h. */
void acd_minheap_free(acd_minheap *h);

#endif
