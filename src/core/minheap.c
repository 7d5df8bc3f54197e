/* core/minheap: binary min-heap of (key, id); see minheap.h. */
#include "core/minheap.h"

#include <stdlib.h>
#include <string.h>

static int item_less(acd_minheap_item a, acd_minheap_item b) { return a.key < b.key || (a.key == b.key && a.id < b.id); }

int acd_minheap_push(acd_minheap *h, double key, uint32_t id) {
    if (h->n == h->cap) {
        size_t nc = h->cap ? 2 * h->cap : 256;
        acd_minheap_item *na = realloc(h->a, nc * sizeof *na);
        if (!na) return 0;
        h->a = na;
        h->cap = nc;
    }
    acd_minheap_item x = {key, id};
    size_t i = h->n++;
    while (i) {
        size_t p = (i - 1) / 2;
        if (!item_less(x, h->a[p])) break;
        h->a[i] = h->a[p];
        i = p;
    }
    h->a[i] = x;
    return 1;
}

acd_minheap_item acd_minheap_pop(acd_minheap *h) {
    acd_minheap_item top = h->a[0], x = h->a[--h->n];
    size_t i = 0;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= h->n) break;
        if (c + 1 < h->n && item_less(h->a[c + 1], h->a[c])) c++;
        if (!item_less(h->a[c], x)) break;
        h->a[i] = h->a[c];
        i = c;
    }
    if (h->n) h->a[i] = x;
    return top;
}

void acd_minheap_free(acd_minheap *h) {
    free(h->a);
    memset(h, 0, sizeof *h);
}
