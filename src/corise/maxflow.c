/* corise/maxflow: Boykov-Kolmogorov maximum flow (IEEE TPAMI 26(9) 2004, Section 3).
 *
 * Two search trees S (rooted at the source) and T (rooted at the sink) grow from the terminals
 * along non-saturated arcs (growth stage, §3.1). When they touch, the path source->...->p->q->
 * ...->sink is augmented by its bottleneck (augmentation stage); arcs that become saturated cut
 * their lower node off its tree, making it an orphan. Orphans look for a new parent in the same
 * tree whose own path reaches the terminal (adoption stage, §3.2); one that finds none becomes
 * free, and its children become orphans. The algorithm stops when no active node is left.
 *
 * Implementation notes (written for this project):
 *   - arcs are stored in pairs: arc a and its reverse a^1; the node lists are singly linked;
 *   - t-links are one residual value per node: tr > 0 is residual source->i, tr < 0 residual
 *     i->sink; adding both directions cancels min(cs, ct), which is flow already;
 *   - active nodes form a FIFO queue; orphans a FIFO ring;
 *   - adoption uses the timestamp/distance marks of Kolmogorov's thesis (§3.2 heuristics): a
 *     node whose origin was verified during the current augmentation carries ts == time and its
 *     distance to the terminal, so each orphan check walks a short path;
 *   - after the trees stop growing, the source set is computed explicitly as the set of nodes
 *     reachable from the source in the residual graph (breadth-first), the unique minimal
 *     minimum cut, so the answer is independent of tree shapes.
 * With doubles, every augmentation subtracts the bottleneck, which is one of the residuals
 * itself, so that residual becomes exactly 0 and none ever becomes negative (c > b implies
 * c - b > 0 in IEEE arithmetic). */
#include "corise/maxflow.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

#define MF_NIL UINT32_MAX            /* no arc / no node */
#define MF_FREE UINT32_MAX           /* parent value: node in no tree */
#define MF_TERMINAL (UINT32_MAX - 1) /* parent value: attached to its terminal directly */
#define MF_ORPHAN (UINT32_MAX - 2)   /* parent value: lost its parent, waiting for adoption */

typedef struct mf_node {
    double tr;       /* residual t-link: > 0 from the source, < 0 to the sink */
    uint64_t ts;     /* time at which dist was verified */
    uint32_t first;  /* first outgoing arc */
    uint32_t parent; /* arc to the parent (from this node), or MF_FREE/TERMINAL/ORPHAN */
    uint32_t next;   /* next active node; MF_NIL when not active; itself when last */
    uint32_t dist;   /* distance to the terminal along the tree (valid when ts is current) */
    uint8_t sink;    /* 1: in the sink tree T; 0: in S (meaningful when parent != MF_FREE) */
    uint8_t source_side;
} mf_node;

typedef struct mf_arc {
    double r;      /* residual capacity */
    uint32_t head; /* node the arc points to */
    uint32_t next; /* next arc out of the same tail */
} mf_arc;

struct acd_maxflow {
    mf_node *nodes;
    size_t nnodes, cap_nodes;
    mf_arc *arcs;
    size_t narcs, cap_arcs;
    double flow; /* flow already pushed through source->i->sink when t-links were added */
    int solved;
    /* solve-time state */
    uint32_t active_first, active_last;
    uint32_t *orphans; /* ring of capacity nnodes */
    size_t orph_head, orph_count;
    uint64_t time;
};

acd_status acd_maxflow_create(acd_maxflow **out, size_t node_hint, size_t edge_hint, acd_error *err) {
    if (!out) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "maxflow: NULL output pointer");
    *out = NULL;
    acd_maxflow *g = calloc(1, sizeof *g);
    if (!g) return acd_fail(err, ACD_ERR_NOMEM, "maxflow: out of memory creating the graph");
    if (node_hint > ACD_MAXFLOW_MAX_NODES) node_hint = ACD_MAXFLOW_MAX_NODES;
    if (edge_hint > ACD_MAXFLOW_MAX_EDGES) edge_hint = ACD_MAXFLOW_MAX_EDGES;
    if (node_hint) {
        g->nodes = malloc(node_hint * sizeof *g->nodes);
        if (!g->nodes) goto nomem;
        g->cap_nodes = node_hint;
    }
    if (edge_hint) {
        g->arcs = malloc(2 * edge_hint * sizeof *g->arcs);
        if (!g->arcs) goto nomem;
        g->cap_arcs = 2 * edge_hint;
    }
    *out = g;
    return ACD_OK;
nomem:
    acd_maxflow_free(g);
    return acd_fail(err, ACD_ERR_NOMEM, "maxflow: out of memory reserving %zu nodes and %zu edges",
                    node_hint, edge_hint);
}

void acd_maxflow_free(acd_maxflow *g) {
    if (!g) return;
    free(g->nodes);
    free(g->arcs);
    free(g->orphans);
    free(g);
}

void acd_maxflow_reset(acd_maxflow *g) {
    if (!g) return;
    g->nnodes = 0;
    g->narcs = 0;
    g->flow = 0.0;
    g->solved = 0;
}

size_t acd_maxflow_node_count(const acd_maxflow *g) { return g ? g->nnodes : 0; }

acd_status acd_maxflow_add_nodes(acd_maxflow *g, size_t n, size_t *first, acd_error *err) {
    if (!g) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "maxflow: NULL graph");
    if (g->solved) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "maxflow: graph already solved; reset it first");
    if (n > ACD_MAXFLOW_MAX_NODES - g->nnodes)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "maxflow: %zu + %zu nodes exceed the limit of %zu",
                        g->nnodes, n, ACD_MAXFLOW_MAX_NODES);
    size_t need = g->nnodes + n;
    if (need > g->cap_nodes) {
        size_t cap = g->cap_nodes ? g->cap_nodes : 16;
        while (cap < need) cap = cap > ACD_MAXFLOW_MAX_NODES / 2 ? ACD_MAXFLOW_MAX_NODES : 2 * cap;
        mf_node *p = realloc(g->nodes, cap * sizeof *p);
        if (!p) return acd_fail(err, ACD_ERR_NOMEM, "maxflow: out of memory growing to %zu nodes", need);
        g->nodes = p;
        g->cap_nodes = cap;
    }
    for (size_t i = g->nnodes; i < need; i++) {
        mf_node *v = &g->nodes[i];
        memset(v, 0, sizeof *v);
        v->first = MF_NIL;
        v->parent = MF_FREE;
        v->next = MF_NIL;
    }
    if (first) *first = g->nnodes;
    g->nnodes = need;
    return ACD_OK;
}

static int valid_capacity(double c) { return isfinite(c) && c >= 0.0; }

acd_status acd_maxflow_add_tweights(acd_maxflow *g, size_t i, double cap_source, double cap_sink,
                                    acd_error *err) {
    if (!g) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "maxflow: NULL graph");
    if (g->solved) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "maxflow: graph already solved; reset it first");
    if (i >= g->nnodes)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "maxflow: t-link on node %zu, but the graph has %zu nodes",
                        i, g->nnodes);
    if (!valid_capacity(cap_source) || !valid_capacity(cap_sink))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT,
                        "maxflow: t-link capacities of node %zu must be finite and >= 0 (got %g, %g)", i,
                        cap_source, cap_sink);
    double cs = cap_source, ct = cap_sink, tr = g->nodes[i].tr;
    if (tr > 0)
        cs += tr;
    else
        ct -= tr;
    if (!isfinite(cs) || !isfinite(ct))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "maxflow: t-link capacity of node %zu overflows", i);
    g->flow += cs < ct ? cs : ct;
    g->nodes[i].tr = cs - ct;
    return ACD_OK;
}

acd_status acd_maxflow_add_edge(acd_maxflow *g, size_t i, size_t j, double cap, double rev_cap,
                                acd_error *err) {
    if (!g) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "maxflow: NULL graph");
    if (g->solved) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "maxflow: graph already solved; reset it first");
    if (i >= g->nnodes || j >= g->nnodes)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "maxflow: edge %zu-%zu, but the graph has %zu nodes", i, j,
                        g->nnodes);
    if (i == j) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "maxflow: edge from node %zu to itself", i);
    if (!valid_capacity(cap) || !valid_capacity(rev_cap))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT,
                        "maxflow: capacities of edge %zu-%zu must be finite and >= 0 (got %g, %g)", i, j, cap,
                        rev_cap);
    if (g->narcs / 2 >= ACD_MAXFLOW_MAX_EDGES)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "maxflow: more than %zu edges", ACD_MAXFLOW_MAX_EDGES);
    if (g->narcs + 2 > g->cap_arcs) {
        size_t cap_arcs = g->cap_arcs ? 2 * g->cap_arcs : 64;
        if (cap_arcs > 2 * ACD_MAXFLOW_MAX_EDGES) cap_arcs = 2 * ACD_MAXFLOW_MAX_EDGES;
        mf_arc *p = realloc(g->arcs, cap_arcs * sizeof *p);
        if (!p) return acd_fail(err, ACD_ERR_NOMEM, "maxflow: out of memory growing to %zu edges", g->narcs / 2 + 1);
        g->arcs = p;
        g->cap_arcs = cap_arcs;
    }
    uint32_t a = (uint32_t)g->narcs;
    g->arcs[a].r = cap;
    g->arcs[a].head = (uint32_t)j;
    g->arcs[a].next = g->nodes[i].first;
    g->nodes[i].first = a;
    g->arcs[a + 1].r = rev_cap;
    g->arcs[a + 1].head = (uint32_t)i;
    g->arcs[a + 1].next = g->nodes[j].first;
    g->nodes[j].first = a + 1;
    g->narcs += 2;
    return ACD_OK;
}

/* ---- solve-time helpers ------------------------------------------------------------------- */

static void set_active(acd_maxflow *g, uint32_t i) {
    mf_node *v = &g->nodes[i];
    if (v->next != MF_NIL) return;
    if (g->active_last != MF_NIL)
        g->nodes[g->active_last].next = i;
    else
        g->active_first = i;
    g->active_last = i;
    v->next = i;
}

/* Pops active nodes until one that is still in a tree; MF_NIL when none is left. */
static uint32_t next_active(acd_maxflow *g) {
    for (;;) {
        uint32_t i = g->active_first;
        if (i == MF_NIL) return MF_NIL;
        mf_node *v = &g->nodes[i];
        if (v->next == i)
            g->active_first = g->active_last = MF_NIL;
        else
            g->active_first = v->next;
        v->next = MF_NIL;
        if (v->parent != MF_FREE) return i;
    }
}

static void push_orphan(acd_maxflow *g, uint32_t i) {
    g->nodes[i].parent = MF_ORPHAN;
    size_t n = g->nnodes;
    g->orphans[(g->orph_head + g->orph_count) % n] = i;
    g->orph_count++;
}

static uint32_t pop_orphan(acd_maxflow *g) {
    uint32_t i = g->orphans[g->orph_head];
    g->orph_head = (g->orph_head + 1) % g->nnodes;
    g->orph_count--;
    return i;
}

/* Augments along the path through the middle arc am (from an S node to a T node). */
static void augment(acd_maxflow *g, uint32_t am) {
    mf_arc *arcs = g->arcs;
    mf_node *nodes = g->nodes;
    double b = arcs[am].r;
    uint32_t x, a;
    /* bottleneck on the source side: arcs parent->x are the reverses of the parent arcs */
    for (x = arcs[am ^ 1u].head; (a = nodes[x].parent) != MF_TERMINAL; x = arcs[a].head)
        if (arcs[a ^ 1u].r < b) b = arcs[a ^ 1u].r;
    if (nodes[x].tr < b) b = nodes[x].tr;
    /* sink side: flow runs x->parent along the parent arcs themselves */
    for (x = arcs[am].head; (a = nodes[x].parent) != MF_TERMINAL; x = arcs[a].head)
        if (arcs[a].r < b) b = arcs[a].r;
    if (-nodes[x].tr < b) b = -nodes[x].tr;

    arcs[am].r -= b;
    arcs[am ^ 1u].r += b;
    for (x = arcs[am ^ 1u].head; (a = nodes[x].parent) != MF_TERMINAL;) {
        arcs[a].r += b;
        arcs[a ^ 1u].r -= b;
        uint32_t up = arcs[a].head;
        if (arcs[a ^ 1u].r == 0.0) push_orphan(g, x);
        x = up;
    }
    nodes[x].tr -= b;
    if (nodes[x].tr == 0.0) push_orphan(g, x);
    for (x = arcs[am].head; (a = nodes[x].parent) != MF_TERMINAL;) {
        arcs[a ^ 1u].r += b;
        arcs[a].r -= b;
        uint32_t up = arcs[a].head;
        if (arcs[a].r == 0.0) push_orphan(g, x);
        x = up;
    }
    nodes[x].tr += b;
    if (nodes[x].tr == 0.0) push_orphan(g, x);
    g->flow += b;
}

/* Distance from j to its tree's terminal if j's chain of parents reaches it without passing
 * through an orphan, else UINT32_MAX. Marks the verified chain with the current time. */
static uint32_t origin_distance(acd_maxflow *g, uint32_t j) {
    mf_node *nodes = g->nodes;
    mf_arc *arcs = g->arcs;
    uint32_t d = 0, x = j;
    for (;;) {
        mf_node *v = &nodes[x];
        if (v->ts == g->time) {
            d += v->dist;
            break;
        }
        uint32_t pa = v->parent;
        d++;
        if (pa == MF_TERMINAL) {
            v->ts = g->time;
            v->dist = 1;
            break;
        }
        if (pa == MF_ORPHAN || pa == MF_FREE) return UINT32_MAX;
        x = arcs[pa].head;
    }
    uint32_t dd = d;
    for (x = j; nodes[x].ts != g->time; x = arcs[nodes[x].parent].head) {
        nodes[x].ts = g->time;
        nodes[x].dist = dd--;
    }
    return d;
}

static void adopt(acd_maxflow *g, uint32_t i) {
    mf_node *nodes = g->nodes;
    mf_arc *arcs = g->arcs;
    uint8_t sink = nodes[i].sink;
    uint32_t best_a = MF_NIL, best_d = UINT32_MAX;
    for (uint32_t a = nodes[i].first; a != MF_NIL; a = arcs[a].next) {
        /* residual must run toward i in S (j->i), away from i in T (i->j) */
        double r = sink ? arcs[a].r : arcs[a ^ 1u].r;
        if (r <= 0.0) continue;
        uint32_t j = arcs[a].head;
        if (nodes[j].parent == MF_FREE || nodes[j].sink != sink) continue;
        uint32_t d = origin_distance(g, j);
        if (d < best_d) {
            best_d = d;
            best_a = a;
        }
    }
    if (best_a != MF_NIL) {
        nodes[i].parent = best_a;
        nodes[i].ts = g->time;
        nodes[i].dist = best_d + 1;
        return;
    }
    /* no parent: i becomes free; neighbours in its tree may regrow into it, its children
     * become orphans */
    nodes[i].parent = MF_FREE;
    for (uint32_t a = nodes[i].first; a != MF_NIL; a = arcs[a].next) {
        uint32_t j = arcs[a].head;
        mf_node *w = &nodes[j];
        if (w->parent == MF_FREE || w->sink != sink) continue;
        double r = sink ? arcs[a].r : arcs[a ^ 1u].r;
        if (r > 0.0) set_active(g, j);
        uint32_t pa = w->parent;
        if (pa != MF_TERMINAL && pa != MF_ORPHAN && arcs[pa].head == i) push_orphan(g, j);
    }
}

/* Growth from active node i; returns the middle arc (S node -> T node) of a found path, or
 * MF_NIL when i's neighbourhood is exhausted. */
static uint32_t grow(acd_maxflow *g, uint32_t i) {
    mf_node *nodes = g->nodes;
    mf_arc *arcs = g->arcs;
    mf_node *v = &nodes[i];
    for (uint32_t a = v->first; a != MF_NIL; a = arcs[a].next) {
        double r = v->sink ? arcs[a ^ 1u].r : arcs[a].r;
        if (r <= 0.0) continue;
        uint32_t j = arcs[a].head;
        mf_node *w = &nodes[j];
        if (w->parent == MF_FREE) {
            w->sink = v->sink;
            w->parent = a ^ 1u;
            w->ts = v->ts;
            w->dist = v->dist + 1;
            set_active(g, j);
        } else if (w->sink != v->sink) {
            return v->sink ? a ^ 1u : a;
        } else if (w->ts <= v->ts && w->dist > v->dist) {
            /* shorten j's path through i (distance heuristic) */
            w->parent = a ^ 1u;
            w->ts = v->ts;
            w->dist = v->dist + 1;
        }
    }
    return MF_NIL;
}

acd_status acd_maxflow_solve(acd_maxflow *g, double *flow, acd_error *err) {
    return acd_maxflow_solve_poll(g, flow, NULL, err);
}

acd_status acd_maxflow_solve_poll(acd_maxflow *g, double *flow, acd3_poll *poll, acd_error *err) {
    if (!g) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "maxflow: NULL graph");
    if (g->solved) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "maxflow: graph already solved; reset it first");
    size_t n = g->nnodes;
    free(g->orphans);
    g->orphans = NULL;
    if (n) {
        g->orphans = malloc(n * sizeof *g->orphans);
        if (!g->orphans)
            return acd_fail(err, ACD_ERR_NOMEM, "maxflow: out of memory for the orphan list of %zu nodes", n);
    }
    g->orph_head = g->orph_count = 0;
    g->active_first = g->active_last = MF_NIL;
    g->time = 0;
    for (size_t k = 0; k < n; k++) {
        mf_node *v = &g->nodes[k];
        v->ts = 0;
        v->dist = 1;
        v->next = MF_NIL;
        v->source_side = 0;
        if (v->tr > 0.0) {
            v->sink = 0;
            v->parent = MF_TERMINAL;
            set_active(g, (uint32_t)k);
        } else if (v->tr < 0.0) {
            v->sink = 1;
            v->parent = MF_TERMINAL;
            set_active(g, (uint32_t)k);
        } else {
            v->parent = MF_FREE;
        }
    }

    uint32_t current = MF_NIL;
    for (size_t steps = 1;; steps++) {
        if (poll && steps % ACD_MAXFLOW_POLL_STEPS == 0 && acd3_poll_stop(poll))
            return acd_fail(err, ACD_ERR_CANCELLED, "maxflow: cancelled by the progress callback (%zu nodes)", n);
        uint32_t i;
        if (current != MF_NIL && g->nodes[current].parent != MF_FREE)
            i = current;
        else
            i = next_active(g);
        current = MF_NIL;
        if (i == MF_NIL) break;
        uint32_t am = grow(g, i);
        if (am == MF_NIL) continue;
        current = i; /* i may have more paths: scan it again after this augmentation */
        g->time++;
        augment(g, am);
        while (g->orph_count) {
            uint32_t o = pop_orphan(g);
            adopt(g, o);
        }
    }

    /* minimal source set: residual reachability from the source (breadth-first) */
    uint32_t *queue = g->orphans; /* reuse: n entries */
    size_t qh = 0, qt = 0;
    for (size_t k = 0; k < n; k++)
        if (g->nodes[k].tr > 0.0) {
            g->nodes[k].source_side = 1;
            queue[qt++] = (uint32_t)k;
        }
    while (qh < qt) {
        uint32_t x = queue[qh++];
        for (uint32_t a = g->nodes[x].first; a != MF_NIL; a = g->arcs[a].next) {
            uint32_t y = g->arcs[a].head;
            if (g->arcs[a].r > 0.0 && !g->nodes[y].source_side) {
                g->nodes[y].source_side = 1;
                queue[qt++] = y;
            }
        }
    }
    g->solved = 1;
    if (flow) *flow = g->flow;
    return ACD_OK;
}

int acd_maxflow_is_source(const acd_maxflow *g, size_t i) {
    if (!g || !g->solved || i >= g->nnodes) return 0;
    return g->nodes[i].source_side;
}
