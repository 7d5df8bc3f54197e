/* eval/concavity2d_ref: reference concavity measures SL, SP, H1, H2 (Lien, dissertation
 * Ch. IV.A.1.a-c, Eqns/Algs 2-4; spec ../shared/spec/acd2d.md §3). See concavity2d_ref.h.
 * Written for the verifier, independently of src/acd2/: simple, quadratic-or-worse where that
 * keeps it obviously right. */
#include "eval/concavity2d_ref.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "acd/verify2d.h"
#include "core/predicates.h"

static double orient(acd_vec2 a, acd_vec2 b, acd_vec2 c) {
    return acd_ref_orient(a, b, c);
}

static int sgn(double v) {
    return (v > 0) - (v < 0);
}

int acd_ref_is_notch(const acd_vec2 *pts, size_t n, size_t v, double notch_tol) {
    acd_vec2 u = pts[(v + n - 1) % n], p = pts[v], w = pts[(v + 1) % n];
    if (notch_tol > 0) {
        double cross = (p.x - u.x) * (w.y - p.y) - (p.y - u.y) * (w.x - p.x);
        return cross < -notch_tol;
    }
    return orient(u, p, w) < 0;
}

/* ---- convex hull (Andrew's monotone chain), marks hull vertices ---- */

typedef struct sort_item {
    double x, y;
    size_t i;
} sort_item;

static int cmp_item(const void *a, const void *b) {
    const sort_item *p = a, *q = b;
    if (p->x != q->x) return p->x < q->x ? -1 : 1;
    if (p->y != q->y) return p->y < q->y ? -1 : 1;
    return (p->i > q->i) - (p->i < q->i);
}

/* is_hull[i] = 1 for the polygon vertices that are corners of the convex hull. 0 / -1. */
static int mark_hull(const acd_vec2 *pts, size_t n, unsigned char *is_hull) {
    sort_item *it = malloc(n * sizeof *it);
    size_t *st = malloc((2 * n + 2) * sizeof *st);
    if (!it || !st) {
        free(it);
        free(st);
        return -1;
    }
    for (size_t i = 0; i < n; i++) {
        it[i].x = pts[i].x;
        it[i].y = pts[i].y;
        it[i].i = i;
        is_hull[i] = 0;
    }
    qsort(it, n, sizeof *it, cmp_item);
    size_t k = 0;
    for (size_t i = 0; i < n; i++) { /* lower hull */
        while (k >= 2 && orient(pts[st[k - 2]], pts[st[k - 1]], pts[it[i].i]) <= 0) k--;
        st[k++] = it[i].i;
    }
    size_t lower = k + 1;
    for (size_t i = n - 1; i-- > 0;) { /* upper hull */
        while (k >= lower && orient(pts[st[k - 2]], pts[st[k - 1]], pts[it[i].i]) <= 0) k--;
        st[k++] = it[i].i;
    }
    for (size_t i = 0; i < k; i++) is_hull[st[i]] = 1;
    free(it);
    free(st);
    return 0;
}

/* ---- SP: Dijkstra over the pocket's visibility graph ---- */

/* The pocket polygon q[0..k-1] is clockwise (interior on the right of every edge, the closing
 * edge q[k-1] -> q[0] being the bridge). Is target t inside the closed interior cone at vertex i? */
static int in_cone(const acd_vec2 *q, size_t k, size_t i, acd_vec2 t) {
    acd_vec2 p = q[(i + k - 1) % k], v = q[i], nx = q[(i + 1) % k];
    int turn = sgn(orient(p, v, nx));
    int a = sgn(orient(v, nx, t)) <= 0, b = sgn(orient(p, v, t)) <= 0;
    return turn <= 0 ? (a && b) : (a || b);
}

static int same_point(acd_vec2 a, acd_vec2 b) {
    return a.x == b.x && a.y == b.y;
}

/* Does the segment from vertex i to point t (vertex j, or j == k for a point on the bridge)
 * lie in the closed pocket polygon? */
static int visible(const acd_vec2 *q, size_t k, size_t i, acd_vec2 t, size_t j) {
    acd_vec2 a = q[i];
    if (same_point(a, t)) return 1;
    if (!in_cone(q, k, i, t)) return 0;
    if (j < k && !in_cone(q, k, j, a)) return 0;
    for (size_t e = 0; e < k; e++) {
        if (j == k && e == k - 1) continue; /* the bridge itself, on which t lies */
        acd_vec2 e0 = q[e], e1 = q[(e + 1) % k];
        if (acd_ref_segrel(a, t, e0, e1) == ACD_SEG_PROPER) return 0;
    }
    for (size_t w = 0; w < k; w++) {
        if (w == i || w == j || same_point(q[w], a) || same_point(q[w], t)) continue;
        if (!acd_ref_on_segment(q[w], a, t)) continue;
        if (in_cone(q, k, w, a) && in_cone(q, k, w, t)) continue;
        /* a repeated point (zero-width slit): fine if another occurrence's cone holds it */
        int ok = 0;
        for (size_t o = 0; o < k && !ok; o++)
            if (o != w && same_point(q[o], q[w]) && in_cone(q, k, o, a) && in_cone(q, k, o, t)) ok = 1;
        if (!ok) return 0;
    }
    return 1;
}

int acd_ref_pocket_sp(const acd_vec2 *q, size_t k, double *dist) {
    if (k < 2) {
        for (size_t i = 0; i < k; i++) dist[i] = 0;
        return 0;
    }
    unsigned char *done = calloc(k, 1);
    double *lb = malloc(k * sizeof *lb);
    if (!done || !lb) {
        free(done);
        free(lb);
        return -1;
    }
    acd_vec2 b0 = q[0], b1 = q[k - 1];
    double dx = b1.x - b0.x, dy = b1.y - b0.y, l2 = dx * dx + dy * dy, len = sqrt(l2);
    for (size_t i = 0; i < k; i++) {
        dist[i] = INFINITY;
        lb[i] = 0;
        if (i == 0 || i == k - 1) {
            dist[i] = 0;
            continue;
        }
        if (!(len > 0)) {
            lb[i] = hypot(q[i].x - b0.x, q[i].y - b0.y);
            continue;
        }
        double t = ((q[i].x - b0.x) * dx + (q[i].y - b0.y) * dy) / l2;
        double h = fabs(orient(b0, b1, q[i])) / len;
        if (t >= 0 && t <= 1) {
            lb[i] = h;
            acd_vec2 f = {b0.x + t * dx, b0.y + t * dy};
            if (visible(q, k, i, f, k)) dist[i] = h;
        } else {
            lb[i] = t < 0 ? hypot(q[i].x - b0.x, q[i].y - b0.y) : hypot(q[i].x - b1.x, q[i].y - b1.y);
        }
    }
    for (;;) {
        size_t u = k;
        for (size_t i = 0; i < k; i++)
            if (!done[i] && isfinite(dist[i]) && (u == k || dist[i] < dist[u])) u = i;
        if (u == k) break;
        done[u] = 1;
        for (size_t v = 0; v < k; v++) {
            if (done[v] || dist[v] <= lb[v]) continue;
            double c = dist[u] + hypot(q[v].x - q[u].x, q[v].y - q[u].y);
            if (c < dist[v] && visible(q, k, u, q[v], v)) dist[v] = c;
        }
    }
    free(done);
    free(lb);
    return 0;
}

/* ---- per-pocket measures ---- */

/* Some pocket edge runs against the bridge direction: its outward normal opposes the bridge's
 * (Obs. A.5). Dot products too close to 0 to have a certain sign count as no hazard. */
static int pocket_hazard(const acd_vec2 *q, size_t k) {
    double dx = q[k - 1].x - q[0].x, dy = q[k - 1].y - q[0].y;
    for (size_t i = 0; i + 1 < k; i++) {
        double ex = q[i + 1].x - q[i].x, ey = q[i + 1].y - q[i].y;
        double d = ex * dx + ey * dy;
        double bound = 8 * DBL_EPSILON * (fabs(ex * dx) + fabs(ey * dy));
        if (d < -bound) return 1;
    }
    return 0;
}

int acd_ref_vertex_concavity(const acd_vec2 *pts, size_t n, acd2d_measure m, double tau, double notch_tol,
                             double *conc, size_t *hazard_pockets) {
    if (hazard_pockets) *hazard_pockets = 0;
    for (size_t i = 0; i < n; i++) conc[i] = 0;
    if (n < 4) return 0;
    unsigned char *is_hull = malloc(n);
    acd_vec2 *q = malloc((n + 1) * sizeof *q);
    double *sp = malloc((n + 1) * sizeof *sp);
    if (!is_hull || !q || !sp || mark_hull(pts, n, is_hull) != 0) {
        free(is_hull);
        free(q);
        free(sp);
        return -1;
    }
    size_t first = n;
    for (size_t i = 0; i < n && first == n; i++)
        if (is_hull[i]) first = i;
    int rc = 0;
    if (first < n) {
        size_t h = first;
        do {
            size_t h2 = (h + 1) % n;
            while (!is_hull[h2]) h2 = (h2 + 1) % n;
            size_t k = (h2 + n - h) % n + 1; /* pocket chain h..h2 */
            if (k == 1) k = n + 1;            /* a single hull vertex: degenerate, whole ring */
            if (k > 2) {
                for (size_t j = 0; j < k; j++) q[j] = pts[(h + j) % n];
                acd_vec2 b0 = q[0], b1 = q[k - 1];
                double len = hypot(b1.x - b0.x, b1.y - b0.y);
                double slmax = 0;
                for (size_t j = 1; j + 1 < k; j++) {
                    double d = len > 0 ? orient(b0, b1, q[j]) / len : hypot(q[j].x - b0.x, q[j].y - b0.y);
                    sp[j] = d > 0 ? d : 0; /* SL, stored in sp[] for now */
                    if (sp[j] > slmax && acd_ref_is_notch(pts, n, (h + j) % n, notch_tol)) slmax = sp[j];
                }
                int hazard = pocket_hazard(q, k);
                if (hazard && hazard_pockets) (*hazard_pockets)++;
                int use_sp = m == ACD2D_MEASURE_SP || (m == ACD2D_MEASURE_H1 && hazard) ||
                             (m == ACD2D_MEASURE_H2 && hazard && !(slmax > tau));
                if (use_sp) {
                    if (acd_ref_pocket_sp(q, k, sp) != 0) {
                        rc = -1;
                        break;
                    }
                }
                for (size_t j = 1; j + 1 < k; j++) {
                    size_t v = (h + j) % n;
                    if (sp[j] > conc[v]) conc[v] = sp[j];
                }
            }
            h = h2;
        } while (h != first);
    }
    free(is_hull);
    free(q);
    free(sp);
    return rc;
}

double acd_verify2d_concavity(const acd_vec2 *pts, size_t n, acd2d_measure m, double tau,
                              double notch_tolerance, size_t *witness) {
    if (witness) *witness = n;
    if (n < 4) return 0;
    double *conc = malloc(n * sizeof *conc);
    if (!conc) return -1;
    if (acd_ref_vertex_concavity(pts, n, m, tau, notch_tolerance, conc, NULL) != 0) {
        free(conc);
        return -1;
    }
    double best = 0;
    for (size_t i = 0; i < n; i++) {
        if (!acd_ref_is_notch(pts, n, i, notch_tolerance)) continue;
        if (witness && *witness == n) *witness = i;
        if (conc[i] > best) {
            best = conc[i];
            if (witness) *witness = i;
        }
    }
    free(conc);
    return best;
}
