/* Reference maximum flow for the max-flow tests: Dinic's blocking-flow algorithm on an explicit
 * graph with the two terminals as ordinary vertices (s = n, t = n + 1). Deliberately plain and
 * independent of src/corise/maxflow.c; header-only so each test program includes it once.
 * A test graph is given as a list of n-links and per-node t-links, which the tests feed to both
 * solvers. */
#ifndef ACD_TEST_MAXFLOW_REF_H
#define ACD_TEST_MAXFLOW_REF_H

#include <stdlib.h>
#include <string.h>

typedef struct ref_edge {
    size_t i, j;
    double cap, rev;
} ref_edge;

typedef struct ref_graph {
    size_t n;
    double *cs, *ct; /* t-links: source->i, i->sink (accumulated) */
    ref_edge *e;
    size_t ne, cap_e;
} ref_graph;

static void ref_init(ref_graph *g, size_t n) {
    memset(g, 0, sizeof *g);
    g->n = n;
    g->cs = calloc(n + 1, sizeof *g->cs);
    g->ct = calloc(n + 1, sizeof *g->ct);
}

static void ref_free(ref_graph *g) {
    free(g->cs);
    free(g->ct);
    free(g->e);
}

static void ref_add_edge(ref_graph *g, size_t i, size_t j, double cap, double rev) {
    if (g->ne == g->cap_e) {
        g->cap_e = g->cap_e ? 2 * g->cap_e : 64;
        g->e = realloc(g->e, g->cap_e * sizeof *g->e);
    }
    g->e[g->ne++] = (ref_edge){i, j, cap, rev};
}

/* Dinic on the arc list; fills src_side[0..n-1] with residual reachability from s.
 * Returns the flow value. */
typedef struct dinic_arc {
    size_t to, next;
    double r;
} dinic_arc;

typedef struct dinic {
    size_t nv;
    dinic_arc *a;
    size_t na;
    size_t *head, *it, *level, *queue;
} dinic;

static void dinic_arc_pair(dinic *d, size_t u, size_t v, double c, double rc) {
    d->a[d->na] = (dinic_arc){v, d->head[u], c};
    d->head[u] = d->na++;
    d->a[d->na] = (dinic_arc){u, d->head[v], rc};
    d->head[v] = d->na++;
}

static int dinic_bfs(dinic *d, size_t s, size_t t) {
    for (size_t v = 0; v < d->nv; v++) d->level[v] = (size_t)-1;
    size_t qh = 0, qt = 0;
    d->level[s] = 0;
    d->queue[qt++] = s;
    while (qh < qt) {
        size_t u = d->queue[qh++];
        for (size_t k = d->head[u]; k != (size_t)-1; k = d->a[k].next)
            if (d->a[k].r > 0 && d->level[d->a[k].to] == (size_t)-1) {
                d->level[d->a[k].to] = d->level[u] + 1;
                d->queue[qt++] = d->a[k].to;
            }
    }
    return d->level[t] != (size_t)-1;
}

/* Iterative blocking-flow DFS: repeatedly finds one s-t path in the level graph. */
static double dinic_path(dinic *d, size_t s, size_t t) {
    double total = 0;
    size_t *stack = malloc(d->nv * sizeof *stack); /* arcs on the current path */
    for (;;) {
        size_t depth = 0, u = s;
        int found = 0;
        for (;;) {
            if (u == t) {
                found = 1;
                break;
            }
            size_t k;
            for (k = d->it[u]; k != (size_t)-1; k = d->a[k].next)
                if (d->a[k].r > 0 && d->level[d->a[k].to] == d->level[u] + 1) break;
            d->it[u] = k;
            if (k == (size_t)-1) {
                if (depth == 0) break;
                d->level[u] = (size_t)-1; /* dead end */
                depth--;
                u = d->a[stack[depth] ^ 1u].to;
                d->it[u] = d->a[d->it[u]].next;
                continue;
            }
            stack[depth++] = k;
            u = d->a[k].to;
        }
        if (!found) break;
        double b = d->a[stack[0]].r;
        for (size_t q = 1; q < depth; q++)
            if (d->a[stack[q]].r < b) b = d->a[stack[q]].r;
        for (size_t q = 0; q < depth; q++) {
            d->a[stack[q]].r -= b;
            d->a[stack[q] ^ 1u].r += b;
        }
        total += b;
    }
    free(stack);
    return total;
}

static double ref_maxflow(const ref_graph *g, unsigned char *src_side) {
    dinic d;
    size_t s = g->n, t = g->n + 1;
    d.nv = g->n + 2;
    d.a = malloc((2 * g->ne + 4 * g->n + 2) * sizeof *d.a);
    d.na = 0;
    d.head = malloc(d.nv * sizeof(size_t));
    d.it = malloc(d.nv * sizeof(size_t));
    d.level = malloc(d.nv * sizeof(size_t));
    d.queue = malloc(d.nv * sizeof(size_t));
    for (size_t v = 0; v < d.nv; v++) d.head[v] = (size_t)-1;
    for (size_t i = 0; i < g->n; i++) {
        if (g->cs[i] > 0) dinic_arc_pair(&d, s, i, g->cs[i], 0);
        if (g->ct[i] > 0) dinic_arc_pair(&d, i, t, g->ct[i], 0);
    }
    for (size_t k = 0; k < g->ne; k++) dinic_arc_pair(&d, g->e[k].i, g->e[k].j, g->e[k].cap, g->e[k].rev);
    double flow = 0;
    while (dinic_bfs(&d, s, t)) {
        memcpy(d.it, d.head, d.nv * sizeof(size_t));
        flow += dinic_path(&d, s, t);
    }
    dinic_bfs(&d, s, t);
    for (size_t i = 0; i < g->n; i++) src_side[i] = d.level[i] != (size_t)-1;
    free(d.a);
    free(d.head);
    free(d.it);
    free(d.level);
    free(d.queue);
    return flow;
}

/* Capacity of the cut (S = nodes with side[i] = 1 plus the source). */
static double ref_cut_capacity(const ref_graph *g, const unsigned char *side) {
    double c = 0;
    for (size_t i = 0; i < g->n; i++) c += side[i] ? g->ct[i] : g->cs[i];
    for (size_t k = 0; k < g->ne; k++) {
        const ref_edge *e = &g->e[k];
        if (side[e->i] && !side[e->j]) c += e->cap;
        if (side[e->j] && !side[e->i]) c += e->rev;
    }
    return c;
}

#endif
