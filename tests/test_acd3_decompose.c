/* Tests of the 3D ACD driver (acd3/decompose, solid mode): partitions conserve volume, parts are
 * closed, every part meets tau under the measure (remeasured independently of the driver's
 * bookkeeping), known shapes give known part counts, output is deterministic, bad input refused. */
// ctest: TIMEOUT 600
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd/hull.h"
#include "acd3/measure.h"
#include "core/rng.h"
#include "geom3/bvh.h"
#include "geom3/dijkstra.h"
#include "geom3/edge_map.h"
#include "shapes.h"
#include "acd3d_check.h"

static double sphere_r(double th, double ph, void *u) { (void)th, (void)ph, (void)u; return 1.0; }
static double waist_r(double th, double ph, void *u) {
    (void)ph;
    double k = *(double *)u, s = sin(th);
    return 1.0 - k * s * s;
}

static double remeasure(const acd_mesh *m, double eps) {
    acd_edge_graph g;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m->vertices, m->nvertices, m->triangles, m->ntriangles, &g, &err), ACD_OK);
    acd3_measure ms;
    assert_int_equal(acd3_measure_compute(m, &g, eps, 1e-9, &ms, &err), ACD_OK);
    double c = ms.concavity;
    acd3_measure_free(&ms);
    acd_edge_graph_free(&g);
    return c;
}

/* Brute force: the largest distance from points of the part's hull (a barycentric grid on each
 * facet) to the part's triangles. */
static double hull_reach(const acd3d_part *pt) {
    const acd_mesh *h = &pt->hull, *m = &pt->mesh;
    double worst = 0;
    enum { GRID = 6 };
    for (size_t t = 0; t < h->ntriangles; t++) {
        const double *a = h->vertices + 3 * h->triangles[3 * t], *b = h->vertices + 3 * h->triangles[3 * t + 1],
                     *c = h->vertices + 3 * h->triangles[3 * t + 2];
        for (int i = 0; i <= GRID; i++)
            for (int j = 0; i + j <= GRID; j++) {
                double u = (double)i / GRID, v = (double)j / GRID, x[3];
                for (int k = 0; k < 3; k++) x[k] = a[k] + u * (b[k] - a[k]) + v * (c[k] - a[k]);
                double best = INFINITY;
                for (size_t s = 0; s < m->ntriangles; s++) {
                    double q[3];
                    const uint32_t *tr = m->triangles + 3 * s;
                    double d2 = acd_closest_point_triangle(x, m->vertices + 3 * tr[0], m->vertices + 3 * tr[1],
                                                           m->vertices + 3 * tr[2], q);
                    if (d2 < best) best = d2;
                }
                if (sqrt(best) > worst) worst = sqrt(best);
            }
    }
    return worst;
}

/* A part made by the merge pass: a record after the tree, its members point at it, their volumes
 * add up to its own, its bound meets tau, and its hull reaches out from it by at most tau. */
static void check_joined(const acd3d_result *r, size_t i) {
    const acd3d_part *pt = &r->parts[i];
    const acd3d_node *nd = &r->nodes[pt->node];
    assert_int_equal(nd->parent, -1);
    assert_int_equal(nd->first_child, -1);
    assert_true(pt->concavity <= r->tau);
    double vol = 0;
    int members = 0;
    for (size_t n = 0; n < r->nnodes; n++)
        if (r->nodes[n].merged_into == pt->node) {
            assert_int_equal(r->nodes[n].part, -1);
            vol += r->nodes[n].volume;
            members++;
        }
    assert_true(members >= 2);
    assert_true(fabs(vol - nd->volume) <= 1e-9 * vol);
    assert_true(fabs(mg_volume(&pt->mesh) - vol) <= 1e-9 * vol);
    /* the joined record's concavity is its bound: an upper bound of how far its hull reaches out */
    double reach = hull_reach(pt);
    assert_true(reach <= r->tau * (1 + 1e-9));
    assert_true(reach <= pt->concavity * (1 + 1e-9));
}

/* The properties every solid decomposition must have. */
static void check_solid(const acd_mesh *in, const acd3d_result *r, const acd3d_params *p) {
    double vin = mg_volume(in), sum = 0;
    assert_true(r->nparts >= 1);
    for (size_t i = 0; i < r->nparts; i++) {
        const acd_mesh *m = &r->parts[i].mesh;
        acd_edge_map em;
        acd_error err;
        assert_int_equal(acd_edge_map_build(m->triangles, m->ntriangles, NULL, &em, &err), ACD_OK);
        assert_int_equal(acd_edge_map_check_closed(&em, m->triangles, m->ntriangles, &err), ACD_OK);
        acd_edge_map_free(&em);
        double v = mg_volume(m);
        assert_true(v > 0);
        sum += v;
        /* the hull encloses the part: hull volume >= part volume */
        assert_true(r->parts[i].hull_volume >= v * (1 - 1e-9));
        if (!p->max_hull_vertices) { /* the hull of this mesh (a leaf's kept from its measure): the same bits */
            acd_hull h;
            assert_int_equal(acd_hull_compute(m->vertices, m->nvertices, &h, &err), ACD_OK);
            assert_true(h.volume == r->parts[i].hull_volume);
            assert_int_equal(h.nvertices, r->parts[i].hull.nvertices);
            assert_int_equal(h.ntriangles, r->parts[i].hull.ntriangles);
            assert_memory_equal(h.vertices, r->parts[i].hull.vertices, 3 * h.nvertices * sizeof(double));
            assert_memory_equal(h.triangles, r->parts[i].hull.triangles, 3 * h.ntriangles * sizeof(uint32_t));
            acd_hull_free(&h);
        }
        const acd3d_node *nd = &r->nodes[r->parts[i].node];
        assert_int_equal(nd->part, (int)i);
        assert_int_equal(nd->merged_into, -1);
        if (nd->leaf_reason == ACD3D_LEAF_JOINED) {
            check_joined(r, i);
            continue;
        }
        double c = remeasure(m, p->eps_ratio * r->tau);
        if (nd->leaf_reason == ACD3D_LEAF_HULL) {
            /* no cut split it, the measure above tau, but within tau of its hull both ways
             * (acd3/leaf_test): its concavity is that bound (test_acd3_leaf_test checks it) */
            assert_true(c > r->tau);
            assert_true(r->parts[i].concavity <= r->tau * (1 + 1e-9));
            continue;
        }
        assert_true(fabs(c - r->parts[i].concavity) <= 1e-12 * (1 + c));
        if (nd->leaf_reason == ACD3D_LEAF_TAU) assert_true(c <= r->tau + r->tol);
        else assert_true(nd->leaf_reason == ACD3D_LEAF_FLAT || nd->leaf_reason == ACD3D_LEAF_NO_CUT ||
                         nd->leaf_reason == ACD3D_LEAF_DEPTH || nd->leaf_reason == ACD3D_LEAF_MERGED);
    }
    assert_true(fabs(sum - vin) <= 1e-9 * vin);
}

static void test_convex_stays_whole(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 24, 12, sphere_r, NULL));
    acd3d_params p = acd3d_default_params();
    acd3d_result r;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_int_equal(r.nparts, 1);
    assert_int_equal(r.nnodes, 1);
    check_solid(&m, &r, &p);
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}

static void test_l_shape_two_convex_parts(void **state) {
    (void)state;
    unsigned char occ[16];
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 4; x++) occ[y * 4 + x] = !(x >= 2 && y >= 2);
    acd_mesh m;
    assert_true(mg_voxels(&m, occ, 4, 4, 1));
    acd3d_params p = acd3d_default_params();
    p.tau = 0.0;
    p.tau_absolute = 1;
    acd3d_result r;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_int_equal(r.nparts, 2);
    /* tau 0: parts convex up to the stated rounding tolerance, 1e-10 of the box diagonal */
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) lo[k] = hi[k] = m.vertices[k];
    for (size_t v = 0; v < m.nvertices; v++)
        for (int k = 0; k < 3; k++) lo[k] = fmin(lo[k], m.vertices[3 * v + k]), hi[k] = fmax(hi[k], m.vertices[3 * v + k]);
    double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
    assert_true(fabs(r.tol - 1e-10 * diag) <= 1e-12 * r.tol);
    check_solid(&m, &r, &p);
    for (size_t i = 0; i < r.nparts; i++) assert_true(r.parts[i].concavity <= r.tol);
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}

static void test_waist_splits_and_is_deterministic(void **state) {
    (void)state;
    double k = 0.7;
    acd_mesh m;
    assert_true(mg_radial(&m, 48, 48, waist_r, &k));
    acd3d_params p = acd3d_default_params();
    p.tau = 0.05;
    acd3d_result r, r2;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_true(r.nparts >= 2);
    check_solid(&m, &r, &p);
    assert_int_equal(acd3d_decompose(&m, &p, &r2, &err), ACD_OK);
    ck3_same_parts(&r, &r2);
    acd3d_result_free(&r);
    acd3d_result_free(&r2);
    acd_mesh_free(&m);
}

static void test_threads_and_hull_budget(void **state) {
    (void)state;
    double k = 0.7;
    acd_mesh m;
    assert_true(mg_radial(&m, 48, 48, waist_r, &k));
    acd3d_params p = acd3d_default_params();
    p.tau = 0.02;
    acd3d_result r[3];
    acd_error err;
    int th[3] = {1, 2, 4};
    for (int i = 0; i < 3; i++) {
        p.threads = th[i];
        assert_int_equal(acd3d_decompose(&m, &p, &r[i], &err), ACD_OK);
    }
    for (int i = 1; i < 3; i++) {
        assert_int_equal(r[i].nparts, r[0].nparts);
        assert_int_equal(r[i].nnodes, r[0].nnodes);
        for (size_t j = 0; j < r[0].nparts; j++) {
            assert_int_equal(r[i].parts[j].mesh.nvertices, r[0].parts[j].mesh.nvertices);
            assert_memory_equal(r[i].parts[j].mesh.vertices, r[0].parts[j].mesh.vertices,
                                3 * r[0].parts[j].mesh.nvertices * sizeof(double));
        }
    }
    /* a hull budget: at most 8 vertices per hull, every part still inside its hull */
    p.threads = 1;
    p.max_hull_vertices = 8;
    acd3d_result rb;
    assert_int_equal(acd3d_decompose(&m, &p, &rb, &err), ACD_OK);
    assert_int_equal(rb.nparts, r[0].nparts);
    for (size_t j = 0; j < rb.nparts; j++) {
        assert_true(rb.parts[j].hull.nvertices <= 8);
        acd_hull h;
        assert_int_equal(acd_hull_compute(rb.parts[j].hull.vertices, rb.parts[j].hull.nvertices, &h, &err), ACD_OK);
        for (size_t v = 0; v < rb.parts[j].mesh.nvertices; v++)
            assert_true(acd_hull_plane_distance(&h, rb.parts[j].mesh.vertices + 3 * v) <= 1e-9);
        acd_hull_free(&h);
    }
    acd3d_result_free(&rb);
    /* max_hulls: at most that many parts, still a partition; the merged parts are the nodes
     * whose splits were undone, smallest concavity first */
    p.max_hull_vertices = 0;
    for (size_t cap = 1; cap <= 3; cap++) {
        p.max_hulls = cap;
        assert_int_equal(acd3d_decompose(&m, &p, &rb, &err), ACD_OK);
        assert_true(rb.nparts <= cap);
        check_solid(&m, &rb, &p);
        if (cap == 1) {
            assert_int_equal(rb.nparts, 1);
            assert_true(fabs(rb.max_concavity - rb.nodes[0].concavity) <= 0); /* back to the input */
        }
        assert_true(rb.max_concavity >= r[0].max_concavity); /* merging never lowers concavity */
        acd3d_result_free(&rb);
    }
    p.max_hulls = 0;
    for (int i = 0; i < 3; i++) acd3d_result_free(&r[i]);
    p.max_hull_vertices = 3;
    assert_int_equal(acd3d_decompose(&m, &p, &rb, &err), ACD_ERR_INVALID_ARGUMENT);
    acd_mesh_free(&m);
}

static void test_torus_finishes(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_torus(&m, 32, 16, 1.0, 0.35));
    acd3d_params p = acd3d_default_params();
    p.tau = 0.1;
    acd3d_result r;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_true(r.nparts >= 3); /* a ring needs at least three convex-ish pieces */
    check_solid(&m, &r, &p);
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}

/* Surface mode: the parts tile the surface (every input face in exactly one part, areas add up)
 * and the tau bound holds for parts that stopped on it. */
static double mesh_area(const acd_mesh *m) {
    double a = 0;
    for (size_t t = 0; t < m->ntriangles; t++) {
        const double *p = m->vertices + 3 * m->triangles[3 * t], *q = m->vertices + 3 * m->triangles[3 * t + 1],
                     *r = m->vertices + 3 * m->triangles[3 * t + 2];
        double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
        double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        a += 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    }
    return a;
}

/* The merge pass: it joins parts of the torus (fewer than without it, each joined part within tau
 * of its hull, checked by brute force in check_solid), the same for 1 and 2 threads; it leaves the
 * L-shape's two parts alone (their joined hull reaches sqrt(2) beyond the notch); --no-merge keeps
 * every leaf. */
static void test_merge_pass(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_torus(&m, 32, 16, 1.0, 0.35));
    acd3d_params p = acd3d_default_params();
    p.tau = 0.1;
    acd3d_result on, on2, off;
    acd_error err;
    p.threads = 1;
    assert_int_equal(acd3d_decompose(&m, &p, &on, &err), ACD_OK);
    p.threads = 2;
    assert_int_equal(acd3d_decompose(&m, &p, &on2, &err), ACD_OK);
    p.merge = 0;
    assert_int_equal(acd3d_decompose(&m, &p, &off, &err), ACD_OK);
    int joined = 0;
    for (size_t i = 0; i < on.nparts; i++) joined += on.nodes[on.parts[i].node].leaf_reason == ACD3D_LEAF_JOINED;
    assert_true(joined >= 1);
    assert_true(on.nparts < off.nparts);
    assert_true(on.nparts >= 3); /* still a ring of pieces */
    for (size_t i = 0; i < off.nparts; i++) assert_true(off.nodes[off.parts[i].node].leaf_reason != ACD3D_LEAF_JOINED);
    assert_int_equal(on2.nparts, on.nparts);
    for (size_t i = 0; i < on.nparts; i++) {
        assert_int_equal(on2.parts[i].mesh.nvertices, on.parts[i].mesh.nvertices);
        assert_memory_equal(on2.parts[i].mesh.vertices, on.parts[i].mesh.vertices,
                            3 * on.parts[i].mesh.nvertices * sizeof(double));
        assert_true(on2.parts[i].concavity == on.parts[i].concavity);
    }
    check_solid(&m, &on, &p);
    check_solid(&m, &off, &p);
    /* a larger merge tolerance joins at least as much; the joined bounds meet it, not tau */
    acd3d_result wide;
    p.merge = 1;
    p.merge_tau = 0.2;
    assert_int_equal(acd3d_decompose(&m, &p, &wide, &err), ACD_OK);
    assert_true(wide.nparts <= on.nparts);
    assert_true(fabs(wide.merge_tau - 2 * wide.tau) <= 1e-12 * wide.tau);
    for (size_t i = 0; i < wide.nparts; i++)
        if (wide.nodes[wide.parts[i].node].leaf_reason == ACD3D_LEAF_JOINED) {
            assert_true(wide.parts[i].concavity <= wide.merge_tau);
            double reach = hull_reach(&wide.parts[i]);
            assert_true(reach <= wide.merge_tau * (1 + 1e-9));
            assert_true(reach <= wide.parts[i].concavity * (1 + 1e-9));
        }
    acd3d_result_free(&wide);
    acd3d_result_free(&on);
    acd3d_result_free(&on2);
    acd3d_result_free(&off);
    acd_mesh_free(&m);

    unsigned char occ[16];
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 4; x++) occ[y * 4 + x] = !(x >= 2 && y >= 2);
    assert_true(mg_voxels(&m, occ, 4, 4, 1));
    p = acd3d_default_params();
    p.tau = 0.3;
    p.tau_absolute = 1;
    assert_int_equal(acd3d_decompose(&m, &p, &on, &err), ACD_OK);
    assert_int_equal(on.nparts, 2);
    check_solid(&m, &on, &p);
    acd3d_result_free(&on);
    acd_mesh_free(&m);
}

/* Hull tightness (docs/acd3d.md): the cut choice by hull volume and the merge pass ordered by the
 * volume a join adds keep every property of a solid decomposition (volumes, closed parts, tau
 * for the leaves, the joined bounds), give the same output for 1 and 2 threads, and merge_parts
 * stops the merge at exactly that many parts when the merge would go below it. */
static void test_hull_tightness(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_torus(&m, 32, 16, 1.0, 0.35));
    acd3d_params p = acd3d_default_params();
    p.tau = 0.05;
    p.cut_choice = ACD3D_CHOICE_VOLUME;
    p.merge_order = ACD3D_MERGE_VOLUME;
    acd3d_result leaves, all, all2, stop;
    acd_error err;
    p.merge = 0;
    assert_int_equal(acd3d_decompose(&m, &p, &leaves, &err), ACD_OK);
    check_solid(&m, &leaves, &p);
    p.merge = 1;
    p.threads = 1;
    assert_int_equal(acd3d_decompose(&m, &p, &all, &err), ACD_OK);
    p.threads = 2;
    assert_int_equal(acd3d_decompose(&m, &p, &all2, &err), ACD_OK);
    check_solid(&m, &all, &p);
    assert_true(all.nparts < leaves.nparts);
    assert_int_equal(all2.nparts, all.nparts);
    for (size_t i = 0; i < all.nparts; i++) {
        assert_int_equal(all2.parts[i].mesh.nvertices, all.parts[i].mesh.nvertices);
        assert_memory_equal(all2.parts[i].mesh.vertices, all.parts[i].mesh.vertices,
                            3 * all.parts[i].mesh.nvertices * sizeof(double));
        assert_true(all2.parts[i].concavity == all.parts[i].concavity);
    }
    /* a stop between the merged and the unmerged counts is met exactly */
    assert_true(leaves.nparts >= all.nparts + 2);
    p.merge_parts = all.nparts + (leaves.nparts - all.nparts) / 2;
    assert_int_equal(acd3d_decompose(&m, &p, &stop, &err), ACD_OK);
    assert_int_equal(stop.nparts, p.merge_parts);
    check_solid(&m, &stop, &p);
    /* the stopped merge is a prefix of the full one (the same greedy sequence): every stopped part's
     * leaves lie in one part of the full merge (the tree, hence the leaves' nodes, is the same) */
    for (size_t i = 0; i < stop.nparts; i++) {
        int jn = stop.parts[i].node, target = -2;
        for (size_t n = 0; n < leaves.nnodes; n++) {
            int in_stop = stop.nodes[n].merged_into == jn || (int)n == jn;
            if (!in_stop) continue;
            int t = all.nodes[n].merged_into >= 0 ? all.nodes[n].merged_into : (int)n;
            if (target == -2) target = t;
            assert_int_equal(t, target);
        }
        assert_true(target != -2);
    }
    acd3d_result_free(&leaves);
    acd3d_result_free(&all);
    acd3d_result_free(&all2);
    acd3d_result_free(&stop);
    acd_mesh_free(&m);
}

/* The cut choice by band (docs/acd3d.md "Cut choice by band"): the default's candidates compared by
 * the volume choice's rule keep every property of a solid decomposition, give the same tree and parts
 * for 1 and 2 threads, and choose other cuts than the default on the torus (the option is used). */
static void test_cut_choice_band(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_torus(&m, 32, 16, 1.0, 0.35));
    acd3d_params p = acd3d_default_params();
    p.tau = 0.05;
    p.merge = 0;
    acd3d_result conc, band, band2;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &conc, &err), ACD_OK);
    p.cut_choice = ACD3D_CHOICE_BAND;
    p.threads = 1;
    assert_int_equal(acd3d_decompose(&m, &p, &band, &err), ACD_OK);
    p.threads = 2;
    assert_int_equal(acd3d_decompose(&m, &p, &band2, &err), ACD_OK);
    check_solid(&m, &band, &p);
    assert_int_equal(band2.nnodes, band.nnodes);
    for (size_t n = 0; n < band.nnodes; n++) {
        assert_memory_equal(band2.nodes[n].cut_plane, band.nodes[n].cut_plane, sizeof band.nodes[n].cut_plane);
        assert_true(band2.nodes[n].concavity == band.nodes[n].concavity);
    }
    assert_int_equal(band2.nparts, band.nparts);
    for (size_t i = 0; i < band.nparts; i++) {
        assert_int_equal(band2.parts[i].mesh.nvertices, band.parts[i].mesh.nvertices);
        assert_memory_equal(band2.parts[i].mesh.vertices, band.parts[i].mesh.vertices,
                            3 * band.parts[i].mesh.nvertices * sizeof(double));
    }
    int differs = band.nnodes != conc.nnodes;
    for (size_t n = 0; n < band.nnodes && !differs; n++)
        differs = memcmp(band.nodes[n].cut_plane, conc.nodes[n].cut_plane, sizeof band.nodes[n].cut_plane) != 0;
    assert_true(differs);
    acd3d_result_free(&conc);
    acd3d_result_free(&band);
    acd3d_result_free(&band2);
    acd_mesh_free(&m);
}

static void check_surface(const acd_mesh *in, const acd3d_result *r, const acd3d_params *p) {
    size_t faces = 0;
    double area = 0;
    for (size_t i = 0; i < r->nparts; i++) {
        faces += r->parts[i].mesh.ntriangles;
        area += mesh_area(&r->parts[i].mesh);
        const acd3d_node *nd = &r->nodes[r->parts[i].node];
        if (nd->leaf_reason == ACD3D_LEAF_TAU)
            assert_true(remeasure(&r->parts[i].mesh, p->eps_ratio * r->tau) <= r->tau + 1e-9);
    }
    assert_int_equal(faces, in->ntriangles);
    assert_true(fabs(area - mesh_area(in)) <= 1e-9 * mesh_area(in));
}

static double hemi_r(double th, double ph, void *u) { (void)th, (void)ph, (void)u; return 1.0; }

static void test_surface_mode(void **state) {
    (void)state;
    acd3d_params p = acd3d_default_params();
    p.mode = ACD3D_SURFACE;
    p.tau = 0.05;
    acd3d_result r;
    acd_error err;
    /* a closed convex surface stays whole */
    acd_mesh m;
    assert_true(mg_radial(&m, 24, 12, sphere_r, NULL));
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_int_equal(r.nparts, 1);
    check_surface(&m, &r, &p);
    acd3d_result_free(&r);
    /* an open surface (the sphere without its southern cap) is taken as it is */
    size_t keep = m.ntriangles - 24; /* the last ring of triangles touches the south pole */
    m.ntriangles = keep;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    check_surface(&m, &r, &p);
    assert_int_equal(r.nparts, 1);
    acd3d_result_free(&r);
    /* the same bowl with its faces reversed shows its inner side to the hull (spec §3.4): still
     * a convex surface patch, one part */
    for (size_t t = 0; t < m.ntriangles; t++) {
        uint32_t x = m.triangles[3 * t + 1];
        m.triangles[3 * t + 1] = m.triangles[3 * t + 2], m.triangles[3 * t + 2] = x;
    }
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    check_surface(&m, &r, &p);
    assert_int_equal(r.nparts, 1);
    acd3d_result_free(&r);
    acd_mesh_free(&m);
    (void)hemi_r;
    /* the waist splits into several patches that tile the surface */
    double k = 0.7;
    assert_true(mg_radial(&m, 48, 48, waist_r, &k));
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_true(r.nparts >= 2);
    check_surface(&m, &r, &p);
    /* the surface splits along section loops (spec §5.1): no part is a sliver of the jagged
     * section (one or two faces cut off along a loop) */
    size_t minfaces = SIZE_MAX;
    for (size_t i = 0; i < r.nparts; i++)
        if (r.parts[i].mesh.ntriangles < minfaces) minfaces = r.parts[i].mesh.ntriangles;
    assert_true(r.nparts <= 4 && minfaces >= 48);
    acd3d_result r2;
    assert_int_equal(acd3d_decompose(&m, &p, &r2, &err), ACD_OK);
    assert_int_equal(r.nparts, r2.nparts);
    for (size_t i = 0; i < r.nparts; i++) assert_int_equal(r.parts[i].mesh.ntriangles, r2.parts[i].mesh.ntriangles);
    acd3d_result_free(&r);
    acd3d_result_free(&r2);
    acd_mesh_free(&m);
}

/* Spiky stars: UV spheres of 8 x 5 whose vertex radii are drawn from {0.3, 0.6, 1.0, 1.4}
 * (coplanar faces and symmetric rings: cut planes run through vertices and along faces). Every
 * part must end within tau, its volume positive and the volumes adding up. Before flat shells
 * were dropped by the plane cut (geom3/plane_cut.c) a zero-volume sheet taken as a cavity made
 * parts that no plane could split (about one star in four ended with a part above tau). */
typedef struct star_radii {
    double r[64];
} star_radii;
static double star_r(double th, double ph, void *u) {
    const star_radii *s = u;
    const double pi = 3.14159265358979323846;
    int j = (int)lround(th / pi * 5), i = (int)lround(ph / (2 * pi) * 8) % 8;
    return s->r[j * 8 + i];
}
static void test_spiky_stars_within_tau(void **state) {
    (void)state;
    static const double levels[4] = {0.3, 0.6, 1.0, 1.4};
    int below = 0;
    for (uint64_t seed = 1; seed <= 16; seed++) {
        star_radii sr;
        acd_rng rng;
        acd_rng_seed(&rng, seed);
        for (int k = 0; k < 64; k++) sr.r[k] = levels[acd_rng_below(&rng, 4)];
        acd_mesh m;
        assert_true(mg_radial(&m, 8, 5, star_r, &sr));
        acd3d_params p = acd3d_default_params();
        p.tau = 0.05;
        p.threads = 1;
        acd3d_result r;
        acd_error err;
        assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
        check_solid(&m, &r, &p);
        int ok = 1;
        for (size_t i = 0; i < r.nparts; i++) {
            acd3d_leaf_reason why = r.nodes[r.parts[i].node].leaf_reason;
            if (why != ACD3D_LEAF_TAU && why != ACD3D_LEAF_JOINED && why != ACD3D_LEAF_FLAT) ok = 0;
        }
        if (!ok) print_message("star seed %llu: a part left above tau\n", (unsigned long long)seed);
        below += ok;
        acd3d_result_free(&r);
        acd_mesh_free(&m);
    }
    assert_int_equal(below, 16);
}

/* The same tree and parts, bit for bit (the nodes' concavities and cut planes, the parts'
 * vertices and triangles). */
static void assert_same_result(const acd3d_result *a, const acd3d_result *b) {
    assert_int_equal(a->nnodes, b->nnodes);
    assert_int_equal(a->nparts, b->nparts);
    for (size_t i = 0; i < a->nnodes; i++) {
        const acd3d_node *x = &a->nodes[i], *y = &b->nodes[i];
        assert_int_equal(x->parent, y->parent);
        assert_int_equal(x->first_child, y->first_child);
        assert_int_equal(x->nchildren, y->nchildren);
        assert_int_equal(x->leaf_reason, y->leaf_reason);
        assert_int_equal(x->merged_into, y->merged_into);
        assert_memory_equal(&x->concavity, &y->concavity, sizeof x->concavity);
        assert_memory_equal(x->cut_plane, y->cut_plane, sizeof x->cut_plane);
    }
    for (size_t j = 0; j < a->nparts; j++) {
        const acd_mesh *x = &a->parts[j].mesh, *y = &b->parts[j].mesh;
        assert_int_equal(x->nvertices, y->nvertices);
        assert_int_equal(x->ntriangles, y->ntriangles);
        assert_memory_equal(x->vertices, y->vertices, 3 * x->nvertices * sizeof(double));
        assert_memory_equal(x->triangles, y->triangles, 3 * x->ntriangles * sizeof(uint32_t));
    }
}

/* A split's candidates are evaluated by every thread without a node of its own (the root's with
 * 2 or 4 threads: its batch has one node), the choice replayed in candidate order: the tree is
 * the single thread's, in both modes, on spiky stars (many candidates per split, ties of
 * concavity between them) and the waist. */
static void test_parallel_candidates_same_tree(void **state) {
    (void)state;
    static const double levels[4] = {0.3, 0.6, 1.0, 1.4};
    for (uint64_t seed = 0; seed <= 6; seed++) {
        acd_mesh m;
        double k = 0.7;
        star_radii sr;
        if (seed == 0) {
            assert_true(mg_radial(&m, 48, 48, waist_r, &k));
        } else {
            acd_rng rng;
            acd_rng_seed(&rng, 100 + seed);
            for (int i = 0; i < 64; i++) sr.r[i] = levels[acd_rng_below(&rng, 4)];
            assert_true(mg_radial(&m, 8, 5, star_r, &sr));
        }
        for (int mode = 0; mode < 2; mode++) {
            acd3d_params p = acd3d_default_params();
            p.tau = 0.03;
            p.mode = mode ? ACD3D_SURFACE : ACD3D_SOLID;
            acd3d_result r[3];
            acd_error err;
            static const int th[3] = {1, 2, 4};
            for (int i = 0; i < 3; i++) {
                p.threads = th[i];
                assert_int_equal(acd3d_decompose(&m, &p, &r[i], &err), ACD_OK);
            }
            assert_true(r[0].nnodes >= 3); /* split at least once */
            for (int i = 1; i < 3; i++) assert_same_result(&r[0], &r[i]);
            for (int i = 0; i < 3; i++) acd3d_result_free(&r[i]);
        }
        acd_mesh_free(&m);
    }
}

static void test_bad_input(void **state) {
    (void)state;
    acd3d_params p = acd3d_default_params();
    acd3d_result r;
    acd_error err;
    acd_mesh empty = {0};
    assert_int_equal(acd3d_decompose(&empty, &p, &r, &err), ACD_ERR_DEGENERATE);
    /* an open mesh (one face missing) in solid mode: refused, naming the edge */
    acd_mesh m;
    assert_true(mg_radial(&m, 12, 6, sphere_r, NULL));
    m.ntriangles--;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_NON_MANIFOLD);
    assert_non_null(strstr(err.message, "closed"));
    m.ntriangles++;
    m.vertices[4] = NAN;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "vertex 1"));
    /* a coordinate too large for the exact predicates: refused, naming the vertex */
    m.vertices[4] = 1e200;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "vertex 1 has coordinate 1e+200, beyond"));
    m.vertices[4] = 0;
    /* a model below ACD_EXTENT_MIN (the exact predicates' products underflow): refused */
    {
        acd_mesh tiny;
        assert_int_equal(acd_mesh_copy(&tiny, &m, &err), ACD_OK);
        for (size_t i = 0; i < 3 * tiny.nvertices; i++) tiny.vertices[i] = ldexp(tiny.vertices[i], -266);
        assert_int_equal(acd3d_decompose(&tiny, &p, &r, &err), ACD_ERR_INVALID_INPUT);
        assert_non_null(strstr(err.message, "below the supported"));
        acd_mesh_free(&tiny);
    }
    acd3d_params bad = p;
    bad.cookie = 0;
    assert_int_equal(acd3d_decompose(&m, &bad, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    bad = p;
    bad.threads = 100000; /* crashed inside libgomp */
    assert_int_equal(acd3d_decompose(&m, &bad, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err.message, "threads 100000"));
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_convex_stays_whole),
        cmocka_unit_test(test_l_shape_two_convex_parts),
        cmocka_unit_test(test_waist_splits_and_is_deterministic),
        cmocka_unit_test(test_threads_and_hull_budget),
        cmocka_unit_test(test_torus_finishes),
        cmocka_unit_test(test_merge_pass),
        cmocka_unit_test(test_hull_tightness),
        cmocka_unit_test(test_cut_choice_band),
        cmocka_unit_test(test_surface_mode),
        cmocka_unit_test(test_spiky_stars_within_tau),
        cmocka_unit_test(test_parallel_candidates_same_tree),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
