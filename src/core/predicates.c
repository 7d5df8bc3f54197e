/* core/predicates: adaptive exact orientation and in-circle tests.
 *
 * Method: floating-point filter with a static relative error bound, then exact evaluation in
 * expansion arithmetic (a number is an unevaluated sum of non-overlapping doubles; sums use the
 * error-free two-sum, products the error-free FMA two-product). The error bounds are those of
 * the standard analysis of the straightforward determinant formulas (Shewchuk 1997, "Adaptive
 * precision floating-point arithmetic and fast robust geometric predicates"); the code is ours. */
#include "core/predicates.h"

#include <math.h>

#define EPS 1.1102230246251565e-16 /* 2^-53, half an ulp of 1 */
#define ORIENT2_BOUND ((3.0 + 16.0 * EPS) * EPS)
#define ORIENT3_BOUND ((7.0 + 56.0 * EPS) * EPS)
#define INCIRCLE_BOUND ((10.0 + 96.0 * EPS) * EPS)

enum { EXP_MAX = 1024 };

typedef struct expansion {
    int n;
    double c[EXP_MAX]; /* increasing magnitude, non-overlapping, no zeros */
} expansion;

static inline void two_sum(double a, double b, double *x, double *y) {
    double s = a + b;
    double bv = s - a;
    double av = s - bv;
    *x = s;
    *y = (a - av) + (b - bv);
}

static inline void two_prod(double a, double b, double *x, double *y) {
    double p = a * b;
    *x = p;
    *y = fma(a, b, -p);
}

/* e += b (Shewchuk's GROW-EXPANSION with zero elimination), in place. */
static void exp_grow(expansion *e, double b) {
    double q = b;
    int k = 0;
    for (int i = 0; i < e->n; i++) {
        double hi, lo;
        two_sum(q, e->c[i], &hi, &lo);
        q = hi;
        if (lo != 0.0) e->c[k++] = lo;
    }
    if (q != 0.0 || k == 0) e->c[k++] = q;
    e->n = k;
    if (k == 1 && e->c[0] == 0.0) e->n = 0;
}

static void exp_add(expansion *e, const expansion *f) {
    for (int i = 0; i < f->n; i++) exp_grow(e, f->c[i]);
}

static void exp_sub(expansion *e, const expansion *f) {
    for (int i = 0; i < f->n; i++) exp_grow(e, -f->c[i]);
}

/* out = e * f (out must not alias e or f). */
static void exp_mul(const expansion *e, const expansion *f, expansion *out) {
    out->n = 0;
    for (int i = 0; i < e->n; i++)
        for (int j = 0; j < f->n; j++) {
            double hi, lo;
            two_prod(e->c[i], f->c[j], &hi, &lo);
            if (lo != 0.0) exp_grow(out, lo);
            exp_grow(out, hi);
        }
}

static void exp_diff(double a, double b, expansion *e) {
    double hi, lo;
    two_sum(a, -b, &hi, &lo);
    e->n = 0;
    if (lo != 0.0) e->c[e->n++] = lo;
    if (hi != 0.0) e->c[e->n++] = hi;
}

static double exp_estimate(const expansion *e) {
    double s = 0.0;
    for (int i = 0; i < e->n; i++) s += e->c[i];
    /* The sum's sign equals the sign of the most significant component. */
    if (e->n > 0 && (s == 0.0 || (s > 0) != (e->c[e->n - 1] > 0))) return e->c[e->n - 1];
    return s;
}

static double orient2d_exact(const double a[2], const double b[2], const double c[2]) {
    expansion acx, bcy, acy, bcx, l, r;
    exp_diff(a[0], c[0], &acx);
    exp_diff(b[1], c[1], &bcy);
    exp_diff(a[1], c[1], &acy);
    exp_diff(b[0], c[0], &bcx);
    exp_mul(&acx, &bcy, &l);
    exp_mul(&acy, &bcx, &r);
    exp_sub(&l, &r);
    return exp_estimate(&l);
}

double acd_orient2d(const double a[2], const double b[2], const double c[2]) {
    double detl = (a[0] - c[0]) * (b[1] - c[1]);
    double detr = (a[1] - c[1]) * (b[0] - c[0]);
    double det = detl - detr;
    double bound = ORIENT2_BOUND * (fabs(detl) + fabs(detr));
    if (det > bound || -det > bound) return det;
    return orient2d_exact(a, b, c);
}

int acd_orient2d_sign(const double a[2], const double b[2], const double c[2]) {
    double d = acd_orient2d(a, b, c);
    return (d > 0) - (d < 0);
}

/* 3x3 determinant of rows (u, v, w), each row given as three exact expansions. */
static void det3_exact(const expansion u[3], const expansion v[3], const expansion w[3], expansion *out) {
    static const int idx[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {1, 0, 2}, {2, 1, 0}};
    expansion t, p;
    out->n = 0;
    for (int k = 0; k < 6; k++) {
        exp_mul(&u[idx[k][0]], &v[idx[k][1]], &t);
        exp_mul(&t, &w[idx[k][2]], &p);
        if (k < 3) exp_add(out, &p);
        else exp_sub(out, &p);
    }
}

static double orient3d_exact(const double a[3], const double b[3], const double c[3], const double d[3]) {
    expansion u[3], v[3], w[3], det;
    for (int i = 0; i < 3; i++) {
        exp_diff(a[i], d[i], &u[i]);
        exp_diff(b[i], d[i], &v[i]);
        exp_diff(c[i], d[i], &w[i]);
    }
    det3_exact(u, v, w, &det);
    return exp_estimate(&det);
}

double acd_orient3d(const double a[3], const double b[3], const double c[3], const double d[3]) {
    double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
    double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
    double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
    double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
    double cdxady = cdx * ady, adxcdy = adx * cdy;
    double adxbdy = adx * bdy, bdxady = bdx * ady;
    double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    double perm = (fabs(bdxcdy) + fabs(cdxbdy)) * fabs(adz) + (fabs(cdxady) + fabs(adxcdy)) * fabs(bdz) +
                  (fabs(adxbdy) + fabs(bdxady)) * fabs(cdz);
    double bound = ORIENT3_BOUND * perm;
    if (det > bound || -det > bound) return det;
    return orient3d_exact(a, b, c, d);
}

int acd_orient3d_sign(const double a[3], const double b[3], const double c[3], const double d[3]) {
    double r = acd_orient3d(a, b, c, d);
    return (r > 0) - (r < 0);
}

static double incircle_exact(const double a[2], const double b[2], const double c[2], const double d[2]) {
    /* rows: (x, y, x^2 + y^2) of a-d, b-d, c-d */
    const double *p[3] = {a, b, c};
    expansion rows[3][3];
    for (int i = 0; i < 3; i++) {
        expansion sx, sy;
        exp_diff(p[i][0], d[0], &rows[i][0]);
        exp_diff(p[i][1], d[1], &rows[i][1]);
        exp_mul(&rows[i][0], &rows[i][0], &sx);
        exp_mul(&rows[i][1], &rows[i][1], &sy);
        exp_add(&sx, &sy);
        rows[i][2] = sx;
    }
    expansion det;
    det3_exact(rows[0], rows[1], rows[2], &det);
    return exp_estimate(&det);
}

double acd_incircle(const double a[2], const double b[2], const double c[2], const double d[2]) {
    double adx = a[0] - d[0], ady = a[1] - d[1];
    double bdx = b[0] - d[0], bdy = b[1] - d[1];
    double cdx = c[0] - d[0], cdy = c[1] - d[1];
    double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy, alift = adx * adx + ady * ady;
    double cdxady = cdx * ady, adxcdy = adx * cdy, blift = bdx * bdx + bdy * bdy;
    double adxbdy = adx * bdy, bdxady = bdx * ady, clift = cdx * cdx + cdy * cdy;
    double det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
    double perm = (fabs(bdxcdy) + fabs(cdxbdy)) * alift + (fabs(cdxady) + fabs(adxcdy)) * blift +
                  (fabs(adxbdy) + fabs(bdxady)) * clift;
    double bound = INCIRCLE_BOUND * perm;
    if (det > bound || -det > bound) return det;
    return incircle_exact(a, b, c, d);
}

/* p lies on the closed segment [a,b], given that a, b, p are collinear. */
static int collinear_between(const double p[2], const double a[2], const double b[2]) {
    return fmin(a[0], b[0]) <= p[0] && p[0] <= fmax(a[0], b[0]) && fmin(a[1], b[1]) <= p[1] &&
           p[1] <= fmax(a[1], b[1]);
}

int acd_point_on_segment(const double p[2], const double a[2], const double b[2]) {
    return acd_orient2d_sign(a, b, p) == 0 && collinear_between(p, a, b);
}

acd_seg_relation acd_segments_relation(const double p0[2], const double p1[2], const double q0[2],
                                       const double q1[2]) {
    int o1 = acd_orient2d_sign(p0, p1, q0);
    int o2 = acd_orient2d_sign(p0, p1, q1);
    int o3 = acd_orient2d_sign(q0, q1, p0);
    int o4 = acd_orient2d_sign(q0, q1, p1);
    if (o1 == 0 && o2 == 0) {
        /* collinear: count shared points */
        int q0in = collinear_between(q0, p0, p1), q1in = collinear_between(q1, p0, p1);
        int p0in = collinear_between(p0, q0, q1), p1in = collinear_between(p1, q0, q1);
        if (!(q0in || q1in || p0in || p1in)) return ACD_SEG_DISJOINT;
        /* a single shared endpoint is a touch, anything more an overlap */
        int same00 = p0[0] == q0[0] && p0[1] == q0[1], same01 = p0[0] == q1[0] && p0[1] == q1[1];
        int same10 = p1[0] == q0[0] && p1[1] == q0[1], same11 = p1[0] == q1[0] && p1[1] == q1[1];
        int shared = same00 + same01 + same10 + same11;
        int inner = (q0in && !same00 && !same10) + (q1in && !same01 && !same11) +
                    (p0in && !same00 && !same01) + (p1in && !same10 && !same11);
        if (inner == 0 && shared == 1) return ACD_SEG_TOUCH;
        return ACD_SEG_OVERLAP;
    }
    if (o1 * o2 > 0 || o3 * o4 > 0) return ACD_SEG_DISJOINT;
    if (o1 != 0 && o2 != 0 && o3 != 0 && o4 != 0) return ACD_SEG_PROPER;
    return ACD_SEG_TOUCH;
}
