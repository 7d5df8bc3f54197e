/* Tests of acd3/resolve's resolver without feature grouping (ACD3D_RESOLVER_NOTCH, spec §5.4,
 * decision A14): the candidate is the plane through the most reflex edge at the witness,
 * bisecting its dihedral angle, followed only by the axis planes; a decomposition with it (eps 0,
 * region cuts) conserves volume, keeps parts closed and meets tau; on an L the notch cut is the
 * plane x = y that separates the notch's two faces. */
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd3/measure.h"
#include "acd3/resolve.h"
#include "geom3/dijkstra.h"
#include "geom3/edge_map.h"
#include "shapes.h"
#include "acd3d_check.h"
#include "acd/hull.h"

/* An L of unit voxels, 6 x 4 x 1 with the corner x, y >= 2 empty (arms of lengths 6 and 4, so
 * that no principal axis of the L is along a diagonal): its reflex edge is the line x = y = 2,
 * between the faces x = 2 (normal +x) and y = 2 (normal +y). */
static void l_shape(acd_mesh *m) {
    unsigned char occ[24];
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 6; x++) occ[y * 6 + x] = !(x >= 2 && y >= 2);
    assert_true(mg_voxels(m, occ, 6, 4, 1));
}

static void test_notch_candidates(void **state) {
    (void)state;
    acd_mesh m;
    l_shape(&m);
    acd_edge_graph g;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &g, &err), ACD_OK);
    acd3_measure ms;
    assert_int_equal(acd3_measure_compute(&m, &g, 0.0, 1e-9, &ms, &err), ACD_OK);
    assert_true(ms.witness != UINT32_MAX);
    const double *w = m.vertices + 3 * (size_t)ms.witness;
    /* the deepest points of the L lie on its reflex edge */
    assert_true(fabs(w[0] - 2) < 1e-12 && fabs(w[1] - 2) < 1e-12);

    acd3_resolve_opts ro;
    memset(&ro, 0, sizeof ro);
    ro.notch = 1;
    acd3_plane_candidate c[ACD3_MAX_CANDIDATES];
    int n = acd3_cut_candidates(&m, &g, &ms, &ro, NULL, c);
    assert_true(n >= 2 && n <= 4);
    assert_string_equal(c[0].kind, "notch");
    /* a bisector of the right angle between +x and +y, through the edge */
    double s = 1 / sqrt(2.0);
    assert_true(fabs(fabs(c[0].normal[0]) - s) < 1e-12 && fabs(fabs(c[0].normal[1]) - s) < 1e-12 &&
                fabs(c[0].normal[2]) < 1e-12);
    /* the bisector of the material's 270 degrees: x = y, separating the two faces */
    assert_true(c[0].normal[0] * c[0].normal[1] < 0);
    assert_true(fabs(c[0].point[0] - 2) < 1e-12 && fabs(c[0].point[1] - 2) < 1e-12);
    for (int i = 1; i < n; i++) assert_string_equal(c[i].kind, "axis");

    /* the witness resolver proposes more kinds (valley, notch, face, centroid, axis) */
    ro.notch = 0;
    int n2 = acd3_cut_candidates(&m, &g, &ms, &ro, NULL, c);
    assert_true(n2 > n);
    int faces = 0;
    for (int i = 0; i < n2; i++) faces += !strcmp(c[i].kind, "face");
    assert_int_equal(faces, 2);

    acd3_measure_free(&ms);
    acd_edge_graph_free(&g);
    acd_mesh_free(&m);
}

static void check_parts(const acd_mesh *in, const acd3d_result *r) {
    double vin = mg_volume(in), sum = 0;
    for (size_t i = 0; i < r->nparts; i++) {
        const acd_mesh *pm = &r->parts[i].mesh;
        acd_edge_map em;
        acd_error err;
        assert_int_equal(acd_edge_map_build(pm->triangles, pm->ntriangles, NULL, &em, &err), ACD_OK);
        assert_int_equal(acd_edge_map_check_closed(&em, pm->triangles, pm->ntriangles, &err), ACD_OK);
        acd_edge_map_free(&em);
        sum += mg_volume(pm);
        assert_true(r->parts[i].concavity <= r->tau + 1e-9 * r->scale);
        assert_int_not_equal(r->nodes[r->parts[i].node].leaf_reason, ACD3D_LEAF_NO_CUT);
    }
    assert_true(fabs(sum - vin) <= 1e-9 * vin);
}

static void no_fg(acd3d_params *p) {
    p->eps_ratio = 0;
    p->resolver = ACD3D_RESOLVER_NOTCH;
    p->region_cuts = 1;
}

static void test_l_shape_notch_cut(void **state) {
    (void)state;
    acd_mesh m;
    l_shape(&m);
    acd3d_params p = acd3d_default_params();
    p.tau = 0.0;
    p.tau_absolute = 1;
    p.merge = 0;
    acd3d_result r, d;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &d, &err), ACD_OK);
    no_fg(&p);
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    check_parts(&m, &r);
    /* the root was cut by the bisector x = y through the notch edge (not an axis plane): two
     * convex parts */
    const double *pl = r.nodes[0].cut_plane, s = 1 / sqrt(2.0);
    assert_true(fabs(fabs(pl[0]) - s) < 1e-12 && fabs(fabs(pl[1]) - s) < 1e-12 && pl[0] * pl[1] < 0 &&
                fabs(pl[2]) < 1e-12 && fabs(pl[3]) < 1e-9);
    assert_int_equal(r.nparts, 2);
    assert_int_equal(d.nparts, 2);
    acd3d_result_free(&r);
    acd3d_result_free(&d);
    acd_mesh_free(&m);
}

static double waist_r(double th, double ph, void *u) {
    (void)ph;
    double k = *(double *)u, s = sin(th);
    return 1.0 - k * s * s;
}

/* A smooth part: the variant meets tau on every part, solid and surface, for 1 and 2 threads. */
static void test_waist_without_grouping(void **state) {
    (void)state;
    double k = 0.6;
    acd_mesh m;
    assert_true(mg_radial(&m, 40, 40, waist_r, &k));
    acd3d_params p = acd3d_default_params();
    p.tau = 0.03;
    no_fg(&p);
    p.threads = 1;
    acd3d_result r, r2;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_true(r.nparts >= 2);
    check_parts(&m, &r);
    p.threads = 2;
    assert_int_equal(acd3d_decompose(&m, &p, &r2, &err), ACD_OK);
    ck3_same_parts(&r, &r2);
    acd3d_result_free(&r2);
    acd3d_result_free(&r);
    p.mode = ACD3D_SURFACE;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_true(r.nparts >= 2);
    for (size_t i = 0; i < r.nparts; i++) assert_true(r.parts[i].concavity <= r.tau + 1e-9 * r.scale);
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}


/* Planes through sharp reflex edges (resolve.c edge_planes; docs/acd3d.md "Planes through reflex
 * edges"). A part is convex when its volume equals its hull's within this fraction of the input's
 * volume (both computed in floating point from the same vertices). */
#define CONVEX_VOLUME_REL 1e-9

/* data/meshes/star.off, made here: a cube of side 0.25 with a square pyramid on each face, tips at
 * +-0.5 on the axes; its 12 cube edges are reflex (53 degrees between the faces' normals), four in
 * each cube face plane. */
static void star(acd_mesh *m) {
    memset(m, 0, sizeof *m);
    m->nvertices = 14, m->ntriangles = 24;
    m->vertices = malloc(3 * 14 * sizeof(double));
    m->triangles = malloc(3 * 24 * sizeof(uint32_t));
    assert_non_null(m->vertices);
    assert_non_null(m->triangles);
    for (int i = 0; i < 8; i++)
        for (int k = 0; k < 3; k++) m->vertices[3 * i + k] = (i >> k) & 1 ? 0.125 : -0.125;
    for (int a = 0; a < 3; a++)
        for (int s = 0; s < 2; s++) {
            double *tip = m->vertices + 3 * (8 + 2 * a + s);
            tip[0] = tip[1] = tip[2] = 0;
            tip[a] = s ? 0.5 : -0.5;
        }
    size_t t = 0;
    for (int a = 0; a < 3; a++)
        for (int s = 0; s < 2; s++) {
            /* the four cube corners on the face (axis a, side s), in a cycle around it */
            int u = (a + 1) % 3, w = (a + 2) % 3, cyc[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            uint32_t c[4];
            for (int q = 0; q < 4; q++) c[q] = (uint32_t)((s << a) | (cyc[q][0] << u) | (cyc[q][1] << w));
            for (int q = 0; q < 4; q++) {
                uint32_t *tr = m->triangles + 3 * t++;
                tr[0] = (uint32_t)(8 + 2 * a + s), tr[1] = c[q], tr[2] = c[(q + 1) % 4];
                /* outward: the normal points away from the origin (the star is star-shaped) */
                const double *p0 = m->vertices + 3 * tr[0], *p1 = m->vertices + 3 * tr[1], *p2 = m->vertices + 3 * tr[2];
                double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
                double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
                if (n[0] * p0[0] + n[1] * p0[1] + n[2] * p0[2] < 0) tr[1] = c[(q + 1) % 4], tr[2] = c[q];
            }
        }
    assert_true(fabs(mg_volume(m) - (0.015625 + 6 * 0.0625 * 0.375 / 3)) < 1e-15);
}

/* At the star's witness (a cube corner, three reflex edges) the first candidates are the planes
 * through its reflex edges that hold the most of them: cube face planes (|x|, |y| or |z| = 0.125),
 * each holding four. */
static void test_star_edge_candidates(void **state) {
    (void)state;
    acd_mesh m;
    star(&m);
    acd_edge_graph g;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &g, &err), ACD_OK);
    acd3_measure ms;
    assert_int_equal(acd3_measure_compute(&m, &g, 0.0, 1e-9, &ms, &err), ACD_OK);
    assert_true(ms.witness < 8); /* a cube corner */
    acd3_resolve_opts ro;
    memset(&ro, 0, sizeof ro);
    acd3_plane_candidate c[ACD3_MAX_CANDIDATES];
    int n = acd3_cut_candidates(&m, &g, &ms, &ro, NULL, c), edges = 0;
    assert_true(n > 3);
    uint8_t axis_seen[3] = {0, 0, 0};
    for (int i = 0; i < n; i++) {
        if (strcmp(c[i].kind, "edges")) continue;
        assert_int_equal(i, edges); /* first */
        edges++;
        int a = fabs(c[i].normal[0]) == 1 ? 0 : fabs(c[i].normal[1]) == 1 ? 1 : fabs(c[i].normal[2]) == 1 ? 2 : -1;
        assert_true(a >= 0);
        assert_true(fabs(c[i].point[a]) == 0.125);
        axis_seen[a] = 1;
    }
    assert_int_equal(edges, 3);
    assert_true(axis_seen[0] && axis_seen[1] && axis_seen[2]);
    /* and with the global cut: still first */
    ro.global = 1;
    ro.gc.tau = 0.01;
    ro.gc.delta = 0.001;
    ro.gc.weight = ACD3D_WEIGHT_RATIO;
    n = acd3_cut_candidates(&m, &g, &ms, &ro, NULL, c);
    assert_true(n > 3);
    assert_string_equal(c[0].kind, "edges");
    acd3_measure_free(&ms);
    acd_edge_graph_free(&g);
    acd_mesh_free(&m);
}

/* A decomposition into exactly `want` convex parts whose volumes add up to the input's. */
static void check_exact(const acd_mesh *in, const acd3d_result *r, size_t want) {
    double vin = mg_volume(in), sum = 0;
    assert_int_equal(r->nparts, want);
    for (size_t i = 0; i < r->nparts; i++) {
        const acd_mesh *pm = &r->parts[i].mesh;
        double v = mg_volume(pm), hv;
        acd_error err;
        assert_int_equal(acd_hull_volume(pm->vertices, pm->nvertices, &hv, &err), ACD_OK);
        assert_true(fabs(hv - v) <= CONVEX_VOLUME_REL * vin);
        sum += v;
    }
    assert_true(fabs(sum - vin) <= CONVEX_VOLUME_REL * vin);
}

/* Decomposes m at tau = rel (relative) and at tau 0 (absolute), with and without the merge pass, on
 * 1 and 2 threads: `want` convex parts each time. */
static void decompose_exact(const acd_mesh *m, double rel, size_t want) {
    for (int k = 0; k < 4; k++) {
        acd3d_params p = acd3d_default_params();
        p.tau = k < 2 ? rel : 0.0;
        p.tau_absolute = k >= 2;
        p.merge = k % 2;
        p.threads = 1;
        acd3d_result r, r2;
        acd_error err;
        assert_int_equal(acd3d_decompose(m, &p, &r, &err), ACD_OK);
        check_exact(m, &r, want);
        p.threads = 2;
        assert_int_equal(acd3d_decompose(m, &p, &r2, &err), ACD_OK);
        ck3_same_parts(&r, &r2);
        acd3d_result_free(&r2);
        acd3d_result_free(&r);
    }
}

/* The star: the planes of the cube's faces cut off its pyramids; two opposite pyramids stay on the
 * cube, which is convex with them: 5 convex parts, the minimum (before the edge planes: 11 parts at
 * tau 0.05, 51 at 0.001, 11205 at tau 0 after 171 s). */
static void test_star_exact(void **state) {
    (void)state;
    acd_mesh m;
    star(&m);
    decompose_exact(&m, 0.001, 5);
    acd_mesh_free(&m);
}

/* Voxel brackets: a plus (3 x 3 x 1, the corners empty; four reflex edges, two in each of the
 * planes y = 1 and y = 2: the bar and two arms, 3 parts; before: 5) and a jack (the centre of a
 * 3 x 3 x 3 block and its six neighbours: the centre with two opposite arms and the other four
 * arms, 5 parts; before: 9 at tau 0, 6 at tau 0.01). */
static void test_brackets_exact(void **state) {
    (void)state;
    acd_mesh m;
    unsigned char plus[9], jack[27];
    for (int y = 0; y < 3; y++)
        for (int x = 0; x < 3; x++) plus[y * 3 + x] = x == 1 || y == 1;
    assert_true(mg_voxels(&m, plus, 3, 3, 1));
    decompose_exact(&m, 0.01, 3);
    acd_mesh_free(&m);
    for (int z = 0; z < 3; z++)
        for (int y = 0; y < 3; y++)
            for (int x = 0; x < 3; x++) jack[(z * 3 + y) * 3 + x] = (x == 1) + (y == 1) + (z == 1) >= 2;
    assert_true(mg_voxels(&m, jack, 3, 3, 3));
    decompose_exact(&m, 0.01, 5);
    acd_mesh_free(&m);
}

/* A smooth part's witness has no sharp reflex edge: no edge plane among its candidates, which stay
 * those of the code before them (a guard for the threshold EDGE_PLANE_MIN_TURN_DEG: a waist of 40 x
 * 40 facets turns by under 10 degrees between faces). */
static void test_smooth_no_edge_planes(void **state) {
    (void)state;
    double k = 0.6;
    acd_mesh m;
    assert_true(mg_radial(&m, 40, 40, waist_r, &k));
    acd_edge_graph g;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m.vertices, m.nvertices, m.triangles, m.ntriangles, &g, &err), ACD_OK);
    acd3_measure ms;
    assert_int_equal(acd3_measure_compute(&m, &g, 0.0, 1e-9, &ms, &err), ACD_OK);
    assert_true(ms.witness != UINT32_MAX && ms.concavity > 0.01);
    acd3_resolve_opts ro;
    memset(&ro, 0, sizeof ro);
    acd3_plane_candidate c[ACD3_MAX_CANDIDATES];
    int n = acd3_cut_candidates(&m, &g, &ms, &ro, NULL, c);
    assert_true(n > 0);
    for (int i = 0; i < n; i++) assert_string_not_equal(c[i].kind, "edges");
    acd3_measure_free(&ms);
    acd_edge_graph_free(&g);
    acd_mesh_free(&m);
}


/* A generic rotation (a unit quaternion of no symmetry), then each coordinate rounded as a file
 * would have it: digits > 0, written with that many significant decimal digits (%.6g, %.9g);
 * digits 0, stored as float32 (binary STL). */
static void rotate_round(acd_mesh *m, int digits) {
    double q[4] = {0.8, 0.3, -0.4, 0.33}, l = 0;
    for (int k = 0; k < 4; k++) l += q[k] * q[k];
    for (int k = 0; k < 4; k++) q[k] /= sqrt(l);
    double w = q[0], x = q[1], y = q[2], z = q[3];
    double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                      {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                      {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    for (size_t v = 0; v < m->nvertices; v++) {
        double *p = m->vertices + 3 * v, r[3];
        for (int i = 0; i < 3; i++) r[i] = R[i][0] * p[0] + R[i][1] * p[1] + R[i][2] * p[2];
        for (int i = 0; i < 3; i++) {
            if (digits > 0) {
                char buf[64];
                snprintf(buf, sizeof buf, "%.*g", digits, r[i]);
                p[i] = strtod(buf, NULL);
            } else {
                p[i] = (double)(float)r[i];
            }
        }
    }
}

/* The star as users have it: rotated and rounded (6 and 9 digits, float32), its cube's faces hold
 * their four reflex edges only within rounding (before: no edge plane, 10-30 parts at tau 0.01,
 * 20-133 at 0.001, docs/results/3d-edgepair.md). The edge planes still cut off the pyramids: 5
 * parts at tau 0.01 and 0.001 (relative), with and without the merge pass, each convex within
 * rounding (its hull's volume above its own by less than 1e-5 of the star's), the volumes adding
 * up. */
static void test_star_rotated_rounded(void **state) {
    (void)state;
    int digits[3] = {6, 9, 0};
    for (int d = 0; d < 3; d++) {
        acd_mesh m;
        star(&m);
        rotate_round(&m, digits[d]);
        double vin = mg_volume(&m);
        for (int k = 0; k < 4; k++) {
            acd3d_params p = acd3d_default_params();
            p.tau = k < 2 ? 0.01 : 0.001;
            p.merge = k % 2;
            acd3d_result r;
            acd_error err;
            assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
            check_parts(&m, &r);
            assert_int_equal(r.nparts, 5);
            for (size_t i = 0; i < r.nparts; i++) {
                const acd_mesh *pm = &r.parts[i].mesh;
                double hv;
                assert_int_equal(acd_hull_volume(pm->vertices, pm->nvertices, &hv, &err), ACD_OK);
                assert_true(hv - mg_volume(pm) <= 1e-5 * vin);
            }
            acd3d_result_free(&r);
        }
        acd_mesh_free(&m);
    }
}

/* Swaps the diagonal a - b of the two coplanar triangles that share it for the quad's other one. */
static void flip_edge(acd_mesh *m, uint32_t a, uint32_t b) {
    int t1 = -1, t2 = -1;
    for (size_t t = 0; t < m->ntriangles; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t u = m->triangles[3 * t + k], v = m->triangles[3 * t + (k + 1) % 3];
            if (u == a && v == b) t1 = (int)t;
            if (u == b && v == a) t2 = (int)t;
        }
    assert_true(t1 >= 0 && t2 >= 0);
    uint32_t *T1 = m->triangles + 3 * t1, *T2 = m->triangles + 3 * t2, c = 0, d = 0;
    for (int k = 0; k < 3; k++) {
        if (T1[k] != a && T1[k] != b) c = T1[k];
        if (T2[k] != a && T2[k] != b) d = T2[k];
    }
    T1[0] = a, T1[1] = d, T1[2] = c;
    T2[0] = d, T2[1] = b, T2[2] = c;
}

static uint32_t vertex_at(const acd_mesh *m, double x, double y, double z) {
    for (size_t v = 0; v < m->nvertices; v++) {
        const double *p = m->vertices + 3 * v;
        if (p[0] == x && p[1] == y && p[2] == z) return (uint32_t)v;
    }
    fail();
    return 0;
}

/* How many edge planes the witness of m gets. */
static int edge_candidates(const acd_mesh *m) {
    acd_edge_graph g;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m->vertices, m->nvertices, m->triangles, m->ntriangles, &g, &err), ACD_OK);
    acd3_measure ms;
    assert_int_equal(acd3_measure_compute(m, &g, 0.0, 1e-9, &ms, &err), ACD_OK);
    acd3_resolve_opts ro;
    memset(&ro, 0, sizeof ro);
    acd3_plane_candidate c[ACD3_MAX_CANDIDATES];
    int n = acd3_cut_candidates(m, &g, &ms, &ro, NULL, c), edges = 0;
    for (int i = 0; i < n; i++) edges += !strcmp(c[i].kind, "edges");
    acd3_measure_free(&ms);
    acd_edge_graph_free(&g);
    return edges;
}

/* The gate against planes that hold edges by chance (a scan's: mirror images on a symmetric model
 * lie in a plane within its rounding). A T of voxels (bar 3 x 1 on a stem 1 x 1, 1 thick): its two
 * inner corners are sharp reflex edges, mirror images, in the plane of the bar's underside.
 * - As made, that plane holds them with a fourth endpoint exactly in it: an edge plane.
 * - Rotated and rounded to 6 digits, only within rounding; the bar meets the stem along a loop of
 *   edges in it (the corners and the edges across the top and the bottom faces): an edge plane.
 * - With those two edges across the faces flipped to the other diagonals, no loop of edges lies in
 *   the plane (the corners are two edges that lie in one plane within rounding, and nothing else
 *   says it is one): exactly as made it is still an edge plane, rotated and rounded none. */
static void test_edge_plane_gate(void **state) {
    (void)state;
    unsigned char tee[6] = {0, 1, 0, 1, 1, 1}; /* y = 0: the stem; y = 1: the bar */
    for (int flip = 0; flip < 2; flip++)
        for (int rot = 0; rot < 2; rot++) {
            acd_mesh m;
            assert_true(mg_voxels(&m, tee, 3, 2, 1));
            if (flip) {
                flip_edge(&m, vertex_at(&m, 1, 1, 1), vertex_at(&m, 2, 1, 1));
                flip_edge(&m, vertex_at(&m, 1, 1, 0), vertex_at(&m, 2, 1, 0));
            }
            if (rot) rotate_round(&m, 6);
            int edges = edge_candidates(&m);
            if (flip && rot) assert_int_equal(edges, 0);
            else assert_true(edges >= 1);
            acd_mesh_free(&m);
        }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_notch_candidates),
        cmocka_unit_test(test_l_shape_notch_cut),
        cmocka_unit_test(test_waist_without_grouping),
        cmocka_unit_test(test_star_edge_candidates),
        cmocka_unit_test(test_star_exact),
        cmocka_unit_test(test_brackets_exact),
        cmocka_unit_test(test_smooth_no_edge_planes),
        cmocka_unit_test(test_star_rotated_rounded),
        cmocka_unit_test(test_edge_plane_gate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
