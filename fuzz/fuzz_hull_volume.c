/* fuzz/fuzz_hull_volume: libFuzzer target for geom3/hull_volume, the own Quickhull that ranks the
 * budget pass's and the volume plane's candidate planes (acd_hull_volume_fast and the incremental
 * sweep acd_hull_volume_sweep). The input: a direction (3 x int8), then points on a small integer grid
 * (3 x int8 each, so duplicates, collinear and coplanar sets are frequent) or, after a leading 'D'
 * byte, raw doubles. The points are sorted along the direction; up to 8 queries take growing
 * prefixes, each with some of the later points projected onto the query's plane (as a plane cut's
 * section crossings). Every volume acd_hull_volume_fast and the sweep give (the sweep may decline a
 * query: -3) must be within HV_FUZZ_TOL_REL x extent^2 x max(extent, the coordinates' magnitude) of
 * acd_hull_volume's (qhull's) on the same set: the estimate's tolerances (a point within 1e-10, a set flat within
 * 1e-8) are relative to the coordinates' magnitude, so its slack is far below that; a wrong
 * horizon or a lost point off by more is a defect. Out of memory (-1) is allowed; anything else aborts.
 *
 * The hull volume screen's assumption (docs/acd3d.md "Cut choice by volume", src/acd3/decompose.h):
 * acd_hull_volume_fast is not above qhull's volume by more than ACD3_VOLUME_SCREEN_REL (1e-4) of
 * qhull's volume, else the screen could drop a candidate that would have won. Checked (the same
 * 1e-4, HV_FUZZ_SCREEN_REL) on every query set that is not thin: qhull's volume at least
 * HV_FUZZ_SCREEN_MIN (1e-6) x extent^2 x max(extent, magnitude), the set's own extent and
 * coordinates' magnitude. The threshold leaves out the nearly flat sets, on which rounding alone
 * can make 1e-4: the estimate's coordinates carry about 1e-16 of the magnitude, so each facet's
 * tetrahedron about 1e-16 x magnitude x extent^2, and up to 8192 facets 1e-12 of that scale (qhull's
 * own roundoff is of the same kind); above the threshold that is at most 1e-6 of the volume, so an
 * estimate above qhull's by 1e-4 is a real overestimate (a fold or a wrong horizon), not rounding.
 * (Such a set fills at least 1e-6 of its box.) Compiled out with -DHV_FUZZ_NO_SCREEN_CHECK. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "acd/hull.h"
#include "geom3/hull_volume.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Volumes may differ from qhull's by this share of extent^2 x max(extent, magnitude) (the slack). */
#define HV_FUZZ_TOL_REL 1e-6
#define HV_FUZZ_MAX_POINTS 4096
#define HV_FUZZ_QUERIES 8
/* The screen's check (see above): the margin, and the volume below which a set counts as thin. */
#define HV_FUZZ_SCREEN_REL 1e-4
#define HV_FUZZ_SCREEN_MIN 1e-6

typedef struct {
    double h;
    size_t i;
} keyed;

static int cmp_keyed(const void *a, const void *b) {
    const keyed *x = a, *y = b;
    if (x->h != y->h) return x->h < y->h ? -1 : 1;
    return x->i < y->i ? -1 : x->i > y->i;
}

static void check(double got, double ref, double tol) {
    if (got == -3.0 || got == -1.0) return; /* declined or out of memory */
    if (!(fabs(got - ref) <= tol)) abort(); /* NaN too; a sliver may come out a hair below 0 */
}

/* The screen's assumption: the estimate got not above qhull's ref by more than HV_FUZZ_SCREEN_REL
 * relative, on a set that is not thin (ref >= thin). */
static void check_screen(double got, double ref, double thin) {
#ifndef HV_FUZZ_NO_SCREEN_CHECK
    if (got == -1.0 || !(ref >= thin) || !(ref > 0)) return;
    if (got > ref * (1 + HV_FUZZ_SCREEN_REL)) abort();
#else
    (void)got, (void)ref, (void)thin;
#endif
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size < 4) return 0;
    double dir[3] = {(int8_t)data[0], (int8_t)data[1], (int8_t)data[2]};
    double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    if (!(len > 0)) return 0;
    for (int k = 0; k < 3; k++) dir[k] /= len;
    data += 3, size -= 3;
    size_t n;
    double *p;
    if (data[0] == 'D') {
        n = (size - 1) / 24;
        if (n > HV_FUZZ_MAX_POINTS) n = HV_FUZZ_MAX_POINTS;
        p = malloc((n ? n : 1) * 3 * sizeof *p);
        if (!p) return 0;
        memcpy(p, data + 1, n * 24);
        for (size_t i = 0; i < 3 * n; i++)
            if (!isfinite(p[i]) || fabs(p[i]) > 1e100 || (p[i] != 0 && fabs(p[i]) < 1e-100)) {
                free(p);
                return 0;
            }
    } else {
        n = size / 3;
        if (n > HV_FUZZ_MAX_POINTS) n = HV_FUZZ_MAX_POINTS;
        p = malloc((n ? n : 1) * 3 * sizeof *p);
        if (!p) return 0;
        for (size_t i = 0; i < 3 * n; i++) p[i] = (int8_t)data[i];
    }
    if (n < 4) {
        free(p);
        return 0;
    }
    /* sorted along dir (ties by index: deterministic) */
    keyed *key = malloc(n * sizeof *key);
    double *s = malloc(3 * n * sizeof *s), *xs = malloc(3 * n * HV_FUZZ_QUERIES * sizeof *xs),
           *set = malloc(3 * 2 * n * sizeof *set);
    if (!key || !s || !xs || !set) goto out;
    for (size_t i = 0; i < n; i++) key[i] = (keyed){dir[0] * p[3 * i] + dir[1] * p[3 * i + 1] + dir[2] * p[3 * i + 2], i};
    qsort(key, n, sizeof *key, cmp_keyed);
    for (size_t i = 0; i < n; i++) memcpy(s + 3 * i, p + 3 * key[i].i, 3 * sizeof(double));
    double lo[3], hi[3], ext = 0;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            if (i == 0 || s[3 * i + k] < lo[k]) lo[k] = s[3 * i + k];
            if (i == 0 || s[3 * i + k] > hi[k]) hi[k] = s[3 * i + k];
        }
    double mag = 0; /* the coordinates' magnitude: the estimate's tolerances are relative to it */
    for (int k = 0; k < 3; k++) ext = fmax(ext, hi[k] - lo[k]), mag = fmax(mag, fmax(fabs(lo[k]), fabs(hi[k])));
    double tol = HV_FUZZ_TOL_REL * ext * ext * fmax(ext, mag);
    /* queries: prefixes at q (n / Q), the plane at the prefix's last height, the next few points
     * projected onto it */
    size_t cnt[HV_FUZZ_QUERIES], xb[HV_FUZZ_QUERIES], xe[HV_FUZZ_QUERIES], nx = 0;
    int nq = 0;
    for (int q = 0; q < HV_FUZZ_QUERIES; q++) {
        size_t c = (size_t)(q + 1) * n / HV_FUZZ_QUERIES;
        if (c < 1) continue;
        cnt[nq] = c;
        xb[nq] = nx;
        double h = key[c - 1].h;
        size_t extra = (size_t)(data[(size_t)q % size] % 7);
        for (size_t j = c; j < n && j < c + extra; j++) {
            const double *x = s + 3 * j;
            double t = dir[0] * x[0] + dir[1] * x[1] + dir[2] * x[2] - h;
            for (int k = 0; k < 3; k++) xs[3 * nx + k] = x[k] - t * dir[k];
            nx++;
        }
        xe[nq] = nx;
        nq++;
    }
    double vol[HV_FUZZ_QUERIES];
    acd_hull_volume_ws w;
    memset(&w, 0, sizeof w);
    int r = acd_hull_volume_sweep(s, n, dir, cnt, xs, xb, xe, nq, vol, &w);
    for (int q = 0; q < nq; q++) {
        size_t m = cnt[q] + (xe[q] - xb[q]);
        memcpy(set, s, 3 * cnt[q] * sizeof(double));
        memcpy(set + 3 * cnt[q], xs + 3 * xb[q], 3 * (xe[q] - xb[q]) * sizeof(double));
        double ref = -1;
        if (acd_hull_volume(set, m, &ref, NULL) != ACD_OK) continue; /* qhull refused: nothing to compare */
        if (r == 0) check(vol[q], ref, tol);
        double fast = acd_hull_volume_fast(set, m, &w, NULL);
        check(fast, ref, tol);
        double slo[3], shi[3], sext = 0, smag = 0; /* the query set's own extent and magnitude */
        for (size_t i = 0; i < m; i++)
            for (int k = 0; k < 3; k++) {
                if (i == 0 || set[3 * i + k] < slo[k]) slo[k] = set[3 * i + k];
                if (i == 0 || set[3 * i + k] > shi[k]) shi[k] = set[3 * i + k];
            }
        for (int k = 0; k < 3; k++)
            sext = fmax(sext, shi[k] - slo[k]), smag = fmax(smag, fmax(fabs(slo[k]), fabs(shi[k])));
        check_screen(fast, ref, HV_FUZZ_SCREEN_MIN * sext * sext * fmax(sext, smag));
    }
    acd_hull_volume_ws_free(&w);
out:
    free(key);
    free(s);
    free(xs);
    free(set);
    free(p);
    return 0;
}
