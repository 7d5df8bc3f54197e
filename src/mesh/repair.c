/* mesh/repair: welding, removal of degenerate and duplicate faces, consistent orientation
 * (closed parts outward), filling of small holes, removal of unused vertices.
 *
 * design (acd_mesh_repair):
 *  1. weld (mesh/weld: exact hashing or a tolerance grid);
 *  2. drop faces that repeat a vertex or have zero area (exact: all three coordinate projections
 *     collinear by acd_orient2d), then faces whose sorted vertex triple was seen before;
 *  3. orient: breadth-first over manifold edges from each part's first face, flipping a face
 *     when it traverses the shared edge in the same direction as its neighbour; a part all of
 *     whose edges are manifold (closed) faces outward (positive signed volume), unless it lies
 *     inside an odd number of other closed parts (by the winding number of sample vertices):
 *     then it bounds a cavity and faces inward; an open part is reversed if that flips fewer
 *     faces (majority orientation kept);
 *  3b. split non-manifold edges and vertices (split_nonmanifold): around an edge of more than two
 *     faces, consistently oriented, the faces are sorted by angle about the edge (ties, faces
 *     exactly in one half-plane, decided by orient3d) and each face using the edge b -> a is paired
 *     with the next one counterclockwise about a -> b, which uses it a -> b: the wedge between them
 *     is inside one solid. Corners of faces are joined across manifold edges and paired seams; each
 *     group of corners at a vertex beyond the first gets a copy of the vertex, unless the vertex is on
 *     a boundary edge (an open pinch stays: the holes meeting there are filled one by one, step 4).
 *     Bodies touching along
 *     an edge or at a point (a CAD assembly, OpenSCAD's booleans) become separate closed shells
 *     sharing positions; an edge whose faces do not alternate in direction is left as it is;
 *  4. fill holes: the boundary is walked along its half-edges and split into simple loops
 *     (a boundary through a pinch vertex gives one loop per side); a loop of at most
 *     fill_holes_max_edges edges is closed by the minimum-area triangulation over its own
 *     vertices that adds no edge the mesh already has (dynamic programme, loops up to
 *     FILL_DP_MAX_EDGES edges), else by a fan around a new vertex at its centroid, so the
 *     result stays edge-manifold; the new faces run against the loop (they agree with their
 *     neighbours); then orient again;
 *  5. drop unused vertices.
 * The caller's progress callback (opt->progress) is polled between the steps and every
 * ACD_REPAIR_POLL_ITEMS items of their passes over the faces (orient's half-edges and breadth-first
 * search, its parts' volumes and nesting rays, the degenerate test, the non-manifold split's and the
 * hole walk's loops): 0.8 CPU-s without a poll at 832k triangles before (issue 4 item 7). The sorts
 * (qsort of the faces' keys and corner edges) are not polled: 0.1-0.3 s at that size. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/mesh.h"
#include "core/error.h"
#include "core/predicates.h"
#include "core/tolerance.h"
#include "core/union_find.h"
#include "mesh/halfedge.h"
#include "mesh/weld.h"
#include "geom3/spatial.h"

/* The caller's callback, polled by the steps (opt->progress; fn NULL: never stops). One thread. */
typedef struct repair_poll {
    acd_progress_fn fn;
    void *user;
    const char *stage; /* the step's */
    int stop;          /* the callback asked to stop */
} repair_poll;

static int repair_stop(void *user) {
    repair_poll *p = user;
    if (p->fn && !p->stop && p->fn(p->user, -1.0, p->stage)) p->stop = 1;
    return p->stop;
}

/* polled at item i of a pass: every ACD_REPAIR_POLL_ITEMS-th item */
static int repair_stop_at(repair_poll *p, size_t i) { return i % ACD_REPAIR_POLL_ITEMS == 0 && repair_stop(p); }

/* polled when the count of items done reaches *next, then ACD_REPAIR_POLL_ITEMS items further (a
 * pass whose index moves by more than one) */
static int repair_stop_after(repair_poll *p, size_t done, size_t *next) {
    if (done < *next) return 0;
    *next = done + ACD_REPAIR_POLL_ITEMS;
    return repair_stop(p);
}

static acd_status repair_cancelled(const repair_poll *p, acd_error *err, size_t n, const char *what) {
    return acd_fail(err, ACD_ERR_CANCELLED, "%s: cancelled by the progress callback (%zu %s)", p->stage, n, what);
}

/* The start of a step: its stage set, a poll */
static acd_status repair_step(repair_poll *p, const char *stage, size_t nfaces, acd_error *err) {
    p->stage = stage;
    return repair_stop(p) ? repair_cancelled(p, err, nfaces, "faces") : ACD_OK;
}

acd_repair_options acd_repair_default_options(void) {
    acd_repair_options o;
    o.weld = 1;
    o.weld_tolerance = 0;
    o.drop_degenerate = 1;
    o.drop_duplicates = 1;
    o.orient = 1;
    o.fill_holes_max_edges = 0;
    o.drop_unused_vertices = 1;
    o.split_nonmanifold = 1;
    o.progress = NULL;
    o.progress_user = NULL;
    return o;
}

acd_status acd_mesh_weld(acd_mesh *m, double tol_rel, size_t *merged, acd_error *err) {
    if (!m || (m->nvertices && !m->vertices)) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_weld: NULL mesh");
    if (!(tol_rel >= 0) || !isfinite(tol_rel))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_weld: tolerance %g is not a finite number >= 0", tol_rel);
    for (size_t i = 0; i < 3 * m->ntriangles; i++)
        if (m->triangles[i] >= m->nvertices)
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "triangle %zu refers to vertex %u of %zu", i / 3, m->triangles[i],
                            m->nvertices);
    if (merged) *merged = 0;
    if (m->nvertices == 0) return ACD_OK;
    uint32_t *remap = malloc(m->nvertices * sizeof *remap);
    if (!remap) return acd_fail(err, ACD_ERR_NOMEM, "out of memory welding %zu vertices", m->nvertices);
    size_t u;
    int ok;
    if (tol_rel > 0) {
        acd_scale sc = acd_scale_of_points(m->vertices, m->nvertices, 3);
        ok = acd_weld_tolerance(m->vertices, m->nvertices, tol_rel * sc.extent, remap, &u);
    } else {
        ok = acd_weld_exact(m->vertices, m->nvertices, remap, &u);
    }
    if (!ok) {
        free(remap);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory welding %zu vertices", m->nvertices);
    }
    for (size_t i = 0; i < 3 * m->ntriangles; i++) m->triangles[i] = remap[m->triangles[i]];
    acd_weld_compact(m->vertices, m->nvertices, remap);
    if (merged) *merged = m->nvertices - u;
    m->nvertices = u;
    free(remap);
    return ACD_OK;
}

static int zero_area(const double *a, const double *b, const double *c) {
    for (int d = 0; d < 3; d++) {
        double pa[2] = {a[(d + 1) % 3], a[(d + 2) % 3]}, pb[2] = {b[(d + 1) % 3], b[(d + 2) % 3]},
               pc[2] = {c[(d + 1) % 3], c[(d + 2) % 3]};
        if (acd_orient2d_sign(pa, pb, pc) != 0) return 0;
    }
    return 1;
}

/* Keeps the faces with keep[t] != 0, in order. */
static void filter_faces(acd_mesh *m, const unsigned char *keep) {
    size_t n = 0;
    for (size_t t = 0; t < m->ntriangles; t++)
        if (keep[t]) {
            if (n != t) memmove(m->triangles + 3 * n, m->triangles + 3 * t, 3 * sizeof(uint32_t));
            n++;
        }
    m->ntriangles = n;
}

typedef struct tri_key {
    uint32_t v[3];
    uint32_t t;
} tri_key;

static int cmp_key(const void *x, const void *y) {
    const tri_key *a = x, *b = y;
    for (int k = 0; k < 3; k++)
        if (a->v[k] != b->v[k]) return a->v[k] < b->v[k] ? -1 : 1;
    return a->t < b->t ? -1 : a->t > b->t;
}

static acd_status drop_faces(acd_mesh *m, int degenerate, int duplicates, acd_repair_stats *st, repair_poll *poll,
                             acd_error *err) {
    size_t nt = m->ntriangles;
    if (!nt) return ACD_OK;
    unsigned char *keep = malloc(nt);
    tri_key *keys = duplicates ? malloc(nt * sizeof *keys) : NULL;
    if (!keep || (duplicates && !keys)) {
        free(keep);
        free(keys);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory repairing %zu faces", nt);
    }
    for (size_t t = 0; t < nt; t++) {
        if (repair_stop_at(poll, t)) {
            free(keep);
            free(keys);
            return repair_cancelled(poll, err, nt, "faces");
        }
        const uint32_t *i = m->triangles + 3 * t;
        keep[t] = 1;
        if (degenerate && (i[0] == i[1] || i[1] == i[2] || i[0] == i[2] ||
                           zero_area(m->vertices + 3 * (size_t)i[0], m->vertices + 3 * (size_t)i[1],
                                     m->vertices + 3 * (size_t)i[2]))) {
            keep[t] = 0;
            st->degenerate_dropped++;
        }
    }
    if (duplicates) {
        size_t n = 0;
        for (size_t t = 0; t < nt; t++) {
            if (!keep[t]) continue;
            uint32_t a = m->triangles[3 * t], b = m->triangles[3 * t + 1], c = m->triangles[3 * t + 2], x;
            if (a > b) { x = a; a = b; b = x; }
            if (b > c) { x = b; b = c; c = x; }
            if (a > b) { x = a; a = b; b = x; }
            keys[n].v[0] = a;
            keys[n].v[1] = b;
            keys[n].v[2] = c;
            keys[n].t = (uint32_t)t;
            n++;
        }
        qsort(keys, n, sizeof *keys, cmp_key);
        for (size_t i = 1; i < n; i++)
            if (!memcmp(keys[i].v, keys[i - 1].v, sizeof keys[i].v)) {
                keep[keys[i].t] = 0; /* the first face (lowest index) of each group stays */
                st->duplicates_dropped++;
            }
    }
    filter_faces(m, keep);
    free(keep);
    free(keys);
    return ACD_OK;
}

static double tet_volume(const acd_mesh *m, size_t t, const double o[3]) {
    const uint32_t *i = m->triangles + 3 * t;
    const double *a = m->vertices + 3 * (size_t)i[0], *b = m->vertices + 3 * (size_t)i[1],
                 *c = m->vertices + 3 * (size_t)i[2];
    double pa[3] = {a[0] - o[0], a[1] - o[1], a[2] - o[2]}, pb[3] = {b[0] - o[0], b[1] - o[1], b[2] - o[2]},
           pc[3] = {c[0] - o[0], c[1] - o[1], c[2] - o[2]};
    return (pa[0] * (pb[1] * pc[2] - pb[2] * pc[1]) - pa[1] * (pb[0] * pc[2] - pb[2] * pc[0]) +
            pa[2] * (pb[0] * pc[1] - pb[1] * pc[0])) / 6.0;
}

static void flip_face(acd_mesh *m, size_t t) {
    uint32_t x = m->triangles[3 * t + 1];
    m->triangles[3 * t + 1] = m->triangles[3 * t + 2];
    m->triangles[3 * t + 2] = x;
}

/* One part of orient(): its faces are queue[start .. start + n). */
typedef struct orient_part {
    size_t start, n;
    double vol;     /* signed volume with the propagated orientation (closed, orientable parts) */
    double lo[3], hi[3];
    int closed;     /* closed and orientable */
    int reverse;
} orient_part;

/* Vertices of a closed part tested against each other closed part that might hold it (nesting),
 * spread over its faces; the part is inside the other when all are. */
#define NEST_SAMPLES 8

/* One ray of the nesting test: from a sample point towards +x through the whole mesh's BVH, each
 * crossing counted (exactly: geom3/spatial, simulation of simplicity at edges and vertices) for the
 * part its face belongs to, with the orientation orient() gave it. */
typedef struct nest_ray {
    const acd_spatial *sp;
    const double *p;
    const uint32_t *part_of; /* face -> part */
    const unsigned char *flip;
    int *wind;               /* per part: signed crossings */
    unsigned char *on;       /* per part: the point lies on one of its faces */
    uint32_t *touched;       /* parts whose wind or on was set (to reset them; a part may be listed
                                again after its crossings cancelled: at most one entry per crossing) */
    size_t ntouched;
} nest_ray;

static int nest_visit(void *user, uint32_t t) {
    nest_ray *r = user;
    int on = 0;
    int c = acd_spatial_ray_crossing(r->sp, t, r->p, &on);
    if (!c && !on) return 0;
    uint32_t q = r->part_of[t];
    if (!r->wind[q] && !r->on[q]) r->touched[r->ntouched++] = q;
    r->wind[q] += r->flip[t] ? -c : c;
    r->on[q] |= (unsigned char)on;
    return 0;
}

/* Nesting depth of each closed part: how many other closed parts contain it whole (all its samples
 * inside: a non-zero crossing count of that part's faces along the ray, the point not on them).
 * depth[] = -1 for open parts. One ray per sample through the mesh's BVH (before 2026-11-27: the
 * winding number summed over every face of every candidate part, 12 s for 600 cubes in an
 * 80,000-face sphere). Returns 0 when memory runs out (no depth known), -1 when poll says stop
 * (polled every ACD_REPAIR_POLL_ITEMS / NEST_SAMPLES closed parts, so every ACD_REPAIR_POLL_ITEMS
 * rays). */
static int nesting_depths(const acd_mesh *m, const uint32_t *queue, const unsigned char *flip, const orient_part *parts,
                          size_t np, int *depth, repair_poll *poll) {
    size_t nclosed = 0;
    for (size_t i = 0; i < np; i++) nclosed += parts[i].closed;
    for (size_t i = 0; i < np; i++) depth[i] = parts[i].closed ? 0 : -1;
    if (nclosed < 2) return 1;
    int ok = 0;
    acd_spatial sp;
    memset(&sp, 0, sizeof sp);
    uint32_t *part_of = malloc(m->ntriangles * sizeof *part_of);
    int *wind = calloc(np, sizeof *wind);
    unsigned char *on = calloc(np, 1);
    uint32_t *touched = malloc((m->ntriangles + 1) * sizeof *touched);
    uint32_t *cnt = calloc(np, sizeof *cnt);
    if (!part_of || !wind || !on || !touched || !cnt) goto done;
    if (acd_spatial_build(&sp, m->vertices, m->nvertices, m->triangles, m->ntriangles, NULL) != ACD_OK) goto done;
    for (size_t i = 0; i < np; i++)
        for (size_t k = parts[i].start; k < parts[i].start + parts[i].n; k++) part_of[queue[k]] = (uint32_t)i;
    for (size_t i = 0, nc = 0; i < np; i++) {
        if (!parts[i].closed) continue;
        if (repair_stop_at(poll, nc++ * NEST_SAMPLES)) {
            ok = -1;
            goto done;
        }
        memset(cnt, 0, np * sizeof *cnt);
        for (size_t s = 0; s < NEST_SAMPLES; s++) {
            uint32_t t = queue[parts[i].start + s * parts[i].n / NEST_SAMPLES];
            const double *p = m->vertices + 3 * (size_t)m->triangles[3 * (size_t)t + s % 3];
            nest_ray r = {&sp, p, part_of, flip, wind, on, touched, 0};
            acd_bvh_query_axis_line(&sp.bvh, p, 0, 1, nest_visit, &r);
            for (size_t k = 0; k < r.ntouched; k++) {
                uint32_t q = touched[k];
                if (wind[q] && !on[q]) cnt[q]++;
                wind[q] = 0, on[q] = 0; /* a part listed twice counts once: reset on its first visit */
            }
        }
        for (size_t j = 0; j < np; j++) {
            if (j == i || !parts[j].closed || cnt[j] < NEST_SAMPLES) continue;
            int boxed = 1;
            for (int k = 0; k < 3; k++) boxed &= parts[j].lo[k] <= parts[i].lo[k] && parts[i].hi[k] <= parts[j].hi[k];
            depth[i] += boxed;
        }
    }
    ok = 1;
done:
    acd_spatial_free(&sp);
    free(part_of), free(wind), free(on), free(touched), free(cnt);
    return ok;
}

static acd_status orient(acd_mesh *m, acd_repair_stats *st, int count_nonorientable, repair_poll *poll,
                         acd_error *err) {
    size_t nt = m->ntriangles;
    if (!nt) return ACD_OK;
    acd_halfedges he;
    acd_status s = acd_halfedges_build_poll(m, &he, poll->fn ? repair_stop : NULL, poll, err);
    if (s == ACD_ERR_CANCELLED) return repair_cancelled(poll, err, nt, "faces");
    if (s != ACD_OK) return s;
    unsigned char *flip = calloc(nt, 1), *seen = calloc(nt, 1);
    uint32_t *queue = malloc(nt * sizeof *queue);
    orient_part *parts = NULL;
    int *depth = NULL;
    size_t np = 0, cap = 0;
    if (!flip || !seen || !queue) {
        s = acd_fail(err, ACD_ERR_NOMEM, "out of memory orienting %zu faces", nt);
        goto done;
    }
    double o[3] = {0, 0, 0};
    if (m->nvertices) memcpy(o, m->vertices, sizeof o); /* any fixed origin: volumes of closed parts do not depend on it */
    size_t qt = 0; /* the parts follow each other in queue */
    for (size_t t0 = 0; t0 < nt; t0++) {
        if (seen[t0]) continue;
        size_t start = qt, qh = qt, nflip = 0;
        int closed = 1, orientable = 1;
        queue[qt++] = (uint32_t)t0;
        seen[t0] = 1;
        while (qh < qt) {
            if (repair_stop_at(poll, qh)) {
                s = repair_cancelled(poll, err, nt, "faces");
                goto done;
            }
            uint32_t t = queue[qh++];
            for (uint32_t k = 0; k < 3; k++) {
                uint32_t h = 3 * t + k, g = he.twin[h];
                if (g == ACD_HE_NONE) {
                    closed = 0;
                    continue;
                }
                unsigned char want = (unsigned char)(flip[t] ^ (acd_he_from(m, g) == acd_he_from(m, h)));
                uint32_t u = g / 3;
                if (!seen[u]) {
                    seen[u] = 1;
                    flip[u] = want;
                    nflip += want;
                    queue[qt++] = u;
                } else if (flip[u] != want) {
                    orientable = 0;
                }
            }
        }
        if (!orientable && count_nonorientable) st->nonorientable_parts++;
        if (np == cap) {
            size_t nc = cap ? 2 * cap : 16;
            orient_part *q = realloc(parts, nc * sizeof *q);
            if (!q) {
                s = acd_fail(err, ACD_ERR_NOMEM, "out of memory orienting %zu faces", nt);
                goto done;
            }
            parts = q;
            cap = nc;
        }
        orient_part *P = &parts[np++];
        memset(P, 0, sizeof *P);
        P->start = start;
        P->n = qt - start;
        P->closed = closed && orientable;
        if (P->closed) {
            for (int k = 0; k < 3; k++) P->lo[k] = P->hi[k] = m->vertices[3 * (size_t)m->triangles[3 * (size_t)t0] + k];
            for (size_t i = start; i < qt; i++) {
                if (repair_stop_at(poll, i)) {
                    s = repair_cancelled(poll, err, nt, "faces");
                    goto done;
                }
                double v = tet_volume(m, queue[i], o);
                P->vol += flip[queue[i]] ? -v : v;
                for (int c = 0; c < 3; c++)
                    for (int k = 0; k < 3; k++) {
                        double x = m->vertices[3 * (size_t)m->triangles[3 * (size_t)queue[i] + c] + k];
                        P->lo[k] = fmin(P->lo[k], x);
                        P->hi[k] = fmax(P->hi[k], x);
                    }
            }
            P->reverse = P->vol < 0;
        } else {
            P->reverse = 2 * nflip > P->n;
        }
    }
    /* a closed part inside an odd number of other closed parts bounds a cavity: it faces inward */
    depth = malloc(np * sizeof *depth);
    if (!depth) {
        s = acd_fail(err, ACD_ERR_NOMEM, "out of memory orienting %zu parts", np);
        goto done;
    }
    st->cavities = 0; /* counted by the last pass (orient runs again after hole filling) */
    int nested = nesting_depths(m, queue, flip, parts, np, depth, poll);
    if (nested < 0) {
        s = repair_cancelled(poll, err, np, "parts");
        goto done;
    }
    if (nested)
        for (size_t i = 0; i < np; i++)
            if (parts[i].closed && depth[i] % 2 == 1) {
                parts[i].reverse = parts[i].vol > 0;
                st->cavities++;
            }
    for (size_t p = 0; p < np; p++)
        for (size_t i = parts[p].start; i < parts[p].start + parts[p].n; i++) {
            uint32_t t = queue[i];
            if (flip[t] ^ (unsigned char)parts[p].reverse) {
                flip_face(m, t);
                st->faces_flipped++;
            }
        }
done:
    free(flip);
    free(seen);
    free(queue);
    free(parts);
    free(depth);
    acd_halfedges_free(&he);
    return s;
}

/* An open-addressing set of undirected edges (key: smaller vertex << 32 | larger). */
typedef struct edge_set {
    uint64_t *slot; /* EDGE_SET_EMPTY when free */
    size_t mask, n;
} edge_set;

#define EDGE_SET_EMPTY UINT64_MAX

static uint64_t edge_key(uint32_t a, uint32_t b) {
    return a < b ? ((uint64_t)a << 32) | b : ((uint64_t)b << 32) | a;
}

static size_t edge_hash(uint64_t k, size_t mask) {
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdULL;
    k ^= k >> 33;
    return (size_t)k & mask;
}

static int edge_set_init(edge_set *s, size_t expected) {
    size_t cap = 16;
    while (cap < 2 * expected + 16) cap *= 2;
    s->slot = malloc(cap * sizeof *s->slot);
    if (!s->slot) return 0;
    for (size_t i = 0; i < cap; i++) s->slot[i] = EDGE_SET_EMPTY;
    s->mask = cap - 1;
    s->n = 0;
    return 1;
}

static int edge_set_has(const edge_set *s, uint32_t a, uint32_t b) {
    uint64_t k = edge_key(a, b);
    for (size_t i = edge_hash(k, s->mask);; i = (i + 1) & s->mask) {
        if (s->slot[i] == k) return 1;
        if (s->slot[i] == EDGE_SET_EMPTY) return 0;
    }
}

static int edge_set_add(edge_set *s, uint32_t a, uint32_t b) {
    if (2 * (s->n + 1) > s->mask + 1) { /* grow */
        edge_set g;
        if (!edge_set_init(&g, s->mask + 1)) return 0;
        for (size_t i = 0; i <= s->mask; i++)
            if (s->slot[i] != EDGE_SET_EMPTY) {
                size_t j = edge_hash(s->slot[i], g.mask);
                while (g.slot[j] != EDGE_SET_EMPTY) j = (j + 1) & g.mask;
                g.slot[j] = s->slot[i];
            }
        g.n = s->n;
        free(s->slot);
        *s = g;
    }
    uint64_t k = edge_key(a, b);
    size_t i = edge_hash(k, s->mask);
    for (; s->slot[i] != EDGE_SET_EMPTY; i = (i + 1) & s->mask)
        if (s->slot[i] == k) return 1;
    s->slot[i] = k;
    s->n++;
    return 1;
}

/* Output of hole filling: triangles and new vertices appended to growable arrays. */
typedef struct fill_out {
    uint32_t *tri;
    size_t ntri, tcap;
    double *vert;
    size_t nvert, vcap;
} fill_out;

static int fill_push_tri(fill_out *o, uint32_t a, uint32_t b, uint32_t c) {
    if (o->ntri == o->tcap) {
        size_t c2 = o->tcap ? 2 * o->tcap : 64;
        uint32_t *t2 = realloc(o->tri, c2 * 3 * sizeof *t2);
        if (!t2) return 0;
        o->tri = t2;
        o->tcap = c2;
    }
    o->tri[3 * o->ntri] = a;
    o->tri[3 * o->ntri + 1] = b;
    o->tri[3 * o->ntri + 2] = c;
    o->ntri++;
    return 1;
}

static double tri_area(const double *p, const double *q, const double *r) {
    double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    return 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

/* Loops up to this many edges are triangulated by the minimum-area dynamic programme over
 * their own vertices (O(n^3)); longer loops, and loops whose every triangulation would repeat
 * an existing edge, get a fan around one new vertex at their centroid. */
#define FILL_DP_MAX_EDGES 96

/* Closes the simple loop v[0..n-1] (the boundary runs v[i] -> v[i+1]); the new faces run
 * against it so they agree with their neighbours. Returns 0 when out of memory. */
static int fill_loop(const acd_mesh *m, const uint32_t *v, size_t n, edge_set *edges, fill_out *o,
                     size_t new_vertex_index) {
    if (n <= FILL_DP_MAX_EDGES) {
        /* cost[i][j]: minimum area of a triangulation of the sub-polygon v[i..j] whose
         * diagonals are all new edges; split[i][j]: the apex k of the triangle on (i, j) */
        double *cost = malloc(n * n * sizeof *cost);
        uint32_t *split = malloc(n * n * sizeof *split);
        if (!cost || !split) {
            free(cost);
            free(split);
            return 0;
        }
        for (size_t i = 0; i + 1 < n; i++) cost[i * n + i + 1] = 0;
        for (size_t len = 2; len < n; len++)
            for (size_t i = 0; i + len < n; i++) {
                size_t j = i + len;
                double best = INFINITY;
                uint32_t bk = 0;
                /* (i, j) is a diagonal unless it is the loop's closing edge (0, n-1) */
                int diag_ok = (i == 0 && j == n - 1) || !edge_set_has(edges, v[i], v[j]);
                if (diag_ok)
                    for (size_t k = i + 1; k < j; k++) {
                        double c = cost[i * n + k] + cost[k * n + j];
                        if (!(c < best)) continue;
                        c += tri_area(m->vertices + 3 * (size_t)v[i], m->vertices + 3 * (size_t)v[k],
                                      m->vertices + 3 * (size_t)v[j]);
                        if (c < best) {
                            best = c;
                            bk = (uint32_t)k;
                        }
                    }
                cost[i * n + j] = best;
                split[i * n + j] = bk;
            }
        int ok = 1, feasible = isfinite(cost[n - 1]) != 0;
        if (feasible) {
            /* emit the triangles (iterative, a stack of sub-polygons) */
            size_t *stack = malloc(2 * n * sizeof *stack), top = 0;
            if (!stack) ok = 0;
            if (ok) {
                stack[top++] = 0;
                stack[top++] = n - 1;
            }
            while (ok && top) {
                size_t j = stack[--top], i = stack[--top];
                if (j - i < 2) continue;
                size_t k = split[i * n + j];
                ok = fill_push_tri(o, v[i], v[j], v[k]) && edge_set_add(edges, v[i], v[j]) &&
                     edge_set_add(edges, v[i], v[k]) && edge_set_add(edges, v[k], v[j]);
                stack[top++] = i;
                stack[top++] = k;
                stack[top++] = k;
                stack[top++] = j;
            }
            free(stack);
        }
        free(cost);
        free(split);
        if (!ok) return 0;
        if (feasible) return 1;
    }
    /* a fan around a new vertex at the centroid of the loop */
    if (o->nvert == o->vcap) {
        size_t c2 = o->vcap ? 2 * o->vcap : 16;
        double *v2 = realloc(o->vert, c2 * 3 * sizeof *v2);
        if (!v2) return 0;
        o->vert = v2;
        o->vcap = c2;
    }
    double *c = o->vert + 3 * o->nvert;
    c[0] = c[1] = c[2] = 0;
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 3; d++) c[d] += m->vertices[3 * (size_t)v[i] + d];
    for (int d = 0; d < 3; d++) c[d] /= (double)n;
    uint32_t ci = (uint32_t)(new_vertex_index + o->nvert);
    o->nvert++;
    for (size_t i = 0; i < n; i++)
        if (!fill_push_tri(o, ci, v[(i + 1) % n], v[i])) return 0;
    return 1;
}

static acd_status fill_holes(acd_mesh *m, size_t max_edges, acd_repair_stats *st, repair_poll *poll, acd_error *err) {
    if (!max_edges || !m->ntriangles) return ACD_OK;
    acd_halfedges he;
    acd_status s = acd_halfedges_build_poll(m, &he, poll->fn ? repair_stop : NULL, poll, err);
    if (s == ACD_ERR_CANCELLED) return repair_cancelled(poll, err, m->ntriangles, "faces");
    if (s != ACD_OK) return s;
    size_t nh = he.nhalfedges, nv = m->nvertices;
    /* boundary half-edges by their start vertex (CSR over vertices) */
    uint32_t *start = calloc(nv + 1, sizeof *start);
    uint32_t *list = malloc((nh ? nh : 1) * sizeof *list);
    unsigned char *used = calloc(nh ? nh : 1, 1);
    uint32_t *pathv = malloc((nh + 1) * sizeof *pathv);
    size_t *pos = malloc((nv ? nv : 1) * sizeof *pos);
    uint32_t *fillp = malloc((nv ? nv : 1) * sizeof *fillp);
    edge_set edges = {0};
    fill_out out = {0};
    if (!start || !list || !used || !pathv || !pos || !fillp || !edge_set_init(&edges, nh)) {
        s = acd_fail(err, ACD_ERR_NOMEM, "out of memory filling holes");
        goto done;
    }
    for (size_t h = 0; h < nh; h++) {
        if (repair_stop_at(poll, h)) {
            s = repair_cancelled(poll, err, m->ntriangles, "faces");
            goto done;
        }
        if (!edge_set_add(&edges, acd_he_from(m, (uint32_t)h), acd_he_to(m, (uint32_t)h))) {
            s = acd_fail(err, ACD_ERR_NOMEM, "out of memory filling holes");
            goto done;
        }
        if (he.edge[h] != ACD_HE_NONE && acd_edge_valence(&he, he.edge[h]) == 1) start[acd_he_from(m, (uint32_t)h) + 1]++;
    }
    for (size_t v = 0; v < nv; v++) start[v + 1] += start[v];
    memcpy(fillp, start, nv * sizeof *fillp);
    for (size_t h = 0; h < nh; h++)
        if (he.edge[h] != ACD_HE_NONE && acd_edge_valence(&he, he.edge[h]) == 1)
            list[fillp[acd_he_from(m, (uint32_t)h)]++] = (uint32_t)h;
    for (size_t v = 0; v < nv; v++) pos[v] = SIZE_MAX;
    /* Walk the boundary; whenever the walk returns to a vertex already on its path, the part
     * of the path since that vertex is a simple loop: close it and go on from that vertex. A
     * boundary that passes twice through a vertex (a pinch) thus gives two simple loops. The poll
     * counts the half-edges walked and n^2 per loop of n edges filled (its programme is n^3 steps
     * of a few operations). m is changed only after the walk. */
    size_t work = 0, next_poll = 0;
    for (size_t b = 0; b < start[nv]; b++) {
        uint32_t cur = list[b];
        if (used[cur]) continue;
        if (repair_stop_after(poll, work, &next_poll)) {
            s = repair_cancelled(poll, err, m->ntriangles, "faces");
            goto done;
        }
        size_t top = 0;
        pathv[0] = acd_he_from(m, cur);
        pos[pathv[0]] = 0;
        for (;;) {
            used[cur] = 1;
            uint32_t w = acd_he_to(m, cur);
            if (pos[w] != SIZE_MAX) {
                size_t k = pos[w], n = top - k + 1;
                if (n >= 3 && n <= max_edges) {
                    if (!fill_loop(m, pathv + k, n, &edges, &out, nv)) {
                        s = acd_fail(err, ACD_ERR_NOMEM, "out of memory filling holes");
                        goto done;
                    }
                    st->holes_filled++;
                    work += n * (n < FILL_DP_MAX_EDGES ? n : FILL_DP_MAX_EDGES);
                }
                for (size_t q = k + 1; q <= top; q++) pos[pathv[q]] = SIZE_MAX;
                top = k;
            } else {
                pathv[++top] = w;
                pos[w] = top;
            }
            uint32_t next = ACD_HE_NONE, at = pathv[top];
            for (uint32_t j = start[at]; j < start[at + 1] && next == ACD_HE_NONE; j++)
                if (!used[list[j]]) next = list[j];
            if (next == ACD_HE_NONE) break; /* closed (top 0) or an open chain: stop the walk */
            cur = next;
            work++;
        }
        for (size_t q = 0; q <= top; q++) pos[pathv[q]] = SIZE_MAX;
    }
    if (out.ntri) {
        uint32_t *t2 = realloc(m->triangles, (m->ntriangles + out.ntri) * 3 * sizeof *t2);
        if (!t2) {
            s = acd_fail(err, ACD_ERR_NOMEM, "out of memory filling holes");
            goto done;
        }
        m->triangles = t2;
        memcpy(m->triangles + 3 * m->ntriangles, out.tri, out.ntri * 3 * sizeof *out.tri);
        m->ntriangles += out.ntri;
        st->hole_faces_added += out.ntri;
    }
    if (out.nvert) {
        double *v2 = realloc(m->vertices, (nv + out.nvert) * 3 * sizeof *v2);
        if (!v2) {
            s = acd_fail(err, ACD_ERR_NOMEM, "out of memory filling holes");
            goto done;
        }
        m->vertices = v2;
        memcpy(m->vertices + 3 * nv, out.vert, out.nvert * 3 * sizeof *out.vert);
        m->nvertices += out.nvert;
        st->hole_vertices_added += out.nvert;
    }
done:
    free(start);
    free(list);
    free(used);
    free(pathv);
    free(pos);
    free(fillp);
    free(edges.slot);
    free(out.tri);
    free(out.vert);
    acd_halfedges_free(&he);
    return s;
}

static acd_status drop_unused(acd_mesh *m, acd_repair_stats *st, acd_error *err) {
    if (!m->nvertices) return ACD_OK;
    uint32_t *remap = malloc(m->nvertices * sizeof *remap);
    if (!remap) return acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < m->nvertices; i++) remap[i] = UINT32_MAX;
    for (size_t i = 0; i < 3 * m->ntriangles; i++) remap[m->triangles[i]] = 0;
    size_t n = 0;
    for (size_t i = 0; i < m->nvertices; i++)
        if (remap[i] == 0) {
            remap[i] = (uint32_t)n;
            if (n != i) memcpy(m->vertices + 3 * n, m->vertices + 3 * i, 3 * sizeof(double));
            n++;
        }
    for (size_t i = 0; i < 3 * m->ntriangles; i++) m->triangles[i] = remap[m->triangles[i]];
    st->unused_vertices_dropped += m->nvertices - n;
    m->nvertices = n;
    free(remap);
    return ACD_OK;
}

/* Step 3b (the file's comment): split non-manifold edges and vertices. */
typedef struct corner_edge {
    uint32_t lo, hi; /* the edge's vertices, lo < hi */
    uint32_t t;      /* the face */
    uint8_t ab;      /* 1: the face runs lo -> hi */
} corner_edge;

static int cmp_corner_edge(const void *x, const void *y) {
    const corner_edge *a = x, *b = y;
    if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
    if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
    return a->t < b->t ? -1 : a->t > b->t;
}

/* the corner of face t at vertex v */
static uint32_t corner_of(const acd_mesh *m, uint32_t t, uint32_t v) {
    const uint32_t *f = m->triangles + 3 * (size_t)t;
    return 3 * t + (f[0] == v ? 0 : f[1] == v ? 1 : 2);
}

typedef struct fan_face {
    double angle; /* about the edge, from the group's first face: [0, 2 pi) */
    uint32_t t, third;
    uint8_t ab;
} fan_face;

/* a before b counterclockwise about lo -> hi; faces in one half-plane (exactly) are one angle,
 * the face running lo -> hi first (it ends a solid's wedge, the other begins the next one) */
static int fan_before(const acd_mesh *m, uint32_t lo, uint32_t hi, const fan_face *a, const fan_face *b) {
    const double *V = m->vertices;
    int same = acd_orient3d_sign(V + 3 * (size_t)lo, V + 3 * (size_t)hi, V + 3 * (size_t)a->third,
                                 V + 3 * (size_t)b->third) == 0 &&
               fabs(a->angle - b->angle) < 1.0; /* one plane, and on one side of the edge's line */
    if (same && a->ab != b->ab) return a->ab;
    if (!same && a->angle != b->angle) return a->angle < b->angle;
    return a->t < b->t;
}

static acd_status split_nonmanifold(acd_mesh *m, acd_repair_stats *st, repair_poll *poll, acd_error *err) {
    size_t nt = m->ntriangles;
    if (nt == 0) return ACD_OK;
    if (nt > UINT32_MAX / 3) return acd_fail(err, ACD_ERR_INVALID_INPUT, "mesh too large to repair (%zu faces)", nt);
    corner_edge *ce = malloc(3 * nt * sizeof *ce);
    uint32_t *par = malloc(3 * nt * sizeof *par);
    uint8_t *open = calloc(m->nvertices ? m->nvertices : 1, 1); /* on a boundary edge: kept whole */
    fan_face *fan = NULL;
    size_t fancap = 0;
    acd_status s = ACD_OK;
    if (!ce || !par || !open) {
        s = acd_fail(err, ACD_ERR_NOMEM, "out of memory splitting non-manifold edges");
        goto done;
    }
    for (size_t t = 0; t < nt; t++) {
        if (repair_stop_at(poll, t)) {
            s = repair_cancelled(poll, err, nt, "faces");
            goto done;
        }
        for (int i = 0; i < 3; i++) {
            uint32_t u = m->triangles[3 * t + i], w = m->triangles[3 * t + (i + 1) % 3];
            ce[3 * t + i] = (corner_edge){u < w ? u : w, u < w ? w : u, (uint32_t)t, (uint8_t)(u < w)};
            par[3 * t + i] = (uint32_t)(3 * t + i);
        }
    }
    qsort(ce, 3 * nt, sizeof *ce, cmp_corner_edge);
    const double PI2 = 2.0 * acos(-1.0);
    size_t next_poll = 0;
    for (size_t i = 0, j; i < 3 * nt; i = j) {
        if (repair_stop_after(poll, i, &next_poll)) {
            s = repair_cancelled(poll, err, nt, "faces");
            goto done;
        }
        for (j = i + 1; j < 3 * nt && ce[j].lo == ce[i].lo && ce[j].hi == ce[i].hi;) j++;
        uint32_t lo = ce[i].lo, hi = ce[i].hi;
        size_t n = j - i;
        int paired = 0;
        if (n == 1) open[lo] = open[hi] = 1;
        if (n > 2 && n % 2 == 0) {
            if (n > fancap) {
                fan_face *nf = realloc(fan, n * sizeof *nf);
                if (!nf) {
                    s = acd_fail(err, ACD_ERR_NOMEM, "out of memory splitting non-manifold edges");
                    goto done;
                }
                fan = nf, fancap = n;
            }
            /* angles about d = hi - lo, in the frame (u, d x u) of the first face's third vertex */
            const double *a = m->vertices + 3 * (size_t)lo, *b = m->vertices + 3 * (size_t)hi;
            double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            double u[3] = {0}, w[3];
            for (size_t k = 0; k < n; k++) {
                const uint32_t *f = m->triangles + 3 * (size_t)ce[i + k].t;
                uint32_t c = f[0] != lo && f[0] != hi ? f[0] : f[1] != lo && f[1] != hi ? f[1] : f[2];
                const double *pc = m->vertices + 3 * (size_t)c;
                double p[3] = {pc[0] - a[0], pc[1] - a[1], pc[2] - a[2]};
                double pd = dd > 0 ? (p[0] * d[0] + p[1] * d[1] + p[2] * d[2]) / dd : 0;
                for (int q = 0; q < 3; q++) p[q] -= pd * d[q]; /* the part across the edge */
                if (k == 0) {
                    memcpy(u, p, sizeof u);
                    w[0] = d[1] * u[2] - d[2] * u[1], w[1] = d[2] * u[0] - d[0] * u[2], w[2] = d[0] * u[1] - d[1] * u[0];
                }
                double x = p[0] * u[0] + p[1] * u[1] + p[2] * u[2], y = p[0] * w[0] + p[1] * w[1] + p[2] * w[2];
                double ang = k == 0 ? 0 : atan2(y, x);
                if (ang < 0) ang += PI2;
                /* exactly in the first face's plane: on its side of the edge (0) or across (pi), not
                 * a rounding away from it (a face at 2 pi - 1e-16 would sort last) */
                if (k > 0 && acd_orient3d_sign(a, b, m->vertices + 3 * (size_t)fan[0].third, pc) == 0)
                    ang = x > 0 ? 0 : PI2 / 2;
                fan[k] = (fan_face){ang, ce[i + k].t, c, ce[i + k].ab};
            }
            for (size_t k = 1; k < n; k++) /* insertion sort: a handful of faces */
                for (size_t q = k; q > 0 && fan_before(m, lo, hi, &fan[q], &fan[q - 1]); q--) {
                    fan_face x = fan[q];
                    fan[q] = fan[q - 1], fan[q - 1] = x;
                }
            paired = 1;
            for (size_t k = 0; k < n && paired; k++) paired = fan[k].ab != fan[(k + 1) % n].ab;
            /* the wedge inside a solid runs counterclockwise from a face using hi -> lo (its
             * interior is on that side) to the next face, which uses lo -> hi */
            for (size_t k = 0; k < n && paired; k++)
                if (!fan[k].ab) {
                    const fan_face *g = &fan[(k + 1) % n];
                    acd_uf_union(par, corner_of(m, fan[k].t, lo), corner_of(m, g->t, lo));
                    acd_uf_union(par, corner_of(m, fan[k].t, hi), corner_of(m, g->t, hi));
                }
            if (paired) st->nonmanifold_edges_split++;
        }
        if (!paired) /* manifold, a boundary, or left as it is */
            for (size_t k = i + 1; k < j; k++) {
                acd_uf_union(par, corner_of(m, ce[i].t, lo), corner_of(m, ce[k].t, lo));
                acd_uf_union(par, corner_of(m, ce[i].t, hi), corner_of(m, ce[k].t, hi));
            }
    }
    /* each group of corners at a vertex beyond the first (in corner order) gets a copy of it */
    {
        size_t nv = m->nvertices, nnew = 0;
        uint8_t *kept = calloc(nv ? nv : 1, 1); /* the vertex went to a group already */
        uint32_t *copy = malloc(3 * nt * sizeof *copy); /* per root corner: its vertex */
        if (!kept || !copy) {
            free(kept), free(copy);
            s = acd_fail(err, ACD_ERR_NOMEM, "out of memory splitting non-manifold vertices");
            goto done;
        }
        for (size_t c = 0; c < 3 * nt; c++) {
            if (repair_stop_at(poll, c)) {
                free(kept), free(copy);
                s = repair_cancelled(poll, err, nt, "faces");
                goto done;
            }
            uint32_t v = m->triangles[c];
            if (acd_uf_find(par, (uint32_t)c) != c) continue; /* roots are the lowest corners: met first */
            if (!kept[v] || open[v]) kept[v] = 1, copy[c] = v;
            else copy[c] = (uint32_t)(nv + nnew++);
        }
        if (nnew > 0) {
            if (nv + nnew >= UINT32_MAX) {
                free(kept), free(copy);
                s = acd_fail(err, ACD_ERR_INVALID_INPUT, "mesh too large to repair (%zu vertices)", nv + nnew);
                goto done;
            }
            double *nvx = realloc(m->vertices, 3 * (nv + nnew) * sizeof *nvx);
            if (!nvx) {
                free(kept), free(copy);
                s = acd_fail(err, ACD_ERR_NOMEM, "out of memory splitting non-manifold vertices");
                goto done;
            }
            m->vertices = nvx;
            /* in corner order a group's root comes first, its vertex still the original: the copy's
             * coordinates are written once, there */
            for (size_t c = 0; c < 3 * nt; c++) {
                uint32_t r = acd_uf_find(par, (uint32_t)c), nvid = copy[r];
                if (r == c && nvid >= nv)
                    memcpy(m->vertices + 3 * (size_t)nvid, m->vertices + 3 * (size_t)m->triangles[c], 3 * sizeof(double));
                m->triangles[c] = nvid;
            }
            m->nvertices = nv + nnew;
            st->vertices_split = nnew;
        }
        free(kept), free(copy);
    }
done:
    free(ce), free(par), free(open), free(fan);
    return s;
}

acd_status acd_mesh_repair(acd_mesh *m, const acd_repair_options *opt, acd_repair_stats *stats, acd_error *err) {
    acd_repair_stats local;
    acd_repair_stats *st = stats ? stats : &local;
    memset(st, 0, sizeof *st);
    if (!m || !opt || (m->nvertices && !m->vertices) || (m->ntriangles && !m->triangles))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd_mesh_repair: NULL argument");
    if (acd_check_coordinates(m->vertices, m->nvertices, 3, err) != ACD_OK) return ACD_ERR_INVALID_INPUT;
    for (size_t i = 0; i < 3 * m->ntriangles; i++)
        if (m->triangles[i] >= m->nvertices)
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "triangle %zu refers to vertex %u of %zu", i / 3, m->triangles[i],
                            m->nvertices);
    acd_status s;
    repair_poll poll = {opt->progress, opt->progress_user, "repair", 0};
    const size_t nt = m->ntriangles; /* the input's, in the messages of the steps' polls */
    if (opt->weld && ((s = repair_step(&poll, "repair: welding", nt, err)) != ACD_OK ||
                      (s = acd_mesh_weld(m, opt->weld_tolerance, &st->vertices_merged, err)) != ACD_OK))
        return s;
    if ((opt->drop_degenerate || opt->drop_duplicates) &&
        ((s = repair_step(&poll, "repair: dropping degenerate and duplicate faces", nt, err)) != ACD_OK ||
         (s = drop_faces(m, opt->drop_degenerate, opt->drop_duplicates, st, &poll, err)) != ACD_OK))
        return s;
    if (opt->orient && ((s = repair_step(&poll, "repair: orienting", nt, err)) != ACD_OK ||
                        (s = orient(m, st, opt->fill_holes_max_edges == 0, &poll, err)) != ACD_OK))
        return s;
    if (opt->split_nonmanifold) {
        if ((s = repair_step(&poll, "repair: splitting non-manifold edges", nt, err)) != ACD_OK ||
            (s = split_nonmanifold(m, st, &poll, err)) != ACD_OK)
            return s;
        /* shells closed by the split face outward now (cavities inward) */
        if (st->vertices_split && opt->orient && !opt->fill_holes_max_edges) {
            st->nonorientable_parts = 0; /* counted again */
            if ((s = repair_step(&poll, "repair: orienting", nt, err)) != ACD_OK ||
                (s = orient(m, st, 1, &poll, err)) != ACD_OK)
                return s;
        }
    }
    if (opt->fill_holes_max_edges) {
        if ((s = repair_step(&poll, "repair: filling holes", nt, err)) != ACD_OK ||
            (s = fill_holes(m, opt->fill_holes_max_edges, st, &poll, err)) != ACD_OK)
            return s;
        if (opt->orient && ((s = repair_step(&poll, "repair: orienting", nt, err)) != ACD_OK ||
                            (s = orient(m, st, 1, &poll, err)) != ACD_OK))
            return s;
    }
    if (opt->drop_unused_vertices && ((s = repair_step(&poll, "repair: dropping unused vertices", nt, err)) != ACD_OK ||
                                      (s = drop_unused(m, st, err)) != ACD_OK))
        return s;
    return ACD_OK;
}
