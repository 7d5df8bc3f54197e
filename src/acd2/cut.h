/* acd2/cut: resolving a notch of a component by one cut (dissertation IV.B Alg. 5, IV.D.1
 * Eqn 4.3; spec acd2d.md §5): scoring of candidate endpoints, ray shooting to the first
 * boundary point, and the split of the ring into two rings. */
#ifndef ACD_ACD2_CUT_H
#define ACD_ACD2_CUT_H

#include <stddef.h>
#include <stdint.h>

#include "acd/acd2d.h"
#include "acd2/ring.h"

/* Where a cut from ring vertex r ends. */
typedef struct acd2_hit {
    size_t ring;     /* which ring (acd2_shoot_multi); 0 otherwise */
    int is_vertex;   /* 1: at ring vertex j; 0: at the new point z inside edge (j, j+1) */
    size_t j;
    acd_vec2 z;      /* the end point */
} acd2_hit;

/* First boundary point met by the segment from ring vertex r towards point x (x may be a ring
 * vertex or a point outside the ring). Vertices at r's coordinates are ignored; crossings count
 * only through edges whose interior side faces r; among coinciding vertices the copy whose
 * interior wedge contains r is taken. The result is verified with exact predicates: the open
 * segment from r to the end point crosses no edge and contains no vertex. Returns 0 on success,
 * -1 when nothing is hit (x not reachable; cannot happen for a point outside the ring). */
int acd2_shoot(const acd2_ring *ring, size_t r, acd_vec2 x, acd2_hit *hit);
/* The same among several rings (an outer ring and holes); the shot starts at vertex r of ring rr. */
int acd2_shoot_multi(const acd2_ring *rings, size_t nrings, size_t rr, size_t r, acd_vec2 x, acd2_hit *hit);

typedef struct acd2_cut_opts {
    double sc, sd;       /* Eqn 4.3 weights */
    acd2d_cut mode;
    double far;          /* a length larger than the ring's diameter (for bisector rays) */
    double weld;         /* snapping distance of a new point to an edge end */
} acd2_cut_opts;

/* Chooses the cut resolving notch r (Eqn 4.3 over the vertices strictly inside r's resolving
 * cone, scored with their stored concavity conc[]; ray mode shoots towards the best one and may
 * stop on an edge; diagonal mode takes the best visible one). Returns 0 or -1 (no cut found). */
int acd2_choose_cut(const acd2_ring *ring, const double *conc, size_t r, const acd2_cut_opts *o, acd2_hit *hit);

/* Splits ring along the cut from vertex r to hit; the new point (if any) gets id new_id.
 * a = r .. end, b = end .. r (both counterclockwise). Returns 0, or -1 when out of memory. */
int acd2_split(const acd2_ring *ring, size_t r, const acd2_hit *hit, int64_t new_id, acd2_ring *a, acd2_ring *b);

#endif
