/* Tests of acd3/surface_cut: one section strip's chain has two sides. An open piece of a bumpy
 * sphere (cut off by a first plane) is cut again by planes close to that first one, through a
 * vertex of the piece's jagged boundary: the cut follows the boundary and, without the joining
 * of teeth, cuts off faces between its chain and the boundary. Every such cut must give at most
 * two pieces, and the pieces must partition the faces. The level cut (acd3_surface_cut_deep) keeps
 * every vertex at or above the level with the seed. A chain cut (acd3_surface_cut_chain) separates
 * along a closed loop and only slits along an open chain or a loop around a handle. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd3/surface_cut.h"
#include "core/rng.h"
#include "geom3/dijkstra.h"
#include "geom3/plane_cut.h"
#include "shapes.h"

static double bumpy(double theta, double phi, void *user) {
    (void)user;
    return 1.0 + 0.15 * sin(5 * theta) * cos(3 * phi) + 0.05 * cos(11 * phi) * sin(7 * theta);
}

static void cut(const acd_mesh *m, const double point[3], const double normal[3], const double *near,
                acd_cut_result *out) {
    acd_edge_graph g;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m->vertices, m->nvertices, m->triangles, m->ntriangles, &g, &err), ACD_OK);
    acd_cut_plane pl;
    assert_int_equal(acd_cut_plane_from_normal(point, normal, 4.0, &pl, &err), ACD_OK);
    assert_int_equal(acd3_surface_cut(m, &g, &pl, near, out, &err), ACD_OK);
    acd_edge_graph_free(&g);
}

static void test_strip_cut_two_sides(void **state) {
    (void)state;
    acd_mesh sphere;
    assert_true(mg_radial(&sphere, 64, 40, bumpy, NULL));
    /* the first cut: a tilted plane through the origin, whole section; the larger piece */
    const double n1[3] = {0.3, 0.2, 0.933}, o[3] = {0, 0, 0.05};
    acd_cut_result first;
    cut(&sphere, o, n1, NULL, &first);
    assert_int_equal(first.npieces, 2);
    size_t big = first.pieces[0].mesh.ntriangles >= first.pieces[1].mesh.ntriangles ? 0 : 1;
    const acd_mesh *a = &first.pieces[big].mesh;
    /* its boundary vertices: on an edge of one face */
    acd_edge_graph g;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(a->vertices, a->nvertices, a->triangles, a->ntriangles, &g, &err), ACD_OK);
    unsigned *nface = calloc(g.nedges, sizeof *nface);
    uint8_t *onb = calloc(a->nvertices, 1);
    assert_non_null(nface);
    assert_non_null(onb);
    for (size_t f = 0; f < a->ntriangles; f++)
        for (int k = 0; k < 3; k++) {
            uint32_t e = acd_edge_graph_find(&g, a->triangles[3 * f + k], a->triangles[3 * f + (k + 1) % 3]);
            assert_true(e != ACD_NO_VERTEX);
            nface[e]++;
        }
    size_t nb = 0;
    for (size_t e = 0; e < g.nedges; e++)
        if (nface[e] == 1) onb[g.edge_v[2 * e]] = onb[g.edge_v[2 * e + 1]] = 1, nb++;
    assert_true(nb > 20);
    acd_rng rng;
    acd_rng_seed(&rng, 4);
    size_t tried = 0, many = 0;
    for (int trial = 0; trial < 200; trial++) {
        uint32_t v = (uint32_t)acd_rng_below(&rng, a->nvertices);
        if (!onb[v]) continue;
        double n2[3];
        for (int k = 0; k < 3; k++) n2[k] = n1[k] + 0.08 * (acd_rng_uniform(&rng) - 0.5);
        const double *p = a->vertices + 3 * (size_t)v;
        double q[3];
        for (int k = 0; k < 3; k++) q[k] = p[k] - 0.01 * acd_rng_uniform(&rng) * n1[k];
        acd_cut_result r;
        cut(a, q, n2, p, &r);
        tried++;
        size_t faces = 0;
        for (size_t i = 0; i < r.npieces; i++) {
            assert_true(r.pieces[i].mesh.ntriangles > 0);
            faces += r.pieces[i].mesh.ntriangles;
        }
        assert_int_equal(faces, a->ntriangles);
        if (r.npieces > 2) many++;
        acd_cut_result_free(&r);
    }
    assert_true(tried >= 10);
    assert_int_equal(many, 0);
    free(nface);
    free(onb);
    acd_edge_graph_free(&g);
    acd_cut_result_free(&first);
    acd_mesh_free(&sphere);
}

/* The level cut: the faces around the seed with a vertex at level >= thr, apart from the rest;
 * every vertex at level >= thr (the seed among them) is in that piece only. */
static void test_deep_cut(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 48, 24, bumpy, NULL));
    double *level = malloc(m.nvertices * sizeof *level);
    assert_non_null(level);
    uint32_t seed = 0;
    for (size_t v = 0; v < m.nvertices; v++) {
        level[v] = m.vertices[3 * v + 2];
        if (level[v] > level[seed]) seed = (uint32_t)v;
    }
    const double thr = 0.5;
    acd_edge_graph g;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &g, &err), ACD_OK);
    acd_cut_result r;
    assert_int_equal(acd3_surface_cut_deep(&m, &g, level, thr, seed, &r, &err), ACD_OK);
    assert_true(r.npieces >= 2);
    size_t faces = 0, seeds = 0;
    for (size_t i = 0; i < r.npieces; i++) {
        faces += r.pieces[i].mesh.ntriangles;
        int has_seed = 0;
        for (size_t v = 0; v < r.pieces[i].mesh.nvertices; v++) has_seed |= r.pieces[i].source[v] == seed;
        seeds += (size_t)has_seed;
        for (size_t v = 0; v < r.pieces[i].mesh.nvertices && !has_seed; v++)
            assert_true(level[r.pieces[i].source[v]] < thr); /* deep vertices only with the seed */
    }
    assert_int_equal(seeds, 1);
    assert_int_equal(faces, m.ntriangles);
    acd_cut_result_free(&r);
    acd_edge_graph_free(&g);
    free(level);
    acd_mesh_free(&m);
}

/* The vertices of m with |z| < 1e-9 (the equator of a radial sphere), by azimuth: a closed
 * chain of mesh edges (the first repeated last); returns its length. */
static size_t equator(const acd_mesh *m, const acd_edge_graph *g, uint32_t *ring) {
    size_t n = 0;
    for (size_t v = 0; v < m->nvertices; v++)
        if (fabs(m->vertices[3 * v + 2]) < 1e-9) ring[n++] = (uint32_t)v;
    for (size_t i = 1; i < n; i++) /* insertion sort by azimuth */
        for (size_t j = i; j > 0; j--) {
            const double *a = m->vertices + 3 * (size_t)ring[j - 1], *b = m->vertices + 3 * (size_t)ring[j];
            if (atan2(a[1], a[0]) <= atan2(b[1], b[0])) break;
            uint32_t t = ring[j];
            ring[j] = ring[j - 1], ring[j - 1] = t;
        }
    for (size_t i = 0; i < n; i++) assert_true(acd_edge_graph_find(g, ring[i], ring[(i + 1) % n]) != ACD_NO_VERTEX);
    ring[n] = ring[0];
    return n + 1;
}

/* A cut along a chain of mesh edges (acd3_surface_cut_chain, the global cut's cycle): a closed
 * loop (the equator) separates the sphere into its two hemispheres; half of it (an open chain)
 * only slits it (one piece, more vertices); a meridian of a torus opens it without separating. */
static void test_chain_cut(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 48, 24, bumpy, NULL));
    acd_edge_graph g;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &g, &err), ACD_OK);
    uint32_t *ring = malloc((m.nvertices + 1) * sizeof *ring);
    assert_non_null(ring);
    size_t n = equator(&m, &g, ring);
    assert_int_equal(n, 49);
    acd_cut_result r;
    assert_int_equal(acd3_surface_cut_chain(&m, &g, ring, n, &r, &err), ACD_OK);
    assert_int_equal(r.npieces, 2);
    size_t faces = 0;
    for (size_t i = 0; i < r.npieces; i++) {
        const acd_mesh *pm = &r.pieces[i].mesh;
        faces += pm->ntriangles;
        /* every face on one side of the equator, the same for the whole piece */
        int side = 0;
        for (size_t f = 0; f < pm->ntriangles; f++) {
            double z = 0;
            for (int k = 0; k < 3; k++) z += pm->vertices[3 * (size_t)pm->triangles[3 * f + k] + 2];
            int s = z > 0 ? 1 : -1;
            if (!side) side = s;
            assert_int_equal(s, side);
        }
        for (size_t v = 0; v < pm->nvertices; v++) assert_int_equal(m.vertices[3 * (size_t)r.pieces[i].source[v]], pm->vertices[3 * v]);
    }
    assert_int_equal(faces, m.ntriangles);
    acd_cut_result_free(&r);
    /* half the equator: a slit */
    assert_int_equal(acd3_surface_cut_chain(&m, &g, ring, n / 2, &r, &err), ACD_OK);
    assert_int_equal(r.npieces, 1);
    assert_int_equal(r.pieces[0].mesh.ntriangles, m.ntriangles);
    assert_true(r.pieces[0].mesh.nvertices > m.nvertices);
    acd_cut_result_free(&r);
    free(ring);
    acd_edge_graph_free(&g);
    acd_mesh_free(&m);
    /* torus: the vertices with y = 0, x > 0 (a meridian) */
    assert_true(mg_torus(&m, 32, 16, 1.0, 0.35));
    assert_int_equal(acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &g, &err), ACD_OK);
    ring = malloc((m.nvertices + 1) * sizeof *ring);
    assert_non_null(ring);
    n = 0;
    for (size_t v = 0; v < m.nvertices; v++)
        if (fabs(m.vertices[3 * v + 1]) < 1e-9 && m.vertices[3 * v] > 0) ring[n++] = (uint32_t)v;
    assert_int_equal(n, 16);
    for (size_t i = 1; i < n; i++) /* by the angle around the tube */
        for (size_t j = i; j > 0; j--) {
            const double *a = m.vertices + 3 * (size_t)ring[j - 1], *b = m.vertices + 3 * (size_t)ring[j];
            if (atan2(a[2], a[0] - 1.0) <= atan2(b[2], b[0] - 1.0)) break;
            uint32_t t = ring[j];
            ring[j] = ring[j - 1], ring[j - 1] = t;
        }
    for (size_t i = 0; i < n; i++) assert_true(acd_edge_graph_find(&g, ring[i], ring[(i + 1) % n]) != ACD_NO_VERTEX);
    ring[n++] = ring[0];
    assert_int_equal(acd3_surface_cut_chain(&m, &g, ring, n, &r, &err), ACD_OK);
    assert_int_equal(r.npieces, 1);
    assert_int_equal(r.pieces[0].mesh.nvertices, m.nvertices + 16);
    acd_cut_result_free(&r);
    free(ring);
    acd_edge_graph_free(&g);
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_strip_cut_two_sides),
        cmocka_unit_test(test_deep_cut),
        cmocka_unit_test(test_chain_cut),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
