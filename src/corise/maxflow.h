/* corise/maxflow: s-t maximum flow / minimum cut on a capacitated graph with two terminals,
 * by the augmenting-path algorithm with two search trees and orphan adoption of
 * Y. Boykov, V. Kolmogorov, "An experimental comparison of min-cut/max-flow algorithms for
 * energy minimization in vision", IEEE TPAMI 26(9), 2004, Section 3 (growth, augmentation and
 * adoption stages; Sections 3.1-3.2).
 *
 * Used by the binary graph cuts of CoRiSe (spec corise.md §2.7, Eq. 8): nodes are facets,
 * n-links join adjacent facets, t-links tie must-link facets to a terminal.
 *
 * The graph:
 *   - nodes 0..n-1, added with acd_maxflow_add_nodes();
 *   - t-links: acd_maxflow_add_tweights(g, i, cap_source, cap_sink) adds capacity from the
 *     source to i and from i to the sink (calls accumulate);
 *   - n-links: acd_maxflow_add_edge(g, i, j, cap, rev_cap) adds an arc i->j of capacity cap and
 *     an arc j->i of capacity rev_cap (calls add parallel arcs).
 * Capacities are finite doubles >= 0. For an "infinite" t-link use a finite value larger than
 * the sum of all other capacities (spec A17): the solver never needs inf.
 *
 * acd_maxflow_solve() returns the maximum flow value. After it, acd_maxflow_is_source(g, i)
 * says whether node i is in the source set of the minimum cut: the set of nodes reachable from
 * the source in the residual graph. That set is the same for every maximum flow (the unique
 * minimal minimum cut), so the answer does not depend on augmentation order. The whole
 * computation is deterministic: it depends only on the sequence of calls.
 *
 * One graph can be solved once; acd_maxflow_reset() empties it (keeping its memory) so that
 * a new graph can be built in the same object. */
#ifndef ACD_CORISE_MAXFLOW_H
#define ACD_CORISE_MAXFLOW_H

#include <stddef.h>

#include "acd/base.h"
#include "acd3/poll.h"

typedef struct acd_maxflow acd_maxflow;

/* Largest number of nodes and of n-link calls a graph may hold. */
#define ACD_MAXFLOW_MAX_NODES ((size_t)0x3fffffff)
#define ACD_MAXFLOW_MAX_EDGES ((size_t)0x3fffffff)

/* Creates an empty graph; node_hint and edge_hint (n-link calls) size the first allocation and
 * may be 0. Free with acd_maxflow_free(). */
acd_status acd_maxflow_create(acd_maxflow **out, size_t node_hint, size_t edge_hint, acd_error *err);
void acd_maxflow_free(acd_maxflow *g);

/* Empties the graph (no nodes, no arcs, no flow), keeping the allocated memory. */
void acd_maxflow_reset(acd_maxflow *g);

/* Adds n nodes with no links; *first (may be NULL) receives the index of the first one. */
acd_status acd_maxflow_add_nodes(acd_maxflow *g, size_t n, size_t *first, acd_error *err);

size_t acd_maxflow_node_count(const acd_maxflow *g);

/* Adds capacity cap_source on the t-link source->i and cap_sink on i->sink. */
acd_status acd_maxflow_add_tweights(acd_maxflow *g, size_t i, double cap_source, double cap_sink,
                                    acd_error *err);

/* Adds an arc i->j of capacity cap and j->i of capacity rev_cap (i != j). */
acd_status acd_maxflow_add_edge(acd_maxflow *g, size_t i, size_t j, double cap, double rev_cap,
                                acd_error *err);

/* Computes a maximum flow; *flow receives its value (the minimum cut capacity). Can be called
 * once per graph; a second call without reset fails with ACD_ERR_INVALID_ARGUMENT. */
acd_status acd_maxflow_solve(acd_maxflow *g, double *flow, acd_error *err);

/* The same, polling poll (may be NULL; acd3/poll) every ACD_MAXFLOW_POLL_STEPS growth steps:
 * when it says stop, ACD_ERR_CANCELLED (the graph is then neither solved nor usable: reset or free
 * it). The flow and the cut are the same with or without a poll. */
#define ACD_MAXFLOW_POLL_STEPS 4096
acd_status acd_maxflow_solve_poll(acd_maxflow *g, double *flow, acd3_poll *poll, acd_error *err);

/* After solve: 1 if node i is on the source side of the minimal minimum cut, else 0. */
int acd_maxflow_is_source(const acd_maxflow *g, size_t i);

#endif
