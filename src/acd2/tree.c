/* acd2/tree: level-of-detail readout of the decomposition tree (Lien dissertation Ch. III,
 * Alg. 1 and Fig. 9b: "the recursion forms a binary tree"; spec acd2d.md §2).
 *
 * For measures that do not depend on tau (SL, SP, H1) the cut made at a node depends only on
 * the node's polygon, so a fresh run at tau' >= tau makes exactly the cuts of the tree nodes
 * whose concavity exceeds tau' (or which are not yet simple polygons), in the same preorder:
 * the frontier read here equals that run. H2 depends on tau; its readout is the tree's
 * frontier, which may differ from a fresh H2 run at tau'. */
#include "acd2/tree.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd2/resolution.h"
#include "core/error.h"
#include "core/tolerance.h"
#include "geom2/hull2d.h"

int acd2_cuts_push(acd2_cuts_list *l, acd_vec2 a, acd_vec2 b) {
    if (l->n == l->cap) {
        size_t nc = l->cap ? 2 * l->cap : 32;
        acd_vec2(*q)[2] = realloc(l->v, nc * sizeof *q);
        if (!q) return -1;
        l->v = q;
        l->cap = nc;
    }
    l->v[l->n][0] = a;
    l->v[l->n][1] = b;
    l->n++;
    return 0;
}

void acd2d_result_free(acd2d_result *r) {
    if (!r) return;
    for (size_t i = 0; i < r->ncomponents; i++) {
        free(r->components[i].points);
        free(r->components[i].hull);
    }
    free(r->components);
    for (size_t i = 0; i < r->nnodes; i++) acd_polygon_free(&r->nodes[i].polygon);
    free(r->nodes);
    free(r->cuts);
    memset(r, 0, sizeof *r);
}

typedef struct pts {
    acd_vec2 *p;
    size_t n;
} pts;

/* Rebuilds the ring of node v from its descendants, iteratively (post-order with an explicit
 * stack). A split node's ring R, with the cut from R[off] to a vertex R[j] or to a new point z in
 * edge (j, j+1), has children A = R[off..j] (+ z) and B = (z +) R[j(+1)..off]; so R rotated to
 * start at off is A without its last point followed by B without its last (and without z). */
static acd_status rebuild(const acd2d_result *res, int v, pts *outp, acd_error *err) {
    size_t nn = res->nnodes;
    pts *built = calloc(nn, sizeof *built);
    int *stack = malloc((nn + 1) * sizeof *stack);
    acd_status st = ACD_OK;
    if (!built || !stack) {
        free(built);
        free(stack);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory rebuilding node %d", v);
    }
    size_t ns = 0;
    stack[ns++] = v;
    while (ns > 0 && st == ACD_OK) {
        int u = stack[ns - 1];
        const acd2d_node *nd = &res->nodes[u];
        if (nd->polygon.nrings > 0) {
            size_t n = acd_polygon_ring_size(&nd->polygon, 0);
            built[u].p = malloc(n * sizeof *built[u].p);
            if (!built[u].p) { st = acd_fail(err, ACD_ERR_NOMEM, "out of memory"); break; }
            memcpy(built[u].p, nd->polygon.points, n * sizeof *built[u].p);
            built[u].n = n;
            ns--;
            continue;
        }
        int a = nd->child[0], b = nd->child[1];
        if (a < 0 || b < 0) { st = acd_fail(err, ACD_ERR_INTERNAL, "tree node %d has no polygon and no children", u); break; }
        if (!built[a].p || !built[b].p) {
            if (!built[b].p) stack[ns++] = b;
            if (!built[a].p) stack[ns++] = a;
            continue;
        }
        size_t s = (size_t)(nd->cut_new_point != 0), na = built[a].n, nb = built[b].n;
        if (na < 2 || nb < 2 + s) { st = acd_fail(err, ACD_ERR_INTERNAL, "tree node %d: children too small", u); break; }
        size_t n = (na - 1) + (nb - 1 - s);
        acd_vec2 *R = malloc((n ? n : 1) * sizeof *R);
        if (!R) { st = acd_fail(err, ACD_ERR_NOMEM, "out of memory"); break; }
        size_t off = nd->ring_offset % (n ? n : 1);
        for (size_t k = 0; k < na - 1; k++) R[(k + off) % n] = built[a].p[k];
        for (size_t k = 0; k < nb - 1 - s; k++) R[(na - 1 + k + off) % n] = built[b].p[s + k];
        free(built[a].p);
        free(built[b].p);
        built[a].p = built[b].p = NULL;
        built[u].p = R;
        built[u].n = n;
        ns--;
    }
    if (st == ACD_OK) {
        *outp = built[v];
        built[v].p = NULL;
    }
    for (size_t i = 0; i < nn; i++) free(built[i].p);
    free(built);
    free(stack);
    return st;
}

acd_status acd2d_node_polygon(const acd2d_result *res, int node, acd_polygon *out, acd_error *err) {
    if (!out) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd2d_node_polygon: out is NULL");
    memset(out, 0, sizeof *out);
    if (!res || node < 0 || (size_t)node >= res->nnodes)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd2d_node_polygon: no node %d", node);
    if (res->nodes[node].polygon.nrings > 0) {
        if (acd_polygon_copy(out, &res->nodes[node].polygon) != ACD_OK) return acd_fail(err, ACD_ERR_NOMEM, "out of memory");
        return ACD_OK;
    }
    pts r = {0};
    acd_status st = rebuild(res, node, &r, err);
    if (st != ACD_OK) return st;
    const acd_vec2 *rings[1] = {r.p};
    size_t sizes[1] = {r.n};
    st = acd_polygon_from_rings(out, rings, sizes, 1, err);
    free(r.p);
    return st;
}

static acd_status add_comp(acd2d_result *out, size_t *cap, const acd2d_result *res, int node, acd_error *err) {
    const acd2d_node *nd = &res->nodes[node];
    acd_polygon tmp;
    acd_status st0 = acd2d_node_polygon(res, node, &tmp, err);
    if (st0 != ACD_OK) return st0;
    if (out->ncomponents == *cap) {
        size_t nc = *cap ? 2 * *cap : 16;
        acd2d_component *q = realloc(out->components, nc * sizeof *q);
        if (!q) { acd_polygon_free(&tmp); return acd_fail(err, ACD_ERR_NOMEM, "out of memory"); }
        out->components = q;
        *cap = nc;
    }
    size_t n = acd_polygon_ring_size(&tmp, 0);
    acd2d_component *c = &out->components[out->ncomponents];
    memset(c, 0, sizeof *c);
    c->points = malloc(n * sizeof *c->points);
    c->hull = malloc((n + 1) * sizeof *c->hull);
    size_t *idx = malloc((n + 1) * sizeof *idx), *scr = malloc((n + 1) * sizeof *scr);
    if (!c->points || !c->hull || !idx || !scr) {
        free(c->points); free(c->hull); free(idx); free(scr);
        acd_polygon_free(&tmp);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    }
    memcpy(c->points, tmp.points, n * sizeof *c->points);
    acd_polygon_free(&tmp);
    c->npoints = n;
    size_t nh = acd_hull2d_indices(c->points, n, idx, scr);
    for (size_t i = 0; i < nh; i++) c->hull[i] = c->points[idx[i]];
    c->nhull = nh;
    c->concavity = nd->concavity;
    c->node = node;
    free(idx);
    free(scr);
    out->ncomponents++;
    if (nd->concavity > out->max_concavity) out->max_concavity = nd->concavity;
    return ACD_OK;
}

acd_status acd2d_result_at_tau(const acd2d_result *res, double tau2, acd2d_result *out, acd_error *err) {
    if (!out) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd2d_result_at_tau: out is NULL");
    memset(out, 0, sizeof *out);
    if (!res || res->nnodes == 0) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd2d_result_at_tau: no tree");
    if (!(tau2 >= res->tau))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd2d_result_at_tau: tau %g is below the tree's tau %g", tau2,
                        res->tau);
    const acd_polygon *root = &res->nodes[0].polygon;
    acd_scale sc = acd_scale_of_points(&root->points[0].x, acd_polygon_num_points(root), 2);
    double m = 0;
    for (size_t i = 0; i < acd_polygon_num_points(root); i++)
        m = fmax(m, fmax(fabs(root->points[i].x), fabs(root->points[i].y)));
    double eps = fmax(sc.dist, ACD2_ROUND_ULPS * DBL_EPSILON * m); /* as acd2d_decompose */
    out->tau = tau2;
    out->measure = res->measure;
    out->input_vertices = res->input_vertices;
    out->input_notches = res->input_notches;
    out->input_holes = res->input_holes;
    size_t comp_cap = 0;
    acd2_cuts_list cl = {0};
    int *stack = malloc((res->nnodes + 1) * sizeof *stack);
    if (!stack) return acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    size_t ns = 0;
    stack[ns++] = 0;
    acd_status st = ACD_OK;
    while (ns > 0 && st == ACD_OK) {
        int v = stack[--ns];
        const acd2d_node *nd = &res->nodes[v];
        int leaf = nd->child[0] < 0 && nd->child[1] < 0;
        if (leaf || (nd->acceptable && nd->concavity <= tau2 + eps)) {
            st = add_comp(out, &comp_cap, res, v, err);
            continue;
        }
        int zero = nd->cut[0].x == nd->cut[1].x && nd->cut[0].y == nd->cut[1].y;
        if (!zero && acd2_cuts_push(&cl, nd->cut[0], nd->cut[1])) {
            st = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
            break;
        }
        if (nd->child[1] >= 0) stack[ns++] = nd->child[1];
        if (nd->child[0] >= 0) stack[ns++] = nd->child[0];
    }
    free(stack);
    out->cuts = cl.v;
    out->ncuts = cl.n;
    if (st != ACD_OK) acd2d_result_free(out);
    return st;
}
