/* geom3/dijkstra: edge graph and shortest paths (Dijkstra 1959) with an indexed binary heap.
 * Used by ACD to project hull edges on the surface (Lien D §V.B.1, P §4.1, Fig 37) and for handle
 * cuts (D §V.C); ties broken by vertex id so results never depend on memory layout. */
#include "geom3/dijkstra.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

void acd_edge_graph_free(acd_edge_graph *g) {
    if (!g) return;
    free(g->edge_v);
    free(g->length);
    free(g->row);
    free(g->adj);
    free(g->adj_edge);
    memset(g, 0, sizeof *g);
}

typedef struct edge_rec {
    uint32_t a, b;
    double w;
} edge_rec;

/* Sorts the records by (a, b) with two stable counting sorts (by b, then by a; both < nv).
 * Returns 0 when out of memory. */
static int sort_edges(size_t nv, edge_rec *rec, size_t nrec) {
    size_t *cnt = malloc((nv + 1) * sizeof *cnt);
    edge_rec *tmp = malloc((nrec ? nrec : 1) * sizeof *tmp);
    if (!cnt || !tmp) {
        free(cnt);
        free(tmp);
        return 0;
    }
    for (int pass = 0; pass < 2; pass++) {
        memset(cnt, 0, (nv + 1) * sizeof *cnt);
        for (size_t i = 0; i < nrec; i++) cnt[(pass ? rec[i].a : rec[i].b) + 1]++;
        for (size_t v = 0; v < nv; v++) cnt[v + 1] += cnt[v];
        for (size_t i = 0; i < nrec; i++) tmp[cnt[pass ? rec[i].a : rec[i].b]++] = rec[i];
        memcpy(rec, tmp, nrec * sizeof *rec);
    }
    free(cnt);
    free(tmp);
    return 1;
}

/* Builds the graph from distinct edge records in increasing (a, b) order. */
static acd_status build_sorted(size_t nv, const edge_rec *rec, size_t ne, acd_edge_graph *g, acd_error *err) {
    g->nvertices = nv;
    g->nedges = ne;
    g->edge_v = malloc((ne ? ne : 1) * 2 * sizeof *g->edge_v);
    g->length = malloc((ne ? ne : 1) * sizeof *g->length);
    g->row = calloc(nv + 1, sizeof *g->row);
    g->adj = malloc((ne ? ne : 1) * 2 * sizeof *g->adj);
    g->adj_edge = malloc((ne ? ne : 1) * 2 * sizeof *g->adj_edge);
    size_t *fill = calloc(nv + 1, sizeof *fill);
    if (!g->edge_v || !g->length || !g->row || !g->adj || !g->adj_edge || !fill) {
        free(fill);
        acd_edge_graph_free(g);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for an edge graph of %zu vertices, %zu edges", nv, ne);
    }
    for (size_t e = 0; e < ne; e++) {
        g->edge_v[2 * e] = rec[e].a;
        g->edge_v[2 * e + 1] = rec[e].b;
        g->length[e] = rec[e].w;
        g->row[rec[e].a + 1]++;
        g->row[rec[e].b + 1]++;
    }
    for (size_t v = 0; v < nv; v++) g->row[v + 1] += g->row[v];
    /* rows in increasing neighbour id: lower neighbours come from edges (x, v) sorted by x, then
     * upper neighbours from edges (v, y) sorted by y; two passes keep that order */
    for (size_t e = 0; e < ne; e++) { /* v as upper end: neighbour a < v, edges sorted by a */
        uint32_t a = rec[e].a, b = rec[e].b;
        size_t k = g->row[b] + fill[b]++;
        g->adj[k] = a;
        g->adj_edge[k] = (uint32_t)e;
    }
    for (size_t e = 0; e < ne; e++) { /* v as lower end: neighbour b > v */
        uint32_t a = rec[e].a, b = rec[e].b;
        size_t k = g->row[a] + fill[a]++;
        g->adj[k] = b;
        g->adj_edge[k] = (uint32_t)e;
    }
    free(fill);
    return ACD_OK;
}

/* Builds the graph from edge records (sorted and merged here, a repeated edge keeping its
 * smallest length; rec is consumed). */
static acd_status build_graph(size_t nv, edge_rec *rec, size_t nrec, acd_edge_graph *g, acd_error *err) {
    if (!sort_edges(nv, rec, nrec))
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory sorting %zu edges", nrec);
    size_t ne = 0;
    for (size_t i = 0; i < nrec; i++)
        if (ne == 0 || rec[i].a != rec[ne - 1].a || rec[i].b != rec[ne - 1].b)
            rec[ne++] = rec[i];
        else if (rec[i].w < rec[ne - 1].w)
            rec[ne - 1].w = rec[i].w;
    return build_sorted(nv, rec, ne, g, err);
}

acd_status acd_edge_graph_from_mesh(const double *vertices, size_t nvertices, const uint32_t *triangles,
                                    size_t ntriangles, acd_edge_graph *g, acd_error *err) {
    memset(g, 0, sizeof *g);
    if (nvertices >= UINT32_MAX || ntriangles > SIZE_MAX / 3)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "edge graph: %zu vertices / %zu triangles too many", nvertices,
                        ntriangles);
    for (size_t t = 0; t < ntriangles; t++)
        for (int k = 0; k < 3; k++)
            if (triangles[3 * t + k] >= nvertices)
                return acd_fail(err, ACD_ERR_INVALID_INPUT, "edge graph: triangle %zu has vertex index %u >= %zu", t,
                                triangles[3 * t + k], nvertices);
    /* The triangles' sides (a, b), a < b, bucketed by a (a counting pass, then the upper ends
     * scattered), each bucket sorted by b and its repeats dropped: the edges in increasing (a, b)
     * order, as build_graph's sort and merge give them. A repeated side has the same length (the
     * same expression of the same two points), so the length is computed once per edge. */
    size_t nh = 3 * ntriangles;
    size_t *start = calloc(nvertices + 2, sizeof *start);
    uint32_t *up = malloc((nh ? nh : 1) * sizeof *up);
    edge_rec *rec = malloc((nh ? nh : 1) * sizeof *rec);
    if (!start || !up || !rec) {
        free(start), free(up), free(rec);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for the edges of %zu triangles", ntriangles);
    }
    for (size_t t = 0; t < ntriangles; t++) {
        const uint32_t *c = triangles + 3 * t;
        uint32_t x = c[0], y = c[1], z = c[2];
        start[(x < y ? x : y) + 2] += x != y;
        start[(y < z ? y : z) + 2] += y != z;
        start[(z < x ? z : x) + 2] += z != x;
    }
    for (size_t v = 0; v < nvertices; v++) start[v + 2] += start[v + 1];
    for (size_t i = 0; i < nh; i++) { /* start[a + 1]: the next free slot of bucket a */
        uint32_t a = triangles[i], b = triangles[i % 3 == 2 ? i - 2 : i + 1];
        if (a == b) continue;
        uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
        up[start[lo + 1]++] = hi;
    }
    size_t ne = 0;
    for (size_t a = 0; a < nvertices; a++) {
        uint32_t *u = up + start[a];
        size_t n = start[a + 1] - start[a];
        for (size_t i = 1; i < n; i++) { /* insertion sort: a bucket holds a few sides */
            uint32_t x = u[i];
            size_t j = i;
            while (j > 0 && u[j - 1] > x) {
                u[j] = u[j - 1];
                j--;
            }
            u[j] = x;
        }
        for (size_t i = 0; i < n; i++) {
            if (i > 0 && u[i] == u[i - 1]) continue;
            uint32_t b = u[i];
            const double *p = vertices + 3 * a, *q = vertices + 3 * (size_t)b;
            double d[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
            rec[ne].a = (uint32_t)a;
            rec[ne].b = b;
            rec[ne].w = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            ne++;
        }
    }
    free(start);
    free(up);
    acd_status st = build_sorted(nvertices, rec, ne, g, err);
    free(rec);
    return st;
}

acd_status acd_edge_graph_from_edges(size_t nvertices, const uint32_t *edges, const double *weights, size_t nedges,
                                     acd_edge_graph *g, acd_error *err) {
    memset(g, 0, sizeof *g);
    if (nvertices >= UINT32_MAX)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "edge graph: %zu vertices too many", nvertices);
    edge_rec *rec = malloc((nedges ? nedges : 1) * sizeof *rec);
    if (!rec) return acd_fail(err, ACD_ERR_NOMEM, "out of memory for %zu edges", nedges);
    size_t nrec = 0;
    for (size_t e = 0; e < nedges; e++) {
        uint32_t a = edges[2 * e], b = edges[2 * e + 1];
        double w = weights ? weights[e] : 1.0;
        if (a >= nvertices || b >= nvertices || !(w >= 0) || !isfinite(w)) {
            free(rec);
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "edge graph: edge %zu (%u, %u) weight %g is invalid (%zu vertices)",
                            e, a, b, w, nvertices);
        }
        if (a == b) continue;
        rec[nrec].a = a < b ? a : b;
        rec[nrec].b = a < b ? b : a;
        rec[nrec].w = w;
        nrec++;
    }
    acd_status st = build_graph(nvertices, rec, nrec, g, err);
    free(rec);
    return st;
}

void acd_sp_tree_free(acd_sp_tree *t) {
    if (!t) return;
    free(t->dist);
    free(t->pred);
    free(t->pred_edge);
    free(t->origin);
    memset(t, 0, sizeof *t);
}

/* Indexed binary min-heap on (dist, vertex). */
typedef struct heap {
    uint32_t *a;   /* heap of vertices */
    uint32_t *pos; /* position of a vertex in a, ACD_NO_VERTEX when absent */
    size_t n;
    const double *key;
} heap;

static int heap_less(const heap *h, uint32_t u, uint32_t v) {
    if (h->key[u] != h->key[v]) return h->key[u] < h->key[v];
    return u < v;
}

static void heap_up(heap *h, size_t i) {
    uint32_t v = h->a[i];
    while (i > 0) {
        size_t p = (i - 1) / 2;
        if (!heap_less(h, v, h->a[p])) break;
        h->a[i] = h->a[p];
        h->pos[h->a[i]] = (uint32_t)i;
        i = p;
    }
    h->a[i] = v;
    h->pos[v] = (uint32_t)i;
}

static void heap_down(heap *h, size_t i) {
    uint32_t v = h->a[i];
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= h->n) break;
        if (c + 1 < h->n && heap_less(h, h->a[c + 1], h->a[c])) c++;
        if (!heap_less(h, h->a[c], v)) break;
        h->a[i] = h->a[c];
        h->pos[h->a[i]] = (uint32_t)i;
        i = c;
    }
    h->a[i] = v;
    h->pos[v] = (uint32_t)i;
}

static void heap_push_or_decrease(heap *h, uint32_t v) {
    if (h->pos[v] == ACD_NO_VERTEX) {
        h->a[h->n] = v;
        h->pos[v] = (uint32_t)h->n;
        h->n++;
    }
    heap_up(h, h->pos[v]);
}

static uint32_t heap_pop(heap *h) {
    uint32_t v = h->a[0];
    h->pos[v] = ACD_NO_VERTEX;
    h->n--;
    if (h->n > 0) {
        h->a[0] = h->a[h->n];
        h->pos[h->a[0]] = 0;
        heap_down(h, 0);
    }
    return v;
}

acd_status acd_dijkstra(const acd_edge_graph *g, const uint32_t *sources, size_t nsources,
                        const acd_dijkstra_opts *opts, acd_sp_tree *tree, acd_error *err) {
    memset(tree, 0, sizeof *tree);
    acd_dijkstra_opts o;
    memset(&o, 0, sizeof o);
    o.target = ACD_NO_VERTEX;
    if (opts) o = *opts;
    size_t n = g->nvertices;
    const double *w = o.weights ? o.weights : g->length;
    if (o.weights)
        for (size_t e = 0; e < g->nedges; e++)
            if (!(w[e] >= 0) || !isfinite(w[e]))
                return acd_fail(err, ACD_ERR_INVALID_INPUT, "dijkstra: edge %zu (%u, %u) has weight %g (must be finite, >= 0)",
                                e, g->edge_v[2 * e], g->edge_v[2 * e + 1], w[e]);
    tree->nvertices = n;
    tree->dist = malloc((n ? n : 1) * sizeof *tree->dist);
    tree->pred = malloc((n ? n : 1) * sizeof *tree->pred);
    tree->pred_edge = malloc((n ? n : 1) * sizeof *tree->pred_edge);
    tree->origin = malloc((n ? n : 1) * sizeof *tree->origin);
    heap h = {malloc((n ? n : 1) * sizeof(uint32_t)), malloc((n ? n : 1) * sizeof(uint32_t)), 0, tree->dist};
    uint8_t *done = calloc(n ? n : 1, 1);
    if (!tree->dist || !tree->pred || !tree->pred_edge || !tree->origin || !h.a || !h.pos || !done) {
        free(h.a);
        free(h.pos);
        free(done);
        acd_sp_tree_free(tree);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory for a shortest-path search on %zu vertices", n);
    }
    for (size_t v = 0; v < n; v++) {
        tree->dist[v] = INFINITY;
        tree->pred[v] = tree->pred_edge[v] = tree->origin[v] = ACD_NO_VERTEX;
        h.pos[v] = ACD_NO_VERTEX;
    }
    for (size_t s = 0; s < nsources; s++) {
        uint32_t v = sources[s];
        if (v >= n) {
            free(h.a);
            free(h.pos);
            free(done);
            acd_sp_tree_free(tree);
            return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "dijkstra: source %zu is vertex %u, graph has %zu vertices", s,
                            v, n);
        }
        if (o.vertex_allowed && !o.vertex_allowed[v]) continue;
        if (tree->dist[v] == 0) continue; /* repeated source keeps the first index */
        tree->dist[v] = 0;
        tree->origin[v] = (uint32_t)s;
        heap_push_or_decrease(&h, v);
    }
    while (h.n > 0) {
        uint32_t u = heap_pop(&h);
        if (o.max_distance > 0 && tree->dist[u] > o.max_distance) {
            tree->dist[u] = INFINITY; /* beyond the limit: reported unreached */
            tree->pred[u] = tree->pred_edge[u] = tree->origin[u] = ACD_NO_VERTEX;
            continue;
        }
        done[u] = 1;
        if (u == o.target) break;
        for (size_t k = g->row[u]; k < g->row[u + 1]; k++) {
            uint32_t v = g->adj[k], e = g->adj_edge[k];
            if (done[v]) continue;
            if (o.edge_blocked && o.edge_blocked[e]) continue;
            if (o.vertex_allowed && !o.vertex_allowed[v]) continue;
            double nd = tree->dist[u] + w[e];
            if (nd < tree->dist[v]) {
                tree->dist[v] = nd;
                tree->pred[v] = u;
                tree->pred_edge[v] = e;
                tree->origin[v] = tree->origin[u];
                heap_push_or_decrease(&h, v);
            } else if (nd == tree->dist[v] && u < tree->pred[v]) { /* tie: smaller predecessor id */
                tree->pred[v] = u;
                tree->pred_edge[v] = e;
                tree->origin[v] = tree->origin[u];
            }
        }
    }
    /* vertices left in the heap when stopping early keep tentative distances: report them unreached */
    for (size_t i = 0; i < h.n; i++) {
        uint32_t v = h.a[i];
        tree->dist[v] = INFINITY;
        tree->pred[v] = tree->pred_edge[v] = tree->origin[v] = ACD_NO_VERTEX;
    }
    free(h.a);
    free(h.pos);
    free(done);
    return ACD_OK;
}

acd_status acd_sp_path(const acd_sp_tree *t, uint32_t target, uint32_t **path, size_t *len, acd_error *err) {
    *path = NULL;
    *len = 0;
    if (target >= t->nvertices)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "shortest path: target %u out of %zu vertices", target,
                        t->nvertices);
    if (!isfinite(t->dist[target]))
        return acd_fail(err, ACD_ERR_DEGENERATE, "shortest path: vertex %u is not reachable from the sources", target);
    size_t n = 1;
    for (uint32_t v = target; t->pred[v] != ACD_NO_VERTEX; v = t->pred[v]) {
        n++;
        if (n > t->nvertices)
            return acd_fail(err, ACD_ERR_INTERNAL, "shortest path: predecessor cycle through vertex %u", v);
    }
    uint32_t *p = malloc(n * sizeof *p);
    if (!p) return acd_fail(err, ACD_ERR_NOMEM, "out of memory for a path of %zu vertices", n);
    size_t k = n;
    for (uint32_t v = target;; v = t->pred[v]) {
        p[--k] = v;
        if (t->pred[v] == ACD_NO_VERTEX) break;
    }
    *path = p;
    *len = n;
    return ACD_OK;
}

acd_status acd_shortest_path(const acd_edge_graph *g, uint32_t s, uint32_t t, const acd_dijkstra_opts *opts,
                             uint32_t **path, size_t *len, double *length, acd_error *err) {
    *path = NULL;
    *len = 0;
    acd_dijkstra_opts o;
    memset(&o, 0, sizeof o);
    if (opts) o = *opts;
    o.target = t;
    if (t >= g->nvertices)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "shortest path: target %u out of %zu vertices", t, g->nvertices);
    acd_sp_tree tree;
    acd_status st = acd_dijkstra(g, &s, 1, &o, &tree, err);
    if (st != ACD_OK) return st;
    st = acd_sp_path(&tree, t, path, len, err);
    if (st == ACD_OK && length) *length = tree.dist[t];
    acd_sp_tree_free(&tree);
    return st;
}

acd_status acd_sp_ws_init(acd_sp_ws *w, size_t nv, acd_error *err) {
    memset(w, 0, sizeof *w);
    size_t n = nv ? nv : 1;
    w->nvertices = nv;
    w->dist = malloc(n * sizeof *w->dist);
    w->pred = malloc(n * sizeof *w->pred);
    w->stamp = calloc(n, sizeof *w->stamp);
    w->done = calloc(n, sizeof *w->done);
    w->tstamp = calloc(n, sizeof *w->tstamp);
    w->visited = malloc(n * sizeof *w->visited);
    if (w->dist && w->pred && w->stamp && w->done && w->tstamp && w->visited) return ACD_OK;
    acd_sp_ws_free(w);
    return acd_fail(err, ACD_ERR_NOMEM, "out of memory for a shortest-path workspace of %zu vertices", nv);
}

void acd_sp_ws_free(acd_sp_ws *w) {
    if (!w) return;
    free(w->dist), free(w->pred), free(w->stamp), free(w->done), free(w->tstamp), free(w->visited);
    acd_minheap_free(&w->heap);
    memset(w, 0, sizeof *w);
}

/* The run's loop; use_allowed, use_below and keep_pred are constants at the calls for the two
 * common kinds of run (always inlined: a ball has a bound but neither an allowed test nor
 * predecessors; a region search the opposite), variables at the third. 0 when out of memory. */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline int sp_ws_loop(acd_sp_ws *w, const acd_edge_graph *g, const double *wt, const uint8_t *allowed,
                             const int use_allowed, const int use_below, const int keep_pred, double below,
                             size_t pending) {
    const uint32_t run = w->run;
    const size_t *row = g->row;
    const uint32_t *adj = g->adj, *adj_edge = g->adj_edge;
    double *dist = w->dist;
    uint32_t *pred = w->pred, *stamp = w->stamp, *done = w->done, *visited = w->visited;
    const uint32_t *tstamp = w->tstamp;
    acd_minheap *heap = &w->heap;
    size_t nvisited = 0;
    int ok = 1;
    while (heap->n) {
        acd_minheap_item it = acd_minheap_pop(heap);
        uint32_t u = it.id;
        if (done[u] == run || it.key != dist[u]) continue; /* a stale item */
        done[u] = run;
        visited[nvisited++] = u;
        if (pending && tstamp[u] == run && --pending == 0) break;
        const double du = it.key;
        for (size_t k = row[u], end = row[u + 1]; k < end; k++) {
            uint32_t v = adj[k];
            if (use_allowed && !allowed[v]) continue;
            double nd = du + wt[adj_edge[k]];
            if (use_below && !(nd < below)) continue; /* never settled: only distances below the bound count */
            /* a settled v is never improved (its distance <= du <= nd: settled in nondecreasing
               order, weights >= 0), so only the tie rule needs to know it is settled */
            if (stamp[v] == run) {
                if (keep_pred && done[v] == run) continue;
                if (!(nd < dist[v])) {
                    if (keep_pred && nd == dist[v] && u < pred[v]) pred[v] = u; /* tie: the smaller predecessor */
                    continue;
                }
            }
            stamp[v] = run;
            dist[v] = nd;
            if (keep_pred) pred[v] = u;
            if (!acd_minheap_push(heap, nd, v)) {
                ok = 0;
                goto out;
            }
        }
    }
out:
    w->nvisited = nvisited;
    return ok;
}

int acd_sp_ws_run(acd_sp_ws *w, const acd_edge_graph *g, uint32_t src, const acd_sp_limits *lim) {
    static const acd_sp_limits none = {0};
    if (!lim) lim = &none;
    if (++w->run == 0) { /* stamp wrap-around: every entry is old */
        memset(w->stamp, 0, w->nvertices * sizeof *w->stamp);
        memset(w->done, 0, w->nvertices * sizeof *w->done);
        memset(w->tstamp, 0, w->nvertices * sizeof *w->tstamp);
        w->run = 1;
    }
    const uint32_t run = w->run;
    const double *wt = lim->weights ? lim->weights : g->length;
    const uint8_t *allowed = lim->vertex_allowed;
    const int bounded = lim->below > 0, keep_pred = !lim->no_pred;
    const double below = bounded ? lim->below : INFINITY;
    w->heap.n = 0;
    w->nvisited = 0;
    size_t pending = 0; /* targets not settled yet (each vertex once) */
    if (lim->targets) {
        for (size_t i = 0; i < lim->ntargets; i++)
            if (w->tstamp[lim->targets[i]] != run) w->tstamp[lim->targets[i]] = run, pending++;
        if (!pending) return 1;
    }
    if (allowed && !allowed[src]) return 1;
    w->stamp[src] = run;
    w->dist[src] = 0;
    w->pred[src] = ACD_NO_VERTEX;
    if (!acd_minheap_push(&w->heap, 0.0, src)) return 0;
    if (!allowed && bounded && !keep_pred) return sp_ws_loop(w, g, wt, NULL, 0, 1, 0, below, pending);
    if (allowed && !bounded && keep_pred) return sp_ws_loop(w, g, wt, allowed, 1, 0, 1, below, pending);
    return sp_ws_loop(w, g, wt, allowed, allowed != NULL, bounded, keep_pred, below, pending);
}
