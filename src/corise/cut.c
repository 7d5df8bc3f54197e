/* corise/cut: sequential binary graph cuts with Eq. 8 smoothness, CoRiSe §5.2; spec corise.md
 * §2.7. */
#include "corise/cut.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/predicates.h"
#include "corise/edgesort.h"
#include "corise/maxflow.h"
#include "corise/regions.h"

acd_corise_cut_params acd_corise_cut_default_params(void) {
    acd_corise_cut_params p;
    p.alpha = 0.8;
    p.concave_weight = 0.3;
    return p;
}

typedef acd_corise_ef ef;

typedef struct dual_edge {
    uint32_t f, g;
    double len;
    int concave;
} dual_edge;

/* The error of a cut the poll stopped (the dual graph, a ridge's cut, its max-flow), nf facets. */
static acd_status cut_cancelled(acd_error *err, size_t nf) {
    return acd_fail(err, ACD_ERR_CANCELLED, "corise: cancelled by the progress callback cutting %zu facets", nf);
}

/* Vertex of triangle t not on edge (lo, hi). */
static uint32_t opposite(const acd_mesh *m, uint32_t t, uint32_t lo, uint32_t hi) {
    for (int k = 0; k < 3; k++) {
        uint32_t v = m->triangles[3 * (size_t)t + k];
        if (v != lo && v != hi) return v;
    }
    return m->triangles[3 * (size_t)t];
}

/* The dual edges; polls poll after the sort and every ACD_CORISE_POLL_DUAL edges (0 on a stop). */
#define ACD_CORISE_POLL_DUAL 65536
static acd_status build_dual(const acd_mesh *m, acd3_poll *poll, dual_edge **out, size_t *nout, acd_error *err) {
    size_t ne = 3 * m->ntriangles;
    ef *e = malloc((ne ? ne : 1) * sizeof *e);
    dual_edge *d = malloc((ne ? ne : 1) * sizeof *d);
    if (!e || !d) {
        free(e);
        free(d);
        return acd_fail(err, ACD_ERR_NOMEM, "corise: out of memory for the dual graph of %zu facets", m->ntriangles);
    }
    for (size_t t = 0; t < m->ntriangles; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t u = m->triangles[3 * t + k], v = m->triangles[3 * t + (k + 1) % 3];
            e[3 * t + k] = (ef){u < v ? u : v, u < v ? v : u, (uint32_t)t};
        }
    if (!acd_corise_ef_sort(e, ne)) {
        free(e);
        free(d);
        return acd_fail(err, ACD_ERR_NOMEM, "corise: out of memory for the dual graph of %zu facets", m->ntriangles);
    }
    size_t nd = 0;
    for (size_t i = 0, groups = 0; i < ne; groups++) {
        if (poll && groups % ACD_CORISE_POLL_DUAL == 0 && acd3_poll_stop(poll)) {
            free(e);
            free(d);
            return cut_cancelled(err, m->ntriangles);
        }
        size_t j = i + 1;
        while (j < ne && e[j].lo == e[i].lo && e[j].hi == e[i].hi) j++;
        /* consecutive facets around the edge are linked (two for a manifold edge) */
        for (size_t k = i; k + 1 < j; k++) {
            if (e[k].face == e[k + 1].face || e[i].lo == e[i].hi) continue;
            const double *a = m->vertices + 3 * (size_t)e[i].lo, *b = m->vertices + 3 * (size_t)e[i].hi;
            double len = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
            uint32_t f = e[k].face, g = e[k + 1].face;
            const uint32_t *T = m->triangles + 3 * (size_t)f;
            uint32_t w = opposite(m, g, e[i].lo, e[i].hi);
            /* concave iff g's far vertex lies on the outer side of f's plane (f counterclockwise
             * seen from outside): orient3d < 0 means "above" */
            int side = acd_orient3d_sign(m->vertices + 3 * (size_t)T[0], m->vertices + 3 * (size_t)T[1],
                                         m->vertices + 3 * (size_t)T[2], m->vertices + 3 * (size_t)w);
            d[nd++] = (dual_edge){f, g, len, j - i == 2 && side < 0};
        }
        i = j;
    }
    free(e);
    *out = d;
    *nout = nd;
    return ACD_OK;
}

acd_status acd_corise_cut(const acd_mesh *m, const acd_corise_bridges *b, const acd_corise_ridges *r,
                          const uint32_t *must_link, const acd_corise_cut_params *params, uint32_t *part,
                          size_t *nparts, acd_error *err) {
    return acd_corise_cut_poll(m, b, r, must_link, params, NULL, part, nparts, err);
}

acd_status acd_corise_cut_poll(const acd_mesh *m, const acd_corise_bridges *b, const acd_corise_ridges *r,
                               const uint32_t *must_link, const acd_corise_cut_params *params, acd3_poll *poll,
                               uint32_t *part, size_t *nparts, acd_error *err) {
    if (!m || !b || !r || !must_link || !part || !nparts)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "corise: NULL argument");
    acd_corise_cut_params prm = params ? *params : acd_corise_cut_default_params();
    if (!(prm.alpha >= 0 && prm.alpha <= 1) || !(prm.concave_weight > 0) || !isfinite(prm.concave_weight))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "corise: alpha %g must be in [0,1], concave weight %g > 0",
                        prm.alpha, prm.concave_weight);
    size_t nf = m->ntriangles, nr = r->nridges;
    *nparts = 0;
    for (size_t f = 0; f < nf; f++) {
        part[f] = UINT32_MAX;
        if (must_link[f] != ACD_CORISE_FUZZY && must_link[f] >= nr)
            return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "corise: facet %zu must-link to ridge %u of %zu", f,
                            must_link[f], nr);
    }
    dual_edge *d = NULL;
    size_t nd = 0;
    acd_status st = build_dual(m, poll, &d, &nd, err);
    if (st != ACD_OK) return st;
    if (acd3_poll_stop(poll)) {
        free(d);
        return cut_cancelled(err, nf);
    }
    /* Eq. 8 weights */
    double *w = malloc((nd ? nd : 1) * sizeof *w);
    double *diag = calloc(nr ? nr : 1, sizeof *diag), *box = malloc((nr ? nr : 1) * 6 * sizeof *box);
    size_t *order = malloc((nr ? nr : 1) * sizeof *order);
    uint8_t *cut_done = calloc(nr ? nr : 1, 1);
    uint32_t *node = malloc((nf ? nf : 1) * sizeof *node);
    acd_maxflow *g = NULL;
    if (!w || !diag || !box || !order || !cut_done || !node) {
        st = acd_fail(err, ACD_ERR_NOMEM, "corise: out of memory for the cuts of %zu facets", nf);
        goto done;
    }
    double mu_theta = 0, mu_e = 0, sumw = 0;
    for (size_t i = 0; i < nd; i++) {
        mu_theta += d[i].concave ? prm.concave_weight : 1.0;
        mu_e += d[i].len;
    }
    if (nd) mu_theta /= (double)nd, mu_e /= (double)nd;
    for (size_t i = 0; i < nd; i++) {
        double th = d[i].concave ? prm.concave_weight : 1.0;
        w[i] = prm.alpha * th / mu_theta + (mu_e > 0 ? (1 - prm.alpha) * d[i].len / mu_e : 0);
        sumw += w[i];
    }
    double inf = 1 + 2 * sumw;
    /* ridge order: bbox diagonal of its hull vertices, ascending, ties by id (A16) */
    for (size_t k = 0; k < nr; k++) {
        box[6 * k] = box[6 * k + 1] = box[6 * k + 2] = INFINITY;
        box[6 * k + 3] = box[6 * k + 4] = box[6 * k + 5] = -INFINITY;
    }
    for (size_t h = 0; h < b->nhull; h++) {
        size_t k = r->ridge_of[h];
        const double *p = m->vertices + 3 * (size_t)b->hull_vertex[h];
        for (int c = 0; c < 3; c++) {
            if (p[c] < box[6 * k + c]) box[6 * k + c] = p[c];
            if (p[c] > box[6 * k + 3 + c]) box[6 * k + 3 + c] = p[c];
        }
    }
    for (size_t k = 0; k < nr; k++) {
        double s = 0;
        for (int c = 0; c < 3; c++) {
            double e = box[6 * k + 3 + c] - box[6 * k + c];
            s += isfinite(e) ? e * e : 0;
        }
        diag[k] = sqrt(s);
        order[k] = k;
    }
    for (size_t i = 1; i < nr; i++) /* insertion sort: stable, ties by id */
        for (size_t j = i; j > 0 && diag[order[j]] < diag[order[j - 1]]; j--) {
            size_t t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
    if ((st = acd_maxflow_create(&g, nf, nd, err)) != ACD_OK) goto done;
    uint32_t next_part = 0;
    for (size_t t = 0; t + 1 < nr; t++) {
        size_t k = order[t];
        if (acd3_poll_stop(poll)) {
            st = cut_cancelled(err, nf);
            goto done;
        }
        acd_maxflow_reset(g);
        size_t nn = 0, nsrc = 0;
        for (size_t f = 0; f < nf; f++) node[f] = part[f] == UINT32_MAX ? (uint32_t)nn++ : UINT32_MAX;
        if ((st = acd_maxflow_add_nodes(g, nn, NULL, err)) != ACD_OK) goto done;
        for (size_t f = 0; f < nf; f++) {
            if (node[f] == UINT32_MAX || must_link[f] == ACD_CORISE_FUZZY) continue;
            if (must_link[f] == k) {
                nsrc++;
                st = acd_maxflow_add_tweights(g, node[f], inf, 0, err);
            } else if (!cut_done[must_link[f]]) {
                st = acd_maxflow_add_tweights(g, node[f], 0, inf, err);
            }
            if (st != ACD_OK) goto done;
        }
        cut_done[k] = 1;
        if (nsrc == 0) continue; /* nothing of this ridge is left */
        for (size_t i = 0; i < nd; i++) {
            uint32_t a = node[d[i].f], c = node[d[i].g];
            if (a == UINT32_MAX || c == UINT32_MAX) continue;
            if ((st = acd_maxflow_add_edge(g, a, c, w[i], w[i], err)) != ACD_OK) goto done;
        }
        double flow;
        if ((st = acd_maxflow_solve_poll(g, &flow, poll, err)) != ACD_OK) {
            if (st == ACD_ERR_CANCELLED) st = cut_cancelled(err, nf); /* the cut's message, not the max-flow's */
            goto done;
        }
        size_t taken = 0;
        for (size_t f = 0; f < nf; f++)
            if (node[f] != UINT32_MAX && acd_maxflow_is_source(g, node[f])) {
                part[f] = next_part;
                taken++;
            }
        if (taken) next_part++;
    }
    size_t rest = 0;
    for (size_t f = 0; f < nf; f++)
        if (part[f] == UINT32_MAX) {
            part[f] = next_part;
            rest++;
        }
    if (rest) next_part++;
    *nparts = next_part;
done:
    acd_maxflow_free(g);
    free(d);
    free(w);
    free(diag);
    free(box);
    free(order);
    free(cut_done);
    free(node);
    return st;
}
