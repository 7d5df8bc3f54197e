/* acd2/ring: one boundary ring of a 2D component (struct of arrays) and the exact local tests
 * the 2D decomposition makes on it (Lien, dissertation Ch. IV; spec acd2d.md §3.0, §5.3).
 *
 * A ring is counterclockwise with the interior on the left of every directed edge. Each vertex
 * carries an id: input vertices are numbered 0..n_input-1 over all rings of the input, new
 * (Steiner) points get ids >= n_input. Copies of a point made by a cut or a hole merge keep the
 * id of the point, so a ring in which an id appears twice touches itself (weakly simple). */
#ifndef ACD_ACD2_RING_H
#define ACD_ACD2_RING_H

#include <stddef.h>
#include <stdint.h>

#include "acd/polygon.h"
#include "core/predicates.h"

typedef struct acd2_ring {
    acd_vec2 *p;
    int64_t *id;
    double *c;    /* last measured concavity (a cache carried into the pieces of a cut) */
    int64_t *be;  /* at a bridge start: the id of the bridge's end, else -1 (same cache) */
    size_t n, cap;
} acd2_ring;

/* 0 on success, -1 when out of memory. */
int acd2_ring_reserve(acd2_ring *r, size_t cap);
int acd2_ring_push(acd2_ring *r, acd_vec2 p, int64_t id);
void acd2_ring_free(acd2_ring *r);
/* Appends src[from], src[from+1], ... (cyclically) count vertices. */
int acd2_ring_append_range(acd2_ring *dst, const acd2_ring *src, size_t from, size_t count);

/* Twice the signed area (shoelace relative to the first vertex). */
double acd2_ring_area2(const acd_vec2 *p, size_t n);

/* Inserts z (with id) between the consecutive vertices `from`, `to` (exact coordinates) of r,
 * at the first place where they occur. Resets the ring's bridge cache (be[]). Returns 1 when
 * inserted, 0 when the edge is not in r, -1 when out of memory. */
int acd2_ring_insert_on_edge(acd2_ring *r, acd_vec2 from, acd_vec2 to, acd_vec2 z, int64_t id);

/* Distance from z to the line through a, b (a != b), computed relative to a. */
double acd2_line_offset(acd_vec2 a, acd_vec2 b, acd_vec2 z);

/* Removes consecutive vertices at the same coordinates and spikes u,v,u (zero-area antennae),
 * cyclically, until none is left. */
void acd2_ring_clean(acd2_ring *r);

/* True if some id occurs twice; *i < *j receive the first such pair of positions. */
int acd2_ring_find_repeat(const acd2_ring *r, size_t *i, size_t *j, unsigned char *mark, int64_t id_limit);

static inline size_t acd2_next(size_t i, size_t n) { return i + 1 == n ? 0 : i + 1; }
static inline size_t acd2_prev(size_t i, size_t n) { return i == 0 ? n - 1 : i - 1; }

static inline double acd2_orient(acd_vec2 a, acd_vec2 b, acd_vec2 c) {
    const double A[2] = {a.x, a.y}, B[2] = {b.x, b.y}, C[2] = {c.x, c.y};
    return acd_orient2d(A, B, C);
}
static inline int acd2_orient_sign(acd_vec2 a, acd_vec2 b, acd_vec2 c) {
    const double A[2] = {a.x, a.y}, B[2] = {b.x, b.y}, C[2] = {c.x, c.y};
    return acd_orient2d_sign(A, B, C);
}
static inline int acd2_same(acd_vec2 a, acd_vec2 b) { return a.x == b.x && a.y == b.y; }

/* Notch test (spec §3.0): cross((v-u),(w-v)) < -tol; tol = 0 uses the exact sign. */
static inline int acd2_is_notch(acd_vec2 u, acd_vec2 v, acd_vec2 w, double tol) {
    if (tol <= 0) return acd2_orient_sign(u, v, w) < 0;
    return acd2_orient(u, v, w) < -tol;
}

/* Direction r->x lies strictly inside the resolving cone of notch r with neighbours u, w
 * (spec §5.3): cross(w-r, x-r) > 0 and cross(x-r, u-r) > 0. Exact. */
static inline int acd2_in_resolving_cone(acd_vec2 u, acd_vec2 r, acd_vec2 w, acd_vec2 x) {
    return acd2_orient_sign(r, w, x) > 0 && acd2_orient_sign(r, x, u) > 0;
}

/* Point q lies strictly inside the interior wedge at v (prev u, next w, interior on the left). */
int acd2_in_wedge(acd_vec2 u, acd_vec2 v, acd_vec2 w, acd_vec2 q);

/* Point q on the line through a, b (collinear, exactness assumed by the caller) lies strictly
 * between a and b (or equal to b when incl_b). Coordinate comparisons only: exact. */
int acd2_between(acd_vec2 a, acd_vec2 b, acd_vec2 q, int incl_b);

#endif
