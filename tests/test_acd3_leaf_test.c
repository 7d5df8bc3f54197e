/* Tests of the hull-distance stopping test (acd3/leaf_test, acd3d_params.stop = ACD3D_STOP_HULL):
 * an accepted part really is within tau of its hull both ways (checked by brute-force sampling,
 * independently of the bounds), a part the measure over-reports is kept whole, really concave
 * parts (a deep dent, a thin bent slab whose vertices all lie near the hull boundary, a deep open
 * cap) are still refused and split, and the output is the same for any thread count. */
// ctest: TIMEOUT 600
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd/hull.h"
#include "acd3/leaf_test.h"
#include "acd3/measure.h"
#include "geom3/bvh.h"
#include "geom3/dijkstra.h"
#include "shapes.h"
#include "acd3d_check.h"

/* A closed heightfield solid over [0, L]^2 (n cells a side): flat bottom z = 0, top a gable roof
 * (ridge along y at x = L/2, `roof` lower at the eaves) with a smooth round dent of depth `dent`
 * and radius dr centred at (dx, dy). */
typedef struct hf {
    double L, top, roof, dent, dx, dy, dr;
} hf;

static double hf_z(const hf *s, double x, double y) {
    double z = s->top - s->roof * fabs(x - 0.5 * s->L) / (0.5 * s->L);
    double r2 = ((x - s->dx) * (x - s->dx) + (y - s->dy) * (y - s->dy)) / (s->dr * s->dr);
    if (r2 < 1) z -= s->dent * (1 - r2) * (1 - r2);
    return z;
}

static void heightfield(acd_mesh *m, const hf *s, int n) {
    size_t side = (size_t)n + 1, nv = 2 * side * side, nt = 4 * (size_t)n * n + 8 * (size_t)n;
    memset(m, 0, sizeof *m);
    m->vertices = malloc(3 * nv * sizeof *m->vertices);
    m->triangles = malloc(3 * nt * sizeof *m->triangles);
    assert_non_null(m->vertices);
    assert_non_null(m->triangles);
    m->nvertices = nv;
    for (size_t l = 0; l < 2; l++)
        for (size_t j = 0; j < side; j++)
            for (size_t i = 0; i < side; i++) {
                double x = s->L * (double)i / n, y = s->L * (double)j / n;
                double *v = m->vertices + 3 * (l * side * side + j * side + i);
                v[0] = x, v[1] = y, v[2] = l ? 0.0 : hf_z(s, x, y);
            }
#define ID(l, i, j) ((uint32_t)((l) * side * side + (size_t)(j) * side + (size_t)(i)))
#define TRI(a, b, c)                                          \
    do {                                                      \
        uint32_t *t_ = m->triangles + 3 * m->ntriangles++;    \
        t_[0] = (a), t_[1] = (b), t_[2] = (c);                \
    } while (0)
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            TRI(ID(0, i, j), ID(0, i + 1, j), ID(0, i + 1, j + 1));
            TRI(ID(0, i, j), ID(0, i + 1, j + 1), ID(0, i, j + 1));
            TRI(ID(1, i, j), ID(1, i + 1, j + 1), ID(1, i + 1, j));
            TRI(ID(1, i, j), ID(1, i, j + 1), ID(1, i + 1, j + 1));
        }
    for (int k = 0; k < n; k++) {
        TRI(ID(0, k, 0), ID(1, k, 0), ID(1, k + 1, 0));
        TRI(ID(0, k, 0), ID(1, k + 1, 0), ID(0, k + 1, 0));
        TRI(ID(0, k, n), ID(1, k + 1, n), ID(1, k, n));
        TRI(ID(0, k, n), ID(0, k + 1, n), ID(1, k + 1, n));
        TRI(ID(0, 0, k), ID(1, 0, k + 1), ID(1, 0, k));
        TRI(ID(0, 0, k), ID(0, 0, k + 1), ID(1, 0, k + 1));
        TRI(ID(0, n, k), ID(1, n, k), ID(1, n, k + 1));
        TRI(ID(0, n, k), ID(1, n, k + 1), ID(0, n, k + 1));
    }
#undef ID
#undef TRI
    assert_int_equal(m->ntriangles, nt);
    assert_true(mg_volume(m) > 0);
}

/* Brute force, independent of acd3/leaf_test: the largest distance from the points of a
 * barycentric grid on every triangle of `from` to the triangles of `to`. */
static double sampled_reach(const acd_mesh *from, const acd_mesh *to) {
    enum { GRID = 4 };
    double worst = 0;
    for (size_t t = 0; t < from->ntriangles; t++) {
        const double *a = from->vertices + 3 * from->triangles[3 * t], *b = from->vertices + 3 * from->triangles[3 * t + 1],
                     *c = from->vertices + 3 * from->triangles[3 * t + 2];
        for (int i = 0; i <= GRID; i++)
            for (int j = 0; i + j <= GRID; j++) {
                double u = (double)i / GRID, v = (double)j / GRID, x[3], q[3];
                for (int k = 0; k < 3; k++) x[k] = a[k] + u * (b[k] - a[k]) + v * (c[k] - a[k]);
                double best = INFINITY;
                for (size_t s = 0; s < to->ntriangles; s++) {
                    const uint32_t *tr = to->triangles + 3 * s;
                    double d2 = acd_closest_point_triangle(x, to->vertices + 3 * tr[0], to->vertices + 3 * tr[1],
                                                           to->vertices + 3 * tr[2], q);
                    if (d2 < best) best = d2;
                }
                if (sqrt(best) > worst) worst = sqrt(best);
            }
    }
    return worst;
}

/* The hull of m as a mesh (dim 3 asserted). */
static void hull_of(const acd_mesh *m, acd_hull *h, acd_mesh *hm) {
    acd_error err;
    assert_int_equal(acd_hull_compute(m->vertices, m->nvertices, h, &err), ACD_OK);
    assert_int_equal(h->dim, 3);
    memset(hm, 0, sizeof *hm);
    hm->vertices = h->vertices;
    hm->nvertices = h->nvertices;
    hm->triangles = h->triangles;
    hm->ntriangles = h->ntriangles;
}

/* The measure's concavity of m (eps = eps_ratio * tau as the driver uses it). */
static double measure_of(const acd_mesh *m, double tau) {
    acd_edge_graph g;
    acd_error err;
    assert_int_equal(acd_edge_graph_from_mesh(m->vertices, m->nvertices, m->triangles, m->ntriangles, &g, &err), ACD_OK);
    acd3_measure ms;
    assert_int_equal(acd3_measure_compute(m, &g, 0.5 * tau, 1e-9, &ms, &err), ACD_OK);
    double c = ms.concavity;
    acd3_measure_free(&ms);
    acd_edge_graph_free(&g);
    return c;
}

/* The test itself on a whole mesh: accepted or not, and the bound. */
static int leaf_ok(const acd_mesh *m, double tau, double *bound) {
    acd_hull h;
    acd_mesh hm;
    hull_of(m, &h, &hm);
    int ok = -1;
    acd_error err;
    assert_int_equal(acd3_leaf_test(m, &h, tau, UINT32_MAX, &ok, bound, &err), ACD_OK);
    acd_hull_free(&h);
    return ok;
}

/* Every part the hull test accepted is within tau of its hull both ways by sampling (and its
 * recorded concavity is the bound, <= tau); every other part meets tau under the measure. */
static size_t check_parts(const acd3d_result *r) {
    size_t hull_leaves = 0;
    for (size_t i = 0; i < r->nparts; i++) {
        const acd3d_part *pt = &r->parts[i];
        const acd3d_node *nd = &r->nodes[pt->node];
        assert_true(pt->concavity <= r->tau * (1 + 1e-9));
        if (nd->leaf_reason != ACD3D_LEAF_HULL) continue;
        hull_leaves++;
        assert_true(measure_of(&pt->mesh, r->tau) > r->tau); /* the measure alone would have split it */
        double din = sampled_reach(&pt->mesh, &pt->hull), dout = sampled_reach(&pt->hull, &pt->mesh);
        assert_true(din <= r->tau * (1 + 1e-9));
        assert_true(dout <= r->tau * (1 + 1e-9));
        assert_true(fmax(din, dout) <= pt->concavity * (1 + 1e-9) + 1e-12);
    }
    return hull_leaves;
}

static acd3d_params params(double tau, acd3d_stop stop) {
    acd3d_params p = acd3d_default_params();
    p.tau = tau;
    p.tau_absolute = 1;
    p.stop = stop;
    p.merge = 0; /* the decomposition's own leaves */
    p.threads = 1;
    return p;
}

/* Decomposes m (params above) and checks its parts (check_parts); returns how many parts,
 * *hull_leaves how many of them the hull test accepted. */
static size_t decompose_checked(const acd_mesh *m, double tau, acd3d_stop stop, int *hull_leaves) {
    acd3d_params p = params(tau, stop);
    acd3d_result r;
    acd_error err;
    assert_int_equal(acd3d_decompose(m, &p, &r, &err), ACD_OK);
    *hull_leaves = check_parts(&r);
    size_t n = r.nparts;
    acd3d_result_free(&r);
    return n;
}

/* A roof so shallow that both slopes fall into one bridge patch (its drop 0.2 <= eps = tau/2): the
 * patch plane lies at the ridge, and a dent of depth 0.95 (under tau = 1 below the roof) near the
 * eave is measured 0.95 + 0.2 * 3/5 deep. The hull test keeps the block whole; the measure splits
 * it. */
static void test_overreport_kept_whole(void **state) {
    (void)state;
    hf s = {10, 3, 0.2, 0.95, 8, 5, 1.5};
    acd_mesh m;
    heightfield(&m, &s, 20);
    double tau = 1.0, bound;
    assert_true(measure_of(&m, tau) > tau * 1.05);
    assert_int_equal(leaf_ok(&m, tau, &bound), 1);
    assert_true(bound <= tau);
    /* the independent check on the whole block */
    acd_hull h;
    acd_mesh hm;
    hull_of(&m, &h, &hm);
    assert_true(sampled_reach(&m, &hm) <= tau);
    assert_true(sampled_reach(&hm, &m) <= tau);
    acd_hull_free(&h);

    int hull_leaves;
    assert_int_equal(decompose_checked(&m, tau, ACD3D_STOP_HULL, &hull_leaves), 1);
    assert_int_equal(hull_leaves, 1); /* the one part is the hull test's leaf */
    assert_true(decompose_checked(&m, tau, ACD3D_STOP_MEASURE, &hull_leaves) >= 2);
    assert_int_equal(hull_leaves, 0);
    acd_mesh_free(&m);
}

/* The same block with a dent 1.6 deep: really concave, refused and split; the parts the hull
 * test accepts on the way are within tau. */
static void test_deep_dent_split(void **state) {
    (void)state;
    hf s = {10, 3, 0.2, 1.6, 8, 5, 1.5};
    acd_mesh m;
    heightfield(&m, &s, 20);
    double tau = 1.0, bound;
    assert_int_equal(leaf_ok(&m, tau, &bound), 0);
    assert_true(bound > tau);
    int hull_leaves;
    assert_true(decompose_checked(&m, tau, ACD3D_STOP_HULL, &hull_leaves) >= 2);
    acd_mesh_free(&m);
}

/* A thin bent slab (an L of 1 x 1 voxel bars, arms 8 long): every point of it lies within
 * sqrt(2)/2 of the boundary of its hull, but the hull's diagonal facet is far from it. The test
 * must refuse it (the direction hull -> part), and the sampled distance confirms why. */
static void test_bent_slab_refused(void **state) {
    (void)state;
    enum { N = 8 };
    unsigned char occ[N * N * 1];
    for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++) occ[y * N + x] = x == 0 || y == 0;
    acd_mesh m;
    assert_true(mg_voxels(&m, occ, N, N, 1));
    double tau = 1.0, bound;
    acd_hull h;
    acd_mesh hm;
    hull_of(&m, &h, &hm);
    assert_true(sampled_reach(&m, &hm) <= tau);    /* part -> hull: within tau */
    assert_true(sampled_reach(&hm, &m) > 3 * tau); /* hull -> part: far */
    acd_hull_free(&h);
    assert_int_equal(leaf_ok(&m, tau, &bound), 0);
    int hull_leaves;
    assert_true(decompose_checked(&m, tau, ACD3D_STOP_HULL, &hull_leaves) >= 2);
    acd_mesh_free(&m);
}

/* A 10 x 10 x 10 block with a slit 0.1 wide from its top down to its middle, running through it
 * along x, coarsely triangulated (16 vertices): every vertex lies on the boundary of the hull (the
 * cube) and the cube's boundary is within 0.05 of the block, but the slit's bottom runs through the
 * cube's centre, 5 deep. Only the bound over whole triangles (not their corners) sees it. */
static void test_slit_between_shallow_vertices(void **state) {
    (void)state;
    const double P[8][2] = {{0, 0}, {10, 0}, {10, 10}, {5.05, 10}, {5.05, 5}, {4.95, 5}, {4.95, 10}, {0, 10}};
    const uint32_t cap[6][3] = {{0, 1, 4}, {1, 2, 3}, {1, 3, 4}, {0, 4, 5}, {0, 5, 6}, {0, 6, 7}};
    acd_mesh m;
    memset(&m, 0, sizeof m);
    m.vertices = malloc(16 * 3 * sizeof *m.vertices);
    m.triangles = malloc((12 + 16) * 3 * sizeof *m.triangles);
    assert_true(m.vertices && m.triangles);
    m.nvertices = 16;
    for (int e = 0; e < 2; e++) /* vertex e * 8 + i: polygon point i at x = 10 e */
        for (int i = 0; i < 8; i++) {
            double *v = m.vertices + 3 * (8 * e + i);
            v[0] = 10.0 * e, v[1] = P[i][0], v[2] = P[i][1];
        }
    for (int t = 0; t < 6; t++) { /* the polygon is counterclockwise seen from +x */
        uint32_t *a = m.triangles + 3 * m.ntriangles++, *b = m.triangles + 3 * m.ntriangles++;
        a[0] = cap[t][0], a[1] = cap[t][2], a[2] = cap[t][1];
        b[0] = 8 + cap[t][0], b[1] = 8 + cap[t][1], b[2] = 8 + cap[t][2];
    }
    for (uint32_t i = 0; i < 8; i++) {
        uint32_t j = (i + 1) % 8;
        uint32_t *a = m.triangles + 3 * m.ntriangles++, *b = m.triangles + 3 * m.ntriangles++;
        a[0] = i, a[1] = j, a[2] = 8 + j;
        b[0] = i, b[1] = 8 + j, b[2] = 8 + i;
    }
    assert_true(fabs(mg_volume(&m) - 995.0) < 1e-9);
    double tau = 1.0, bound;
    acd_hull h;
    acd_mesh hm;
    hull_of(&m, &h, &hm);
    assert_true(fabs(h.volume - 1000.0) < 1e-9);
    for (size_t v = 0; v < m.nvertices; v++) { /* every vertex on the cube's boundary */
        const double *x = m.vertices + 3 * v;
        double d = INFINITY;
        for (int k = 0; k < 3; k++) d = fmin(d, fmin(x[k], 10 - x[k]));
        assert_true(d < 1e-12);
    }
    assert_true(sampled_reach(&hm, &m) <= 0.05 + 1e-12); /* hull -> part: close */
    assert_true(sampled_reach(&m, &hm) > 4 * tau);       /* part -> hull: the slit's bottom */
    acd_hull_free(&h);
    assert_int_equal(leaf_ok(&m, tau, &bound), 0);
    assert_true(bound > tau);
    acd_mesh_free(&m);
}

static double sphere_r(double th, double ph, void *u) { (void)th, (void)ph, (void)u; return 1.0; }

/* An open spherical cap (surface mode's parts are open): every vertex is on its hull's boundary,
 * so only the hull facets spanning the opening (at up to the cap's height from it) decide. It is
 * accepted when tau exceeds that height and refused below it, whichever side faces out. */
static void test_open_cap(void **state) {
    (void)state;
    acd_mesh sph;
    assert_true(mg_radial(&sph, 32, 16, sphere_r, NULL));
    /* the faces with every vertex above z = 0.5: a cap of height 0.5 */
    acd_mesh cap;
    memset(&cap, 0, sizeof cap);
    uint32_t *map = malloc(sph.nvertices * sizeof *map);
    cap.vertices = malloc(3 * sph.nvertices * sizeof *cap.vertices);
    cap.triangles = malloc(3 * sph.ntriangles * sizeof *cap.triangles);
    assert_true(map && cap.vertices && cap.triangles);
    for (size_t v = 0; v < sph.nvertices; v++) {
        map[v] = UINT32_MAX;
        if (sph.vertices[3 * v + 2] > 0.5 - 1e-12) {
            map[v] = (uint32_t)cap.nvertices;
            memcpy(cap.vertices + 3 * cap.nvertices++, sph.vertices + 3 * v, sizeof(double[3]));
        }
    }
    for (size_t t = 0; t < sph.ntriangles; t++) {
        const uint32_t *tr = sph.triangles + 3 * t;
        if (map[tr[0]] != UINT32_MAX && map[tr[1]] != UINT32_MAX && map[tr[2]] != UINT32_MAX) {
            for (int k = 0; k < 3; k++) cap.triangles[3 * cap.ntriangles + (size_t)k] = map[tr[k]];
            cap.ntriangles++;
        }
    }
    assert_true(cap.ntriangles > 10);
    double top = 0, lo = 1;
    for (size_t v = 0; v < cap.nvertices; v++) {
        top = fmax(top, cap.vertices[3 * v + 2]);
        lo = fmin(lo, cap.vertices[3 * v + 2]);
    }
    double height = top - lo, bound;
    assert_int_equal(leaf_ok(&cap, 0.8 * height, &bound), 0);
    assert_int_equal(leaf_ok(&cap, 1.2 * height, &bound), 1);
    /* the same with the faces turned over (the inner side out) */
    for (size_t t = 0; t < cap.ntriangles; t++) {
        uint32_t x = cap.triangles[3 * t + 1];
        cap.triangles[3 * t + 1] = cap.triangles[3 * t + 2];
        cap.triangles[3 * t + 2] = x;
    }
    assert_int_equal(leaf_ok(&cap, 0.8 * height, &bound), 0);
    assert_int_equal(leaf_ok(&cap, 1.2 * height, &bound), 1);
    acd_hull h;
    acd_mesh hm;
    hull_of(&cap, &h, &hm);
    assert_true(sampled_reach(&hm, &cap) <= 1.2 * height);
    assert_true(sampled_reach(&hm, &cap) > 0.8 * height);
    acd_hull_free(&h);
    free(map);
    acd_mesh_free(&cap);
    acd_mesh_free(&sph);
}

/* Several dents and a shallow roof, with the merge pass: the same parts for 1, 2 and 3 threads,
 * solid and surface mode. */
static void test_threads(void **state) {
    (void)state;
    hf s = {10, 3, 0.2, 1.3, 3, 3, 1.8};
    acd_mesh m;
    heightfield(&m, &s, 24);
    /* a second dent near the other eave */
    for (size_t v = 0; v < m.nvertices; v++) {
        double *x = m.vertices + 3 * v;
        if (x[2] > 0) {
            double r2 = ((x[0] - 8) * (x[0] - 8) + (x[1] - 7) * (x[1] - 7)) / 4.0;
            if (r2 < 1) x[2] -= 0.9 * (1 - r2) * (1 - r2);
        }
    }
    for (int mode = 0; mode < 2; mode++) {
        acd3d_params p = params(0.6, ACD3D_STOP_HULL);
        p.mode = mode ? ACD3D_SURFACE : ACD3D_SOLID;
        p.merge = 1;
        acd3d_result r1, r2;
        acd_error err;
        assert_int_equal(acd3d_decompose(&m, &p, &r1, &err), ACD_OK);
        if (!mode) assert_true(check_parts(&r1) >= 1); /* the test is exercised: some leaves are its */
        for (int th = 2; th <= 3; th++) {
            p.threads = th;
            assert_int_equal(acd3d_decompose(&m, &p, &r2, &err), ACD_OK);
            ck3_same_parts(&r1, &r2);
            acd3d_result_free(&r2);
        }
        acd3d_result_free(&r1);
    }
    acd_mesh_free(&m);
}

static void test_bad_stop(void **state) {
    (void)state;
    hf s = {10, 3, 0.2, 0.5, 5, 5, 1.5};
    acd_mesh m;
    heightfield(&m, &s, 8);
    acd3d_params p = params(1.0, (acd3d_stop)7);
    acd3d_result r;
    acd_error err;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    acd_mesh_free(&m);
}

/* acd3_leaf_test_keep on m (its hull h): the verdict and bound of acd3_leaf_test, bit for bit; the
 * tree handed out when the test got to d_out (built over m's own arrays), the facet table only when
 * accepted: every facet of h, sorted, each bound within tau, the largest the d_out of
 * acd3_merge_hull_reach over that tree (so at most the bound). Returns the verdict. */
static int keep_checked(const acd_mesh *m, double tau, int expect_tree) {
    acd_hull h;
    acd_mesh hm;
    hull_of(m, &h, &hm);
    acd_error err;
    int ok = -1, ok2 = -1;
    double bound, bound2;
    assert_int_equal(acd3_leaf_test(m, &h, tau, UINT32_MAX, &ok, &bound, &err), ACD_OK);
    acd_bvh bvh;
    acd3_facet_table tb;
    assert_int_equal(acd3_leaf_test_keep(m, &h, tau, UINT32_MAX, &ok2, &bound2, &bvh, &tb, &err), ACD_OK);
    assert_int_equal(ok, ok2);
    assert_memory_equal(&bound, &bound2, sizeof bound);
    assert_int_equal(bvh.nnodes > 0, expect_tree);
    if (expect_tree) {
        assert_ptr_equal(bvh.vertices, m->vertices);
        assert_ptr_equal(bvh.triangles, m->triangles);
        assert_int_equal(bvh.ntriangles, m->ntriangles);
    }
    if (!ok2) {
        assert_null(tb.key);
    } else {
        assert_non_null(tb.key);
        assert_int_equal(tb.n, h.ntriangles);
        assert_true(tb.tau == tau);
        double worst = 0;
        for (size_t f = 0; f < tb.n; f++) {
            assert_true(tb.ub[f] <= tau);
            worst = fmax(worst, tb.ub[f]);
            if (f) assert_true(memcmp(tb.key + 9 * (f - 1), tb.key + 9 * f, 9 * sizeof(double)) < 0);
        }
        for (size_t t = 0; t < h.ntriangles; t++) { /* every facet of h is in the table */
            const uint32_t *tr = h.triangles + 3 * t;
            int found = 0;
            for (size_t f = 0; f < tb.n && !found; f++) {
                int all = 1;
                for (int c = 0; c < 3 && all; c++) {
                    int in = 0;
                    for (int d = 0; d < 3; d++) in |= memcmp(tb.key + 9 * f + 3 * d, h.vertices + 3 * tr[c], 3 * sizeof(double)) == 0;
                    all = in;
                }
                found = all;
            }
            assert_true(found);
        }
        assert_true(worst == acd3_merge_hull_reach(&bvh, &h, tau));
        assert_true(worst <= bound);
    }
    acd3_facet_table_free(&tb);
    acd_bvh_free(&bvh);
    acd_hull_free(&h);
    return ok2;
}

/* What the budget pass keeps for the merge (acd3_leaf_test_keep): the shallow block is accepted (tree
 * and table), the bent slab is refused by d_out (its tree, no table), the deep dent by d_in (neither:
 * the test stops before building a tree). */
static void test_keep_tree_and_table(void **state) {
    (void)state;
    hf s = {10, 3, 0.2, 0.95, 8, 5, 1.5};
    acd_mesh m;
    heightfield(&m, &s, 20);
    assert_int_equal(keep_checked(&m, 1.0, 1), 1);
    acd_mesh_free(&m);
    hf deep = {10, 3, 0.2, 1.6, 8, 5, 1.5};
    heightfield(&m, &deep, 20);
    assert_int_equal(keep_checked(&m, 1.0, 0), 0);
    acd_mesh_free(&m);
    enum { N = 8 };
    unsigned char occ[N * N];
    for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++) occ[y * N + x] = x == 0 || y == 0;
    assert_true(mg_voxels(&m, occ, N, N, 1));
    assert_int_equal(keep_checked(&m, 1.0, 1), 0);
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_overreport_kept_whole),
        cmocka_unit_test(test_deep_dent_split),
        cmocka_unit_test(test_bent_slab_refused),
        cmocka_unit_test(test_slit_between_shallow_vertices),
        cmocka_unit_test(test_open_cap),
        cmocka_unit_test(test_threads),
        cmocka_unit_test(test_bad_stop),
        cmocka_unit_test(test_keep_tree_and_table),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
