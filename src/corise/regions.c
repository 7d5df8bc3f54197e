/* corise/regions: potential regions (Eq. 4), overlaps (Eq. 5), must-link (Eq. 6) and fuzzy
 * (Eq. 7) facets, CoRiSe §5.2; spec corise.md §2.6. */
#include "corise/regions.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "corise/separator.h"
#ifdef _OPENMP
#include <omp.h>
#endif

#define MULTI (UINT32_MAX - 1) /* claimed by two or more ridges */
#define CLAIM_ROUND 64         /* balls grown in one parallel loop */

static double piece_length(const double *V, const uint32_t *p, size_t s, size_t t) {
    double sum = 0;
    for (size_t k = s; k < t; k++) {
        const double *a = V + 3 * (size_t)p[k], *b = V + 3 * (size_t)p[k + 1];
        sum += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    }
    return sum;
}

/* A ball claim: the facets whose three vertices are at edge-graph distance < len from r. */
typedef struct claim_req {
    uint32_t r, ridge;
    double len;
} claim_req;

static int cmp_claim(const void *x, const void *y) {
    const claim_req *p = x, *q = y;
    return (p->r > q->r) - (p->r < q->r);
}

/* Per-claim output: the claimed facets. */
typedef struct ball_work {
    uint32_t *faces;
    size_t nfaces, cap_faces;
} ball_work;

static int grow(uint32_t **a, size_t *cap, size_t n) {
    if (n < *cap) return 1;
    size_t nc = *cap ? 2 * *cap : 256;
    uint32_t *p = realloc(*a, nc * sizeof *p);
    if (!p) return 0;
    *a = p;
    *cap = nc;
    return 1;
}

/* w->faces[0..w->nfaces) = the facets whose three vertices are at edge-graph distance < len from r
 * (len > 0), in no particular order (apply_claim's result does not depend on it): the facets by
 * their first vertex (first_row[v] .. first_row[v+1] of first_face) of the vertices a search of
 * s bounded below len settles (geom3/dijkstra's workspace: a ball costs its own vertices, not a
 * pass over the mesh; the same distances as acd_dijkstra's, which it replaced). 0: out of memory. */
static int ball(const acd_mesh *m, const acd_edge_graph *g, const size_t *first_row, const uint32_t *first_face,
                uint32_t r, double len, acd_sp_ws *s, ball_work *w) {
    w->nfaces = 0;
    acd_sp_limits lim = {.below = len, .no_pred = 1};
    if (!acd_sp_ws_run(s, g, r, &lim)) return 0;
    for (size_t i = 0; i < s->nvisited; i++) {
        uint32_t u = s->visited[i];
        for (size_t j = first_row[u]; j < first_row[u + 1]; j++) {
            uint32_t f = first_face[j];
            const uint32_t *T = m->triangles + 3 * (size_t)f;
            if (!acd_sp_ws_settled(s, T[1]) || !acd_sp_ws_settled(s, T[2])) continue;
            if (!grow(&w->faces, &w->cap_faces, w->nfaces)) return 0;
            w->faces[w->nfaces++] = f;
        }
    }
    return 1;
}

/* Claims the facets of a ball for ridge k (a facet claimed by two ridges becomes MULTI; the final
 * owner of a facet depends only on the set of ridges that claim it, not on the order). */
static void apply_claim(const ball_work *w, uint32_t k, uint32_t *owner) {
    for (size_t i = 0; i < w->nfaces; i++) {
        uint32_t f = w->faces[i];
        if (owner[f] == ACD_CORISE_FUZZY)
            owner[f] = k;
        else if (owner[f] != k)
            owner[f] = MULTI;
    }
}

acd_status acd_corise_regions(const acd_mesh *m, const acd_edge_graph *g, const acd_corise_bridges *b,
                              const acd_corise_ridges *r, double tau, uint32_t *must_link, size_t *nsub,
                              acd_error *err) {
    return acd_corise_regions_mt(m, g, b, r, tau, 1, NULL, must_link, nsub, err);
}

acd_status acd_corise_regions_mt(const acd_mesh *m, const acd_edge_graph *g, const acd_corise_bridges *b,
                                 const acd_corise_ridges *r, double tau, int nthreads, acd3_poll *poll,
                                 uint32_t *must_link, size_t *nsub, acd_error *err) {
    if (!m || !g || !b || !r || !must_link) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "corise: NULL argument");
    if (nsub) *nsub = 0;
    size_t nf = m->ntriangles;
    for (size_t f = 0; f < nf; f++) must_link[f] = ACD_CORISE_FUZZY;
    acd_status st = ACD_OK;
    size_t count = 0;
    /* the deep valleys, each split at its separators independently (in parallel) */
    size_t ndeep = 0;
    for (size_t i = 0; i < b->nbridges; i++) {
        const acd_corise_bridge *br = &b->bridge[i];
        ndeep += isfinite(br->length) && br->concavity > tau && br->count >= 3;
    }
    size_t *deep = malloc((ndeep ? ndeep : 1) * sizeof *deep);
    acd_corise_split *sp = malloc((ndeep ? ndeep : 1) * sizeof *sp);
    acd_status *sst = malloc((ndeep ? ndeep : 1) * sizeof *sst);
    claim_req *cl = malloc((ndeep ? 2 * ndeep : 1) * sizeof *cl);
    int nt = 1;
#ifdef _OPENMP
    if (nthreads > 1 && !omp_in_parallel() && m->ntriangles >= ACD_CORISE_PARALLEL_MIN_FACES)
        nt = nthreads < ACD_CORISE_MAX_THREADS ? nthreads : ACD_CORISE_MAX_THREADS;
#endif
    size_t nbw = nt > 1 ? CLAIM_ROUND : 1;
    acd_sp_ws *bs = NULL;
    size_t *first_row = NULL;
    uint32_t *first_face = NULL;
    ball_work *bw = calloc(nbw, sizeof *bw);
    if (!deep || !sp || !sst || !cl || !bw) {
        st = acd_fail(err, ACD_ERR_NOMEM, "corise: out of memory for %zu deep valleys", ndeep);
        goto done;
    }
    ndeep = 0;
    for (size_t i = 0; i < b->nbridges; i++) {
        const acd_corise_bridge *br = &b->bridge[i];
        if (isfinite(br->length) && br->concavity > tau && br->count >= 3) deep[ndeep++] = i;
    }
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt) if (nt > 1 && ndeep > 1)
#endif
    for (long d = 0; d < (long)ndeep; d++) {
        const acd_corise_bridge *br = &b->bridge[deep[d]];
        acd_error e;
        sst[d] = acd3_poll_stop(poll) ? ACD_ERR_CANCELLED
                                      : acd_corise_valley_split(m->vertices, b->path + br->first, br->count, tau, &sp[d], &e);
    }
    if (acd3_poll_stopped(poll)) goto cancelled;
    size_t ncl = 0;
    for (size_t d = 0; d < ndeep; d++) {
        const acd_corise_bridge *br = &b->bridge[deep[d]];
        if (sst[d] != ACD_OK) {
            st = acd_fail(err, sst[d], "corise: splitting the valley of bridge (%u, %u) (out of memory)", br->a, br->b);
            goto done;
        }
        const uint32_t *p = b->path + br->first;
        size_t ha = acd_corise_hull_index(b, br->a), hb = acd_corise_hull_index(b, br->b);
        if (ha == SIZE_MAX || hb == SIZE_MAX) {
            st = acd_fail(err, ACD_ERR_INTERNAL, "corise: bridge (%u, %u) ends off the hull", br->a, br->b);
            goto done;
        }
        /* the valley runs from a (p[0]) to b (p[count-1]) */
        double l0 = piece_length(m->vertices, p, 0, sp[d].first),
               l1 = piece_length(m->vertices, p, sp[d].second, br->count - 1);
        cl[ncl++] = (claim_req){p[0], r->ridge_of[ha], l0};
        cl[ncl++] = (claim_req){p[br->count - 1], r->ridge_of[hb], l1};
        count += 2;
    }
    /* Claims from the same vertex are one: its ridge is its hull vertex's, and balls around one
       vertex are nested (a facet within the smaller radius is within the larger), so the facets
       they claim together are the largest ball's. One ball per distinct vertex, with the largest
       radius; the owners come out the same because a facet's owner depends only on the set of
       ridges that claim it. */
    if (ncl) {
        qsort(cl, ncl, sizeof *cl, cmp_claim);
        size_t k = 0;
        for (size_t c = 0; c < ncl; c++) {
            if (k && cl[k - 1].r == cl[c].r) {
                if (cl[c].len > cl[k - 1].len) cl[k - 1].len = cl[c].len;
            } else {
                cl[k++] = cl[c];
            }
        }
        ncl = k;
    }
    /* the balls, a round at a time in parallel, applied in order; each thread's search workspace
       is reused, the facets are listed by their first vertex */
    if (ncl) {
        int ok = 1;
        size_t nv = m->nvertices;
        first_row = calloc(nv + 1, sizeof *first_row);
        first_face = malloc((nf ? nf : 1) * sizeof *first_face);
        bs = calloc((size_t)nt, sizeof *bs);
        if (!first_row || !first_face || !bs) {
            st = acd_fail(err, ACD_ERR_NOMEM, "corise: out of memory for the regions of %zu facets", nf);
            goto done;
        }
        for (int t = 0; t < nt; t++)
            if ((st = acd_sp_ws_init(&bs[t], g->nvertices, err)) != ACD_OK) goto done;
        for (size_t f = 0; f < nf; f++) first_row[m->triangles[3 * f] + 1]++;
        for (size_t v = 0; v < nv; v++) first_row[v + 1] += first_row[v];
        for (size_t f = 0; f < nf; f++) first_face[first_row[m->triangles[3 * f]]++] = (uint32_t)f;
        for (size_t v = nv; v > 0; v--) first_row[v] = first_row[v - 1];
        first_row[0] = 0;
        if (nt == 1) {
            for (size_t c = 0; c < ncl && ok; c++) {
                if (!(cl[c].len > 0)) continue;
                if (acd3_poll_stop(poll)) goto cancelled;
                ok = ball(m, g, first_row, first_face, cl[c].r, cl[c].len, &bs[0], &bw[0]);
                if (ok) apply_claim(&bw[0], cl[c].ridge, must_link);
            }
        } else {
#ifdef _OPENMP
            /* rounds of up to CLAIM_ROUND claims in one parallel loop each (few parallel regions:
               their fork and join cost more than a small ball), applied in claim order */
            for (size_t c0 = 0; c0 < ncl && ok; c0 += CLAIM_ROUND) {
                size_t c1 = c0 + CLAIM_ROUND < ncl ? c0 + CLAIM_ROUND : ncl;
                int rok[CLAIM_ROUND];
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
                for (long c = (long)c0; c < (long)c1; c++) {
                    ball_work *w = &bw[c - (long)c0]; /* one workspace per claim of the round */
                    w->nfaces = 0;
                    rok[c - (long)c0] =
                        cl[c].len > 0 && !acd3_poll_stop(poll)
                            ? ball(m, g, first_row, first_face, cl[c].r, cl[c].len, &bs[omp_get_thread_num()], w)
                            : 1;
                }
                if (acd3_poll_stopped(poll)) goto cancelled;
                for (size_t c = c0; c < c1; c++) {
                    ok &= rok[c - c0];
                    if (ok && cl[c].len > 0) apply_claim(&bw[c - c0], cl[c].ridge, must_link);
                }
            }
#endif
        }
        if (!ok) {
            st = acd_fail(err, ACD_ERR_NOMEM, "corise: out of memory growing a region of %zu vertices", m->nvertices);
            goto done;
        }
    }
    for (size_t f = 0; f < nf; f++)
        if (must_link[f] == MULTI) must_link[f] = ACD_CORISE_FUZZY;
    /* safety net: ridges without must-link facets get their hull vertices' unclaimed facets */
    uint8_t *has = calloc(r->nridges ? r->nridges : 1, 1);
    if (!has) {
        st = acd_fail(err, ACD_ERR_NOMEM, "corise: out of memory for %zu ridges", r->nridges);
        goto done;
    }
    for (size_t f = 0; f < nf; f++)
        if (must_link[f] != ACD_CORISE_FUZZY) has[must_link[f]] = 1;
    for (size_t f = 0; f < nf; f++) {
        if (must_link[f] != ACD_CORISE_FUZZY) continue;
        uint32_t want = ACD_CORISE_FUZZY;
        int conflict = 0;
        for (int k = 0; k < 3; k++) {
            size_t h = acd_corise_hull_index(b, m->triangles[3 * f + k]);
            if (h == SIZE_MAX || has[r->ridge_of[h]]) continue;
            if (want == ACD_CORISE_FUZZY)
                want = r->ridge_of[h];
            else if (want != r->ridge_of[h])
                conflict = 1;
        }
        if (want != ACD_CORISE_FUZZY && !conflict) must_link[f] = want; /* `has` is not updated here */
    }
    free(has);
    if (nsub) *nsub = count;
    goto done;
cancelled:
    st = acd_fail(err, ACD_ERR_CANCELLED, "corise: cancelled by the progress callback growing the regions of %zu facets", nf);
done:
    free(deep);
    free(sp);
    free(sst);
    free(cl);
    if (bw)
        for (size_t t = 0; t < nbw; t++) free(bw[t].faces);
    free(bw);
    if (bs)
        for (int t = 0; t < nt; t++) acd_sp_ws_free(&bs[t]);
    free(bs);
    free(first_row);
    free(first_face);
    return st;
}
