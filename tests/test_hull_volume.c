/* Tests of geom3/hull_volume (acd_hull_volume_fast, the hull volume acd3/budget ranks its planes
 * by): it agrees with acd_hull_compute (qhull) within 1e-9 relative on random, coplanar-section,
 * box-surface and grid sets, by itself (the qhull fallback hardly used), is 0 for a flat set and
 * for fewer than 4 points; a workspace reused across sets of different sizes gives the same
 * volumes as a fresh one; the sweep (acd_hull_volume_sweep) gives each query the volume of its set
 * computed alone, also on the degenerate sets fuzz_hull_volume found; the volumes' bits are those of
 * the code before its speed work (test_volume_bits). */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "geom3/hull_volume.h"

/* A deterministic generator for the point sets below. */
static double lcg01(unsigned long long *s) {
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) / 9007199254740992.0;
}

static double qhull_volume(const double *p, size_t n) {
    acd_hull h;
    assert_int_equal(acd_hull_compute(p, n, &h, NULL), ACD_OK);
    double v = h.dim == 3 ? h.volume : 0;
    acd_hull_free(&h);
    return v;
}

/* The scores' own hull volume against acd_hull_compute (qhull): points in a box, one side of a
 * sphere's sample with the section's crossings (coplanar, as score_plane makes them), a grid (every
 * point on a face or an edge of another), a flat set and too few points. */
static double hv(const double *p, size_t n, int *nfb) {
    int fb = 0;
    acd_hull_volume_ws w;
    memset(&w, 0, sizeof w);
    double v = acd_hull_volume_fast(p, n, &w, &fb);
    acd_hull_volume_ws_free(&w);
    *nfb += fb;
    return v;
}

static void test_hull_volume(void **state) {
    (void)state;
    int nfb = 0; /* sets qhull computed instead (a horizon that was not one cycle) */
    unsigned long long seed = 12345;
    size_t n = 1200;
    double *p = malloc(3 * n * sizeof *p);
    assert_non_null(p);
    for (int round = 0; round < 20; round++) {
        for (size_t i = 0; i < 3 * n; i++) p[i] = 10 + 3 * lcg01(&seed);
        size_t m = 50 + (size_t)round * 55;
        double a = hv(p, m, &nfb), b = qhull_volume(p, m);
        assert_true(fabs(a - b) <= 1e-9 * b);
    }
    for (int round = 0; round < 20; round++) {
        double c = -0.8 + 0.08 * round; /* the plane z = c */
        size_t m = 0;
        for (int i = 0; i < 700; i++) {
            double z = 2 * lcg01(&seed) - 1, ph = 6.283185307179586 * lcg01(&seed), r = sqrt(1 - z * z);
            if (z < c) continue;
            p[3 * m] = r * cos(ph), p[3 * m + 1] = 0.6 * r * sin(ph), p[3 * m + 2] = z;
            m++;
        }
        for (int i = 0; i < 300; i++) { /* on the section's boundary, some twice */
            double ph = 6.283185307179586 * (i / 2) / 150.0, r = sqrt(1 - c * c);
            p[3 * m] = r * cos(ph), p[3 * m + 1] = 0.6 * r * sin(ph), p[3 * m + 2] = c;
            m++;
        }
        double a = hv(p, m, &nfb), b = qhull_volume(p, m);
        assert_true(fabs(a - b) <= 1e-9 * b);
    }
    for (int round = 0; round < 40; round++) { /* a box's faces sampled, cut by a tilted plane */
        size_t m = 0;
        double nz[3] = {0.3, -0.2 + 0.01 * round, 1}, c = 0.1 * (round % 7) - 0.3;
        for (int i = 0; i < 900; i++) {
            double q[3] = {2 * lcg01(&seed) - 1, 2 * lcg01(&seed) - 1, 2 * lcg01(&seed) - 1};
            int ax = i % 3;
            q[ax] = q[ax] < 0 ? -1 : 1;
            if (nz[0] * q[0] + nz[1] * q[1] + nz[2] * q[2] < c) continue;
            memcpy(p + 3 * m++, q, sizeof q);
        }
        for (int e = 0; e < 12 && m + 40 < n; e++) /* crossings of the box's edges and faces */
            for (int i = 0; i < 40; i++) {
                double t = 2 * lcg01(&seed) - 1, q[3];
                int ax = e % 3;
                q[ax] = t, q[(ax + 1) % 3] = e / 3 % 2 ? 1 : -1;
                q[(ax + 2) % 3] = 0;
                /* on the plane along the face x[(ax+1)%3] = +-1: solve for x[(ax+2)%3] */
                int k = (ax + 2) % 3;
                double rest = c - nz[ax] * q[ax] - nz[(ax + 1) % 3] * q[(ax + 1) % 3];
                q[k] = rest / nz[k];
                if (fabs(q[k]) > 1) continue;
                memcpy(p + 3 * m++, q, sizeof q);
            }
        if (m < 4) continue;
        double a = hv(p, m, &nfb), b = qhull_volume(p, m);
        assert_true(fabs(a - b) <= 1e-9 * b);
    }
    size_t m = 0;
    for (int x = 0; x < 6; x++)
        for (int y = 0; y < 6; y++)
            for (int z = 0; z < 6; z++) p[3 * m] = x, p[3 * m + 1] = y, p[3 * m + 2] = z, m++;
    assert_true(fabs(hv(p, m, &nfb) - 125) <= 1e-9 * 125);
    for (size_t i = 0; i < m; i++) p[3 * i + 2] = 0.5 * p[3 * i] - p[3 * i + 1]; /* flat */
    assert_true(hv(p, m, &nfb) == 0);
    assert_true(hv(p, 3, &nfb) == 0);
    print_message("hull volumes: %d of 84 sets by the qhull fallback\n", nfb);
    assert_true(nfb <= 4); /* the own hull, not the fallback, is what agreed */
    free(p);
}

/* One workspace for sets of growing and shrinking sizes: the same volumes as a fresh workspace. */
static void test_workspace_reuse(void **state) {
    (void)state;
    unsigned long long seed = 777;
    size_t n = 900;
    double *p = malloc(3 * n * sizeof *p);
    assert_non_null(p);
    for (size_t i = 0; i < 3 * n; i++) p[i] = lcg01(&seed);
    acd_hull_volume_ws w;
    memset(&w, 0, sizeof w);
    const size_t sizes[] = {900, 10, 400, 5, 900, 60};
    for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++) {
        int nfb = 0;
        double a = acd_hull_volume_fast(p, sizes[k], &w, NULL), b = hv(p, sizes[k], &nfb);
        assert_true(a == b);
        assert_true(a > 0);
    }
    acd_hull_volume_ws_free(&w);
    free(p);
}

/* pts sorted along dir (insertion: the sets are small) */
static void sort_along(double *pts, size_t n, const double dir[3]) {
    for (size_t i = 1; i < n; i++) {
        double x[3];
        memcpy(x, pts + 3 * i, sizeof x);
        double s = dir[0] * x[0] + dir[1] * x[1] + dir[2] * x[2];
        size_t j = i;
        for (; j > 0; j--) {
            const double *y = pts + 3 * (j - 1);
            if (!(dir[0] * y[0] + dir[1] * y[1] + dir[2] * y[2] > s)) break;
            memcpy(pts + 3 * j, y, sizeof x);
        }
        memcpy(pts + 3 * j, x, sizeof x);
    }
}

/* One sweep along dir over pts (kind 0: a box's volume, 1: a sphere's surface, 2: a box's faces),
 * nine planes, each with points on it inside the set (the sections' crossings, some twice): every
 * query the sweep computes agrees with acd_hull_volume_fast on its set within 1e-9; returns how
 * many it computed. */
static int sweep_round(int kind, const double dir[3], unsigned long long *seed) {
    enum { N = 800, NX = 120, NQ = 9 };
    double *pts = malloc(3 * N * sizeof *pts), *xs = malloc(3 * NQ * NX * sizeof *xs), *set = malloc(3 * (N + NX) * sizeof *set);
    assert_true(pts && xs && set);
    for (size_t i = 0; i < N; i++) {
        double *q = pts + 3 * i;
        if (kind == 1) {
            double z = 2 * lcg01(seed) - 1, ph = 6.283185307179586 * lcg01(seed), r = sqrt(1 - z * z);
            q[0] = r * cos(ph), q[1] = 0.7 * r * sin(ph), q[2] = z;
        } else {
            for (int k = 0; k < 3; k++) q[k] = 2 * lcg01(seed) - 1;
            if (kind == 2) q[i % 3] = q[i % 3] < 0 ? -1 : 1;
        }
    }
    sort_along(pts, N, dir);
    double lo = dir[0] * pts[0] + dir[1] * pts[1] + dir[2] * pts[2];
    double hi = dir[0] * pts[3 * (N - 1)] + dir[1] * pts[3 * (N - 1) + 1] + dir[2] * pts[3 * (N - 1) + 2];
    size_t cnt[NQ], xb[NQ], xe[NQ];
    /* two directions across dir, for the planes' points */
    double u[3] = {dir[1], -dir[0], 0};
    if (fabs(dir[2]) > 0.9) u[0] = 0, u[1] = dir[2], u[2] = -dir[1];
    double ul = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int k = 0; k < 3; k++) u[k] /= ul;
    double v[3] = {dir[1] * u[2] - dir[2] * u[1], dir[2] * u[0] - dir[0] * u[2], dir[0] * u[1] - dir[1] * u[0]};
    for (int q = 0; q < NQ; q++) {
        double c = lo + (hi - lo) * (q + 1) / (NQ + 1);
        size_t k = 0;
        while (k < N && dir[0] * pts[3 * k] + dir[1] * pts[3 * k + 1] + dir[2] * pts[3 * k + 2] - c < 0) k++;
        cnt[q] = k;
        xb[q] = (size_t)q * NX, xe[q] = xb[q] + NX;
        for (int j = 0; j < NX; j++) { /* a ring on the plane (inside the set's extent), each point twice */
            double a = 6.283185307179586 * (j / 2) / (NX / 2), r = 0.3 + 0.1 * (q % 3);
            double *x = xs + 3 * (xb[q] + (size_t)j);
            for (int d = 0; d < 3; d++) x[d] = c * dir[d] + r * (cos(a) * u[d] + 0.8 * sin(a) * v[d]);
        }
    }
    acd_hull_volume_ws w;
    memset(&w, 0, sizeof w);
    double vol[NQ];
    assert_int_equal(acd_hull_volume_sweep(pts, N, dir, cnt, xs, xb, xe, NQ, vol, &w), 0);
    /* some queries only (acd_hull_volume_sweep_some): those asked for get the whole sweep's bits
     * (a skipped query's points are not added, so the hull the next one grows from is the same),
     * the others -4; masks: every other query (either phase), the first, the last, scattered */
    for (int mk = 0; mk < 5; mk++) {
        unsigned char need[NQ];
        for (int q = 0; q < NQ; q++)
            need[q] = mk < 2 ? (q + mk) % 2 == 0 : mk == 2 ? q == 0 : mk == 3 ? q == NQ - 1 : (q * 7 + 3) % 5 < 2;
        double some[NQ];
        assert_int_equal(acd_hull_volume_sweep_some(pts, N, dir, cnt, xs, xb, xe, NQ, need, some, &w), 0);
        for (int q = 0; q < NQ; q++) {
            if (need[q]) assert_memory_equal(&some[q], &vol[q], sizeof(double));
            else assert_true(some[q] == -4);
        }
    }
    int done = 0;
    for (int q = 0; q < NQ; q++) {
        memcpy(set, pts, 3 * cnt[q] * sizeof *set);
        memcpy(set + 3 * cnt[q], xs + 3 * xb[q], 3 * NX * sizeof *set);
        double ref = acd_hull_volume_fast(set, cnt[q] + NX, &w, NULL);
        if (vol[q] == -3) continue;
        assert_true(fabs(vol[q] - ref) <= 1e-9 * ref);
        done++;
    }
    acd_hull_volume_ws_free(&w);
    free(pts), free(xs), free(set);
    return done;
}

static void test_sweep(void **state) {
    (void)state;
    unsigned long long seed = 4242;
    int done[3] = {0, 0, 0};
    for (int round = 0; round < 12; round++) {
        double dir[3] = {0.2 * (round % 4) - 0.3, 0.1 * round - 0.5, 1};
        if (round % 3 == 2) dir[0] = dir[1] = 0; /* along an axis: a box's faces parallel and across */
        double l = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
        for (int k = 0; k < 3; k++) dir[k] /= l;
        for (int kind = 0; kind < 3; kind++) done[kind] += sweep_round(kind, dir, &seed);
    }
    print_message("sweep queries computed: box %d, sphere %d, box faces %d of 108 each\n", done[0], done[1], done[2]);
    /* the sweep, not the caller's fallback, computed most of them */
    assert_true(done[0] >= 100 && done[1] >= 100);
    /* fewer than 4 points before the first plane: left to the caller */
    double p[3 * 6] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2}, d[3] = {0, 0, 1}, x[3] = {0.2, 0.2, 0.5};
    size_t cnt[1] = {3}, xb[1] = {0}, xe[1] = {1};
    double vol[1];
    acd_hull_volume_ws w;
    memset(&w, 0, sizeof w);
    assert_int_equal(acd_hull_volume_sweep(p, 6, d, cnt, x, xb, xe, 1, vol, &w), 0);
    assert_true(vol[0] == -3);
    acd_hull_volume_ws_free(&w);
}

/* The hull's vertices as the own Quickhull finds them (acd_hull_volume_vertices): on random sets
 * (in a ball, in a box, with points inside) the flagged points' hull is the whole set's (qhull's
 * volumes within 1e-9), every vertex of qhull's hull is flagged and no point well inside is; a flat
 * set has none. */
static void test_vertices(void **state) {
    (void)state;
    unsigned long long seed = 77;
    enum { N = 400 };
    double *pts = malloc(3 * N * sizeof *pts), *sub = malloc(3 * N * sizeof *sub);
    unsigned char flag[N];
    acd_hull_volume_ws w;
    memset(&w, 0, sizeof w);
    for (int kind = 0; kind < 3; kind++) {
        for (int i = 0; i < N; i++) {
            double *p = pts + 3 * i;
            do {
                for (int k = 0; k < 3; k++) p[k] = 2 * lcg01(&seed) - 1;
            } while (kind == 0 && p[0] * p[0] + p[1] * p[1] + p[2] * p[2] > 1);
            if (kind == 2 && i % 2) /* half the points well inside */
                for (int k = 0; k < 3; k++) p[k] *= 0.3;
        }
        size_t nh = 0;
        assert_int_equal(acd_hull_volume_vertices(pts, N, &w, flag, &nh), 1);
        size_t ns = 0, nf = 0;
        for (int i = 0; i < N; i++)
            if (flag[i]) memcpy(sub + 3 * ns++, pts + 3 * i, sizeof(double[3]));
        for (int i = 0; i < N; i++) nf += flag[i];
        assert_true(nf == nh && nh >= 4 && nh < N);
        double all = qhull_volume(pts, N), part = qhull_volume(sub, ns);
        assert_true(fabs(all - part) <= 1e-9 * all);
        acd_hull H;
        memset(&H, 0, sizeof H);
        assert_int_equal(acd_hull_compute(pts, N, &H, NULL), ACD_OK);
        for (size_t k = 0; k < H.nvertices; k++) assert_true(flag[H.source[k]]);
        acd_hull_free(&H);
        if (kind == 2)
            for (int i = 1; i < N; i += 2) assert_false(flag[i]);
    }
    for (int i = 0; i < N; i++) pts[3 * i + 2] = 0.5; /* flat */
    size_t nh = 0;
    assert_int_equal(acd_hull_volume_vertices(pts, N, &w, flag, &nh), 0);
    acd_hull_volume_ws_free(&w);
    free(pts), free(sub);
}

/* Coordinates at any scale: fuzz_hull_volume's nine points (a sliver at 2e84, a cluster at 1e-42)
 * and a tetrahedron at 1e-70 and 1e90 get qhull's volume (the own Quickhull's cross products would
 * overflow or underflow: such sets go to qhull), 0 before that fix for the nine; a slab far from
 * the origin gets its volume (moved to its centre first), 0 before. */
static void test_extreme_scales(void **state) {
    (void)state;
    const double nine[27] = {-6.290423992676007e-10, 2.1026533892325537e+84, 2.1026533892325537e+84,
                             5.256633473081384e+83, 5.256633473081384e+83, 5.262562028615726e+83,
                             1.684635518523213e-43, 8.96831024570393e-44, 1.0410273767909543e-42,
                             1.0410273767909543e-42, 5.256633000831295e+83, 5.256633473081384e+83,
                             5.262562028615726e+83, 1.684635518523213e-43, 8.96831024570393e-44,
                             1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
                             1.0410273767909543e-42, 1.0410273767909543e-42, 1.3980433222694975e-76,
                             3.6947213095772724e-57, 9.515194426837388e-43, 1.0411210059817749e-42,
                             1.0409895966853888e-42, 1.0410273767909543e-42, 1.0410273767909543e-42};
    acd_hull_volume_ws w;
    memset(&w, 0, sizeof w);
    double ref = qhull_volume(nine, 9); /* exact: 1.0934454242429589e248 (rational arithmetic) */
    assert_true(fabs(ref - 1.0934454242429589e248) <= 1e-9 * ref);
    double v = acd_hull_volume_fast(nine, 9, &w, NULL);
    assert_true(fabs(v - ref) <= 1e-9 * ref);
    const double scales[2] = {1e-70, 1e90};
    for (int c = 0; c < 2; c++) {
        double t[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
        for (int i = 0; i < 12; i++) t[i] *= scales[c];
        double r = qhull_volume(t, 4), f = acd_hull_volume_fast(t, 4, &w, NULL);
        assert_true(r > 0 && fabs(f - r) <= 1e-9 * r);
    }
    /* a slab 1 x 1 x 0.05 at 1e7 from the origin (a part of a scan in UTM coordinates): the
     * tolerances follow the coordinates' magnitude, so before the set was moved to its centre it
     * came out flat (0) */
    unsigned long long seed = 5;
    double slab[3 * 60];
    for (int i = 0; i < 60; i++) {
        slab[3 * i] = 1e7 + lcg01(&seed);
        slab[3 * i + 1] = -3e7 + lcg01(&seed);
        slab[3 * i + 2] = 2e7 + 0.05 * lcg01(&seed);
    }
    double rs = qhull_volume(slab, 60), fs = acd_hull_volume_fast(slab, 60, &w, NULL);
    assert_true(rs > 0.02 && fabs(fs - rs) <= 1e-6 * rs);
    acd_hull_volume_ws_free(&w);
}

/* Whether the sweep of the n points pts along dir with the nq queries (cnt, xs[xb..xe)) succeeds and
 * every query it computes (vol[q], -3 when left) is within tol of qhull's volume of that query's set
 * (the prefix and its extra points). */
static int sweep_matches_qhull(const double *pts, size_t n, const double dir[3], const size_t *cnt, const double *xs,
                               const size_t *xb, const size_t *xe, int nq, double tol, double *vol) {
    acd_hull_volume_ws w;
    memset(&w, 0, sizeof w);
    size_t mx = 0;
    for (int q = 0; q < nq; q++) mx = cnt[q] + xe[q] - xb[q] > mx ? cnt[q] + xe[q] - xb[q] : mx;
    double *set = malloc(3 * (mx + 1) * sizeof *set);
    int ok = set && acd_hull_volume_sweep(pts, n, dir, cnt, xs, xb, xe, nq, vol, &w) == 0;
    for (int q = 0; q < nq && ok; q++) {
        size_t m = cnt[q] + xe[q] - xb[q];
        memcpy(set, pts, 3 * cnt[q] * sizeof *set);
        if (xe[q] > xb[q]) memcpy(set + 3 * cnt[q], xs + 3 * xb[q], 3 * (xe[q] - xb[q]) * sizeof *set);
        double ref;
        if (acd_hull_volume(set, m, &ref, NULL) != ACD_OK || vol[q] == -3) continue;
        ok = fabs(vol[q] - ref) <= tol;
    }
    free(set);
    acd_hull_volume_ws_free(&w);
    return ok;
}

/* fuzz_hull_volume's queries on 23 points sorted along (68, -56, 105) with the 20 section points xs:
 * prefixes of 2, 5, ..., 23 points, each with a few of xs. Whether every query the sweep computes is
 * within the target's tolerance of qhull's volume (1e-6 x extent^2 x max(extent, magnitude)), and the
 * last two are computed. */
static int sweep_fuzz_queries(const double *pts, const double *xs) {
    const size_t cnt[8] = {2, 5, 8, 11, 14, 17, 20, 23}, xb[8] = {0, 5, 9, 9, 9, 11, 17, 20}, xe[8] = {5, 9, 9, 9, 11, 17, 20, 20};
    double dir[3] = {68, -56, 105}, l = sqrt(68.0 * 68 + 56 * 56 + 105 * 105);
    for (int k = 0; k < 3; k++) dir[k] /= l;
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) lo[k] = hi[k] = pts[k];
    for (int i = 1; i < 23; i++)
        for (int k = 0; k < 3; k++) lo[k] = fmin(lo[k], pts[3 * i + k]), hi[k] = fmax(hi[k], pts[3 * i + k]);
    double ext = 0, mag = 0;
    for (int k = 0; k < 3; k++) ext = fmax(ext, hi[k] - lo[k]), mag = fmax(mag, fmax(fabs(lo[k]), fabs(hi[k])));
    double tol = 1e-6 * ext * ext * fmax(ext, mag); /* fuzz_hull_volume's HV_FUZZ_TOL_REL */
    double vol[8];
    return sweep_matches_qhull(pts, 23, dir, cnt, xs, xb, xe, 8, tol, vol) && vol[6] > 0 && vol[7] > 0;
}

/* fuzz_hull_volume's sweep underestimate (fuzz/corpus/hull_volume/sweep_thin_prefix): 23 points at
 * 1e-42 sorted along dir (most on the plane x = y, 1.6e-8 of the extent off it, near-duplicates),
 * eight queries. The prefix of 17 points is a hull that thin: point 19 lies 6.5e-3 of the extent
 * beyond its rim but within the tolerance of every facet, so it was taken as inside and forgotten;
 * point 18's cone then replaced the rim, and the prefix of 20 and every query after missed it
 * (queries 6 and 7: 0.3% below qhull's volume, 700 times the target's tolerance). The sweep now
 * keeps such points and tests them against the facets made later (hv_near_retest). Every query the
 * sweep computes is within the target's tolerance of qhull's volume, and the last two are computed. */
static void test_sweep_thin_prefix(void **state) {
    (void)state;
    static const double pts[3 * 23] = {
        1.3980432860952889e-76, 1.3980432860952889e-76, 1.107644006727337e-47,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.3980433222694975e-76,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.6936477909996416e-43,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.6936477909996416e-43,
        1.0410273767909543e-42, 1.0410273767961745e-42, 2.6025684419773857e-43,
        1.0410273767909543e-42, 1.0410273767909543e-42, 2.6025684419773857e-43,
        1.2444927205786585e-47, 1.2460995198351858e-47, 1.0410273783105702e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273764568587e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767892822e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767896492e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909605e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410814307844512e-42,
        1.0411149579449746e-42, 1.0410273767909543e-42, 1.0410273767896492e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0478587068045377e-42,
        1.0410273767941761e-42, 1.3980432860933274e-76, 1.0410273767175843e-42,
        1.0410276106494882e-42, 1.5707759177945867e-76, 1.0410273767909531e-42,
        1.0410869042724818e-42, 6.014732326702936e-67, 1.0410273767906677e-42
    };
    static const double xs[3 * 20] = {
        9.766534336036376e-43, 1.0940412123569798e-42, 6.996383741366631e-44,
        9.766534336036376e-43, 1.0940412123569798e-42, 6.996383741366631e-44,
        9.4210622334128836e-43, 1.1224918561076642e-42, 1.0751094548869556e-43,
        9.4210622334023007e-43, 1.1224918561033153e-42, 1.0751094548706155e-43,
        -3.5045160806985238e-43, 2.8862991640454038e-43, 4.99869649418054e-43,
        1.041027376789896e-42, 1.0410273767918257e-42, 2.6025684419610453e-43,
        -2.5153045462018643e-43, 2.0716543709305077e-43, 6.5261554812709693e-43,
        7.4426391656471001e-43, 1.2854208146243318e-42, 5.8278968051927566e-43,
        7.4426391643835903e-43, 1.2854208147283856e-42, 5.8278968065659843e-43,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410068313816635e-42, 1.0410442965397819e-42, 1.0410497062553994e-42,
        1.0410933995075602e-42, 1.0410451307982368e-42, 1.0409940880259946e-42,
        1.038430853165884e-42, 1.0431656903645414e-42, 1.0438493688540617e-42,
        8.2999558279306089e-43, 1.7379088917738897e-43, 7.1516945950998e-43,
        8.2999575905610181e-43, 1.7379093660631822e-43, 7.1516937065410646e-43,
        8.3004045732585157e-43, 1.7380295630898959e-43, 7.1514683371131223e-43,
        8.3259210641813115e-43, 1.7165257560380173e-43, 7.1917879746045607e-43,
        8.325922826811719e-43, 1.71652623032731e-43, 7.1917870860458253e-43,
        8.3263698095092182e-43, 1.7166464273540235e-43, 7.191561716617883e-43
    };
    assert_true(sweep_fuzz_queries(pts, xs));
}

/* fuzz_hull_volume's second sweep underestimate (fuzz/corpus/hull_volume/sweep_thin_prefix2, a
 * mutation of the set above; the same queries). Point 13 of the prefix of 14 is 1.6e-53 (1.5e-11 of
 * the extent, within the tolerance) above facet (4, 6, 10) and 2.2e-47 beyond vertex 10, nearly on
 * the line of edge (10, 6): the cone over the horizon edge (10, 6) made facet (10, 6, 13), whose
 * plane is y = const while (4, 6, 10) is tilted, so vertex 4 lay 1.1e-44 (1.1e-2 of the extent) above
 * it: a fold, the hull no longer convex. Point 19 (9e-5 of the extent above facet (4, 6, 10)) was then
 * never tested against that facet, and queries 6 and 7 came out 1.33e-131 (11 times the target's
 * tolerance) below qhull's volume. A step whose new facet has its horizon facet's third vertex above
 * it is now numerically ambiguous (the prefix's hull built again from scratch). */
static void test_sweep_fold(void **state) {
    (void)state;
    static const double pts[3 * 23] = {
        1.3980432860952889e-76, 1.3980432860952889e-76, 1.107644006727337e-47,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.3980433222694975e-76,
        1.0409897442638362e-42, 1.0410273767909543e-42, 1.6936477909996416e-43,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.6951804611949969e-43,
        1.0410273767909543e-42, 1.0522377645055528e-42, 2.6025684419773857e-43,
        1.0410273767909543e-42, 1.0410273767961745e-42, 2.6025684419773857e-43,
        1.3980432860952889e-76, 1.0410273767909531e-42, 1.0410814307844512e-42,
        1.0410273767909543e-42, 2.0049457978885926e-76, 1.3980432860952889e-76,
        1.2444927205786585e-47, 1.2460995198351858e-47, 1.0410273783105702e-42,
        1.0410273767909543e-42, 1.0410273767178709e-42, 1.0409897442638362e-42,
        1.0410054815024492e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273764568587e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767896492e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410273767909543e-42, 1.0410273762167275e-42, 1.0410273767909543e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0478587068045377e-42,
        1.0410272912657054e-42, 1.3980432860933274e-76, 1.0410273767175843e-42,
        1.0410276106494882e-42, 1.5707759177945867e-76, 1.0410273767909531e-42,
        1.0410869042724818e-42, 6.014732326702936e-67, 1.0410273767906677e-42
    };
    static const double xs[3 * 20] = {
        9.7662506446780998e-43, 1.0940335836817993e-42, 6.9978141179629702e-44,
        9.7659517826589558e-43, 1.0940891873410026e-42, 7.0027151338159007e-44,
        9.4437873632490886e-43, 1.1318307625364136e-42, 1.1101997288987444e-43,
        9.4210622334128836e-43, 1.1224918561076642e-42, 1.0751094548869556e-43,
        -1.3945226646364721e-43, 1.1558704197610156e-42, 8.2575072521558424e-43,
        1.0387548638073336e-42, 1.0428988580768032e-42, 2.567478167965597e-43,
        -4.2803625997601872e-44, 1.0762774217301546e-42, 9.7498759652344826e-43,
        9.2664422322878801e-43, 9.4197891168842767e-44, -1.7662104594158018e-43,
        -2.5380296760380701e-43, 2.090369183736795e-43, 6.491065207259181e-43,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42,
        1.0410273766745499e-42, 1.0410273763125899e-42, 1.0410273766112122e-42,
        1.0384308531658816e-42, 1.0431656903645435e-42, 1.043849368854058e-42,
        8.2999551831774982e-43, 1.737908718394928e-43, 7.1516949201853532e-43,
        8.2999575905609942e-43, 1.737909366063202e-43, 7.151693706541028e-43,
        8.3004045732584918e-43, 1.7380295630899154e-43, 7.1514683371130856e-43,
        8.3259204194282247e-43, 1.7165255826590361e-43, 7.1917882996901505e-43,
        8.325922826811719e-43, 1.71652623032731e-43, 7.1917870860458253e-43,
        8.3263698095092182e-43, 1.7166464273540235e-43, 7.191561716617883e-43
    };
    assert_true(sweep_fuzz_queries(pts, xs));
}

/* fuzz_hull_volume (fuzz/corpus/hull_volume/fold_per_set; fuzzrun2, 2026-11-27): eight points, a
 * corner of a cube of side a = 1.67 with a few points moved by 3e-7 to 8e-5 of a and the zero
 * coordinates 1e-94 (the fuzz input is these times 2^173). The per-set Quickhull
 * (acd_hull_volume_fast) added point 5, 1.2e-8 above the facet (4, 0, 7) (70 tolerances) and as
 * near the line of its edge (4, 7); then point 1, 3.9e-7 of a above (0, 6, 7) and 3.9e-7 off the
 * line of the horizon edge (7, 0), made the facet (7, 0, 1), which point 5 (the third vertex of
 * the horizon facet (0, 7, 5)) lay 1.4e-4 above: a fold (as the sweep's, test_sweep_fold), and
 * point 3, tested against (0, 2, 6) alone, was never tested against the folded facets: the volume
 * 2.79e-5 below qhull's (the fuzz target's slack is 1e-6 of extent^3). The fold check the sweep
 * made now runs in the per-set hull too: the set goes to qhull. */
static void test_fold_per_set(void **state) {
    (void)state;
    static const double pts[3 * 8] = {
        -0x1.acacacacacacap+0, -0x1.acacacacacacap+0, -0x1.acacacacacacap+0,
        -0x1.acaca37373737p+0, -0x1.acacacacacacap+0, -0x1.acacacacacacap+0,
        -0x1.acacacacacacap+0, 0x1.73737370e3737p-313, 0x1.7373737373737p-313,
        0x1.7373737373737p-313, -0x1.acaca37373737p+0, -0x1.acacacacacacap+0,
        -0x1.acacacacacacap+0, -0x1.acacacacacacap+0, 0x1.acacacacacacap-304,
        -0x1.aca37373737cap+0, -0x1.acacacacacacap+0, 0x1.7cacacacacacap-313,
        0x1.7cacacacacacap-313, 0x1.7373737373737p-313, 0x1.7373737373737p-313,
        0x1.7373737373737p-313, -0x1.aca3737373737p+0, 0x1.73737cacacacap-313,
    };
    for (int e = 0; e <= 173; e += 173) {
        double q[3 * 8];
        for (int i = 0; i < 3 * 8; i++) q[i] = ldexp(pts[i], e);
        double ref = qhull_volume(q, 8);
        acd_hull_volume_ws w;
        memset(&w, 0, sizeof w);
        double v = acd_hull_volume_fast(q, 8, &w, NULL);
        acd_hull_volume_ws_free(&w);
        assert_true(ref > 0);
        assert_true(fabs(v - ref) <= 1e-9 * ref);
    }
}

/* fuzz_hull_volume (fuzz/corpus/hull_volume/sweep_tiny_prefix): ten points, the first six within
 * 6e-25 of the origin, the other four near 0.9 (here scaled by 2^43 from the fuzz input). The sweep's
 * first prefix (the six) started the hull with its own tolerance, 6e-35; the four far points were
 * then tested against that tolerance and the hull of all ten lost a corner: 4.0e-6 for qhull's
 * 8.0e-6. A prefix under HULL_VOLUME_PREFIX_REL of the sweep's extent no longer starts the hull.
 * Every query the sweep computes must be qhull's volume of its prefix (or left, -3). */
static void test_sweep_tiny_prefix(void **state) {
    (void)state;
    double pts[10][3] = {
        {1.0410273767909543e-42, 1.0410273767909543e-42, 2.4238307419953734e-52},
        {1.0410276106494882e-42, 1.5707759177945867e-76, 9.1622164797543344e-72},
        {1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767896492e-42},
        {1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42},
        {1.0410273767909543e-42, 1.0410273765821445e-42, 1.0410273767909543e-42},
        {6.8247549143607734e-38, 3.6860247183499265e-40, 5.2009192740295908e-42},
        {1.0387856152602562e-13, 1.0387856152602562e-13, 1.0410273765821445e-42},
        {1.0410273767909543e-42, 1.0410273767909543e-42, 1.0387856152602562e-13},
        {1.0387528880247567e-13, 1.0387856152602562e-13, 1.0387856152602562e-13},
        {1.0387856152602562e-13, 1.0387856152602562e-13, 1.0387856152602562e-13}};
    for (int i = 0; i < 10; i++)
        for (int k = 0; k < 3; k++) pts[i][k] *= 8796093022208.0; /* 2^43 */
    const double l = sqrt(68.0 * 68 + 56 * 56 + 105 * 105), dir[3] = {68 / l, -56 / l, 105 / l};
    static const size_t cnt[5] = {5, 6, 7, 8, 10}, xb[5] = {0}, xe[5] = {0};
    double vol[5], ref;
    assert_int_equal(acd_hull_volume(&pts[0][0], 10, &ref, NULL), ACD_OK);
    /* (the prefixes of 6-8 points are flat to qhull: 0 or left) */
    assert_true(sweep_matches_qhull(&pts[0][0], 10, dir, cnt, NULL, xb, xe, 5, 1e-9 * ref, vol));
    assert_true(vol[4] != -3); /* was 4.0e-6, half of qhull's */
}

/* fuzz_hull_volume's sweep underestimate from a thin start (CI, 2026-11-26; corpus
 * hull_volume/sweep_thin_start): ten points near 1e-42 sorted along (68, -56, 105), the first five
 * within 8e-8 of their scale of the plane x = 1.041e-42 (about 800 of the sweep's tolerances). The
 * sweep started its hull from them; the prefixes of 7 and 8 points came out 4e-6 and 8e-5 below
 * qhull's volume, and a query with two section points over the 8, 2.3 times the target's tolerance.
 * A sweep now starts only from a prefix at least HULL_VOLUME_THICK_START tolerances thick (the thinner
 * ones are left to acd_hull_volume_fast): every query it computes is within 1e-9 of the whole set's
 * volume of qhull's, and the last is computed. */
static void test_sweep_thin_start(void **state) {
    (void)state;
    static const double pts[10][3] = {
        {1.0410273767909543e-42, 1.0410273767909543e-42, 1.6951332360629891e-43},
        {1.0410273767909543e-42, 1.0522377645055528e-42, 2.6025684419773857e-43},
        {1.0410273767909543e-42, 1.0410273767961745e-42, 2.6025684419773857e-43},
        {1.0410273767909543e-42, 2.2142021372824507e-52, 2.21420213728226e-52},
        {1.0410272912657049e-42, 1.3980222016974409e-76, 1.5884817149624453e-47},
        {1.0410273767909543e-42, 1.0410273767909543e-42, 1.0410273767909543e-42},
        {1.0410273767909543e-42, 1.0410273767909543e-42, 1.0413777014070355e-42},
        {1.0410273767909543e-42, 1.0410273767909543e-42, 1.0478587068045377e-42},
        {1.0410276106494882e-42, 1.5707759177945867e-76, 1.0410273767909531e-42},
        {1.0410869042724818e-42, 6.014732326702936e-67, 1.0410273767906677e-42}};
    const double l = sqrt(68.0 * 68 + 56 * 56 + 105 * 105), dir[3] = {68 / l, -56 / l, 105 / l};
    static const size_t cnt[5] = {5, 6, 7, 8, 10}, xb[5] = {0}, xe[5] = {0};
    double vol[5], ref;
    assert_int_equal(acd_hull_volume(&pts[0][0], 10, &ref, NULL), ACD_OK);
    assert_true(sweep_matches_qhull(&pts[0][0], 10, dir, cnt, NULL, xb, xe, 5, 1e-9 * ref, vol));
    assert_true(vol[4] != -3);
}

/* The bits of the volumes, for speed work that must keep them (docs/results/3d-speed.md "The
 * sweep's Quickhull, same bits"): sweeps along 24 directions over a box's points, a box's faces', a
 * thin slab's and a grid's (the planes' points from the same generator, no libm but floor and sqrt:
 * the inputs are the same everywhere), and acd_hull_volume_fast on each query's set, folded into
 * one FNV-1a hash of every volume's bits. The constant was taken from the code before that work
 * (main at b451eb7); another order of a sum in the cone volume moves it. A change meant to move the
 * volumes updates it. The arithmetic as written (no contraction into FMA), so checked on x86-64
 * without FMA only; elsewhere the hash is printed. */
static unsigned long long fnv_double(unsigned long long h, double v) {
    unsigned char b[sizeof v];
    memcpy(b, &v, sizeof v);
    for (size_t i = 0; i < sizeof v; i++) h = (h ^ b[i]) * 1099511628211ULL;
    return h;
}

static void test_volume_bits(void **state) {
    (void)state;
    enum { N = 600, NX = 40, NQ = 9 };
    double *pts = malloc(3 * N * sizeof *pts), *xs = malloc(3 * NQ * NX * sizeof *xs), *set = malloc(3 * (N + NX) * sizeof *set);
    assert_true(pts && xs && set);
    unsigned long long seed = 777, h = 1469598103934665603ULL;
    acd_hull_volume_ws w;
    memset(&w, 0, sizeof w);
    int computed = 0;
    for (int round = 0; round < 24; round++) {
        int kind = round % 4;
        double dir[3] = {0.3 * (round % 4) - 0.4, 0.15 * (round % 5) - 0.3, 1};
        double l = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
        for (int k = 0; k < 3; k++) dir[k] /= l;
        for (size_t i = 0; i < N; i++) {
            double *q = pts + 3 * i;
            for (int k = 0; k < 3; k++) q[k] = 2 * lcg01(&seed) - 1;
            if (kind == 1) q[i % 3] = q[i % 3] < 0 ? -1 : 1;
            if (kind == 2) q[0] *= 1e-3;
            if (kind == 3) /* a grid: many coplanar points, ties, points on edges */
                for (int k = 0; k < 3; k++) q[k] = floor(4 * q[k]) / 4;
        }
        sort_along(pts, N, dir);
        double lo = dir[0] * pts[0] + dir[1] * pts[1] + dir[2] * pts[2];
        double hi = dir[0] * pts[3 * (N - 1)] + dir[1] * pts[3 * (N - 1) + 1] + dir[2] * pts[3 * (N - 1) + 2];
        size_t cnt[NQ], xb[NQ], xe[NQ];
        for (int q = 0; q < NQ; q++) {
            double c = lo + (hi - lo) * (q + 1) / (NQ + 1);
            size_t k = 0;
            while (k < N && dir[0] * pts[3 * k] + dir[1] * pts[3 * k + 1] + dir[2] * pts[3 * k + 2] - c < 0) k++;
            cnt[q] = k;
            xb[q] = (size_t)q * NX, xe[q] = xb[q] + NX;
            for (int j = 0; j < NX; j++) { /* a point of the box moved onto the plane along dir */
                double *x = xs + 3 * (xb[q] + (size_t)j), y[3];
                for (int d = 0; d < 3; d++) y[d] = 1.6 * lcg01(&seed) - 0.8;
                double s = dir[0] * y[0] + dir[1] * y[1] + dir[2] * y[2] - c;
                for (int d = 0; d < 3; d++) x[d] = y[d] - s * dir[d];
            }
        }
        double vol[NQ];
        assert_int_equal(acd_hull_volume_sweep(pts, N, dir, cnt, xs, xb, xe, NQ, vol, &w), 0);
        for (int q = 0; q < NQ; q++) {
            memcpy(set, pts, 3 * cnt[q] * sizeof *set);
            memcpy(set + 3 * cnt[q], xs + 3 * xb[q], 3 * NX * sizeof *set);
            double ref = acd_hull_volume_fast(set, cnt[q] + NX, &w, NULL);
            h = fnv_double(fnv_double(h, vol[q]), ref);
            computed += vol[q] != -3;
        }
    }
    acd_hull_volume_ws_free(&w);
    free(pts), free(xs), free(set);
    print_message("volume bits: %d of 216 queries swept, hash %016llx\n", computed, h);
    assert_true(computed >= 120);
#if defined(__x86_64__) && !defined(__FMA__)
    assert_true(h == 0x9a29039e5f8060c4ULL);
#endif
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hull_volume),
        cmocka_unit_test(test_workspace_reuse),
        cmocka_unit_test(test_sweep),
        cmocka_unit_test(test_vertices),
        cmocka_unit_test(test_extreme_scales),
        cmocka_unit_test(test_sweep_thin_prefix),
        cmocka_unit_test(test_sweep_fold),
        cmocka_unit_test(test_fold_per_set),
        cmocka_unit_test(test_sweep_tiny_prefix),
        cmocka_unit_test(test_sweep_thin_start),
        cmocka_unit_test(test_volume_bits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
