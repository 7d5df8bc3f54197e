/* Tests of geom3/plane_cut: random closed meshes (convex hulls of random points, tori, voxel solids
 * with coplanar faces, cubes with cavities) cut by random planes and by planes through vertices;
 * every piece closed and consistently oriented, volumes adding up to 1e-9 relative, caps of equal
 * area on both sides, known section areas; the same results (to the bit) whether the mesh's edge
 * map comes with its twins (acd_edge_map_closed), without them, or not at all. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "core/rng.h"
#include "geom3/edge_map.h"
#include "geom3/plane_cut.h"
#include "geom3/volume.h"

static double norm3s(const double *v) {
    double m = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
    if (!(m > 0)) return 0;
    double a = v[0] / m, b = v[1] / m, c = v[2] / m;
    return m * sqrt(a * a + b * b + c * c);
}

typedef struct stats {
    size_t cuts, pieces, split, forced;
} stats;

/* Cuts m by pl and checks: pieces closed (every half-edge once, opposite present), each piece
 * on its side of the plane, volumes add up, caps of both sides with the same area. */
static void check_cut(const acd_mesh *m, const acd_cut_plane *pl, stats *S, size_t expect_pieces) {
    acd_cut_result r;
    acd_error err;
    acd_status st = acd_plane_cut(m, pl, &r, &err);
    if (st != ACD_OK) print_message("cut failed: %s\n", err.message);
    assert_int_equal(st, ACD_OK);
    double v0 = acd_geom3_signed_volume(m), vs = 0, absv = 0;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (size_t v = 0; v < m->nvertices; v++)
        for (int k = 0; k < 3; k++) {
            if (v == 0 || m->vertices[3 * v + k] < lo[k]) lo[k] = m->vertices[3 * v + k];
            if (v == 0 || m->vertices[3 * v + k] > hi[k]) hi[k] = m->vertices[3 * v + k];
        }
    double diag[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}, ext = norm3s(diag);
    double cap_area[2] = {0, 0};
    int sides_seen[2] = {0, 0};
    for (size_t p = 0; p < r.npieces; p++) {
        const acd_cut_piece *pc = &r.pieces[p];
        assert_true(pc->side == 1 || pc->side == -1);
        sides_seen[pc->side > 0]++;
        assert_true(pc->mesh.ntriangles >= 4);
        acd_edge_map em;
        assert_int_equal(acd_edge_map_build(pc->mesh.triangles, pc->mesh.ntriangles, NULL, &em, &err), ACD_OK);
        st = acd_edge_map_check_closed(&em, pc->mesh.triangles, pc->mesh.ntriangles, &err);
        if (st != ACD_OK) print_message("piece %zu not closed: %s\n", p, err.message);
        assert_int_equal(st, ACD_OK);
        acd_edge_map_free(&em);
        double v = acd_geom3_signed_volume(&pc->mesh);
        vs += v;
        absv += fabs(v);
        /* every input vertex of the piece is on its side or on the plane */
        for (size_t i = 0; i < pc->mesh.nvertices; i++)
            if (pc->source[i] != ACD_CUT_NEW_VERTEX)
                assert_true(acd_cut_plane_side(pl, pc->mesh.vertices + 3 * i) * pc->side >= 0);
        for (size_t t = 0; t < pc->mesh.ntriangles; t++) {
            if (!pc->is_cap[t]) continue;
            const uint32_t *q = pc->mesh.triangles + 3 * t;
            const double *a = pc->mesh.vertices + 3 * q[0], *b = pc->mesh.vertices + 3 * q[1], *c = pc->mesh.vertices + 3 * q[2];
            double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
            double nn = norm3s(n);
            cap_area[pc->side > 0] += 0.5 * nn;
            /* cap faces point away from the piece: against the normal on the + side */
            double d = n[0] * pl->normal[0] + n[1] * pl->normal[1] + n[2] * pl->normal[2];
            /* (slivers next to vertices, below the weld tolerance, may tilt either way) */
            if (nn < 1e-12 * ext * ext) continue;
            if (r.nforced) continue; /* forced triangulation steps: the cap's embedding is not guaranteed */
            if (d * pc->side > 1e-9 * nn) print_message("cap triangle %zu of piece %zu inverted: area %g\n", t, p, 0.5 * nn);
            assert_true(d * pc->side <= 1e-9 * nn);
        }
    }
    if (fabs(vs - v0) > 1e-9 * fabs(v0)) print_message("volume %.17g vs %.17g\n", vs, v0);
    assert_true(fabs(vs - v0) <= 1e-9 * fabs(v0));
    assert_true(fabs(cap_area[0] - cap_area[1]) <= 1e-12 * cap_area[0]);
    assert_true(fabs(cap_area[0] - r.section_area) <= 1e-9 * cap_area[0]);
    if (expect_pieces) assert_int_equal(r.npieces, expect_pieces);
    S->cuts++;
    S->forced += r.nforced;
    S->pieces += r.npieces;
    if (sides_seen[0] && sides_seen[1]) S->split++;
    (void)absv;
    acd_cut_result_free(&r);
}

static void hull_mesh(acd_rng *r, size_t n, acd_mesh *m) {
    double *p = malloc(3 * n * sizeof *p);
    assert_non_null(p);
    for (size_t i = 0; i < 3 * n; i++) p[i] = 2 * acd_rng_uniform(r) - 1;
    acd_hull h;
    assert_int_equal(acd_hull_compute(p, n, &h, NULL), ACD_OK);
    m->vertices = h.vertices;
    m->nvertices = h.nvertices;
    m->triangles = h.triangles;
    m->ntriangles = h.ntriangles;
    h.vertices = NULL;
    h.triangles = NULL;
    acd_hull_free(&h);
    free(p);
}

static void torus_mesh(int nu, int nv, double R, double rr, acd_mesh *m) {
    m->nvertices = (size_t)nu * (size_t)nv;
    m->ntriangles = 2 * m->nvertices;
    m->vertices = malloc(3 * m->nvertices * sizeof(double));
    m->triangles = malloc(3 * m->ntriangles * sizeof(uint32_t));
    assert_non_null(m->vertices);
    assert_non_null(m->triangles);
    const double pi = 3.14159265358979323846;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            double u = 2 * pi * i / nu, v = 2 * pi * j / nv;
            double *p = m->vertices + 3 * (size_t)(i * nv + j);
            p[0] = (R + rr * cos(v)) * cos(u);
            p[1] = (R + rr * cos(v)) * sin(u);
            p[2] = rr * sin(v);
        }
    size_t t = 0;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            uint32_t a = (uint32_t)(i * nv + j), b = (uint32_t)(((i + 1) % nu) * nv + j);
            uint32_t c = (uint32_t)(((i + 1) % nu) * nv + (j + 1) % nv), d = (uint32_t)(i * nv + (j + 1) % nv);
            uint32_t *q = m->triangles + 3 * t;
            q[0] = a, q[1] = b, q[2] = c, q[3] = a, q[4] = c, q[5] = d;
            t += 2;
        }
    if (acd_geom3_signed_volume(m) < 0) /* make it outward */
        for (size_t k = 0; k < m->ntriangles; k++) {
            uint32_t x = m->triangles[3 * k + 1];
            m->triangles[3 * k + 1] = m->triangles[3 * k + 2];
            m->triangles[3 * k + 2] = x;
        }
}

/* Boundary of a set of unit voxels in an N^3 grid (vertices at every grid point); returns 0 if the
 * result is not a closed manifold (voxels meeting only along an edge). */
static int voxel_mesh(const uint8_t *vox, int N, acd_mesh *m) {
    int G = N + 1;
    m->nvertices = (size_t)G * G * G;
    m->vertices = malloc(3 * m->nvertices * sizeof(double));
    m->triangles = malloc((size_t)N * N * N * 12 * 3 * sizeof(uint32_t));
    assert_non_null(m->vertices);
    assert_non_null(m->triangles);
    for (int x = 0; x < G; x++)
        for (int y = 0; y < G; y++)
            for (int z = 0; z < G; z++) {
                double *p = m->vertices + 3 * (size_t)((x * G + y) * G + z);
                p[0] = x, p[1] = y, p[2] = z;
            }
#define VOX(x, y, z) ((x) >= 0 && (y) >= 0 && (z) >= 0 && (x) < N && (y) < N && (z) < N && vox[((x) * N + (y)) * N + (z)])
#define VID(x, y, z) ((uint32_t)(((x) * G + (y)) * G + (z)))
    size_t t = 0;
    for (int x = 0; x < N; x++)
        for (int y = 0; y < N; y++)
            for (int z = 0; z < N; z++) {
                if (!VOX(x, y, z)) continue;
                for (int ax = 0; ax < 3; ax++)
                    for (int dir = -1; dir <= 1; dir += 2) {
                        int d[3] = {0, 0, 0};
                        d[ax] = dir;
                        if (VOX(x + d[0], y + d[1], z + d[2])) continue;
                        /* face quad at the dir side, counterclockwise seen from outside */
                        int e1 = (ax + 1) % 3, e2 = (ax + 2) % 3;
                        int base[3] = {x, y, z};
                        if (dir > 0) base[ax] += 1;
                        int c0[3], c1[3], c2[3], c3[3];
                        memcpy(c0, base, sizeof c0);
                        memcpy(c1, base, sizeof c1);
                        memcpy(c2, base, sizeof c2);
                        memcpy(c3, base, sizeof c3);
                        c1[e1]++;
                        c2[e1]++, c2[e2]++;
                        c3[e2]++;
                        uint32_t q[4] = {VID(c0[0], c0[1], c0[2]), VID(c1[0], c1[1], c1[2]), VID(c2[0], c2[1], c2[2]),
                                         VID(c3[0], c3[1], c3[2])};
                        if (dir < 0) { /* reverse */
                            uint32_t s = q[1];
                            q[1] = q[3];
                            q[3] = s;
                        }
                        uint32_t *o = m->triangles + 3 * t;
                        o[0] = q[0], o[1] = q[1], o[2] = q[2], o[3] = q[0], o[4] = q[2], o[5] = q[3];
                        t += 2;
                    }
            }
#undef VOX
#undef VID
    m->ntriangles = t;
    acd_edge_map em;
    assert_int_equal(acd_edge_map_build(m->triangles, t, NULL, &em, NULL), ACD_OK);
    int ok = acd_edge_map_check_closed(&em, m->triangles, t, NULL) == ACD_OK;
    acd_edge_map_free(&em);
    return ok;
}

/* Fills voxels until no two voxels meet along an edge only (which would make a non-manifold edge). */
static void fix_edge_contacts(uint8_t *vox, int N) {
#define AT(x, y, z) vox[((x) * N + (y)) * N + (z)]
    for (int changed = 1; changed;) {
        changed = 0;
        for (int x = 0; x < N; x++)
            for (int y = 0; y < N; y++)
                for (int z = 0; z < N; z++)
                    for (int ax = 0; ax < 3; ax++) { /* the 2x2 square in the plane normal to ax */
                        int p[3] = {x, y, z}, e1 = (ax + 1) % 3, e2 = (ax + 2) % 3;
                        if (p[e1] + 1 >= N || p[e2] + 1 >= N) continue;
                        int q[4][3];
                        for (int k = 0; k < 4; k++) {
                            memcpy(q[k], p, sizeof p);
                            q[k][e1] += k & 1;
                            q[k][e2] += k >> 1;
                        }
                        int a = AT(q[0][0], q[0][1], q[0][2]), b = AT(q[1][0], q[1][1], q[1][2]);
                        int c = AT(q[2][0], q[2][1], q[2][2]), d = AT(q[3][0], q[3][1], q[3][2]);
                        if ((a && d && !b && !c) || (b && c && !a && !d)) {
                            int k = a ? 1 : 0;
                            AT(q[k][0], q[k][1], q[k][2]) = 1;
                            changed = 1;
                        }
                    }
    }
#undef AT
}

/* A random solid of the VOXEL_SOLID_N^3 voxel grid (each voxel with probability fill, then edge
 * contacts filled: fix_edge_contacts) into m; 0 (nothing to free) when it has no faces. */
#define VOXEL_SOLID_N 5
static int random_voxel_solid(acd_rng *r, double fill, acd_mesh *m) {
    const int N = VOXEL_SOLID_N;
    uint8_t vox[VOXEL_SOLID_N * VOXEL_SOLID_N * VOXEL_SOLID_N];
    for (int i = 0; i < N * N * N; i++) vox[i] = acd_rng_uniform(r) < fill;
    fix_edge_contacts(vox, N);
    if (!voxel_mesh(vox, N, m) || m->ntriangles == 0) {
        acd_mesh_free(m);
        return 0;
    }
    return 1;
}

static void random_plane(acd_rng *r, acd_cut_plane *pl, double spread) {
    double p[3], n[3];
    for (int k = 0; k < 3; k++) {
        p[k] = spread * (2 * acd_rng_uniform(r) - 1);
        n[k] = 2 * acd_rng_uniform(r) - 1;
    }
    assert_int_equal(acd_cut_plane_from_normal(p, n, 1, pl, NULL), ACD_OK);
}

static void plane_through_vertices(acd_rng *r, const acd_mesh *m, acd_cut_plane *pl) {
    for (;;) {
        const double *a = m->vertices + 3 * acd_rng_below(r, m->nvertices);
        const double *b = m->vertices + 3 * acd_rng_below(r, m->nvertices);
        const double *c = m->vertices + 3 * acd_rng_below(r, m->nvertices);
        if (acd_cut_plane_from_points(a, b, c, pl, NULL) == ACD_OK) return;
    }
}

static void test_convex_hulls(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 51);
    stats S = {0};
    for (int trial = 0; trial < 60; trial++) {
        acd_mesh m;
        hull_mesh(&r, 8 + (size_t)acd_rng_below(&r, 200), &m);
        acd_cut_plane pl;
        if (trial % 2)
            plane_through_vertices(&r, &m, &pl);
        else
            random_plane(&r, &pl, 0.5);
        check_cut(&m, &pl, &S, 0);
        acd_mesh_free(&m);
    }
    assert_true(S.split > 30); /* most planes really cut */
    /* a convex solid cut into at most one piece per side */
    assert_true(S.pieces <= 2 * S.cuts);
    assert_int_equal(S.forced, 0);
}

static void test_torus(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 52);
    stats S = {0};
    acd_mesh m;
    torus_mesh(40, 24, 2, 0.7, &m);
    /* z = 0 through a ring of vertices: two pieces; section two annuli-free discs? no: an annulus */
    double o[3] = {0, 0, 0}, nz[3] = {0, 0, 1}, nx[3] = {1, 0, 0};
    acd_cut_plane pl;
    assert_int_equal(acd_cut_plane_from_normal(o, nz, 3, &pl, NULL), ACD_OK);
    check_cut(&m, &pl, &S, 2);
    /* x = 0 through vertices: two pieces (two C shapes), each section two discs */
    assert_int_equal(acd_cut_plane_from_normal(o, nx, 3, &pl, NULL), ACD_OK);
    check_cut(&m, &pl, &S, 2);
    /* x = 2: tangent-ish vertical plane through the tube: 1 piece on one side? check only properties */
    double o2[3] = {2.5, 0, 0};
    assert_int_equal(acd_cut_plane_from_normal(o2, nx, 3, &pl, NULL), ACD_OK);
    check_cut(&m, &pl, &S, 2);
    for (int trial = 0; trial < 40; trial++) {
        if (trial % 2)
            plane_through_vertices(&r, &m, &pl);
        else
            random_plane(&r, &pl, 1.5);
        check_cut(&m, &pl, &S, 0);
    }
    acd_mesh_free(&m);
}

static void test_section_of_torus_is_annulus(void **state) {
    (void)state;
    acd_mesh m;
    torus_mesh(64, 32, 2, 0.5, &m);
    double o[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
    acd_cut_plane pl;
    assert_int_equal(acd_cut_plane_from_normal(o, nz, 3, &pl, NULL), ACD_OK);
    acd_cut_result r;
    acd_error err;
    assert_int_equal(acd_plane_cut(&m, &pl, &r, &err), ACD_OK);
    assert_int_equal(r.npieces, 2);
    assert_int_equal(r.nloops, 2);   /* outer and inner circles */
    assert_int_equal(r.nregions, 1); /* one annulus: a loop with a hole */
    /* area of the annulus between the polygonal circles of radius 2.5 and 1.5 (64-gons) */
    const double pi = 3.14159265358979323846;
    double poly = 0.5 * 64 * sin(2 * pi / 64);
    assert_true(fabs(r.section_area - poly * (2.5 * 2.5 - 1.5 * 1.5)) < 1e-12);
    acd_cut_result_free(&r);
    acd_mesh_free(&m);
}

static void test_voxel_solids(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 53);
    stats S = {0};
    const int N = VOXEL_SOLID_N;
    int made = 0;
    for (int trial = 0; trial < 400 && made < 40; trial++) {
        acd_mesh m;
        if (!random_voxel_solid(&r, 0.5, &m)) continue;
        made++;
        for (int k = 0; k < 6; k++) {
            acd_cut_plane pl;
            if (k < 3) { /* axis plane through grid vertices: coplanar faces and on-plane vertices */
                double o[3] = {0, 0, 0}, n[3] = {0, 0, 0};
                o[k] = (double)acd_rng_below(&r, (uint64_t)N + 1);
                n[k] = acd_rng_uniform(&r) < 0.5 ? 1 : -1;
                assert_int_equal(acd_cut_plane_from_normal(o, n, N, &pl, NULL), ACD_OK);
            } else if (k == 3) { /* diagonal plane through grid vertices */
                double a[3] = {0, 0, 2}, b[3] = {5, 0, 3}, c[3] = {0, 5, 1};
                assert_int_equal(acd_cut_plane_from_points(a, b, c, &pl, NULL), ACD_OK);
            } else {
                plane_through_vertices(&r, &m, &pl);
            }
            check_cut(&m, &pl, &S, 0);
        }
        acd_mesh_free(&m);
    }
    print_message("voxel solids: %d, cuts %zu, pieces %zu, split %zu, forced %zu\n", made, S.cuts, S.pieces, S.split, S.forced);
    assert_int_equal(S.forced, 0);
    assert_true(made >= 20);
}

static void test_cube_with_cavity(void **state) {
    (void)state;
    /* 3x3x3 voxels minus the centre one: a cube with a cubic cavity (two shells) */
    uint8_t vox[27];
    for (int i = 0; i < 27; i++) vox[i] = i != 13;
    acd_mesh m;
    assert_true(voxel_mesh(vox, 3, &m));
    assert_true(fabs(acd_geom3_signed_volume(&m) - 26) < 1e-12);
    stats S = {0};
    /* through the cavity: two pieces, each section a square with a square hole */
    double o[3] = {1.5, 1.5, 1.5}, n[3] = {0, 0, 1};
    acd_cut_plane pl;
    assert_int_equal(acd_cut_plane_from_normal(o, n, 3, &pl, NULL), ACD_OK);
    acd_cut_result r;
    acd_error err;
    assert_int_equal(acd_plane_cut(&m, &pl, &r, &err), ACD_OK);
    assert_int_equal(r.npieces, 2);
    assert_int_equal(r.nregions, 1);
    assert_true(fabs(r.section_area - 8) < 1e-12);
    for (size_t p = 0; p < r.npieces; p++) assert_true(fabs(acd_geom3_signed_volume(&r.pieces[p].mesh) - 13) < 1e-12);
    acd_cut_result_free(&r);
    check_cut(&m, &pl, &S, 2);
    /* away from the cavity: the piece holding the cavity keeps it as one piece */
    o[2] = 0.5;
    assert_int_equal(acd_cut_plane_from_normal(o, n, 3, &pl, NULL), ACD_OK);
    assert_int_equal(acd_plane_cut(&m, &pl, &r, &err), ACD_OK);
    assert_int_equal(r.npieces, 2);
    for (size_t p = 0; p < r.npieces; p++)
        assert_true(fabs(acd_geom3_signed_volume(&r.pieces[p].mesh) - (r.pieces[p].side > 0 ? 3 * 3 * 2.5 - 1 : 4.5)) < 1e-12);
    acd_cut_result_free(&r);
    /* exactly through the cavity's floor (z = 1): coplanar faces of both shells */
    o[2] = 1;
    assert_int_equal(acd_cut_plane_from_normal(o, n, 3, &pl, NULL), ACD_OK);
    check_cut(&m, &pl, &S, 2);
    acd_mesh_free(&m);
}

static void test_no_crossing(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 54);
    acd_mesh m;
    hull_mesh(&r, 50, &m);
    stats S = {0};
    double o[3] = {0, 0, 5}, n[3] = {0, 0, 1};
    acd_cut_plane pl;
    assert_int_equal(acd_cut_plane_from_normal(o, n, 1, &pl, NULL), ACD_OK);
    check_cut(&m, &pl, &S, 1);
    acd_cut_result res;
    assert_int_equal(acd_plane_cut(&m, &pl, &res, NULL), ACD_OK);
    assert_int_equal(res.pieces[0].side, -1);
    assert_int_equal(res.pieces[0].mesh.ntriangles, m.ntriangles);
    acd_cut_result_free(&res);
    acd_mesh_free(&m);
    /* an open mesh is refused */
    double v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t t[3] = {0, 1, 2};
    acd_mesh open = {v, 3, t, 1};
    acd_error err;
    assert_int_equal(acd_plane_cut(&open, &pl, &res, &err), ACD_ERR_NON_MANIFOLD);
    assert_non_null(strstr(err.message, "triangle 0"));
}

static void test_near_degenerate_planes(void **state) {
    (void)state;
    /* planes a few ulps away from grid vertices: crossing points land next to vertices. Pieces must
     * still be closed and the volumes add up (the caps cancel whatever the triangulation does). */
    acd_rng r;
    acd_rng_seed(&r, 55);
    stats S = {0};
    uint8_t vox[64];
    for (int i = 0; i < 64; i++) vox[i] = 1;
    vox[0] = vox[21] = vox[63] = 0;
    fix_edge_contacts(vox, 4);
    acd_mesh m;
    assert_true(voxel_mesh(vox, 4, &m));
    for (int trial = 0; trial < 60; trial++) {
        double a[3], b[3], c[3];
        for (int k = 0; k < 3; k++) {
            /* grid coordinates 1..5 (4 is the voxel grid's far side): an ulp off them stays normal */
            a[k] = 1.0 + (double)acd_rng_below(&r, 5);
            b[k] = 1.0 + (double)acd_rng_below(&r, 5);
            c[k] = 1.0 + (double)acd_rng_below(&r, 5);
        }
        int steps = 1 + (int)acd_rng_below(&r, 3);
        for (int q = 0; q < steps; q++) {
            int k = (int)acd_rng_below(&r, 3);
            a[k] = nextafter(a[k], acd_rng_uniform(&r) < 0.5 ? -10.0 : 10.0);
        }
        acd_cut_plane pl;
        if (acd_cut_plane_from_points(a, b, c, &pl, NULL) != ACD_OK) continue;
        check_cut(&m, &pl, &S, 0);
    }
    print_message("near-degenerate: cuts %zu, pieces %zu, forced %zu\n", S.cuts, S.pieces, S.forced);
    assert_true(S.forced <= S.cuts / 10); /* rounding of crossing points rarely makes loops self-touch */
    assert_true(S.cuts > 40);
    acd_mesh_free(&m);
}

/* A tetrahedron over the triangle (x0, 0, z), (x0 + 1, 0, z), (x0, 1, z) with apex height h, outward,
 * appended to the vertex and triangle arrays (nv, nt updated). */
static void add_tetra(double *V, uint32_t *T, size_t *nv, size_t *nt, double x0, double z, double h) {
    double p[12] = {x0, 0, z, x0 + 1, 0, z, x0, 1, z, x0 + 0.25, 0.25, z + h};
    memcpy(V + 3 * *nv, p, sizeof p);
    uint32_t a = (uint32_t)*nv, b = a + 1, c = a + 2, d = a + 3;
    uint32_t t[12] = {a, c, b, a, b, d, b, c, d, c, a, d};
    memcpy(T + 3 * *nt, t, sizeof t);
    *nv += 4;
    *nt += 4;
}

/* Flat shells (mean thickness at most 1e-12 of the box diagonal) are dropped, a shell a little
 * thicker is a piece: a unit cube cut in two, and away from the plane a sheet (two coincident
 * triangles, volume 0), a tetrahedron half as thick as the bound and one 1.5 times as thick. */
static void test_flat_shells(void **state) {
    (void)state;
    double V[3 * 20];
    uint32_t T[3 * 30];
    size_t nv = 8, nt = 0;
    for (int i = 0; i < 8; i++) V[3 * i] = i & 1, V[3 * i + 1] = (i >> 1) & 1, V[3 * i + 2] = (i >> 2) & 1;
    acd_hull h;
    assert_int_equal(acd_hull_compute(V, 8, &h, NULL), ACD_OK);
    assert_int_equal(h.ntriangles, 12);
    assert_int_equal(h.nvertices, 8);
    memcpy(V, h.vertices, 24 * sizeof *V);
    memcpy(T, h.triangles, 36 * sizeof *T);
    nt = 12;
    acd_hull_free(&h);
    double sheet[9] = {0, 0, 3, 1, 0, 3, 0, 1, 3};
    memcpy(V + 3 * nv, sheet, sizeof sheet);
    uint32_t st[6] = {(uint32_t)nv, (uint32_t)nv + 1, (uint32_t)nv + 2, (uint32_t)nv, (uint32_t)nv + 2, (uint32_t)nv + 1};
    memcpy(T + 3 * nt, st, sizeof st);
    nv += 3, nt += 2;
    /* the box: [0, 5] x [0, 1] x [0, 3 + a little]; a tetrahedron's area (base and three sides,
     * nearly flat: twice the base's 0.5) */
    double diag = sqrt(25.0 + 1.0 + 9.0), area = 1.0, bound = 1e-12 * diag * 0.5 * area; /* on |volume| */
    add_tetra(V, T, &nv, &nt, 2, 3, 6 * 0.5 * bound); /* volume h / 6 */
    add_tetra(V, T, &nv, &nt, 4, 3, 6 * 1.5 * bound);
    acd_mesh m = {V, nv, T, nt};
    assert_true(acd_geom3_signed_volume(&m) > 0.99);
    double o[3] = {0.5, 0.5, 0.5}, n[3] = {0, 0, 1};
    acd_cut_plane pl;
    assert_int_equal(acd_cut_plane_from_normal(o, n, 1, &pl, NULL), ACD_OK);
    acd_cut_result r;
    acd_error err;
    assert_int_equal(acd_plane_cut(&m, &pl, &r, &err), ACD_OK);
    assert_int_equal(r.ndropped, 6); /* the sheet's 2 triangles, the thin tetrahedron's 4 */
    assert_int_equal(r.npieces, 3); /* the cube's halves, the thicker tetrahedron */
    size_t tetra = 0;
    for (size_t p = 0; p < r.npieces; p++)
        if (r.pieces[p].mesh.ntriangles == 4) {
            tetra++;
            double v = acd_geom3_signed_volume(&r.pieces[p].mesh);
            assert_true(v > 0 && v < 1e-11);
        }
    assert_int_equal(tetra, 1);
    acd_cut_result_free(&r);
}

/* Two cut results equal to the bit. */
static void assert_same_result(const acd_cut_result *a, const acd_cut_result *b) {
    assert_int_equal(a->npieces, b->npieces);
    assert_int_equal(a->nloops, b->nloops);
    assert_int_equal(a->nregions, b->nregions);
    assert_int_equal(a->nforced, b->nforced);
    assert_int_equal(a->ndropped, b->ndropped);
    assert_memory_equal(&a->section_area, &b->section_area, sizeof a->section_area);
    for (size_t p = 0; p < a->npieces; p++) {
        const acd_cut_piece *x = &a->pieces[p], *y = &b->pieces[p];
        assert_int_equal(x->side, y->side);
        assert_int_equal(x->closed, y->closed);
        assert_int_equal(x->mesh.nvertices, y->mesh.nvertices);
        assert_int_equal(x->mesh.ntriangles, y->mesh.ntriangles);
        assert_memory_equal(x->mesh.vertices, y->mesh.vertices, 3 * x->mesh.nvertices * sizeof(double));
        assert_memory_equal(x->mesh.triangles, y->mesh.triangles, 3 * x->mesh.ntriangles * sizeof(uint32_t));
        assert_memory_equal(x->is_cap, y->is_cap, x->mesh.ntriangles);
        assert_memory_equal(x->source, y->source, x->mesh.nvertices * sizeof(uint32_t));
    }
}

/* m cut by pl with its map and twins (acd_edge_map_closed), its map alone (built and checked) and
 * none, with and without DROP_SPECKS: the same results; a piece said closed is. Returns the pieces. */
static size_t cut_three_ways(const acd_mesh *m, const acd_cut_plane *pl) {
    acd_edge_map tw, plain;
    acd_error err;
    assert_int_equal(acd_edge_map_closed(m->triangles, m->ntriangles, &tw, &err), ACD_OK);
    assert_non_null(tw.twin);
    assert_int_equal(acd_edge_map_build(m->triangles, m->ntriangles, NULL, &plain, &err), ACD_OK);
    assert_int_equal(acd_edge_map_check_closed(&plain, m->triangles, m->ntriangles, &err), ACD_OK);
    assert_null(plain.twin);
    size_t np = 0;
    for (unsigned flags = 0; flags <= ACD_PLANE_CUT_DROP_SPECKS; flags += ACD_PLANE_CUT_DROP_SPECKS) {
        acd_cut_result r0, r1, r2;
        assert_int_equal(acd_plane_cut_map(m, NULL, pl, flags, &r0, &err), ACD_OK);
        assert_int_equal(acd_plane_cut_map(m, &tw, pl, flags, &r1, &err), ACD_OK);
        assert_int_equal(acd_plane_cut_map(m, &plain, pl, flags, &r2, &err), ACD_OK);
        assert_same_result(&r0, &r1);
        assert_same_result(&r0, &r2);
        for (size_t p = 0; p < r0.npieces; p++) {
            const acd_mesh *pm = &r0.pieces[p].mesh;
            if (r0.pieces[p].closed) assert_int_equal(acd_edge_map_closed(pm->triangles, pm->ntriangles, NULL, NULL), ACD_OK);
        }
        np += r0.npieces;
        acd_cut_result_free(&r0);
        acd_cut_result_free(&r1);
        acd_cut_result_free(&r2);
    }
    acd_edge_map_free(&tw);
    acd_edge_map_free(&plain);
    return np;
}

static void test_map_paths(void **state) {
    (void)state;
    acd_rng r;
    acd_rng_seed(&r, 57);
    size_t cuts = 0, pieces = 0;
    const int N = VOXEL_SOLID_N;
    for (int solid = 0; solid < 12; solid++) { /* voxel solids: coplanar faces, planes through vertices */
        acd_mesh m;
        if (!random_voxel_solid(&r, 0.55, &m)) continue;
        for (int k = 0; k < 8; k++) {
            acd_cut_plane pl;
            if (k < 3) {
                double o[3] = {0, 0, 0}, n[3] = {0, 0, 0};
                o[k] = (double)acd_rng_below(&r, (uint64_t)N + 1);
                n[k] = acd_rng_uniform(&r) < 0.5 ? 1 : -1;
                assert_int_equal(acd_cut_plane_from_normal(o, n, N, &pl, NULL), ACD_OK);
            } else if (k < 6) {
                plane_through_vertices(&r, &m, &pl);
            } else {
                random_plane(&r, &pl, 2.5);
                for (int q = 0; q < 3; q++) pl.a[q] += 2.5, pl.b[q] += 2.5, pl.c[q] += 2.5;
            }
            pieces += cut_three_ways(&m, &pl);
            cuts++;
        }
        acd_mesh_free(&m);
    }
    acd_mesh m;
    torus_mesh(40, 24, 2, 0.7, &m);
    for (int trial = 0; trial < 20; trial++) {
        acd_cut_plane pl;
        if (trial % 2)
            plane_through_vertices(&r, &m, &pl);
        else
            random_plane(&r, &pl, 1.5);
        pieces += cut_three_ways(&m, &pl);
        cuts++;
    }
    acd_mesh_free(&m);
    print_message("map paths: cuts %zu, pieces %zu\n", cuts, pieces);
    assert_true(cuts >= 60);
    assert_true(pieces > 2 * cuts); /* most cuts split (counted twice: with and without DROP_SPECKS) */
}

static void test_scales(void **state) {
    (void)state;
    /* the same torus cut at scales 1e-100 and 1e100 (the cut works on a copy scaled by a power of
     * two there) and 1e70 (not rescaled): same piece counts, also with DROP_SPECKS, volumes scale
     * exactly-ish. DROP_SPECKS (the budget pass's cuts) compares each shell's volume with a rounding
     * scale (sum of |a| |b| |c| / 6 per face): computed as the root of a product of squares it
     * overflowed between 1e51 and 1e90, every shell was then a speck and the cut gave no piece */
    double scales[] = {1e-100, 1, 1e100, 1e70};
    size_t npieces[4];
    double vol[4];
    for (int si = 0; si < 4; si++) {
        acd_mesh m;
        torus_mesh(24, 12, 2, 0.7, &m);
        for (size_t i = 0; i < 3 * m.nvertices; i++) m.vertices[i] = m.vertices[i] * scales[si] + 3 * scales[si];
        double o[3] = {3 * scales[si] + 0.3 * scales[si], 3 * scales[si], 3 * scales[si]}, n[3] = {1, 0.2, 0.1};
        acd_cut_plane pl;
        assert_int_equal(acd_cut_plane_from_normal(o, n, scales[si], &pl, NULL), ACD_OK);
        stats S = {0};
        check_cut(&m, &pl, &S, 0);
        acd_cut_result res;
        assert_int_equal(acd_plane_cut(&m, &pl, &res, NULL), ACD_OK);
        npieces[si] = res.npieces;
        vol[si] = acd_geom3_signed_volume(&res.pieces[0].mesh) / scales[si] / scales[si] / scales[si];
        acd_cut_result_free(&res);
        assert_int_equal(acd_plane_cut_flags(&m, &pl, ACD_PLANE_CUT_DROP_SPECKS, &res, NULL), ACD_OK);
        assert_int_equal(res.npieces, npieces[si]);
        acd_cut_result_free(&res);
        acd_mesh_free(&m);
    }
    for (int si = 0; si < 4; si++) {
        assert_int_equal(npieces[si], npieces[1]);
        assert_true(fabs(vol[si] - vol[1]) < 1e-9 * fabs(vol[1]));
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_convex_hulls),
        cmocka_unit_test(test_torus),
        cmocka_unit_test(test_section_of_torus_is_annulus),
        cmocka_unit_test(test_voxel_solids),
        cmocka_unit_test(test_cube_with_cavity),
        cmocka_unit_test(test_no_crossing),
        cmocka_unit_test(test_near_degenerate_planes),
        cmocka_unit_test(test_scales),
        cmocka_unit_test(test_map_paths),
        cmocka_unit_test(test_flat_shells),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
