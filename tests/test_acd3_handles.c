/* Tests of acd3/handles (spec acd3d.md §6, decision A15): pockets shared by handle caps are cut
 * along shortest cap-to-cap arcs that form a forest (they never separate a pocket), each arc lies
 * inside its pocket and off every projected path (so re-projecting with the arcs as barriers
 * would change nothing), and a handle's wall is measured against its nearer cap: the handle's
 * depth, not the whole wall's. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd3/handles.h"
#include "acd3/measure.h"
#include "core/union_find.h"
#include "shapes.h"

#define PI 3.14159265358979323846

typedef struct fixture {
    acd_edge_graph g;
    acd3_measure ms;
    uint32_t *face_of;
} fixture;

static void measure(const acd_mesh *m, double eps, fixture *fx) {
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m->vertices, m->nvertices, m->triangles, m->ntriangles, &fx->g, &err), ACD_OK);
    assert_int_equal(acd3_measure_compute(m, &fx->g, eps, 1e-9, &fx->ms, &err), ACD_OK);
    assert_int_equal(acd3_edge_faces(m, &fx->g, &fx->face_of, &err), ACD_OK);
}

static void fixture_free(fixture *fx) {
    acd3_measure_free(&fx->ms);
    acd_edge_graph_free(&fx->g);
    free(fx->face_of);
}

static long genus_of(const acd_mesh *m, const fixture *fx) { return acd3_handles_genus(m, &fx->g, fx->face_of); }

/* faces joined across edges that are not blocked: the number of groups */
static size_t count_regions(const acd_mesh *m, const fixture *fx, const uint8_t *b0, const uint8_t *b1) {
    size_t nf = m->ntriangles, n = 0;
    uint32_t *par = malloc(nf * sizeof *par);
    assert_non_null(par);
    for (size_t f = 0; f < nf; f++) par[f] = (uint32_t)f;
    for (size_t e = 0; e < fx->g.nedges; e++) {
        uint32_t f0 = fx->face_of[2 * e], f1 = fx->face_of[2 * e + 1];
        if (f0 == UINT32_MAX || f1 == UINT32_MAX || b0[e] || (b1 && b1[e])) continue;
        acd_uf_union(par, f0, f1);
    }
    for (size_t f = 0; f < nf; f++) n += acd_uf_find(par, (uint32_t)f) == f;
    free(par);
    return n;
}

/* The arcs' invariants: each runs through its pocket's faces from a path vertex to a path
 * vertex, its inner vertices on no path and its edges no path's; the arcs of one pocket never
 * close a cycle of loops (G_h a forest); cutting along all of them separates no pocket. */
static void check_arcs(const acd_mesh *m, const fixture *fx) {
    const acd3_measure *ms = &fx->ms;
    const acd3_handle_arcs *h = &ms->handle_arcs;
    const acd_edge_graph *g = &fx->g;
    uint8_t *onpath = calloc(m->nvertices, 1);
    assert_non_null(onpath);
    for (size_t e = 0; e < g->nedges; e++)
        if (ms->edge_barrier[e]) onpath[g->edge_v[2 * e]] = onpath[g->edge_v[2 * e + 1]] = 1;
    for (size_t i = 0; i < h->narcs; i++) {
        const uint32_t *v = h->vert + h->off[i];
        size_t n = h->off[i + 1] - h->off[i];
        assert_true(n >= 2);
        assert_true(h->a[i] < h->b[i]);
        assert_true(onpath[v[0]] && onpath[v[n - 1]]);
        double len = 0;
        for (size_t k = 0; k < n; k++) {
            if (k > 0 && k + 1 < n) assert_false(onpath[v[k]]);
            if (k + 1 == n) break;
            uint32_t e = acd_edge_graph_find(g, v[k], v[k + 1]);
            assert_true(e != ACD_NO_VERTEX);
            assert_true(ms->edge_handle[e]);
            assert_false(ms->edge_barrier[e]);
            for (int s = 0; s < 2; s++) {
                uint32_t f = fx->face_of[2 * (size_t)e + s];
                if (f != UINT32_MAX) assert_int_equal(ms->face_region[f], h->region[i]);
            }
            len += g->length[e];
        }
        assert_true(fabs(len - h->length[i]) <= 1e-9 * (1 + len));
    }
    /* G_h is a forest in every pocket */
    for (size_t i = 0; i < h->narcs; i++) {
        uint32_t maxl = 0;
        for (size_t j = 0; j < h->narcs; j++)
            if (h->region[j] == h->region[i] && h->b[j] > maxl) maxl = h->b[j];
        uint32_t *par = malloc((maxl + 1) * sizeof *par);
        assert_non_null(par);
        for (uint32_t l = 0; l <= maxl; l++) par[l] = l;
        for (size_t j = 0; j < h->narcs; j++) {
            if (h->region[j] != h->region[i]) continue;
            assert_true(acd_uf_find(par, h->a[j]) != acd_uf_find(par, h->b[j]));
            acd_uf_union(par, h->a[j], h->b[j]);
        }
        free(par);
    }
    /* re-labelled with the arcs as barriers, the pockets are the same */
    assert_int_equal(count_regions(m, fx, ms->edge_barrier, ms->edge_handle), ms->nregions);
    assert_int_equal(count_regions(m, fx, ms->edge_barrier, NULL), ms->nregions);
    free(onpath);
}

/* The torus's hole is bridged by its top and bottom caps; the hole's wall is a pocket bounded by
 * both caps' loops: one arc (down the inner wall) joins them, and the wall measures r (its inner
 * equator, against the nearer cap), not 2 r (the bottom rim against the top cap). */
static void test_torus_one_arc_wall_depth(void **state) {
    (void)state;
    const double R = 1.0, r = 0.35, eps = 0.01;
    acd_mesh m;
    assert_true(mg_torus(&m, 64, 32, R, r));
    fixture fx;
    measure(&m, eps, &fx);
    const acd3_measure *ms = &fx.ms;
    print_message("torus: %zu shared pockets, %zu arcs (of %zu candidates), concavity %g\n", ms->nhandle_pockets,
                  ms->handle_arcs.narcs, ms->nhandle_candidates, ms->concavity);
    assert_int_equal(genus_of(&m, &fx), 1);
    assert_int_equal(ms->nhandle_pockets, 1);
    assert_int_equal(ms->handle_arcs.narcs, 1);
    check_arcs(&m, &fx);
    /* the arc runs down the inner wall, from the top rim to the bottom rim: about pi r long */
    const uint32_t *v = ms->handle_arcs.vert;
    size_t n = ms->handle_arcs.off[1];
    assert_true(fabs(fabs(m.vertices[3 * (size_t)v[0] + 2] - m.vertices[3 * (size_t)v[n - 1] + 2]) - 2 * r) < 0.05);
    double inner = INFINITY;
    for (size_t k = 0; k < n; k++) {
        const double *p = m.vertices + 3 * (size_t)v[k];
        if (hypot(p[0], p[1]) < inner) inner = hypot(p[0], p[1]);
    }
    assert_true(fabs(inner - (R - r)) < 0.01); /* through the hole: across the inner equator */
    assert_true(ms->handle_arcs.length[0] > 0.9 * PI * r && ms->handle_arcs.length[0] < 1.2 * PI * r);
    assert_true(ms->concavity > r - 0.02 && ms->concavity < r + eps + 0.02);
    fixture_free(&fx);
    acd_mesh_free(&m);
}

/* A mug made of voxels: body 8 x 8 x 12 with a cavity open at the top, a handle (a ring of
 * voxels) on its side, 8 thick along y like the body. The hole's wall (the handle's inside and the
 * body's wall facing it) lies between the front (y = 0) and back (y = 8) caps; measured against
 * the nearer one it is 4 deep (half the thickness; each face takes the cap of its vertex nearest
 * to one, so up to one edge more), against one cap 8. */
enum { MX = 14, MY = 8, MZ = 12 };
static void mug_voxels(unsigned char *occ) {
    memset(occ, 0, MX * MY * MZ);
    for (int z = 0; z < MZ; z++)
        for (int y = 0; y < MY; y++)
            for (int x = 0; x < MX; x++) {
                int body = x < 8 && !(x >= 2 && x < 6 && y >= 1 && y < MY - 1 && z >= 2);
                int handle = x >= 8 && x < 13 && z >= 3 && z < 9 && (x == 12 || z == 3 || z == 8);
                occ[((size_t)z * MY + y) * MX + x] = (unsigned char)(body || handle);
            }
}

static void test_mug_handle_depth(void **state) {
    (void)state;
    unsigned char occ[MX * MY * MZ];
    mug_voxels(occ);
    acd_mesh m;
    assert_true(mg_voxels(&m, occ, MX, MY, MZ));
    fixture fx;
    measure(&m, 0.05, &fx);
    const acd3_measure *ms = &fx.ms;
    check_arcs(&m, &fx);
    assert_true(ms->nhandle_pockets >= 1);
    assert_true(ms->handle_arcs.narcs >= 1);
    /* the wall of the hole: x in [8, 12], z in [4, 8], strictly between the caps */
    double wall = 0;
    size_t nwall = 0;
    for (size_t v = 0; v < m.nvertices; v++) {
        const double *p = m.vertices + 3 * v;
        if (p[0] < 8 || p[0] > 12 || p[2] < 4 || p[2] > 8 || p[1] <= 0 || p[1] >= MY) continue;
        nwall++;
        if (ms->vconc[v] > wall) wall = ms->vconc[v];
    }
    print_message("mug: %zu shared pockets, %zu arcs, hole wall depth %g (%zu vertices), concavity %g\n",
                  ms->nhandle_pockets, ms->handle_arcs.narcs, wall, nwall, ms->concavity);
    assert_true(nwall > 20);
    assert_true(wall >= 0.5 * MY - 1e-9 && wall <= 0.5 * MY + 1 + 1e-9);
    /* the cavity, 10 deep below the top cap, is an ordinary pocket */
    assert_true(fabs(ms->concavity - 10) < 1e-9);
    fixture_free(&fx);
    acd_mesh_free(&m);
}

/* A block with two crossing tunnels (genus 3): one pocket bounded by the outlines of four faces.
 * Their loops meet pairwise in the crossing (more candidate arcs than needed); Kruskal keeps
 * three arcs, a tree joining the four loops, and the pocket stays one piece. */
enum { TX = 8, TY = 8, TZ = 6 };
static void test_crossing_tunnels_forest(void **state) {
    (void)state;
    unsigned char occ[TX * TY * TZ];
    for (int z = 0; z < TZ; z++)
        for (int y = 0; y < TY; y++)
            for (int x = 0; x < TX; x++) {
                int tz = z >= 2 && z < 4;
                int hole = tz && ((y >= 3 && y < 5) || (x >= 3 && x < 5));
                occ[((size_t)z * TY + y) * TX + x] = (unsigned char)!hole;
            }
    acd_mesh m;
    assert_true(mg_voxels(&m, occ, TX, TY, TZ));
    fixture fx;
    measure(&m, 0.05, &fx);
    const acd3_measure *ms = &fx.ms;
    print_message("crossing tunnels: %zu shared pockets, %zu arcs of %zu candidates, concavity %g\n",
                  ms->nhandle_pockets, ms->handle_arcs.narcs, ms->nhandle_candidates, ms->concavity);
    assert_int_equal(genus_of(&m, &fx), 3);
    check_arcs(&m, &fx);
    assert_int_equal(ms->nhandle_pockets, 1);
    assert_int_equal(ms->handle_arcs.narcs, 3);
    assert_true(ms->nhandle_candidates > 3);
    /* every tunnel vertex is measured against its nearest mouth: at most half a tunnel deep */
    assert_true(ms->concavity <= 0.5 * TX + 1e-9);
    fixture_free(&fx);
    acd_mesh_free(&m);
}

/* A plate 4 thick with two holes through it (genus 2): the front and back caps share one pocket
 * (both faces and both holes' walls). Two cap loops take one arc; the second handle stays inside
 * the pocket (a hidden handle: arcs join loops, they do not count handles). Both walls are measured
 * against the nearer cap. */
enum { PX = 12, PY = 4, PZ = 6 };
static void test_plate_two_holes_one_arc(void **state) {
    (void)state;
    unsigned char occ[PX * PY * PZ];
    for (int z = 0; z < PZ; z++)
        for (int y = 0; y < PY; y++)
            for (int x = 0; x < PX; x++) {
                int hole = z >= 2 && z < 4 && ((x >= 2 && x < 5) || (x >= 7 && x < 10));
                occ[((size_t)z * PY + y) * PX + x] = (unsigned char)!hole;
            }
    acd_mesh m;
    assert_true(mg_voxels(&m, occ, PX, PY, PZ));
    fixture fx;
    measure(&m, 0.05, &fx);
    const acd3_measure *ms = &fx.ms;
    assert_int_equal(genus_of(&m, &fx), 2);
    check_arcs(&m, &fx);
    assert_int_equal(ms->nhandle_pockets, 1);
    assert_int_equal(ms->handle_arcs.narcs, 1);
    print_message("plate with two holes: concavity %g\n", ms->concavity);
    assert_true(ms->concavity >= 0.5 * PY - 1e-9 && ms->concavity <= 0.5 * PY + 1 + 1e-9); /* one cap: 4 */
    fixture_free(&fx);
    acd_mesh_free(&m);
}

/* A handle inside a bowl (a bar across a box's cavity, under the rim): genus 1, but the handle
 * maps to one bridge (the top cap), its pocket has one loop: a hidden handle, not cut; the cavity
 * is measured against the top cap as any pocket (5 deep). */
enum { BX = 8, BY = 8, BZ = 6 };
static void test_hidden_handle_in_a_bowl(void **state) {
    (void)state;
    unsigned char occ[BX * BY * BZ];
    for (int z = 0; z < BZ; z++)
        for (int y = 0; y < BY; y++)
            for (int x = 0; x < BX; x++) {
                int cavity = x >= 1 && x < BX - 1 && y >= 1 && y < BY - 1 && z >= 1;
                int bar = y >= 3 && y < 5 && z == 2;
                occ[((size_t)z * BY + y) * BX + x] = (unsigned char)(!cavity || bar);
            }
    acd_mesh m;
    assert_true(mg_voxels(&m, occ, BX, BY, BZ));
    fixture fx;
    measure(&m, 0.05, &fx);
    assert_int_equal(genus_of(&m, &fx), 1);
    assert_int_equal(fx.ms.nhandle_pockets, 0);
    assert_int_equal(fx.ms.handle_arcs.narcs, 0);
    assert_true(fabs(fx.ms.concavity - (BZ - 1)) < 1e-9);
    fixture_free(&fx);
    acd_mesh_free(&m);
}

/* Genus 0: no shared pocket, no arc (a sphere with a dimple has one pocket, one loop). */
static double dimple_r(double th, double ph, void *u) {
    (void)ph, (void)u;
    return th < 0.5 ? 1.0 - 0.3 * cos(th * PI) : 1.0;
}

static void test_genus_zero_has_no_arcs(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 48, 24, dimple_r, NULL));
    fixture fx;
    measure(&m, 0.02, &fx);
    assert_int_equal(genus_of(&m, &fx), 0);
    assert_int_equal(fx.ms.nhandle_pockets, 0);
    assert_int_equal(fx.ms.handle_arcs.narcs, 0);
    assert_true(fx.ms.concavity > 0.1);
    fixture_free(&fx);
    acd_mesh_free(&m);
}

/* Three closed tetrahedra sharing one apex: not a 2-manifold there (V 10, E 18, F 12, one
 * component, no boundary: Euler's formula gives genus -1). Such surfaces reach surface mode from
 * soups and CAD files (assimp's spider.obj); they have no handles, and the genus used to come
 * back as -1, read as an allocation failure ("out of memory cutting the handles"). */
static void test_nonmanifold_vertex_genus_zero(void **state) {
    (void)state;
    double V[30] = {0, 0, 0};
    uint32_t T[36];
    for (int k = 0; k < 3; k++) {
        double ox = 3.0 * k;
        double *q = V + 3 + 9 * k;
        q[0] = ox + 1, q[1] = 0, q[2] = 0.2;
        q[3] = ox + 1, q[4] = 1, q[5] = -0.3;
        q[6] = ox + 1, q[7] = -1, q[8] = -0.4;
        uint32_t a = 0, b = (uint32_t)(1 + 3 * k), c = b + 1, d = b + 2;
        uint32_t t[12] = {a, b, c, a, c, d, a, d, b, b, d, c};
        for (int i = 0; i < 12; i++) T[12 * k + i] = t[i];
    }
    acd_mesh m = {V, 10, T, 12};
    fixture fx;
    measure(&m, 0.02, &fx);
    assert_int_equal(genus_of(&m, &fx), 0);
    assert_int_equal(fx.ms.handle_arcs.narcs, 0);
    fixture_free(&fx);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_torus_one_arc_wall_depth),
        cmocka_unit_test(test_mug_handle_depth),
        cmocka_unit_test(test_crossing_tunnels_forest),
        cmocka_unit_test(test_plate_two_holes_one_arc),
        cmocka_unit_test(test_hidden_handle_in_a_bowl),
        cmocka_unit_test(test_genus_zero_has_no_arcs),
        cmocka_unit_test(test_nonmanifold_vertex_genus_zero),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
