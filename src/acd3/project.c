/* acd3/project: A* shortest paths with reusable work arrays; see project.h. */
#include "acd3/project.h"
#include "geom3/vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int acd3_pathfinder_init(acd3_pathfinder *pf, const acd_edge_graph *g, const double *coords) {
    memset(pf, 0, sizeof *pf);
    size_t n = g->nvertices ? g->nvertices : 1;
    pf->g = g;
    pf->coords = coords;
    pf->dist = malloc(n * sizeof *pf->dist);
    pf->pred = malloc(n * sizeof *pf->pred);
    pf->stamp = calloc(n, sizeof *pf->stamp);
    pf->closed = calloc(n, 1);
    if (!pf->dist || !pf->pred || !pf->stamp || !pf->closed) {
        acd3_pathfinder_free(pf);
        return 0;
    }
    return 1;
}

void acd3_pathfinder_free(acd3_pathfinder *pf) {
    free(pf->dist);
    free(pf->pred);
    free(pf->stamp);
    free(pf->closed);
    acd_minheap_free(&pf->heap);
    free(pf->path);
    memset(pf, 0, sizeof *pf);
}

int acd3_shortest_path(acd3_pathfinder *pf, uint32_t s, uint32_t t) {
    const acd_edge_graph *g = pf->g;
    if (++pf->cur == 0) { /* stamp wrapped: clear */
        memset(pf->stamp, 0, g->nvertices * sizeof *pf->stamp);
        pf->cur = 1;
    }
    uint32_t cur = pf->cur;
    const double *tp = pf->coords + 3 * (size_t)t;
    pf->heap.n = 0;
    pf->stamp[s] = cur;
    pf->dist[s] = 0;
    pf->pred[s] = UINT32_MAX;
    pf->closed[s] = 0;
    if (!acd_minheap_push(&pf->heap, acd_dist3(pf->coords + 3 * (size_t)s, tp), s)) return -1;
    int found = 0;
    /* the least item the last expansion added waits outside the heap (have_next): the next
     * vertex taken is it or the heap's top, whichever precedes (acd_minheap_pushpop), so along
     * the way to t, where the estimate barely grows, most steps skip the heap; the heap gives
     * up the same items in the same order as with every item pushed */
    acd_minheap_item next = {0, 0, 0};
    int have_next = 0;
    for (;;) {
        uint32_t v;
        if (have_next) {
            v = acd_minheap_pushpop(&pf->heap, next).id;
            have_next = 0;
        } else if (pf->heap.n) {
            v = acd_minheap_pop(&pf->heap).id;
        } else {
            break;
        }
        if (pf->closed[v]) continue;
        pf->closed[v] = 1;
        if (v == t) {
            found = 1;
            break;
        }
        for (size_t k = g->row[v]; k < g->row[v + 1]; k++) {
            uint32_t u = g->adj[k];
            double d = pf->dist[v] + g->length[g->adj_edge[k]];
            if (pf->stamp[u] != cur) {
                pf->stamp[u] = cur;
                pf->closed[u] = 0;
                pf->dist[u] = INFINITY;
            }
            if (pf->closed[u]) continue;
            if (d < pf->dist[u] || (d == pf->dist[u] && v < pf->pred[u])) {
                pf->dist[u] = d;
                pf->pred[u] = v;
                acd_minheap_item x = {d + acd_dist3(pf->coords + 3 * (size_t)u, tp), u, 0};
                if (!acd_minheap_offer(&pf->heap, &next, &have_next, x)) return -1;
            }
        }
    }
    if (!found) return 0;
    size_t len = 0;
    for (uint32_t v = t; v != UINT32_MAX; v = pf->pred[v]) len++;
    if (len > pf->path_cap) {
        uint32_t *np = realloc(pf->path, len * sizeof *np);
        if (!np) return -1;
        pf->path = np;
        pf->path_cap = len;
    }
    size_t i = len;
    for (uint32_t v = t; v != UINT32_MAX; v = pf->pred[v]) pf->path[--i] = v;
    pf->path_len = len;
    return 1;
}
