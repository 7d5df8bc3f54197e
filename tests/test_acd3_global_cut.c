/* Tests of acd3/pocket_cut and acd3/global_cut (spec acd3d.md §4.2-4.5, §5.2): boundary chains,
 * knots, pocket cuts (matching, no crossings), the cut weight, the minimum-weight cycle around a
 * neck, the plane at an L-shaped notch, the cut through a cup-shaped dent, and the solid
 * decomposition with the global resolver (volume conserved, tau met, same output for 1/2/4
 * threads, both cut weights). */
// ctest: TIMEOUT 600
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd3/global_cut.h"
#include "acd3/measure.h"
#include "acd3/pocket_cut.h"
#include "acd3/surface_cut.h"
#include "geom3/dijkstra.h"
#include "geom3/edge_map.h"
#include "shapes.h"

typedef struct analysed {
    acd_edge_graph g;
    acd3_measure ms;
    acd3_cut_graph cg;
    acd3_global_cut gc;
    acd3_gc_opts o;
    double point[3], normal[3];
    int has_plane;
} analysed;

static void analyse_opts(const acd_mesh *m, double tau, acd3d_weight w, int dynamic, int witness_root, analysed *a) {
    acd_error err;
    memset(a, 0, sizeof *a);
    a->o.dynamic = dynamic;
    a->o.witness_root = witness_root;
    assert_int_equal(acd_edge_graph_from_mesh(m->vertices, m->nvertices, m->triangles, m->ntriangles, &a->g, &err), ACD_OK);
    assert_int_equal(acd3_measure_compute(m, &a->g, 0.5 * tau, 1e-9, &a->ms, &err), ACD_OK);
    a->o.tau = tau;
    a->o.delta = 0.1 * tau;
    a->o.weight = w;
    assert_int_equal(acd3_cut_graph_build(m, &a->g, &a->ms, &a->o, NULL, &a->cg, &err), ACD_OK);
    assert_int_equal(acd3_global_cut_find(m, &a->g, &a->ms, &a->cg, &a->o, &a->gc, &err), ACD_OK);
    a->has_plane = acd3_global_cut_plane(m, &a->ms, &a->cg, &a->gc, &a->o, a->point, a->normal, NULL);
}

static void analyse(const acd_mesh *m, double tau, acd3d_weight w, analysed *a) { analyse_opts(m, tau, w, 0, 0, a); }

static void release(analysed *a) {
    acd3_global_cut_free(&a->gc);
    acd3_cut_graph_free(&a->cg);
    acd3_measure_free(&a->ms);
    acd_edge_graph_free(&a->g);
}

/* Structural properties of any cut graph. */
static void check_cut_graph(const acd_mesh *m, const analysed *a) {
    const acd3_cut_graph *cg = &a->cg;
    const acd3_measure *ms = &a->ms;
    /* chains: consecutive vertices joined by barrier edges with the chain's two regions on their sides */
    for (size_t c = 0; c < cg->nchains; c++) {
        assert_true(cg->chain_off[c + 1] - cg->chain_off[c] >= 2);
        assert_true(cg->chain_region[2 * c] < cg->chain_region[2 * c + 1]);
        for (size_t i = cg->chain_off[c]; i + 1 < cg->chain_off[c + 1]; i++) {
            uint32_t e = acd_edge_graph_find(&a->g, cg->chain_v[i], cg->chain_v[i + 1]);
            assert_true(e != ACD_NO_VERTEX);
            assert_true(ms->edge_barrier[e]);
            uint32_t r0 = ms->face_region[cg->face_of[2 * (size_t)e]], r1 = ms->face_region[cg->face_of[2 * (size_t)e + 1]];
            uint32_t lo = r0 < r1 ? r0 : r1, hi = r0 < r1 ? r1 : r0;
            assert_int_equal(lo, cg->chain_region[2 * c]);
            assert_int_equal(hi, cg->chain_region[2 * c + 1]);
        }
    }
    /* knots: on their chain, concavity above delta */
    for (size_t k = 0; k < cg->nknots; k++) {
        uint32_t c = cg->knot_chain[k];
        int on = 0;
        for (size_t i = cg->chain_off[c]; i < cg->chain_off[c + 1]; i++) on |= cg->chain_v[i] == cg->knot_v[k];
        assert_true(on);
        assert_true(ms->vconc[cg->knot_v[k]] > a->o.delta);
    }
    /* cuts: join two knots on different chains of their region, along edges of that region, and
     * each knot meets at most one cut toward a given other chain (the matching) */
    for (size_t c = 0; c < cg->ncuts; c++) {
        const acd3_pocket_cut *pc = &cg->cuts[c];
        uint32_t k0 = pc->knot[0], k1 = pc->knot[1];
        assert_true(cg->knot_chain[k0] != cg->knot_chain[k1]);
        for (int s = 0; s < 2; s++) {
            const uint32_t *cr = cg->chain_region + 2 * (size_t)cg->knot_chain[pc->knot[s]];
            assert_true(cr[0] == pc->region || cr[1] == pc->region);
        }
        const uint32_t *p = cg->cut_v + pc->off;
        assert_int_equal(p[0], cg->knot_v[k0]);
        assert_int_equal(p[pc->n - 1], cg->knot_v[k1]);
        for (size_t i = 0; i < pc->n; i++) {
            int touches = 0;
            for (size_t q = cg->vf_row[p[i]]; q < cg->vf_row[p[i] + 1]; q++) touches |= ms->face_region[cg->vf[q]] == pc->region;
            assert_true(touches);
            if (i + 1 < pc->n) assert_true(acd_edge_graph_find(&a->g, p[i], p[i + 1]) != ACD_NO_VERTEX);
        }
        assert_true(pc->w > 0 && isfinite(pc->w));
        for (size_t d = c + 1; d < cg->ncuts; d++) {
            const acd3_pocket_cut *qc = &cg->cuts[d];
            if (qc->region != pc->region) continue;
            /* matched: a knot meets at most one cut toward a given other chain */
            for (int s = 0; s < 2; s++)
                for (int t = 0; t < 2; t++)
                    if (pc->knot[s] == qc->knot[t])
                        assert_true(cg->knot_chain[pc->knot[1 - s]] != cg->knot_chain[qc->knot[1 - t]]);
        }
    }
    /* a cycle returns to its start */
    if (a->gc.closed) assert_int_equal(a->gc.v[0], a->gc.v[a->gc.n - 1]);
    (void)m;
}

static double waist_r(double th, double ph, void *u) {
    (void)ph;
    double k = *(double *)u, s = sin(th);
    return 1.0 - k * s * s;
}

/* A peanut with a neck at z = 0: the global cut is a cycle around the neck, its plane z = 0. */
static void test_neck_cycle(void **state) {
    (void)state;
    double k = 0.7;
    acd_mesh m;
    assert_true(mg_radial(&m, 48, 48, waist_r, &k));
    analysed a;
    analyse(&m, 0.05, ACD3D_WEIGHT_RATIO, &a);
    check_cut_graph(&m, &a);
    assert_true(a.cg.nknots >= 3);
    assert_true(a.cg.ncuts >= 3);
    assert_true(a.gc.closed);
    assert_true(a.gc.ncuts >= 3);
    /* the cycle goes around the neck: all four azimuth quadrants, all near z = 0 */
    int quad[4] = {0};
    for (size_t i = 0; i < a.gc.n; i++) {
        const double *p = m.vertices + 3 * (size_t)a.gc.v[i];
        assert_true(fabs(p[2]) < 0.25);
        quad[(p[0] >= 0) + 2 * (p[1] >= 0)] = 1;
    }
    assert_true(quad[0] && quad[1] && quad[2] && quad[3]);
    assert_true(a.has_plane);
    assert_true(fabs(a.normal[2]) > 0.95);
    assert_true(fabs(a.point[2]) < 0.1);
    release(&a);
    /* the dissertation's product weight finds the same neck */
    analyse(&m, 0.05, ACD3D_WEIGHT_PRODUCT, &a);
    check_cut_graph(&m, &a);
    assert_true(a.gc.closed);
    assert_true(a.has_plane && fabs(a.normal[2]) > 0.95);
    release(&a);
    acd_mesh_free(&m);
}

/* An L-shaped slab (voxels): the plane goes through the notch edge. */
static void test_l_notch_plane(void **state) {
    (void)state;
    unsigned char occ[16];
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 4; x++) occ[y * 4 + x] = !(x >= 2 && y >= 2);
    acd_mesh m;
    assert_true(mg_voxels(&m, occ, 4, 4, 1));
    analysed a;
    analyse(&m, 0.1, ACD3D_WEIGHT_RATIO, &a);
    check_cut_graph(&m, &a);
    assert_true(a.gc.n >= 2);
    assert_true(a.has_plane);
    /* the witness is on the notch edge x = y = 2; the cut is that edge (a straight cut), so the
     * plane contains it (vertical, through (2, 2)) and bisects the notch: normal (1, -1) / sqrt 2,
     * which splits the L into two convex pieces */
    const double *x = m.vertices + 3 * (size_t)a.ms.witness;
    assert_true(fabs(x[0] - 2) < 1e-12 && fabs(x[1] - 2) < 1e-12);
    assert_true(fabs(a.normal[2]) < 1e-9);
    assert_true(fabs(fabs(a.normal[0]) - sqrt(0.5)) < 1e-9 && a.normal[0] * a.normal[1] < 0);
    double off = a.normal[0] * (2 - a.point[0]) + a.normal[1] * (2 - a.point[1]);
    assert_true(fabs(off) < 1e-9);
    release(&a);
    acd_mesh_free(&m);
}

/* A 5x5x2 box of voxels with the middle voxel of the top layer removed: a 1x1 dent. */
static void dented_box(acd_mesh *m) {
    enum { N = 5 };
    unsigned char occ[N * N * 2];
    for (int z = 0; z < 2; z++)
        for (int y = 0; y < N; y++)
            for (int x = 0; x < N; x++) occ[(z * N + y) * N + x] = !(z == 1 && x == 2 && y == 2);
    assert_true(mg_voxels(m, occ, N, N, 2));
}

/* A 5x5x2 box with a 1x1 dent in the top: the dent has no knots (its rim is where the hull
 * touches), the pocket is cup-shaped, the cut runs through the dent's bottom and its plane is
 * vertical. */
static void test_cup_dent(void **state) {
    (void)state;
    acd_mesh m;
    dented_box(&m);
    analysed a;
    analyse(&m, 0.02, ACD3D_WEIGHT_RATIO, &a);
    check_cut_graph(&m, &a);
    assert_true(a.ms.concavity > 0.99);
    assert_true(a.gc.cup);
    int through = 0;
    for (size_t i = 0; i < a.gc.n; i++) through |= a.gc.v[i] == a.ms.witness;
    assert_true(through);
    assert_true(a.has_plane);
    assert_true(fabs(a.normal[2]) < 1e-6);
    /* the plane passes through the dent (x, y in [2, 3]) */
    const double *x = m.vertices + 3 * (size_t)a.ms.witness;
    assert_true(fabs(a.normal[0] * (x[0] - a.point[0]) + a.normal[1] * (x[1] - a.point[1])) < 1e-9);
    release(&a);
    acd_mesh_free(&m);
}

/* W: ratio x product = omega^2, product / ratio = gamma^2; a path along a fold has a
 * larger gamma than a straight path on a flat face. */
static void test_cut_weight(void **state) {
    (void)state;
    unsigned char occ[8] = {1, 1, 1, 1, 1, 1, 1, 1};
    acd_mesh m;
    assert_true(mg_voxels(&m, occ, 2, 2, 2));
    acd_edge_graph g;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &g, &err), ACD_OK);
    uint32_t *face_of;
    assert_int_equal(acd3_edge_faces(&m, &g, &face_of, &err), ACD_OK);
    double *conc = malloc(m.nvertices * sizeof *conc);
    for (size_t v = 0; v < m.nvertices; v++) conc[v] = 0.25;
    /* a path of two edges on the cube's top face (z = 2) vs one along its top front edge (y = 0, z = 2) */
    uint32_t flat[3], fold[3];
    size_t nflat = 0, nfold = 0;
    for (double xx = 0; xx <= 2; xx += 1)
        for (size_t v = 0; v < m.nvertices; v++) {
            const double *p = m.vertices + 3 * v;
            if (p[0] == xx && p[1] == 1 && p[2] == 2) flat[nflat++] = (uint32_t)v;
            if (p[0] == xx && p[1] == 0 && p[2] == 2) fold[nfold++] = (uint32_t)v;
        }
    assert_int_equal(nflat, 3);
    assert_int_equal(nfold, 3);
    acd3_gc_opts o = {1.0, 0.1, ACD3D_WEIGHT_RATIO, 0, 0};
    double rf = acd3_cut_weight(&m, &g, face_of, conc, flat, 3, &o), rd = acd3_cut_weight(&m, &g, face_of, conc, fold, 3, &o);
    o.weight = ACD3D_WEIGHT_PRODUCT;
    double pf = acd3_cut_weight(&m, &g, face_of, conc, flat, 3, &o), pd = acd3_cut_weight(&m, &g, face_of, conc, fold, 3, &o);
    double omega = 3.0 / (0.75 + 1e-3);
    assert_true(fabs(rf * pf - omega * omega) <= 1e-9 * omega * omega);
    assert_true(fabs(rd * pd - omega * omega) <= 1e-9 * omega * omega);
    /* flat: gamma = eta (0.05 rad) per edge only; the fold turns by pi/2 more at both edges */
    assert_true(fabs(sqrt(pf / rf) - 0.1) < 1e-12);
    assert_true(fabs(sqrt(pd / rd) - (3.14159265358979323846 + 0.1)) < 1e-9);
    assert_true(rd < rf && pd > pf);
    free(conc);
    free(face_of);
    acd_edge_graph_free(&g);
    acd_mesh_free(&m);
}

static void check_solid(const acd_mesh *in, const acd3d_result *r) {
    double vin = mg_volume(in), sum = 0;
    for (size_t i = 0; i < r->nparts; i++) {
        const acd_mesh *m = &r->parts[i].mesh;
        acd_edge_map em;
        acd_error err;
        assert_int_equal(acd_edge_map_build(m->triangles, m->ntriangles, NULL, &em, &err), ACD_OK);
        assert_int_equal(acd_edge_map_check_closed(&em, m->triangles, m->ntriangles, &err), ACD_OK);
        acd_edge_map_free(&em);
        sum += mg_volume(m);
        const acd3d_node *nd = &r->nodes[r->parts[i].node];
        if (nd->leaf_reason == ACD3D_LEAF_TAU) assert_true(r->parts[i].concavity <= r->tau + 1e-9);
        else assert_true(nd->leaf_reason != ACD3D_LEAF_NONE);
    }
    assert_true(fabs(sum - vin) <= 1e-9 * vin);
}

static void same_result(const acd3d_result *a, const acd3d_result *b) {
    assert_int_equal(a->nparts, b->nparts);
    for (size_t i = 0; i < a->nparts; i++) {
        assert_int_equal(a->parts[i].mesh.nvertices, b->parts[i].mesh.nvertices);
        assert_memory_equal(a->parts[i].mesh.vertices, b->parts[i].mesh.vertices,
                            3 * a->parts[i].mesh.nvertices * sizeof(double));
    }
}

/* The global resolver in the driver: the peanut splits at its neck first; volume conserved,
 * tau met, the same parts for 1, 2 and 4 threads and for both cut weights' own runs. */
static void test_decompose_global(void **state) {
    (void)state;
    double k = 0.7;
    acd_mesh m;
    assert_true(mg_radial(&m, 48, 48, waist_r, &k));
    acd3d_params p = acd3d_default_params();
    assert_int_equal(p.resolver, ACD3D_RESOLVER_GLOBAL);
    p.tau = 0.05;
    acd3d_result r[3];
    acd_error err;
    int th[3] = {1, 2, 4};
    for (int i = 0; i < 3; i++) {
        p.threads = th[i];
        assert_int_equal(acd3d_decompose(&m, &p, &r[i], &err), ACD_OK);
        check_solid(&m, &r[i]);
        if (i) same_result(&r[0], &r[i]);
    }
    /* the first cut is the neck's plane z = 0 */
    assert_true(r[0].nodes[0].first_child >= 0);
    assert_true(fabs(r[0].nodes[0].cut_plane[2]) > 0.95);
    assert_true(fabs(r[0].nodes[0].cut_plane[3]) < 0.1);
    for (int i = 0; i < 3; i++) acd3d_result_free(&r[i]);
    p.threads = 1;
    p.weight = ACD3D_WEIGHT_PRODUCT;
    assert_int_equal(acd3d_decompose(&m, &p, &r[0], &err), ACD_OK);
    check_solid(&m, &r[0]);
    acd3d_result_free(&r[0]);
    /* the dent box */
    enum { N = 5 };
    unsigned char occ[N * N * 2];
    for (int z = 0; z < 2; z++)
        for (int y = 0; y < N; y++)
            for (int x = 0; x < N; x++) occ[(z * N + y) * N + x] = !(z == 1 && x == 2 && y == 2);
    acd_mesh box;
    assert_true(mg_voxels(&box, occ, N, N, 2));
    p = acd3d_default_params();
    p.tau = 0.0;
    p.tau_absolute = 1;
    assert_int_equal(acd3d_decompose(&box, &p, &r[0], &err), ACD_OK);
    check_solid(&box, &r[0]);
    for (size_t i = 0; i < r[0].nparts; i++) assert_true(r[0].parts[i].concavity <= 1e-9);
    acd3d_result_free(&r[0]);
    acd_mesh_free(&box);
    acd_mesh_free(&m);
}

/* A closed cycle is a closed walk of mesh edges; split along it (acd3_surface_cut_chain) the
 * surface falls into pieces that hold every face once. Returns the number of pieces. */
static size_t check_cycle_split(const acd_mesh *m, const analysed *a) {
    assert_true(a->gc.closed);
    assert_true(a->gc.n >= 4);
    assert_int_equal(a->gc.v[0], a->gc.v[a->gc.n - 1]);
    for (size_t i = 0; i + 1 < a->gc.n; i++) assert_true(acd_edge_graph_find(&a->g, a->gc.v[i], a->gc.v[i + 1]) != ACD_NO_VERTEX);
    assert_true(a->gc.plane_n >= 2 && a->gc.plane_n <= a->gc.n);
    acd_cut_result r;
    acd_error err;
    assert_int_equal(acd3_surface_cut_chain(m, &a->g, a->gc.v, a->gc.n, &r, &err), ACD_OK);
    size_t faces = 0, np = r.npieces;
    for (size_t i = 0; i < r.npieces; i++) faces += r.pieces[i].mesh.ntriangles;
    assert_int_equal(faces, m->ntriangles);
    acd_cut_result_free(&r);
    return np;
}

/* The paper's dynamic geodesic cuts (acd3_gc_opts.dynamic): the dent of the box is a cup-shaped
 * pocket whose cut ends on the pocket's rim, which has no knots; the dynamic search closes it
 * into a cycle across the knot-less boundaries (the rim), and the cycle separates the box's
 * surface. The cycle's plane is still the cup cut's (plane_n). With witness_root the peanut's
 * cycle starts with a cut through the witness (its pocket is a strip between two projected hull
 * edges across the neck, so the cycle runs up the lobe and back, not around the neck, and need
 * not separate: the driver then keeps the plane strips). */
static void test_dynamic_cycle(void **state) {
    (void)state;
    acd_mesh m;
    dented_box(&m);
    analysed a, b;
    analyse(&m, 0.02, ACD3D_WEIGHT_RATIO, &a);
    analyse_opts(&m, 0.02, ACD3D_WEIGHT_RATIO, 1, 0, &b);
    assert_true(a.gc.cup && !a.gc.closed);
    assert_true(b.gc.cup && b.gc.closed && b.gc.dynamic);
    assert_int_equal(b.gc.plane_n, a.gc.n);
    assert_memory_equal(b.gc.v, a.gc.v, a.gc.n * sizeof *a.gc.v); /* the cup cut first */
    assert_true(b.has_plane);
    assert_memory_equal(b.normal, a.normal, sizeof a.normal);
    assert_true(check_cycle_split(&m, &b) >= 2);
    release(&a);
    release(&b);
    acd_mesh_free(&m);
    double k = 0.7;
    assert_true(mg_radial(&m, 48, 48, waist_r, &k));
    analyse_opts(&m, 0.05, ACD3D_WEIGHT_RATIO, 1, 1, &b);
    check_cut_graph(&m, &b);
    int through = 0;
    for (size_t i = 0; i < b.gc.n; i++) through |= b.gc.v[i] == b.ms.witness;
    assert_true(through);
    assert_true(b.gc.closed);
    assert_true(check_cycle_split(&m, &b) >= 1); /* here it runs up and back: it may not separate */
    release(&b);
    acd_mesh_free(&m);
}

/* Surface mode splitting along the cycle (acd3d_params.surface_cut): on the peanut and, when the
 * data is there, the elephant (genus 3): every part within tau, the parts hold every input face
 * once, the same parts for 1 and 2 threads. */
static void check_surface_run(const acd_mesh *m, acd3d_surface_cut sc, double tau) {
    acd3d_params p = acd3d_default_params();
    p.mode = ACD3D_SURFACE;
    p.surface_cut = sc;
    p.tau = tau;
    acd3d_result r[2];
    acd_error err;
    for (int i = 0; i < 2; i++) {
        p.threads = i + 1;
        assert_int_equal(acd3d_decompose(m, &p, &r[i], &err), ACD_OK);
        size_t faces = 0;
        for (size_t k = 0; k < r[i].nparts; k++) {
            faces += r[i].parts[k].mesh.ntriangles;
            acd3d_leaf_reason why = r[i].nodes[r[i].parts[k].node].leaf_reason;
            assert_true(why == ACD3D_LEAF_TAU || why == ACD3D_LEAF_FLAT || why == ACD3D_LEAF_JOINED);
            assert_true(r[i].parts[k].concavity <= r[i].tau * (1 + 1e-12));
        }
        assert_int_equal(faces, m->ntriangles);
    }
    same_result(&r[0], &r[1]);
    acd3d_result_free(&r[0]);
    acd3d_result_free(&r[1]);
}

static void test_surface_cycle_decompose(void **state) {
    (void)state;
    double k = 0.7;
    acd_mesh m;
    assert_true(mg_radial(&m, 48, 48, waist_r, &k));
    check_surface_run(&m, ACD3D_SURFACE_CYCLE, 0.05);
    check_surface_run(&m, ACD3D_SURFACE_CYCLE_WITNESS, 0.05);
    acd_mesh_free(&m);
    char path[1024];
    snprintf(path, sizeof path, "%s/elephant.off", ACD_MESH_DATA);
    acd_error err;
    if (acd_mesh_read(path, &m, &err) != ACD_OK) TU_SKIP("no elephant in %s (run scripts/fetch-data.sh)", ACD_MESH_DATA);
    /* at its root (tau 0.02) no cycle of G_K closes; the dynamic cuts close one */
    double tau = 0.02 * 0.557041;
    analysed a;
    analyse_opts(&m, tau, ACD3D_WEIGHT_RATIO, 1, 0, &a);
    assert_true(a.gc.closed && a.gc.dynamic);
    assert_true(check_cycle_split(&m, &a) >= 2);
    release(&a);
    check_surface_run(&m, ACD3D_SURFACE_CYCLE, 0.1);
    check_surface_run(&m, ACD3D_SURFACE_CYCLE_WITNESS, 0.1);
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_neck_cycle),
        cmocka_unit_test(test_l_notch_plane),
        cmocka_unit_test(test_cup_dent),
        cmocka_unit_test(test_cut_weight),
        cmocka_unit_test(test_decompose_global),
        cmocka_unit_test(test_dynamic_cycle),
        cmocka_unit_test(test_surface_cycle_decompose),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
