/* acd2/exact_hm: Hertel-Mehlhorn convex decomposition.
 *
 * S. Hertel and K. Mehlhorn, "Fast triangulation of simple polygons", FCT 1983, LNCS 158: a diagonal
 * of a triangulation is inessential when removing it leaves both of its endpoints convex in the
 * merged piece; removing inessential diagonals one at a time until none is left gives at most
 * 4 times the minimum number of convex pieces (each remaining diagonal is essential for a reflex
 * vertex, and a reflex vertex has at most two essential diagonals, so pieces <= 2r + 1 <= 4 OPT
 * since OPT >= r/2 + 1). The dissertation compares ACD against the exact minimum (IV.D.3); HM is our
 * fast exact baseline that also takes holes (hole bridges are ordinary diagonals here).
 *
 * design:
 *   1. Triangulate (ear clipping with hole bridging, geom2/triangulate).
 *   2. Half-edges 3t+k of triangle t (from corner k to k+1); twins by sorting edge keys; a face
 *      cycle (next/prev) per triangle, a union-find over triangles for the face identity.
 *   3. For each diagonal in increasing half-edge order: with h = (u->v) in face A and its twin
 *      t = (v->u) in face B (A != B), remove it when orient2d(prev(h).org, u, next(t).dst) >= 0 and
 *      orient2d(prev(t).org, v, next(h).dst) >= 0 (exact), splicing the two cycles.
 *   4. Walk the remaining cycles: the pieces; the remaining twinned edges: the diagonals. */
#include "acd2/exact_hm.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/union_find.h"
#include "core/predicates.h"
#include "geom2/triangulate.h"

#define NONE ((size_t)-1)
#define V2(p) ((const double *)(const void *)(p))

void acd_index_pieces_free(acd_index_pieces *p) {
    if (!p) return;
    free(p->idx);
    free(p->start);
    free(p->diag);
    memset(p, 0, sizeof *p);
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

acd_status acd_exact_hm(const acd_polygon *p, acd_index_pieces *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    size_t *tri = NULL, nt = 0;
    acd_status st = acd_triangulate_polygon(p, &tri, &nt, NULL, err);
    if (st != ACD_OK) return st;
    size_t nh = 3 * nt;
    size_t *org = malloc(nh * sizeof *org), *dst = malloc(nh * sizeof *dst);
    size_t *nxt = malloc(nh * sizeof *nxt), *prv = malloc(nh * sizeof *prv), *twin = malloc(nh * sizeof *twin);
    size_t *par = malloc((nt ? nt : 1) * sizeof *par);
    unsigned char *dead = calloc(nh ? nh : 1, 1), *seen = calloc(nh ? nh : 1, 1);
    edge_key *keys = malloc((nh ? nh : 1) * sizeof *keys);
    if (!org || !dst || !nxt || !prv || !twin || !par || !dead || !seen || !keys) {
        st = acd_fail(err, ACD_ERR_NOMEM, "Hertel-Mehlhorn: out of memory for %zu triangles", nt);
        goto done;
    }
    const acd_vec2 *pts = p->points;
    for (size_t t = 0; t < nt; t++) {
        par[t] = t;
        for (size_t k = 0; k < 3; k++) {
            size_t h = 3 * t + k;
            org[h] = tri[h];
            dst[h] = tri[3 * t + (k + 1) % 3];
            nxt[h] = 3 * t + (k + 1) % 3;
            prv[h] = 3 * t + (k + 2) % 3;
            twin[h] = NONE;
            keys[h].a = org[h] < dst[h] ? org[h] : dst[h];
            keys[h].b = org[h] < dst[h] ? dst[h] : org[h];
            keys[h].he = h;
        }
    }
    qsort(keys, nh, sizeof *keys, cmp_key);
    for (size_t i = 0; i + 1 < nh;) {
        size_t j = i + 1;
        while (j < nh && keys[j].a == keys[i].a && keys[j].b == keys[i].b) j++;
        if (j - i == 2) {
            size_t h = keys[i].he, g = keys[i + 1].he;
            if (org[h] == dst[g] && dst[h] == org[g] && org[h] != dst[h]) {
                twin[h] = g;
                twin[g] = h;
            }
        }
        i = j;
    }
    /* 3. remove inessential diagonals */
    for (size_t h = 0; h < nh; h++) {
        size_t t = twin[h];
        if (t == NONE || t < h || dead[h]) continue;
        size_t fa = acd_uf_find_z(par, h / 3), fb = acd_uf_find_z(par, t / 3);
        if (fa == fb) continue;
        const double *u = V2(&pts[org[h]]), *v = V2(&pts[dst[h]]);
        if (acd_orient2d_sign(V2(&pts[org[prv[h]]]), u, V2(&pts[dst[nxt[t]]])) < 0) continue;
        if (acd_orient2d_sign(V2(&pts[org[prv[t]]]), v, V2(&pts[dst[nxt[h]]])) < 0) continue;
        size_t hp = prv[h], hn = nxt[h], tp = prv[t], tn = nxt[t];
        nxt[hp] = tn;
        prv[tn] = hp;
        nxt[tp] = hn;
        prv[hn] = tp;
        dead[h] = dead[t] = 1;
        par[fa] = fb;
    }
    /* 4. pieces and diagonals */
    size_t npieces = 0, ndiag = 0, nidx = 0;
    for (size_t h = 0; h < nh; h++)
        if (!dead[h]) {
            nidx++;
            if (twin[h] != NONE && twin[h] > h) ndiag++;
        }
    out->idx = malloc((nidx ? nidx : 1) * sizeof *out->idx);
    out->start = malloc((nt + 1) * sizeof *out->start);
    out->diag = malloc((ndiag ? ndiag : 1) * sizeof *out->diag);
    if (!out->idx || !out->start || !out->diag) {
        st = acd_fail(err, ACD_ERR_NOMEM, "Hertel-Mehlhorn: out of memory for the pieces");
        goto done;
    }
    size_t k = 0;
    for (size_t h = 0; h < nh; h++) {
        if (dead[h] || seen[h]) continue;
        out->start[npieces++] = k;
        size_t g = h;
        do {
            seen[g] = 1;
            out->idx[k++] = org[g];
            g = nxt[g];
        } while (g != h && k <= nidx);
        if (g != h) {
            st = acd_fail(err, ACD_ERR_INTERNAL, "Hertel-Mehlhorn: a face cycle does not close");
            goto done;
        }
    }
    out->start[npieces] = k;
    out->npieces = npieces;
    for (size_t h = 0; h < nh; h++)
        if (!dead[h] && twin[h] != NONE && twin[h] > h) {
            out->diag[out->ndiag][0] = org[h];
            out->diag[out->ndiag][1] = dst[h];
            out->ndiag++;
        }
done:
    if (st != ACD_OK) acd_index_pieces_free(out);
    free(tri);
    free(org);
    free(dst);
    free(nxt);
    free(prv);
    free(twin);
    free(par);
    free(dead);
    free(seen);
    free(keys);
    return st;
}
