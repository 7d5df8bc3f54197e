/* geom3/hull_volume: the volume of a point set's convex hull, for scores that compare many sets.
 *
 * A Quickhull of our own (Barber, Dobkin and Huhdanpaa's outside sets) written for one output, the
 * volume: no facet merging, no facets returned, no setup per call but a workspace the caller
 * reuses; 3-4x cheaper than a qhull run through acd_hull_compute on the sets acd3/budget scores
 * (docs/acd3d.md "Excess-driven budget"). The points of a removed facet go to the new facets or,
 * failing those, the horizon facets (as qhull's qh_findbestnew looks at both). Its tests are
 * floating-point (with a tolerance relative to the coordinates' scale), not the exact predicates
 * of core/predicates: a point just above a facet farther away can be lost, so the volume is an
 * estimate (against acd_hull_compute within 1e-9 relative on every set knot1's budget run scores,
 * within 2e-5 on fandisk's, a CAD model with many coplanar points). It is therefore used only to
 * rank candidate planes; every cut made and every volume reported comes from acd_hull_compute.
 * When the horizon is not one simple cycle (numerically ambiguous) the set is handed to
 * acd_hull_compute (qhull) instead. */
#ifndef ACD_GEOM3_HULL_VOLUME_H
#define ACD_GEOM3_HULL_VOLUME_H

#include <stddef.h>

struct acd_hv_facet;
struct acd_hv_out;

/* Scratch reused between calls (zero-initialise it; free with acd_hull_volume_ws_free). */
typedef struct acd_hull_volume_ws {
    struct acd_hv_facet *f;
    struct acd_hv_out *o; /* per facet: its outside set */
    unsigned char *alive; /* per facet: on the hull (the full scans read these, not the facets) */
    size_t nf, fcap;
    int *next, *start, *end, *stack; /* per point: list link, horizon edge from / to it;
                                       per facet: search stack */
    size_t pcap;
    int *pend, *visl;                   /* facets pending, facets visible */
    size_t pendcap, vcap;
    int *hor, *horf, *horu, *newf;      /* horizon: edges, facets (all, each once), new facets */
    size_t nnarrow;                     /* horizon edges a sweep's point is near the line of (in horu) */
    double *pl;                         /* planes of the new and horizon facets */
    size_t hcap;
    int *near;                          /* acd_hull_volume_sweep: points near the hull (see there) */
    size_t nnear, nearcap;
    int iter;  /* the visible search's stamp (vis, facets' marks) */
    int lastf; /* a facet made by the last step */
    int sweep; /* in acd_hull_volume_sweep (slivers and folds refused) */
    double cen[3]; /* the initial simplex's centroid: inside every facet of a valid hull */
} acd_hull_volume_ws;

void acd_hull_volume_ws_free(acd_hull_volume_ws *w);

/* The volume of the convex hull of n points (3 doubles each): 0 for fewer than 4 points or a flat
 * set, -1 when out of memory. *fallback (if not NULL) is set to 1 when qhull computed it. */
double acd_hull_volume_fast(const double *pts, size_t n, acd_hull_volume_ws *w, int *fallback);

/* The vertices of the hull of n points (3 doubles each) as this Quickhull finds them (a point within
 * its tolerance of the hull is not one): flag[i] = 1 for each (n flags), their count in *nflag.
 * Returns 1; 0 when it has none (fewer than 4 points, a flat set, or a set it leaves to qhull); -1
 * when out of memory. Not qhull's vertex set near rounding: for uses where any subset of the points
 * serves (acd3/budget's directions' bound: a subset's hull lies in the set's). */
int acd_hull_volume_vertices(const double *pts, size_t n, acd_hull_volume_ws *w, unsigned char *flag, size_t *nflag);

/* The hull volumes of nested sets swept along the unit direction dir, for scores that cut one
 * point set by parallel planes: query q's set is the first cnt[q] of the n points pts (sorted along
 * dir, cnt not decreasing) and the points xs[xb[q]..xe[q]) (3 doubles each), which lie on
 * a plane of normal dir at or beyond the prefix. One hull grows over the sweep (Quickhull's outside
 * sets: each query adds only the points since the previous one), each query's extra points (the
 * corners of their planar hull) are added and undone. A point found inside but above a facet (within
 * the tolerance) is kept and tested against the facets made later: beyond the rim of a nearly flat
 * prefix it can lie far outside (fuzz_hull_volume). vol[q]: the volume, or -3 when not computed
 * (fewer than 4 points, a flat prefix, or a numerically ambiguous step: a sliver, or a new facet
 * folding over its horizon facet; the caller computes those with acd_hull_volume_fast). Returns 0,
 * -1 when out of memory. */
int acd_hull_volume_sweep(const double *pts, size_t n, const double dir[3], const size_t *cnt, const double *xs,
                          const size_t *xb, const size_t *xe, int nq, double *vol, acd_hull_volume_ws *w);

/* The same sweep computing only the queries q with need[q] (need NULL: all), each the same bits as
 * the whole sweep gives it (a query's extra points are undone, so the hull each later query grows
 * from is the same); the others' vol[q] is -4, and the sweep stops after the last query asked for. */
int acd_hull_volume_sweep_some(const double *pts, size_t n, const double dir[3], const size_t *cnt, const double *xs,
                               const size_t *xb, const size_t *xe, int nq, const unsigned char *need, double *vol,
                               acd_hull_volume_ws *w);

#endif
