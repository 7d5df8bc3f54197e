/* Tests of acd3/surface_merge: pieces of a sphere (a convex surface: every union measures 0 up to
 * eps) all join back into the closed sphere; pieces of a torus join only into groups whose welded
 * union measures within tau (measured again here), and with a tolerant tau back into the torus
 * (genus 1: the welding restores the input's connectivity); tau 0 on the torus joins nothing
 * that is not convex. Through the driver (acd3d_decompose, surface mode, whose tree is cut finer
 * than tau for the merge pass): every part measured again here at the output's eps is within the
 * merge tolerance (also with a merge tolerance above tau: the merge pass measures with that
 * tolerance's eps), the parts tile the input's faces, the same parts for 1 and 2 threads, and no
 * more parts than without the merge pass. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd3/measure.h"
#include "acd3/surface_cut.h"
#include "acd3/surface_merge.h"
#include "acd3/topology.h"
#include "geom3/dijkstra.h"
#include "geom3/plane_cut.h"
#include "acd3d_check.h"
#include "shapes.h"

static double sphere_r(double th, double ph, void *u) {
    (void)th, (void)ph, (void)u;
    return 1.0;
}

/* Cuts every piece by each plane through the origin with the given normals (whole sections). */
static size_t slice(const acd_mesh *m, const double (*normals)[3], int nn, acd_mesh **out) {
    size_t n = 1;
    acd_mesh *cur = malloc(sizeof *cur);
    assert_non_null(cur);
    acd_error err;
    assert_int_equal(acd_mesh_copy(&cur[0], m, &err), ACD_OK);
    const double o[3] = {0, 0, 0};
    for (int i = 0; i < nn; i++) {
        acd_mesh *next = NULL;
        size_t nn2 = 0;
        for (size_t k = 0; k < n; k++) {
            acd_edge_graph g;
            assert_int_equal(acd_edge_graph_from_mesh(cur[k].vertices, cur[k].nvertices, cur[k].triangles, cur[k].ntriangles,
                                                      &g, &err),
                             ACD_OK);
            acd_cut_plane pl;
            assert_int_equal(acd_cut_plane_from_normal(o, normals[i], 4.0, &pl, &err), ACD_OK);
            acd_cut_result r;
            assert_int_equal(acd3_surface_cut(&cur[k], &g, &pl, NULL, &r, &err), ACD_OK);
            next = realloc(next, (nn2 + r.npieces) * sizeof *next);
            assert_non_null(next);
            for (size_t j = 0; j < r.npieces; j++) {
                next[nn2++] = r.pieces[j].mesh;
                memset(&r.pieces[j].mesh, 0, sizeof r.pieces[j].mesh);
            }
            acd_cut_result_free(&r);
            acd_edge_graph_free(&g);
            acd_mesh_free(&cur[k]);
        }
        free(cur);
        cur = next;
        n = nn2;
    }
    *out = cur;
    return n;
}

static double measure(const acd_mesh *m, double eps) {
    acd_edge_graph g;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m->vertices, m->nvertices, m->triangles, m->ntriangles, &g, &err), ACD_OK);
    acd3_measure ms;
    assert_int_equal(acd3_measure_compute(m, &g, eps, 1e-12, &ms, &err), ACD_OK);
    double c = ms.concavity;
    acd3_measure_free(&ms);
    acd_edge_graph_free(&g);
    return c;
}

/* Every group of r (over n parts) of two parts or more within tau, as recorded and measured again
 * (at eps), one connected piece (of genus 0 when genus0); the groups' sizes add up to n. */
static void check_groups(const acd3_surface_merge_result *r, size_t n, double eps, double tau, int genus0) {
    size_t total = 0;
    for (size_t g = 0; g < r->ngroups; g++) {
        total += r->group_size[g];
        if (r->group_size[g] < 2) continue;
        assert_true(r->concavity[g] <= tau);
        assert_true(measure(&r->meshes[g], eps) <= tau);
        acd3_topology t;
        acd_error err;
        assert_int_equal(acd3_topology_of(&r->meshes[g], &t, &err), ACD_OK);
        assert_int_equal(t.components, 1);
        if (genus0) assert_int_equal(t.genus, 0);
    }
    assert_int_equal(total, n);
}

static void free_parts(acd_mesh *p, size_t n) {
    for (size_t i = 0; i < n; i++) acd_mesh_free(&p[i]);
    free(p);
}

static void test_sphere_joins_back(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 32, 16, sphere_r, NULL));
    const double nrm[3][3] = {{0, 0, 1}, {1, 0, 0}, {0.6, 0.8, 0}};
    acd_mesh *parts;
    size_t n = slice(&m, nrm, 3, &parts);
    assert_true(n >= 6);
    acd3_surface_merge_result r;
    acd_error err;
    assert_int_equal(acd3_surface_merge(parts, n, 0.01, 0.02, 1e-12, 2, NULL, NULL, &r, &err), ACD_OK);
    assert_int_equal(r.ngroups, 1);
    assert_int_equal(r.merges, n - 1);
    assert_true(r.concavity[0] <= 0.02);
    assert_int_equal(r.meshes[0].ntriangles, m.ntriangles);
    acd3_topology t;
    assert_int_equal(acd3_topology_of(&r.meshes[0], &t, &err), ACD_OK);
    assert_true(t.genus == 0 && t.boundary_loops == 0 && t.components == 1);
    acd3_surface_merge_result_free(&r);
    free_parts(parts, n);
    acd_mesh_free(&m);
}

static void test_torus_groups_within_tau(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_torus(&m, 48, 16, 1.0, 0.35));
    const double nrm[4][3] = {{1, 0, 0}, {0, 1, 0}, {0.7071067811865476, 0.7071067811865476, 0},
                              {0.7071067811865476, -0.7071067811865476, 0}};
    acd_mesh *parts;
    size_t n = slice(&m, nrm, 4, &parts);
    assert_int_equal(n, 8);
    acd_error err;
    const double tau = 0.25, eps = 0.2 * tau;
    acd3_surface_merge_result r;
    assert_int_equal(acd3_surface_merge(parts, n, eps, tau, 1e-12, 1, NULL, NULL, &r, &err), ACD_OK);
    assert_true(r.ngroups < n);  /* a quarter of the ring: its inner wall 0.65 (1 - cos 45 deg) = 0.19 deep */
    assert_true(r.ngroups >= 3); /* three eighths: 0.40 */
    print_message("torus eighths: %zu groups\n", r.ngroups);
    check_groups(&r, n, eps, tau, 1);
    /* same groups with two threads */
    acd3_surface_merge_result r2;
    assert_int_equal(acd3_surface_merge(parts, n, eps, tau, 1e-12, 2, NULL, NULL, &r2, &err), ACD_OK);
    assert_int_equal(r2.ngroups, r.ngroups);
    for (size_t i = 0; i < n; i++) assert_int_equal(r2.group_of[i], r.group_of[i]);
    acd3_surface_merge_result_free(&r2);
    acd3_surface_merge_result_free(&r);
    /* a tolerant tau: one group, the torus again */
    assert_int_equal(acd3_surface_merge(parts, n, eps, 10.0, 1e-12, 1, NULL, NULL, &r, &err), ACD_OK);
    assert_int_equal(r.ngroups, 1);
    acd3_topology t;
    assert_int_equal(acd3_topology_of(&r.meshes[0], &t, &err), ACD_OK);
    assert_true(t.genus == 1 && t.boundary_loops == 0);
    acd3_surface_merge_result_free(&r);
    free_parts(parts, n);
    acd_mesh_free(&m);
}

static double bumpy(double th, double ph, void *u) {
    (void)u;
    return 1.0 + 0.15 * sin(5 * th) * cos(3 * ph) + 0.05 * cos(11 * ph) * sin(7 * th);
}

/* Slices of a bumpy sphere: groups within tau (measured again), connected, the same for 1 and 2
 * threads; on this input some parts are moved (a pair nearly joinable joined by moving one of
 * its parts to a third group). */
static void test_moves(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 64, 32, bumpy, NULL));
    const double nrm[6][3] = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {0.6, 0.8, 0}, {0.8, 0, 0.6}, {0, 0.6, -0.8}};
    acd_mesh *parts;
    size_t n = slice(&m, nrm, 6, &parts);
    acd_error err;
    const double taus[2] = {0.0965, 0.212};
    size_t moves = 0;
    for (int i = 0; i < 2; i++) {
        const double tau = taus[i], eps = 0.5 * tau;
        acd3_surface_merge_result r, r2;
        assert_int_equal(acd3_surface_merge(parts, n, eps, tau, 1e-12, 1, NULL, NULL, &r, &err), ACD_OK);
        assert_int_equal(acd3_surface_merge(parts, n, eps, tau, 1e-12, 2, NULL, NULL, &r2, &err), ACD_OK);
        print_message("tau %g: %zu pieces, %zu groups, %zu joins, %zu moves\n", tau, n, r.ngroups, r.merges, r.moves);
        assert_int_equal(r.ngroups + r.merges + r.moves, n);
        assert_int_equal(r2.ngroups, r.ngroups);
        assert_int_equal(r2.moves, r.moves);
        for (size_t k = 0; k < n; k++) assert_int_equal(r2.group_of[k], r.group_of[k]);
        check_groups(&r, n, eps, tau, 0);
        moves += r.moves;
        acd3_surface_merge_result_free(&r);
        acd3_surface_merge_result_free(&r2);
    }
    assert_true(moves > 0);
    free_parts(parts, n);
    acd_mesh_free(&m);
}

static acd3d_result decompose(const acd_mesh *m, double tau, double merge_tau, int merge, int threads) {
    acd3d_params p = acd3d_default_params();
    p.mode = ACD3D_SURFACE;
    p.tau = tau;
    p.merge = merge;
    p.merge_tau = merge_tau;
    p.threads = threads;
    acd3d_result r;
    acd_error err;
    assert_int_equal(acd3d_decompose(m, &p, &r, &err), ACD_OK);
    return r;
}

/* Every part within bound by the measure at eps = eps_ratio x bound; the parts hold every face once. */
static void check_parts(const acd_mesh *m, const acd3d_result *r, double bound) {
    const double eps = acd3d_default_params().eps_ratio * bound, tol = 1e-9 * r->scale;
    size_t faces = 0;
    for (size_t i = 0; i < r->nparts; i++) {
        faces += r->parts[i].mesh.ntriangles;
        double c = measure(&r->parts[i].mesh, eps);
        if (c > bound + tol) print_message("part %zu: %.17g > %.17g\n", i, c, bound);
        assert_true(c <= bound + tol);
        assert_true(r->parts[i].concavity <= bound + tol);
    }
    assert_int_equal(faces, m->ntriangles);
}

static void test_decompose_within_tau(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 48, 24, bumpy, NULL));
    const double tau = 0.03;
    acd3d_result a = decompose(&m, tau, 0, 1, 1), b = decompose(&m, tau, 0, 1, 2), c = decompose(&m, tau, 0, 0, 1);
    print_message("bumpy sphere, surface, tau %g: %zu parts (%zu without the merge pass)\n", tau, a.nparts, c.nparts);
    check_parts(&m, &a, a.tau);
    check_parts(&m, &c, c.tau);
    ck3_same_parts(&a, &b);
    assert_true(a.nparts <= c.nparts);
    assert_true(a.nparts < c.nparts); /* this input: the merge pass joins something */
    acd3d_result_free(&b);
    /* a merge tolerance above tau: measured with its own eps */
    b = decompose(&m, tau, 2 * tau, 1, 1);
    assert_true(b.merge_tau > b.tau);
    check_parts(&m, &b, b.merge_tau);
    assert_true(b.nparts <= a.nparts);
    acd3d_result_free(&a);
    acd3d_result_free(&b);
    acd3d_result_free(&c);
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sphere_joins_back),
        cmocka_unit_test(test_torus_groups_within_tau),
        cmocka_unit_test(test_decompose_within_tau),
        cmocka_unit_test(test_moves),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
