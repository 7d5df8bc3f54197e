/* mesh/halfedge: building the edge/half-edge view with a hash table on vertex pairs. */
#include "mesh/halfedge.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"

void acd_halfedges_free(acd_halfedges *he) {
    if (!he) return;
    free(he->edge);
    free(he->twin);
    free(he->edge_v);
    free(he->edge_start);
    free(he->edge_he);
    memset(he, 0, sizeof *he);
}

static uint64_t mix64(uint64_t h) {
    h ^= h >> 33;
    h *= UINT64_C(0xff51afd7ed558ccd);
    h ^= h >> 33;
    h *= UINT64_C(0xc4ceb9fe1a85ec53);
    h ^= h >> 33;
    return h;
}

acd_status acd_halfedges_build(const acd_mesh *m, acd_halfedges *he, acd_error *err) {
    return acd_halfedges_build_poll(m, he, NULL, NULL, err);
}

/* whether to stop at half-edge h: stop asked, at every ACD_HE_POLL_HALFEDGES-th */
static int he_stop(int (*stop)(void *), void *user, size_t h) {
    return stop && h % ACD_HE_POLL_HALFEDGES == 0 && stop(user);
}

acd_status acd_halfedges_build_poll(const acd_mesh *m, acd_halfedges *he, int (*stop)(void *), void *user,
                                    acd_error *err) {
    memset(he, 0, sizeof *he);
    if (!m || (m->ntriangles && !m->triangles))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_halfedges_build: NULL mesh");
    if (m->ntriangles >= UINT32_MAX / 3)
        return acd_fail(err, ACD_ERR_UNSUPPORTED, "mesh has %zu triangles (at most %u)", m->ntriangles,
                        UINT32_MAX / 3 - 1);
    for (size_t i = 0; i < 3 * m->ntriangles; i++)
        if (m->triangles[i] >= m->nvertices)
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "triangle %zu refers to vertex %u (mesh has %zu vertices)", i / 3,
                            m->triangles[i], m->nvertices);
    size_t nh = 3 * m->ntriangles;
    size_t cap = 64;
    while (cap < 2 * nh) cap *= 2;
    uint64_t *keys = malloc(cap * sizeof *keys);
    uint32_t *vals = malloc(cap * sizeof *vals);
    he->nhalfedges = nh;
    he->edge = malloc((nh ? nh : 1) * sizeof *he->edge);
    he->twin = malloc((nh ? nh : 1) * sizeof *he->twin);
    he->edge_v = malloc((nh ? nh : 1) * 2 * sizeof *he->edge_v);
    uint32_t *count = calloc(nh + 1, sizeof *count);
    if (!keys || !vals || !he->edge || !he->twin || !he->edge_v || !count) {
        free(keys);
        free(vals);
        free(count);
        acd_halfedges_free(he);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory building the edges of %zu triangles", m->ntriangles);
    }
    /* polled: the table written in slices of ACD_HE_POLL_HALFEDGES slots with a poll between them,
     * the keys too (not needed, but their pages' first touch, 64 MB at 2.5 M half-edges, would
     * otherwise fall in the first slice of the hash pass: 0.4-0.5 CPU-s there on a loaded machine) */
    for (size_t c = 0; c < cap; c += ACD_HE_POLL_HALFEDGES) {
        size_t n = cap - c < ACD_HE_POLL_HALFEDGES ? cap - c : ACD_HE_POLL_HALFEDGES;
        if (stop && c > 0 && stop(user)) goto cancelled;
        memset(vals + c, 0xff, n * sizeof *vals);
        if (stop) memset(keys + c, 0, n * sizeof *keys);
    }
    size_t ne = 0;
    for (size_t h = 0; h < nh; h++) {
        if (he_stop(stop, user, h)) goto cancelled;
        const uint32_t *t = m->triangles + (h - h % 3);
        he->twin[h] = ACD_HE_NONE;
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
            he->edge[h] = ACD_HE_NONE;
            continue;
        }
        uint32_t a = acd_he_from(m, (uint32_t)h), b = acd_he_to(m, (uint32_t)h);
        if (a > b) {
            uint32_t x = a;
            a = b;
            b = x;
        }
        uint64_t key = (uint64_t)a << 32 | b;
        size_t s = (size_t)mix64(key) & (cap - 1);
        while (vals[s] != UINT32_MAX && keys[s] != key) s = (s + 1) & (cap - 1);
        if (vals[s] == UINT32_MAX) {
            keys[s] = key;
            vals[s] = (uint32_t)ne;
            he->edge_v[2 * ne] = a;
            he->edge_v[2 * ne + 1] = b;
            ne++;
        }
        he->edge[h] = vals[s];
        count[vals[s]]++;
    }
    free(keys);
    free(vals);
    keys = NULL;
    vals = NULL;
    he->nedges = ne;
    he->edge_start = malloc((ne + 1) * sizeof *he->edge_start);
    he->edge_he = malloc((nh ? nh : 1) * sizeof *he->edge_he);
    if (!he->edge_start || !he->edge_he) {
        free(count);
        acd_halfedges_free(he);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory building the edges of %zu triangles", m->ntriangles);
    }
    uint32_t acc = 0;
    for (size_t e = 0; e < ne; e++) {
        he->edge_start[e] = acc;
        acc += count[e];
        count[e] = he->edge_start[e]; /* fill cursor */
    }
    he->edge_start[ne] = acc;
    for (size_t h = 0; h < nh; h++) {
        if (he_stop(stop, user, h)) goto cancelled;
        if (he->edge[h] != ACD_HE_NONE) he->edge_he[count[he->edge[h]]++] = (uint32_t)h;
    }
    free(count);
    for (size_t e = 0; e < ne; e++)
        if (he->edge_start[e + 1] - he->edge_start[e] == 2) {
            uint32_t h0 = he->edge_he[he->edge_start[e]], h1 = he->edge_he[he->edge_start[e] + 1];
            he->twin[h0] = h1;
            he->twin[h1] = h0;
        }
    return ACD_OK;
cancelled:
    free(keys);
    free(vals);
    free(count);
    acd_halfedges_free(he);
    return acd_fail(err, ACD_ERR_CANCELLED, "cancelled building the edges of %zu triangles", m->ntriangles);
}
