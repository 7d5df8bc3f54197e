/* Hole merging of the 2D decomposition (src/acd2/holes.c; dissertation IV.A.2, IV.B; spec
 * ../shared/spec/acd2d.md §4.6).
 *
 * 1. Regression: tests/data/2d/star120-hole-refused.poly was refused ("no hole could be
 *    connected to the outer boundary or another hole": the ray from a principal-axis extreme was
 *    aimed at 2 q - R, rounded off the line through the nearest vertex q, grazed q and ended in
 *    the interior). Every measure at tau 0 and 1 now decomposes it and the independent verifier
 *    (include/acd/verify2d.h, via tests/support/props2d.h) accepts the result; no hole-merge
 *    diagonal crosses or overlaps an input edge (acd_segments_relation).
 * 2. The fallback bridge (rightmost hole vertex, Eberly), forced for every merge: each diagonal
 *    ends at a vertex, meets the input rings and the earlier diagonals only at its ends, and the
 *    merged ring has the polygon's area and n + 2 h vertices. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>

#include "acd/polygon.h"
#include "acd2/holes.h"
#include "core/predicates.h"
#include "core/tolerance.h"
#include "props2d.h"

static void read_one(const char *rel, acd_polygon_set *set) {
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", ACD_SOURCE_DIR, rel);
    acd_error err;
    if (acd_polygon_set_read_file(set, path, ACD_POLY_FORMAT_AUTO, NULL, &err) != ACD_OK) fail_msg("%s: %s", rel, err.message);
    assert_true(set->count >= 1);
    if (acd_polygon_validate(&set->polygons[0], 0, &err) != ACD_OK) fail_msg("%s: %s", rel, err.message);
}

static int same_pt(const double *a, const double *b) { return a[0] == b[0] && a[1] == b[1]; }

/* Segment (a, b) meets segment (c, d) only at common end points (exact). */
static int meets_only_at_ends(acd_vec2 a, acd_vec2 b, acd_vec2 c, acd_vec2 d) {
    const double A[2] = {a.x, a.y}, B[2] = {b.x, b.y}, C[2] = {c.x, c.y}, D[2] = {d.x, d.y};
    acd_seg_relation rel = acd_segments_relation(A, B, C, D);
    if (rel == ACD_SEG_DISJOINT) return 1;
    if (rel != ACD_SEG_TOUCH) return 0;
    return same_pt(A, C) || same_pt(A, D) || same_pt(B, C) || same_pt(B, D);
}

/* Does segment (a, b) cross or overlap an edge of p (PROPER or OVERLAP)? */
static int crosses_input(const acd_polygon *p, acd_vec2 a, acd_vec2 b, size_t *ring, size_t *edge) {
    const double A[2] = {a.x, a.y}, B[2] = {b.x, b.y};
    for (size_t r = 0; r < p->nrings; r++) {
        const acd_vec2 *q = acd_polygon_ring(p, r);
        size_t n = acd_polygon_ring_size(p, r);
        for (size_t k = 0; k < n; k++) {
            const double C[2] = {q[k].x, q[k].y}, D[2] = {q[(k + 1) % n].x, q[(k + 1) % n].y};
            acd_seg_relation rel = acd_segments_relation(A, B, C, D);
            if (rel == ACD_SEG_PROPER || rel == ACD_SEG_OVERLAP) {
                *ring = r;
                *edge = k;
                return 1;
            }
        }
    }
    return 0;
}

static void test_refused_star_regression(void **state) {
    (void)state;
    acd_polygon_set set;
    read_one("tests/data/2d/star120-hole-refused.poly", &set);
    const acd_polygon *p = &set.polygons[0];
    assert_int_equal(p->nrings, 2);
    p2d_stats st = {0};
    for (int m = 0; m < 4; m++) {
        const double taus[2] = {0, 1};
        for (int t = 0; t < 2; t++) {
            p2d_check(p, "star120-hole-refused", (acd2d_measure)m, taus[t], 1, &st);
            /* the hole-merge diagonals of the tree cross no input edge */
            acd2d_params prm = acd2d_default_params();
            prm.measure = (acd2d_measure)m;
            prm.tau = taus[t];
            acd2d_result res;
            acd_error err;
            if (acd2d_decompose(p, &prm, &res, &err) != ACD_OK) continue; /* counted as refused above */
            size_t merges = 0;
            for (size_t k = 0; k < res.nnodes; k++) {
                const acd2d_node *nd = &res.nodes[k];
                if (!nd->is_hole_merge) continue;
                merges++;
                size_t r, e;
                if (crosses_input(p, nd->cut[0], nd->cut[1], &r, &e))
                    fail_msg("measure %s, tau %g: hole-merge diagonal (%g, %g)-(%g, %g) crosses ring %zu edge %zu",
                             acd2d_measure_name((acd2d_measure)m), taus[t], nd->cut[0].x, nd->cut[0].y, nd->cut[1].x,
                             nd->cut[1].y, r, e);
            }
            assert_int_equal(merges, 1);
            acd2d_result_free(&res);
        }
    }
    print_message("    %zu runs checked (%zu components), %zu unsupported, %zu refused\n", st.runs, st.components,
                  st.unsupported, st.refused);
    assert_int_equal(st.refused, 0);
    assert_int_equal(st.unsupported, 0);
    assert_int_equal(st.runs, 8);
    acd_polygon_set_free(&set);
}

/* Merges every hole of p by the fallback bridge alone and checks the diagonals and the result. */
static void check_forced_bridges(const acd_polygon *p, const char *name) {
    size_t np = acd_polygon_num_points(p), nh = p->nrings - 1;
    double *conc = calloc(np, sizeof *conc);
    acd_vec2 *segs = malloc((nh + 1) * 2 * sizeof *segs);
    assert_non_null(conc);
    assert_non_null(segs);
    acd_scale sc = acd_scale_of_points(&p->points[0].x, np, 2);
    acd2_holes hs;
    acd_error err;
    assert_int_equal(acd2_holes_init(&hs, p, conc, 4 * sc.extent + 1, &err), ACD_OK);
    hs.force_bridge = 1;
    for (size_t s = 0; s < nh; s++) {
        int into_outer;
        double val;
        if (acd2_holes_step(&hs, &segs[2 * s], &into_outer, &val, &err) != ACD_OK) fail_msg("%s: merge %zu: %s", name, s, err.message);
        acd_vec2 a = segs[2 * s], b = segs[2 * s + 1];
        size_t r, e;
        if (crosses_input(p, a, b, &r, &e))
            fail_msg("%s: bridge %zu (%g, %g)-(%g, %g) crosses ring %zu edge %zu", name, s, a.x, a.y, b.x, b.y, r, e);
        for (size_t r2 = 0; r2 < p->nrings; r2++) {
            const acd_vec2 *q = acd_polygon_ring(p, r2);
            size_t n = acd_polygon_ring_size(p, r2);
            for (size_t k = 0; k < n; k++)
                if (!meets_only_at_ends(a, b, q[k], q[(k + 1) % n]))
                    fail_msg("%s: bridge %zu touches ring %zu edge %zu away from its ends", name, s, r2, k);
        }
        for (size_t s2 = 0; s2 < s; s2++)
            if (!meets_only_at_ends(a, b, segs[2 * s2], segs[2 * s2 + 1]))
                fail_msg("%s: bridge %zu meets bridge %zu away from their ends", name, s, s2);
    }
    assert_int_equal(hs.alive, 0);
    /* bridges end at vertices: no new point, two copies per hole */
    assert_int_equal(hs.next_id, (int64_t)np);
    assert_int_equal(hs.outer.n, np + 2 * nh);
    double want = 0;
    for (size_t r = 0; r < p->nrings; r++) want += acd2_ring_area2(acd_polygon_ring(p, r), acd_polygon_ring_size(p, r));
    double got = acd2_ring_area2(hs.outer.p, hs.outer.n);
    if (!(fabs(got - want) <= 1e-9 * fabs(want))) fail_msg("%s: merged area %.17g, polygon %.17g", name, got, want);
    acd2_holes_free(&hs);
    free(conc);
    free(segs);
}

static void test_forced_bridge_files(void **state) {
    (void)state;
    acd_polygon_set set;
    read_one("tests/data/2d/star120-hole-refused.poly", &set);
    check_forced_bridges(&set.polygons[0], "star120-hole-refused");
    acd_polygon_set_free(&set);
    static const char *const lien[] = {"hole1.poly", "hole2.poly", "hole3.poly", "hole4.poly", "hole5.poly", "torus1.poly"};
    size_t found = 0;
    for (size_t i = 0; i < sizeof lien / sizeof lien[0]; i++) {
        char rel[256], buf[1024];
        snprintf(rel, sizeof rel, "polygons-lien/%s", lien[i]);
        const char *path = tu_shared_data(buf, sizeof buf, rel);
        if (!path) continue;
        acd_error err;
        if (acd_polygon_set_read_file(&set, path, ACD_POLY_FORMAT_AUTO, NULL, &err) != ACD_OK) fail_msg("%s: %s", rel, err.message);
        for (size_t k = 0; k < set.count; k++) {
            if (acd_polygon_validate(&set.polygons[k], k, &err) != ACD_OK) fail_msg("%s: %s", rel, err.message);
            if (set.polygons[k].nrings > 1) check_forced_bridges(&set.polygons[k], rel);
        }
        acd_polygon_set_free(&set);
        found++;
    }
    print_message("    %zu shared hole files checked\n", found);
}

/* A square with a 3 x 3 grid of square holes: rightmost vertices tie in x (ties by y), and the
 * rays of the left columns meet the slits and rings of the holes merged before them. */
static void test_forced_bridge_grid(void **state) {
    (void)state;
    acd_vec2 outer[4] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    acd_vec2 holes[9][4];
    const acd_vec2 *rings[10] = {outer};
    size_t rs[10] = {4};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            acd_vec2 *h = holes[3 * i + j];
            double x0 = 1 + 3 * i, y0 = 1 + 3 * j;
            h[0] = (acd_vec2){x0, y0};
            h[1] = (acd_vec2){x0, y0 + 2};
            h[2] = (acd_vec2){x0 + 2, y0 + 2};
            h[3] = (acd_vec2){x0 + 2, y0};
            rings[1 + 3 * i + j] = h;
            rs[1 + 3 * i + j] = 4;
        }
    acd_polygon p;
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(&p, rings, rs, 10, &err), ACD_OK);
    if (acd_polygon_validate(&p, 0, &err) != ACD_OK) fail_msg("grid invalid: %s", err.message);
    check_forced_bridges(&p, "grid 3x3");
    /* and the whole decomposition, verified */
    p2d_stats st = {0};
    for (int m = 0; m < 4; m++) p2d_check(&p, "grid 3x3", (acd2d_measure)m, 0, 1, &st);
    assert_int_equal(st.refused, 0);
    acd_polygon_free(&p);
}

/* The end P of the edge met by the ray is hidden by a reflex vertex of a notch inside the
 * triangle (M, I, P): the bridge must go to that vertex, not to P (Eberly's case). */
static void test_forced_bridge_hidden_end(void **state) {
    (void)state;
    /* ray from M = (2, 5) meets x = 10 at I = (10, 5); P = (10, 0); the notch (5,0)-(6,4)-(7,0)
     * pokes into the triangle and crosses the segment M P */
    const acd_vec2 outer[] = {{0, 0}, {5, 0}, {6, 4}, {7, 0}, {10, 0}, {10, 10}, {0, 10}};
    const acd_vec2 hole[] = {{1, 4}, {1, 5}, {2, 5}, {2, 4}};
    const acd_vec2 *rings[2] = {outer, hole};
    size_t rs[2] = {7, 4};
    acd_polygon p;
    acd_error err;
    assert_int_equal(acd_polygon_from_rings(&p, rings, rs, 2, &err), ACD_OK);
    if (acd_polygon_validate(&p, 0, &err) != ACD_OK) fail_msg("notch polygon invalid: %s", err.message);
    check_forced_bridges(&p, "hidden end");
    p2d_stats st = {0};
    for (int m = 0; m < 4; m++) p2d_check(&p, "hidden end", (acd2d_measure)m, 0, 1, &st);
    assert_int_equal(st.refused, 0);
    acd_polygon_free(&p);
}

int main(void) {
    (void)p2d_sweep_file; /* shared helper, not used here */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_refused_star_regression),
        cmocka_unit_test(test_forced_bridge_files),
        cmocka_unit_test(test_forced_bridge_grid),
        cmocka_unit_test(test_forced_bridge_hidden_end),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
