/* corise/regions: potential regions (Eq. 4), overlaps (Eq. 5), must-link (Eq. 6) and fuzzy
 * (Eq. 7) facets, CoRiSe §5.2; spec corise.md §2.6. */
#include "corise/regions.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "corise/separator.h"

#define MULTI (UINT32_MAX - 1) /* claimed by two or more ridges */

static double piece_length(const double *V, const uint32_t *p, size_t s, size_t t) {
    double sum = 0;
    for (size_t k = s; k < t; k++) {
        const double *a = V + 3 * (size_t)p[k], *b = V + 3 * (size_t)p[k + 1];
        sum += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    }
    return sum;
}

/* Claims for ridge k the facets within len of vertex r. */
static acd_status claim(const acd_mesh *m, const acd_edge_graph *g, uint32_t r, double len, uint32_t k,
                        uint32_t *owner, acd_error *err) {
    if (!(len > 0)) return ACD_OK;
    acd_dijkstra_opts o;
    memset(&o, 0, sizeof o);
    o.target = ACD_NO_VERTEX;
    o.max_distance = len;
    acd_sp_tree t;
    memset(&t, 0, sizeof t);
    acd_status st = acd_dijkstra(g, &r, 1, &o, &t, err);
    if (st != ACD_OK) {
        acd_sp_tree_free(&t);
        return st;
    }
    for (size_t f = 0; f < m->ntriangles; f++) {
        const uint32_t *T = m->triangles + 3 * f;
        double d = t.dist[T[0]];
        if (t.dist[T[1]] > d) d = t.dist[T[1]];
        if (t.dist[T[2]] > d) d = t.dist[T[2]];
        if (!(d < len)) continue;
        if (owner[f] == ACD_CORISE_FUZZY)
            owner[f] = k;
        else if (owner[f] != k)
            owner[f] = MULTI;
    }
    acd_sp_tree_free(&t);
    return ACD_OK;
}

acd_status acd_corise_regions(const acd_mesh *m, const acd_edge_graph *g, const acd_corise_bridges *b,
                              const acd_corise_ridges *r, double tau, uint32_t *must_link, size_t *nsub,
                              acd_error *err) {
    if (!m || !g || !b || !r || !must_link) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "corise: NULL argument");
    if (nsub) *nsub = 0;
    size_t nf = m->ntriangles;
    for (size_t f = 0; f < nf; f++) must_link[f] = ACD_CORISE_FUZZY;
    acd_status st = ACD_OK;
    size_t count = 0;
    for (size_t i = 0; i < b->nbridges; i++) {
        const acd_corise_bridge *br = &b->bridge[i];
        if (!isfinite(br->length) || !(br->concavity > tau) || br->count < 3) continue;
        const uint32_t *p = b->path + br->first;
        acd_corise_split s;
        if ((st = acd_corise_valley_split(m->vertices, p, br->count, tau, &s, err)) != ACD_OK) return st;
        size_t ha = acd_corise_hull_index(b, br->a), hb = acd_corise_hull_index(b, br->b);
        if (ha == SIZE_MAX || hb == SIZE_MAX)
            return acd_fail(err, ACD_ERR_INTERNAL, "corise: bridge (%u, %u) ends off the hull", br->a, br->b);
        /* the valley runs from a (p[0]) to b (p[count-1]) */
        double l0 = piece_length(m->vertices, p, 0, s.first), l1 = piece_length(m->vertices, p, s.second, br->count - 1);
        if ((st = claim(m, g, p[0], l0, r->ridge_of[ha], must_link, err)) != ACD_OK) return st;
        if ((st = claim(m, g, p[br->count - 1], l1, r->ridge_of[hb], must_link, err)) != ACD_OK) return st;
        count += 2;
    }
    for (size_t f = 0; f < nf; f++)
        if (must_link[f] == MULTI) must_link[f] = ACD_CORISE_FUZZY;
    /* safety net: ridges without must-link facets get their hull vertices' unclaimed facets */
    uint8_t *has = calloc(r->nridges ? r->nridges : 1, 1);
    if (!has) return acd_fail(err, ACD_ERR_NOMEM, "corise: out of memory for %zu ridges", r->nridges);
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
    return ACD_OK;
}
