/* Tests of geom3/dijkstra: distances against Bellman-Ford on random graphs, exact grid distances,
 * deterministic tie-breaks, barriers, regions, several sources, early stop; the mesh graph's
 * arrays equal, bit for bit, those of the triangles' sides given as explicit edges; the reusable
 * workspace (bounded and targeted runs) against full searches. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "geom3/dijkstra.h"

static void check_tree_consistent(const acd_edge_graph *g, const acd_sp_tree *t, const double *w) {
    for (size_t v = 0; v < g->nvertices; v++) {
        if (t->pred[v] == ACD_NO_VERTEX) continue;
        uint32_t e = t->pred_edge[v];
        assert_true(e < g->nedges);
        uint32_t u = t->pred[v];
        assert_true((g->edge_v[2 * e] == u && g->edge_v[2 * e + 1] == v) ||
                    (g->edge_v[2 * e] == v && g->edge_v[2 * e + 1] == u));
        assert_true(t->dist[v] == t->dist[u] + w[e]);
        assert_int_equal(t->origin[v], t->origin[u]);
    }
}

static void test_random_vs_bellman_ford(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 21);
    for (int trial = 0; trial < 30; trial++) {
        size_t nv = 2 + (size_t)acd_rng_below(&r, 60), ne = (size_t)acd_rng_below(&r, 4 * nv);
        uint32_t *edges = malloc((ne + 1) * 2 * sizeof *edges);
        double *wt = malloc((ne + 1) * sizeof *wt);
        assert_non_null(edges);
        assert_non_null(wt);
        for (size_t e = 0; e < ne; e++) {
            edges[2 * e] = (uint32_t)acd_rng_below(&r, nv);
            edges[2 * e + 1] = (uint32_t)acd_rng_below(&r, nv);
            wt[e] = trial % 2 ? (double)acd_rng_below(&r, 4) : acd_rng_uniform(&r); /* integer weights: ties */
        }
        acd_edge_graph g;
        acd_error err;
        assert_int_equal(acd_edge_graph_from_edges(nv, edges, wt, ne, &g, &err), ACD_OK);
        /* Bellman-Ford from the merged graph's own weights */
        double *bf = malloc(nv * sizeof *bf);
        assert_non_null(bf);
        uint32_t src[2] = {(uint32_t)acd_rng_below(&r, nv), (uint32_t)acd_rng_below(&r, nv)};
        size_t nsrc = 1 + (size_t)(trial % 2);
        for (size_t v = 0; v < nv; v++) bf[v] = INFINITY;
        for (size_t s = 0; s < nsrc; s++) bf[src[s]] = 0;
        for (size_t it = 0; it < nv; it++)
            for (size_t e = 0; e < g.nedges; e++) {
                uint32_t a = g.edge_v[2 * e], b = g.edge_v[2 * e + 1];
                if (bf[a] + g.length[e] < bf[b]) bf[b] = bf[a] + g.length[e];
                if (bf[b] + g.length[e] < bf[a]) bf[a] = bf[b] + g.length[e];
            }
        acd_sp_tree t;
        assert_int_equal(acd_dijkstra(&g, src, nsrc, NULL, &t, &err), ACD_OK);
        for (size_t v = 0; v < nv; v++) {
            if (isinf(bf[v])) {
                assert_true(isinf(t.dist[v]));
                assert_int_equal(t.pred[v], ACD_NO_VERTEX);
            } else {
                assert_true(fabs(t.dist[v] - bf[v]) <= 1e-12 * (1 + bf[v]));
            }
        }
        check_tree_consistent(&g, &t, g.length);
        /* the path to every reached vertex sums to its distance */
        for (uint32_t v = 0; v < nv; v++) {
            uint32_t *path;
            size_t len;
            acd_status st = acd_sp_path(&t, v, &path, &len, &err);
            if (isinf(t.dist[v])) {
                assert_int_equal(st, ACD_ERR_DEGENERATE);
                continue;
            }
            assert_int_equal(st, ACD_OK);
            assert_int_equal(path[len - 1], v);
            assert_true(path[0] == src[0] || path[0] == src[nsrc - 1]);
            assert_int_equal(path[0], src[t.origin[v]]);
            double sum = 0;
            for (size_t i = 0; i + 1 < len; i++) {
                uint32_t e = acd_edge_graph_find(&g, path[i], path[i + 1]);
                assert_true(e != ACD_NO_VERTEX);
                sum += g.length[e];
            }
            assert_true(sum == t.dist[v]);
            free(path);
        }
        acd_sp_tree_free(&t);
        acd_edge_graph_free(&g);
        free(bf);
        free(edges);
        free(wt);
    }
}

/* An n x n grid of unit squares, each split into two triangles along (i,j)-(i+1,j+1). */
static void grid_mesh(int n, double **verts, uint32_t **tris, size_t *nv, size_t *nt) {
    *nv = (size_t)(n + 1) * (size_t)(n + 1);
    *nt = (size_t)2 * (size_t)n * (size_t)n;
    *verts = malloc(*nv * 3 * sizeof **verts);
    *tris = malloc(*nt * 3 * sizeof **tris);
    assert_non_null(*verts);
    assert_non_null(*tris);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            size_t v = (size_t)j * (size_t)(n + 1) + (size_t)i;
            (*verts)[3 * v] = i;
            (*verts)[3 * v + 1] = j;
            (*verts)[3 * v + 2] = 0;
        }
    size_t t = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)(n + 1) + 1, d = a + (uint32_t)(n + 1);
            uint32_t *q = *tris + 3 * t;
            q[0] = a, q[1] = b, q[2] = c, q[3] = a, q[4] = c, q[5] = d;
            t += 2;
        }
}

static void test_grid_distances_and_ties(void **state) {
    (void)state;
    int n = 10;
    double *verts;
    uint32_t *tris;
    size_t nv, nt;
    grid_mesh(n, &verts, &tris, &nv, &nt);
    acd_edge_graph g;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(verts, nv, tris, nt, &g, &err), ACD_OK);
    assert_int_equal(g.nedges, (size_t)3 * n * n + 2 * n); /* 2n(n+1) axis edges + n^2 diagonals */
    acd_sp_tree t;
    uint32_t s = 0;
    assert_int_equal(acd_dijkstra(&g, &s, 1, NULL, &t, &err), ACD_OK);
    /* exact: with diagonals along (1,1), distance = |dx - dy| + sqrt2 min(dx, dy) */
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            double expect = fabs((double)(i - j)) + sqrt(2.0) * (i < j ? i : j);
            assert_true(fabs(t.dist[j * (n + 1) + i] - expect) < 1e-12);
        }
    check_tree_consistent(&g, &t, g.length);
    acd_sp_tree_free(&t);

    /* unit weights: many equal paths; the tie rule picks the smaller predecessor id, so the
     * path from corner 0 to the far corner is the same on every run and fixed by the rule */
    double *unit = malloc(g.nedges * sizeof *unit);
    assert_non_null(unit);
    for (size_t e = 0; e < g.nedges; e++) unit[e] = 1;
    acd_dijkstra_opts o;
    memset(&o, 0, sizeof o);
    o.weights = unit;
    o.target = ACD_NO_VERTEX;
    assert_int_equal(acd_dijkstra(&g, &s, 1, &o, &t, &err), ACD_OK);
    for (size_t v = 0; v < nv; v++) {
        if (t.pred[v] == ACD_NO_VERTEX) continue;
        /* every neighbour at distance d(v) - 1 has an id >= the chosen predecessor */
        for (size_t k = g.row[v]; k < g.row[v + 1]; k++) {
            uint32_t u = g.adj[k];
            if (t.dist[u] + 1 == t.dist[v]) assert_true(u >= t.pred[v]);
        }
    }
    uint32_t *p1, *p2;
    size_t l1, l2;
    double len;
    uint32_t far = (uint32_t)(nv - 1);
    assert_int_equal(acd_shortest_path(&g, 0, far, &o, &p1, &l1, &len, &err), ACD_OK);
    assert_true(len == 10);
    assert_int_equal(acd_shortest_path(&g, 0, far, &o, &p2, &l2, &len, &err), ACD_OK);
    assert_int_equal(l1, l2);
    assert_memory_equal(p1, p2, l1 * sizeof *p1);
    free(p1);
    free(p2);
    acd_sp_tree_free(&t);

    /* barrier: block every edge crossing the vertical line x = 5.5 except at the top row */
    uint8_t *blocked = calloc(g.nedges, 1);
    assert_non_null(blocked);
    for (size_t e = 0; e < g.nedges; e++) {
        double xa = verts[3 * g.edge_v[2 * e]], xb = verts[3 * g.edge_v[2 * e + 1]];
        double ya = verts[3 * g.edge_v[2 * e] + 1];
        if (((xa <= 5 && xb >= 6) || (xb <= 5 && xa >= 6)) && ya < n) blocked[e] = 1;
    }
    memset(&o, 0, sizeof o);
    o.edge_blocked = blocked;
    o.target = ACD_NO_VERTEX;
    assert_int_equal(acd_dijkstra(&g, &s, 1, &o, &t, &err), ACD_OK);
    /* (6, 0) must be reached over the top: 5 + 10 + 1 + 10 at least with unit axis steps */
    double d60 = t.dist[6];
    assert_true(d60 >= 2 * n + 1 - 1e-9);
    acd_sp_tree_free(&t);

    /* region: only the bottom row allowed: distances along it are |i| */
    uint8_t *allowed = calloc(nv, 1);
    assert_non_null(allowed);
    for (int i = 0; i <= n; i++) allowed[i] = 1;
    memset(&o, 0, sizeof o);
    o.vertex_allowed = allowed;
    o.target = ACD_NO_VERTEX;
    assert_int_equal(acd_dijkstra(&g, &s, 1, &o, &t, &err), ACD_OK);
    for (int i = 0; i <= n; i++) assert_true(t.dist[i] == i);
    for (size_t v = (size_t)n + 1; v < nv; v++) assert_true(isinf(t.dist[v]));
    acd_sp_tree_free(&t);

    /* two sources: every vertex labelled with the nearer one (ties to the smaller predecessor) */
    uint32_t two[2] = {0, (uint32_t)(nv - 1)};
    assert_int_equal(acd_dijkstra(&g, two, 2, NULL, &t, &err), ACD_OK);
    acd_sp_tree t0, t1;
    assert_int_equal(acd_dijkstra(&g, &two[0], 1, NULL, &t0, &err), ACD_OK);
    assert_int_equal(acd_dijkstra(&g, &two[1], 1, NULL, &t1, &err), ACD_OK);
    for (size_t v = 0; v < nv; v++) {
        double m = t0.dist[v] < t1.dist[v] ? t0.dist[v] : t1.dist[v];
        assert_true(t.dist[v] == m);
        if (t0.dist[v] < t1.dist[v]) assert_int_equal(t.origin[v], 0);
        if (t1.dist[v] < t0.dist[v]) assert_int_equal(t.origin[v], 1);
    }
    acd_sp_tree_free(&t0);
    acd_sp_tree_free(&t1);
    acd_sp_tree_free(&t);

    /* early stop at a target and at a distance limit */
    memset(&o, 0, sizeof o);
    o.target = 12;
    assert_int_equal(acd_dijkstra(&g, &s, 1, &o, &t, &err), ACD_OK);
    assert_true(fabs(t.dist[12] - sqrt(2.0)) < 1e-15);
    assert_true(isinf(t.dist[nv - 1]));
    acd_sp_tree_free(&t);
    memset(&o, 0, sizeof o);
    o.target = ACD_NO_VERTEX;
    o.max_distance = 3.5;
    assert_int_equal(acd_dijkstra(&g, &s, 1, &o, &t, &err), ACD_OK);
    for (size_t v = 0; v < nv; v++) assert_true(isinf(t.dist[v]) || t.dist[v] <= 3.5);
    assert_true(t.dist[3] == 3);
    assert_true(isinf(t.dist[4]));
    acd_sp_tree_free(&t);

    free(allowed);
    free(blocked);
    free(unit);
    acd_edge_graph_free(&g);
    free(verts);
    free(tris);
}

static void test_bad_input(void **state) {
    (void)state;
    acd_edge_graph g;
    acd_error err;
    uint32_t tri[3] = {0, 1, 7};
    double v[9] = {0};
    assert_int_equal(acd_edge_graph_from_mesh(v, 3, tri, 1, &g, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "triangle 0"));
    uint32_t e[2] = {0, 1};
    double w = -1;
    assert_int_equal(acd_edge_graph_from_edges(2, e, &w, 1, &g, &err), ACD_ERR_INVALID_INPUT);
    w = NAN;
    assert_int_equal(acd_edge_graph_from_edges(2, e, &w, 1, &g, &err), ACD_ERR_INVALID_INPUT);
    w = 2;
    assert_int_equal(acd_edge_graph_from_edges(2, e, &w, 1, &g, &err), ACD_OK);
    acd_sp_tree t;
    uint32_t s = 5;
    assert_int_equal(acd_dijkstra(&g, &s, 1, NULL, &t, &err), ACD_ERR_INVALID_ARGUMENT);
    acd_sp_tree_free(&t);
    acd_edge_graph_free(&g);
}

/* acd_edge_graph_from_mesh buckets the sides itself; acd_edge_graph_from_edges sorts and merges
 * the same sides (each with its length, computed as from_mesh does from the lower vertex): the
 * two graphs must be identical (edge numbers, lengths' bits, rows, incidences), on meshes with
 * repeated triangles, repeated sides in both directions, sides of length 0 (a == b), vertices of
 * high degree and vertices on no triangle. */
static void check_mesh_graph(uint64_t seed, size_t nv, size_t nt, uint32_t hub_every) {
    acd_rng r;
    acd_rng_seed(&r, seed);
    double *verts = malloc(3 * nv * sizeof *verts);
    uint32_t *tris = malloc(3 * nt * sizeof *tris), *sides = malloc(6 * nt * sizeof *sides);
    double *w = malloc(3 * nt * sizeof *w);
    assert_true(verts && tris && sides && w);
    for (size_t i = 0; i < 3 * nv; i++) verts[i] = acd_rng_uniform(&r) * 10 - 5;
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            uint64_t x = acd_rng_below(&r, 100);
            /* a hub (high degree), a repeat of the previous triangle's corner (a == b sides and
             * repeated sides), or any vertex but the last (on no triangle) */
            tris[3 * t + k] = hub_every && x < hub_every ? 0
                              : x < 10 && t > 0     ? tris[3 * (t - 1) + k]
                              : x < 14 && k > 0     ? tris[3 * t + k - 1]
                                                    : (uint32_t)acd_rng_below(&r, nv - 1);
        }
    size_t ns = 0;
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = tris[3 * t + k], b = tris[3 * t + (k + 1) % 3];
            if (a > b) {
                uint32_t x = a;
                a = b;
                b = x;
            }
            const double *p = verts + 3 * (size_t)a, *q = verts + 3 * (size_t)b;
            double d[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
            sides[2 * ns] = tris[3 * t + k]; /* in the triangle's direction */
            sides[2 * ns + 1] = tris[3 * t + (k + 1) % 3];
            w[ns++] = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        }
    acd_edge_graph gm, ge;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(verts, nv, tris, nt, &gm, &err), ACD_OK);
    assert_int_equal(acd_edge_graph_from_edges(nv, sides, w, ns, &ge, &err), ACD_OK);
    assert_int_equal(gm.nvertices, ge.nvertices);
    assert_int_equal(gm.nedges, ge.nedges);
    assert_true(gm.nedges > 0 && gm.nedges < ns); /* repeats were merged */
    assert_memory_equal(gm.edge_v, ge.edge_v, 2 * gm.nedges * sizeof *gm.edge_v);
    assert_memory_equal(gm.length, ge.length, gm.nedges * sizeof *gm.length);
    assert_memory_equal(gm.row, ge.row, (nv + 1) * sizeof *gm.row);
    assert_memory_equal(gm.adj, ge.adj, 2 * gm.nedges * sizeof *gm.adj);
    assert_memory_equal(gm.adj_edge, ge.adj_edge, 2 * gm.nedges * sizeof *gm.adj_edge);
    assert_int_equal(gm.row[nv] - gm.row[nv - 1], 0); /* the last vertex is on no triangle */
    acd_edge_graph_free(&gm);
    acd_edge_graph_free(&ge);
    free(verts), free(tris), free(sides), free(w);
}

static void test_mesh_graph_as_edges(void **state) {
    (void)state;
    check_mesh_graph(1, 50, 200, 0);
    check_mesh_graph(2, 2000, 4000, 0);
    check_mesh_graph(3, 300, 900, 20); /* vertex 0 on a fifth of the corners: degree in the hundreds */
    check_mesh_graph(4, 4, 30, 0);     /* few vertices: nearly every side repeated */
}

/* (dist, id) order of the settling */
static int key_le(double da, uint32_t a, double db, uint32_t b) { return da < db || (da == db && a <= b); }

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* One run of the workspace against the full acd_dijkstra tree ref from the same source (same
 * weights and allowed vertices): the settled vertices are exactly those the limits ask for, with
 * ref's distances (bit for bit) and predecessors, listed once each in (distance, id) order;
 * below > 0: nothing else is reached; targets: each reachable one's path is ref's. */
static void check_ws_run(const acd_edge_graph *g, const acd_sp_ws *w, const acd_sp_tree *ref, double below,
                         const uint32_t *tg, size_t ntg) {
    size_t nv = g->nvertices;
    /* the last vertex the run must settle in (distance, id) order: the farthest target when all
     * are reachable (and below the bound), else none (settle all within the bound) */
    int capped = tg != NULL;
    double kd = -INFINITY;
    uint32_t kv = 0;
    for (size_t i = 0; i < ntg && capped; i++) {
        double d = ref->dist[tg[i]];
        if (!isfinite(d) || (below > 0 && !(d < below))) capped = 0;
        else if (!key_le(d, tg[i], kd, kv)) kd = d, kv = tg[i];
    }
    if (tg && ntg == 0) { /* targets given, none: nothing is run */
        assert_int_equal(w->nvisited, 0);
        for (size_t v = 0; v < nv; v++) assert_true(isinf(acd_sp_ws_dist(w, (uint32_t)v)));
        return;
    }
    size_t want = 0;
    for (size_t v = 0; v < nv; v++) {
        double d = ref->dist[v];
        int in = isfinite(d) && (!(below > 0) || d < below) && (!capped || key_le(d, (uint32_t)v, kd, kv));
        want += in;
        assert_int_equal(acd_sp_ws_settled(w, (uint32_t)v), in);
        if (in) {
            assert_true(same_bits(acd_sp_ws_dist(w, (uint32_t)v), d));
            assert_int_equal(w->pred[v], ref->pred[v]);
        } else if (!capped) {
            assert_true(isinf(acd_sp_ws_dist(w, (uint32_t)v))); /* no early stop: nothing tentative */
        }
    }
    assert_int_equal(w->nvisited, want);
    for (size_t i = 1; i < w->nvisited; i++) {
        uint32_t a = w->visited[i - 1], b = w->visited[i];
        assert_true(a != b && key_le(ref->dist[a], a, ref->dist[b], b));
    }
    for (size_t i = 0; i < ntg; i++) { /* a reached target's path, through settled vertices */
        if (!acd_sp_ws_settled(w, tg[i])) continue;
        for (uint32_t v = tg[i]; v != ACD_NO_VERTEX; v = w->pred[v]) {
            assert_true(acd_sp_ws_settled(w, v));
            assert_int_equal(w->pred[v], ref->pred[v]);
        }
    }
}

/* Many sources through one workspace (never reinitialised, its run stamp wrapped around once),
 * full, bounded, targeted and both, on meshes with exact ties (a flat unit grid, integer weights)
 * and without (a jittered grid), with and without a region of allowed vertices. */
static void check_ws_mesh(uint64_t seed, int n, int jitter, int int_weights, int region) {
    acd_rng r;
    acd_rng_seed(&r, seed);
    double *verts;
    uint32_t *tris;
    size_t nv, nt;
    grid_mesh(n, &verts, &tris, &nv, &nt);
    if (jitter)
        for (size_t v = 0; v < nv; v++) verts[3 * v + 2] = acd_rng_uniform(&r) * 0.7;
    acd_edge_graph g;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(verts, nv, tris, nt, &g, &err), ACD_OK);
    double *wt = NULL;
    if (int_weights) {
        wt = malloc(g.nedges * sizeof *wt);
        assert_non_null(wt);
        for (size_t e = 0; e < g.nedges; e++) wt[e] = (double)(1 + acd_rng_below(&r, 3));
    }
    uint8_t *allowed = NULL;
    if (region) { /* a disc with a slit: paths bend around it */
        allowed = malloc(nv);
        assert_non_null(allowed);
        for (size_t v = 0; v < nv; v++) {
            double x = (double)(v % (size_t)(n + 1)) - n / 2.0, y = (double)(v / (size_t)(n + 1)) - n / 2.0;
            allowed[v] = x * x + y * y < (n / 2.0) * (n / 2.0) && !(fabs(x) < 0.6 && y > -n / 4.0);
        }
    }
    acd_sp_ws w;
    assert_int_equal(acd_sp_ws_init(&w, nv, &err), ACD_OK);
    acd_dijkstra_opts o;
    memset(&o, 0, sizeof o);
    o.weights = wt;
    o.vertex_allowed = allowed;
    o.target = ACD_NO_VERTEX;
    const double *len = wt ? wt : g.length;
    for (int run = 0; run < 160; run++) {
        if (run == 102) { /* the next run (targeted) wraps the stamp around, over entries left by a run 1 */
            w.run = UINT32_MAX;
            for (size_t v = 0; v < nv; v++) w.stamp[v] = w.done[v] = w.tstamp[v] = 1, w.dist[v] = 0;
        }
        uint32_t src = (uint32_t)acd_rng_below(&r, nv);
        acd_sp_tree ref;
        assert_int_equal(acd_dijkstra(&g, &src, 1, &o, &ref, &err), ACD_OK);
        check_tree_consistent(&g, &ref, len);
        acd_sp_limits lim = {.weights = wt, .vertex_allowed = allowed};
        int mode = run % 4;
        uint32_t tg[5];
        size_t ntg = 0;
        if (mode & 1) { /* a bound: a vertex's distance (exact ties at the bound), or a fraction of the span */
            uint32_t x = (uint32_t)acd_rng_below(&r, nv);
            lim.below = isfinite(ref.dist[x]) && ref.dist[x] > 0 && run % 3 ? ref.dist[x] : 0.37 * n;
        }
        if (mode & 2) {
            ntg = (size_t)acd_rng_below(&r, 6);
            for (size_t i = 0; i < ntg; i++) tg[i] = (uint32_t)acd_rng_below(&r, nv);
            if (ntg > 1 && run % 5 == 0) tg[1] = tg[0]; /* a repeated target */
            lim.targets = tg;
            lim.ntargets = ntg;
        }
        assert_int_equal(acd_sp_ws_run(&w, &g, src, &lim), 1);
        check_ws_run(&g, &w, &ref, lim.below, lim.targets, ntg);
        if (run % 8 == 1) { /* without predecessors: the same distances and visited list */
            double *d0 = malloc(nv * sizeof *d0);
            uint32_t *v0 = malloc(nv * sizeof *v0);
            assert_true(d0 && v0);
            size_t n0 = w.nvisited;
            for (size_t v = 0; v < nv; v++) d0[v] = acd_sp_ws_dist(&w, (uint32_t)v);
            memcpy(v0, w.visited, n0 * sizeof *v0);
            acd_sp_limits lp = lim;
            lp.no_pred = 1;
            assert_int_equal(acd_sp_ws_run(&w, &g, src, &lp), 1);
            assert_int_equal(w.nvisited, n0);
            assert_memory_equal(w.visited, v0, n0 * sizeof *v0);
            for (size_t v = 0; v < nv; v++) assert_true(same_bits(acd_sp_ws_dist(&w, (uint32_t)v), d0[v]));
            free(d0), free(v0);
        }
        if (mode == 1) { /* the strict bound is acd_dijkstra's max_distance at the next double down */
            acd_dijkstra_opts ob = o;
            ob.max_distance = nextafter(lim.below, 0);
            acd_sp_tree tb;
            assert_int_equal(acd_dijkstra(&g, &src, 1, &ob, &tb, &err), ACD_OK);
            for (size_t v = 0; v < nv; v++) assert_true(same_bits(acd_sp_ws_dist(&w, (uint32_t)v), tb.dist[v]));
            acd_sp_tree_free(&tb);
        }
        acd_sp_tree_free(&ref);
    }
    assert_true(w.run < 100); /* it wrapped */
    acd_sp_ws_free(&w);
    acd_edge_graph_free(&g);
    free(verts), free(tris), free(wt), free(allowed);
}

static void test_workspace_vs_full(void **state) {
    (void)state;
    check_ws_mesh(1, 12, 0, 0, 0); /* flat unit grid: many equal distances */
    check_ws_mesh(2, 14, 1, 0, 0); /* jittered heights */
    check_ws_mesh(3, 12, 0, 1, 0); /* integer weights: ties everywhere */
    check_ws_mesh(4, 16, 1, 0, 1); /* a region with a slit */
    check_ws_mesh(5, 12, 0, 1, 1);
}

/* A source outside the region or targets given but none: nothing is settled; a target that is the
 * source stops at once. */
static void test_workspace_edges(void **state) {
    (void)state;
    double *verts;
    uint32_t *tris;
    size_t nv, nt;
    grid_mesh(4, &verts, &tris, &nv, &nt);
    acd_edge_graph g;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(verts, nv, tris, nt, &g, &err), ACD_OK);
    acd_sp_ws w;
    assert_int_equal(acd_sp_ws_init(&w, nv, &err), ACD_OK);
    assert_int_equal(acd_sp_ws_run(&w, &g, 0, NULL), 1);
    assert_int_equal(w.nvisited, nv);
    assert_true(acd_sp_ws_dist(&w, 24) == 4 * sqrt(2.0)); /* the diagonal of the 4 x 4 grid */
    uint8_t *allowed = calloc(nv, 1);
    assert_non_null(allowed);
    allowed[1] = allowed[2] = 1;
    acd_sp_limits lim = {.vertex_allowed = allowed};
    assert_int_equal(acd_sp_ws_run(&w, &g, 0, &lim), 1);
    assert_int_equal(w.nvisited, 0);
    assert_true(isinf(acd_sp_ws_dist(&w, 0)) && isinf(acd_sp_ws_dist(&w, 1)));
    uint32_t tg[1] = {7};
    lim = (acd_sp_limits){.targets = tg, .ntargets = 0};
    assert_int_equal(acd_sp_ws_run(&w, &g, 0, &lim), 1);
    assert_int_equal(w.nvisited, 0);
    tg[0] = 7;
    lim.ntargets = 1;
    assert_int_equal(acd_sp_ws_run(&w, &g, 7, &lim), 1);
    assert_int_equal(w.nvisited, 1);
    assert_true(acd_sp_ws_settled(&w, 7) && acd_sp_ws_dist(&w, 7) == 0 && w.pred[7] == ACD_NO_VERTEX);
    assert_false(acd_sp_ws_settled(&w, 6));
    lim = (acd_sp_limits){.below = 1.0}; /* strict: the neighbours at exactly 1 are out */
    assert_int_equal(acd_sp_ws_run(&w, &g, 12, &lim), 1);
    assert_int_equal(w.nvisited, 1);
    lim.below = nextafter(1.0, 2.0);
    assert_int_equal(acd_sp_ws_run(&w, &g, 12, &lim), 1);
    assert_int_equal(w.nvisited, 5);
    acd_sp_ws_free(&w);
    acd_sp_ws_free(&w); /* freeing twice is harmless */
    acd_edge_graph_free(&g);
    free(verts), free(tris), free(allowed);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_vs_bellman_ford),
        cmocka_unit_test(test_grid_distances_and_ties),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_mesh_graph_as_edges),
        cmocka_unit_test(test_workspace_vs_full),
        cmocka_unit_test(test_workspace_edges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
