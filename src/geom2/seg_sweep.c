/* geom2/seg_sweep: exact Shamos-Hoey sweep for edge conflicts (see seg_sweep.h).
 *
 * Events are the vertices in lexicographic (x, y) order; an edge's left end is its
 * lexicographically smaller vertex (the lower end of a vertical edge). At a vertex, the edges
 * ending there leave the status first, then the edges starting there enter it. The status is a
 * treap (deterministic priorities) ordered by height at the sweep position just right of the
 * event; entering edge s with left end p compares with edge t by orient(t, p), and when p is on
 * t: if t also starts at p, by orient(t, right end of s); otherwise p lies inside t, which is a
 * conflict. Pairs are handed to the callback whenever they become neighbours. Two distinct
 * vertices at the same point are handed over before the sweep. */
#include "geom2/seg_sweep.h"

#include <stdint.h>
#include <stdlib.h>

#include "core/error.h"
#include "core/predicates.h"

#define NIL SIZE_MAX

typedef struct sweep {
    const acd_vec2 *pts;
    const size_t *next;
    size_t *lc, *rc, *par;
    uint64_t *prio;
    size_t root;
    acd_sweep_pair_fn conflict;
    void *ctx;
    acd_error *err;
} sweep;

static int lex_less(acd_vec2 a, acd_vec2 b) {
    return a.x < b.x || (a.x == b.x && a.y < b.y);
}

static void left_right(const sweep *w, size_t e, double l[2], double r[2]) {
    acd_vec2 a = w->pts[e], b = w->pts[w->next[e]];
    if (lex_less(b, a)) {
        acd_vec2 t = a;
        a = b;
        b = t;
    }
    l[0] = a.x;
    l[1] = a.y;
    r[0] = b.x;
    r[1] = b.y;
}


typedef struct vkey {
    double x, y;
    size_t id;
} vkey;

static int cmp_vkey(const void *a, const void *b) {
    const vkey *p = a, *q = b;
    if (p->x != q->x) return p->x < q->x ? -1 : 1;
    if (p->y != q->y) return p->y < q->y ? -1 : 1;
    return p->id < q->id ? -1 : p->id > q->id;
}

static uint64_t mix(uint64_t z) {
    z += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Replaces child `old` of parent p (or the root) by `nw`. */
static void relink(sweep *w, size_t p, size_t old, size_t nw) {
    if (p == NIL) w->root = nw;
    else if (w->lc[p] == old) w->lc[p] = nw;
    else w->rc[p] = nw;
    if (nw != NIL) w->par[nw] = p;
}

/* Rotates x above its parent. */
static void rotate_up(sweep *w, size_t x) {
    size_t p = w->par[x], g = w->par[p];
    if (w->lc[p] == x) {
        size_t b = w->rc[x];
        w->lc[p] = b;
        if (b != NIL) w->par[b] = p;
        w->rc[x] = p;
    } else {
        size_t b = w->lc[x];
        w->rc[p] = b;
        if (b != NIL) w->par[b] = p;
        w->lc[x] = p;
    }
    w->par[p] = x;
    relink(w, g, p, x);
}

static size_t pred(const sweep *w, size_t x) {
    if (w->lc[x] != NIL) {
        x = w->lc[x];
        while (w->rc[x] != NIL) x = w->rc[x];
        return x;
    }
    size_t p = w->par[x];
    while (p != NIL && w->lc[p] == x) x = p, p = w->par[p];
    return p;
}

static size_t succ(const sweep *w, size_t x) {
    if (w->rc[x] != NIL) {
        x = w->rc[x];
        while (w->lc[x] != NIL) x = w->lc[x];
        return x;
    }
    size_t p = w->par[x];
    while (p != NIL && w->rc[p] == x) x = p, p = w->par[p];
    return p;
}

/* Hands a pair to the callback; a pair the sweep knows to meet but the callback allows means the
 * callback and the sweep disagree: an internal error. */
static acd_status must_conflict(sweep *w, size_t s, size_t t) {
    acd_status st = w->conflict(w->ctx, s, t);
    if (st != ACD_OK) return st;
    return acd_fail(w->err, ACD_ERR_INTERNAL, "edge sweep: edges %zu and %zu meet but were allowed", s, t);
}

static acd_status insert(sweep *w, size_t s) {
    double p[2], sr[2];
    left_right(w, s, p, sr);
    size_t parent = NIL, x = w->root;
    int went_right = 0;
    while (x != NIL) {
        double tl[2], tr[2];
        left_right(w, x, tl, tr);
        int o = acd_orient2d_sign(tl, tr, p);
        if (o == 0) {
            if (tl[0] == p[0] && tl[1] == p[1]) o = acd_orient2d_sign(tl, tr, sr);
            if (o == 0) return must_conflict(w, s, x); /* p inside t, or collinear overlap */
        }
        parent = x;
        went_right = o > 0;
        x = went_right ? w->rc[x] : w->lc[x];
    }
    w->lc[s] = w->rc[s] = NIL;
    w->par[s] = parent;
    if (parent == NIL) w->root = s;
    else if (went_right) w->rc[parent] = s;
    else w->lc[parent] = s;
    while (w->par[s] != NIL && w->prio[w->par[s]] < w->prio[s]) rotate_up(w, s);
    size_t a = pred(w, s), b = succ(w, s);
    acd_status st = ACD_OK;
    if (a != NIL) st = w->conflict(w->ctx, a, s);
    if (st == ACD_OK && b != NIL) st = w->conflict(w->ctx, s, b);
    return st;
}

static acd_status erase(sweep *w, size_t t) {
    size_t a = pred(w, t), b = succ(w, t);
    /* rotate t down to a leaf, then cut it off */
    while (w->lc[t] != NIL || w->rc[t] != NIL) {
        size_t c;
        if (w->lc[t] == NIL) c = w->rc[t];
        else if (w->rc[t] == NIL) c = w->lc[t];
        else c = w->prio[w->lc[t]] > w->prio[w->rc[t]] ? w->lc[t] : w->rc[t];
        rotate_up(w, c);
    }
    relink(w, w->par[t], t, NIL);
    w->par[t] = NIL;
    if (a != NIL && b != NIL) return w->conflict(w->ctx, a, b);
    return ACD_OK;
}

/* The highest status edge strictly below point v (v must not lie on a status edge; if it does,
 * the insertion at v reports the conflict, so any answer will do). */
static size_t edge_below(const sweep *w, acd_vec2 v) {
    double p[2] = {v.x, v.y};
    size_t x = w->root, best = NIL;
    while (x != NIL) {
        double tl[2], tr[2];
        left_right(w, x, tl, tr);
        int o = acd_orient2d_sign(tl, tr, p);
        if (o == 0) break;
        if (o > 0) {
            best = x;
            x = w->rc[x];
        } else {
            x = w->lc[x];
        }
    }
    return best;
}

acd_status acd_sweep_edges(const acd_vec2 *pts, const size_t *next, size_t n, acd_sweep_pair_fn conflict,
                           void *ctx, const unsigned char *want_below, size_t *below, acd_error *err) {
    if (n == 0) return ACD_OK;
    sweep w = {pts, next, NULL, NULL, NULL, NULL, NIL, conflict, ctx, err};
    size_t *prev = malloc(n * sizeof *prev);
    vkey *ev = malloc(n * sizeof *ev);
    w.lc = malloc(n * sizeof *w.lc);
    w.rc = malloc(n * sizeof *w.rc);
    w.par = malloc(n * sizeof *w.par);
    w.prio = malloc(n * sizeof *w.prio);
    acd_status st = ACD_OK;
    if (!prev || !ev || !w.lc || !w.rc || !w.par || !w.prio) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory for the edge sweep (%zu edges)", n);
        goto done;
    }
    for (size_t i = 0; i < n; i++) {
        prev[next[i]] = i;
        ev[i].x = pts[i].x;
        ev[i].y = pts[i].y;
        ev[i].id = i;
        w.lc[i] = w.rc[i] = w.par[i] = NIL;
        w.prio[i] = mix((uint64_t)i);
    }
    qsort(ev, n, sizeof *ev, cmp_vkey);
    /* two vertices at one point touch: hand their outgoing edges over */
    for (size_t k = 1; k < n; k++)
        if (ev[k].x == ev[k - 1].x && ev[k].y == ev[k - 1].y) {
            st = must_conflict(&w, ev[k - 1].id, ev[k].id);
            goto done;
        }
    for (size_t k = 0; k < n && st == ACD_OK; k++) {
        size_t v = ev[k].id;
        size_t in = prev[v], out = v;
        acd_vec2 pv = pts[v];
        int in_ends = lex_less(pts[in], pv);          /* edge in = prev->v ends (right end) at v */
        int out_ends = lex_less(pts[next[out]], pv); /* edge out = v->next ends at v */
        if (in_ends) st = erase(&w, in);
        if (st == ACD_OK && out_ends) st = erase(&w, out);
        if (st == ACD_OK && below && want_below && want_below[v]) below[v] = edge_below(&w, pv);
        if (st == ACD_OK && !in_ends) st = insert(&w, in);
        if (st == ACD_OK && !out_ends) st = insert(&w, out);
    }
done:
    free(prev);
    free(ev);
    free(w.lc);
    free(w.rc);
    free(w.par);
    free(w.prio);
    return st;
}
