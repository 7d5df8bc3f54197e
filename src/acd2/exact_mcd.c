/* acd2/exact_mcd: minimum convex decomposition (MCD) of a simple polygon, no Steiner points.
 *
 * J. M. Keil and J. Snoeyink, "On the time bound for convex decomposition of simple polygons",
 * Int. J. Comput. Geom. Appl. 12(3), 2002 (after J. M. Keil, "Decomposing a polygon into simpler
 * components", SIAM J. Comput. 14, 1985). The dissertation's Table 3 (IV.D.3) compares ACD with this
 * decomposition (Snoeyink's code, [71], [122]); this is our own implementation of the paper's
 * dynamic programming, with exact predicates.
 *
 * Facts used (n vertices 0..n-1 counterclockwise, r reflex vertices):
 *   - In a minimum decomposition every diagonal has a reflex endpoint (a diagonal between two convex
 *     vertices can be removed, the merged piece stays convex). So only "reflex" diagonals are
 *     subproblems: for a valid diagonal (i, k), i < k, with i or k reflex, P(i,k) is the polygon
 *     i, i+1, .., k; w(i,k) is the minimum number of convex pieces of P(i,k) and S(i,k) the set of
 *     pairs (s, t) such that some minimum decomposition has the piece C containing edge ik with
 *     vertices i, s, .., t, k; only non-dominated pairs are kept (larger s and smaller t make C
 *     narrower at i and k), a staircase sorted by s (t then increases too).
 *   - A diagonal with one reflex end keeps one pair: the angle condition at its convex end always
 *     holds (a merged piece stays inside the polygon's angle there, < 180 degrees), so only the
 *     narrowest pair at the reflex end can be chosen (largest s when i is reflex, smallest t when k
 *     is). On the 2560-vertex star this cuts the stored pairs from 28 million to 2.3 million.
 *   - Only minimum-weight decompositions of a subproblem matter: one more piece can always be had by
 *     not merging across the diagonal at all (Keil-Snoeyink, Lemma on weights).
 *   - Type A (i reflex): j is the vertex of C before k. C = C' + triangle(i, j, k) where C' is the
 *     ij-piece of P(i,j) (merged: needs a pair (s,t) of S(i,j) with orient(t, j, k) >= 0 and
 *     orient(k, i, s) >= 0; cost w(i,j) + w(j,k); new pair (s, j)) or C = triangle (not merged;
 *     cost w(i,j) + 1 + w(j,k); pair (j, j)). (j, k) must be an edge or a reflex diagonal.
 *   - Type B (k reflex): j is the vertex of C after i; symmetric with P(j,k) merged at j and k
 *     (orient(i, j, s) >= 0, orient(t, k, i) >= 0; new pair (j, t)).
 *   - Rotating the polygon so that vertex 0 is reflex makes P = P(0, n-1) a subproblem itself.
 *
 * design:
 *   1. Work order: the ring counterclockwise, rotated to start at a reflex vertex (exact orient2d;
 *      flat vertices are convex). No reflex vertex: one piece.
 *   2. Visibility from each reflex vertex v in O(n): a walk of the triangulation's dual tree from the
 *      triangles around v, narrowing a cone bounded by two polygon vertices at each crossed
 *      diagonal (exact orient2d; a vertex on a cone boundary is hidden, as the segment would touch
 *      another vertex). Kept as sorted lists and bit rows.
 *   3. Reflex diagonals in order (i decreasing, k increasing), so w(i,j) (j < k) and w(j,k) (j > i)
 *      are known. Candidates j are read off the shorter of the two visibility lists restricted to
 *      (i, k) (or the reflex list when the far end is convex). The pair scans are exact.
 *   4. Reconstruction from the root's first pair: each piece's vertices are collected along the
 *      merges; every non-merged subproblem is a diagonal and a new piece.
 *   Collinear vertices (the paper assumes general position; docs/exact2d.md): straight boundary
 *   chains act as edges (fwd/bwd); "composite" piece sides made of collinear hops (edges and
 *   reflex diagonals, found through an exact angular order of each vertex's connections) have
 *   their hops decomposed separately (pair types C, D); a 180-degree piece vertex k (or i) makes
 *   the chord (i, j) pass through it, and such "weak" chords get entries of their own in a hash
 *   map, computed on first use (pair types F, G).
 * Time O(sum over reflex diagonals of their candidate counts times staircase lengths), at most
 * O(n r^2) candidates as in the paper; memory O(r n) bits plus the staircases. */
#include "acd2/exact_mcd.h"

#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/predicates.h"
#include "geom2/triangulate.h"

#define NONE ((size_t)-1)
#define V2(p) ((const double *)(const void *)(p))

/* Compact records (32-bit vertex and pool indices; the polygon is refused above UINT32_MAX - 1
 * vertices): the staircases are the bulk of the memory on polygons with many notches. */
#define PNONE UINT32_MAX

typedef struct mcd_pair {
    uint32_t s, t, j, child; /* child: pool index of the merged pair, PNONE if none */
    char type;               /* 'A' .. 'G' */
} mcd_pair;

typedef struct mcd_entry {
    int32_t w;              /* -1: not computed or no decomposition, -2: weak entry in progress */
    uint32_t first, count;  /* the staircase: pool[first .. first + count) */
    uint32_t s1, t1;        /* count == 1: the pair's s and t (read without touching the pool) */
} mcd_entry;

static mcd_pair mkpair(size_t s, size_t t, size_t j, size_t child, char type) {
    mcd_pair p = {(uint32_t)s, (uint32_t)t, (uint32_t)j, child == NONE ? PNONE : (uint32_t)child, type};
    return p;
}

static size_t child_of(const mcd_pair *p) {
    return p->child == PNONE ? NONE : p->child;
}

typedef struct mcd_opt {
    long cost;
    mcd_pair pr;
} mcd_opt;

typedef struct mcd {
    size_t n;
    acd_vec2 *wp; /* work points */
    unsigned char *reflex;
    size_t *fwd, *bwd; /* straight runs: a..fwd[a] and bwd[b]..b are straight boundary chains */
    size_t *row, nrows, *rl; /* row of a reflex vertex; reflex list (sorted) */
    uint64_t *bits;
    size_t words;
    size_t *vstart, *vlist; /* visibility lists per row, sorted */
    mcd_entry *ent;
    uint32_t *rank; /* per row and bit word: set bits of the row before the word (NULL: use hkey) */
    uint64_t *hkey; /* (i, k) -> entry index, open addressing; key i * n + k + 1, 0 = empty */
    size_t *hval, hmask;
    mcd_entry root;
    mcd_pair *pool;
    size_t npool, cpool;
    mcd_opt *opt;
    size_t nopt, copt;
    long bound; /* the smallest option cost of the subproblem being computed, so far */
    /* row cache of the DP's current i: crow[j] = index of the entry (i, j), j > i, PNONE if (i, j)
     * is not a reflex diagonal; cset lists the j set */
    size_t ci, ncset;
    uint32_t *crow, *cset;
    /* straight composites: chains i = x0 < x1 < .. < xm = j of collinear vertices, each hop an edge
     * or a reflex diagonal; cont maps a hop (a, b) to the next vertex c of its line */
    size_t *tstart, *ta, *tc;        /* per b: (a, c) sorted by a: a-b-c collinear, b between */
    size_t ntrip;
    size_t *cstart, *cang, *chalf; /* per vertex: its connections sorted by angle; first of half 1 */
    /* weak entries: chords (i, j) through a vertex outside i..j (a flat vertex of a piece) */
    size_t *wkey_i, *wkey_j, *wslot, wcap;
    mcd_entry *went;
    size_t nwent, cwent;
    size_t *fstart, *cbyf;           /* composites by start vertex */
    size_t *estart, *cbye;           /* composites by end vertex */
    size_t (*comp)[4];               /* (start, end, first hop, last hop) */
    size_t ncomp;
} mcd;

static const double *W(const mcd *m, size_t i) {
    return V2(&m->wp[i]);
}

static int bit(const mcd *m, size_t a, size_t b) {
    size_t r = m->row[a];
    return r != NONE && ((m->bits[r * m->words + b / 64] >> (b % 64)) & 1u);
}

/* (a, b), a < b - 1: a valid diagonal with a reflex endpoint. */
static int reflex_diag(const mcd *m, size_t a, size_t b) {
    return bit(m, a, b) || bit(m, b, a);
}

/* first position in sorted v[lo..hi) with v[pos] >= x */
static size_t lower(const size_t *v, size_t lo, size_t hi, size_t x) {
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (v[mid] < x) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

static size_t hslot(const mcd *m, uint64_t key) {
    return (size_t)((key * 0x9E3779B97F4A7C15ull) >> 17) & m->hmask;
}

static unsigned popcount64(uint64_t x) {
    x = x - ((x >> 1) & 0x5555555555555555ull);
    x = (x & 0x3333333333333333ull) + ((x >> 2) & 0x3333333333333333ull);
    x = (x + (x >> 4)) & 0x0F0F0F0F0F0F0F0Full;
    return (unsigned)((x * 0x0101010101010101ull) >> 56);
}

/* The table entry of the reflex diagonal (i, k), i < k; NULL if it is not one. The entry of
 * (i, k) sits at the position of the other end in the owner's visibility list (owner k if
 * reflex, else i: for a notch k all entries (j, k) are contiguous, read so by type B), which is
 * the rank of that bit in the owner's bit row: a prefix count per 64-bit word plus a popcount,
 * next to the bit just tested (the hash is the fallback). */
static mcd_entry *entry_of(mcd *m, size_t i, size_t k) {
    if (m->rank) {
        size_t a = m->reflex[k] ? k : i, b = a == i ? k : i, r = m->row[a];
        if (r == NONE) return NULL;
        size_t w = r * m->words + b / 64;
        uint64_t word = m->bits[w], mask = (uint64_t)1 << (b % 64);
        if (!(word & mask)) return NULL;
        return &m->ent[m->vstart[r] + m->rank[w] + popcount64(word & (mask - 1))];
    }
    uint64_t key = (uint64_t)i * m->n + k + 1;
    for (size_t h = hslot(m, key);; h = (h + 1) & m->hmask) {
        if (m->hkey[h] == key) return &m->ent[m->hval[h]];
        if (m->hkey[h] == 0) return NULL;
    }
}

/* The entry of (i, j), i < j, through the row cache when i is the DP's current row. */
static mcd_entry *eij_of(mcd *m, size_t i, size_t j) {
    if (i == m->ci) return m->crow[j] == PNONE ? NULL : &m->ent[m->crow[j]];
    return entry_of(m, i, j);
}

/* reflex_diag(m, i, j), i < j, through the row cache when it applies. */
static int rdiag_i(const mcd *m, size_t i, size_t j) {
    return i == m->ci ? m->crow[j] != PNONE : reflex_diag(m, i, j);
}

/* Points the row cache at row i (the entries (i, j), j > i). */
static void set_row(mcd *m, size_t i) {
    for (size_t z = 0; z < m->ncset; z++) m->crow[m->cset[z]] = PNONE;
    m->ncset = 0;
    m->ci = i;
    size_t r = m->row[i];
    if (r != NONE) {
        for (size_t q = lower(m->vlist, m->vstart[r], m->vstart[r + 1], i + 1); q < m->vstart[r + 1]; q++) {
            size_t j = m->vlist[q];
            if (m->reflex[j]) {
                /* a notch-notch entry lives in the larger end's row; on degenerate input (collinear
                 * and repeated points) j's list may lack i, and there is no entry (fuzz_exact2d) */
                mcd_entry *e = entry_of(m, i, j);
                if (!e) continue;
                m->crow[j] = (uint32_t)(e - m->ent);
            } else {
                m->crow[j] = (uint32_t)q;
            }
            m->cset[m->ncset++] = (uint32_t)j;
        }
    } else {
        for (size_t z = lower(m->rl, 0, m->nrows, i + 1); z < m->nrows; z++) {
            size_t k = m->rl[z];
            mcd_entry *e = bit(m, k, i) ? entry_of(m, i, k) : NULL;
            if (!e) continue;
            m->crow[k] = (uint32_t)(e - m->ent);
            m->cset[m->ncset++] = (uint32_t)k;
        }
    }
}

/* The rank index of the bit rows; left NULL (the hash is used) when a row's list does not match
 * its bits one to one or the counts do not fit 32 bits. Returns 0 on out of memory. */
static int build_rank(mcd *m) {
    size_t nw = m->nrows * m->words;
    if (m->n > UINT32_MAX) return 1;
    uint32_t *rank = malloc((nw ? nw : 1) * sizeof *rank);
    if (!rank) return 0;
    for (size_t r = 0; r < m->nrows; r++) {
        uint32_t c = 0;
        for (size_t w = 0; w < m->words; w++) {
            rank[r * m->words + w] = c;
            c += popcount64(m->bits[r * m->words + w]);
        }
        if (c != m->vstart[r + 1] - m->vstart[r]) {
            free(rank);
            return 1;
        }
    }
    m->rank = rank;
    return 1;
}

/* Fills the entry hash from the visibility rows (owner of (i, k): k if reflex, else i). */
static int build_entry_hash(mcd *m) {
    if (!build_rank(m)) return 0;
    if (m->rank) return 1;
    size_t nv = m->vstart[m->nrows], cap = 16;
    while (cap < 2 * nv + 2) cap *= 2;
    m->hkey = calloc(cap, sizeof *m->hkey);
    m->hval = malloc(cap * sizeof *m->hval);
    if (!m->hkey || !m->hval) return 0;
    m->hmask = cap - 1;
    for (size_t r = 0; r < m->nrows; r++) {
        size_t a = m->rl[r];
        for (size_t q = m->vstart[r]; q < m->vstart[r + 1]; q++) {
            size_t b = m->vlist[q], i = a < b ? a : b, k = a < b ? b : a;
            if ((m->reflex[k] ? k : i) != a) continue;
            uint64_t key = (uint64_t)i * m->n + k + 1;
            size_t h = hslot(m, key);
            while (m->hkey[h]) h = (h + 1) & m->hmask;
            m->hkey[h] = key;
            m->hval[h] = q;
        }
    }
    return 1;
}

/* Adds an option of the subproblem being computed; one costing more than an option already
 * found cannot be in its staircase and is dropped. */
static int push_opt(mcd *m, long cost, mcd_pair pr) {
    if (cost > m->bound) return 1;
    m->bound = cost;
    if (m->nopt == m->copt) {
        size_t c = m->copt ? 2 * m->copt : 64;
        mcd_opt *o = realloc(m->opt, c * sizeof *o);
        if (!o) return 0;
        m->opt = o;
        m->copt = c;
    }
    m->opt[m->nopt].cost = cost;
    m->opt[m->nopt].pr = pr;
    m->nopt++;
    return 1;
}

static int half_of(const double *o, const double *p) {
    return (p[1] > o[1] || (p[1] == o[1] && p[0] > o[0])) ? 0 : 1;
}

/* The connection of b opposite to its connection a (a, b, c collinear, b between), or NONE. */
static size_t opp(const mcd *m, size_t a, size_t b) {
    size_t lo = m->tstart[b], hi = m->tstart[b + 1];
    size_t pos = lower(m->ta, lo, hi, a);
    return pos < hi && m->ta[pos] == a ? m->tc[pos] : NONE;
}

/* The connection c of b with a, b, c collinear and b between (a any vertex), or NONE. */
static size_t opp_dir(const mcd *m, size_t a, size_t b) {
    const size_t *ang = m->cang + m->cstart[b];
    size_t u = m->cstart[b + 1] - m->cstart[b], h1 = m->chalf[b];
    int ha = half_of(W(m, b), W(m, a));
    size_t x = ha == 0 ? h1 : 0, end = ha == 0 ? u : h1, y = end;
    while (x < y) {
        size_t mid = x + (y - x) / 2;
        if (acd_orient2d_sign(W(m, b), W(m, a), W(m, ang[mid])) <= 0) y = mid;
        else x = mid + 1;
    }
    if (x < end && acd_orient2d_sign(W(m, b), W(m, a), W(m, ang[x])) == 0) return ang[x];
    return NONE;
}

/* The vertex after b on the line a -> b (a < b), or NONE. */
static size_t cont(const mcd *m, size_t a, size_t b) {
    size_t c = opp(m, a, b);
    return c != NONE && c > b ? c : NONE;
}

/* Weight of the separate subproblems along a composite (sum over its hops); -1 if unknown. */
static long comp_cost(mcd *m, const size_t *c) {
    long w = 0;
    size_t prev = c[0], cur = c[2];
    for (;;) {
        if (cur > prev + 1) {
            mcd_entry *e = entry_of(m, prev, cur);
            if (!e || e->w < 0) return -1;
            w += e->w;
        }
        if (cur == c[1]) return w;
        size_t nx = cont(m, prev, cur);
        if (nx == NONE || nx > c[1]) return -1;
        prev = cur;
        cur = nx;
    }
}

/* Composite options: type A with C = (i, x1, .., j, k) (the side i..j straight) and type B with
 * C = (i, j, .., k) (the side j..k straight). */
static int composite_options(mcd *m, size_t i, size_t k) {
    if (m->reflex[i])
        for (size_t q = m->fstart[i]; q < m->fstart[i + 1]; q++) {
            const size_t *c = m->comp[m->cbyf[q]];
            size_t j = c[1];
            if (j >= k || !(j >= m->bwd[k] || reflex_diag(m, j, k))) continue;
            if (acd_orient2d_sign(W(m, i), W(m, j), W(m, k)) <= 0) continue;
            long wc = comp_cost(m, c), wjk = 0;
            if (wc < 0) continue;
            if (j < m->bwd[k]) {
                mcd_entry *e = entry_of(m, j, k);
                if (!e || e->w < 0) continue;
                wjk = e->w;
            }
            mcd_pair pr = mkpair(c[2], j, j, NONE, 'C');
            if (!push_opt(m, wc + wjk + 1, pr)) return 0;
        }
    if (m->reflex[k])
        for (size_t q = m->estart[k]; q < m->estart[k + 1]; q++) {
            const size_t *c = m->comp[m->cbye[q]];
            size_t j = c[0];
            if (j <= i || !(j <= m->fwd[i] || reflex_diag(m, i, j))) continue;
            if (acd_orient2d_sign(W(m, i), W(m, j), W(m, k)) <= 0) continue;
            long wc = comp_cost(m, c), wij = 0;
            if (wc < 0) continue;
            if (j > m->fwd[i]) {
                mcd_entry *e = entry_of(m, i, j);
                if (!e || e->w < 0) continue;
                wij = e->w;
            }
            mcd_pair pr = mkpair(j, c[3], j, c[2], 'D');
            if (!push_opt(m, wij + wc + 1, pr)) return 0;
        }
    return 1;
}

/* The staircase pair of entry e to merge in type A at (i, j, k): the largest s with
 * orient(t, j, k) >= 0 (a prefix of the staircase, t grows with s) and orient(k, i, s) >= 0 (a suffix).
 * Binary search for the prefix end, checked; a linear scan if the check fails. NONE if none. */
static size_t merge_a(const mcd *m, const mcd_entry *e, size_t i, size_t j, size_t k) {
    if (e->count == 1) /* the condition at j holds when j is convex (see the pruning above) */
        return (!m->reflex[j] || acd_orient2d_sign(W(m, e->t1), W(m, j), W(m, k)) >= 0) &&
                       acd_orient2d_sign(W(m, k), W(m, i), W(m, e->s1)) >= 0
                   ? e->first
                   : NONE;
    size_t lo = e->first, hi = e->first + e->count;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (acd_orient2d_sign(W(m, m->pool[mid].t), W(m, j), W(m, k)) >= 0) lo = mid + 1;
        else hi = mid;
    }
    if (lo > e->first) {
        const mcd_pair *c = &m->pool[lo - 1];
        if (acd_orient2d_sign(W(m, k), W(m, i), W(m, c->s)) >= 0) return lo - 1;
    }
    size_t best = NONE; /* not monotone (collinear pairs): exact scan */
    for (size_t q = e->first; q < e->first + e->count; q++) {
        const mcd_pair *c = &m->pool[q];
        if (best != NONE && c->s <= m->pool[best].s) continue;
        if (acd_orient2d_sign(W(m, c->t), W(m, j), W(m, k)) >= 0 &&
            acd_orient2d_sign(W(m, k), W(m, i), W(m, c->s)) >= 0)
            best = q;
    }
    return best;
}

/* Type B: the smallest t with orient(i, j, s) >= 0 (a suffix) and orient(t, k, i) >= 0 (a prefix). */
static size_t merge_b(const mcd *m, const mcd_entry *e, size_t i, size_t j, size_t k) {
    if (e->count == 1)
        return (!m->reflex[j] || acd_orient2d_sign(W(m, i), W(m, j), W(m, e->s1)) >= 0) &&
                       acd_orient2d_sign(W(m, e->t1), W(m, k), W(m, i)) >= 0
                   ? e->first
                   : NONE;
    size_t lo = e->first, hi = e->first + e->count;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (acd_orient2d_sign(W(m, i), W(m, j), W(m, m->pool[mid].s)) >= 0) hi = mid;
        else lo = mid + 1;
    }
    if (lo < e->first + e->count) {
        const mcd_pair *c = &m->pool[lo];
        if (acd_orient2d_sign(W(m, c->t), W(m, k), W(m, i)) >= 0) return lo;
    }
    size_t best = NONE;
    for (size_t q = e->first; q < e->first + e->count; q++) {
        const mcd_pair *c = &m->pool[q];
        if (best != NONE && c->t >= m->pool[best].t) continue;
        if (acd_orient2d_sign(W(m, i), W(m, j), W(m, c->s)) >= 0 &&
            acd_orient2d_sign(W(m, c->t), W(m, k), W(m, i)) >= 0)
            best = q;
    }
    return best;
}

/* Type A option for (i, k) through j; eij / ejk are the table entries when the caller knows them
 * (NULL: looked up). Returns 0 on out of memory. */
static int option_a(mcd *m, size_t i, size_t j, size_t k, const mcd_entry *eij, const mcd_entry *ejk) {
    long wjk = 0;
    if (j < m->bwd[k]) {
        const mcd_entry *e = ejk ? ejk : entry_of(m, j, k);
        if (!e || e->w < 0) return 1;
        wjk = e->w;
    }
    mcd_pair pr = mkpair(j, j, j, NONE, 'A');
    if (j <= m->fwd[i]) return push_opt(m, wjk + 1, pr);
    const mcd_entry *e = eij ? eij : eij_of(m, i, j);
    if (!e || e->w < 0 || wjk + e->w > m->bound) return 1; /* costs more than an option found */
    size_t best = merge_a(m, e, i, j, k);
    if (best != NONE) {
        pr.s = e->count == 1 ? e->s1 : m->pool[best].s;
        pr.child = (uint32_t)best;
        return push_opt(m, wjk + e->w, pr);
    }
    return push_opt(m, wjk + e->w + 1, pr);
}

static int option_b(mcd *m, size_t i, size_t j, size_t k, const mcd_entry *eij, const mcd_entry *ejk) {
    long wij = 0;
    if (j > m->fwd[i]) {
        const mcd_entry *e = eij ? eij : eij_of(m, i, j);
        if (!e || e->w < 0) return 1;
        wij = e->w;
    }
    mcd_pair pr = mkpair(j, j, j, NONE, 'B');
    if (j >= m->bwd[k]) return push_opt(m, wij + 1, pr);
    const mcd_entry *e = ejk ? ejk : entry_of(m, j, k);
    if (!e || e->w < 0 || wij + e->w > m->bound) return 1;
    size_t best = merge_b(m, e, i, j, k);
    if (best != NONE) {
        pr.t = e->count == 1 ? e->t1 : m->pool[best].t;
        pr.child = (uint32_t)best;
        return push_opt(m, wij + e->w, pr);
    }
    return push_opt(m, wij + e->w + 1, pr);
}

/* Options of equal cost sorted by s, then t (staircase order). */
static int cmp_pair_s(const void *a, const void *b) {
    const mcd_opt *x = a, *y = b;
    if (x->pr.s != y->pr.s) return x->pr.s < y->pr.s ? -1 : 1;
    if (x->pr.t != y->pr.t) return x->pr.t < y->pr.t ? -1 : 1;
    return (x->pr.type > y->pr.type) - (x->pr.type < y->pr.type);
}

/* Range of the sorted list of reflex row r (or the reflex list when r == NONE) strictly between
 * lo and hi. */
static void list_range(const mcd *m, size_t r, size_t lo, size_t hi, const size_t **v, size_t *a, size_t *b) {
    if (r == NONE) {
        *v = m->rl;
        *a = lower(m->rl, 0, m->nrows, lo + 1);
        *b = lower(m->rl, 0, m->nrows, hi);
    } else {
        *v = m->vlist;
        *a = lower(m->vlist, m->vstart[r], m->vstart[r + 1], lo + 1);
        *b = lower(m->vlist, m->vstart[r], m->vstart[r + 1], hi);
    }
    if (*b < *a) *b = *a;
}

static int flat_options(mcd *m, size_t i, size_t k);

static int compute_options(mcd *m, size_t i, size_t k, mcd_entry *out, int prune);

/* Computes the entry of subproblem (i, k) (re-entered for weak entries: the bound is saved). */
static int compute(mcd *m, size_t i, size_t k, mcd_entry *out, int prune) {
    long saved = m->bound;
    m->bound = LONG_MAX;
    int ok = compute_options(m, i, k, out, prune);
    m->bound = saved;
    return ok;
}

static int compute_options(mcd *m, size_t i, size_t k, mcd_entry *out, int prune) {
    size_t base = m->nopt; /* options stack: a weak entry may be computed inside (flat_options) */
    const size_t *va, *vb;
    size_t a0, a1, b0, b1;
    size_t fi = m->fwd[i] < k ? m->fwd[i] : k - 1, bk = m->bwd[k] > i ? m->bwd[k] : i + 1;
    if (m->reflex[i]) {
        /* j on the straight chain from i ((i, j) boundary) or on the one into k ((j, k) boundary) */
        for (size_t j = i + 1; j <= fi; j++)
            if ((j >= m->bwd[k] || reflex_diag(m, j, k)) && !option_a(m, i, j, k, NULL, NULL)) return 0;
        for (size_t j = bk > fi + 1 ? bk : fi + 1; j < k; j++)
            if (bit(m, i, j) && !option_a(m, i, j, k, NULL, NULL)) return 0;
        list_range(m, m->row[i], fi, bk, &va, &a0, &a1);
        list_range(m, m->reflex[k] ? m->row[k] : NONE, fi, bk, &vb, &b0, &b1);
        if (a1 - a0 <= b1 - b0) {
            /* va = vis(i); the entry (i, j) from the row cache */
            for (size_t q = a0; q < a1; q++)
                if (reflex_diag(m, va[q], k) && !option_a(m, i, va[q], k, NULL, NULL)) return 0;
        } else {
            /* vb = vis(k) (k reflex: the entry (j, k) is at the same position) or the notches */
            int vk = m->reflex[k] != 0;
            for (size_t q = b0; q < b1; q++) {
                size_t j = vb[q];
                if (bit(m, i, j) && reflex_diag(m, j, k) &&
                    !option_a(m, i, j, k, NULL, vk ? &m->ent[q] : NULL))
                    return 0;
            }
        }
    }
    if (m->reflex[k]) {
        for (size_t j = bk; j < k; j++)
            if ((j <= m->fwd[i] || rdiag_i(m, i, j)) && !option_b(m, i, j, k, NULL, NULL)) return 0;
        for (size_t j = i + 1; j <= fi && j < bk; j++)
            if (bit(m, k, j) && !option_b(m, i, j, k, NULL, NULL)) return 0;
        list_range(m, m->row[k], fi, bk, &va, &a0, &a1);
        list_range(m, m->reflex[i] ? m->row[i] : NONE, fi, bk, &vb, &b0, &b1);
        if (a1 - a0 <= b1 - b0) {
            /* va = vis(k): the entry (j, k) is at the same position */
            for (size_t q = a0; q < a1; q++) {
                size_t j = va[q];
                if (rdiag_i(m, i, j) && !option_b(m, i, j, k, NULL, &m->ent[q])) return 0;
            }
        } else {
            for (size_t q = b0; q < b1; q++) {
                size_t j = vb[q];
                if (bit(m, k, j) && rdiag_i(m, i, j) && !option_b(m, i, j, k, NULL, NULL))
                    return 0;
            }
        }
    }
    if (m->ncomp && !composite_options(m, i, k)) return 0;
    if (m->cang && !flat_options(m, i, k)) return 0;
    out->w = -1;
    out->first = (uint32_t)m->npool;
    out->count = 0;
    size_t nopt = m->nopt - base;
    m->nopt = base;
    if (!nopt) return 1; /* no decomposition of this kind: the entry stays unusable */
    mcd_opt *opt = m->opt + base; /* (after the check: m->opt is still NULL when no option was ever made) */
    long best = opt[0].cost;
    for (size_t q = 1; q < nopt; q++)
        if (opt[q].cost < best) best = opt[q].cost;
    size_t nk = 0;
    for (size_t q = 0; q < nopt; q++)
        if (opt[q].cost == best) opt[nk++] = opt[q];
    size_t keep = 0, top = nk;
    if (prune && m->reflex[i] != m->reflex[k]) {
        /* one reflex end: the angle condition at the convex end always holds (the merged piece
         * stays inside the polygon's angle there), so only the narrowest pair at the reflex end is
         * ever chosen: the staircase's last (largest s) when i is reflex, its first (smallest t)
         * when k is; picked in one pass, ties as the stable sort below would leave them */
        size_t b = 0;
        for (size_t q = 1; q < nk; q++) {
            const mcd_pair *x = &opt[q].pr, *y = &opt[b].pr;
            if (m->reflex[i] ? cmp_pair_s(&opt[q], &opt[b]) >= 0
                             : x->t < y->t || (x->t == y->t && (x->s > y->s || (x->s == y->s && x->type >= y->type))))
                b = q;
        }
        opt[0] = opt[b];
        top = 0;
        nk = keep = 1;
    } else {
        qsort(opt, nk, sizeof *opt, cmp_pair_s);
        /* non-dominated: scanning s downwards, keep strictly decreasing t; the kept ones are packed
         * at the top (positions already visited), ending as opt[nk - keep .. nk) in staircase order */
        size_t mint = NONE;
        for (size_t q = nk; q-- > 0;)
            if (mint == NONE || opt[q].pr.t < mint) {
                mint = opt[q].pr.t;
                opt[--top] = opt[q];
                keep++;
            }
    }
    if (m->npool + keep >= PNONE) return 0; /* 32-bit pool indices */
    if (m->npool + keep > m->cpool) {
        size_t c = m->cpool ? m->cpool : 1024;
        while (c < m->npool + keep) c *= 2;
        mcd_pair *p = realloc(m->pool, c * sizeof *p);
        if (!p) return 0;
        m->pool = p;
        m->cpool = c;
    }
    for (size_t q = top; q < nk; q++) m->pool[m->npool++] = opt[q].pr;
    out->w = (int32_t)best;
    out->count = (uint32_t)keep;
    out->s1 = m->pool[out->first].s;
    out->t1 = m->pool[out->first].t;
    return 1;
}

/* Weak entry of chord (i, j) (computed on first use); *idx = NONE when it has no decomposition or is
 * being computed. Returns 0 on out of memory. */
static int weak_get(mcd *m, size_t i, size_t j, size_t *idx) {
    *idx = NONE;
    if (2 * (m->nwent + 1) > m->wcap) {
        size_t cap = m->wcap ? 2 * m->wcap : 64;
        size_t *ki = malloc(cap * sizeof *ki), *kj = malloc(cap * sizeof *kj), *sl = malloc(cap * sizeof *sl);
        if (!ki || !kj || !sl) {
            free(ki);
            free(kj);
            free(sl);
            return 0;
        }
        for (size_t z = 0; z < cap; z++) sl[z] = NONE;
        for (size_t z = 0; z < m->wcap; z++)
            if (m->wslot[z] != NONE) {
                size_t h = (m->wkey_i[z] * 1000003u + m->wkey_j[z]) & (cap - 1);
                while (sl[h] != NONE) h = (h + 1) & (cap - 1);
                ki[h] = m->wkey_i[z];
                kj[h] = m->wkey_j[z];
                sl[h] = m->wslot[z];
            }
        free(m->wkey_i);
        free(m->wkey_j);
        free(m->wslot);
        m->wkey_i = ki;
        m->wkey_j = kj;
        m->wslot = sl;
        m->wcap = cap;
    }
    size_t h = (i * 1000003u + j) & (m->wcap - 1);
    while (m->wslot[h] != NONE) {
        if (m->wkey_i[h] == i && m->wkey_j[h] == j) {
            size_t e = m->wslot[h];
            if (m->went[e].w >= 0) *idx = e;
            return 1;
        }
        h = (h + 1) & (m->wcap - 1);
    }
    if (m->nwent == m->cwent) {
        size_t c = m->cwent ? 2 * m->cwent : 64;
        mcd_entry *ne = realloc(m->went, c * sizeof *ne);
        if (!ne) return 0;
        m->went = ne;
        m->cwent = c;
    }
    size_t e = m->nwent++;
    m->went[e].w = -2; /* in progress */
    m->wkey_i[h] = i;
    m->wkey_j[h] = j;
    m->wslot[h] = e;
    mcd_entry res;
    if (!compute(m, i, j, &res, 0)) return 0;
    m->went[e] = res;
    if (res.w >= 0) *idx = e;
    return 1;
}

/* Options where k (F) or i (G) is a 180-degree vertex of the piece C: C is the piece of the weak
 * chord (i, j) (resp. (j, k)) through k (resp. i), plus that vertex. */
static int flat_options(mcd *m, size_t i, size_t k) {
    size_t j = opp_dir(m, i, k), e;
    if (j != NONE && j > i && j < k) {
        long sep = 0;
        int ok = 1;
        if (j < m->bwd[k]) {
            mcd_entry *r = entry_of(m, j, k);
            if (!r || r->w < 0) ok = 0;
            else sep = r->w;
        }
        if (ok) {
            if (!weak_get(m, i, j, &e)) return 0;
            if (e != NONE) {
                const mcd_entry *we = &m->went[e];
                size_t best = we->first; /* the largest s: the last of the staircase */
                for (size_t q = we->first; q < we->first + we->count; q++)
                    if (m->pool[q].s > m->pool[best].s) best = q;
                mcd_pair pr = mkpair(m->pool[best].s, j, j, best, 'F');
                if (!push_opt(m, we->w + sep, pr)) return 0;
            }
        }
    }
    j = opp_dir(m, k, i);
    if (j != NONE && j > i && j < k) {
        long sep = 0;
        if (j > m->fwd[i]) {
            mcd_entry *r = entry_of(m, i, j);
            if (!r || r->w < 0) return 1;
            sep = r->w;
        }
        if (!weak_get(m, j, k, &e)) return 0;
        if (e != NONE) {
            const mcd_entry *we = &m->went[e];
            size_t best = we->first;
            for (size_t q = we->first; q < we->first + we->count; q++)
                if (m->pool[q].t < m->pool[best].t) best = q;
            mcd_pair pr = mkpair(j, m->pool[best].t, j, best, 'G');
            if (!push_opt(m, we->w + sep, pr)) return 0;
        }
    }
    return 1;
}

typedef struct edge_key {
    size_t a, b, he;
} edge_key;

static int cmp_key(const void *x, const void *y) {
    const edge_key *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return (p->he > q->he) - (p->he < q->he);
}

static int cmp_size(const void *x, const void *y) {
    size_t a = *(const size_t *)x, b = *(const size_t *)y;
    return (a > b) - (a < b);
}

typedef struct vis_item {
    size_t h, R, L;
} vis_item;

/* Step 2: visibility lists and bit rows of the reflex vertices. */
static acd_status visibility(mcd *m, acd_error *err) {
    size_t n = m->n, *tri = NULL, nt = 0;
    size_t ring[2] = {0, n};
    acd_status st = acd_triangulate_rings(m->wp, ring, 1, 0, &tri, &nt, NULL, NULL, err);
    if (st != ACD_OK) return st;
    size_t nh = 3 * nt;
    size_t *twin = malloc(nh * sizeof *twin), *inc_start = calloc(n + 1, sizeof *inc_start);
    size_t *inc = malloc(nh * sizeof *inc), *stamp = malloc(n * sizeof *stamp), *found = malloc(n * sizeof *found);
    edge_key *keys = malloc(nh * sizeof *keys);
    vis_item *stack = malloc((nt + 3) * sizeof *stack);
    m->words = (n + 63) / 64;
    m->bits = calloc(m->nrows * m->words + 1, sizeof *m->bits);
    m->vstart = calloc(m->nrows + 1, sizeof *m->vstart);
    size_t cap = 0, len = 0;
    size_t *list = NULL;
    if (!twin || !inc_start || !inc || !stamp || !found || !keys || !stack || !m->bits || !m->vstart) {
        st = acd_fail(err, ACD_ERR_NOMEM, "MCD: out of memory for the visibility of %zu vertices", n);
        goto done;
    }
    for (size_t h = 0; h < nh; h++) {
        size_t a = tri[h], b = tri[3 * (h / 3) + (h % 3 + 1) % 3];
        keys[h] = (edge_key){a < b ? a : b, a < b ? b : a, h};
        twin[h] = NONE;
        inc_start[a + 1]++;
    }
    qsort(keys, nh, sizeof *keys, cmp_key);
    for (size_t q = 0; q + 1 < nh; q++)
        if (keys[q].a == keys[q + 1].a && keys[q].b == keys[q + 1].b &&
            (q + 2 >= nh || keys[q + 2].a != keys[q].a || keys[q + 2].b != keys[q].b) &&
            (q == 0 || keys[q - 1].a != keys[q].a || keys[q - 1].b != keys[q].b)) {
            twin[keys[q].he] = keys[q + 1].he;
            twin[keys[q + 1].he] = keys[q].he;
        }
    for (size_t v = 0; v < n; v++) inc_start[v + 1] += inc_start[v];
    {
        size_t *fill = malloc((n + 1) * sizeof *fill);
        if (!fill) {
            st = acd_fail(err, ACD_ERR_NOMEM, "MCD: out of memory");
            goto done;
        }
        memcpy(fill, inc_start, (n + 1) * sizeof *fill);
        for (size_t h = 0; h < nh; h++) inc[fill[tri[h]]++] = h; /* half-edges leaving each vertex */
        free(fill);
    }
    for (size_t v = 0; v < n; v++) stamp[v] = NONE;
    for (size_t r = 0; r < m->nrows; r++) {
        size_t v = m->rl[r], nf = 0, sp = 0;
        const double *pv = W(m, v);
        for (size_t q = inc_start[v]; q < inc_start[v + 1]; q++) {
            size_t h0 = inc[q], t = h0 / 3, h1 = 3 * t + (h0 % 3 + 1) % 3;
            size_t a = tri[h1], b = tri[3 * t + (h0 % 3 + 2) % 3];
            if (acd_orient2d_sign(pv, W(m, a), W(m, b)) <= 0) continue;
            if (stamp[a] != v) { stamp[a] = v; found[nf++] = a; }
            if (stamp[b] != v) { stamp[b] = v; found[nf++] = b; }
            if (twin[h1] != NONE) stack[sp++] = (vis_item){twin[h1], a, b};
        }
        while (sp) {
            vis_item it = stack[--sp];
            size_t h = it.h, t = h / 3, hn = 3 * t + (h % 3 + 1) % 3, hnn = 3 * t + (h % 3 + 2) % 3;
            size_t c = tri[hnn]; /* h: x->y, hn: y->c, hnn: c->x */
            int oR = acd_orient2d_sign(pv, W(m, it.R), W(m, c)), oL = acd_orient2d_sign(pv, W(m, it.L), W(m, c));
            if (oR > 0 && oL < 0 && stamp[c] != v) {
                stamp[c] = v;
                found[nf++] = c;
            }
            if (oR > 0 && twin[hn] != NONE) stack[sp++] = (vis_item){twin[hn], it.R, oL < 0 ? c : it.L};
            if (oL < 0 && twin[hnn] != NONE) stack[sp++] = (vis_item){twin[hnn], oR > 0 ? c : it.R, it.L};
        }
        qsort(found, nf, sizeof *found, cmp_size);
        m->vstart[r] = len;
        for (size_t q = 0; q < nf; q++) {
            size_t b = found[q];
            if (b == v || b == (v + 1) % n || b == (v + n - 1) % n) continue;
            if (len == cap) {
                cap = cap ? 2 * cap : 1024;
                size_t *nl = realloc(list, cap * sizeof *nl);
                if (!nl) {
                    st = acd_fail(err, ACD_ERR_NOMEM, "MCD: out of memory for visibility lists");
                    goto done;
                }
                list = nl;
            }
            list[len++] = b;
            m->bits[r * m->words + b / 64] |= (uint64_t)1 << (b % 64);
        }
    }
    m->vstart[m->nrows] = len;
    m->vlist = list;
    list = NULL;
done:
    free(list);
    free(tri);
    free(twin);
    free(inc_start);
    free(inc);
    free(stamp);
    free(found);
    free(keys);
    free(stack);
    return st;
}

/* Exact angular order around vertex b (half-plane, then orient2d). */
static int ang_less(const mcd *m, size_t b, size_t p, size_t q) {
    const double *o = W(m, b), *a = W(m, p), *c = W(m, q);
    int hp = half_of(o, a), hq = half_of(o, c);
    if (hp != hq) return hp < hq;
    return acd_orient2d_sign(o, a, c) > 0;
}

static void ang_sort(const mcd *m, size_t b, size_t *v, size_t *tmp, size_t n) {
    if (n < 2) return;
    size_t h = n / 2;
    ang_sort(m, b, v, tmp, h);
    ang_sort(m, b, v + h, tmp, n - h);
    size_t x = 0, y = h, k = 0;
    while (x < h && y < n) tmp[k++] = ang_less(m, b, v[y], v[x]) ? v[y++] : v[x++];
    while (x < h) tmp[k++] = v[x++];
    while (y < n) tmp[k++] = v[y++];
    memcpy(v, tmp, n * sizeof *v);
}

static int grow(size_t **v, size_t *cap, size_t need) {
    if (need <= *cap) return 1;
    size_t c = *cap ? *cap : 256;
    while (c < need) c *= 2;
    size_t *nv = realloc(*v, c * sizeof *nv);
    if (!nv) return 0;
    *v = nv;
    *cap = c;
    return 1;
}

/* Straight composites (see struct mcd): the continuation table and the composite lists. */
static acd_status composites(mcd *m, acd_error *err) {
    size_t n = m->n, nv = m->vstart[m->nrows];
    size_t *cs = calloc(n + 1, sizeof *cs), *cl = malloc((2 * nv + 2 * n + 1) * sizeof *cl);
    size_t *fill = malloc((n + 1) * sizeof *fill), *tmp = malloc((2 * n + 2) * sizeof *tmp);
    size_t cta = 0, ctc = 0, ccomp = 0, nt = 0;
    size_t *comp = NULL;
    acd_status st = ACD_OK;
    m->tstart = calloc(n + 1, sizeof *m->tstart);
    m->cstart = calloc(n + 1, sizeof *m->cstart);
    m->chalf = calloc(n + 1, sizeof *m->chalf);
    m->cang = malloc((2 * nv + 2 * n + 1) * sizeof *m->cang);
    size_t ncang = 0;
    if (!cs || !cl || !fill || !tmp || !m->tstart || !m->cstart || !m->chalf || !m->cang) goto nomem;
    /* connections: edges (no wrap) and reflex diagonals, both directions */
    for (size_t r = 0; r < m->nrows; r++)
        for (size_t q = m->vstart[r]; q < m->vstart[r + 1]; q++) {
            cs[m->rl[r] + 1]++;
            cs[m->vlist[q] + 1]++;
        }
    for (size_t b = 0; b < n; b++) { /* edges, with the closing edge (n-1, 0) */
        cs[b + 1]++;
        cs[(b + 1) % n + 1]++;
    }
    for (size_t b = 0; b < n; b++) cs[b + 1] += cs[b];
    memcpy(fill, cs, (n + 1) * sizeof *fill);
    for (size_t r = 0; r < m->nrows; r++)
        for (size_t q = m->vstart[r]; q < m->vstart[r + 1]; q++) {
            cl[fill[m->rl[r]]++] = m->vlist[q];
            cl[fill[m->vlist[q]]++] = m->rl[r];
        }
    for (size_t b = 0; b < n; b++) {
        cl[fill[b]++] = (b + 1) % n;
        cl[fill[(b + 1) % n]++] = b;
    }
    /* continuation table */
    for (size_t b = 0; b < n; b++) {
        m->tstart[b] = nt;
        size_t *v = cl + cs[b], d = cs[b + 1] - cs[b];
        qsort(v, d, sizeof *v, cmp_size);
        size_t u = 0;
        for (size_t q = 0; q < d; q++)
            if (!u || v[u - 1] != v[q]) v[u++] = v[q];
        m->cstart[b] = ncang;
        size_t *ang = m->cang + ncang;
        memcpy(ang, v, u * sizeof *ang);
        ang_sort(m, b, ang, tmp, u);
        ncang += u;
        size_t h1 = 0;
        while (h1 < u && half_of(W(m, b), W(m, ang[h1])) == 0) h1++;
        m->chalf[b] = h1;
        for (size_t q = 0; q < u; q++) {
            size_t a = v[q];
            int ha = half_of(W(m, b), W(m, a));
            size_t x = ha == 0 ? h1 : 0, end = ha == 0 ? u : h1, y = end;
            /* along the other half, sorted by angle, orient(b, a, c) goes +, 0, - (the angle from a
             * to c grows through 180 degrees) */
            while (x < y) {
                size_t mid = x + (y - x) / 2;
                if (acd_orient2d_sign(W(m, b), W(m, a), W(m, ang[mid])) <= 0) y = mid;
                else x = mid + 1;
            }
            if (x < end && acd_orient2d_sign(W(m, b), W(m, a), W(m, ang[x])) == 0) {
                if (!grow(&m->ta, &cta, nt + 1) || !grow(&m->tc, &ctc, nt + 1)) goto nomem;
                m->ta[nt] = a;
                m->tc[nt] = ang[x];
                nt++;
            }
        }
        /* v is sorted by index, so ta is sorted within b */
    }
    m->tstart[n] = nt;
    m->cstart[n] = ncang;
    m->ntrip = nt;
    /* composites: follow every hop (i, c), c > i, along its line */
    for (size_t i = 0; i < n; i++) {
        size_t d0 = cs[i], d1 = cs[i + 1];
        for (size_t q = d0; q < d1; q++) {
            size_t c = cl[q];
            if (c <= i || (q > d0 && cl[q - 1] == c)) continue;
            size_t prev = i, cur = c, nx = cont(m, prev, cur);
            while (nx != NONE) {
                if (!grow(&comp, &ccomp, 4 * (m->ncomp + 1))) goto nomem;
                comp[4 * m->ncomp] = i;
                comp[4 * m->ncomp + 1] = nx;
                comp[4 * m->ncomp + 2] = c;
                comp[4 * m->ncomp + 3] = cur;
                m->ncomp++;
                prev = cur;
                cur = nx;
                nx = cont(m, prev, cur);
            }
        }
    }
    m->comp = (size_t(*)[4])(void *)comp;
    comp = NULL;
    m->fstart = calloc(n + 2, sizeof *m->fstart);
    m->estart = calloc(n + 2, sizeof *m->estart);
    m->cbyf = malloc((m->ncomp + 1) * sizeof *m->cbyf);
    m->cbye = malloc((m->ncomp + 1) * sizeof *m->cbye);
    if (!m->fstart || !m->estart || !m->cbyf || !m->cbye) goto nomem;
    for (size_t z = 0; z < m->ncomp; z++) {
        m->fstart[m->comp[z][0] + 1]++;
        m->estart[m->comp[z][1] + 1]++;
    }
    for (size_t b = 0; b < n; b++) {
        m->fstart[b + 1] += m->fstart[b];
        m->estart[b + 1] += m->estart[b];
    }
    memcpy(fill, m->fstart, (n + 1) * sizeof *fill);
    for (size_t z = 0; z < m->ncomp; z++) m->cbyf[fill[m->comp[z][0]]++] = z;
    memcpy(fill, m->estart, (n + 1) * sizeof *fill);
    for (size_t z = 0; z < m->ncomp; z++) m->cbye[fill[m->comp[z][1]]++] = z;
    goto done;
nomem:
    st = acd_fail(err, ACD_ERR_NOMEM, "MCD: out of memory for the collinear chains of %zu vertices", n);
done:
    free(cs);
    free(cl);
    free(fill);
    free(tmp);
    free(comp);
    return st;
}

typedef struct task {
    size_t i, k, pair;
} task;

static void mcd_free(mcd *m) {
    free(m->wp);
    free(m->reflex);
    free(m->row);
    free(m->fwd);
    free(m->bwd);
    free(m->rl);
    free(m->bits);
    free(m->vstart);
    free(m->vlist);
    free(m->ent);
    free(m->rank);
    free(m->hkey);
    free(m->hval);
    free(m->pool);
    free(m->opt);
    free(m->tstart);
    free(m->ta);
    free(m->tc);
    free(m->fstart);
    free(m->cbyf);
    free(m->estart);
    free(m->cbye);
    free(m->comp);
    free(m->cstart);
    free(m->cang);
    free(m->chalf);
    free(m->wkey_i);
    free(m->wkey_j);
    free(m->wslot);
    free(m->went);
    free(m->crow);
    free(m->cset);
}

acd_status acd_exact_mcd(const acd_polygon *p, acd_index_pieces *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    if (!p || p->nrings == 0) return acd_fail(err, ACD_ERR_DEGENERATE, "MCD: empty polygon");
    if (p->nrings > 1)
        return acd_fail(err, ACD_ERR_UNSUPPORTED,
                        "MCD (Keil-Snoeyink) decomposes polygons without holes; this one has %zu hole%s "
                        "(use the Hertel-Mehlhorn method, --exact hm)",
                        p->nrings - 1, p->nrings == 2 ? "" : "s");
    size_t n = acd_polygon_ring_size(p, 0);
    if (n < 3) return acd_fail(err, ACD_ERR_DEGENERATE, "MCD: the polygon has %zu vertices (needs 3)", n);
    if (n >= PNONE) return acd_fail(err, ACD_ERR_UNSUPPORTED, "MCD: %zu vertices (at most %u)", n, PNONE - 1);
    const acd_vec2 *ring = acd_polygon_ring(p, 0);
    mcd m;
    memset(&m, 0, sizeof m);
    m.ci = NONE;
    m.n = n;
    size_t *perm = malloc(n * sizeof *perm);
    task *stack = NULL;
    acd_status st = ACD_OK;
    m.wp = malloc(n * sizeof *m.wp);
    m.reflex = calloc(n, 1);
    m.row = malloc(n * sizeof *m.row);
    m.fwd = malloc(n * sizeof *m.fwd);
    m.bwd = malloc(n * sizeof *m.bwd);
    m.rl = malloc(n * sizeof *m.rl);
    if (!perm || !m.wp || !m.reflex || !m.row || !m.rl || !m.fwd || !m.bwd) {
        st = acd_fail(err, ACD_ERR_NOMEM, "MCD: out of memory for %zu vertices", n);
        goto done;
    }
    /* 1. work order */
    int ccw = acd_ring_is_ccw(ring, n);
    for (size_t w = 0; w < n; w++) perm[w] = ccw ? w : n - 1 - w;
    size_t first = NONE;
    for (size_t w = 0; w < n && first == NONE; w++) {
        const double *a = V2(&ring[perm[(w + n - 1) % n]]), *b = V2(&ring[perm[w]]), *c = V2(&ring[perm[(w + 1) % n]]);
        if (acd_orient2d_sign(a, b, c) < 0) first = w;
    }
    size_t base_idx = p->ring_start[0];
    if (first == NONE) { /* convex: one piece */
        out->idx = malloc(n * sizeof *out->idx);
        out->start = malloc(2 * sizeof *out->start);
        out->diag = malloc(sizeof *out->diag);
        if (!out->idx || !out->start || !out->diag) {
            st = acd_fail(err, ACD_ERR_NOMEM, "MCD: out of memory");
            goto done;
        }
        for (size_t w = 0; w < n; w++) out->idx[w] = base_idx + perm[w];
        out->start[0] = 0;
        out->start[1] = n;
        out->npieces = 1;
        goto done;
    }
    {
        size_t *rot = malloc(n * sizeof *rot);
        if (!rot) {
            st = acd_fail(err, ACD_ERR_NOMEM, "MCD: out of memory");
            goto done;
        }
        for (size_t w = 0; w < n; w++) rot[w] = perm[(w + first) % n];
        free(perm);
        perm = rot;
    }
    for (size_t w = 0; w < n; w++) m.wp[w] = ring[perm[w]];
    /* straight chains: x is straight when x-1, x, x+1 are collinear and in this order */
    for (size_t a = n - 1; a-- > 0;) {
        size_t x = a + 1;
        int straight = x + 1 < n && acd_orient2d_sign(W(&m, x - 1), W(&m, x), W(&m, x + 1)) == 0 &&
                       acd_point_on_segment(W(&m, x), W(&m, x - 1), W(&m, x + 1));
        m.fwd[a] = straight ? m.fwd[x] : x;
    }
    m.fwd[n - 1] = n - 1;
    m.bwd[0] = 0;
    for (size_t b = 1; b < n; b++) {
        size_t x = b - 1;
        int straight = x > 0 && acd_orient2d_sign(W(&m, x - 1), W(&m, x), W(&m, x + 1)) == 0 &&
                       acd_point_on_segment(W(&m, x), W(&m, x - 1), W(&m, x + 1));
        m.bwd[b] = straight ? m.bwd[x] : x;
    }
    for (size_t w = 0; w < n; w++) {
        m.row[w] = NONE;
        if (acd_orient2d_sign(W(&m, (w + n - 1) % n), W(&m, w), W(&m, (w + 1) % n)) < 0) {
            m.reflex[w] = 1;
            m.row[w] = m.nrows;
            m.rl[m.nrows++] = w;
        }
    }
    /* 2. visibility */
    st = visibility(&m, err);
    if (st != ACD_OK) goto done;
    st = composites(&m, err);
    if (st != ACD_OK) goto done;
    size_t nv = m.vstart[m.nrows];
    m.ent = malloc((nv ? nv : 1) * sizeof *m.ent);
    if (!m.ent || !build_entry_hash(&m)) {
        st = acd_fail(err, ACD_ERR_NOMEM, "MCD: out of memory for %zu diagonals", nv);
        goto done;
    }
    m.crow = malloc(n * sizeof *m.crow);
    m.cset = malloc(n * sizeof *m.cset);
    if (!m.crow || !m.cset) goto dp_nomem;
    for (size_t j = 0; j < n; j++) m.crow[j] = PNONE;
    for (size_t q = 0; q < nv; q++) {
        m.ent[q].w = -1;
        m.ent[q].first = m.ent[q].count = m.ent[q].s1 = m.ent[q].t1 = 0;
    }
    /* 3. dynamic programming over the reflex diagonals (i, k), i decreasing, k increasing: for a
     * reflex i its visibility list beyond i; for a convex i the reflex k > i that see it */
    for (size_t i = n; i-- > 0;) {
        set_row(&m, i); /* the entries (i, k), k > i, in k order */
        for (size_t z = 0; z < m.ncset; z++) {
            size_t k = m.cset[z];
            if (!compute(&m, i, k, &m.ent[m.crow[k]], 1)) goto dp_nomem;
        }
    }
    if (!compute(&m, 0, n - 1, &m.root, 0)) {
    dp_nomem:
        st = acd_fail(err, ACD_ERR_NOMEM, "MCD: out of memory in the dynamic program");
        goto done;
    }
    if (m.root.w < 1 || m.root.count == 0) {
        st = acd_fail(err, ACD_ERR_INVALID_INPUT,
                      "MCD: no convex decomposition found; the polygon is not simple (vertex %zu at (%g, %g))",
                      perm[0], m.wp[0].x, m.wp[0].y);
        goto done;
    }
    /* 4. reconstruction */
    size_t np = (size_t)m.root.w;
    out->idx = malloc((n + 2 * np) * sizeof *out->idx);
    out->start = malloc((np + 1) * sizeof *out->start);
    out->diag = malloc(np * sizeof *out->diag);
    stack = malloc(np * sizeof *stack);
    if (!out->idx || !out->start || !out->diag || !stack) {
        st = acd_fail(err, ACD_ERR_NOMEM, "MCD: out of memory for %zu pieces", np);
        goto done;
    }
    size_t sp = 0, nidx = 0, cap_idx = n + 2 * np;
    stack[sp++] = (task){0, n - 1, m.root.first};
    while (sp) {
        task tk = stack[--sp];
        if (out->npieces == np) {
            st = acd_fail(err, ACD_ERR_INTERNAL, "MCD: reconstruction yields more than %zu pieces", np);
            goto done;
        }
        size_t s0 = nidx;
        out->start[out->npieces++] = nidx;
        out->idx[nidx++] = tk.i;
        out->idx[nidx++] = tk.k;
        size_t a = tk.i, b = tk.k, q = tk.pair;
        for (;;) {
            const mcd_pair *pr = &m.pool[q];
            size_t j = pr->j;
            if (nidx >= cap_idx) {
                st = acd_fail(err, ACD_ERR_INTERNAL, "MCD: reconstruction overflow");
                goto done;
            }
            out->idx[nidx++] = j;
            size_t sep[2][2], nsep = 0, next_a = NONE, next_b = NONE, next_q = NONE;
            size_t run[2][2], nrun = 0; /* straight chains: their inner vertices belong to this piece */
            size_t hop_a = NONE, hop_first = NONE, hop_end = NONE; /* a composite side */
            if (pr->type == 'C') {
                hop_a = a; hop_first = pr->s; hop_end = j;
                if (b > m.fwd[j]) { sep[nsep][0] = j; sep[nsep][1] = b; nsep++; }
                else { run[nrun][0] = j; run[nrun][1] = b; nrun++; }
            } else if (pr->type == 'D') {
                hop_a = j; hop_first = child_of(pr); hop_end = b;
                if (j > m.fwd[a]) { sep[nsep][0] = a; sep[nsep][1] = j; nsep++; }
                else { run[nrun][0] = a; run[nrun][1] = j; nrun++; }
            } else if (pr->type == 'F') {
                if (b > m.fwd[j]) { sep[nsep][0] = j; sep[nsep][1] = b; nsep++; }
                else { run[nrun][0] = j; run[nrun][1] = b; nrun++; }
                next_a = a; next_b = j; next_q = child_of(pr);
            } else if (pr->type == 'G') {
                if (j > m.fwd[a]) { sep[nsep][0] = a; sep[nsep][1] = j; nsep++; }
                else { run[nrun][0] = a; run[nrun][1] = j; nrun++; }
                next_a = j; next_b = b; next_q = child_of(pr);
            } else if (pr->type == 'A') {
                if (b > m.fwd[j]) { sep[nsep][0] = j; sep[nsep][1] = b; nsep++; }
                else { run[nrun][0] = j; run[nrun][1] = b; nrun++; }
                if (pr->child != PNONE) { next_a = a; next_b = j; next_q = pr->child; }
                else if (j > m.fwd[a]) { sep[nsep][0] = a; sep[nsep][1] = j; nsep++; }
                else { run[nrun][0] = a; run[nrun][1] = j; nrun++; }
            } else {
                if (j > m.fwd[a]) { sep[nsep][0] = a; sep[nsep][1] = j; nsep++; }
                else { run[nrun][0] = a; run[nrun][1] = j; nrun++; }
                if (pr->child != PNONE) { next_a = j; next_b = b; next_q = pr->child; }
                else if (b > m.fwd[j]) { sep[nsep][0] = j; sep[nsep][1] = b; nsep++; }
                else { run[nrun][0] = j; run[nrun][1] = b; nrun++; }
            }
            if (hop_a != NONE) {
                size_t prev = hop_a, cur = hop_first;
                for (;;) {
                    if (cur > prev + 1) {
                        mcd_entry *e = entry_of(&m, prev, cur);
                        if (!e || e->count == 0 || out->ndiag == np || sp == np) {
                            st = acd_fail(err, ACD_ERR_INTERNAL, "MCD: broken chain at (%zu, %zu)", prev, cur);
                            goto done;
                        }
                        out->diag[out->ndiag][0] = base_idx + perm[prev];
                        out->diag[out->ndiag][1] = base_idx + perm[cur];
                        out->ndiag++;
                        stack[sp++] = (task){prev, cur, e->first};
                    }
                    if (cur == hop_end) break;
                    if (nidx >= cap_idx) {
                        st = acd_fail(err, ACD_ERR_INTERNAL, "MCD: reconstruction overflow");
                        goto done;
                    }
                    out->idx[nidx++] = cur;
                    size_t nx = cont(&m, prev, cur);
                    if (nx == NONE || nx > hop_end) {
                        st = acd_fail(err, ACD_ERR_INTERNAL, "MCD: broken chain after (%zu, %zu)", prev, cur);
                        goto done;
                    }
                    prev = cur;
                    cur = nx;
                }
            }
            for (size_t z = 0; z < nrun; z++)
                for (size_t x = run[z][0] + 1; x < run[z][1]; x++) {
                    if (nidx >= cap_idx) {
                        st = acd_fail(err, ACD_ERR_INTERNAL, "MCD: reconstruction overflow");
                        goto done;
                    }
                    out->idx[nidx++] = x;
                }
            for (size_t z = 0; z < nsep; z++) {
                mcd_entry *e = entry_of(&m, sep[z][0], sep[z][1]);
                if (!e || e->count == 0 || out->ndiag == np || sp == np) {
                    st = acd_fail(err, ACD_ERR_INTERNAL, "MCD: broken reconstruction at diagonal (%zu, %zu)",
                                  sep[z][0], sep[z][1]);
                    goto done;
                }
                out->diag[out->ndiag][0] = base_idx + perm[sep[z][0]];
                out->diag[out->ndiag][1] = base_idx + perm[sep[z][1]];
                out->ndiag++;
                stack[sp++] = (task){sep[z][0], sep[z][1], e->first};
            }
            if (next_q == NONE) break;
            a = next_a;
            b = next_b;
            q = next_q;
        }
        qsort(out->idx + s0, nidx - s0, sizeof *out->idx, cmp_size);
        for (size_t z = s0; z < nidx; z++) out->idx[z] = base_idx + perm[out->idx[z]];
    }
    out->start[out->npieces] = nidx;
    if (out->npieces != np) {
        st = acd_fail(err, ACD_ERR_INTERNAL, "MCD: %zu pieces reconstructed, %zu expected", out->npieces, np);
        goto done;
    }
done:
    if (st != ACD_OK) acd_index_pieces_free(out);
    free(perm);
    free(stack);
    mcd_free(&m);
    return st;
}
