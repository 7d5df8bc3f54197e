/* geom3/edge_map: directed-edge lookup for triangle meshes (keys sorted by a stable radix sort, binary search).
 * Maps the half-edge (a, b) of triangle t, corner i (edge from corner i to i+1) to 3t + i. */
#ifndef ACD_GEOM3_EDGE_MAP_H
#define ACD_GEOM3_EDGE_MAP_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"

typedef struct acd_edge_map {
    uint64_t *key;   /* (a << 32) | b, sorted */
    uint32_t *half;  /* 3t + i */
    size_t n;
    uint32_t *twin;  /* by half-edge: twin[3t + i] is the half-edge opposite 3t + i (kept by
                      * acd_edge_map_closed, for every triangle), or NULL when not computed */
} acd_edge_map;

#define ACD_EDGE_NONE UINT32_MAX

/* Builds the map of the triangles for which keep[t] is non-zero (keep NULL: all). Repeated
 * half-edges are kept (acd_edge_map_count tells how many). No twins (m->twin NULL). */
acd_status acd_edge_map_build(const uint32_t *triangles, size_t ntriangles, const uint8_t *keep, acd_edge_map *m,
                              acd_error *err);
/* Sorts a map the caller filled (m->key[0..n), m->half[0..n) in increasing half order, twin NULL)
 * into the order acd_edge_map_build gives: by key, equal keys by half. */
acd_status acd_edge_map_sort(acd_edge_map *m, acd_error *err);
void acd_edge_map_free(acd_edge_map *m);
/* The half-edge a -> b (the first of them if repeated), or ACD_EDGE_NONE. */
uint32_t acd_edge_map_find(const acd_edge_map *m, uint32_t a, uint32_t b);
/* How many half-edges a -> b there are. */
size_t acd_edge_map_count(const acd_edge_map *m, uint32_t a, uint32_t b);

/* For every entry i of the map (key order), the half-edge b -> a opposite key[i] = (a, b) (the
 * first if repeated, as acd_edge_map_find), or ACD_EDGE_NONE; *twin is malloc'd (m->n entries).
 * Linear after one radix sort, instead of a binary search per half-edge. */
acd_status acd_edge_map_twins(const acd_edge_map *m, uint32_t **twin, acd_error *err);

/* Checks that the triangles form a closed, consistently oriented 2-manifold-with-pinches: every
 * half-edge (a, b) unique, its opposite (b, a) present, no triangle repeating a vertex. Fails with
 * ACD_ERR_NON_MANIFOLD naming the triangle and the edge. */
acd_status acd_edge_map_check_closed(const acd_edge_map *m, const uint32_t *triangles, size_t ntriangles,
                                     acd_error *err);
/* Whether the triangles form such a surface: builds their map and checks it
 * (acd_edge_map_check_closed). ACD_OK: closed, and *map (when not NULL) holds the map with its
 * twins by half-edge (map->twin, from the check), freed by the caller. Otherwise the failure,
 * nothing left to free: ACD_ERR_NON_MANIFOLD (not closed, err names the triangle and the edge),
 * ACD_ERR_NOMEM, ACD_ERR_INVALID_ARGUMENT (too many triangles). */
acd_status acd_edge_map_closed(const uint32_t *triangles, size_t ntriangles, acd_edge_map *map, acd_error *err);
/* Its conditions one at a time (for a caller that walks the map anyway, as geom3/plane_cut): entry
 * i of m (twin: acd_edge_map_twins of m) is the only half-edge of its key (not repeated) and has an
 * opposite; the triangle q repeats no vertex. */
static inline int acd_edge_map_repeated(const acd_edge_map *m, size_t i) {
    return i + 1 < m->n && m->key[i + 1] == m->key[i];
}
static inline int acd_edge_map_entry_closed(const acd_edge_map *m, const uint32_t *twin, size_t i) {
    return twin[i] != ACD_EDGE_NONE && !acd_edge_map_repeated(m, i);
}
static inline int acd_edge_map_triangle_proper(const uint32_t *q) {
    return q[0] != q[1] && q[1] != q[2] && q[2] != q[0];
}

#endif
