/* acd3/trim: hulls trimmed within a coverage budget (see trim.h). */
#include "acd3/trim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "core/error.h"
#include "geom3/bvh.h"
#include "geom3/plane_cut.h"

/* The depths a facet's plane is moved inward by, as fractions of the cube root of the part's
 * initial hull volume (increasing). */
static const double ACD3_TRIM_DEPTHS[] = {0.001, 0.002, 0.005, 0.01, 0.02, 0.04};
#define NDEPTHS (sizeof ACD3_TRIM_DEPTHS / sizeof ACD3_TRIM_DEPTHS[0])
/* Distinct hulls cut per round (their next cuts searched in parallel); fixed, so the result does not
 * depend on the thread count. */
#define ACD3_TRIM_BATCH 4
/* A cut removing no part volume is scored as removing this fraction of min_gain (finite ratios). */
#define ACD3_TRIM_LOSS_FLOOR 1e-6

/* A candidate plane of a hull: a facet plane of the initial hull or a plane a cut was made by, and
 * its caps at the depths: the hull volume beyond (gain, for the current hull) and the part volume
 * beyond (loss: the part never changes, so computed once). */
typedef struct trim_plane {
    double n[3], off0;               /* n.x = off0: the facet's plane (n unit, outward) */
    double gain[NDEPTHS], loss[NDEPTHS];
    int have_loss;
} trim_plane;

typedef struct trim_hull {
    acd_hull h;       /* the current hull (dim 3) */
    acd_bvh bvh;      /* over the part's triangles */
    double unit;      /* depth unit: cube root of the initial hull volume */
    double centre[3]; /* of the initial hull's bounding box (apexes of the cones) */
    int active;       /* a solid hull that may still be cut */
    trim_plane *pl;   /* candidate planes */
    size_t npl, cappl;
    double *removed;  /* 3 * nremoved: the corners of the last cut's removed cap */
    size_t nremoved;
    int have;         /* best cut found */
    double plane[3], off, gain, loss, ratio, depth;
} trim_hull;

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* max of n.x over the box (lo, hi) */
static double box_max_proj(const double n[3], const double lo[3], const double hi[3]) {
    double s = 0;
    for (int k = 0; k < 3; k++) s += n[k] * (n[k] >= 0 ? hi[k] : lo[k]);
    return s;
}

static void apex_on(const double centre[3], const double n[3], double off, double o[3]) {
    double s = dot3(n, centre) - off; /* n unit */
    for (int k = 0; k < 3; k++) o[k] = centre[k] - s * n[k];
}

/* the volumes beyond the planes n.x = off[k] of the triangle (a, b, c), added to v[k] (offsets
 * decreasing: once a plane is above the triangle the shallower ones are too) */
static void add_beyond(const double *a, const double *b, const double *c, const double n[3], const double *off,
                       const double (*apex)[3], double *v) {
    double top = fmax(dot3(n, a), fmax(dot3(n, b), dot3(n, c)));
    for (size_t k = NDEPTHS; k-- > 0;) {
        if (!(top > off[k])) break;
        v[k] += acd_geom3_triangle_volume_beyond(a, b, c, n, off[k], apex[k]);
    }
}

/* The part's triangles beyond the deepest plane, through the BVH (a node whose box lies below it
 * holds none). */
static void part_beyond(const acd_bvh *bvh, const double n[3], const double *off, const double (*apex)[3], double *v) {
    if (bvh->nnodes == 0) return;
    uint32_t stack[128];
    int sp = 0;
    stack[sp++] = 0;
    const double deepest = off[NDEPTHS - 1];
    while (sp > 0) {
        const acd_bvh_node *nd = &bvh->nodes[stack[--sp]];
        if (!(box_max_proj(n, nd->lo, nd->hi) > deepest)) continue;
        if (nd->count > 0) {
            for (uint32_t i = nd->first; i < nd->first + nd->count; i++) {
                const uint32_t *t = bvh->triangles + 3 * (size_t)bvh->order[i];
                add_beyond(bvh->vertices + 3 * (size_t)t[0], bvh->vertices + 3 * (size_t)t[1],
                           bvh->vertices + 3 * (size_t)t[2], n, off, apex, v);
            }
        } else if (sp + 2 <= (int)(sizeof stack / sizeof stack[0])) {
            stack[sp++] = nd->first;
            stack[sp++] = nd->first + 1;
        } else { /* deeper than the stack (not with the SAH build's depths): the whole subtree, linearly */
            for (size_t i = 0; i < bvh->ntriangles; i++) {
                const uint32_t *t = bvh->triangles + 3 * i;
                add_beyond(bvh->vertices + 3 * (size_t)t[0], bvh->vertices + 3 * (size_t)t[1],
                           bvh->vertices + 3 * (size_t)t[2], n, off, apex, v);
            }
            return;
        }
    }
}

static void plane_offsets(const trim_hull *T, const trim_plane *P, double *off, double (*apex)[3]) {
    for (size_t k = 0; k < NDEPTHS; k++) {
        off[k] = P->off0 - ACD3_TRIM_DEPTHS[k] * T->unit;
        apex_on(T->centre, P->n, off[k], apex[k]);
    }
}

/* P's gains for the current hull, and its losses when not known and some gain reaches min_gain */
static void plane_measure(trim_hull *T, trim_plane *P, double min_gain) {
    double off[NDEPTHS], apex[NDEPTHS][3];
    plane_offsets(T, P, off, apex);
    memset(P->gain, 0, sizeof P->gain);
    const acd_hull *h = &T->h;
    for (size_t t = 0; t < h->ntriangles; t++) {
        const uint32_t *tr = h->triangles + 3 * t;
        add_beyond(h->vertices + 3 * (size_t)tr[0], h->vertices + 3 * (size_t)tr[1], h->vertices + 3 * (size_t)tr[2],
                   P->n, off, (const double(*)[3])apex, P->gain);
    }
    if (P->have_loss || !(P->gain[NDEPTHS - 1] >= min_gain)) return; /* the deepest cap holds the others */
    memset(P->loss, 0, sizeof P->loss);
    part_beyond(&T->bvh, P->n, off, (const double(*)[3])apex, P->loss);
    for (size_t k = 0; k < NDEPTHS; k++) P->loss[k] = fmax(P->loss[k], 0.0);
    P->have_loss = 1;
}

static int add_plane(trim_hull *T, const double n[3], double off0) {
    if (T->npl == T->cappl) {
        size_t nc = T->cappl ? 2 * T->cappl : 64;
        trim_plane *np = realloc(T->pl, nc * sizeof *np);
        if (!np) return 0;
        T->pl = np;
        T->cappl = nc;
    }
    trim_plane *P = &T->pl[T->npl++];
    memset(P, 0, sizeof *P);
    memcpy(P->n, n, sizeof P->n);
    P->off0 = off0;
    return 1;
}

/* The best cut of hull T among its planes' caps (largest gain / loss) removing at most `room` of
 * part volume. */
static void choose(trim_hull *T, double room, double min_gain, double ratio_floor, double loss_floor) {
    T->have = 0;
    if (!T->active) return;
    for (size_t j = 0; j < T->npl; j++) {
        const trim_plane *P = &T->pl[j];
        if (!P->have_loss) continue;
        for (size_t k = 0; k < NDEPTHS; k++) {
            if (!(P->gain[k] >= min_gain) || !(P->loss[k] <= room)) continue;
            double r = P->gain[k] / fmax(P->loss[k], loss_floor);
            if (!(r > ratio_floor) || (T->have && !(r > T->ratio))) continue;
            T->have = 1;
            memcpy(T->plane, P->n, sizeof T->plane);
            T->off = P->off0 - ACD3_TRIM_DEPTHS[k] * T->unit;
            T->gain = P->gain[k];
            T->loss = P->loss[k];
            T->ratio = r;
            T->depth = ACD3_TRIM_DEPTHS[k] * T->unit;
        }
    }
}

/* After a cut: the planes whose deepest cap reached into the removed cap measured again (a cap
 * meets that convex region exactly when one of its corners is beyond the plane), and the cut's
 * plane added as a candidate of its own. 0 when out of memory. */
static int after_cut(trim_hull *T, double min_gain) {
    for (size_t j = 0; j < T->npl; j++) {
        trim_plane *P = &T->pl[j];
        double deepest = P->off0 - ACD3_TRIM_DEPTHS[NDEPTHS - 1] * T->unit;
        int meets = 0;
        for (size_t v = 0; v < T->nremoved && !meets; v++) meets = dot3(P->n, T->removed + 3 * v) > deepest;
        if (meets) plane_measure(T, P, min_gain);
    }
    if (!add_plane(T, T->plane, T->off)) return 0;
    plane_measure(T, &T->pl[T->npl - 1], min_gain);
    return 1;
}

/* The hull's facet planes as candidates, measured (a facet split into triangles once: the triangle
 * of lowest index among its neighbours of the same plane; a few repeats are only extra work). */
static int init_planes(trim_hull *T, double min_gain) {
    const acd_hull *h = &T->h;
    for (size_t f = 0; f < h->ntriangles; f++) {
        const double *pl = h->planes + 4 * f;
        int repeat = 0;
        for (int e = 0; e < 3 && !repeat; e++) {
            uint32_t g = h->neighbors[3 * f + e];
            repeat = g < f && !memcmp(h->planes + 4 * (size_t)g, pl, 4 * sizeof *pl);
        }
        if (repeat) continue;
        if (!add_plane(T, pl, -pl[3])) return 0;
        plane_measure(T, &T->pl[T->npl - 1], min_gain);
    }
    return 1;
}

/* The hull cut by the plane: the hull of its vertices at or below it and of its edges' crossings
 * (the corners of the removed cap, the vertices beyond and the crossings, kept in T->removed).
 * 1 done, 0 refused (degenerate, or more than max_vertices), -1 out of memory. */
static int cut_hull(trim_hull *T, size_t max_vertices) {
    const acd_hull *h = &T->h;
    size_t room = h->nvertices + 3 * h->ntriangles;
    double *pts = malloc(3 * room * sizeof *pts), *rem = realloc(T->removed, 3 * room * sizeof *rem);
    if (!pts || !rem) {
        free(pts);
        if (rem) T->removed = rem;
        return -1;
    }
    T->removed = rem;
    size_t np = 0, nr = 0;
    for (size_t v = 0; v < h->nvertices; v++) {
        const double *x = h->vertices + 3 * v;
        if (dot3(T->plane, x) <= T->off)
            memcpy(pts + 3 * np++, x, 3 * sizeof *pts);
        else
            memcpy(rem + 3 * nr++, x, 3 * sizeof *rem);
    }
    for (size_t t = 0; t < h->ntriangles; t++)
        for (int e = 0; e < 3; e++) { /* each edge once: from the triangle of lower index */
            uint32_t g = h->neighbors[3 * t + e];
            if (g < t) continue;
            const double *a = h->vertices + 3 * (size_t)h->triangles[3 * t + e];
            const double *b = h->vertices + 3 * (size_t)h->triangles[3 * t + (e == 2 ? 0 : e + 1)];
            double sa = dot3(T->plane, a) - T->off, sb = dot3(T->plane, b) - T->off;
            if ((sa > 0) == (sb > 0)) continue;
            double x = sa / (sa - sb);
            for (int q = 0; q < 3; q++) pts[3 * np + q] = a[q] + x * (b[q] - a[q]);
            memcpy(rem + 3 * nr++, pts + 3 * np, 3 * sizeof *rem);
            np++;
        }
    T->nremoved = nr;
    acd_hull nh;
    acd_error e;
    acd_status st = acd_hull_compute(pts, np, &nh, &e);
    free(pts);
    if (st == ACD_ERR_NOMEM) return -1;
    if (st != ACD_OK) return 0;
    if (nh.dim != 3 || (max_vertices >= 4 && nh.nvertices > max_vertices)) {
        acd_hull_free(&nh);
        return 0;
    }
    acd_hull_free(&T->h);
    T->h = nh;
    return 1;
}

acd_status acd3_trim_hulls(acd3d_part *parts, size_t nparts, double input_volume, double budget, double min_gain,
                           size_t max_vertices, int threads, acd_progress_fn progress, void *progress_user,
                           acd3_trim_stats *stats, acd_error *err) {
    memset(stats, 0, sizeof *stats);
    for (size_t i = 0; i < nparts; i++) parts[i].trimmed_volume = 0;
    if (!(budget > 0) || nparts == 0 || !(input_volume > 0)) return ACD_OK;
    trim_hull *T = calloc(nparts, sizeof *T);
    acd_status *pst = calloc(nparts, sizeof *pst);
    if (!T || !pst) {
        free(T);
        free(pst);
        return acd_fail(err, ACD_ERR_NOMEM, "trim: out of memory");
    }
    double hull_sum = 0;
    for (size_t i = 0; i < nparts; i++) hull_sum += parts[i].hull_volume;
    /* a cut raises IoU = |M n U| / |M u U| when the hull volume it removes over the part volume it
     * removes exceeds 1 + |M u U| / |M n U|; the hulls' sum over the input's volume bounds that */
    const double ratio_floor = 1.0 + hull_sum / input_volume;
    const double loss_floor = ACD3_TRIM_LOSS_FLOOR * min_gain;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nparts > 1)
#endif
    for (long j = 0; j < (long)nparts; j++) {
        trim_hull *H = &T[j];
        const acd3d_part *p = &parts[j];
        H->h.dim = -1;
        if (!(p->volume > 0) || p->hull.nvertices < 4) continue;
        acd_error e;
        pst[j] = acd_hull_compute(p->hull.vertices, p->hull.nvertices, &H->h, &e);
        if (pst[j] != ACD_OK || H->h.dim != 3) continue;
        pst[j] = acd_bvh_build(&H->bvh, p->mesh.vertices, p->mesh.nvertices, p->mesh.triangles, p->mesh.ntriangles, &e);
        if (pst[j] != ACD_OK) continue;
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (size_t v = 0; v < H->h.nvertices; v++)
            for (int k = 0; k < 3; k++) {
                double x = H->h.vertices[3 * v + k];
                lo[k] = fmin(lo[k], x);
                hi[k] = fmax(hi[k], x);
            }
        for (int k = 0; k < 3; k++) H->centre[k] = lo[k] + 0.5 * (hi[k] - lo[k]);
        H->unit = cbrt(H->h.volume);
        H->active = 1;
        if (!init_planes(H, min_gain)) pst[j] = ACD_ERR_NOMEM;
    }
    acd_status st = ACD_OK;
    for (size_t i = 0; i < nparts && st == ACD_OK; i++)
        if (pst[i] == ACD_ERR_NOMEM) st = acd_fail(err, ACD_ERR_NOMEM, "trim: out of memory");
    double spent = 0;
    size_t batch[ACD3_TRIM_BATCH];
    while (st == ACD_OK) {
        if (progress && progress(progress_user, fmin(1.0, spent / budget), "trim")) {
            st = acd_fail(err, ACD_ERR_CANCELLED, "cancelled while trimming the hulls after %zu cuts", stats->cuts);
            break;
        }
        const double room = budget - spent;
        for (size_t j = 0; j < nparts; j++) choose(&T[j], room, min_gain, ratio_floor, loss_floor);
        /* the round: up to ACD3_TRIM_BATCH hulls of best ratio (ties: lower index), in that order,
         * while their cuts fit the budget */
        int nb = 0;
        for (size_t i = 0; i < nparts; i++) {
            if (!T[i].have) continue;
            int at = nb < ACD3_TRIM_BATCH ? nb++ : ACD3_TRIM_BATCH;
            while (at > 0 && T[batch[at - 1]].ratio < T[i].ratio) {
                if (at < ACD3_TRIM_BATCH) batch[at] = batch[at - 1];
                at--;
            }
            if (at < ACD3_TRIM_BATCH) batch[at] = i;
        }
        if (nb == 0) break;
        int take = 0;
        double planned = 0;
        for (int b = 0; b < nb; b++) {
            trim_hull *H = &T[batch[b]];
            if (planned + H->loss > room) break; /* the next round chooses within the room left */
            planned += H->loss;
            take = b + 1;
        }
        if (take == 0) continue;
        int res[ACD3_TRIM_BATCH];
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && take > 1)
#endif
        for (int b = 0; b < take; b++) {
            res[b] = cut_hull(&T[batch[b]], max_vertices);
            if (res[b] == 1 && !after_cut(&T[batch[b]], min_gain)) res[b] = -1;
        }
        for (int b = 0; b < take; b++) {
            trim_hull *H = &T[batch[b]];
            size_t i = batch[b];
            if (res[b] < 0) {
                st = acd_fail(err, ACD_ERR_NOMEM, "trim: out of memory");
                break;
            }
            if (res[b] == 0) { /* refused: this hull is left as it is */
                H->active = 0;
                continue;
            }
            spent += H->loss;
            parts[i].trimmed_volume += H->loss;
            stats->cuts++;
            stats->removed_hull += H->gain;
            stats->removed_part += H->loss;
            if (H->depth > stats->max_depth) stats->max_depth = H->depth;
        }
    }
    /* the trimmed hulls out */
    for (size_t i = 0; i < nparts && st == ACD_OK; i++) {
        trim_hull *H = &T[i];
        if (!(parts[i].trimmed_volume > 0)) continue;
        acd_mesh *m = &parts[i].hull;
        acd_mesh_free(m);
        m->vertices = H->h.vertices;
        m->nvertices = H->h.nvertices;
        m->triangles = H->h.triangles;
        m->ntriangles = H->h.ntriangles;
        parts[i].hull_volume = H->h.volume;
        H->h.vertices = NULL;
        H->h.triangles = NULL;
    }
    for (size_t i = 0; i < nparts; i++) {
        acd_hull_free(&T[i].h);
        acd_bvh_free(&T[i].bvh);
        free(T[i].pl);
        free(T[i].removed);
    }
    free(T);
    free(pst);
    return st;
}
