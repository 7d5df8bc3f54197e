/* Applications of CoRiSe (Liu, Xi, Lien, CAD 2016, §7; spec corise.md §5), as tests:
 *  - hulls for physics (§7.1): the convex hulls of the parts stand in for the mesh. Asserted: every
 *    vertex of every face lies in its part's hull (so the surface is in the union of hulls: each face
 *    lies in its part's hull by convexity), within ACD_TOL_REL_DIST x diagonal; how many exactly
 *    (acd_orient3d against the hull's triangles) is reported. The volume coverage |M n U| / |M|
 *    (acd_eval_hulls) is measured and reported; it is asserted >= 0.999 only on the dumbbell, whose
 *    cut loop bounds a disc inside both halves' hulls, and shown < 0.9 on a sphere labelled into six
 *    cube patches (the union of surface-patch hulls need not contain the solid; docs/corise.md,
 *    "Applications").
 *  - model repair (§7.3, Fig. 15): 45 % of a real mesh's facets deleted (fixed seed), the rest
 *    segmented, once deleted uniformly at random and once as holes grown over shared edges.
 *    Asserted: it finishes, labels every face, every part is edge-connected and parts are at least
 *    the damaged mesh's edge-components; with holes, the parts beyond one per edge-component stay
 *    under 3 times the intact mesh's part count. Part counts are reported. */
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/eval.h"
#include "acd/hull.h"
#include "acd/mesh.h"
#include "acd/segment.h"
#include "core/predicates.h"
#include "core/rng.h"
#include "core/tolerance.h"
#include "shapes.h"

/* r = 1 - k sin^2(theta): two bulbs along z joined by a waist of radius 1 - k */
static double waist_r(double th, double ph, void *u) {
    (void)ph;
    double k = *(double *)u, s = sin(th);
    return 1.0 - k * s * s;
}

/* ---- face adjacency through shared undirected edges ---- */

typedef struct edge_key {
    uint64_t key;
    uint32_t face;
} edge_key;

static int cmp_edge_key(const void *a, const void *b) {
    const edge_key *x = a, *y = b;
    if (x->key != y->key) return x->key < y->key ? -1 : 1;
    return x->face < y->face ? -1 : x->face > y->face;
}

/* Sorted (edge, face) pairs: faces sharing an edge are consecutive. */
static edge_key *edge_keys(const acd_mesh *m) {
    edge_key *e = malloc(3 * m->ntriangles * sizeof *e);
    assert_non_null(e);
    for (size_t f = 0; f < m->ntriangles; f++) {
        const uint32_t *T = m->triangles + 3 * f;
        for (int k = 0; k < 3; k++) {
            uint64_t a = T[k], b = T[(k + 1) % 3];
            if (a > b) {
                uint64_t t = a;
                a = b;
                b = t;
            }
            e[3 * f + k] = (edge_key){(a << 32) | b, (uint32_t)f};
        }
    }
    qsort(e, 3 * m->ntriangles, sizeof *e, cmp_edge_key);
    return e;
}

static uint32_t uf_find(uint32_t *p, uint32_t x) {
    while (p[x] != x) x = p[x] = p[p[x]];
    return x;
}

/* Edge-components of the faces for which same(label) holds across each shared edge (labels NULL:
 * the whole mesh). Returns the number of components among the faces. */
static size_t components(const acd_mesh *m, const edge_key *e, const uint32_t *labels) {
    size_t n = m->ntriangles;
    uint32_t *p = malloc(n * sizeof *p);
    assert_non_null(p);
    for (size_t f = 0; f < n; f++) p[f] = (uint32_t)f;
    for (size_t i = 0; i + 1 < 3 * n; i++) {
        if (e[i].key != e[i + 1].key) continue;
        uint32_t a = e[i].face, b = e[i + 1].face;
        if (labels && labels[a] != labels[b]) continue;
        a = uf_find(p, a), b = uf_find(p, b);
        if (a != b) p[a] = b;
    }
    size_t c = 0;
    for (size_t f = 0; f < n; f++) c += uf_find(p, (uint32_t)f) == f;
    free(p);
    return c;
}

/* ---- labelling and connectivity of a segmentation ---- */

static void check_labels(const acd_mesh *m, const acd_segment_result *r, size_t *ncomponents) {
    assert_int_equal(r->nfaces, m->ntriangles);
    size_t *count = calloc(r->nparts, sizeof *count);
    assert_non_null(count);
    for (size_t f = 0; f < m->ntriangles; f++) {
        assert_true(r->labels[f] < r->nparts);
        count[r->labels[f]]++;
    }
    for (size_t k = 0; k < r->nparts; k++) {
        assert_true(count[k] > 0);
        assert_int_equal(count[k], r->parts[k].nfaces);
    }
    free(count);
    edge_key *e = edge_keys(m);
    /* every part is one edge-component: the label-respecting components are exactly the parts */
    assert_int_equal(components(m, e, r->labels), r->nparts);
    *ncomponents = components(m, e, NULL);
    assert_true(r->nparts >= *ncomponents);
    free(e);
}

/* ---- hulls of the parts and the exact surface-coverage check ---- */

/* One hull per part, from the part's vertices (as acd_segment does). */
static acd_hull *part_hulls(const acd_mesh *m, const acd_segment_result *r) {
    acd_hull *h = calloc(r->nparts, sizeof *h);
    double *pts = malloc(3 * m->nvertices * sizeof *pts);
    uint32_t *mark = malloc(m->nvertices * sizeof *mark);
    assert_true(h && pts && mark);
    for (size_t v = 0; v < m->nvertices; v++) mark[v] = UINT32_MAX;
    /* faces of each part, gathered by a counting sort on the labels */
    size_t *start = calloc(r->nparts + 1, sizeof *start);
    uint32_t *order = malloc(m->ntriangles * sizeof *order);
    assert_true(start && order);
    for (size_t f = 0; f < m->ntriangles; f++) start[r->labels[f] + 1]++;
    for (size_t k = 0; k < r->nparts; k++) start[k + 1] += start[k];
    size_t *fill = malloc(r->nparts * sizeof *fill);
    assert_non_null(fill);
    memcpy(fill, start, r->nparts * sizeof *fill);
    for (size_t f = 0; f < m->ntriangles; f++) order[fill[r->labels[f]]++] = (uint32_t)f;
    for (size_t k = 0; k < r->nparts; k++) {
        size_t n = 0;
        for (size_t i = start[k]; i < start[k + 1]; i++) {
            const uint32_t *T = m->triangles + 3 * order[i];
            for (int j = 0; j < 3; j++) {
                if (mark[T[j]] == k) continue;
                mark[T[j]] = (uint32_t)k;
                memcpy(pts + 3 * n++, m->vertices + 3 * T[j], 3 * sizeof *pts);
            }
        }
        acd_error err;
        assert_int_equal(acd_hull_compute(pts, n, &h[k], &err), ACD_OK);
    }
    free(fill), free(order), free(start), free(mark), free(pts);
    return h;
}

static void free_hulls(acd_hull *h, size_t n) {
    for (size_t k = 0; k < n; k++) acd_hull_free(&h[k]);
    free(h);
}

/* Every vertex of every face lies in its part's hull. Solid hulls: exactly (acd_orient3d >= 0
 * against every outward hull triangle, whose corners are input points), counted in *exact; all
 * hulls: within the named distance tolerance of the mesh (flat parts, and points qhull leaves a
 * rounding error outside a merged facet). Returns the vertex-face incidences checked. */
static size_t check_surface_covered(const acd_mesh *m, const acd_segment_result *r, const acd_hull *h,
                                    size_t *exact, size_t *flat) {
    acd_scale tol = acd_scale_of_points(m->vertices, m->nvertices, 3);
    size_t checked = 0;
    *exact = *flat = 0;
    for (size_t f = 0; f < m->ntriangles; f++) {
        const acd_hull *H = &h[r->labels[f]];
        for (int j = 0; j < 3; j++) {
            const double *p = m->vertices + 3 * m->triangles[3 * f + j];
            checked++;
            assert_true(acd_hull_plane_distance(H, p) <= tol.dist);
            if (H->dim < 3) {
                (*flat)++;
                continue;
            }
            int inside = 1;
            for (size_t t = 0; t < H->ntriangles && inside; t++) {
                const uint32_t *T = H->triangles + 3 * t;
                inside = acd_orient3d(H->vertices + 3 * T[0], H->vertices + 3 * T[1], H->vertices + 3 * T[2], p) >= 0;
            }
            *exact += inside;
        }
    }
    return checked;
}

typedef struct physics_numbers {
    size_t parts, checked, exact, flat;
    double coverage, iou, excess, hull_ratio;
} physics_numbers;

static physics_numbers physics(const acd_mesh *m, int clamp, double tau) {
    acd_segment_params p = acd_segment_default_params();
    p.tau = tau;
    p.clamp_hull_depth = clamp;
    acd_segment_result r;
    acd_error err;
    assert_int_equal(acd_segment(m, &p, &r, &err), ACD_OK);
    size_t ncomp;
    check_labels(m, &r, &ncomp);
    acd_hull *h = part_hulls(m, &r);
    physics_numbers out = {.parts = r.nparts};
    out.checked = check_surface_covered(m, &r, h, &out.exact, &out.flat);
    acd_eval_params ep = acd_eval_default_params();
    ep.samples = 100000;
    ep.surface_samples = 10000;
    acd_eval_report rep;
    assert_int_equal(acd_eval_hulls(m, h, r.nparts, &ep, &rep, &err), ACD_OK);
    out.coverage = rep.coverage, out.iou = rep.iou, out.excess = rep.excess;
    out.hull_ratio = rep.hull_volume_sum / rep.mesh_volume;
    print_message("[  INFO    ] clamp %d tau %.2f: %zu faces, %zu parts; vertices in their part's hull: %zu of %zu "
                  "exactly (%zu on flat parts, within tolerance); volume coverage %.5f, IoU %.4f, excess %.4f, "
                  "hull sum / mesh %.4f\n",
                  clamp, tau, m->ntriangles, r.nparts, out.exact, out.checked, out.flat, out.coverage, out.iou,
                  out.excess, out.hull_ratio);
    free_hulls(h, r.nparts);
    acd_segment_result_free(&r);
    return out;
}

/* Dumbbell: two parts split at the waist. The cut loop bounds a disc inside both halves' hulls,
 * so the union of the two hulls contains the solid: coverage 1 up to the Monte Carlo inside test. */
static void test_physics_dumbbell(void **state) {
    (void)state;
    double k = 0.7;
    acd_mesh m;
    assert_true(mg_radial(&m, 32, 32, waist_r, &k));
    physics_numbers n = physics(&m, 1, 0.1);
    assert_int_equal(n.parts, 2);
    assert_true(n.coverage >= 0.999);
    assert_true(n.hull_ratio > 1.0);
    acd_mesh_free(&m);
}

static double unit_r(double th, double ph, void *u) { (void)th, (void)ph, (void)u; return 1.0; }

/* Why volume coverage is not asserted on real meshes: a sphere labelled by hand into the six
 * patches of a cube projected onto it (face centroid's dominant axis and sign). Every patch is
 * edge-connected and its hull encloses its faces, yet the six hulls are shallow caps and the
 * centre lies in none (exactly: outside some facet of each). */
static void test_patch_hulls_miss_interior(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(mg_radial(&m, 32, 32, unit_r, NULL));
    acd_segment_result r = {.nfaces = m.ntriangles, .nparts = 6};
    r.labels = malloc(m.ntriangles * sizeof *r.labels);
    r.parts = calloc(6, sizeof *r.parts);
    assert_true(r.labels && r.parts);
    for (size_t f = 0; f < m.ntriangles; f++) {
        double c[3] = {0, 0, 0};
        for (int j = 0; j < 3; j++)
            for (int a = 0; a < 3; a++) c[a] += m.vertices[3 * m.triangles[3 * f + j] + a];
        int best = 0;
        for (int a = 1; a < 3; a++)
            if (fabs(c[a]) > fabs(c[best])) best = a;
        r.labels[f] = (uint32_t)(2 * best + (c[best] < 0));
        r.parts[r.labels[f]].nfaces++;
    }
    size_t ncomp;
    check_labels(&m, &r, &ncomp);
    assert_int_equal(ncomp, 1);
    acd_hull *h = part_hulls(&m, &r);
    size_t exact, flat, checked = check_surface_covered(&m, &r, h, &exact, &flat);
    const double centre[3] = {0, 0, 0};
    for (size_t k = 0; k < 6; k++) {
        assert_int_equal(h[k].dim, 3);
        int outside = 0;
        for (size_t t = 0; t < h[k].ntriangles && !outside; t++) {
            const uint32_t *T = h[k].triangles + 3 * t;
            outside = acd_orient3d(h[k].vertices + 3 * T[0], h[k].vertices + 3 * T[1], h[k].vertices + 3 * T[2],
                                   centre) < 0;
        }
        assert_true(outside);
    }
    acd_eval_params ep = acd_eval_default_params();
    ep.samples = 100000;
    ep.surface_samples = 10000;
    acd_eval_report rep;
    acd_error err;
    assert_int_equal(acd_eval_hulls(&m, h, 6, &ep, &rep, &err), ACD_OK);
    print_message("[  INFO    ] sphere as six cube patches: vertices in their part's hull %zu of %zu exactly; volume "
                  "coverage %.4f, hull sum / sphere %.4f\n",
                  exact, checked, rep.coverage, rep.hull_volume_sum / rep.mesh_volume);
    assert_true(rep.coverage < 0.9);
    free_hulls(h, 6);
    free(r.labels), free(r.parts);
    acd_mesh_free(&m);
}

static int load(acd_mesh *m, const char *name) {
    char path[1024];
    if (!tu_mesh_data(path, sizeof path, name)) return 0;
    acd_error err;
    assert_int_equal(acd_mesh_read(path, m, &err), ACD_OK);
    return 1;
}

/* Real meshes: surface coverage asserted; volume coverage measured and reported, not asserted: the
 * union of the patches' hulls does not contain the solid in general (elephant: 0.86 with the clamp;
 * docs/corise.md, "Applications"). */
static void test_physics_real(void **state) {
    (void)state;
    const char *names[] = {"elephant.off", "camel.off"};
    int ran = 0;
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        acd_mesh m;
        if (!load(&m, names[i])) continue;
        ran = 1;
        print_message("[  INFO    ] %s\n", names[i]);
        physics_numbers a = physics(&m, 1, 0.1), b = physics(&m, 0, 0.1);
        /* sanity of the measurement, not a coverage claim: the union covers most of the solid */
        assert_true(a.coverage > 0.5 && b.coverage > 0.5);
        acd_mesh_free(&m);
    }
    if (!ran) TU_SKIP("no CGAL meshes in data/meshes (run scripts/fetch-data.sh)");
}

/* ---- damaged meshes ---- */

/* A copy of m with a fraction of its facets deleted, chosen by a partial Fisher-Yates shuffle with
 * a fixed seed (vertices kept; unused ones are allowed). */
static void delete_facets(const acd_mesh *m, double fraction, uint64_t seed, acd_mesh *out) {
    size_t n = m->ntriangles, del = (size_t)(fraction * (double)n + 0.5);
    uint32_t *perm = malloc(n * sizeof *perm);
    unsigned char *gone = calloc(n, 1);
    assert_true(perm && gone);
    for (size_t f = 0; f < n; f++) perm[f] = (uint32_t)f;
    acd_rng rng;
    acd_rng_seed(&rng, seed);
    for (size_t i = 0; i < del; i++) {
        size_t j = i + (size_t)acd_rng_below(&rng, n - i);
        uint32_t t = perm[i];
        perm[i] = perm[j], perm[j] = t;
        gone[perm[i]] = 1;
    }
    acd_error err;
    assert_int_equal(acd_mesh_copy(out, m, &err), ACD_OK);
    size_t kept = 0;
    for (size_t f = 0; f < n; f++)
        if (!gone[f]) memmove(out->triangles + 3 * kept++, m->triangles + 3 * f, 3 * sizeof *out->triangles);
    out->ntriangles = kept;
    assert_int_equal(kept, n - del);
    free(perm), free(gone);
}

/* The same fraction deleted as holes: from a random remaining facet (fixed seed), a breadth-first
 * patch of up to `hole` facets over shared edges is deleted, until the fraction is reached. */
static void delete_holes(const acd_mesh *m, double fraction, size_t hole, uint64_t seed, acd_mesh *out) {
    size_t n = m->ntriangles, del = (size_t)(fraction * (double)n + 0.5), ndel = 0;
    edge_key *e = edge_keys(m);
    uint32_t *nb = malloc(3 * n * sizeof *nb), *queue = malloc(n * sizeof *queue);
    unsigned char *gone = calloc(n, 1);
    size_t *deg = calloc(n, sizeof *deg);
    assert_true(nb && queue && gone && deg);
    for (size_t i = 0; i + 1 < 3 * n; i++) {
        if (e[i].key != e[i + 1].key) continue;
        uint32_t a = e[i].face, b = e[i + 1].face;
        if (deg[a] < 3) nb[3 * a + deg[a]++] = b;
        if (deg[b] < 3) nb[3 * b + deg[b]++] = a;
    }
    acd_rng rng;
    acd_rng_seed(&rng, seed);
    while (ndel < del) {
        uint32_t s;
        do s = (uint32_t)acd_rng_below(&rng, n);
        while (gone[s]);
        size_t head = 0, tail = 0, here = 0;
        queue[tail++] = s;
        gone[s] = 1;
        while (head < tail && ndel < del && here < hole) {
            uint32_t f = queue[head++];
            ndel++, here++;
            for (size_t k = 0; k < deg[f]; k++)
                if (!gone[nb[3 * f + k]]) gone[nb[3 * f + k]] = 1, queue[tail++] = nb[3 * f + k];
        }
        for (size_t i = head; i < tail; i++) gone[queue[i]] = 0; /* queued, not deleted */
    }
    acd_error err;
    assert_int_equal(acd_mesh_copy(out, m, &err), ACD_OK);
    size_t kept = 0;
    for (size_t f = 0; f < n; f++)
        if (!gone[f]) memmove(out->triangles + 3 * kept++, m->triangles + 3 * f, 3 * sizeof *out->triangles);
    out->ntriangles = kept;
    assert_int_equal(kept, n - del);
    free(e), free(nb), free(queue), free(gone), free(deg);
}

static void test_damaged_real(void **state) {
    (void)state;
    const char *names[] = {"elephant.off", "camel.off"};
    int ran = 0;
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        acd_mesh m, d;
        if (!load(&m, names[i])) continue;
        ran = 1;
        acd_segment_params p = acd_segment_default_params();
        acd_segment_result r0, r1;
        acd_error err;
        size_t c0, c1;
        assert_int_equal(acd_segment(&m, &p, &r0, &err), ACD_OK);
        check_labels(&m, &r0, &c0);
        delete_facets(&m, 0.45, 20161, &d);
        assert_int_equal(acd_segment(&d, &p, &r1, &err), ACD_OK);
        check_labels(&d, &r1, &c1);
        size_t big = 0; /* parts of more than 1 % of the remaining faces */
        for (size_t k = 0; k < r1.nparts; k++) big += r1.parts[k].nfaces * 100 > d.ntriangles;
        print_message("[  INFO    ] %s tau %.2f: intact %zu faces, %zu parts (%.2f s); 45%% deleted: %zu faces in %zu "
                      "edge-components, %zu parts (%zu with > 1%% of the faces), %zu unresolved (%.2f s)\n",
                      names[i], p.tau, m.ntriangles, r0.nparts, r0.seconds, d.ntriangles, c1, r1.nparts, big,
                      r1.unresolved, r1.seconds);
        acd_segment_result_free(&r1);
        acd_mesh_free(&d);
        /* holes: the edge graph stays mostly connected, and so does the segmentation */
        delete_holes(&m, 0.45, m.ntriangles / 50, 20161, &d);
        assert_int_equal(acd_segment(&d, &p, &r1, &err), ACD_OK);
        check_labels(&d, &r1, &c1);
        big = 0;
        for (size_t k = 0; k < r1.nparts; k++) big += r1.parts[k].nfaces * 100 > d.ntriangles;
        print_message("[  INFO    ] %s: 45%% deleted as holes of <= %zu faces: %zu faces in %zu edge-components, %zu "
                      "parts (%zu with > 1%% of the faces), %zu unresolved (%.2f s)\n",
                      names[i], m.ntriangles / 50, d.ntriangles, c1, r1.nparts, big, r1.unresolved, r1.seconds);
        /* sane: the parts beyond one per edge-component are at most 3 times the intact mesh's parts */
        assert_true(r1.nparts - c1 <= 3 * r0.nparts);
        acd_segment_result_free(&r0), acd_segment_result_free(&r1);
        acd_mesh_free(&d), acd_mesh_free(&m);
    }
    if (!ran) TU_SKIP("no CGAL meshes in data/meshes (run scripts/fetch-data.sh)");
}

/* Always runs: the dumbbell with 45 % of its facets deleted still segments, fully labelled. */
static void test_damaged_dumbbell(void **state) {
    (void)state;
    double k = 0.7;
    acd_mesh m, d;
    assert_true(mg_radial(&m, 32, 32, waist_r, &k));
    delete_facets(&m, 0.45, 20161, &d);
    acd_segment_params p = acd_segment_default_params();
    acd_segment_result r;
    acd_error err;
    size_t c;
    assert_int_equal(acd_segment(&d, &p, &r, &err), ACD_OK);
    check_labels(&d, &r, &c);
    print_message("[  INFO    ] dumbbell, 45%% deleted: %zu faces in %zu edge-components, %zu parts\n", d.ntriangles,
                  c, r.nparts);
    acd_segment_result_free(&r);
    acd_mesh_free(&d), acd_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_physics_dumbbell),
        cmocka_unit_test(test_patch_hulls_miss_interior),
        cmocka_unit_test(test_damaged_dumbbell),
        cmocka_unit_test(test_physics_real),
        cmocka_unit_test(test_damaged_real),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
