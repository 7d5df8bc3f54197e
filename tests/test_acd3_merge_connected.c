/* Tests that the merge pass (acd3/merge) keeps every group connected (issue 4, "hull over a gap"):
 * a group whose pieces do not touch is one part whose hull spans the empty space between them.
 *
 * The refinement: a slab shaped like a table (a bar of 7 cells on two legs of 3 cells, one cell
 * apart) and two cells continuing the bar. At 3 groups its best trade cuts the table under the bar
 * (hull 22 -> bar 7 + legs 9, the legs' hull over the gap within tau: it reaches 0.5 out) and joins
 * the two cells: the legs side holds two pieces that do not touch, and the old code made it one
 * group. Now each side's connected components are groups (the legs two), and the step joins one
 * more pair to keep the count: after one step every group is connected (its atoms' surfaces, welded
 * by their coordinates, edge-connected), within tau, the groups tile the input and their hulls are
 * the optimum (the input's volume), for 1, 2 and 4 threads alike.
 *
 * The greedy joins: two boxes a small gap apart (a tolerance far above the gap) are never joined,
 * nor are two parts of separate bodies in acd3d_decompose's default pipeline. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd/hull.h"
#include "acd3/merge.h"
#include "core/union_find.h"
#include "merge_check.h"
#include "shapes.h"

enum { NX = 9, NY = 4 };

/* Unit voxels of a 9 x 4 x 1 grid: the cells (xs[i], ys[i]). */
static void voxels(acd_mesh *m, const int *xs, const int *ys, int n) {
    unsigned char occ[NX * NY];
    memset(occ, 0, sizeof occ);
    for (int i = 0; i < n; i++) occ[ys[i] * NX + xs[i]] = 1;
    assert_true(mg_voxels(m, occ, NX, NY, 1));
}

typedef struct wpos {
    double p[3];
    uint32_t id; /* the vertex's index in the group's concatenated vertex list */
} wpos;

static int cmp_wpos(const void *x, const void *y) {
    const wpos *a = x, *b = y;
    int c = memcmp(a->p, b->p, sizeof a->p);
    if (c) return c;
    return (a->id > b->id) - (a->id < b->id);
}

/* Edge-connected components of the union of the meshes ms[0..n), vertices welded by their exact
 * coordinates (what the CLI's --parts file shows of a joined part, as bench/audit_3d_openscad.py counts
 * them). */
static size_t components(const acd_mesh *const *ms, size_t n) {
    size_t nv = 0;
    for (size_t i = 0; i < n; i++) nv += ms[i]->nvertices;
    wpos *w = malloc(nv * sizeof *w);
    uint32_t *uf = malloc(nv * sizeof *uf), *used = calloc(nv, sizeof *used);
    assert_non_null(w);
    assert_non_null(uf);
    assert_non_null(used);
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t v = 0; v < ms[i]->nvertices; v++, k++) {
            memcpy(w[k].p, ms[i]->vertices + 3 * v, sizeof w[k].p);
            w[k].id = (uint32_t)k;
            uf[k] = (uint32_t)k;
        }
    qsort(w, nv, sizeof *w, cmp_wpos);
    for (size_t i = 1; i < nv; i++)
        if (!memcmp(w[i].p, w[i - 1].p, sizeof w[i].p)) acd_uf_union(uf, w[i - 1].id, w[i].id);
    size_t off = 0;
    for (size_t i = 0; i < n; i++) {
        for (size_t t = 0; t < ms[i]->ntriangles; t++)
            for (int c = 0; c < 3; c++) {
                uint32_t a = (uint32_t)(off + ms[i]->triangles[3 * t + c]);
                uint32_t b = (uint32_t)(off + ms[i]->triangles[3 * t + (c + 1) % 3]);
                acd_uf_union(uf, a, b);
                used[a] = used[b] = 1;
            }
        off += ms[i]->nvertices;
    }
    size_t nc = 0;
    for (size_t v = 0; v < nv; v++) nc += used[v] && acd_uf_find(uf, (uint32_t)v) == v;
    free(w);
    free(uf);
    free(used);
    return nc;
}

/* Components of group g of r. */
static size_t group_components(const acd_mesh *parts, size_t nparts, const acd3_merge_result *r, size_t g) {
    size_t na = nparts + r->nnew, n = 0;
    const acd_mesh **ms = malloc(na * sizeof *ms);
    assert_non_null(ms);
    for (size_t k = 0; k < na; k++)
        if (r->group_of[k] == g) ms[n++] = mck_atom(parts, nparts, r, k);
    size_t nc = components(ms, n);
    free(ms);
    return nc;
}

static void test_refine_side_connected(void **state) {
    (void)state;
    /* the table: bar y = 3, x 0..6; legs x = 2 and x = 4, y 0..2 */
    int tx[13], ty[13], n = 0;
    for (int x = 0; x <= 6; x++) tx[n] = x, ty[n++] = 3;
    for (int y = 0; y <= 2; y++) {
        tx[n] = 2, ty[n++] = y;
        tx[n] = 4, ty[n++] = y;
    }
    int ix[15], iy[15];
    memcpy(ix, tx, sizeof tx);
    memcpy(iy, ty, sizeof ty);
    ix[13] = 7, iy[13] = 3, ix[14] = 8, iy[14] = 3;
    const int bx[] = {7}, by[] = {3}, cx[] = {8}, cy[] = {3};
    acd_mesh in, parts[3];
    voxels(&in, ix, iy, 15);
    voxels(&parts[0], tx, ty, 13);
    voxels(&parts[1], bx, by, 1);
    voxels(&parts[2], cx, cy, 1);
    const double tau = 0.6, tol = 1e-9, vin = mg_volume(&in);
    assert_true(fabs(vin - 15) <= 1e-12);
    acd3_merge_opts mo = {.by_volume = 1, .stop_at = 3};
    acd3_merge_result plain;
    acd_error err;
    assert_int_equal(acd3_merge_adjacent(&in, parts, 3, tau, tol, &mo, 1, &plain, &err), ACD_OK);
    assert_int_equal(plain.ngroups, 3);
    double h0 = 0;
    for (size_t g = 0; g < plain.ngroups; g++) h0 += mck_group_hull_volume(parts, 3, &plain, g);
    assert_true(fabs(h0 - 24) <= 1e-9); /* the table's hull 22, the cells 1 each */
    /* one step (the old code's first: the legs one group), then up to five */
    for (size_t steps = 1; steps <= 5; steps += 4) {
        mo.refine = steps;
        acd3_merge_result ref[3];
        const int threads[3] = {1, 2, 4};
        for (int t = 0; t < 3; t++)
            assert_int_equal(acd3_merge_adjacent(&in, parts, 3, tau, tol, &mo, threads[t], &ref[t], &err), ACD_OK);
        const acd3_merge_result *r = &ref[0];
        size_t na = 3 + r->nnew;
        double hs = 0, sum = 0;
        print_message("refine %zu: %zu steps, %zu pieces, %zu groups\n", steps, r->trades, r->nnew, r->ngroups);
        assert_int_equal(r->ngroups, 3);
        for (size_t g = 0; g < r->ngroups; g++) {
            size_t nc = group_components(parts, 3, r, g);
            double hv = mck_group_hull_volume(parts, 3, r, g);
            print_message("group %zu: %zu component(s), hull volume %.9g, bound %.9g\n", g, nc, hv, r->bound[g]);
            assert_int_equal(nc, 1);
            assert_true(r->bound[g] <= tau);
            hs += hv;
        }
        for (size_t k = 0; k < na; k++)
            if (r->group_of[k] != UINT32_MAX) sum += mg_volume(mck_atom(parts, 3, r, k));
        assert_true(fabs(sum - vin) <= 1e-9 * vin);
        /* the optimum: the bar with the cells (9) and the legs (3 each), 15 = the input's volume (the
         * volume plane is searched at sampled offsets: within 0.1 of it); the legs side as one group
         * (the old code) 18 after one step, the cut refused 24 */
        assert_true(hs >= vin - 1e-9 && hs <= vin + 0.1);
        for (int t = 1; t < 3; t++) {
            assert_int_equal(ref[t].nnew, r->nnew);
            assert_int_equal(ref[t].ngroups, r->ngroups);
            assert_int_equal(ref[t].trades, r->trades);
            assert_memory_equal(ref[t].group_of, r->group_of, na * sizeof *r->group_of);
            for (size_t g = 0; g < r->ngroups; g++) assert_memory_equal(&ref[t].bound[g], &r->bound[g], sizeof(double));
        }
        for (int t = 0; t < 3; t++) acd3_merge_result_free(&ref[t]);
    }
    acd3_merge_result_free(&plain);
    for (int k = 0; k < 3; k++) acd_mesh_free(&parts[k]);
    acd_mesh_free(&in);
}

/* Two unit-section boxes 1 x 1 x 4 side by side, 0.05 apart (the box from x0 along x). */
static void box(acd_mesh *m, double x0, double y0) {
    const int xs[] = {0, 1, 2, 3}, ys[] = {0, 0, 0, 0};
    voxels(m, xs, ys, 4);
    for (size_t v = 0; v < m->nvertices; v++) {
        m->vertices[3 * v] += x0;
        m->vertices[3 * v + 1] += y0;
    }
}

static void join_meshes(acd_mesh *out, const acd_mesh *a, const acd_mesh *b) {
    memset(out, 0, sizeof *out);
    out->nvertices = a->nvertices + b->nvertices;
    out->ntriangles = a->ntriangles + b->ntriangles;
    out->vertices = malloc(3 * out->nvertices * sizeof *out->vertices);
    out->triangles = malloc(3 * out->ntriangles * sizeof *out->triangles);
    assert_non_null(out->vertices);
    assert_non_null(out->triangles);
    memcpy(out->vertices, a->vertices, 3 * a->nvertices * sizeof *out->vertices);
    memcpy(out->vertices + 3 * a->nvertices, b->vertices, 3 * b->nvertices * sizeof *out->vertices);
    memcpy(out->triangles, a->triangles, 3 * a->ntriangles * sizeof *out->triangles);
    for (size_t k = 0; k < 3 * b->ntriangles; k++)
        out->triangles[3 * a->ntriangles + k] = b->triangles[k] + (uint32_t)a->nvertices;
}

static void test_gap_never_joined(void **state) {
    (void)state;
    acd_mesh parts[2], in;
    box(&parts[0], 0, 0);
    box(&parts[1], 0, 1.05);
    join_meshes(&in, &parts[0], &parts[1]);
    acd_error err;
    /* the joint hull of the two boxes reaches 0.025 out of them: within any of these tolerances */
    const double taus[2] = {0.1, 1.0};
    for (int k = 0; k < 2; k++) {
        acd3_merge_opts mo = {.by_volume = k};
        acd3_merge_result r;
        assert_int_equal(acd3_merge_adjacent(&in, parts, 2, taus[k], 1e-9, &mo, 1, &r, &err), ACD_OK);
        assert_int_equal(r.ngroups, 2);
        assert_int_equal(r.merges, 0);
        acd3_merge_result_free(&r);
    }
    /* the whole pipeline: the bodies are split at the root, and their parts never joined */
    acd3d_params prm = acd3d_default_params();
    prm.tau = 0.2;
    acd3d_result res;
    assert_int_equal(acd3d_decompose(&in, &prm, &res, &err), ACD_OK);
    assert_int_equal(res.nparts, 2);
    for (size_t i = 0; i < res.nparts; i++) {
        const acd_mesh *m = &res.parts[i].mesh;
        assert_int_equal(components(&m, 1), 1);
    }
    acd3d_result_free(&res);
    for (int k = 0; k < 2; k++) acd_mesh_free(&parts[k]);
    acd_mesh_free(&in);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_refine_side_connected),
        cmocka_unit_test(test_gap_never_joined),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
