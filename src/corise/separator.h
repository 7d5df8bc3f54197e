/* corise/separator: residual concavity and valley separators, CoRiSe §4.2 (Eq. 3), §4.3 and §5.1
 * (Liu, Xi, Lien, CAD 2016); spec corise.md §1.7-1.9 and §2.5 (0-based reformulation).
 *
 * For a deep valley v_0..v_{n-1} (indices into its chain), with C(V[s..t]) the concavity of the
 * sub-chain against its own new bridge (v_s, v_t) (acd_corise_chain_concavity, spec A6):
 *   P(m) = C(V[0..m]), S(m) = C(V[m..n-1]), RC(m) = max(P(m), S(m)), 0 < m < n-1.
 * V-shaped (some RC(m) <= tau): one separator s, the vertex of largest concavity against the
 * original bridge, replaced by argmin RC when RC(s) > tau (spec A8).
 * U-shaped otherwise: i = the largest m with P(m) <= tau, j = the smallest m with S(m) <= tau
 * (spec A7), k = the best split of the shallow prefix V[0..i], g = the best split of the shallow
 * suffix V[j..n-1] (argmin of the max of the two pieces' concavities); the valley becomes
 * V[0..k], V[k..g] (the bottom, fuzzy) and V[g..n-1]. If i >= j (non-monotone P, S), it is
 * treated as V-shaped with s = argmin RC.
 * Ties everywhere: larger concavity against the original bridge, then smaller index.
 * Shallow and deep follow spec A9: shallow iff C <= tau. */
#ifndef ACD_CORISE_SEPARATOR_H
#define ACD_CORISE_SEPARATOR_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"

typedef struct acd_corise_split {
    int ushaped;      /* 0: V-shaped, one separator (first == second); 1: U-shaped */
    size_t first;     /* V: the separator s; U: k */
    size_t second;    /* V: s; U: g (first < second) */
    double residual;  /* V: RC(s); U: the larger concavity of V[0..k], V[g..n-1] */
} acd_corise_split;

/* Splits the chain vertices[chain[0..n)] (n >= 3). Costs O(n^2) concavity evaluations' worth of
 * work (each O(n) for x-monotone pieces). */
acd_status acd_corise_valley_split(const double *vertices, const uint32_t *chain, size_t n, double tau,
                                   acd_corise_split *out, acd_error *err);

#endif
