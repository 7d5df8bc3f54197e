/* core/minheap: binary min-heap of (key, id, tie); see minheap.h. */
#include "core/minheap.h"

#include <stdlib.h>
#include <string.h>

int acd_minheap_push(acd_minheap *h, double key, uint32_t id) {
    return acd_minheap_push_item(h, (acd_minheap_item){key, id, 0});
}

int acd_minheap_push_item(acd_minheap *h, acd_minheap_item x) {
    if (h->n == h->cap) {
        size_t nc = h->cap ? 2 * h->cap : 256;
        acd_minheap_item *na = realloc(h->a, nc * sizeof *na);
        if (!na) return 0;
        h->a = na;
        h->cap = nc;
    }
    size_t i = h->n++;
    while (i) {
        size_t p = (i - 1) / 2;
        if (!acd_minheap_less(x, h->a[p])) break;
        h->a[i] = h->a[p];
        i = p;
    }
    h->a[i] = x;
    return 1;
}

/* Bottom-up deletion (Wegener): the hole left by the top walks down to a leaf along the smaller
 * children (one comparison per level, without branches: its outcome is unpredictable), then x
 * (the last item) sifts up from there (it usually belongs near the bottom). a[0..n) holds the
 * heap, the top's slot included. The items are distinct under acd_minheap_less's total order up to
 * exact copies, so any layout that keeps the heap property gives up the same items in the same
 * order: the pops are the same as with the classic sift-down. */
static void fill_top(acd_minheap_item *a, size_t n, acd_minheap_item x) {
    size_t i = 0;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c + 1 >= n) {
            if (c < n) {
                a[i] = a[c];
                i = c;
            }
            break;
        }
        c += (size_t)acd_minheap_less(a[c + 1], a[c]);
        a[i] = a[c];
        i = c;
    }
    while (i) {
        size_t p = (i - 1) / 2;
        if (!acd_minheap_less(x, a[p])) break;
        a[i] = a[p];
        i = p;
    }
    a[i] = x;
}

acd_minheap_item acd_minheap_pop(acd_minheap *h) {
    acd_minheap_item top = h->a[0], x = h->a[--h->n];
    if (h->n) fill_top(h->a, h->n, x);
    return top;
}

acd_minheap_item acd_minheap_pushpop(acd_minheap *h, acd_minheap_item x) {
    if (h->n == 0 || acd_minheap_less(x, h->a[0])) return x;
    acd_minheap_item *a = h->a, top = a[0];
    size_t n = h->n, i = 0;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= n) break;
        if (c + 1 < n) c += (size_t)acd_minheap_less(a[c + 1], a[c]);
        if (!acd_minheap_less(a[c], x)) break;
        a[i] = a[c];
        i = c;
    }
    a[i] = x;
    return top;
}

void acd_minheap_free(acd_minheap *h) {
    free(h->a);
    memset(h, 0, sizeof *h);
}
