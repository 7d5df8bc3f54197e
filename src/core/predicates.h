/* core/predicates: robust geometric predicates (adaptive exact arithmetic).
 *
 * Each predicate first evaluates the determinant in floating point with a forward error
 * bound; only when the sign is not certain does it recompute exactly with floating-point
 * expansions (error-free sums and FMA products). The signs returned are exact for any finite
 * double input. Every geometric decision in acd (notch, side of line, segment crossing,
 * side of plane) goes through these. */
#ifndef ACD_CORE_PREDICATES_H
#define ACD_CORE_PREDICATES_H

/* > 0 if a, b, c turn counterclockwise, < 0 if clockwise, 0 if collinear. The magnitude is an
 * approximation of twice the signed triangle area (exact sign). */
double acd_orient2d(const double a[2], const double b[2], const double c[2]);

/* Sign (-1, 0, +1) of acd_orient2d. */
int acd_orient2d_sign(const double a[2], const double b[2], const double c[2]);

/* > 0 if d lies below the plane through a, b, c (a, b, c counterclockwise seen from above),
 * i.e. the sign of det[a-d; b-d; c-d]; 0 if coplanar. Exact sign. */
double acd_orient3d(const double a[3], const double b[3], const double c[3], const double d[3]);
int acd_orient3d_sign(const double a[3], const double b[3], const double c[3], const double d[3]);

/* > 0 if d lies inside the circle through a, b, c (counterclockwise), < 0 outside, 0 on it. */
double acd_incircle(const double a[2], const double b[2], const double c[2], const double d[2]);

/* Segment relations in 2D, decided exactly. */
typedef enum acd_seg_relation {
    ACD_SEG_DISJOINT = 0,
    ACD_SEG_PROPER,   /* the interiors cross at one point */
    ACD_SEG_TOUCH,    /* they meet at an endpoint of one of them (not overlapping) */
    ACD_SEG_OVERLAP   /* collinear and sharing more than one point */
} acd_seg_relation;

acd_seg_relation acd_segments_relation(const double p0[2], const double p1[2],
                                       const double q0[2], const double q1[2]);

/* True if point p lies on the closed segment [a, b] (exact). */
int acd_point_on_segment(const double p[2], const double a[2], const double b[2]);

#endif
