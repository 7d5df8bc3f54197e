/* Cages (acd/cage.h; CoRiSe §7.2) and the exact union of convex polytopes under them
 * (geom3/polyunion). Asserted:
 *  - two overlapping boxes (sharing the planes z = 0 and z = 1, facing the same way): union volume
 *    3.5 up to the quantization (1e-6 relative), closed, oriented, manifold, no degenerate face,
 *    no self-intersection (exact test), area 2 * 3.5 + ... = the union's;
 *  - two boxes glued face to face: the glued face disappears (volume 2, area 10, 0 interior faces);
 *  - one box inside another: the cage is the outer box;
 *  - random convex hulls: closed and oriented, volume within 4 standard errors of a Monte Carlo
 *    estimate of the union (exact point-in-hull tests), bitwise deterministic;
 *  - enclosure: every vertex of a segmented mesh strictly inside the cage (exact ray winding
 *    numbers), the cage closed and oriented, its volume at least that of the exact union of the
 *    parts' hulls (which is at most their sum), every expanded simplified hull within its vertex
 *    budget plus quantization splits;
 *  - bad parameters are refused. */
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/cage.h"
#include "acd/hull.h"
#include "acd/mesh.h"
#include "acd/segment.h"
#include "core/rng.h"
#include "geom3/polyunion.h"

static void box_mesh(acd_mesh *m, const double lo[3], const double hi[3]) {
    static const uint32_t T[36] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                   1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
    m->nvertices = 8;
    m->ntriangles = 12;
    m->vertices = malloc(24 * sizeof(double));
    m->triangles = malloc(36 * sizeof(uint32_t));
    assert_non_null(m->vertices);
    assert_non_null(m->triangles);
    for (int v = 0; v < 8; v++) {
        int bx = (v == 1 || v == 2 || v == 5 || v == 6), by = (v == 2 || v == 3 || v == 6 || v == 7), bz = v >= 4;
        m->vertices[3 * v] = bx ? hi[0] : lo[0];
        m->vertices[3 * v + 1] = by ? hi[1] : lo[1];
        m->vertices[3 * v + 2] = bz ? hi[2] : lo[2];
    }
    memcpy(m->triangles, T, sizeof T);
}

/* Two meshes as one (for the enclosure check of the boxes' own vertices). */
static void concat(acd_mesh *out, const acd_mesh *a, const acd_mesh *b) {
    out->nvertices = a->nvertices + b->nvertices;
    out->ntriangles = a->ntriangles + b->ntriangles;
    out->vertices = malloc(3 * out->nvertices * sizeof(double));
    out->triangles = malloc(3 * out->ntriangles * sizeof(uint32_t));
    assert_non_null(out->vertices);
    assert_non_null(out->triangles);
    memcpy(out->vertices, a->vertices, 3 * a->nvertices * sizeof(double));
    memcpy(out->vertices + 3 * a->nvertices, b->vertices, 3 * b->nvertices * sizeof(double));
    memcpy(out->triangles, a->triangles, 3 * a->ntriangles * sizeof(uint32_t));
    for (size_t t = 0; t < 3 * b->ntriangles; t++) out->triangles[3 * a->ntriangles + t] = b->triangles[t] + (uint32_t)a->nvertices;
}

/* The cage's report: closed, oriented, manifold, no degenerate face, no self-intersection. */
static acd_mesh_report check_closed(const acd_mesh *cage, int manifold) {
    acd_mesh_report r;
    acd_error err;
    assert_int_equal(acd_mesh_validate(cage, 1, &r, &err), ACD_OK);
    assert_true(r.closed || !manifold);
    assert_int_equal(r.boundary_edges, 0);
    if (manifold) {
        assert_int_equal(r.nonmanifold_edges, 0);
        assert_int_equal(r.nonmanifold_vertices, 0);
    }
    assert_true(r.oriented);
    assert_int_equal(r.degenerate_faces, 0);
    assert_int_equal(r.duplicate_faces, 0);
    assert_int_equal(r.inward_components, 0);
    assert_int_equal(r.self_intersections, 0);
    return r;
}

static acd_cage_params exact_params(void) {
    acd_cage_params p = acd_cage_default_params();
    p.offset = 0;
    p.max_vertices = 0;
    return p;
}

static void test_two_overlapping_boxes(void **state) {
    (void)state;
    acd_mesh a, b, both;
    box_mesh(&a, (double[]){0, 0, 0}, (double[]){2, 1, 1});
    box_mesh(&b, (double[]){1, 0.5, 0}, (double[]){3, 1.5, 1});
    concat(&both, &a, &b);
    acd_mesh hulls[2] = {a, b};
    acd_cage_params p = exact_params();
    acd_cage_result r;
    acd_error err;
    assert_int_equal(acd_cage_build(&both, hulls, 2, &p, &r, &err), ACD_OK);
    print_message("two boxes: %zu vertices, %zu triangles, volume %.9f\n", r.cage.nvertices, r.cage.ntriangles, r.volume);
    /* union: 2 + 2 - overlap [1,2]x[0.5,1]x[0,1] = 3.5; the outward quantization adds < 1e-6 */
    assert_true(r.volume >= 3.5 && r.volume < 3.5 * (1 + 1e-6));
    acd_mesh_report rep = check_closed(&r.cage, 1);
    assert_int_equal(rep.components, 1);
    assert_int_equal(rep.genus, 0);
    /* area of the union: top and bottom 2 x 3.5, sides: the outline's perimeter (9) x 1 */
    assert_true(fabs(rep.area - 16.0) < 1e-5);
    /* the boxes' corners are on the cage (offset 0): none outside */
    assert_int_equal(r.outside_vertices, 0);
    assert_int_equal(r.checked_vertices, 16);
    /* with an offset every corner is strictly inside, and the volume grows */
    acd_cage_result r2;
    p.offset = 0.05;
    assert_int_equal(acd_cage_build(&both, hulls, 2, &p, &r2, &err), ACD_OK);
    assert_int_equal(r2.outside_vertices, 0);
    assert_int_equal(r2.surface_vertices, 0);
    assert_true(r2.volume > r.volume);
    acd_mesh_report rep2 = check_closed(&r2.cage, 1);
    acd_mesh_report_free(&rep2);
    acd_mesh_report_free(&rep);
    acd_cage_result_free(&r);
    acd_cage_result_free(&r2);
    acd_mesh_free(&a);
    acd_mesh_free(&b);
    acd_mesh_free(&both);
}

static void test_glued_and_nested_boxes(void **state) {
    (void)state;
    acd_mesh a, b, c, both;
    box_mesh(&a, (double[]){0, 0, 0}, (double[]){1, 1, 1});
    box_mesh(&b, (double[]){1, 0, 0}, (double[]){2, 1, 1});
    box_mesh(&c, (double[]){0.25, 0.25, 0.25}, (double[]){0.75, 0.5, 0.75});
    concat(&both, &a, &b);
    acd_mesh hulls[3] = {a, b, c};
    acd_cage_params p = exact_params();
    acd_cage_result r;
    acd_error err;
    assert_int_equal(acd_cage_build(&both, hulls, 3, &p, &r, &err), ACD_OK);
    acd_mesh_report rep = check_closed(&r.cage, 1);
    /* the glued face x = 1 and the nested box leave no face: a 2 x 1 x 1 box */
    assert_true(fabs(r.volume - 2.0) < 2e-6);
    assert_true(fabs(rep.area - 10.0) < 1e-5);
    for (size_t v = 0; v < r.cage.nvertices; v++) {
        const double *x = r.cage.vertices + 3 * v;
        int on_box = fabs(x[0]) < 1e-6 || fabs(x[0] - 2) < 1e-6 || fabs(x[1]) < 1e-6 || fabs(x[1] - 1) < 1e-6 ||
                     fabs(x[2]) < 1e-6 || fabs(x[2] - 1) < 1e-6;
        assert_true(on_box);
    }
    acd_mesh_report_free(&rep);
    acd_cage_result_free(&r);
    acd_mesh_free(&a);
    acd_mesh_free(&b);
    acd_mesh_free(&c);
    acd_mesh_free(&both);
}

/* In hull h (closed, by its planes, up to rounding of the planes). */
static int in_hull(const acd_hull *h, const double *p) { return acd_hull_plane_distance(h, p) <= 0; }

static void test_random_hulls_volume_and_determinism(void **state) {
    (void)state;
    acd_rng rng;
    acd_rng_seed(&rng, 20240611);
    enum { NH = 6, NP = 40 };
    acd_hull hulls[NH];
    for (int h = 0; h < NH; h++) {
        double pts[3 * NP], c[3];
        for (int k = 0; k < 3; k++) c[k] = acd_rng_uniform(&rng);
        for (int i = 0; i < NP; i++)
            for (int k = 0; k < 3; k++) pts[3 * i + k] = c[k] + 0.6 * (acd_rng_uniform(&rng) - 0.5);
        acd_error err;
        assert_int_equal(acd_hull_compute(pts, NP, &hulls[h], &err), ACD_OK);
        assert_int_equal(hulls[h].dim, 3);
    }
    acd_polyunion_polytope pp[NH];
    for (int h = 0; h < NH; h++)
        pp[h] = (acd_polyunion_polytope){hulls[h].planes, hulls[h].ntriangles, hulls[h].vertices, hulls[h].nvertices};
    acd_mesh u1, u2;
    acd_polyunion_stats s1, s2;
    acd_error err;
    assert_int_equal(acd_polyunion(pp, NH, 0, &u1, &s1, &err), ACD_OK);
    assert_int_equal(acd_polyunion(pp, NH, 0, &u2, &s2, &err), ACD_OK);
    assert_int_equal(u1.nvertices, u2.nvertices);
    assert_int_equal(u1.ntriangles, u2.ntriangles);
    assert_memory_equal(u1.vertices, u2.vertices, 3 * u1.nvertices * sizeof(double));
    assert_memory_equal(u1.triangles, u2.triangles, 3 * u1.ntriangles * sizeof(uint32_t));
    acd_mesh_report rep = check_closed(&u1, 0);
    /* Monte Carlo volume of the union over the hulls' box */
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int h = 0; h < NH; h++)
        for (size_t v = 0; v < hulls[h].nvertices; v++)
            for (int k = 0; k < 3; k++) {
                lo[k] = fmin(lo[k], hulls[h].vertices[3 * v + k]);
                hi[k] = fmax(hi[k], hulls[h].vertices[3 * v + k]);
            }
    const int NS = 200000;
    int hits = 0;
    for (int i = 0; i < NS; i++) {
        double p[3];
        for (int k = 0; k < 3; k++) p[k] = lo[k] + (hi[k] - lo[k]) * acd_rng_uniform(&rng);
        for (int h = 0; h < NH; h++)
            if (in_hull(&hulls[h], p)) {
                hits++;
                break;
            }
    }
    double boxv = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]), f = (double)hits / NS;
    double mc = f * boxv, se = boxv * sqrt(f * (1 - f) / NS);
    print_message("random hulls: %zu fragments, %zu inserted, %zu triangles; volume %.6f, Monte Carlo %.6f +- %.6f\n",
                  s1.fragments, s1.inserted, u1.ntriangles, rep.volume, mc, se);
    assert_true(fabs(rep.volume - mc) < 4 * se);
    double sum = 0;
    for (int h = 0; h < NH; h++) sum += hulls[h].volume;
    assert_true(rep.volume < sum); /* they overlap */
    acd_mesh_report_free(&rep);
    acd_mesh_free(&u1);
    acd_mesh_free(&u2);
    for (int h = 0; h < NH; h++) acd_hull_free(&hulls[h]);
}

static void test_segmented_mesh_enclosed(void **state) {
    (void)state;
    char path[1024];
    if (!tu_mesh_data(path, sizeof path, "elephant.off")) TU_SKIP("data/meshes/elephant.off missing (scripts/fetch-data.sh)");
    acd_mesh m;
    acd_error err;
    assert_int_equal(acd_mesh_read(path, &m, &err), ACD_OK);
    acd_segment_params sp = acd_segment_default_params();
    acd_segment_result seg;
    assert_int_equal(acd_segment(&m, &sp, &seg, &err), ACD_OK);
    /* the exact union of the parts' own hulls (no offset, no simplification): every cage holds it,
       so its volume is a lower bound of theirs; the union itself holds every mesh vertex (on its
       surface or inside: offset 0) */
    acd_cage_params ep = exact_params();
    acd_cage_result u;
    assert_int_equal(acd_cage_from_segment(&m, &seg, &ep, &u, &err), ACD_OK);
    assert_int_equal(u.outside_vertices, 0);
    assert_true(u.volume > 0);
    double hsum = 0;
    for (size_t k = 0; k < seg.nparts; k++) hsum += seg.parts[k].hull_volume;
    assert_true(u.volume <= hsum * (1 + 1e-6)); /* a union is at most the sum */
    size_t budgets[2] = {32, 12};
    for (int t = 0; t < 2; t++) {
        acd_cage_params cp = acd_cage_default_params();
        cp.max_vertices = budgets[t];
        acd_cage_result r;
        assert_int_equal(acd_cage_from_segment(&m, &seg, &cp, &r, &err), ACD_OK);
        print_message("elephant cage (N = %zu): %zu parts -> %zu hulls, %zu chosen corners, %zu corners, %zu vertices, "
                      "%zu triangles, volume / mesh %.3f, %.3f s\n",
                      budgets[t], seg.nparts, r.hulls, r.chosen_corners, r.corners, r.cage.nvertices, r.cage.ntriangles,
                      r.volume / seg.mesh_volume, r.seconds);
        assert_int_equal(r.hulls, seg.nparts);
        assert_int_equal(r.checked_vertices, m.nvertices);
        assert_int_equal(r.outside_vertices, 0);
        assert_int_equal(r.surface_vertices, 0);
        assert_true(r.chosen_corners <= r.hulls * budgets[t]);
        assert_true(r.corners >= r.chosen_corners);
        assert_true(r.volume > seg.mesh_volume);
        assert_true(r.volume >= u.volume); /* the cage holds the union of the hulls */
        acd_mesh_report rep;
        assert_int_equal(acd_mesh_validate(&r.cage, 0, &rep, &err), ACD_OK);
        assert_int_equal(rep.boundary_edges, 0);
        assert_true(rep.oriented);
        assert_int_equal(rep.degenerate_faces, 0);
        assert_true(fabs(rep.volume - r.volume) < 1e-9 * fabs(r.volume));
        acd_mesh_report_free(&rep);
        acd_cage_result_free(&r);
    }
    print_message("elephant: union of the part hulls %.6f, sum of their volumes %.6f, mesh %.6f\n", u.volume, hsum,
                  seg.mesh_volume);
    acd_cage_result_free(&u);
    acd_segment_result_free(&seg);
    acd_mesh_free(&m);
}

static void test_bad_params(void **state) {
    (void)state;
    acd_mesh a;
    box_mesh(&a, (double[]){0, 0, 0}, (double[]){1, 1, 1});
    acd_cage_result r;
    acd_error err;
    acd_cage_params p = acd_cage_default_params();
    p.offset = -1;
    assert_int_equal(acd_cage_build(&a, &a, 1, &p, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    p = acd_cage_default_params();
    p.max_vertices = 3;
    assert_int_equal(acd_cage_build(&a, &a, 1, &p, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    p = acd_cage_default_params();
    p.cookie = 0;
    assert_int_equal(acd_cage_build(&a, &a, 1, &p, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    p = acd_cage_default_params();
    p.offset = 0;
    acd_mesh flat = a;
    flat.nvertices = 4; /* the bottom face only: flat, and offset 0 */
    assert_int_equal(acd_cage_build(&a, &flat, 1, &p, &r, &err), ACD_ERR_DEGENERATE);
    acd_mesh_free(&a);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_two_overlapping_boxes),
        cmocka_unit_test(test_glued_and_nested_boxes),
        cmocka_unit_test(test_random_hulls_volume_and_determinism),
        cmocka_unit_test(test_segmented_mesh_enclosed),
        cmocka_unit_test(test_bad_params),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
