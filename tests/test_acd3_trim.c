/* Tests of the trimmed hulls (acd3d_params.trim_coverage, acd3/trim; docs/acd3d.md "Trimmed hulls")
 * and of acd_mesh_volume_beyond, the volume they are accounted with:
 * - the volume beyond a plane of a cube and of a sphere against the closed forms;
 * - on a bumpy sphere at a part budget: the parts are those of the untrimmed run, every trimmed hull
 *   lies within the untrimmed one and holds less volume, the reported trimmed volumes add up and stay
 *   within the budget, the union of hulls scored by acd eval (independent code) covers at least
 *   1 - trim_coverage of the input and has a higher IoU; the same output for 1 and 2 threads;
 * - max_hull_vertices still holds with trimming; bad values and surface mode are refused;
 * - on one part, the volume outside its trimmed hull computed by cutting the part with the hull's
 *   planes (the library's acd_hull_volume_outside, what --verify measures with, and this file's own
 *   plane cuts): within the part's account (the guarantee), and equal to it up to rounding;
 * - a part that intersects itself is not trimmed (its signed volumes bound nothing), and it is counted;
 * - an internal wall on a part's hull (a face a cut made) is not cut under, which the same pass does
 *   without the input (a U prism cut across its arms);
 * - a thin fin on a box stays within the distance bound of the trimmed hull (fails without it);
 * - a cap leaning along an internal wall is not cut deep enough to leave the part's layer along the
 *   wall outside every hull farther than the bound inside the solid (the wall check; fails without it);
 * - acd3/trim_beyond's volumes beyond a plane's levels, in one pass, are bitwise the sums of
 *   acd_geom3_triangle_volume_beyond per level over the triangles of acd_bvh_query_halfspace in its
 *   order (what the trimmed hulls were chosen by before it), with levels through vertices. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd/eval.h"
#include "acd/hull.h"
#include "acd3/trim.h"
#include "acd3/trim_beyond.h"
#include "geom3/bvh.h"
#include "geom3/plane_cut.h"
#include "geom3/volume.h"
#include "mesh/selfintersect.h"
#include "shapes.h"

static void cube(acd_mesh *m) {
    static const double V[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
    static const uint32_t T[] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
    m->nvertices = 8;
    m->ntriangles = 12;
    m->vertices = malloc(sizeof V);
    m->triangles = malloc(sizeof T);
    memcpy(m->vertices, V, sizeof V);
    memcpy(m->triangles, T, sizeof T);
}

static void test_volume_beyond_cube(void **state) {
    (void)state;
    acd_mesh m;
    cube(&m);
    const double x25[4] = {1, 0, 0, -0.25};     /* x > 0.25 */
    const double x25s[4] = {-2, 0, 0, 0.5};     /* x < 0.25, normal not unit */
    const double diag[4] = {1, 1, 0, -1};       /* x + y > 1: half the cube */
    const double corner[4] = {1, 1, 1, -2.5};   /* x + y + z > 2.5: a corner tetrahedron, 1/48 */
    const double none[4] = {0, 0, 1, -3};       /* z > 3 */
    const double all[4] = {0, 0, 1, 3};         /* z > -3 */
    assert_float_equal(acd_mesh_volume_beyond(&m, x25), 0.75, 1e-14);
    assert_float_equal(acd_mesh_volume_beyond(&m, x25s), 0.25, 1e-14);
    assert_float_equal(acd_mesh_volume_beyond(&m, diag), 0.5, 1e-14);
    assert_float_equal(acd_mesh_volume_beyond(&m, corner), 1.0 / 48, 1e-14);
    assert_float_equal(acd_mesh_volume_beyond(&m, none), 0.0, 1e-15);
    assert_float_equal(acd_mesh_volume_beyond(&m, all), 1.0, 1e-14);
    const double zero[4] = {0, 0, 0, 1}, bad[4] = {NAN, 0, 1, 0};
    assert_true(isnan(acd_mesh_volume_beyond(&m, zero)));
    assert_true(isnan(acd_mesh_volume_beyond(&m, bad)));
    acd_mesh_free(&m);
}

static double radius2(double theta, double phi, void *user) {
    (void)theta, (void)phi, (void)user;
    return 2.0;
}

/* a sphere's cap against the closed form pi h^2 (3r - h) / 3, within the polyhedron's error */
static void test_volume_beyond_sphere(void **state) {
    (void)state;
    acd_mesh m;
    double r = 2.0;
    assert_true(mg_radial(&m, 96, 64, radius2, NULL));
    for (size_t i = 0; i < m.nvertices; i++) m.vertices[3 * i] += 10; /* off the origin */
    for (double h = 0.25; h < 4; h += 0.75) {
        const double pl[4] = {0, 0, 1, -(r - h)}; /* z > r - h */
        double exact = 3.14159265358979323846 * h * h * (3 * r - h) / 3;
        assert_true(fabs(acd_mesh_volume_beyond(&m, pl) - exact) < 0.01 * exact);
    }
    acd_mesh_free(&m);
}

static void bumpy(acd_mesh *m) { assert_true(mg_radial(m, 48, 32, mg_bumpy_r, NULL)); }

static double hulls_volume(const acd3d_result *r) {
    double s = 0;
    for (size_t i = 0; i < r->nparts; i++) s += r->parts[i].hull_volume;
    return s;
}

static void eval_result(const acd_mesh *m, const acd3d_result *r, acd_eval_report *rep) {
    acd_hull *h = calloc(r->nparts, sizeof *h);
    acd_error err;
    for (size_t i = 0; i < r->nparts; i++)
        assert_int_equal(acd_hull_compute(r->parts[i].hull.vertices, r->parts[i].hull.nvertices, &h[i], &err), ACD_OK);
    acd_eval_params ep = acd_eval_default_params();
    ep.samples = 200000;
    ep.surface_samples = 20000;
    assert_int_equal(acd_eval_hulls(m, h, r->nparts, &ep, rep, &err), ACD_OK);
    for (size_t i = 0; i < r->nparts; i++) acd_hull_free(&h[i]);
    free(h);
}

static void test_trim_bumpy(void **state) {
    (void)state;
    acd_mesh m;
    bumpy(&m);
    acd_error err;
    acd3d_params p = acd3d_budget_params(6);
    p.threads = 1;
    acd3d_result plain, trimmed, trimmed2;
    assert_int_equal(acd3d_decompose(&m, &p, &plain, &err), ACD_OK);
    const double F = 0.002;
    p.trim_coverage = F;
    assert_int_equal(acd3d_decompose(&m, &p, &trimmed, &err), ACD_OK);
    p.threads = 2;
    assert_int_equal(acd3d_decompose(&m, &p, &trimmed2, &err), ACD_OK);
    assert_int_equal(plain.nparts, trimmed.nparts);
    assert_true(trimmed.trim_cuts > 0);
    assert_true(plain.trim_cuts == 0 && plain.trimmed_volume == 0);
    double tsum = 0;
    for (size_t i = 0; i < trimmed.nparts; i++) {
        const acd3d_part *a = &plain.parts[i], *b = &trimmed.parts[i];
        /* the same part, its hull inside the untrimmed one and no larger */
        assert_int_equal(a->mesh.nvertices, b->mesh.nvertices);
        assert_memory_equal(a->mesh.vertices, b->mesh.vertices, 3 * a->mesh.nvertices * sizeof(double));
        assert_true(b->hull_volume <= a->hull_volume * (1 + 1e-12));
        assert_true(b->trimmed_volume >= 0);
        tsum += b->trimmed_volume;
        acd_hull ha;
        assert_int_equal(acd_hull_compute(a->hull.vertices, a->hull.nvertices, &ha, &err), ACD_OK);
        for (size_t v = 0; v < b->hull.nvertices; v++)
            assert_true(acd_hull_plane_distance(&ha, b->hull.vertices + 3 * v) <= 1e-9 * plain.scale);
        acd_hull_free(&ha);
        /* a hull with nothing trimmed is the untrimmed one */
        if (b->trimmed_volume == 0) assert_true(b->hull_volume == a->hull_volume);
    }
    assert_float_equal(tsum, trimmed.trimmed_volume, 1e-9 * trimmed.input_volume);
    assert_true(trimmed.trimmed_volume <= F * trimmed.input_volume * (1 + 1e-12));
    assert_true(trimmed.trimmed_volume > 0);
    assert_true(hulls_volume(&trimmed) < hulls_volume(&plain) - 1e-4 * trimmed.input_volume);
    /* the union scored independently: coverage within the budget (sampling error: 1e-3), higher IoU */
    acd_eval_report e0, e1;
    eval_result(&m, &plain, &e0);
    eval_result(&m, &trimmed, &e1);
    assert_true(e0.coverage > 0.9999);
    assert_true(e1.coverage >= 1 - F - 1e-3);
    assert_true(e1.iou > e0.iou);
    /* the same output for 1 and 2 threads */
    assert_int_equal(trimmed.nparts, trimmed2.nparts);
    assert_int_equal(trimmed.trim_cuts, trimmed2.trim_cuts);
    for (size_t i = 0; i < trimmed.nparts; i++) {
        assert_int_equal(trimmed.parts[i].hull.nvertices, trimmed2.parts[i].hull.nvertices);
        assert_memory_equal(trimmed.parts[i].hull.vertices, trimmed2.parts[i].hull.vertices,
                            3 * trimmed.parts[i].hull.nvertices * sizeof(double));
    }
    acd3d_result_free(&plain);
    acd3d_result_free(&trimmed);
    acd3d_result_free(&trimmed2);
    acd_mesh_free(&m);
}

static void test_trim_max_vertices(void **state) {
    (void)state;
    acd_mesh m;
    bumpy(&m);
    acd_error err;
    acd3d_params p = acd3d_budget_params(4);
    p.trim_coverage = 0.005;
    p.max_hull_vertices = 24;
    acd3d_result r;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    for (size_t i = 0; i < r.nparts; i++) assert_true(r.parts[i].hull.nvertices <= 24);
    assert_true(r.trimmed_volume <= 0.005 * r.input_volume * (1 + 1e-12));
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}

static void test_trim_refused(void **state) {
    (void)state;
    acd_mesh m;
    cube(&m);
    acd_error err;
    acd3d_result r;
    const double bad[] = {-1e-3, 0.02, NAN, INFINITY};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        acd3d_params p = acd3d_default_params();
        p.trim_coverage = bad[k];
        assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_INVALID_ARGUMENT);
        assert_non_null(strstr(err.message, "trim_coverage"));
    }
    acd3d_params p = acd3d_default_params();
    p.mode = ACD3D_SURFACE;
    p.trim_coverage = 0.001;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err.message, "solid mode only"));
    /* a convex input: nothing to trim, the hull is the cube */
    p = acd3d_default_params();
    p.trim_coverage = 0.01;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_int_equal(r.nparts, 1);
    assert_int_equal(r.trim_cuts, 0);
    assert_float_equal(r.parts[0].hull_volume, 1.0, 1e-12);
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}

/* two bumpy spheres overlapping: one closed, outward mesh that crosses itself */
static void two_bumpy(acd_mesh *out) {
    acd_mesh a, b, m;
    bumpy(&a);
    bumpy(&b);
    m.nvertices = a.nvertices + b.nvertices;
    m.ntriangles = a.ntriangles + b.ntriangles;
    m.vertices = malloc(3 * m.nvertices * sizeof *m.vertices);
    m.triangles = malloc(3 * m.ntriangles * sizeof *m.triangles);
    memcpy(m.vertices, a.vertices, 3 * a.nvertices * sizeof *m.vertices);
    for (size_t i = 0; i < b.nvertices; i++) {
        m.vertices[3 * (a.nvertices + i)] = b.vertices[3 * i] + 0.8;
        m.vertices[3 * (a.nvertices + i) + 1] = b.vertices[3 * i + 1];
        m.vertices[3 * (a.nvertices + i) + 2] = b.vertices[3 * i + 2];
    }
    memcpy(m.triangles, a.triangles, 3 * a.ntriangles * sizeof *m.triangles);
    for (size_t t = 0; t < 3 * b.ntriangles; t++) m.triangles[3 * a.ntriangles + t] = b.triangles[t] + (uint32_t)a.nvertices;
    acd_mesh_free(&a);
    acd_mesh_free(&b);
    *out = m;
}

static void test_trim_self_crossing(void **state) {
    (void)state;
    acd_mesh m;
    two_bumpy(&m);
    acd_error err;
    acd3d_params p = acd3d_budget_params(4);
    p.trim_coverage = 0.005;
    acd3d_result r;
    assert_int_equal(acd3d_decompose(&m, &p, &r, &err), ACD_OK);
    assert_true(r.trim_skipped > 0);
    /* the parts left whole are those that cross themselves: their hulls enclose them */
    size_t whole = 0;
    for (size_t i = 0; i < r.nparts; i++) {
        size_t nx = 0;
        assert_int_equal(acd_mesh_self_intersections(&r.parts[i].mesh, &nx, NULL, 0, &err), ACD_OK);
        if (nx > 0) {
            whole++;
            assert_true(r.parts[i].trimmed_volume == 0);
        }
    }
    assert_int_equal(whole, r.trim_skipped);
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}

static double closed_volume(const acd_mesh *m) {
    double s = 0;
    for (size_t t = 0; t < m->ntriangles; t++) {
        const double *a = m->vertices + 3 * (size_t)m->triangles[3 * t], *b = m->vertices + 3 * (size_t)m->triangles[3 * t + 1],
                     *c = m->vertices + 3 * (size_t)m->triangles[3 * t + 2];
        s += a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return s / 6;
}

/* The volume of the closed part m outside the convex hull of pts, exactly (up to rounding): m cut by
 * each distinct facet plane of that hull that some piece reaches beyond (geom3/plane_cut, exact
 * sides), the pieces inside kept; independent of acd3/trim's accounts. */
static double volume_outside(const acd_mesh *m, const double *pts, size_t npts, double scale) {
    acd_error err;
    acd_hull h;
    assert_int_equal(acd_hull_compute(pts, npts, &h, &err), ACD_OK);
    size_t npc = 1;
    const size_t cap = 256;
    acd_mesh *pc = calloc(cap, sizeof *pc);
    assert_non_null(pc);
    pc[0].nvertices = m->nvertices, pc[0].ntriangles = m->ntriangles;
    pc[0].vertices = malloc(3 * m->nvertices * sizeof(double));
    pc[0].triangles = malloc(3 * m->ntriangles * sizeof(uint32_t));
    assert_true(pc[0].vertices && pc[0].triangles);
    memcpy(pc[0].vertices, m->vertices, 3 * m->nvertices * sizeof(double));
    memcpy(pc[0].triangles, m->triangles, 3 * m->ntriangles * sizeof(uint32_t));
    for (size_t f = 0; f < h.ntriangles; f++) {
        const double *pl = h.planes + 4 * f;
        int dup = 0;
        for (size_t g = 0; g < f && !dup; g++) dup = !memcmp(h.planes + 4 * g, pl, 4 * sizeof(double));
        if (dup) continue;
        const double pt[3] = {-pl[3] * pl[0], -pl[3] * pl[1], -pl[3] * pl[2]};
        acd_cut_plane cp;
        assert_int_equal(acd_cut_plane_from_normal(pt, pl, scale, &cp, &err), ACD_OK);
        size_t nn = 0;
        acd_mesh *next = calloc(cap, sizeof *next);
        assert_non_null(next);
        for (size_t i = 0; i < npc; i++) {
            int beyond = 0;
            for (size_t v = 0; v < pc[i].nvertices && !beyond; v++) beyond = acd_cut_plane_side(&cp, pc[i].vertices + 3 * v) > 0;
            if (!beyond) {
                next[nn++] = pc[i];
                continue;
            }
            acd_cut_result r;
            if (acd_plane_cut(&pc[i], &cp, &r, &err) != ACD_OK) { /* a piece the rounding pinched: not measured */
                for (size_t k = i; k < npc; k++) acd_mesh_free(&pc[k]);
                for (size_t k = 0; k < nn; k++) acd_mesh_free(&next[k]);
                free(pc), free(next);
                acd_hull_free(&h);
                return NAN;
            }
            for (size_t k = 0; k < r.npieces; k++)
                if (r.pieces[k].side < 0) {
                    assert_true(nn < cap);
                    next[nn++] = r.pieces[k].mesh;
                    memset(&r.pieces[k].mesh, 0, sizeof r.pieces[k].mesh);
                }
            acd_cut_result_free(&r);
            acd_mesh_free(&pc[i]);
        }
        free(pc);
        pc = next, npc = nn;
    }
    double inside = 0;
    for (size_t i = 0; i < npc; i++) {
        inside += closed_volume(&pc[i]);
        acd_mesh_free(&pc[i]);
    }
    free(pc);
    acd_hull_free(&h);
    return closed_volume(m) - inside;
}

/* The accounts against the volume outside computed independently, on the bumpy sphere as one part
 * (a closed, manifold mesh): the part's trimmed_volume holds what lies outside its trimmed hull (the
 * guarantee), and exactly: each cut charges the part volume beyond its plane and inside the hull's
 * earlier cuts (acd3_trim_tree_charge). History: every cut charged its whole loss (200 cuts, 1.34 x
 * what lay outside); then a cut deeper along its own plane charged only the part between the two
 * planes (293 cuts, 1.026 x: the overlaps of caps of different planes counted twice); now 1 x up to
 * rounding. The measures: acd_hull_volume_outside (geom3/hull_outside, what --verify uses), and this
 * file's own plane cuts where they go through (a piece the rounding pinches is not measured). */
static void test_trim_accounts_exact(void **state) {
    (void)state;
    acd_mesh m;
    bumpy(&m);
    acd_error err;
    acd_hull h;
    assert_int_equal(acd_hull_compute(m.vertices, m.nvertices, &h, &err), ACD_OK);
    acd3d_part part;
    memset(&part, 0, sizeof part);
    part.mesh = m;
    part.hull.vertices = h.vertices, part.hull.nvertices = h.nvertices;
    part.hull.triangles = h.triangles, part.hull.ntriangles = h.ntriangles;
    part.hull_volume = h.volume;
    part.volume = closed_volume(&m);
    h.vertices = NULL, h.triangles = NULL;
    acd_hull_free(&h);
    const double vol = part.volume, F = 0.004;
    acd3_trim_stats st;
    /* (no distance bound: the accounts are the point here) */
    assert_int_equal(acd3_trim_hulls_within(&part, 1, vol, F * vol, ACD3_TRIM_MIN_GAIN_REL * vol, 0, INFINITY, &m, NULL,
                                            1, NULL, NULL, &st, &err),
                     ACD_OK);
    assert_true(st.cuts > 0);
    assert_float_equal(st.removed_part, part.trimmed_volume, 1e-12 * vol);
    assert_true(part.trimmed_volume <= F * vol * (1 + 1e-12));
    assert_true(part.trimmed_volume > 0.9 * F * vol);
    acd_hull th;
    assert_int_equal(acd_hull_compute(part.hull.vertices, part.hull.nvertices, &th, &err), ACD_OK);
    double lib;
    assert_int_equal(acd_hull_volume_outside(&th, &m, 1e-9 * 2.0, 2.0, &lib, &err), ACD_OK);
    const double bound = acd_hull_volume_outside_bound(&th, &m, 1e-9 * 2.0, 2.0);
    const double own = volume_outside(&m, part.hull.vertices, part.hull.nvertices, 2.0);
    print_message("trim accounts: %zu cuts, charged %.9g, outside %.9g (acd_hull_volume_outside), %.9g (here), the "
                  "bound %.6g (of the part's volume), charged / outside %.9f\n",
                  st.cuts, part.trimmed_volume / vol, lib / vol, own / vol, bound / vol, part.trimmed_volume / lib);
    /* an upper bound, and the same up to rounding */
    assert_true(lib <= part.trimmed_volume + 1e-9 * vol);
    assert_float_equal(part.trimmed_volume, lib, 1e-9 * vol);
    if (own == own) assert_float_equal(own, lib, 1e-9 * vol);
    assert_true(bound > lib);
    acd_hull_free(&th);
    acd_mesh_free(&part.hull);
    acd_mesh_free(&m);
}

/* The parts of r with their untrimmed hulls (trimmed in place: the hull of the part's vertices, as
 * acd3d_decompose computes it without max_hull_vertices) and their own meshes (the same arrays: the
 * trees are over them). */
static acd3d_part *hull_copies(const acd3d_result *r) {
    acd3d_part *c = calloc(r->nparts, sizeof *c);
    acd_error err;
    assert_non_null(c);
    for (size_t i = 0; i < r->nparts; i++) {
        c[i] = r->parts[i];
        acd_hull h;
        assert_int_equal(acd_hull_compute(c[i].mesh.vertices, c[i].mesh.nvertices, &h, &err), ACD_OK);
        c[i].hull = (acd_mesh){h.vertices, h.nvertices, h.triangles, h.ntriangles};
        c[i].hull_volume = h.volume;
        h.vertices = NULL, h.triangles = NULL;
        acd_hull_free(&h);
    }
    return c;
}

static void hull_copies_free(acd3d_part *c, size_t n) {
    for (size_t i = 0; i < n; i++) acd_mesh_free(&c[i].hull);
    free(c);
}

static void assert_same_hulls(const acd3d_part *a, const acd3d_part *b, size_t n) {
    for (size_t i = 0; i < n; i++) {
        assert_int_equal(a[i].hull.nvertices, b[i].hull.nvertices);
        assert_int_equal(a[i].hull.ntriangles, b[i].hull.ntriangles);
        assert_memory_equal(a[i].hull.vertices, b[i].hull.vertices, 3 * a[i].hull.nvertices * sizeof(double));
        assert_memory_equal(a[i].hull.triangles, b[i].hull.triangles, 3 * a[i].hull.ntriangles * sizeof(uint32_t));
        assert_memory_equal(&a[i].hull_volume, &b[i].hull_volume, sizeof(double));
        assert_memory_equal(&a[i].trimmed_volume, &b[i].trimmed_volume, sizeof(double));
    }
}

/* acd3_trim_hulls with the trees given (acd3_trim_trees: all, some, the input's only, and trees of
 * other parts, which are not over the part's arrays: not used) trims as with none, bit for bit, at 1
 * and 2 threads; and acd3d_decompose, which hands it the merge's and the budget pass's trees, gives
 * those hulls too. On the bumpy sphere and on an input that crosses itself (whose parts are then
 * tested with their trees: acd_mesh_self_intersections_bvh, the same count as without). */
static void test_trim_given_trees(void **state) {
    (void)state;
    for (int shape = 0; shape < 2; shape++) {
        acd_mesh m;
        if (shape == 0) bumpy(&m);
        else two_bumpy(&m);
        acd_error err;
        acd3d_params p = acd3d_budget_params(shape == 0 ? 6 : 4);
        p.threads = 1;
        acd3d_result trimmed;
        const double F = shape == 0 ? 0.002 : 0.005;
        p.trim_coverage = F;
        assert_int_equal(acd3d_decompose(&m, &p, &trimmed, &err), ACD_OK);
        const acd3d_result *plain = &trimmed; /* its parts, their hulls untrimmed again (hull_copies) */
        const size_t n = trimmed.nparts;
        const double vol = trimmed.input_volume;
        /* the trees, built here */
        acd_bvh BI, *B = calloc(n, sizeof *B);
        const acd_bvh **all = calloc(n, sizeof *all), **some = calloc(n, sizeof *some), **other = calloc(n, sizeof *other);
        assert_true(B && all && some && other);
        assert_int_equal(acd_bvh_build(&BI, m.vertices, m.nvertices, m.triangles, m.ntriangles, &err), ACD_OK);
        for (size_t i = 0; i < n; i++) {
            const acd_mesh *pm = &plain->parts[i].mesh;
            assert_int_equal(acd_bvh_build(&B[i], pm->vertices, pm->nvertices, pm->triangles, pm->ntriangles, &err),
                             ACD_OK);
            all[i] = &B[i];
            some[i] = i % 2 ? &B[i] : NULL;
        }
        for (size_t i = 0; i < n; i++) other[i] = &B[(i + 1) % n];
        if (shape == 1) { /* the input's test on its tree */
            size_t c0 = 0, c1 = 0;
            uint32_t p0[4] = {0}, p1[4] = {0};
            assert_int_equal(acd_mesh_self_intersections(&m, &c0, p0, 2, &err), ACD_OK);
            assert_int_equal(acd_mesh_self_intersections_bvh(&m, &BI, &c1, p1, 2, &err), ACD_OK);
            assert_true(c0 > 0);
            assert_int_equal(c0, c1);
            assert_memory_equal(p0, p1, sizeof p0);
        }
        { /* the test trim makes (stopping at the first crossing): whether the count is > 0, on the input and
           * on each part, with its tree and without */
            size_t c0 = 0;
            int any = -1, any2 = -1;
            assert_int_equal(acd_mesh_self_intersections(&m, &c0, NULL, 0, &err), ACD_OK);
            assert_int_equal(acd_mesh_self_intersects_bvh(&m, &BI, &any, &err), ACD_OK);
            assert_int_equal(acd_mesh_self_intersects_bvh(&m, NULL, &any2, &err), ACD_OK);
            assert_int_equal(any, shape == 1);
            assert_int_equal(any, c0 > 0);
            assert_int_equal(any2, any);
            size_t crossing_parts = 0;
            for (size_t i = 0; i < n; i++) {
                assert_int_equal(acd_mesh_self_intersections(&plain->parts[i].mesh, &c0, NULL, 0, &err), ACD_OK);
                assert_int_equal(acd_mesh_self_intersects_bvh(&plain->parts[i].mesh, &B[i], &any, &err), ACD_OK);
                assert_int_equal(any, c0 > 0);
                crossing_parts += c0 > 0;
            }
            if (shape == 1) assert_true(crossing_parts > 0);
        }
        const acd3_trim_trees sets[4] = {{&BI, all}, {NULL, some}, {&BI, NULL}, {NULL, other}};
        acd3d_part *ref = hull_copies(plain);
        acd3_trim_stats sref;
        assert_int_equal(acd3_trim_hulls(ref, n, vol, F * vol, ACD3_TRIM_MIN_GAIN_REL * vol, p.max_hull_vertices, &m,
                                         NULL, 1, NULL, NULL, &sref, &err),
                         ACD_OK);
        assert_true(sref.cuts > 0);
        assert_true(shape == 0 ? sref.skipped == 0 : sref.skipped > 0);
        for (int s = 0; s < 4; s++)
            for (int th = 1; th <= 2; th++) {
                acd3d_part *c = hull_copies(plain);
                acd3_trim_stats st;
                assert_int_equal(acd3_trim_hulls(c, n, vol, F * vol, ACD3_TRIM_MIN_GAIN_REL * vol, p.max_hull_vertices,
                                                 &m, &sets[s], th, NULL, NULL, &st, &err),
                                 ACD_OK);
                assert_memory_equal(&st, &sref, sizeof st);
                assert_same_hulls(c, ref, n);
                hull_copies_free(c, n);
            }
        /* the decomposition's own trim (with the trees of its merge and budget pass) */
        assert_same_hulls(trimmed.parts, ref, n);
        assert_int_equal(trimmed.trim_cuts, sref.cuts);
        assert_int_equal(trimmed.trim_skipped, sref.skipped);
        hull_copies_free(ref, n);
        for (size_t i = 0; i < n; i++) acd_bvh_free(&B[i]);
        acd_bvh_free(&BI);
        free(B), free(all), free(some), free(other);
        acd3d_result_free(&trimmed);
        acd_mesh_free(&m);
    }
}

static double lcg(uint64_t *s) {
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) / 9007199254740992.0;
}

/* acd3_trim_clip_cone against acd_geom3_clipped_cone_volume, term by term (memcmp): random triangles
 * and apexes, every sign pattern of s (each corner beyond, on the level or below: 27) */
static void test_trim_clip_cone_bitwise(void **state) {
    (void)state;
    uint64_t seed = 777;
    size_t cases[8] = {0};
    for (int it = 0; it < 20000; it++) {
        double P[3][3], apex[3], s[3];
        for (int c = 0; c < 3; c++)
            for (int q = 0; q < 3; q++) P[c][q] = 10 * lcg(&seed) - 5;
        for (int q = 0; q < 3; q++) apex[q] = 4 * lcg(&seed) - 2;
        const int pattern = it % 27;
        for (int c = 0, r = pattern; c < 3; c++, r /= 3) {
            const double mag = lcg(&seed) * (it % 5 == 0 ? 1e-300 : 3.0); /* (tiny: crossings near corners) */
            s[c] = r % 3 == 0 ? mag + 1e-320 : r % 3 == 1 ? 0.0 : -mag - 1e-320;
        }
        const double *const p[3] = {P[0], P[1], P[2]};
        double e[3][3];
        for (int c = 0; c < 3; c++)
            for (int q = 0; q < 3; q++) e[c][q] = P[c == 2 ? 0 : c + 1][q] - P[c][q];
        const double got = acd3_trim_clip_cone(p, (const double(*)[3])e, s, apex);
        const double want = acd_geom3_clipped_cone_volume(p, s, apex);
        assert_memory_equal(&got, &want, sizeof got);
        cases[(s[0] > 0) | (s[1] > 0) << 1 | (s[2] > 0) << 2]++;
    }
    for (int k = 0; k < 8; k++) assert_true(cases[k] > 100);
}

/* the reference: per level, acd_geom3_triangle_volume_beyond over the query's triangles in its order */
typedef struct beyond_ref {
    const acd_mesh *m;
    const double *n;
    const acd3_trim_levels *L;
    size_t k_lo;
    double *v;
} beyond_ref;

static int beyond_ref_tri(void *user, uint32_t t) {
    const beyond_ref *q = user;
    const uint32_t *tr = q->m->triangles + 3 * (size_t)t;
    const double *V = q->m->vertices;
    for (size_t k = q->k_lo; k < ACD3_TRIM_NDEPTHS; k++) {
        const double apex[3] = {q->L->ax[k], q->L->ay[k], q->L->az[k]};
        q->v[k] += acd_geom3_triangle_volume_beyond(V + 3 * (size_t)tr[0], V + 3 * (size_t)tr[1], V + 3 * (size_t)tr[2],
                                                    q->n, q->L->off[k], apex);
    }
    return 0;
}

static void test_trim_beyond_bitwise(void **state) {
    (void)state;
    acd_mesh m;
    bumpy(&m);
    for (size_t i = 0; i < m.nvertices; i++) m.vertices[3 * i] += 3.25; /* off the origin */
    acd_bvh bvh;
    acd_error err;
    assert_int_equal(acd_bvh_build(&bvh, m.vertices, m.nvertices, m.triangles, m.ntriangles, &err), ACD_OK);
    acd3_trim_tree tree;
    assert_true(acd3_trim_tree_build(&tree, &bvh));
    static const double depth[ACD3_TRIM_NDEPTHS] = {0.001, 0.002, 0.005, 0.01, 0.02, 0.04};
    const double vol = acd_geom3_signed_volume(&m), centre[3] = {3.25, 0, 0};
    uint64_t seed = 12345;
    size_t crossing = 0, whole = 0, on_vertex = 0;
    for (int it = 0; it < 400; it++) {
        double n[3] = {2 * lcg(&seed) - 1, 2 * lcg(&seed) - 1, 2 * lcg(&seed) - 1}, nn = 0;
        for (int q = 0; q < 3; q++) nn += n[q] * n[q];
        if (!(nn > 0.01)) continue;
        for (int q = 0; q < 3; q++) n[q] /= sqrt(nn);
        double top = -INFINITY;
        size_t vtop = 0;
        for (size_t v = 0; v < m.nvertices; v++) {
            double d = acd_dot3(n, m.vertices + 3 * v);
            if (d > top) top = d, vtop = v;
        }
        /* levels from just below the top to well into the mesh (scaled up to reach more triangles) */
        const double unit = 2 + 8 * lcg(&seed);
        acd3_trim_levels L;
        for (size_t k = 0; k < ACD3_TRIM_NDEPTHS; k++) L.off[k] = top - depth[k] * unit;
        if (it % 3 == 0) { /* a level through a vertex (its n.x exactly): s = 0 at that corner */
            size_t k = 1 + (size_t)it % (ACD3_TRIM_NDEPTHS - 2);
            double best = INFINITY;
            for (size_t v = 0; v < m.nvertices; v++) {
                double d = acd_dot3(n, m.vertices + 3 * v);
                if (d < L.off[k - 1] && d > L.off[k + 1] && fabs(d - L.off[k]) < best) best = fabs(d - L.off[k]), L.off[k] = d;
            }
            on_vertex += best < INFINITY;
        }
        if (it % 7 == 0) L.off[0] = acd_dot3(n, m.vertices + 3 * vtop); /* through the top vertex */
        for (size_t k = 0; k < ACD3_TRIM_NDEPTHS; k++) { /* apexes as acd3/trim places them */
            double s = acd_dot3(n, centre) - L.off[k];
            L.ax[k] = centre[0] - s * n[0], L.ay[k] = centre[1] - s * n[1], L.az[k] = centre[2] - s * n[2];
        }
        const size_t k_lo = (size_t)it % 4;
        double got[ACD3_TRIM_NDEPTHS] = {0}, want[ACD3_TRIM_NDEPTHS] = {0}, all[ACD3_TRIM_NDEPTHS] = {0};
        acd3_trim_tree_beyond(&tree, n, &L, k_lo, got, NULL);
        beyond_ref ref = {&m, n, &L, k_lo, want};
        acd_bvh_query_halfspace(&bvh, n, L.off[ACD3_TRIM_NDEPTHS - 1], beyond_ref_tri, &ref);
        assert_memory_equal(got, want, sizeof got);
        /* the kernel over every triangle in index order against the function likewise */
        double ref_all[ACD3_TRIM_NDEPTHS] = {0};
        for (size_t t = 0; t < m.ntriangles; t++) {
            const uint32_t *tr = m.triangles + 3 * t;
            const double *const p[3] = {m.vertices + 3 * (size_t)tr[0], m.vertices + 3 * (size_t)tr[1],
                                        m.vertices + 3 * (size_t)tr[2]};
            const double d[3] = {acd_dot3(n, p[0]), acd_dot3(n, p[1]), acd_dot3(n, p[2])};
            acd3_trim_tri_beyond(p, d, &L, 0, all);
            for (size_t k = 0; k < ACD3_TRIM_NDEPTHS; k++) {
                const double apex[3] = {L.ax[k], L.ay[k], L.az[k]};
                ref_all[k] += acd_geom3_triangle_volume_beyond(p[0], p[1], p[2], n, L.off[k], apex);
                crossing += d[0] > L.off[k] && !(fmin(d[0], fmin(d[1], d[2])) > L.off[k]);
                whole += fmin(d[0], fmin(d[1], d[2])) > L.off[k];
            }
        }
        assert_memory_equal(all, ref_all, sizeof all);
        /* and they are the volumes beyond (a cap of the closed mesh), growing with depth */
        for (size_t k = 0; k < ACD3_TRIM_NDEPTHS; k++) {
            const double pl[4] = {n[0], n[1], n[2], -L.off[k]};
            assert_float_equal(all[k], acd_mesh_volume_beyond(&m, pl), 1e-12 * vol);
            if (k > 0) assert_true(all[k] >= all[k - 1] - 1e-12 * vol);
        }
        for (size_t k = 0; k < k_lo; k++) assert_true(got[k] == 0);
        assert_true(got[ACD3_TRIM_NDEPTHS - 1] > 0);
    }
    /* the cases met: crossing and whole triangles, levels through vertices */
    assert_true(crossing > 1000 && whole > 1000 && on_vertex > 100);
    acd3_trim_tree_free(&tree);
    acd_bvh_free(&bvh);
    acd_mesh_free(&m);
}

/* A prism over a U (in x, y; arms and bar 0.2 wide, 3 x 3), along z from 0 to 1. */
static void u_prism(acd_mesh *m) {
    static const double P[8][2] = {{0, 0}, {3, 0}, {3, 3}, {2.8, 3}, {2.8, 0.2}, {0.2, 0.2}, {0.2, 3}, {0, 3}};
    static const uint32_t Q[3][4] = {{0, 1, 4, 5}, {1, 2, 3, 4}, {0, 5, 6, 7}}; /* convex, counterclockwise */
    m->nvertices = 16;
    m->ntriangles = 12 + 16;
    m->vertices = malloc(3 * m->nvertices * sizeof *m->vertices);
    m->triangles = malloc(3 * m->ntriangles * sizeof *m->triangles);
    for (size_t k = 0; k < 16; k++) {
        m->vertices[3 * k] = P[k % 8][0];
        m->vertices[3 * k + 1] = P[k % 8][1];
        m->vertices[3 * k + 2] = k < 8 ? 0 : 1;
    }
    uint32_t *t = m->triangles;
    for (int q = 0; q < 3; q++) {
        const uint32_t *c = Q[q];
        const uint32_t tri[4][3] = {{c[0] + 8, c[1] + 8, c[2] + 8}, {c[0] + 8, c[2] + 8, c[3] + 8}, /* top */
                                    {c[0], c[2], c[1]}, {c[0], c[3], c[2]}};                       /* bottom */
        memcpy(t, tri, sizeof tri);
        t += 12;
    }
    for (uint32_t a = 0; a < 8; a++) {
        const uint32_t b = (a + 1) % 8, tri[2][3] = {{a, b, b + 8}, {a, b + 8, a + 8}};
        memcpy(t, tri, sizeof tri);
        t += 6;
    }
}

/* Trims copies of the pieces' hulls of cr; the largest y of piece `low`'s trimmed hull. */
static double trim_pieces_max_y(const acd_cut_result *cr, size_t low, const acd_mesh *input, size_t *cuts) {
    const size_t n = cr->npieces;
    acd3d_part *parts = calloc(n, sizeof *parts);
    double vol = 0;
    acd_error err;
    for (size_t i = 0; i < n; i++) {
        acd_hull h;
        assert_int_equal(acd_hull_compute(cr->pieces[i].mesh.vertices, cr->pieces[i].mesh.nvertices, &h, &err), ACD_OK);
        parts[i].mesh = cr->pieces[i].mesh; /* (read only) */
        parts[i].hull.vertices = h.vertices, parts[i].hull.nvertices = h.nvertices;
        parts[i].hull.triangles = h.triangles, parts[i].hull.ntriangles = h.ntriangles;
        parts[i].hull_volume = h.volume;
        parts[i].volume = closed_volume(&parts[i].mesh);
        vol += parts[i].volume;
        h.vertices = NULL, h.triangles = NULL;
        acd_hull_free(&h);
    }
    acd3_trim_stats st;
    assert_int_equal(acd3_trim_hulls_within(parts, n, vol, 0.005 * vol, ACD3_TRIM_MIN_GAIN_REL * vol, 0, INFINITY, input,
                                            NULL, 2, NULL, NULL, &st, &err),
                     ACD_OK);
    *cuts = st.cuts;
    double ymax = -INFINITY;
    for (size_t v = 0; v < parts[low].hull.nvertices; v++) ymax = fmax(ymax, parts[low].hull.vertices[3 * v + 1]);
    for (size_t i = 0; i < n; i++) acd_mesh_free(&parts[i].hull);
    free(parts);
    return ymax;
}

/* An internal wall on a part's hull is not cut under (acd3/trim's is_wall). The U prism cut across
 * its arms at y = 1: the lower piece (the bar and the arms' feet) touches the cut plane in the arms'
 * two sections (area 0.4) where its hull's facet spans 3 x 1, so a cap under that facet passes the
 * ratio test (about 7.5 against 1 + 3.8 / 1.72); cutting it would leave the piece's layer along the two
 * walls outside every hull (the arms' tops lie across them), the union's boundary inside the solid.
 * With the input given the lower hull keeps its facet at y = 1; without it (NULL: the walls are not
 * looked for, nor the input's crossings) the same pass cuts under that facet. */
static void test_trim_internal_wall(void **state) {
    (void)state;
    acd_mesh m;
    u_prism(&m);
    acd_error err;
    acd_cut_plane pl;
    const double o[3] = {1.5, 1, 0.5}, n[3] = {0, 1, 0};
    assert_int_equal(acd_cut_plane_from_normal(o, n, 4, &pl, &err), ACD_OK);
    acd_cut_result cr;
    assert_int_equal(acd_plane_cut(&m, &pl, &cr, &err), ACD_OK);
    assert_int_equal(cr.npieces, 3);
    size_t low = SIZE_MAX;
    for (size_t i = 0; i < cr.npieces; i++)
        if (cr.pieces[i].side < 0) low = i;
    assert_true(low < cr.npieces);
    assert_float_equal(closed_volume(&cr.pieces[low].mesh), 0.92, 1e-12);
    size_t cuts_walls, cuts_none;
    const double y_walls = trim_pieces_max_y(&cr, low, &m, &cuts_walls);
    const double y_none = trim_pieces_max_y(&cr, low, NULL, &cuts_none);
    print_message("internal wall: lower hull up to y = %.6f with the walls (%zu cuts), %.6f without (%zu cuts)\n",
                  y_walls, cuts_walls, y_none, cuts_none);
    assert_float_equal(y_walls, 1.0, 1e-12);
    assert_true(cuts_none > 0 && y_none < 1 - 1e-3);
    acd_cut_result_free(&cr);
    acd_mesh_free(&m);
}

/* A box 10 x 10 x 10 with a fin 0.1 thick and 5 high along its top (the profile in x, z extruded
 * along y): closed, outward. */
static void box_fin(acd_mesh *m) {
    static const double P[8][2] = {{0, 0}, {10, 0}, {10, 10}, {5.05, 10}, {5.05, 15}, {4.95, 15}, {4.95, 10}, {0, 10}};
    static const uint32_t C[6][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 6}, {0, 6, 7}, {6, 3, 4}, {6, 4, 5}}; /* the profile */
    m->nvertices = 16;
    m->ntriangles = 2 * 6 + 2 * 8;
    m->vertices = malloc(3 * m->nvertices * sizeof *m->vertices);
    m->triangles = malloc(3 * m->ntriangles * sizeof *m->triangles);
    for (int y = 0; y < 2; y++)
        for (int i = 0; i < 8; i++) {
            double *v = m->vertices + 3 * (8 * y + i);
            v[0] = P[i][0], v[1] = 10.0 * y, v[2] = P[i][1];
        }
    uint32_t *t = m->triangles;
    for (int k = 0; k < 6; k++) { /* the profile (ccw in x, z) faces -y at y = 0, +y at y = 10 */
        const uint32_t a[6] = {C[k][0], C[k][1], C[k][2], C[k][0] + 8, C[k][2] + 8, C[k][1] + 8};
        memcpy(t, a, sizeof a);
        t += 6;
    }
    for (uint32_t a = 0; a < 8; a++) {
        const uint32_t b = (a + 1) % 8, q[6] = {a, a + 8, b + 8, a, b + 8, b};
        memcpy(t, q, sizeof q);
        t += 6;
    }
    if (closed_volume(m) < 0)
        for (size_t i = 0; i < m->ntriangles; i++) {
            uint32_t x = m->triangles[3 * i + 1];
            m->triangles[3 * i + 1] = m->triangles[3 * i + 2], m->triangles[3 * i + 2] = x;
        }
}

/* The distance from p to the convex hull h (0 inside): the nearest of its triangles when outside. */
static double hull_distance(const acd_hull *h, const double p[3]) {
    if (!(acd_hull_plane_distance(h, p) > 0)) return 0;
    double best = INFINITY;
    for (size_t t = 0; t < h->ntriangles; t++) {
        const uint32_t *tr = h->triangles + 3 * t;
        double q[3];
        best = fmin(best, acd_closest_point_triangle(p, h->vertices + 3 * (size_t)tr[0], h->vertices + 3 * (size_t)tr[1],
                                                     h->vertices + 3 * (size_t)tr[2], q));
    }
    return sqrt(best);
}

/* A thin fin on a box, as one part of concavity 0.5, at the largest coverage allowed: the fin holds
 * 0.5% of the volume, so within the budget of 1% the hull's roof over it (250 of air) could be cut
 * down through the fin, leaving its top outside the hull (before the bound: 119 cuts, its tip 0.86
 * from the hull, every cut within the volume budget). The bound: no vertex of the part farther than its concavity
 * from its trimmed hull (the distance to a convex set is largest at a corner of a triangle, so none
 * of its surface), while the roof is still trimmed. At 1, 2 and 4 threads the same. */
static void test_trim_thin_fin(void **state) {
    (void)state;
    acd_mesh m;
    box_fin(&m);
    acd_error err;
    const double vol = closed_volume(&m), F = 0.01, bound = 0.5;
    assert_float_equal(vol, 1005, 1e-9);
    acd3d_part part[3];
    const int threads[3] = {1, 2, 4};
    for (int r = 0; r < 3; r++) {
        acd_hull h;
        assert_int_equal(acd_hull_compute(m.vertices, m.nvertices, &h, &err), ACD_OK);
        memset(&part[r], 0, sizeof part[r]);
        part[r].mesh = m; /* (read only) */
        part[r].hull = (acd_mesh){h.vertices, h.nvertices, h.triangles, h.ntriangles};
        part[r].hull_volume = h.volume;
        part[r].volume = vol;
        part[r].concavity = bound;
        h.vertices = NULL, h.triangles = NULL;
        acd_hull_free(&h);
        acd3_trim_stats st;
        assert_int_equal(acd3_trim_hulls(&part[r], 1, vol, F * vol, ACD3_TRIM_MIN_GAIN_REL * vol, 0, &m, NULL,
                                         threads[r], NULL, NULL, &st, &err),
                         ACD_OK);
        acd_hull th;
        assert_int_equal(acd_hull_compute(part[r].hull.vertices, part[r].hull.nvertices, &th, &err), ACD_OK);
        double far = 0;
        for (size_t v = 0; v < m.nvertices; v++) far = fmax(far, hull_distance(&th, m.vertices + 3 * v));
        print_message("thin fin: %zu cuts (%zu refused after the cut), hull %.4f -> %.4f, part outside %.4g, farthest "
                      "vertex %.4f from the hull (bound %.2f)\n",
                      st.cuts, st.refused_far, 1250.0 + 0.5, th.volume, part[r].trimmed_volume, far, bound);
        assert_true(far <= bound * (1 + 1e-9));
        assert_true(st.cuts > 0 && th.volume < 1250.5 - 1);
        acd_hull_free(&th);
    }
    for (int r = 1; r < 3; r++) {
        assert_int_equal(part[0].hull.nvertices, part[r].hull.nvertices);
        assert_memory_equal(part[0].hull.vertices, part[r].hull.vertices, 3 * part[0].hull.nvertices * sizeof(double));
    }
    for (int r = 0; r < 3; r++) acd_mesh_free(&part[r].hull);
    acd_mesh_free(&m);
}

/* The polygon P[0..np) (counterclockwise in x, y) with its triangles C[0..nc) extruded along z from
 * 0 to 10: closed, outward. */
static void extrude(acd_mesh *m, const double (*P)[2], uint32_t np, const uint32_t (*C)[3], size_t nc) {
    m->nvertices = 2 * np;
    m->ntriangles = 2 * nc + 2 * np;
    m->vertices = malloc(3 * m->nvertices * sizeof *m->vertices);
    m->triangles = malloc(3 * m->ntriangles * sizeof *m->triangles);
    assert_true(m->vertices && m->triangles);
    for (uint32_t z = 0; z < 2; z++)
        for (uint32_t i = 0; i < np; i++) {
            double *v = m->vertices + 3 * (size_t)(np * z + i);
            v[0] = P[i][0], v[1] = P[i][1], v[2] = 10.0 * z;
        }
    uint32_t *t = m->triangles;
    for (size_t k = 0; k < nc; k++) { /* the bottom faces -z, the top +z */
        const uint32_t a[6] = {C[k][0], C[k][2], C[k][1], C[k][0] + np, C[k][1] + np, C[k][2] + np};
        memcpy(t, a, sizeof a);
        t += 6;
    }
    for (uint32_t a = 0; a < np; a++) {
        const uint32_t b = (a + 1) % np, q[6] = {a, b, b + np, a, b + np, a + np};
        memcpy(t, q, sizeof q);
        t += 6;
    }
    assert_true(closed_volume(m) > 0);
}

/* The wall check (acd3/trim's wall_check): a cap must not expose a part's internal wall farther than
 * the distance bound from the input's surface. An L-shaped prism (profile: a 10 x 5 foot, x from -5
 * to 5, and a 4.5 x 5 upright on its left, x from -5 to -0.5) cut at x = 0 into A (the upright and
 * the left half of the foot) and B (the right half of the foot, a box). A's face at x = 0 is a wall
 * (B lies across it); its hull's facet from the wall's top edge (0, 5) to the upright's corner (-0.5,
 * 10) leans 5.7 degrees off the wall's plane and spans air over A's ledge, so caps under it pass the
 * ratio test, and a cap at depth d takes a slab of A along the wall down to y = 5 - 10 d: no hull
 * covers that slab (B's hull ends at the wall), and the union's boundary there, the cap's section,
 * runs inside the solid, up to 5 - 10 d from the input's surface. With the bound 0.5 the points of A
 * just off the wall and more than 2 x 0.5 from the input's surface stay inside A's trimmed hull
 * (5 cuts, A's hull leaving out y >= 4.62 there; with wall_check returning 1: 21 cuts, down to y =
 * 3.35, 1122 of the points checked left out; docs/acd3d.md "The distance bound"), while the hull is
 * still trimmed. 1, 2 threads the same. */
static void test_trim_wall_check(void **state) {
    (void)state;
    static const double L[6][2] = {{-5, 0}, {5, 0}, {5, 5}, {-0.5, 5}, {-0.5, 10}, {-5, 10}};
    static const uint32_t LC[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};
    static const double PA[6][2] = {{-5, 0}, {0, 0}, {0, 5}, {-0.5, 5}, {-0.5, 10}, {-5, 10}};
    static const uint32_t AC[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};
    static const double PB[4][2] = {{0, 0}, {5, 0}, {5, 5}, {0, 5}};
    static const uint32_t BC[2][3] = {{0, 1, 2}, {0, 2, 3}};
    acd_mesh in, pm[2];
    extrude(&in, L, 6, LC, 4);
    extrude(&pm[0], PA, 6, AC, 4);
    extrude(&pm[1], PB, 4, BC, 2);
    const double vol = closed_volume(&in), bound = 0.5, F = 0.01;
    assert_float_equal(vol, 725, 1e-9);
    acd_error err;
    double first_hull[2] = {0, 0};
    acd_mesh first = {0};
    for (int threads = 1; threads <= 2; threads++) {
        acd3d_part parts[2];
        memset(parts, 0, sizeof parts);
        for (int i = 0; i < 2; i++) {
            acd_hull h;
            assert_int_equal(acd_hull_compute(pm[i].vertices, pm[i].nvertices, &h, &err), ACD_OK);
            parts[i].mesh = pm[i]; /* (read only) */
            parts[i].hull = (acd_mesh){h.vertices, h.nvertices, h.triangles, h.ntriangles};
            parts[i].hull_volume = h.volume;
            parts[i].volume = closed_volume(&pm[i]);
            h.vertices = NULL, h.triangles = NULL;
            acd_hull_free(&h);
        }
        const double hull0 = parts[0].hull_volume;
        acd3_trim_stats st;
        assert_int_equal(acd3_trim_hulls_within(parts, 2, vol, F * vol, ACD3_TRIM_MIN_GAIN_REL * vol, 0, bound, &in,
                                                NULL, threads, NULL, NULL, &st, &err),
                         ACD_OK);
        acd_hull th;
        assert_int_equal(acd_hull_compute(parts[0].hull.vertices, parts[0].hull.nvertices, &th, &err), ACD_OK);
        /* the lowest point just off the wall (x = -0.001) the trimmed hull leaves out, over z = 1 .. 9 */
        double low = INFINITY;
        size_t out = 0;
        for (int zi = 0; zi <= 16; zi++)
            for (int yi = 0; yi <= 500; yi++) {
                const double p[3] = {-0.001, 5.0 * yi / 500, 1 + 0.5 * zi};
                if (acd_hull_plane_distance(&th, p) > 1e-9) {
                    low = fmin(low, p[1]);
                    out += p[1] >= 1 && p[1] <= 4; /* farther than 2 x the bound from the surface */
                }
            }
        print_message("wall check (%d thread(s)): %zu cuts, A's hull %.4f -> %.4f, charged %.4g; off the wall the "
                      "hull leaves out y >= %.3f (%zu points deeper than 1 in the solid)\n",
                      threads, st.cuts, hull0, th.volume, parts[0].trimmed_volume, low, out);
        assert_true(st.cuts > 0 && th.volume < hull0 - 0.5); /* trimmed */
        assert_int_equal(out, 0);
        if (threads == 1) {
            first_hull[0] = th.volume;
            first = parts[0].hull;
            parts[0].hull = (acd_mesh){0};
        } else {
            first_hull[1] = th.volume;
            assert_int_equal(first.nvertices, parts[0].hull.nvertices);
            assert_memory_equal(first.vertices, parts[0].hull.vertices, 3 * first.nvertices * sizeof(double));
        }
        acd_hull_free(&th);
        for (int i = 0; i < 2; i++) acd_mesh_free(&parts[i].hull);
    }
    assert_true(first_hull[0] == first_hull[1]);
    acd_mesh_free(&first);
    acd_mesh_free(&in);
    for (int i = 0; i < 2; i++) acd_mesh_free(&pm[i]);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_volume_beyond_cube),   cmocka_unit_test(test_volume_beyond_sphere),
        cmocka_unit_test(test_trim_bumpy),           cmocka_unit_test(test_trim_max_vertices),
        cmocka_unit_test(test_trim_refused),         cmocka_unit_test(test_trim_self_crossing),
        cmocka_unit_test(test_trim_beyond_bitwise),  cmocka_unit_test(test_trim_given_trees),
        cmocka_unit_test(test_trim_clip_cone_bitwise), cmocka_unit_test(test_trim_accounts_exact),
        cmocka_unit_test(test_trim_internal_wall),   cmocka_unit_test(test_trim_thin_fin),
        cmocka_unit_test(test_trim_wall_check),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
