/* fuzz/fuzz_exact2d: libFuzzer target for the triangulation and the exact decompositions
 * (geom2/triangulate, acd2/exact_hm, acd2/exact_mcd).
 *
 * Input: byte 0 gives the ring count (1..3); each ring is a size byte (3..15 points) followed by
 * int8 coordinate pairs, so collinear and repeated points are frequent. Valid polygons
 * (acd_polygon_validate) must triangulate into n + 2h - 2 counterclockwise triangles whose doubled
 * areas add up exactly (integer coordinates), decompose with Hertel-Mehlhorn (k = d - h + 1 pieces
 * from d diagonals, at most two per notch) and, without holes, with MCD into at most as many pieces,
 * exactly the brute-force minimum up to 10 vertices (tests/exact2d_brute.h). Invalid ones must
 * merely return (best-effort triangulation, errors from the decompositions). Violations abort. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "acd/exact2d.h"
#include "acd/polygon.h"
#include "core/predicates.h"
#include "geom2/triangulate.h"
#include "../tests/exact2d_brute.h"

#define V2(p) ((const double *)(const void *)(p))

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static double twice_area(const acd_vec2 *v, size_t n) {
    double a = 0;
    for (size_t i = 0; i < n; i++) a += v[i].x * v[(i + 1) % n].y - v[(i + 1) % n].x * v[i].y;
    return a;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size < 2) return 0;
    size_t pos = 0, nrings = 1 + data[pos++] % 3;
    acd_vec2 pts[3][16];
    const acd_vec2 *rings[3];
    size_t sizes[3], got = 0;
    for (size_t r = 0; r < nrings && pos < size; r++) {
        size_t m = 3 + data[pos++] % 13;
        if (pos + 2 * m > size) break;
        for (size_t i = 0; i < m; i++) {
            pts[r][i].x = (double)(int8_t)data[pos++];
            pts[r][i].y = (double)(int8_t)data[pos++];
        }
        rings[r] = pts[r];
        sizes[r] = m;
        got++;
    }
    if (!got) return 0;
    acd_polygon p;
    if (acd_polygon_from_rings(&p, rings, sizes, got, NULL) != ACD_OK) return 0;
    acd_error err;
    size_t *tris = NULL, nt = 0, n = acd_polygon_num_points(&p), h = got - 1;
    if (acd_polygon_validate(&p, 0, NULL) != ACD_OK) {
        size_t forced = 0;
        if (acd_triangulate_rings(p.points, p.ring_start, p.nrings, ACD_TRI_BEST_EFFORT, &tris, &nt, NULL, &forced,
                                  &err) == ACD_OK) {
            if (nt != n + 2 * h - 2) abort();
            for (size_t i = 0; i < 3 * nt; i++)
                if (tris[i] >= n) abort();
            free(tris);
        }
        acd_exact2d_result res;
        for (int m = 0; m < 2; m++)
            if (acd_exact2d_decompose(&p, (acd_exact2d_method)m, &res, &err) == ACD_OK) acd_exact2d_result_free(&res);
        acd_polygon_free(&p);
        return 0;
    }
    if (acd_triangulate_polygon(&p, &tris, &nt, NULL, &err) != ACD_OK) abort();
    if (nt != n + 2 * h - 2) abort();
    double sum = 0, want = 0;
    for (size_t i = 0; i < nt; i++) {
        const acd_vec2 t[3] = {p.points[tris[3 * i]], p.points[tris[3 * i + 1]], p.points[tris[3 * i + 2]]};
        if (acd_orient2d_sign(V2(&t[0]), V2(&t[1]), V2(&t[2])) < 0) abort();
        sum += twice_area(t, 3);
    }
    for (size_t r = 0; r < p.nrings; r++) {
        double a = twice_area(acd_polygon_ring(&p, r), acd_polygon_ring_size(&p, r));
        want += r == 0 ? (a < 0 ? -a : a) : -(a < 0 ? -a : a);
    }
    if (sum != want) abort(); /* integer coordinates: exact */
    free(tris);
    acd_exact2d_result hm, mcd;
    if (acd_exact2d_decompose(&p, ACD_EXACT2D_HM, &hm, &err) != ACD_OK) abort();
    if (hm.npieces + h != hm.ndiagonals + 1) abort();
    if (hm.ndiagonals > 2 * hm.input_notches) abort(); /* <= 2 essential diagonals per notch */
    if (h == 0) {
        if (acd_exact2d_decompose(&p, ACD_EXACT2D_MCD, &mcd, &err) != ACD_OK) abort();
        if (mcd.npieces > hm.npieces) abort();
        if (n <= 10) { /* optimality against brute force (counterclockwise copy of the ring) */
            acd_vec2 ccw[16];
            int ok = acd_ring_is_ccw(p.points, n);
            for (size_t i = 0; i < n; i++) ccw[i] = p.points[ok ? i : n - 1 - i];
            if ((size_t)br_mcd(ccw, (int)n) != mcd.npieces) abort();
        }
        acd_exact2d_result_free(&mcd);
    } else if (acd_exact2d_decompose(&p, ACD_EXACT2D_MCD, &mcd, &err) != ACD_ERR_UNSUPPORTED) {
        abort();
    }
    acd_exact2d_result_free(&hm);
    acd_polygon_free(&p);
    return 0;
}
