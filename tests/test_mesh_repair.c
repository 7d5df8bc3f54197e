/* Tests of mesh repair: a cube given as a badly oriented soup with defects comes out as the
 * closed outward unit cube; holes are filled; tolerance welding; non-orientable input survives. */
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/mesh.h"
#include "core/rng.h"
#include "shapes.h"

static const double cube_v[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
static const uint32_t cube_t[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                       {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};

/* The cube as a soup (3 vertices per face) with noise of size `noise` on the copies. */
static void cube_soup(acd_mesh *m, double noise, uint64_t seed) {
    acd_rng r;
    acd_rng_seed(&r, seed);
    m->nvertices = 36;
    m->ntriangles = 12;
    m->vertices = malloc(36 * 3 * sizeof(double));
    m->triangles = malloc(12 * 3 * sizeof(uint32_t));
    assert_non_null(m->vertices);
    assert_non_null(m->triangles);
    for (int t = 0; t < 12; t++)
        for (int k = 0; k < 3; k++) {
            for (int d = 0; d < 3; d++)
                m->vertices[9 * t + 3 * k + d] = cube_v[cube_t[t][k]][d] + noise * (acd_rng_uniform(&r) - 0.5);
            m->triangles[3 * t + k] = (uint32_t)(3 * t + k);
        }
}

static void report(const acd_mesh *m, acd_mesh_report *r) {
    acd_error err;
    if (acd_mesh_validate(m, 1, r, &err) != ACD_OK) fail_msg("%s", err.message);
}

static void push_face(acd_mesh *m, uint32_t a, uint32_t b, uint32_t c) {
    m->triangles = realloc(m->triangles, (m->ntriangles + 1) * 3 * sizeof(uint32_t));
    assert_non_null(m->triangles);
    m->triangles[3 * m->ntriangles] = a;
    m->triangles[3 * m->ntriangles + 1] = b;
    m->triangles[3 * m->ntriangles + 2] = c;
    m->ntriangles++;
}

static void test_soup_to_closed_cube(void **state) {
    (void)state;
    acd_mesh m;
    cube_soup(&m, 0, 1);
    /* flip some faces, add a duplicate (reversed), a zero-area face and a face repeating a vertex */
    for (int t = 0; t < 12; t += 3) {
        uint32_t x = m.triangles[3 * t + 1];
        m.triangles[3 * t + 1] = m.triangles[3 * t + 2];
        m.triangles[3 * t + 2] = x;
    }
    push_face(&m, m.triangles[5], m.triangles[4], m.triangles[3]);
    push_face(&m, 0, 0, 1);
    push_face(&m, 0, 1, 1);
    acd_mesh_report r;
    report(&m, &r);
    assert_int_equal(r.vertices, 36);
    assert_false(r.closed);
    acd_mesh_report_free(&r);

    acd_repair_options o = acd_repair_default_options();
    acd_repair_stats st;
    acd_error err;
    assert_int_equal(acd_mesh_repair(&m, &o, &st, &err), ACD_OK);
    assert_int_equal(st.vertices_merged, 28);
    assert_int_equal(st.degenerate_dropped, 2);
    assert_int_equal(st.duplicates_dropped, 1);
    assert_true(st.faces_flipped > 0);
    report(&m, &r);
    assert_int_equal(r.vertices, 8);
    assert_int_equal(r.faces, 12);
    assert_true(r.closed && r.oriented);
    assert_int_equal(r.genus, 0);
    assert_true(fabs(r.volume - 1) < 1e-15);
    assert_int_equal(r.degenerate_faces, 0);
    assert_int_equal(r.duplicate_faces, 0);
    assert_int_equal(r.self_intersections, 0);
    acd_mesh_report_free(&r);
    acd_mesh_free(&m);
}

static void test_inside_out_is_reversed(void **state) {
    (void)state;
    acd_mesh m;
    cube_soup(&m, 0, 2);
    for (int t = 0; t < 12; t++) {
        uint32_t x = m.triangles[3 * t + 1];
        m.triangles[3 * t + 1] = m.triangles[3 * t + 2];
        m.triangles[3 * t + 2] = x;
    }
    acd_repair_options o = acd_repair_default_options();
    acd_repair_stats st;
    acd_error err;
    assert_int_equal(acd_mesh_repair(&m, &o, &st, &err), ACD_OK);
    assert_int_equal(st.faces_flipped, 12);
    acd_mesh_report r;
    report(&m, &r);
    assert_true(r.volume > 0.999999 && r.oriented);
    acd_mesh_report_free(&r);
    acd_mesh_free(&m);
}

/* A cube of side 3 with the unit cube (shifted by 1) as a cavity, given as a soup with each of its
 * shells in the orientation `outer_in` / `inner_in` (1: inward). Repair must give the cavity model
 * whatever the shells' input orientations: the outer shell outward, the inner one inward (volume
 * 27 - 1 = 26), where orienting every closed part outward made it a solid inside a solid (28). */
static void cavity_soup(acd_mesh *m, int outer_in, int inner_in) {
    acd_mesh a, b;
    cube_soup(&a, 0, 5);
    cube_soup(&b, 0, 6);
    m->nvertices = 72;
    m->ntriangles = 24;
    m->vertices = malloc(72 * 3 * sizeof(double));
    m->triangles = malloc(24 * 3 * sizeof(uint32_t));
    assert_non_null(m->vertices);
    assert_non_null(m->triangles);
    for (int i = 0; i < 36 * 3; i++) {
        m->vertices[i] = 3 * a.vertices[i];
        m->vertices[36 * 3 + i] = 1 + b.vertices[i];
    }
    for (int t = 0; t < 24; t++) {
        int in = t < 12 ? outer_in : inner_in;
        m->triangles[3 * t] = (uint32_t)(3 * t);
        m->triangles[3 * t + 1] = (uint32_t)(3 * t + (in ? 2 : 1));
        m->triangles[3 * t + 2] = (uint32_t)(3 * t + (in ? 1 : 2));
    }
    acd_mesh_free(&a);
    acd_mesh_free(&b);
}

static void test_cavity_stays_inward(void **state) {
    (void)state;
    for (int outer_in = 0; outer_in < 2; outer_in++)
        for (int inner_in = 0; inner_in < 2; inner_in++) {
            acd_mesh m;
            cavity_soup(&m, outer_in, inner_in);
            acd_repair_options o = acd_repair_default_options();
            acd_repair_stats st;
            acd_error err;
            assert_int_equal(acd_mesh_repair(&m, &o, &st, &err), ACD_OK);
            assert_int_equal(st.vertices_merged, 56);
            assert_int_equal(st.cavities, 1);
            assert_int_equal(st.faces_flipped, 12 * (size_t)outer_in + 12 * (size_t)!inner_in);
            acd_mesh_report r;
            report(&m, &r);
            assert_true(r.closed && r.oriented);
            assert_int_equal(r.components, 2);
            assert_true(fabs(r.volume - 26) < 1e-12);
            acd_mesh_report_free(&r);
            acd_mesh_free(&m);
        }
}

/* Two unit cubes side by side (not nested) and a cube of side 3 around a cube that holds a
 * smaller cube (nesting depth 2: a solid inside the cavity): outward, inward, outward. */
static void test_nesting_parity(void **state) {
    (void)state;
    acd_mesh m;
    cavity_soup(&m, 1, 1);
    acd_mesh c;
    cube_soup(&c, 0, 7);
    size_t nv = m.nvertices;
    m.vertices = realloc(m.vertices, (nv + 36) * 3 * sizeof(double));
    assert_non_null(m.vertices);
    for (int i = 0; i < 36 * 3; i++) m.vertices[nv * 3 + i] = 1.25 + 0.5 * c.vertices[i];
    m.nvertices = nv + 36;
    for (int t = 0; t < 12; t++) push_face(&m, (uint32_t)(nv + 3 * t), (uint32_t)(nv + 3 * t + 2), (uint32_t)(nv + 3 * t + 1));
    nv = m.nvertices; /* a separate unit cube beside the others, inward */
    m.vertices = realloc(m.vertices, (nv + 36) * 3 * sizeof(double));
    assert_non_null(m.vertices);
    for (int i = 0; i < 36 * 3; i++) m.vertices[nv * 3 + i] = c.vertices[i] + (i % 3 == 0 ? 5 : 0);
    m.nvertices = nv + 36;
    for (int t = 0; t < 12; t++) push_face(&m, (uint32_t)(nv + 3 * t), (uint32_t)(nv + 3 * t + 2), (uint32_t)(nv + 3 * t + 1));
    acd_mesh_free(&c);
    acd_repair_options o = acd_repair_default_options();
    acd_repair_stats st;
    acd_error err;
    assert_int_equal(acd_mesh_repair(&m, &o, &st, &err), ACD_OK);
    assert_int_equal(st.cavities, 1);
    acd_mesh_report r;
    report(&m, &r);
    assert_int_equal(r.components, 4);
    assert_int_equal(r.inward_components, 1);
    assert_true(fabs(r.volume - (27 - 1 + 0.125 + 1)) < 1e-12);
    acd_mesh_report_free(&r);
    acd_mesh_free(&m);
}

static void test_fill_holes(void **state) {
    (void)state;
    acd_mesh m;
    cube_soup(&m, 0, 3);
    /* remove the top (faces 2, 3) and one side (faces 4, 5) */
    memmove(m.triangles + 6, m.triangles + 18, 6 * 3 * sizeof(uint32_t));
    memmove(m.triangles + 24, m.triangles + 30, 2 * 3 * sizeof(uint32_t));
    m.ntriangles = 8;
    acd_mesh copy;
    acd_error err;
    assert_int_equal(acd_mesh_copy(&copy, &m, &err), ACD_OK);
    acd_repair_options o = acd_repair_default_options();
    acd_repair_stats st;
    /* the hole has 6 edges: a limit of 5 leaves it open */
    o.fill_holes_max_edges = 5;
    assert_int_equal(acd_mesh_repair(&m, &o, &st, &err), ACD_OK);
    assert_int_equal(st.holes_filled, 0);
    acd_mesh_report r;
    report(&m, &r);
    assert_int_equal(r.boundary_edges, 6);
    acd_mesh_report_free(&r);
    o.fill_holes_max_edges = 6;
    assert_int_equal(acd_mesh_repair(&copy, &o, &st, &err), ACD_OK);
    assert_int_equal(st.holes_filled, 1);
    assert_int_equal(st.hole_faces_added, 4);
    report(&copy, &r);
    assert_true(r.closed && r.oriented);
    assert_int_equal(r.faces, 12);
    /* a fan over a non-planar loop: the volume is not 1, but positive (outward) */
    assert_true(r.volume > 0);
    acd_mesh_report_free(&r);
    acd_mesh_free(&m);
    acd_mesh_free(&copy);
}

static void test_tolerance_weld(void **state) {
    (void)state;
    acd_mesh m;
    cube_soup(&m, 1e-9, 4);
    acd_error err;
    size_t merged;
    acd_mesh c;
    assert_int_equal(acd_mesh_copy(&c, &m, &err), ACD_OK);
    assert_int_equal(acd_mesh_weld(&c, 0, &merged, &err), ACD_OK);
    assert_int_equal(merged, 0); /* exact: noisy copies all differ */
    acd_mesh_free(&c);
    assert_int_equal(acd_mesh_weld(&m, 1e-8, &merged, &err), ACD_OK);
    assert_int_equal(merged, 28);
    assert_int_equal(m.nvertices, 8);
    acd_mesh_report r;
    report(&m, &r);
    assert_true(r.closed);
    acd_mesh_report_free(&r);
    assert_int_equal(acd_mesh_weld(&m, -1, &merged, &err), ACD_ERR_INVALID_ARGUMENT);
    acd_mesh_free(&m);
}

static void test_nonorientable_survives(void **state) {
    (void)state;
    /* Moebius strip */
    int n = 12;
    acd_mesh m = {malloc((size_t)(2 * n) * 3 * sizeof(double)), (size_t)(2 * n),
                  malloc((size_t)(2 * n) * 3 * sizeof(uint32_t)), (size_t)(2 * n)};
    assert_non_null(m.vertices);
    assert_non_null(m.triangles);
    for (int i = 0; i < n; i++) {
        double u = 6.283185307179586 * i / n;
        for (int s = 0; s < 2; s++) {
            double w = s ? 0.3 : -0.3;
            m.vertices[3 * (2 * i + s)] = (1 + w * cos(u / 2)) * cos(u);
            m.vertices[3 * (2 * i + s) + 1] = (1 + w * cos(u / 2)) * sin(u);
            m.vertices[3 * (2 * i + s) + 2] = w * sin(u / 2);
        }
    }
    for (int i = 0; i < n; i++) {
        uint32_t a = (uint32_t)(2 * i), c = a + 1, a2 = (uint32_t)(2 * ((i + 1) % n)), c2 = a2 + 1;
        if (i == n - 1) {
            uint32_t x = a2;
            a2 = c2;
            c2 = x;
        }
        uint32_t t[6] = {a, a2, c2, a, c2, c};
        memcpy(m.triangles + 6 * i, t, sizeof t);
    }
    acd_repair_options o = acd_repair_default_options();
    o.fill_holes_max_edges = 100;
    acd_repair_stats st;
    acd_error err;
    assert_int_equal(acd_mesh_repair(&m, &o, &st, &err), ACD_OK);
    assert_int_equal(st.nonorientable_parts, 1);
    acd_mesh_free(&m);
}

/* An open cylinder (n segments, radius 1, height 1, no caps) as an indexed mesh. */
static void open_cylinder(acd_mesh *m, int n) {
    m->nvertices = (size_t)(2 * n);
    m->ntriangles = (size_t)(2 * n);
    m->vertices = malloc(m->nvertices * 3 * sizeof(double));
    m->triangles = malloc(m->ntriangles * 3 * sizeof(uint32_t));
    assert_non_null(m->vertices);
    assert_non_null(m->triangles);
    for (int i = 0; i < n; i++) {
        double u = 6.283185307179586 * i / n;
        for (int s = 0; s < 2; s++) {
            m->vertices[3 * (2 * i + s)] = cos(u);
            m->vertices[3 * (2 * i + s) + 1] = sin(u);
            m->vertices[3 * (2 * i + s) + 2] = s;
        }
    }
    for (int i = 0; i < n; i++) {
        uint32_t a = (uint32_t)(2 * i), b = (uint32_t)(2 * ((i + 1) % n));
        uint32_t t[6] = {a, b, b + 1, a, b + 1, a + 1};
        memcpy(m->triangles + 6 * i, t, sizeof t);
    }
}

/* Both caps of a cylinder: a short rim (24 edges) is triangulated over its own vertices, a
 * long one (200 edges) gets a fan around a new centre vertex; the result is closed, oriented
 * outward, edge-manifold, with the volume of the prism over the regular polygon exactly. */
static void test_fill_caps_short_and_long(void **state) {
    (void)state;
    for (int n = 24; n <= 200; n += 176) {
        acd_mesh m;
        open_cylinder(&m, n);
        acd_repair_options o = acd_repair_default_options();
        o.fill_holes_max_edges = SIZE_MAX;
        acd_repair_stats st;
        acd_error err;
        assert_int_equal(acd_mesh_repair(&m, &o, &st, &err), ACD_OK);
        assert_int_equal(st.holes_filled, 2);
        assert_int_equal(st.hole_vertices_added, n > 96 ? 2 : 0);
        assert_int_equal(st.hole_faces_added, n > 96 ? 2 * (size_t)n : 2 * (size_t)(n - 2));
        acd_mesh_report r;
        report(&m, &r);
        assert_true(r.closed && r.oriented);
        assert_int_equal(r.nonmanifold_edges, 0);
        assert_int_equal(r.nonmanifold_vertices, 0);
        assert_int_equal(r.self_intersections, 0);
        double area = 0.5 * n * sin(6.283185307179586 / n);
        assert_true(fabs(r.volume - area) < 1e-12);
        acd_mesh_report_free(&r);
        acd_mesh_free(&m);
    }
}

/* Two square holes in the top of a box that touch at one vertex: the boundary walk passes twice
 * through that vertex and must be split into two simple loops (a single loop through the pinch
 * would give non-manifold edges). Top face grid 2x2 with cells (0,0) and (1,1) removed. */
static void test_fill_pinched_holes(void **state) {
    (void)state;
    /* vertices: the 3x3 top grid at z = 1 (index 3*j + i), the bottom corners at z = 0 */
    double v[13][3];
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++) {
            v[3 * j + i][0] = i;
            v[3 * j + i][1] = j;
            v[3 * j + i][2] = 1;
        }
    const double bc[4][2] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
    for (int k = 0; k < 4; k++) {
        v[9 + k][0] = bc[k][0];
        v[9 + k][1] = bc[k][1];
        v[9 + k][2] = 0;
    }
    /* outward faces: top cells (1,0) and (0,1) only; sides through the grid's border vertices;
     * bottom as two triangles */
    const uint32_t t[][3] = {
        {1, 2, 5}, {1, 5, 4},                          /* top cell (1,0) */
        {3, 4, 7}, {3, 7, 6},                          /* top cell (0,1) */
        {9, 10, 1}, {10, 2, 1}, {9, 1, 0},             /* side y = 0: bottom 9-10, top 0-1-2 */
        {10, 11, 5}, {10, 5, 2}, {11, 8, 5},           /* side x = 2: bottom 10-11, top 2-5-8 */
        {11, 12, 7}, {11, 7, 8}, {12, 6, 7},           /* side y = 2: bottom 11-12, top 8-7-6 */
        {12, 9, 3}, {12, 3, 6}, {9, 0, 3},             /* side x = 0: bottom 12-9, top 6-3-0 */
        {9, 12, 11}, {9, 11, 10},                      /* bottom */
    };
    size_t nt = sizeof t / sizeof t[0];
    acd_mesh m = {malloc(sizeof v), 13, malloc(sizeof t), nt};
    assert_non_null(m.vertices);
    assert_non_null(m.triangles);
    memcpy(m.vertices, v, sizeof v);
    memcpy(m.triangles, t, sizeof t);
    acd_mesh_report r;
    report(&m, &r);
    assert_int_equal(r.boundary_edges, 8); /* the two squares' rims, meeting at vertex 4 */
    assert_int_equal(r.nonmanifold_edges, 0);
    acd_mesh_report_free(&r);
    acd_repair_options o = acd_repair_default_options();
    o.fill_holes_max_edges = SIZE_MAX;
    acd_repair_stats st;
    acd_error err;
    assert_int_equal(acd_mesh_repair(&m, &o, &st, &err), ACD_OK);
    assert_int_equal(st.holes_filled, 2);
    assert_int_equal(st.hole_faces_added, 4);
    report(&m, &r);
    assert_true(r.closed && r.oriented);
    assert_int_equal(r.nonmanifold_edges, 0);
    assert_true(fabs(r.volume - 4) < 1e-12);
    acd_mesh_report_free(&r);
    acd_mesh_free(&m);
}

/* Two unit cubes (cube_v, cube_t) with shared vertices where their positions coincide: the second
 * moved by (dx, dy, dz). */
static void two_cubes(acd_mesh *m, double dx, double dy, double dz) {
    double v[16][3];
    uint32_t idx[16], nv = 0;
    for (int c = 0; c < 2; c++)
        for (int i = 0; i < 8; i++) {
            double p[3] = {cube_v[i][0] + c * dx, cube_v[i][1] + c * dy, cube_v[i][2] + c * dz};
            uint32_t k = 0;
            while (k < nv && memcmp(v[k], p, sizeof p)) k++;
            if (k == nv) memcpy(v[nv++], p, sizeof p);
            idx[8 * c + i] = k;
        }
    m->nvertices = nv;
    m->ntriangles = 24;
    m->vertices = malloc(nv * 3 * sizeof(double));
    m->triangles = malloc(24 * 3 * sizeof(uint32_t));
    assert_non_null(m->vertices);
    assert_non_null(m->triangles);
    memcpy(m->vertices, v, nv * 3 * sizeof(double));
    for (int c = 0; c < 2; c++)
        for (int t = 0; t < 12; t++)
            for (int k = 0; k < 3; k++) m->triangles[3 * (12 * c + t) + k] = idx[8 * c + cube_t[t][k]];
}

/* Bodies touching along an edge or at a point (split_nonmanifold): the edge's four faces are paired
 * into the two cubes' wedges and its two vertices copied, so the mesh becomes two closed, manifold
 * shells of volume 2 sharing positions (solid mode then decomposes it; before, "edge used in the
 * same direction by two triangles"); a pinch vertex between two closed cubes is copied too; with the
 * option off nothing changes. */
static void test_split_nonmanifold(void **state) {
    (void)state;
    acd_mesh_report r;
    acd_repair_stats st;
    acd_error err;
    acd_repair_options o = acd_repair_default_options();
    for (int off = 0; off < 2; off++) {
        acd_mesh m;
        two_cubes(&m, 1, 1, 0); /* along the edge x = y = 1 */
        assert_int_equal(m.nvertices, 14);
        report(&m, &r);
        assert_int_equal(r.nonmanifold_edges, 1);
        acd_mesh_report_free(&r);
        o.split_nonmanifold = !off;
        assert_int_equal(acd_mesh_repair(&m, &o, &st, &err), ACD_OK);
        report(&m, &r);
        if (!off) {
            assert_int_equal(st.nonmanifold_edges_split, 1);
            assert_int_equal(st.vertices_split, 2);
            assert_int_equal(m.nvertices, 16);
            assert_int_equal(r.nonmanifold_edges, 0);
            assert_int_equal(r.nonmanifold_vertices, 0);
            assert_int_equal(r.components, 2);
            assert_true(r.closed && r.oriented);
            assert_true(fabs(r.volume - 2) < 1e-12);
        } else {
            assert_int_equal(st.vertices_split, 0);
            assert_int_equal(m.nvertices, 14);
            assert_int_equal(r.nonmanifold_edges, 1);
        }
        acd_mesh_report_free(&r);
        acd_mesh_free(&m);
    }
    /* at a point: the corner (1, 1, 1) */
    {
        acd_mesh m;
        two_cubes(&m, 1, 1, 1);
        assert_int_equal(m.nvertices, 15);
        o.split_nonmanifold = 1;
        assert_int_equal(acd_mesh_repair(&m, &o, &st, &err), ACD_OK);
        assert_int_equal(st.nonmanifold_edges_split, 0);
        assert_int_equal(st.vertices_split, 1);
        report(&m, &r);
        assert_int_equal(r.nonmanifold_vertices, 0);
        assert_true(r.closed && r.oriented);
        assert_true(fabs(r.volume - 2) < 1e-12);
        acd_mesh_report_free(&r);
        acd_mesh_free(&m);
    }
}

/* A real scan-like mesh with 171 holes of up to hundreds of edges: closing them all gives a
 * closed, edge-manifold, self-intersection-free mesh of the elephant's genus (3). */
static void test_fill_real_holes(void **state) {
    (void)state;
    char path[4096];
    snprintf(path, sizeof path, "%s/elephant-with-holes.off", ACD_MESH_DATA);
    acd_mesh m;
    acd_error err;
    if (acd_mesh_read(path, &m, &err) != ACD_OK) TU_SKIP("%s not found (run scripts/fetch-data.sh)", path);
    acd_repair_options o = acd_repair_default_options();
    o.fill_holes_max_edges = SIZE_MAX;
    acd_repair_stats st;
    assert_int_equal(acd_mesh_repair(&m, &o, &st, &err), ACD_OK);
    assert_true(st.holes_filled > 100);
    acd_mesh_report r;
    report(&m, &r);
    assert_true(r.closed && r.oriented);
    assert_int_equal(r.nonmanifold_edges, 0);
    assert_int_equal(r.duplicate_faces, 0);
    assert_int_equal(r.self_intersections, 0);
    assert_int_equal(r.genus, 3);
    assert_true(r.volume > 0);
    acd_mesh_report_free(&r);
    acd_mesh_free(&m);
}

/* The stages of the progress calls (static strings of the library). */
typedef struct stage_log {
    const char *stage[256];
    size_t n;
} stage_log;

static int log_stage(void *user, double fraction, const char *stage) {
    stage_log *l = user;
    assert_true(fraction == -1.0);
    if (l->n < 256) l->stage[l->n] = stage;
    l->n++;
    return 0;
}

static size_t stage_calls(const stage_log *l, const char *stage) {
    size_t c = 0;
    for (size_t i = 0; i < l->n && i < 256; i++) c += !strcmp(l->stage[i], stage);
    return c;
}

static void copy_mesh(acd_mesh *dst, const acd_mesh *src) {
    acd_error err;
    assert_int_equal(acd_mesh_copy(dst, src, &err), ACD_OK);
}

/* Progress and cancellation of the repair (issue 4 item 7; 0.7-0.8 CPU-s without a poll at 832k
 * faces before, in acd_segment's preparation and acd 3d's checks): on a bumpy sphere of 71,600 faces
 * (more than ACD_REPAIR_POLL_ITEMS) with a third of its faces reversed, 18 holes and 10 duplicate
 * faces, every step of the full repair calls the callback, the passes of orient more than once each
 * (so within the step); a callback that never stops leaves the result as without one, bit for bit;
 * one that stops at call N, for every N, gets ACD_ERR_CANCELLED with no call after it and a mesh
 * whose indices are in range (the ASan build checks nothing leaks). */
static void test_progress_and_cancel(void **state) {
    (void)state;
    acd_mesh in;
    assert_true(mg_radial(&in, 200, 180, mg_bumpy_r, NULL));
    size_t nt = 0;
    for (size_t t = 0; t < in.ntriangles; t++) {
        if (t % 4000 == 1000) continue; /* a hole */
        uint32_t *f = in.triangles + 3 * t;
        uint32_t a = f[0], b = f[1], c = f[2];
        if (t % 3 == 0) b = f[2], c = f[1];
        in.triangles[3 * nt] = a, in.triangles[3 * nt + 1] = b, in.triangles[3 * nt + 2] = c;
        nt++;
    }
    in.ntriangles = nt;
    for (uint32_t t = 0; t < 10; t++) push_face(&in, in.triangles[3 * t], in.triangles[3 * t + 1], in.triangles[3 * t + 2]);
    print_message("%zu faces\n", in.ntriangles);
    assert_true(in.ntriangles > ACD_REPAIR_POLL_ITEMS);
    acd_repair_options o = acd_repair_default_options();
    o.fill_holes_max_edges = SIZE_MAX;
    acd_repair_stats st0, st1;
    acd_error err;
    acd_mesh ref, m;
    copy_mesh(&ref, &in);
    assert_int_equal(acd_mesh_repair(&ref, &o, &st0, &err), ACD_OK);
    assert_int_equal(st0.holes_filled, 18);
    assert_int_equal(st0.duplicates_dropped, 10);
    assert_true(st0.faces_flipped > 0);
    /* never stopped: every step told, the same mesh */
    static stage_log log;
    memset(&log, 0, sizeof log);
    o.progress = log_stage;
    o.progress_user = &log;
    copy_mesh(&m, &in);
    assert_int_equal(acd_mesh_repair(&m, &o, &st1, &err), ACD_OK);
    assert_int_equal(m.nvertices, ref.nvertices);
    assert_int_equal(m.ntriangles, ref.ntriangles);
    assert_memory_equal(m.vertices, ref.vertices, 3 * m.nvertices * sizeof *m.vertices);
    assert_memory_equal(m.triangles, ref.triangles, 3 * m.ntriangles * sizeof *m.triangles);
    assert_memory_equal(&st1, &st0, sizeof st0);
    acd_mesh_free(&m);
    const char *steps[] = {"repair: welding", "repair: dropping degenerate and duplicate faces", "repair: orienting",
                           "repair: splitting non-manifold edges", "repair: filling holes",
                           "repair: dropping unused vertices"};
    for (size_t k = 0; k < sizeof steps / sizeof *steps; k++) {
        print_message("%s: %zu calls\n", steps[k], stage_calls(&log, steps[k]));
        assert_true(stage_calls(&log, steps[k]) >= 1);
    }
    print_message("%zu calls\n", log.n);
    assert_true(log.n < 256);
    /* two orient passes, each: the step, its half-edges' two passes, its search (faces 0 and 65536) */
    assert_true(stage_calls(&log, "repair: orienting") >= 2 * 5);
    assert_true(stage_calls(&log, "repair: dropping degenerate and duplicate faces") >= 3);
    assert_true(stage_calls(&log, "repair: splitting non-manifold edges") >= 4);
    assert_true(stage_calls(&log, "repair: filling holes") >= 4);
    /* stopped at every call in turn */
    for (int stop = 1; stop <= (int)log.n; stop++) {
        tu_counter c = {0, stop};
        o.progress = tu_count_calls;
        o.progress_user = &c;
        copy_mesh(&m, &in);
        assert_int_equal(acd_mesh_repair(&m, &o, &st1, &err), ACD_ERR_CANCELLED);
        assert_int_equal(c.calls, stop);
        assert_non_null(strstr(err.message, "cancelled"));
        assert_non_null(strstr(err.message, log.stage[stop - 1]));
        for (size_t i = 0; i < 3 * m.ntriangles; i++) assert_true(m.triangles[i] < m.nvertices);
        acd_mesh_free(&m);
    }
    acd_mesh_free(&ref);
    acd_mesh_free(&in);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_soup_to_closed_cube),
        cmocka_unit_test(test_inside_out_is_reversed),
        cmocka_unit_test(test_cavity_stays_inward),
        cmocka_unit_test(test_nesting_parity),
        cmocka_unit_test(test_fill_holes),
        cmocka_unit_test(test_fill_caps_short_and_long),
        cmocka_unit_test(test_fill_pinched_holes),
        cmocka_unit_test(test_fill_real_holes),
        cmocka_unit_test(test_tolerance_weld),
        cmocka_unit_test(test_nonorientable_survives),
        cmocka_unit_test(test_split_nonmanifold),
        cmocka_unit_test(test_progress_and_cancel),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
