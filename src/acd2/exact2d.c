/* acd2/exact2d: the public entry of the exact 2D decompositions (include/acd/exact2d.h): runs
 * Keil-Snoeyink MCD (exact_mcd) or Hertel-Mehlhorn (exact_hm), builds the result and verifies it
 * (Lien, dissertation IV.D.3, Table 3: the exact baselines ACD is compared with). */
#include "acd/exact2d.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "acd2/exact_hm.h"
#include "acd2/exact_mcd.h"
#include "core/error.h"
#include "core/predicates.h"
#include "core/tolerance.h"
#include "geom2/triangulate.h"

#define V2(p) ((const double *)(const void *)(p))

const char *acd_exact2d_method_name(acd_exact2d_method m) {
    return m == ACD_EXACT2D_HM ? "hm" : "mcd";
}

int acd_exact2d_method_parse(const char *name, acd_exact2d_method *out) {
    if (!name) return 0;
    if (strcmp(name, "mcd") == 0) *out = ACD_EXACT2D_MCD;
    else if (strcmp(name, "hm") == 0) *out = ACD_EXACT2D_HM;
    else return 0;
    return 1;
}

void acd_exact2d_result_free(acd_exact2d_result *r) {
    if (!r) return;
    for (size_t i = 0; i < r->npieces; i++) {
        free(r->pieces[i].points);
        free(r->pieces[i].index);
    }
    free(r->pieces);
    free(r->diagonals);
    memset(r, 0, sizeof *r);
}

static double now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Reflex vertices of the region (a convex corner of a hole is a notch), exact orient2d. */
static size_t count_notches(const acd_polygon *p) {
    size_t count = 0;
    for (size_t r = 0; r < p->nrings; r++) {
        size_t n = acd_polygon_ring_size(p, r);
        const acd_vec2 *v = acd_polygon_ring(p, r);
        if (n < 3) continue;
        int ccw = acd_ring_is_ccw(v, n), want = r == 0;
        for (size_t i = 0; i < n; i++) {
            int o = acd_orient2d_sign(V2(&v[(i + n - 1) % n]), V2(&v[i]), V2(&v[(i + 1) % n]));
            if (ccw != want) o = -o;
            if (o < 0) count++;
        }
    }
    return count;
}

static double region_area(const acd_polygon *p) {
    double total = 0;
    for (size_t r = 0; r < p->nrings; r++) {
        size_t n = acd_polygon_ring_size(p, r);
        const acd_vec2 *v = acd_polygon_ring(p, r);
        double a = 0;
        for (size_t i = 0; i < n; i++) {
            const acd_vec2 *u = &v[i], *w = &v[(i + 1) % n];
            a += (u->x - v[0].x) * (w->y - v[0].y) - (w->x - v[0].x) * (u->y - v[0].y);
        }
        total += r == 0 ? fabs(a) / 2 : -fabs(a) / 2;
    }
    return total;
}

acd_status acd_exact2d_verify(const acd_polygon *poly, const acd_exact2d_result *r, acd_error *err) {
    size_t n = acd_polygon_num_points(poly);
    double sum = 0, sumabs = 0;
    for (size_t i = 0; i < r->npieces; i++) {
        const acd_exact2d_piece *pc = &r->pieces[i];
        if (pc->npoints < 3)
            return acd_fail(err, ACD_ERR_VERIFY, "exact2d verify: piece %zu has %zu vertices", i, pc->npoints);
        int any = 0;
        double a = 0;
        for (size_t k = 0; k < pc->npoints; k++) {
            size_t id = pc->index[k];
            if (id >= n || poly->points[id].x != pc->points[k].x || poly->points[id].y != pc->points[k].y)
                return acd_fail(err, ACD_ERR_VERIFY,
                                "exact2d verify: piece %zu vertex %zu (%g, %g) is not input vertex %zu", i, k,
                                pc->points[k].x, pc->points[k].y, id);
            const acd_vec2 *u = &pc->points[(k + pc->npoints - 1) % pc->npoints], *v = &pc->points[k],
                           *w = &pc->points[(k + 1) % pc->npoints];
            int o = acd_orient2d_sign(V2(u), V2(v), V2(w));
            if (o < 0)
                return acd_fail(err, ACD_ERR_VERIFY,
                                "exact2d verify: piece %zu is not convex at its vertex %zu (input vertex %zu, (%g, %g))",
                                i, k, id, v->x, v->y);
            if (o > 0) any = 1;
            a += (v->x - pc->points[0].x) * (w->y - pc->points[0].y) - (w->x - pc->points[0].x) * (v->y - pc->points[0].y);
        }
        if (!any) return acd_fail(err, ACD_ERR_VERIFY, "exact2d verify: piece %zu is degenerate (all collinear)", i);
        sum += a / 2;
        sumabs += fabs(a) / 2;
    }
    for (size_t d = 0; d < r->ndiagonals; d++)
        if (r->diagonals[d][0] >= n || r->diagonals[d][1] >= n)
            return acd_fail(err, ACD_ERR_VERIFY, "exact2d verify: diagonal %zu names a vertex out of range", d);
    double area = region_area(poly);
    double tol = ACD_TOL_REL_MEASURE * (fabs(area) + sumabs); /* relative to the areas involved */
    if (!(fabs(sum - area) <= tol))
        return acd_fail(err, ACD_ERR_VERIFY,
                        "exact2d verify: the pieces' areas add up to %.17g, the polygon's area is %.17g "
                        "(pieces overlap or leave gaps; is the input a simple polygon with holes?)",
                        sum, area);
    return ACD_OK;
}

acd_status acd_exact2d_decompose(const acd_polygon *poly, acd_exact2d_method m, acd_exact2d_result *out,
                                 acd_error *err) {
    memset(out, 0, sizeof *out);
    if (!poly || !poly->nrings)
        return acd_fail(err, ACD_ERR_DEGENERATE, "exact decomposition: empty polygon");
    if (m != ACD_EXACT2D_MCD && m != ACD_EXACT2D_HM)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "exact decomposition: unknown method %d", (int)m);
    size_t n = acd_polygon_num_points(poly);
    for (size_t i = 0; i < n; i++)
        if (!isfinite(poly->points[i].x) || !isfinite(poly->points[i].y))
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "exact decomposition: vertex %zu has a non-finite coordinate",
                            i);
    double t0 = now_seconds();
    acd_index_pieces ip;
    acd_status st = m == ACD_EXACT2D_MCD ? acd_exact_mcd(poly, &ip, err) : acd_exact_hm(poly, &ip, err);
    if (st != ACD_OK) return st;
    double t1 = now_seconds();
    out->method = m;
    out->input_vertices = n;
    out->input_holes = poly->nrings - 1;
    out->input_notches = count_notches(poly);
    out->seconds = t1 - t0;
    out->pieces = calloc(ip.npieces ? ip.npieces : 1, sizeof *out->pieces);
    out->diagonals = malloc((ip.ndiag ? ip.ndiag : 1) * sizeof *out->diagonals);
    if (!out->pieces || !out->diagonals) goto nomem;
    out->npieces = ip.npieces;
    for (size_t i = 0; i < ip.npieces; i++) {
        acd_exact2d_piece *pc = &out->pieces[i];
        size_t k = ip.start[i + 1] - ip.start[i];
        pc->points = malloc(k * sizeof *pc->points);
        pc->index = malloc(k * sizeof *pc->index);
        if (!pc->points || !pc->index) goto nomem;
        pc->npoints = k;
        for (size_t z = 0; z < k; z++) {
            pc->index[z] = ip.idx[ip.start[i] + z];
            pc->points[z] = poly->points[pc->index[z]];
        }
    }
    if (ip.ndiag) memcpy(out->diagonals, ip.diag, ip.ndiag * sizeof *out->diagonals);
    out->ndiagonals = ip.ndiag;
    acd_index_pieces_free(&ip);
    st = acd_exact2d_verify(poly, out, err);
    if (st != ACD_OK) acd_exact2d_result_free(out);
    return st;
nomem:
    acd_index_pieces_free(&ip);
    acd_exact2d_result_free(out);
    return acd_fail(err, ACD_ERR_NOMEM, "exact decomposition: out of memory for the result");
}
