/* acd3/decompose: Algorithm 1 for polyhedra, solid mode (dissertation Ch. III and §V.B;
 * paper §3-§4; spec acd3d.md §2, §7.1).
 *
 *   queue <- [P]
 *   while queue: C <- pop; measure C (acd3/measure); if concavity(C) <= tau: C is a leaf;
 *                else split C by the first candidate plane (acd3/resolve) that gives two or more
 *                solids (acd_plane_cut caps every section), and queue the pieces.
 *
 * The tree of all parts is kept (node 0 is the input). Nodes are processed in creation order, so
 * the result does not depend on anything but the input and the parameters. The recursion always
 * terminates: a part no candidate can split, or one at max_depth, becomes a leaf with its reason. */
#include "acd/acd3d.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "acd/hull.h"
#include "acd3/budget.h"
#include "acd3/decompose.h"
#include "acd3/leaf_test.h"
#include "acd3/measure.h"
#include "acd3/merge.h"
#include "acd3/poll.h"
#include "acd3/resolve.h"
#include "acd3/split.h"
#include "acd3/surface_cut.h"
#include "acd3/surface_merge.h"
#include "acd3/topology.h"
#include "acd3/trim.h"
#include "core/error.h"
#include "core/tolerance.h"
#include "geom3/edge_map.h"
#include "geom3/frame.h"
#include "geom3/hull_simplify.h"
#include "geom3/plane_cut.h"
#include "geom3/volume.h"
#include "geom3/sphere.h"

/* A piece whose volume is below this fraction of its parent's is a sliver: the cut that made it
 * is rejected. */
#define ACD3_MIN_PIECE_FRACTION 1e-6
/* When every candidate leaves such a sliver (the part already carries one, left by an earlier cut
 * at a thin wedge, and every plane separates it again), the candidates are tried once more
 * accepting pieces down to this fraction of the part's hull volume (not of its own volume: a
 * part that is itself nearly flat inside a big hull gets no such retry): the part is split
 * rather than left above tau. The retry's cuts also drop every shell whose volume is within
 * rounding (ACD_PLANE_CUT_DROP_SPECKS), which would otherwise come back as a piece the sliver rule
 * refuses (4 of the 72 stars of bench/bench_spiky_stars.py ended with a part above tau so). */
#define ACD3_MIN_PIECE_FRACTION_RETRY 1e-12
/* Safety net on the number of nodes of the tree. */
#define ACD3_MAX_NODES 20000
/* Surface mode with the merge pass: the tree is cut down to this fraction of tau (its measure's
 * eps scaled alike) and the merge pass (acd3/surface_merge) joins the leaves back up to the merge
 * tolerance; finer leaves give the merge pass more places to put the parts' boundaries
 * (docs/acd3d.md "Splitting a surface", "Finer leaves for the merge pass"). */
#define ACD3_SURFACE_SPLIT_RATIO 0.5

acd3d_params acd3d_default_params(void) {
    acd3d_params p;
    memset(&p, 0, sizeof p);
    p.cookie = ACD3D_PARAMS_COOKIE;
    p.tau = 0.05;
    p.mode = ACD3D_SOLID;
    p.eps_ratio = 0.5;
    p.delta_ratio = 0.1;
    p.weight = ACD3D_WEIGHT_RATIO;
    p.resolver = ACD3D_RESOLVER_GLOBAL;
    p.max_depth = 48;
    p.merge = 1;
    return p;
}

const char *acd3d_leaf_reason_name(acd3d_leaf_reason r) {
    switch (r) {
    case ACD3D_LEAF_NONE: return "split";
    case ACD3D_LEAF_TAU: return "tau";
    case ACD3D_LEAF_FLAT: return "flat";
    case ACD3D_LEAF_NO_CUT: return "no_cut";
    case ACD3D_LEAF_DEPTH: return "depth";
    case ACD3D_LEAF_MERGED: return "merged";
    case ACD3D_LEAF_JOINED: return "joined";
    case ACD3D_LEAF_HULL: return "hull_distance";
    case ACD3D_LEAF_REFINED: return "refined";
    case ACD3D_LEAF_BUDGET: return "budget";
    }
    return "unknown";
}

acd3d_params acd3d_budget_params(size_t parts) {
    acd3d_params p = acd3d_default_params();
    if (parts == 0) return p;
    p.tau = ACD3D_BUDGET_TAU;
    p.budget_parts = parts;
    p.merge_tau_diag = ACD3D_BUDGET_MERGE_TAU_DIAG;
    p.cut_choice = ACD3D_CHOICE_VOLUME;
    p.merge_order = ACD3D_MERGE_VOLUME;
    p.merge_parts = parts;
    p.merge_refine = ACD3D_BUDGET_MERGE_REFINE;
    return p;
}


typedef struct work_node {
    acd3d_node node;
    acd_mesh mesh;
    size_t depth;
    acd3_measured cache;
    /* a leaf's hull, kept from its measure for the output (hull_mesh: the same qhull run on the
     * same mesh); used while the node is a part with this mesh, freed with the tree */
    acd_hull hull;
    int have_hull;
    const double *hull_of; /* the vertices (mesh.vertices then) the hull was computed from */
    /* a budget piece that is a part: its tree and its hull's facet table from the budget pass's leaf
     * test (acd3/budget new_bvh, new_table), for the merge; dropped with its mesh (kept_drop), or
     * after the merge, except a part's tree that the trim pass uses (acd3/trim: with trim_coverage,
     * the tree of a part the merge left alone, the budget's or the merge's, over the arrays of the
     * part's mesh, which moves to the result's part) */
    acd_bvh bvh;
    acd3_facet_table table;
} work_node;

/* A node's tree and facet table (work_node.bvh, table) freed. */
static void kept_drop(work_node *w) {
    acd_bvh_free(&w->bvh);
    acd3_facet_table_free(&w->table);
}

typedef struct tree {
    work_node *a;
    size_t n, cap;
    acd_bvh input_bvh; /* the input's tree from the merge (acd3_merge_result.input_bvh), for acd3/trim */
} tree;

static int tree_push(tree *t, int parent, acd_mesh *mesh, size_t depth, int solid) {
    if (t->n == t->cap) {
        size_t nc = t->cap ? 2 * t->cap : 16;
        work_node *na = realloc(t->a, nc * sizeof *na);
        if (!na) return 0;
        t->a = na;
        t->cap = nc;
    }
    work_node *w = &t->a[t->n++];
    memset(w, 0, sizeof *w);
    w->node.parent = parent;
    w->node.first_child = -1;
    w->node.part = -1;
    w->node.merged_into = -1;
    w->mesh = *mesh;
    w->depth = depth;
    w->node.volume = solid ? acd_geom3_signed_volume(mesh) : 0.0;
    return 1;
}

/* The part's convex hull as a mesh; with max_vertices >= 4, an enclosing polytope of at most that
 * many vertices (geom3/hull_simplify) when the hull has more. kept: m's hull (acd_hull_compute of
 * its vertices, taken over: its arrays are moved or freed), or NULL to compute it. */
static acd_status hull_mesh(const acd_mesh *m, acd_hull *kept, size_t max_vertices, acd_mesh *out, double *volume,
                            acd_error *err) {
    memset(out, 0, sizeof *out);
    acd_hull h;
    acd_status st = ACD_OK;
    if (kept)
        h = acd_hull_take(kept);
    else
        st = acd_hull_compute(m->vertices, m->nvertices, &h, err);
    if (st == ACD_OK && max_vertices >= 4 && h.dim == 3 && h.nvertices > max_vertices) {
        acd_hull_free(&h);
        st = acd_hull_simplify(m->vertices, m->nvertices, max_vertices, &h, err);
    }
    if (st != ACD_OK) return st;
    *volume = h.volume;
    out->vertices = h.vertices;
    out->nvertices = h.nvertices;
    out->triangles = h.triangles;
    out->ntriangles = h.ntriangles;
    h.vertices = NULL;
    h.triangles = NULL;
    acd_hull_free(&h);
    return ACD_OK;
}

static acd_status check_input(const acd_mesh *m, acd_error *err) {
    if (m->nvertices == 0 || m->ntriangles == 0)
        return acd_fail(err, ACD_ERR_DEGENERATE, "the mesh is empty (%zu vertices, %zu triangles)", m->nvertices,
                        m->ntriangles);
    if (acd_check_coordinates(m->vertices, m->nvertices, 3, err) != ACD_OK) return ACD_ERR_INVALID_INPUT;
    if (acd_check_extent(m->vertices, m->nvertices, 3, err) != ACD_OK) return ACD_ERR_INVALID_INPUT;
    for (size_t i = 0; i < 3 * m->ntriangles; i++)
        if (m->triangles[i] >= m->nvertices)
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "triangle %zu refers to vertex %u of %zu", i / 3,
                            m->triangles[i], m->nvertices);
    return ACD_OK;
}

/* The part budget's smallest saving worth a cut, relative to the input's volume (the merge
 * refinement's min_gain, MERGE_REFINE_MIN_GAIN_REL, too). */
#define ACD3_BUDGET_MIN_GAIN_REL 2e-5

typedef struct run_ctx {
    const acd3d_params *params;
    int solid;
    double tau, eps, tol, extent;
    int tree_full; /* the node budget is spent: no more splits */
    int helpers;   /* threads that may join the evaluation of a split's candidates */
    size_t max_depth; /* params->max_depth + 2 x the input's genus */
    double screen_rel; /* the hull volume screen's margin (acd3_decompose_screen) */
    acd3_poll *poll; /* NULL without a progress callback */
    int multi;       /* the input has more than one edge-connected component (acd3_topology_of) */
} run_ctx;

typedef struct node_work {
    acd_status st;
    acd_error err;
    acd3d_leaf_reason reason;
    int split;
    acd3_split_choice choice;
    acd3_decompose_stats stats; /* its splits' candidate evaluations */
} node_work;

/* ACD3D_STOP_HULL: whether w, its measure above tau, is within tau of its hull both ways
 * (acd3/leaf_test); its concavity is then that bound. A failure is left in out->st. */
static int hull_leaf(const run_ctx *c, work_node *w, const acd3_measure *ms, node_work *out) {
    int ok = 0;
    double bound;
    out->st = acd3_leaf_test(&w->mesh, &ms->hull, c->tau + c->tol, ms->witness, &ok, &bound, &out->err);
    if (out->st == ACD_OK && ok) w->node.concavity = bound;
    return out->st == ACD_OK && ok;
}

/* The root of an input of several bodies is split into them before anything else, whatever its
 * measure (docs/acd3d.md "Bodies"): solid mode, its connected solids (edge-connected shells, each
 * cavity with the smallest shell around it: geom3/plane_cut's pieces of one side); surface mode, its
 * edge-connected patches. A part is then always one body, as every cut's pieces are: the measure
 * of a set of separate bodies is not the paper's (pockets between bodies are not projected), and a
 * hull spanning separate bodies fills the space between them. Returns 1 when it split the root
 * (out->choice holds the bodies, unmeasured), 0 for a root of one body, -status on failure. */
static int split_bodies(const run_ctx *c, work_node *w, const acd3_measured *cur, node_work *out) {
    acd_cut_result r;
    acd_status st = c->solid ? acd_plane_cut_bodies(&w->mesh, NULL, &r, &out->err)
                             : acd3_surface_components(&w->mesh, &cur->g, &r, &out->err);
    if (st != ACD_OK) return -(int)st;
    if (r.npieces < 2) {
        acd_cut_result_free(&r);
        return 0;
    }
    out->choice.pieces = calloc(r.npieces, sizeof *out->choice.pieces);
    if (!out->choice.pieces) {
        acd_cut_result_free(&r);
        return -(int)acd_fail(&out->err, ACD_ERR_NOMEM, "out of memory splitting %zu bodies", r.npieces);
    }
    out->choice.cut = r;
    out->choice.bodies = 1;
    out->choice.concavity = cur->ms.concavity;
    return 1;
}

/* Measures node w (unless its measure was kept) and chooses its split; touches only w and out. */
static void process_node(const run_ctx *c, work_node *w, node_work *out) {
    acd3_measured cur = w->cache;
    w->cache.valid = 0;
    out->st = ACD_OK;
    if (!cur.valid) {
        out->st = acd3_measure_mesh(&w->mesh, c->eps, c->tol, NULL, c->poll, &cur, &out->err);
        if (out->st != ACD_OK) return;
    }
    w->node.concavity = cur.ms.concavity;
    if (c->multi && w->node.parent < 0) {
        int b = split_bodies(c, w, &cur, out);
        if (b != 0) {
            if (b < 0) out->st = (acd_status)(-b);
            acd3_measured_free(&cur);
            out->reason = ACD3D_LEAF_NONE;
            out->split = b > 0;
            return;
        }
    }
    acd3d_leaf_reason reason = ACD3D_LEAF_NONE;
    if (cur.ms.hull.dim < 3) reason = ACD3D_LEAF_FLAT;
    else if (cur.ms.concavity <= c->tau + c->tol) reason = ACD3D_LEAF_TAU; /* tau = 0: up to rounding */
    else if (c->params->stop == ACD3D_STOP_HULL && hull_leaf(c, w, &cur.ms, out)) reason = ACD3D_LEAF_HULL;
    else if (w->depth >= c->max_depth || c->tree_full) reason = ACD3D_LEAF_DEPTH;
    if (out->st != ACD_OK) { /* the hull test failed (out of memory) */
        acd3_measured_free(&cur);
        return;
    }
    int split = 0;
    if (reason == ACD3D_LEAF_NONE) {
        /* solid mode: the global cut's plane first (acd3/resolve) */
        const acd3_resolve_opts ro = {c->params->resolver == ACD3D_RESOLVER_GLOBAL,
                                      {c->tau, c->params->delta_ratio * c->tau, c->params->weight,
                                       !c->solid && c->params->surface_cut != ACD3D_SURFACE_STRIP,
                                       !c->solid && c->params->surface_cut == ACD3D_SURFACE_CYCLE_WITNESS},
                                      c->params->resolver == ACD3D_RESOLVER_NOTCH};
        /* surface mode, and solid mode with region_cuts, cut along the section nearest the
         * witness first; solid mode then whole-plane cuts when that does not split the part
         * (surface mode does not: cutting a surface along every crossing of a plane leaves many
         * slivers; its section cut already tries the strips nearest the witness in turn) */
        /* surface parts have no volume: every piece passes the sliver test */
        const double vol = c->solid ? acd_geom3_signed_volume(&w->mesh) : -INFINITY;
        /* solid mode: the part's edge map once for all its tries (every try cuts this same mesh) */
        acd_edge_map em;
        const int have_em = c->solid && cur.ms.witness != UINT32_MAX && acd3_part_edge_map(&w->mesh, &em);
        const acd_edge_map *emp = have_em ? &em : NULL;
        if ((c->params->region_cuts || !c->solid) && !acd3_poll_stop(c->poll))
            split = acd3_try_split(&w->mesh, &cur.g, &cur.ms, c->extent, c->eps, c->tau, c->tol, c->solid, 1,
                                   ACD3_MIN_PIECE_FRACTION * vol, 0, &ro, c->params->cut_choice, c->helpers, emp,
                                   c->screen_rel, c->poll, NULL, 0, &out->stats, &out->choice, &out->err);
        if (split == 0 && c->solid && !acd3_poll_stop(c->poll))
            split = acd3_try_split(&w->mesh, &cur.g, &cur.ms, c->extent, c->eps, c->tau, c->tol, c->solid, 0,
                                   ACD3_MIN_PIECE_FRACTION * vol, 0, &ro, c->params->cut_choice, c->helpers, emp,
                                   c->screen_rel, c->poll, NULL, 0, &out->stats, &out->choice, &out->err);
        if (split == 0 && c->solid && !acd3_poll_stop(c->poll))
            split = acd3_try_split(&w->mesh, &cur.g, &cur.ms, c->extent, c->eps, c->tau, c->tol, c->solid, 0,
                                   ACD3_MIN_PIECE_FRACTION_RETRY * cur.ms.hull.volume, ACD_PLANE_CUT_DROP_SPECKS, &ro,
                                   c->params->cut_choice, c->helpers, emp, c->screen_rel, c->poll, NULL, 0, &out->stats,
                                   &out->choice, &out->err);
        if (split < 0) {
            out->st = (acd_status)(-split);
            split = 0;
        }
        /* no cut split it: whatever --stop says, the part is still a leaf within tau when it is
         * within tau of its hull both ways (acd3/leaf_test); else (solid mode) the halving planes,
         * as for the candidates with the sliver rule and then its retry; else it stays above tau,
         * said so */
        if (!split && out->st == ACD_OK)
            reason = c->params->stop != ACD3D_STOP_HULL && hull_leaf(c, w, &cur.ms, out) ? ACD3D_LEAF_HULL : ACD3D_LEAF_NO_CUT;
        if (!split && out->st == ACD_OK && reason == ACD3D_LEAF_NO_CUT && c->solid) {
            acd3_plane_candidate hv[ACD3_HALVING_PLANES];
            const int nh = acd3_halving_planes(&w->mesh, hv);
            for (int retry = 0; nh > 0 && split == 0 && retry < 2 && !acd3_poll_stop(c->poll); retry++)
                split = acd3_try_split(&w->mesh, &cur.g, &cur.ms, c->extent, c->eps, c->tau, c->tol, c->solid, 0,
                                       retry ? ACD3_MIN_PIECE_FRACTION_RETRY * cur.ms.hull.volume : ACD3_MIN_PIECE_FRACTION * vol,
                                       retry ? ACD_PLANE_CUT_DROP_SPECKS : 0, &ro, ACD3D_CHOICE_CONCAVITY, c->helpers, emp,
                                       c->screen_rel, c->poll, hv, nh, &out->stats, &out->choice, &out->err);
            if (split < 0) {
                out->st = (acd_status)(-split);
                split = 0;
            }
            if (split) {
                reason = ACD3D_LEAF_NONE;
                out->stats.halved++;
            }
        }
        if (have_em) acd_edge_map_free(&em);
    }
    if (!split && out->st == ACD_OK) { /* a leaf: its hull is its part's (until the mesh changes) */
        w->hull = acd_hull_take(&cur.ms.hull);
        w->have_hull = 1;
        w->hull_of = w->mesh.vertices;
    }
    acd3_measured_free(&cur);
    out->reason = reason;
    out->split = split;
}

static int node_is_part(const acd3d_node *nd) {
    return nd->merged_into < 0 &&
           (nd->leaf_reason == ACD3D_LEAF_MERGED || (nd->first_child < 0 && nd->leaf_reason != ACD3D_LEAF_NONE));
}

/* Per part idx[i] of t, the hull its node kept (process_node) when it is the hull of the node's
 * current mesh, else NULL; the array is the caller's to free (NULL when out of memory). */
static const acd_hull **kept_hulls(const tree *t, const size_t *idx, size_t np) {
    const acd_hull **hulls = malloc((np ? np : 1) * sizeof *hulls);
    if (!hulls) return NULL;
    for (size_t i = 0; i < np; i++) {
        const work_node *w = &t->a[idx[i]];
        hulls[i] = w->have_hull && w->hull_of && w->hull_of == w->mesh.vertices ? &w->hull : NULL;
    }
    return hulls;
}

/* The parts (node_is_part) in node order: *idx their nodes, *meshes their meshes (shallow
 * copies). *np = 0 leaves nothing allocated. */
static acd_status collect_parts(const tree *t, size_t *np, size_t **idx, acd_mesh **meshes, acd_error *err) {
    size_t n0 = 0;
    for (size_t n = 0; n < t->n; n++) n0 += (size_t)node_is_part(&t->a[n].node);
    *np = n0;
    *idx = NULL;
    *meshes = NULL;
    if (n0 == 0) return ACD_OK;
    *idx = malloc(n0 * sizeof **idx);
    *meshes = malloc(n0 * sizeof **meshes);
    if (!*idx || !*meshes) {
        free(*idx);
        free(*meshes);
        *np = 0;
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    }
    size_t k = 0;
    for (size_t n = 0; n < t->n; n++)
        if (node_is_part(&t->a[n].node)) {
            (*idx)[k] = n;
            (*meshes)[k++] = t->a[n].mesh;
        }
    return ACD_OK;
}

/* The members of group g (group_of over the np parts idx) now belong to the node just appended:
 * merged_into set, their meshes released. */
static void mark_joined(tree *t, const size_t *idx, size_t np, const uint32_t *group_of, size_t g) {
    for (size_t i = 0; i < np; i++)
        if (group_of[i] == g) {
            t->a[idx[i]].node.merged_into = (int)(t->n - 1);
            acd_mesh_free(&t->a[idx[i]].mesh);
        }
}

/* The merge pass (acd3/merge): every group of adjacent parts it joins becomes a node appended
 * after the tree (ACD3D_LEAF_JOINED, its mesh the members' meshes one after the other, so each
 * component stays closed); the members keep their nodes, with merged_into set and no mesh. */
static acd_status join_adjacent(tree *t, const acd_mesh *input, double tau, double tol, const acd3_merge_opts *mo,
                                int threads, size_t *nparts, acd_error *err) {
    size_t np, *idx;
    acd_mesh *meshes;
    acd_status st = collect_parts(t, &np, &idx, &meshes, err);
    if (st != ACD_OK || np < 2) { /* nothing to join */
        free(idx);
        free(meshes);
        return st;
    }
    /* the leaves' kept hulls (process_node) and the budget pieces' trees and facet tables: the merge's
     * parts', not computed again */
    const acd_hull **hulls = kept_hulls(t, idx, np);
    acd3_merge_kept *kept = calloc(np, sizeof *kept);
    if (!hulls || !kept) {
        free(hulls);
        free(kept);
        free(idx);
        free(meshes);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    }
    for (size_t i = 0; i < np; i++) {
        const work_node *w = &t->a[idx[i]];
        kept[i].hull = hulls[i];
        kept[i].bvh = w->bvh.nnodes ? &w->bvh : NULL;
        kept[i].table = w->table.key ? &w->table : NULL;
    }
    acd3_merge_result mr;
    st = acd3_merge_adjacent_kept(input, meshes, kept, np, tau, tol, mo, threads, &mr, err);
    free(kept);
    free(hulls);
    free(meshes);
    /* the trees trim uses (mo->keep_trees: those of the parts left alone, and the input's) kept, the
     * rest dropped (their meshes may go below) */
    for (size_t i = 0; i < np; i++) {
        work_node *w = &t->a[idx[i]];
        if (st != ACD_OK || !mo->keep_trees || mr.group_of[i] == UINT32_MAX || mr.group_size[mr.group_of[i]] != 1) {
            kept_drop(w);
            continue;
        }
        acd3_facet_table_free(&w->table);
        if (i < mr.npart_bvh && mr.part_bvh[i].nnodes) { /* the merge's (it did not use w's) */
            acd_bvh_free(&w->bvh);
            w->bvh = mr.part_bvh[i];
            memset(&mr.part_bvh[i], 0, sizeof mr.part_bvh[i]);
        }
    }
    if (st == ACD_OK && mo->keep_trees) {
        acd_bvh_free(&t->input_bvh);
        t->input_bvh = mr.input_bvh;
        memset(&mr.input_bvh, 0, sizeof mr.input_bvh);
    }
    /* the refinement's pieces (acd3/merge): children of the parts they were cut from */
    size_t na = np + mr.nnew, *idx2 = st == ACD_OK ? realloc(idx, (na ? na : 1) * sizeof *idx) : NULL;
    if (st == ACD_OK && !idx2) st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    if (idx2) idx = idx2;
    for (size_t k = 0; st == ACD_OK && k < mr.nnew; k++) {
        size_t pn = idx[mr.new_parent[k]];
        if (!tree_push(t, (int)pn, &mr.new_parts[k], t->a[pn].depth + 1, 1)) {
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
            break;
        }
        memset(&mr.new_parts[k], 0, sizeof mr.new_parts[k]);
        idx[np + k] = t->n - 1;
        acd3d_node *pa = &t->a[pn].node, *nd = &t->a[t->n - 1].node;
        if (pa->first_child < 0) {
            pa->first_child = (int)(t->n - 1);
            memcpy(pa->cut_plane, mr.new_plane[k], sizeof pa->cut_plane);
            pa->leaf_reason = ACD3D_LEAF_NONE;
            acd_mesh_free(&t->a[pn].mesh);
        }
        pa->nchildren++;
        nd->leaf_reason = ACD3D_LEAF_REFINED;
        if (mr.group_of[np + k] != UINT32_MAX) nd->concavity = mr.bound[mr.group_of[np + k]];
    }
    for (size_t g = 0; st == ACD_OK && g < mr.ngroups; g++) {
        if (mr.group_size[g] < 2) { /* a part alone: joined when a piece */
            size_t i = 0;
            while (i < na && mr.group_of[i] != g) i++;
            if (i < np) continue;
        }
        acd_mesh joined;
        memset(&joined, 0, sizeof joined);
        size_t nv = 0, ntr = 0;
        double vol = 0;
        for (size_t i = 0; i < na; i++)
            if (mr.group_of[i] == g) {
                nv += t->a[idx[i]].mesh.nvertices;
                ntr += t->a[idx[i]].mesh.ntriangles;
                vol += t->a[idx[i]].node.volume;
            }
        joined.vertices = malloc(3 * nv * sizeof(double));
        joined.triangles = malloc(3 * ntr * sizeof(uint32_t));
        if (!joined.vertices || !joined.triangles || nv >= UINT32_MAX) {
            acd_mesh_free(&joined);
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory joining parts");
            break;
        }
        for (size_t i = 0; i < na; i++) {
            if (mr.group_of[i] != g) continue;
            acd_mesh *m = &t->a[idx[i]].mesh;
            memcpy(joined.vertices + 3 * joined.nvertices, m->vertices, 3 * m->nvertices * sizeof(double));
            for (size_t k = 0; k < 3 * m->ntriangles; k++)
                joined.triangles[3 * joined.ntriangles + k] = m->triangles[k] + (uint32_t)joined.nvertices;
            joined.nvertices += m->nvertices;
            joined.ntriangles += m->ntriangles;
        }
        if (!tree_push(t, -1, &joined, 0, 0)) {
            acd_mesh_free(&joined);
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
            break;
        }
        work_node *w = &t->a[t->n - 1];
        w->node.volume = vol;
        w->node.concavity = mr.bound[g];
        w->node.leaf_reason = ACD3D_LEAF_JOINED;
        mark_joined(t, idx, na, mr.group_of, g);
    }
    if (st == ACD_OK) *nparts = mr.ngroups;
    acd3_merge_result_free(&mr);
    free(idx);
    return st;
}

/* Surface mode's merge pass (acd3/surface_merge): like join_adjacent, the joined node's mesh the
 * members welded along their shared chains, its concavity measured as the leaves'. */
static acd_status join_surface(tree *t, double eps, double tau, double tol, int threads, const acd3d_params *params,
                               size_t *nparts, acd_error *err) {
    size_t np, *idx;
    acd_mesh *meshes;
    acd_status st = collect_parts(t, &np, &idx, &meshes, err);
    if (st != ACD_OK || np < 2) { /* nothing to join */
        free(idx);
        free(meshes);
        return st;
    }
    acd3_surface_merge_result mr;
    st = acd3_surface_merge(meshes, np, eps, tau, tol, threads, params->progress, params->progress_user, &mr, err);
    free(meshes);
    for (size_t g = 0; st == ACD_OK && g < mr.ngroups; g++) {
        if (mr.group_size[g] < 2) continue;
        if (!tree_push(t, -1, &mr.meshes[g], 0, 0)) {
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
            break;
        }
        memset(&mr.meshes[g], 0, sizeof mr.meshes[g]);
        work_node *w = &t->a[t->n - 1];
        w->node.concavity = mr.concavity[g];
        w->node.leaf_reason = ACD3D_LEAF_JOINED;
        mark_joined(t, idx, np, mr.group_of, g);
        *nparts -= mr.group_size[g] - 1;
    }
    acd3_surface_merge_result_free(&mr);
    free(idx);
    return st;
}

/* The parts (the np input parts idx[0..np) and the pieces idx[np..) of br) that are above limit after
 * the budget pass (its test: acd3_leaf_test with that limit, the node's kept hull when it is its
 * mesh's): leaf reason ACD3D_LEAF_NO_CUT, concavity the bound of that test (a value above limit)
 * when finite, else (the test stops at the first value known above its limit, often INFINITY) a
 * finite upper bound of the two-sided distance: the test's with the part's bounding-box diagonal as
 * the limit, else that diagonal (no point of the part's surface or its hull's boundary is farther
 * from the other). */
static acd_status mark_over_limit(tree *t, const size_t *idx, size_t np, const acd3_budget_result *br, double limit,
                                  acd_error *err) {
    for (size_t i = 0; i < np + br->nnew; i++) {
        work_node *w = &t->a[idx[i]];
        if (w->node.first_child >= 0) continue;                    /* cut */
        if (i >= np && !(br->new_bound[i - np] > limit)) continue; /* a piece within the limit */
        acd_hull T;
        memset(&T, 0, sizeof T);
        T.dim = -1;
        const acd_hull *H = &T;
        if (w->have_hull && w->hull_of == w->mesh.vertices &&
            acd3_kept_hull_matches(&w->hull, w->mesh.vertices, w->mesh.nvertices))
            H = &w->hull;
        else if (acd_hull_compute(w->mesh.vertices, w->mesh.nvertices, &T, err) != ACD_OK)
            return acd_fail(err, ACD_ERR_NOMEM, "budget: out of memory");
        double bound = 0, lo[3], hi[3];
        int acc = 1;
        acd_status st = ACD_OK;
        if (i >= np)
            bound = br->new_bound[i - np], acc = 0; /* the pass's test of the piece */
        else if (H->dim == 3)
            st = acd3_leaf_test(&w->mesh, H, limit, UINT32_MAX, &acc, &bound, err);
        if (st == ACD_OK && !acc && !isfinite(bound)) {
            for (int k = 0; k < 3; k++) lo[k] = INFINITY, hi[k] = -INFINITY;
            for (size_t v = 0; v < w->mesh.nvertices; v++)
                for (int k = 0; k < 3; k++)
                    lo[k] = fmin(lo[k], w->mesh.vertices[3 * v + k]), hi[k] = fmax(hi[k], w->mesh.vertices[3 * v + k]);
            const double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                     (hi[2] - lo[2]) * (hi[2] - lo[2]));
            st = acd3_leaf_test(&w->mesh, H, diag, UINT32_MAX, &acc, &bound, err);
            if (!(bound <= diag)) bound = diag;
            acc = 0;
        }
        if (H == &T) acd_hull_free(&T);
        if (st != ACD_OK) return st;
        if (acc) continue;
        w->node.leaf_reason = ACD3D_LEAF_NO_CUT;
        w->node.concavity = bound;
    }
    return ACD_OK;
}

/* The part budget (params.budget_parts, acd3/budget): the parts are split further, best first by
 * the hull volume a split saves, the pieces children of the parts they were cut from
 * (ACD3D_LEAF_BUDGET, their concavity the two-sided bound). The pass's counts and phase-1 stop
 * reason go to res (budget_cuts, budget_phase1_cuts, budget_over, budget_stop). */
static acd_status split_to_budget(tree *t, size_t budget, double limit, double min_gain, double extent,
                                  int threads, const acd3d_params *params, size_t *nparts, acd3d_result *res,
                                  acd_error *err) {
    size_t np, *idx;
    acd_mesh *meshes;
    acd_status st = collect_parts(t, &np, &idx, &meshes, err);
    if (st != ACD_OK || np == 0) return st;
    /* the parts' kept hulls (process_node) for the budget's own tests, not computed again */
    const acd_hull **hulls = kept_hulls(t, idx, np);
    if (!hulls) {
        free(idx);
        free(meshes);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    }
    acd3_budget_result br;
    st = acd3_budget_split_hulls(meshes, hulls, np, budget, limit, min_gain, extent, threads, params->progress,
                                 params->progress_user, &br, err);
    free(hulls);
    free(meshes);
    size_t na = np + br.nnew, *idx2 = st == ACD_OK ? realloc(idx, na * sizeof *idx) : NULL;
    if (st == ACD_OK && !idx2) st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    if (idx2) idx = idx2;
    for (size_t k = 0; st == ACD_OK && k < br.nnew; k++) {
        size_t pn = idx[br.new_parent[k]];
        if (!tree_push(t, (int)pn, &br.new_parts[k], t->a[pn].depth + 1, 1)) {
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
            break;
        }
        memset(&br.new_parts[k], 0, sizeof br.new_parts[k]);
        idx[np + k] = t->n - 1;
        work_node *w = &t->a[t->n - 1];
        if (br.new_hull[k].dim >= 0) { /* a part: its hull from the budget pass (the merge's and the output's) */
            w->hull = acd_hull_take(&br.new_hull[k]);
            w->have_hull = 1;
            w->hull_of = w->mesh.vertices;
            w->bvh = br.new_bvh[k]; /* and its leaf test's tree and facet table (over the same arrays) */
            w->table = br.new_table[k];
            memset(&br.new_bvh[k], 0, sizeof br.new_bvh[k]);
            memset(&br.new_table[k], 0, sizeof br.new_table[k]);
        }
        acd3d_node *pa = &t->a[pn].node, *nd = &w->node;
        if (pa->first_child < 0) {
            pa->first_child = (int)(t->n - 1);
            memcpy(pa->cut_plane, br.new_plane[k], sizeof pa->cut_plane);
            pa->leaf_reason = ACD3D_LEAF_NONE;
            acd_mesh_free(&t->a[pn].mesh);
            acd_hull_free(&t->a[pn].hull); /* cut: its kept hull is no part's */
            t->a[pn].have_hull = 0;
            t->a[pn].hull_of = NULL;
            kept_drop(&t->a[pn]);
        }
        pa->nchildren++;
        nd->leaf_reason = ACD3D_LEAF_BUDGET;
        nd->concavity = br.new_bound[k];
    }
    /* the parts the budget pass left above the limit (no cut could split them: often a solid that
     * crosses itself) are stuck parts, ACD3D_LEAF_NO_CUT, their concavity the two-sided bound: the
     * caller sees them as it sees parts stuck above tau (before, an input part kept its tree leaf
     * reason and measure, below tau = 10 x radius, and the result read as meeting its tolerances) */
    if (st == ACD_OK && br.over > 0) st = mark_over_limit(t, idx, np, &br, limit, err);
    if (st == ACD_OK) {
        *nparts = br.nalive;
        res->budget_cuts = br.cuts;
        res->budget_phase1_cuts = br.phase1_cuts;
        res->budget_over = br.over;
        res->budget_stop = br.over > 0 ? br.phase1_stop : NULL;
    }
    acd3_budget_result_free(&br);
    free(idx);
    return st;
}

static acd_status decompose_mesh(const acd_mesh *mesh, const acd_frame *frame, const acd_mesh *model,
                                 const acd3d_params *params, double screen_rel, acd3_decompose_stats *stats,
                                 acd3d_result *out, acd_error *err);

/* The vertices some triangle uses, renumbered in their order (*c: a new mesh) when there are others;
 * *c empty (nothing allocated) when every vertex is used or an index is out of range (check_input
 * names that). */
static acd_status used_vertices(const acd_mesh *m, acd_mesh *c, acd_error *err) {
    memset(c, 0, sizeof *c);
    if (m->nvertices == 0 || m->ntriangles == 0 || !m->vertices || !m->triangles) return ACD_OK;
    uint32_t *map = malloc(m->nvertices * sizeof *map);
    if (!map) return acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    for (size_t v = 0; v < m->nvertices; v++) map[v] = UINT32_MAX;
    for (size_t k = 0; k < 3 * m->ntriangles; k++) {
        if (m->triangles[k] >= m->nvertices) {
            free(map);
            return ACD_OK;
        }
        map[m->triangles[k]] = 0;
    }
    size_t n = 0;
    for (size_t v = 0; v < m->nvertices; v++)
        if (map[v] == 0) map[v] = (uint32_t)n++;
    if (n == m->nvertices) {
        free(map);
        return ACD_OK;
    }
    c->vertices = malloc((n ? 3 * n : 1) * sizeof *c->vertices);
    c->triangles = malloc((m->ntriangles ? 3 * m->ntriangles : 1) * sizeof *c->triangles);
    if (!c->vertices || !c->triangles) {
        free(map);
        acd_mesh_free(c);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    }
    for (size_t v = 0; v < m->nvertices; v++)
        if (map[v] != UINT32_MAX) memcpy(c->vertices + 3 * (size_t)map[v], m->vertices + 3 * v, sizeof(double[3]));
    for (size_t k = 0; k < 3 * m->ntriangles; k++) c->triangles[k] = map[m->triangles[k]];
    c->nvertices = n;
    c->ntriangles = m->ntriangles;
    free(map);
    return ACD_OK;
}

/* Vertices no triangle uses are not part of the input: dropped before anything (before, they set
 * the scale and entered the hull of an uncut part: the budget pass found a cube with three stray
 * vertices 3.9 from its hull, prim.off of the budget sweep). */
acd_status acd3d_decompose(const acd_mesh *mesh, const acd3d_params *params, acd3d_result *out, acd_error *err) {
    return acd3_decompose_screen(mesh, params, ACD3_VOLUME_SCREEN_REL, NULL, out, err);
}

/* The result of a run in the local frame moved back to model coordinates: the parts' and hulls'
 * vertices + c (exact for the input's own vertices, computed ones rounded to the spacing there), the
 * cut planes' offsets d - n.c. Everything else (volumes, concavities, scale, tolerances) does not
 * depend on the position. */
static void result_to_model(const acd_frame *f, acd3d_result *r) {
    if (!f->moved) return;
    for (size_t i = 0; i < r->nparts; i++) {
        acd_geom3_frame_to_model(f, r->parts[i].mesh.vertices, r->parts[i].mesh.nvertices);
        acd_geom3_frame_to_model(f, r->parts[i].hull.vertices, r->parts[i].hull.nvertices);
    }
    for (size_t i = 0; i < r->nnodes; i++) acd_geom3_frame_plane_to_model(f, r->nodes[i].cut_plane);
}

acd_status acd3_decompose_screen(const acd_mesh *mesh, const acd3d_params *params, double screen_rel,
                                 acd3_decompose_stats *stats, acd3d_result *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    acd3_decompose_stats sink;
    if (!stats) stats = &sink;
    memset(stats, 0, sizeof *stats);
    acd_frame frame;
    memset(&frame, 0, sizeof frame);
    if (!mesh) return decompose_mesh(mesh, &frame, mesh, params, screen_rel, stats, out, err);
    acd_mesh c;
    acd_status st = used_vertices(mesh, &c, err);
    if (st != ACD_OK) return st;
    const acd_mesh *in = c.vertices ? &c : mesh;
    /* far from the origin: the run in a local frame (geom3/frame, docs/acd3d.md "Local frame"), on a
     * copy translated exactly; near it (every data mesh) the input as it is */
    if (in->vertices && in->ntriangles && in->triangles) acd_geom3_frame_of(in->vertices, in->nvertices, &frame);
    acd_mesh local;
    memset(&local, 0, sizeof local);
    if (frame.moved) {
        st = acd_mesh_copy(&local, in, err);
        if (st != ACD_OK) {
            acd_mesh_free(&c);
            return st;
        }
        acd_geom3_frame_to_local(&frame, local.vertices, local.nvertices);
    }
    st = decompose_mesh(frame.moved ? &local : in, &frame, in, params, screen_rel, stats, out, err);
    if (st == ACD_OK) result_to_model(&frame, out);
    acd_mesh_free(&local);
    acd_mesh_free(&c);
    return st;
}

/* mesh: the input in the frame (model: as given, for messages) */
static acd_status decompose_mesh(const acd_mesh *mesh, const acd_frame *frame, const acd_mesh *model,
                                 const acd3d_params *params, double screen_rel, acd3_decompose_stats *stats,
                                 acd3d_result *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    if (!params || params->cookie != ACD3D_PARAMS_COOKIE)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd3d_params not initialised by acd3d_default_params");
    if (!(params->tau >= 0) || !isfinite(params->tau))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "tau must be a finite number >= 0");
    if (!(params->merge_tau >= 0) || !isfinite(params->merge_tau))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "merge_tau must be a finite number >= 0");
    if (!(params->merge_tau_diag >= 0) || !isfinite(params->merge_tau_diag))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "merge_tau_diag must be a finite number >= 0");
    if (!(params->trim_coverage >= 0 && params->trim_coverage <= ACD3D_TRIM_COVERAGE_MAX))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "trim_coverage must be a number in [0, %g]",
                        ACD3D_TRIM_COVERAGE_MAX);
    if (params->max_hull_vertices > 0 && params->max_hull_vertices < 4)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "max_hull_vertices must be 0 (no limit) or at least 4");
    if (params->mode != ACD3D_SOLID && params->mode != ACD3D_SURFACE)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "unknown mode %d", (int)params->mode);
    if (params->stop != ACD3D_STOP_MEASURE && params->stop != ACD3D_STOP_HULL)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "unknown stopping test %d", (int)params->stop);
    if (params->threads > 1024) /* 100000 crashed inside libgomp */
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "threads %d: at most 1024 (0: as many as cores)", params->threads);
    if (params->mode == ACD3D_SURFACE) { /* solid mode's options, refused rather than ignored */
        const char *opt = params->cut_choice != ACD3D_CHOICE_CONCAVITY ? "cut_choice (--cut-choice)"
                          : params->merge_order != ACD3D_MERGE_BOUND  ? "merge_order (--merge-order)"
                          : params->merge_parts > 0                   ? "merge_parts (--merge-parts)"
                          : params->merge_refine > 0                  ? "merge_refine (--merge-refine)"
                          : params->budget_parts > 0                  ? "budget_parts (--budget)"
                          : params->trim_coverage > 0                 ? "trim_coverage (--trim-coverage)"
                                                                      : NULL;
        if (opt) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "%s is for solid mode only", opt);
    }
    if (params->budget_parts > 0 && params->max_hulls > 0)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT,
                        "budget_parts (--budget) and max_hulls (--max-hulls) exclude each other: use merge_parts "
                        "(--merge-parts) to end the merge at a part count");
    int solid = params->mode == ACD3D_SOLID;
    acd_status st = check_input(mesh, err);
    if (st != ACD_OK) return st;
    /* coordinates that cannot resolve the extent (geom3/frame): refused, never a result that the
     * rounding back to them would break */
    st = acd_geom3_frame_check(frame, model->vertices, solid ? "solid decomposition" : "surface decomposition", err);
    if (st != ACD_OK) return st;
    /* the checks of a large input take a while too: the callback between them (this thread's) */
    acd3_poll check = acd3_poll_make(params->progress, params->progress_user, "checking the input");
    acd3_poll *checkp = params->progress ? &check : NULL;
    if (acd3_poll_stop(checkp)) return acd_fail(err, ACD_ERR_CANCELLED, "cancelled checking the input");
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);

    double vol = 0;
    if (solid) { /* solid mode: the input must be closed and consistently oriented */
        acd_edge_map em;
        st = acd_edge_map_build(mesh->triangles, mesh->ntriangles, NULL, &em, err);
        if (st != ACD_OK) return st;
        acd_error cerr;
        st = acd_edge_map_check_closed(&em, mesh->triangles, mesh->ntriangles, &cerr);
        acd_edge_map_free(&em);
        if (st != ACD_OK)
            return acd_fail(err, st,
                            "solid mode needs a closed, consistently oriented mesh: %.300s (repair it with "
                            "'acd info --repair', or use surface mode)",
                            cerr.message);
        vol = acd_geom3_signed_volume(mesh);
        if (!(vol > 0))
            return acd_fail(err, ACD_ERR_DEGENERATE,
                            "the mesh encloses no positive volume (%g): it is flat or oriented inward", vol);
        if (acd3_poll_stop(checkp)) return acd_fail(err, ACD_ERR_CANCELLED, "cancelled checking the input");
    }

    acd_sphere sph;
    st = acd_min_sphere(mesh->vertices, mesh->nvertices, &sph, err);
    if (st != ACD_OK) return st;
    if (acd3_poll_stop(checkp)) return acd_fail(err, ACD_ERR_CANCELLED, "cancelled checking the input");
    acd_scale sc = acd_scale_of_points(mesh->vertices, mesh->nvertices, 3);
    out->scale = sph.radius;
    out->tau = params->tau_absolute ? params->tau : params->tau * sph.radius;
    out->tol = sc.dist;
    if (params->merge_tau > 0) {
        out->merge_tau = params->tau_absolute ? params->merge_tau : params->merge_tau * sph.radius;
        out->merge_tau_relative = params->tau_absolute ? (sph.radius > 0 ? params->merge_tau / sph.radius : 0)
                                                       : params->merge_tau;
    } else if (params->merge_tau_diag > 0 && sph.radius > 0) {
        /* through the relative value, so that merge_tau = merge_tau_relative gives this very run */
        out->merge_tau_relative = params->merge_tau_diag * sc.extent / sph.radius;
        out->merge_tau = out->merge_tau_relative * sph.radius;
    } else if (params->merge_tau_diag > 0) { /* a single point: no radius */
        out->merge_tau = params->merge_tau_diag * sc.extent;
    } else {
        out->merge_tau = out->tau;
        out->merge_tau_relative = !params->tau_absolute ? params->tau : sph.radius > 0 ? out->tau / sph.radius : 0;
    }
    out->input_volume = vol;
    double tau = out->tau;
    if (!solid && params->merge) tau *= ACD3_SURFACE_SPLIT_RATIO; /* the tree's tau; the parts' is out->merge_tau */
    double eps = params->eps_ratio * tau;

    /* every handle may take a cut that only opens it (surface mode cuts a non-separating loop
     * open, spec §5.3 step 6; the spec's genus rounds are 2g + 2): the depth guard grows by
     * twice the input's genus */
    size_t max_depth = params->max_depth;
    int multi = 0;
    {
        acd3_topology topo;
        st = acd3_topology_of(mesh, &topo, err);
        if (st != ACD_OK) return st;
        if (topo.genus > 0) max_depth += 2 * (size_t)topo.genus;
        multi = topo.components > 1;
    }
    if (acd3_poll_stop(checkp)) return acd_fail(err, ACD_ERR_CANCELLED, "cancelled checking the input");
    tree t = {0};
    acd_mesh root;
    st = acd_mesh_copy(&root, mesh, err);
    if (st != ACD_OK) return st;
    if (!tree_push(&t, -1, &root, 0, solid)) {
        acd_mesh_free(&root);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    }
    size_t nleaves = 0;
    int nthreads = params->threads;
#ifdef _OPENMP
    if (nthreads <= 0) nthreads = omp_get_num_procs();
#else
    nthreads = 1;
#endif
    /* Nodes are processed in batches: every node waiting when a batch starts is measured and
     * split independently (in parallel), then the children are appended in node order. The
     * tree, and so the output, is the same for any number of threads. */
    /* the poll within a batch (acd3/poll): the callback is called by this thread (between candidate
     * cuts, within the measure and the global cut: the root's batch is most of a large mesh's run);
     * once it asks to stop, every thread stops claiming work and the batch ends ACD_ERR_CANCELLED */
    acd3_poll poll = acd3_poll_make(params->progress, params->progress_user, "measuring and cutting");
    for (size_t i = 0; i < t.n;) {
        if (params->progress && params->progress(params->progress_user, -1.0, "measuring and cutting")) {
            st = acd_fail(err, ACD_ERR_CANCELLED, "cancelled after %zu parts", nleaves);
            goto fail;
        }
        size_t b0 = i, b1 = t.n;
        int full = t.n >= ACD3_MAX_NODES;
        node_work *wk = calloc(b1 - b0, sizeof *wk);
        if (!wk) {
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
            goto fail;
        }
        /* a thread without a node of its own helps with the candidates of the others' splits
         * (acd3_try_split): so a batch of fewer nodes than threads, the root's above all, still uses
         * every thread */
        const run_ctx ctx = {params, solid, tau, eps, sc.dist, sc.extent, full, nthreads - 1, max_depth, screen_rel,
                             params->progress ? &poll : NULL, multi};
        /* the batch's nodes are taken largest first (most vertices; then in node order), so that a
         * large node taken last does not keep one thread busy while the others wait; each node's
         * work goes to its own record, so the order changes nothing else */
        size_t *bord = malloc((b1 - b0) * sizeof *bord);
        if (!bord) {
            free(wk);
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
            goto fail;
        }
        for (size_t j = 0; j < b1 - b0; j++) {
            size_t q = j, nv = t.a[b0 + j].mesh.nvertices;
            while (q > 0 && t.a[b0 + bord[q - 1]].mesh.nvertices < nv) {
                bord[q] = bord[q - 1];
                q--;
            }
            bord[q] = j;
        }
        /* the first (largest) node is this thread's (the team's thread 0, the poll's owner), so that
         * the callback keeps being called while it is worked on (a root of a large mesh: its measure
         * and global cut); the other threads claim the rest in order, then so does this one */
        const long nb = (long)(b1 - b0);
        long next = 1;
#ifdef _OPENMP
#pragma omp parallel num_threads(nthreads) if (nthreads > 1)
#endif
        { /* (the region's end is a barrier where the threads without a node run helper tasks) */
            long j = 0;
#ifdef _OPENMP
            if (omp_get_thread_num() != 0) {
#pragma omp atomic capture
                j = next++;
            }
#endif
            while (j < nb) {
                process_node(&ctx, &t.a[b0 + bord[j]], &wk[bord[j]]);
#ifdef _OPENMP
#pragma omp atomic capture
#endif
                j = next++;
            }
        }
        free(bord);
        if (acd3_poll_stopped(&poll)) /* the callback asked to stop during the batch: its nodes' work is dropped */
            st = acd_fail(err, ACD_ERR_CANCELLED, "cancelled after %zu parts", nleaves);
        /* the first failure in node order is reported */
        for (size_t j = 0; j < b1 - b0; j++) {
            stats->screened += wk[j].stats.screened;
            stats->hulled += wk[j].stats.hulled;
            stats->halved += wk[j].stats.halved;
            if (wk[j].st != ACD_OK && st == ACD_OK) {
                st = wk[j].st;
                if (err) *err = wk[j].err;
            }
        }
        for (size_t j = 0; j < b1 - b0 && st == ACD_OK; j++) {
            size_t n = b0 + j;
            if (!wk[j].split) {
                t.a[n].node.leaf_reason = wk[j].reason;
                nleaves++;
                continue;
            }
            acd3_split_choice *choice = &wk[j].choice;
            acd_cut_result *cut = &choice->cut;
            const acd3_plane_candidate *used = &choice->plane;
            /* plane n.x + d = 0 */
            double *cp = t.a[n].node.cut_plane;
            if (choice->bodies) { /* no plane; the bodies are not a level of cuts */
                memset(cp, 0, sizeof t.a[n].node.cut_plane);
                t.a[n].node.bodies = 1;
            } else {
                memcpy(cp, used->normal, sizeof(double[3]));
                cp[3] = -(used->normal[0] * used->point[0] + used->normal[1] * used->point[1] +
                          used->normal[2] * used->point[2]);
            }
            t.a[n].node.first_child = (int)t.n;
            t.a[n].node.nchildren = (int)cut->npieces;
            size_t depth = t.a[n].depth + !choice->bodies;
            for (size_t k = 0; k < cut->npieces; k++) {
                acd_mesh piece = cut->pieces[k].mesh;
                memset(&cut->pieces[k].mesh, 0, sizeof piece);
                if (!tree_push(&t, (int)n, &piece, depth, solid)) {
                    acd_mesh_free(&piece);
                    st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
                    break;
                }
                t.a[t.n - 1].cache = choice->pieces[k];
                choice->pieces[k].valid = 0;
            }
            /* the interior node's mesh is no longer needed, unless parts may be merged back */
            if (!params->max_hulls) acd_mesh_free(&t.a[n].mesh);
        }
        for (size_t j = 0; j < b1 - b0; j++) acd3_split_choice_free(&wk[j].choice);
        free(wk);
        if (st != ACD_OK) goto fail;
        i = b1;
    }

    /* max_hulls: merge the cheapest adjacent parts. Siblings are adjacent (they share their
     * parent's cut), and their union is their parent, whose concavity is known: collapse the
     * node whose children are all leaves and whose concavity is smallest (lowest index on
     * ties), until at most max_hulls parts remain. */
    if (params->max_hulls > 0)
        while (nleaves > params->max_hulls) {
            size_t best = SIZE_MAX;
            for (size_t n = 0; n < t.n; n++) {
                const acd3d_node *nd = &t.a[n].node;
                if (nd->first_child < 0 || nd->leaf_reason == ACD3D_LEAF_MERGED) continue;
                int all_leaves = 1;
                for (int k = 0; k < nd->nchildren && all_leaves; k++) {
                    const acd3d_node *c = &t.a[nd->first_child + k].node;
                    all_leaves = c->leaf_reason == ACD3D_LEAF_MERGED || (c->first_child < 0 && c->leaf_reason != ACD3D_LEAF_NONE);
                }
                if (all_leaves && (best == SIZE_MAX || nd->concavity < t.a[best].node.concavity)) best = n;
            }
            if (best == SIZE_MAX) break;
            acd3d_node *nd = &t.a[best].node;
            for (int k = 0; k < nd->nchildren; k++) {
                work_node *c = &t.a[nd->first_child + k];
                acd_mesh_free(&c->mesh);
                c->node.leaf_reason = ACD3D_LEAF_NONE; /* dropped: merged into its parent */
                c->node.part = -1;
            }
            nleaves -= (size_t)nd->nchildren - 1;
            nd->leaf_reason = ACD3D_LEAF_MERGED;
        }
    for (size_t n = 0; n < t.n; n++)
        if (t.a[n].node.first_child >= 0 && t.a[n].node.leaf_reason != ACD3D_LEAF_MERGED) acd_mesh_free(&t.a[n].mesh);

    if (params->budget_parts > 0) {
        st = split_to_budget(&t, params->budget_parts, out->merge_tau, ACD3_BUDGET_MIN_GAIN_REL * vol, sc.extent,
                             nthreads, params, &nleaves, out, err);
        if (st != ACD_OK) goto fail;
    }

    if (params->merge && solid) {
        /* (no refinement after max_hulls: its merged parts keep their dropped children, the pieces
         * could not be their children) */
        const acd3_merge_opts mo = {params->merge_order == ACD3D_MERGE_VOLUME, params->merge_parts,
                                    params->max_hulls ? 0 : params->merge_refine, params->progress,
                                    params->progress_user, params->trim_coverage > 0, 0};
        st = join_adjacent(&t, mesh, out->merge_tau, sc.dist, &mo, nthreads, &nleaves, err);
        if (st != ACD_OK) goto fail;
    } else if (params->merge) {
        st = join_surface(&t, params->eps_ratio * out->merge_tau, out->merge_tau, sc.dist, nthreads, params, &nleaves, err);
        if (st != ACD_OK) goto fail;
    }

    /* results: nodes, parts (leaves, merged and joined nodes, in node order) with hulls */
    out->nodes = calloc(t.n, sizeof *out->nodes);
    out->parts = calloc(nleaves ? nleaves : 1, sizeof *out->parts);
    if (!out->nodes || !out->parts) {
        st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
        goto fail;
    }
    out->nnodes = t.n;
    for (size_t i = 0; i < t.n; i++) {
        out->nodes[i] = t.a[i].node;
        int is_part = t.a[i].node.merged_into < 0 && (t.a[i].node.leaf_reason == ACD3D_LEAF_MERGED ||
                      (t.a[i].node.first_child < 0 && t.a[i].node.leaf_reason != ACD3D_LEAF_NONE));
        if (!is_part) continue;
        acd3d_part *p = &out->parts[out->nparts];
        p->mesh = t.a[i].mesh;
        memset(&t.a[i].mesh, 0, sizeof t.a[i].mesh);
        p->concavity = t.a[i].node.concavity;
        p->volume = t.a[i].node.volume;
        p->node = (int)i;
        out->nodes[i].part = (int)out->nparts;
        out->nparts++;
        if (p->concavity > out->max_concavity) out->max_concavity = p->concavity;
    }
    /* the parts' hulls and topology, independently (in parallel); the first failure in part order
     * is reported */
    {
        acd_status *pst = calloc(out->nparts ? out->nparts : 1, sizeof *pst);
        acd_error *perr = calloc(out->nparts ? out->nparts : 1, sizeof *perr);
        if (!pst || !perr) {
            free(pst);
            free(perr);
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
            goto fail;
        }
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(nthreads) if (nthreads > 1 && out->nparts > 1)
#endif
        for (long j = 0; j < (long)out->nparts; j++) {
            acd3d_part *p = &out->parts[j];
            work_node *w = &t.a[p->node];
            pst[j] = hull_mesh(&p->mesh, w->have_hull ? &w->hull : NULL, params->max_hull_vertices, &p->hull,
                               &p->hull_volume, &perr[j]);
            if (pst[j] != ACD_OK) continue;
            acd3_topology topo;
            pst[j] = acd3_topology_of(&p->mesh, &topo, &perr[j]);
            p->genus = topo.genus;
            p->boundary_loops = topo.boundary_loops;
        }
        for (size_t j = 0; j < out->nparts && st == ACD_OK; j++)
            if (pst[j] != ACD_OK) {
                st = pst[j];
                if (err) *err = perr[j];
            }
        free(pst);
        free(perr);
        if (st != ACD_OK) goto fail;
    }
    if (solid && params->trim_coverage > 0) { /* the hulls trimmed within the coverage budget (acd3/trim) */
        /* (on an input that crosses itself, its parts are tested for crossings: acd3/trim) */
        acd3_trim_stats ts;
        /* the trees built already (the merge's and the budget pass's: acd3_trim_trees) */
        const acd_bvh **ptrees = malloc((out->nparts ? out->nparts : 1) * sizeof *ptrees);
        if (ptrees)
            for (size_t j = 0; j < out->nparts; j++) {
                const acd_bvh *b = &t.a[out->parts[j].node].bvh;
                ptrees[j] = b->nnodes ? b : NULL;
            }
        const acd3_trim_trees trees = {t.input_bvh.nnodes ? &t.input_bvh : NULL, ptrees};
        st = acd3_trim_hulls(out->parts, out->nparts, vol, params->trim_coverage * vol, ACD3_TRIM_MIN_GAIN_REL * vol,
                             params->max_hull_vertices, mesh, &trees, nthreads, params->progress,
                             params->progress_user, &ts, err);
        free(ptrees);
        if (st != ACD_OK) goto fail;
        out->trimmed_volume = ts.removed_part;
        out->trim_cuts = ts.cuts;
        out->trim_depth_max = ts.max_depth;
        out->trim_skipped = ts.skipped;
        out->trim_distance_bound = ts.max_distance;
        out->trim_refused_far = ts.refused_far;
    }
    for (size_t i = 0; i < t.n; i++) {
        acd_hull_free(&t.a[i].hull);
        kept_drop(&t.a[i]);
    }
    free(t.a);
    acd_bvh_free(&t.input_bvh);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    out->seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    return ACD_OK;
fail:
    for (size_t i = 0; i < t.n; i++) {
        acd_mesh_free(&t.a[i].mesh);
        acd3_measured_free(&t.a[i].cache);
        acd_hull_free(&t.a[i].hull);
        kept_drop(&t.a[i]);
    }
    free(t.a);
    acd_bvh_free(&t.input_bvh);
    acd3d_result_free(out);
    return st;
}

void acd3d_result_free(acd3d_result *r) {
    if (!r) return;
    for (size_t i = 0; i < r->nparts; i++) {
        acd_mesh_free(&r->parts[i].mesh);
        acd_mesh_free(&r->parts[i].hull);
    }
    free(r->parts);
    free(r->nodes);
    memset(r, 0, sizeof *r);
}
