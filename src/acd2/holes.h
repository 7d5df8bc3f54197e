/* acd2/holes: resolving the holes of a polygon before any outer notch (dissertation IV.A.2,
 * IV.B, Figs. 19-23, Eqns 4.1-4.2, Alg. 5 line 4; spec acd2d.md §4 and the ★ procedure §4.6).
 *
 * Each merge joins one hole to the current outer boundary by a diagonal from one of the hole's
 * two principal-axis extremes (the approximate antipodal pair) to the first boundary point met
 * by a ray inside that vertex's resolving cone, aimed at the nearest boundary point in the cone.
 * A hole is ready when that point lies on the outer boundary (holes behind other holes wait:
 * the dependency order of Fig. 23); among ready holes the one with the largest Eqn 4.2 value
 * goes first. The merged boundary is weakly simple: the diagonal is a two-sided slit. */
#ifndef ACD_ACD2_HOLES_H
#define ACD_ACD2_HOLES_H

#include <stddef.h>
#include <stdint.h>

#include "acd/base.h"
#include "acd/polygon.h"
#include "acd2/cut.h"
#include "acd2/ring.h"

/* where a ray from a hole's extreme first meets the boundary (cached between merges) */
typedef struct acd2_target {
    int ok;
    size_t owner;       /* while computing: ring index; cached: 0 = outer, else hole index + 1 */
    acd2_hit hit;
    size_t e;           /* extreme position in the hole ring */
    double dist;        /* |from - hit| */
    acd_vec2 from;
    double aim_dist;    /* distance of the nearest boundary point in the cone (inf: bisector) */
    int64_t ida, idb;   /* ids of the hit vertex, or of the hit edge's ends */
} acd2_target;

typedef struct acd2_hole {
    acd2_ring ring;   /* clockwise */
    size_t ext[2];    /* principal-axis extremes (positions in ring) */
    int alive;
    int cached[2];
    acd2_target t[2];
} acd2_hole;

typedef struct acd2_holes {
    acd2_ring outer;  /* counterclockwise, holes merged so far spliced in */
    acd2_hole *h;
    size_t nh, alive;
    double *idconc;   /* concavity by vertex id (Eqn 4.2's concavity(x)); idcap entries */
    int64_t idcap;
    int64_t next_id;  /* next id for a new point */
    double far;       /* longer than the polygon's diameter */
    double weld;      /* a new point farther than this from the edge it splits is shared with the
                         edge's other side (a slit); set by the caller (0 after acd2_holes_init) */
    int force_bridge; /* tests only: always take the fallback bridge (0 after acd2_holes_init) */
} acd2_holes;

/* Takes the rings of poly (outer counterclockwise, holes clockwise); ids are positions in
 * poly->points. outer_conc[k] is the concavity of outer vertex k under the chosen measure. */
acd_status acd2_holes_init(acd2_holes *hs, const acd_polygon *poly, const double *outer_conc, double far,
                           acd_error *err);
void acd2_holes_free(acd2_holes *hs);

/* Merges one hole (into the outer ring, or, when every hole is blocked by others, into another
 * hole). When no hole gets a target through its resolving cones, the fallback is the classic
 * bridge from the rightmost hole vertex (holes.c, bridge_target), which always exists for valid
 * rings. seg receives the diagonal (hole vertex, boundary point); *into_outer whether the
 * merge reached the outer ring; *value the Eqn 4.2 value of the merged hole. */
acd_status acd2_holes_step(acd2_holes *hs, acd_vec2 seg[2], int *into_outer, double *value, acd_error *err);

/* Principal-axis extremes of a ring (Eqn 4.1 via the covariance eigenvector, ★ spec §4.2). */
void acd2_pa_extremes(const acd_vec2 *p, size_t n, size_t *lo, size_t *hi);

#endif
