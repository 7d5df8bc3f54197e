/* Tests of the public segmentation API (acd/segment.h, src/corise/segment_api.c): a dumbbell
 * splits into its two bulbs, a convex shape stays one part, every face is labelled and the
 * parts cover the faces, per-part hulls enclose their faces, parts meet tau, output is bitwise
 * deterministic and the same for 1-4 threads, bad params are refused; a triangle soup and
 * reversed faces are welded and oriented first (the clean mesh's labels). */
// ctest: TIMEOUT 600
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/segment.h"
#include "corise/corise.h"
#include "shapes.h"

static double sphere_r(double th, double ph, void *u) { (void)th, (void)ph, (void)u; return 1.0; }
/* r = 1 - k sin^2(theta): two bulbs along z joined by a waist of radius 1 - k */
static double waist_r(double th, double ph, void *u) {
    (void)ph;
    double k = *(double *)u, s = sin(th);
    return 1.0 - k * s * s;
}

static void check_result(const acd_mesh *m, const acd_segment_result *r, double tau) {
    assert_int_equal(r->nfaces, m->ntriangles);
    size_t sum = 0;
    for (size_t k = 0; k < r->nparts; k++) sum += r->parts[k].nfaces;
    assert_int_equal(sum, m->ntriangles);
    for (size_t f = 0; f < m->ntriangles; f++) assert_true(r->labels[f] < r->nparts);
    /* parts numbered by their smallest face */
    uint32_t next = 0;
    for (size_t f = 0; f < m->ntriangles; f++) {
        assert_true(r->labels[f] <= next);
        if (r->labels[f] == next) next++;
    }
    for (size_t k = 0; k < r->nparts; k++) {
        const acd_segment_part *p = &r->parts[k];
        assert_true(p->nfaces > 0);
        if (r->unresolved == 0) assert_true(p->concavity_rel <= tau);
        assert_true(fabs(p->concavity - p->concavity_rel * r->scale) <= 1e-12 * (1 + p->concavity));
        if (p->hull_dim == 3) {
            assert_true(p->hull_volume > 0);
            /* the hull encloses the part's vertices (planes from the triangles) */
            for (size_t f = 0; f < m->ntriangles; f++) {
                if (r->labels[f] != k) continue;
                for (int c = 0; c < 3; c++) {
                    const double *q = m->vertices + 3 * (size_t)m->triangles[3 * f + c];
                    for (size_t t = 0; t < p->hull.ntriangles; t++) {
                        const uint32_t *T = p->hull.triangles + 3 * t;
                        const double *a = p->hull.vertices + 3 * (size_t)T[0], *b = p->hull.vertices + 3 * (size_t)T[1],
                                     *d = p->hull.vertices + 3 * (size_t)T[2];
                        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
                        double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
                        double s = n[0] * (q[0] - a[0]) + n[1] * (q[1] - a[1]) + n[2] * (q[2] - a[2]);
                        assert_true(s <= 1e-9 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));
                    }
                }
            }
        }
    }
    double hv = 0;
    for (size_t k = 0; k < r->nparts; k++) hv += r->parts[k].hull_volume;
    assert_true(fabs(hv - r->hull_volume) <= 1e-12 * hv);
    assert_true(r->seconds >= 0);
}

static void test_dumbbell_splits_in_two(void **state) {
    (void)state;
    double k = 0.7;
    acd_mesh m;
    assert_true(mg_radial(&m, 32, 32, waist_r, &k));
    acd_segment_params p = acd_segment_default_params();
    p.tau = 0.1;
    acd_segment_result r;
    acd_error err;
    assert_int_equal(acd_segment(&m, &p, &r, &err), ACD_OK);
    check_result(&m, &r, p.tau);
    assert_int_equal(r.nparts, 2);
    /* one bulb each side of the waist: faces away from the waist are labelled by the sign of z */
    int lab[2] = {-1, -1};
    size_t wrong = 0;
    for (size_t f = 0; f < m.ntriangles; f++) {
        double z = 0;
        for (int c = 0; c < 3; c++) z += m.vertices[3 * (size_t)m.triangles[3 * f + c] + 2] / 3;
        if (fabs(z) < 0.3) continue; /* near the waist: either side */
        int side = z > 0;
        if (lab[side] < 0) lab[side] = (int)r.labels[f];
        wrong += r.labels[f] != (uint32_t)lab[side];
    }
    assert_int_equal(wrong, 0);
    assert_true(lab[0] >= 0 && lab[1] >= 0 && lab[0] != lab[1]);
    /* the valley test re-run per part: the two parts pass, the whole dumbbell as one part does not */
    acd_corise_params c = acd_corise_default_params();
    c.clamp_hull_depth = p.clamp_hull_depth;
    double conc[2];
    assert_int_equal(acd_corise_parts_concavity(&m, &c, r.labels, 2, conc, &err), ACD_OK);
    assert_memory_equal(&conc[0], &r.parts[0].concavity_rel, sizeof(double));
    assert_memory_equal(&conc[1], &r.parts[1].concavity_rel, sizeof(double));
    uint32_t *one = calloc(m.ntriangles, sizeof *one);
    assert_non_null(one);
    assert_int_equal(acd_corise_parts_concavity(&m, &c, one, 1, conc, &err), ACD_OK);
    assert_true(conc[0] > p.tau);
    one[3] = 1; /* label out of range */
    assert_int_equal(acd_corise_parts_concavity(&m, &c, one, 1, conc, &err), ACD_ERR_INVALID_ARGUMENT);
    free(one);
    /* the hulls of the two bulbs hold less than the dumbbell's hull, more than the dumbbell */
    assert_true(r.hull_volume > r.mesh_volume);
    acd_segment_result_free(&r);
    acd_mesh_free(&m);
}

static void test_convex_stays_one(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 24, 12, sphere_r, NULL));
    acd_segment_params p = acd_segment_default_params();
    acd_segment_result r;
    acd_error err;
    assert_int_equal(acd_segment(&m, &p, &r, &err), ACD_OK);
    check_result(&m, &r, p.tau);
    assert_int_equal(r.nparts, 1);
    assert_int_equal(r.cuts, 0);
    /* one part: its hull is the sphere's polyhedron itself */
    assert_true(fabs(r.hull_volume - r.mesh_volume) <= 1e-9 * r.mesh_volume);
    assert_true(r.parts[0].concavity_rel <= 1e-9);
    acd_segment_result_free(&r);
    acd_mesh_free(&m);
}

static void test_cross_deterministic(void **state) {
    (void)state;
    /* a 3D cross of voxels: six arms of 2 cells around a centre cell, 5 x 5 x 5 */
    unsigned char occ[125];
    for (int z = 0; z < 5; z++)
        for (int y = 0; y < 5; y++)
            for (int x = 0; x < 5; x++) occ[(z * 5 + y) * 5 + x] = (x == 2) + (y == 2) + (z == 2) >= 2;
    acd_mesh m;
    assert_true(mg_voxels(&m, occ, 5, 5, 5));
    acd_segment_params p = acd_segment_default_params();
    p.tau = 0.1;
    acd_segment_result a, b;
    acd_error err;
    assert_int_equal(acd_segment(&m, &p, &a, &err), ACD_OK);
    assert_int_equal(acd_segment(&m, &p, &b, &err), ACD_OK);
    check_result(&m, &a, p.tau);
    assert_true(a.nparts >= 2);
    assert_int_equal(a.nparts, b.nparts);
    assert_memory_equal(a.labels, b.labels, m.ntriangles * sizeof *a.labels);
    for (size_t k = 0; k < a.nparts; k++) {
        assert_memory_equal(&a.parts[k].concavity, &b.parts[k].concavity, sizeof(double));
        assert_memory_equal(&a.parts[k].hull_volume, &b.parts[k].hull_volume, sizeof(double));
        assert_int_equal(a.parts[k].hull.ntriangles, b.parts[k].hull.ntriangles);
        assert_memory_equal(a.parts[k].hull.vertices, b.parts[k].hull.vertices,
                            3 * a.parts[k].hull.nvertices * sizeof(double));
    }
    acd_segment_result_free(&a);
    acd_segment_result_free(&b);
    acd_mesh_free(&m);
}

/* Results bit for bit equal: labels, counts, per-part concavity, volumes and hulls. */
static void assert_same(const acd_mesh *m, const acd_segment_result *a, const acd_segment_result *b) {
    assert_int_equal(a->nparts, b->nparts);
    assert_int_equal(a->cuts, b->cuts);
    assert_int_equal(a->depth, b->depth);
    assert_int_equal(a->unresolved, b->unresolved);
    assert_memory_equal(a->labels, b->labels, m->ntriangles * sizeof *a->labels);
    assert_memory_equal(&a->hull_volume, &b->hull_volume, sizeof(double));
    for (size_t k = 0; k < a->nparts; k++) {
        assert_memory_equal(&a->parts[k].concavity_rel, &b->parts[k].concavity_rel, sizeof(double));
        assert_memory_equal(&a->parts[k].hull_volume, &b->parts[k].hull_volume, sizeof(double));
        assert_int_equal(a->parts[k].hull.nvertices, b->parts[k].hull.nvertices);
        assert_int_equal(a->parts[k].hull.ntriangles, b->parts[k].hull.ntriangles);
        assert_memory_equal(a->parts[k].hull.vertices, b->parts[k].hull.vertices,
                            3 * a->parts[k].hull.nvertices * sizeof(double));
        assert_memory_equal(a->parts[k].hull.triangles, b->parts[k].hull.triangles,
                            3 * a->parts[k].hull.ntriangles * sizeof(uint32_t));
    }
}

typedef struct progress_log {
    double f[4096]; /* the fractions of the loop's milestones (stage "corise") */
    size_t n;
    size_t calls;    /* all the calls (the polls within the steps too) */
    int decreasing;  /* a fraction below the one before */
    double last;
} progress_log;

static int log_cb(void *u, double f, const char *s) {
    progress_log *l = u;
    if (l->calls++ && f < l->last) l->decreasing = 1;
    l->last = f;
    if (!strcmp(s, "corise") && l->n < 4096) l->f[l->n++] = f;
    return 0;
}

/* The same result, and the same sequence of the loop's milestone calls (stage "corise": each
 * wave's start, the phases of a lone part, each final part), for 1, 2, 3 and 4 threads: on a noisy
 * sphere with two bulbs (many bridges: the first part's valleys are shared among the threads) and,
 * when fetched, the elephant (20 parts in waves of several parts). The polls within the steps come
 * from the calling thread's share of the work, so their number may depend on the threads; the
 * fractions never decrease. */
static void test_threads_identical(void **state) {
    (void)state;
    for (int mesh = 0; mesh < 2; mesh++) {
        acd_mesh m;
        if (mesh == 0) {
            double k = 0.6;
            assert_true(mg_radial(&m, 48, 24, waist_r, &k));
            for (size_t v = 0; v < m.nvertices; v++) /* deterministic wobble: bridges of every length */
                for (int c = 0; c < 3; c++) m.vertices[3 * v + c] *= 1 + 0.05 * sin(7.0 * (double)v + c);
        } else {
            char path[1024];
            acd_error err;
            if (!tu_mesh_data(path, sizeof path, "elephant.off")) {
                print_message("elephant.off missing (scripts/fetch-data.sh): only the synthetic mesh\n");
                break;
            }
            assert_int_equal(acd_mesh_read(path, &m, &err), ACD_OK);
        }
        acd_segment_result ref;
        static progress_log lref, lrun;
        for (int t = 1; t <= 4; t++) {
            acd_segment_params p = acd_segment_default_params();
            p.threads = t;
            p.progress = log_cb;
            acd_segment_result r;
            acd_error err;
            progress_log *l = t == 1 ? &lref : &lrun;
            memset(l, 0, sizeof *l);
            p.progress_user = l;
            assert_int_equal(acd_segment(&m, &p, t == 1 ? &ref : &r, &err), ACD_OK);
            if (t == 1) {
                check_result(&m, &ref, p.tau);
                print_message("mesh %d: %zu faces, %zu parts, %zu cuts, %zu progress calls (%zu milestones)\n", mesh,
                              m.ntriangles, ref.nparts, ref.cuts, lref.calls, lref.n);
                assert_false(lref.decreasing);
                assert_true(ref.nparts >= 2);
                continue;
            }
            assert_same(&m, &ref, &r);
            assert_false(lrun.decreasing);
            assert_int_equal(lrun.n, lref.n);
            assert_memory_equal(lrun.f, lref.f, lref.n * sizeof(double));
            acd_segment_result_free(&r);
        }
        acd_segment_result_free(&ref);
        acd_mesh_free(&m);
    }
}

/* Input preparation (params.prepare, docs/corise.md "Input preparation"): a triangle soup of the
 * torus (every face its own three vertices, as OBJ exporters write meshes split at texture seams),
 * the torus with every face reversed and with every other face reversed give the clean torus's
 * labels face for face, and say what was done; the input is left untouched. With prepare = 0 the
 * soup and the reversed torus are segmented as given: other labels (the soup one part per face),
 * which is what the preparation is there for. */
static void test_prepare_soup_and_flips(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_torus(&m, 24, 12, 1.0, 0.4));
    size_t nf = m.ntriangles;
    acd_segment_params p = acd_segment_default_params();
    p.tau = 0.3; /* 4 parts */
    p.clamp_hull_depth = 0;
    acd_segment_result ref;
    acd_error err;
    assert_int_equal(acd_segment(&m, &p, &ref, &err), ACD_OK);
    check_result(&m, &ref, p.tau);
    print_message("torus: %zu faces, %zu parts\n", nf, ref.nparts);
    assert_true(ref.nparts >= 2 && ref.nparts <= 8);
    /* a clean mesh is segmented as it is: nothing merged or flipped, result.mesh is its copy */
    assert_int_equal(ref.vertices_merged, 0);
    assert_int_equal(ref.faces_flipped, 0);
    assert_int_equal(ref.mesh.nvertices, m.nvertices);
    assert_int_equal(ref.mesh.ntriangles, nf);
    assert_memory_equal(ref.mesh.vertices, m.vertices, 3 * m.nvertices * sizeof(double));
    assert_memory_equal(ref.mesh.triangles, m.triangles, 3 * nf * sizeof(uint32_t));
    assert_true(ref.mesh_volume > 0);

    /* the soup: 3 nf vertices, in face order */
    acd_mesh soup = {malloc(9 * nf * sizeof(double)), 3 * nf, malloc(3 * nf * sizeof(uint32_t)), nf};
    assert_non_null(soup.vertices);
    assert_non_null(soup.triangles);
    for (size_t i = 0; i < 3 * nf; i++) {
        memcpy(soup.vertices + 3 * i, m.vertices + 3 * (size_t)m.triangles[i], 3 * sizeof(double));
        soup.triangles[i] = (uint32_t)i;
    }
    acd_mesh keep;
    assert_int_equal(acd_mesh_copy(&keep, &soup, &err), ACD_OK);
    acd_segment_result r;
    assert_int_equal(acd_segment(&soup, &p, &r, &err), ACD_OK);
    assert_int_equal(r.nparts, ref.nparts);
    assert_memory_equal(r.labels, ref.labels, nf * sizeof *r.labels);
    assert_int_equal(r.vertices_merged, 3 * nf - m.nvertices);
    assert_int_equal(r.faces_flipped, 0);
    assert_int_equal(r.mesh.nvertices, m.nvertices);
    assert_true(fabs(r.mesh_volume - ref.mesh_volume) <= 1e-12 * ref.mesh_volume);
    check_result(&r.mesh, &r, p.tau);
    assert_memory_equal(soup.vertices, keep.vertices, 9 * nf * sizeof(double)); /* input untouched */
    assert_memory_equal(soup.triangles, keep.triangles, 3 * nf * sizeof(uint32_t));
    acd_segment_result_free(&r);
    assert_null(r.mesh.vertices); /* freed with the result */
    p.prepare = 0;
    assert_int_equal(acd_segment(&soup, &p, &r, &err), ACD_OK);
    assert_int_equal(r.nparts, nf); /* as before: every face its own part */
    assert_int_equal(r.vertices_merged, 0);
    acd_segment_result_free(&r);
    p.prepare = 1;

    /* every face reversed (inside out), then every other face reversed */
    for (int mode = 0; mode < 2; mode++) {
        acd_mesh f;
        assert_int_equal(acd_mesh_copy(&f, &m, &err), ACD_OK);
        size_t flipped = 0;
        for (size_t t = 0; t < nf; t++)
            if (mode == 0 || t % 2) {
                uint32_t *T = f.triangles + 3 * t, x = T[1];
                T[1] = T[2];
                T[2] = x;
                flipped++;
            }
        assert_int_equal(acd_segment(&f, &p, &r, &err), ACD_OK);
        assert_int_equal(r.nparts, ref.nparts);
        assert_memory_equal(r.labels, ref.labels, nf * sizeof *r.labels);
        assert_int_equal(r.faces_flipped, flipped);
        assert_int_equal(r.vertices_merged, 0);
        assert_true(fabs(r.mesh_volume - ref.mesh_volume) <= 1e-12 * ref.mesh_volume);
        /* the mesh segmented faces the way the clean torus does */
        for (size_t t = 0; t < nf; t++) {
            const uint32_t *a = r.mesh.triangles + 3 * t, *b = m.triangles + 3 * t;
            int k = a[0] == b[0] ? 0 : a[0] == b[1] ? 1 : 2;
            assert_true(a[0] == b[k] && a[1] == b[(k + 1) % 3] && a[2] == b[(k + 2) % 3]);
        }
        acd_segment_result_free(&r);
        if (mode == 0) { /* as given: valleys and ridges swap */
            p.prepare = 0;
            assert_int_equal(acd_segment(&f, &p, &r, &err), ACD_OK);
            assert_int_equal(r.faces_flipped, 0);
            assert_true(r.mesh_volume < 0);
            assert_true(r.nparts != ref.nparts || memcmp(r.labels, ref.labels, nf * sizeof *r.labels) != 0);
            acd_segment_result_free(&r);
            p.prepare = 1;
        }
        acd_mesh_free(&f);
    }
    acd_mesh_free(&keep);
    acd_mesh_free(&soup);
    acd_segment_result_free(&ref);
    acd_mesh_free(&m);
}

/* Closed shells are not welded and a shell inside another is a cavity: the torus twice, coincident
 * and each with its own vertices, stays two closed tori (twice the parts, nothing merged); a sphere
 * inside a larger one, both facing outward, has its faces turned inward. */
static void test_prepare_closed_shells(void **state) {
    (void)state;
    acd_mesh m;
    acd_error err;
    assert_true(mg_torus(&m, 24, 12, 1.0, 0.4));
    size_t nv = m.nvertices, nf = m.ntriangles;
    acd_segment_params p = acd_segment_default_params();
    p.tau = 0.3;
    p.clamp_hull_depth = 0;
    acd_segment_result one, two;
    assert_int_equal(acd_segment(&m, &p, &one, &err), ACD_OK);
    acd_mesh d = {malloc(6 * nv * sizeof(double)), 2 * nv, malloc(6 * nf * sizeof(uint32_t)), 2 * nf};
    assert_non_null(d.vertices);
    assert_non_null(d.triangles);
    memcpy(d.vertices, m.vertices, 3 * nv * sizeof(double));
    memcpy(d.vertices + 3 * nv, m.vertices, 3 * nv * sizeof(double));
    for (size_t i = 0; i < 3 * nf; i++) {
        d.triangles[i] = m.triangles[i];
        d.triangles[3 * nf + i] = m.triangles[i] + (uint32_t)nv;
    }
    assert_int_equal(acd_segment(&d, &p, &two, &err), ACD_OK);
    assert_int_equal(two.vertices_merged, 0);
    assert_int_equal(two.faces_flipped, 0);
    assert_int_equal(two.nparts, 2 * one.nparts);
    acd_segment_result_free(&one);
    acd_segment_result_free(&two);
    acd_mesh_free(&d);
    acd_mesh_free(&m);

    acd_mesh in, out;
    assert_true(mg_radial(&in, 16, 8, sphere_r, NULL));
    assert_true(mg_radial(&out, 16, 8, sphere_r, NULL));
    for (size_t i = 0; i < 3 * out.nvertices; i++) out.vertices[i] *= 2;
    acd_mesh both = {malloc(3 * (in.nvertices + out.nvertices) * sizeof(double)), in.nvertices + out.nvertices,
                     malloc(3 * (in.ntriangles + out.ntriangles) * sizeof(uint32_t)), in.ntriangles + out.ntriangles};
    assert_non_null(both.vertices);
    assert_non_null(both.triangles);
    memcpy(both.vertices, out.vertices, 3 * out.nvertices * sizeof(double));
    memcpy(both.vertices + 3 * out.nvertices, in.vertices, 3 * in.nvertices * sizeof(double));
    memcpy(both.triangles, out.triangles, 3 * out.ntriangles * sizeof(uint32_t));
    for (size_t i = 0; i < 3 * in.ntriangles; i++)
        both.triangles[3 * out.ntriangles + i] = in.triangles[i] + (uint32_t)out.nvertices;
    acd_segment_result r;
    assert_int_equal(acd_segment(&both, &p, &r, &err), ACD_OK);
    assert_int_equal(r.faces_flipped, in.ntriangles);
    for (size_t t = 0; t < both.ntriangles; t++) { /* the outer sphere's faces kept, the inner's reversed */
        const uint32_t *a = r.mesh.triangles + 3 * t, *b = both.triangles + 3 * t;
        int k = a[0] == b[0] ? 0 : a[0] == b[1] ? 1 : 2, dir = t < out.ntriangles ? 1 : 2;
        assert_true(a[0] == b[k] && a[1] == b[(k + dir) % 3] && a[2] == b[(k + 2 * dir) % 3]);
    }
    /* the solid between the spheres: the outer ball less the inner one */
    assert_true(fabs(r.mesh_volume - (mg_volume(&out) - mg_volume(&in))) <= 1e-12 * mg_volume(&out));
    acd_segment_result_free(&r);
    acd_mesh_free(&both);
    acd_mesh_free(&in);
    acd_mesh_free(&out);
}

static int cancel_cb(void *u, double f, const char *s) {
    (void)f, (void)s;
    ++*(int *)u;
    return 1;
}

static void test_bad_params(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 8, 4, sphere_r, NULL));
    acd_segment_result r;
    acd_error err;
    acd_segment_params p;
    memset(&p, 0, sizeof p); /* no cookie */
    p.tau = 0.1;
    assert_int_equal(acd_segment(&m, &p, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err.message, "cookie"));
    assert_null(r.labels);
    const double bad_tau[] = {-1, NAN, INFINITY};
    for (int i = 0; i < 3; i++) {
        p = acd_segment_default_params();
        p.tau = bad_tau[i];
        assert_int_equal(acd_segment(&m, &p, &r, &err), ACD_ERR_INVALID_ARGUMENT);
        assert_non_null(strstr(err.message, "tau"));
    }
    p = acd_segment_default_params();
    p.alpha = 1.5;
    assert_int_equal(acd_segment(&m, &p, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    p = acd_segment_default_params();
    p.concave_weight = 0;
    assert_int_equal(acd_segment(&m, &p, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    p = acd_segment_default_params();
    p.max_depth = 0;
    assert_int_equal(acd_segment(&m, &p, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    p = acd_segment_default_params();
    p.threads = 100000; /* crashed inside libgomp */
    assert_int_equal(acd_segment(&m, &p, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(err.message, "threads"));
    p = acd_segment_default_params();
    assert_int_equal(acd_segment(NULL, &p, &r, &err), ACD_ERR_INVALID_ARGUMENT);
    assert_int_equal(acd_segment(&m, &p, NULL, &err), ACD_ERR_INVALID_ARGUMENT);
    /* bad mesh: index out of range, NaN coordinate, no faces */
    m.triangles[4] = (uint32_t)m.nvertices;
    assert_int_equal(acd_segment(&m, &p, &r, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "triangle 1"));
    m.triangles[4] = 0;
    double keep = m.vertices[5];
    m.vertices[5] = NAN;
    assert_int_equal(acd_segment(&m, &p, &r, &err), ACD_ERR_INVALID_INPUT);
    /* beyond ACD_COORD_MAX: refused (a 1e300 tetrahedron was segmented with scale 1 and null
     * volumes) */
    m.vertices[5] = 1e300;
    assert_int_equal(acd_segment(&m, &p, &r, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, "magnitude"));
    m.vertices[5] = keep;
    /* a model below ACD_EXTENT_MIN: refused (decisions changed under an exact scale of 2^-266) */
    {
        acd_mesh tiny;
        assert_int_equal(acd_mesh_copy(&tiny, &m, &err), ACD_OK);
        for (size_t i = 0; i < 3 * tiny.nvertices; i++) tiny.vertices[i] = ldexp(tiny.vertices[i], -266);
        assert_int_equal(acd_segment(&tiny, &p, &r, &err), ACD_ERR_INVALID_INPUT);
        assert_non_null(strstr(err.message, "below the supported"));
        acd_mesh_free(&tiny);
    }
    size_t nt = m.ntriangles;
    m.ntriangles = 0;
    assert_int_equal(acd_segment(&m, &p, &r, &err), ACD_ERR_DEGENERATE);
    m.ntriangles = nt;
    /* cancellation */
    int calls = 0;
    p.progress = cancel_cb;
    p.progress_user = &calls;
    assert_int_equal(acd_segment(&m, &p, &r, &err), ACD_ERR_CANCELLED);
    assert_int_equal(calls, 1);
    assert_null(r.labels);
    acd_segment_result_free(&r);
    acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dumbbell_splits_in_two),
        cmocka_unit_test(test_convex_stays_one),
        cmocka_unit_test(test_cross_deterministic),
        cmocka_unit_test(test_threads_identical),
        cmocka_unit_test(test_bad_params),
        cmocka_unit_test(test_prepare_soup_and_flips),
        cmocka_unit_test(test_prepare_closed_shells),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
