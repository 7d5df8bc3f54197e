/* geom3/frame: a local frame for input far from the origin (docs/acd3d.md "Local frame").
 *
 * A mesh whose bounding box lies far from the origin relative to its size (CAD in mm placed at a
 * site, a scan in UTM coordinates) loses its shape in every quantity accumulated about the origin:
 * a triple product of coordinates of magnitude M carries rounding ~eps M^3, a plane offset n.p
 * ~eps M. acd3d_decompose therefore runs on the input translated by a vector c chosen so that
 * x - c is EXACT for every coordinate x (the local coordinates are the input's, only moved), and
 * moves its outputs back by + c.
 *
 * The rule (per axis k, with P the smallest power of two >= the box's largest side E):
 *   - |centre_k| <= ACD_FRAME_NEAR x P: c_k = 0 (near the origin: the input as it is, bit for bit;
 *     the coordinates spend at most log2(16.5) < 5 bits on the offset there);
 *   - else c_k = the multiple of P nearest centre_k. Then every coordinate x of the box has
 *     |x - c_k| <= E/2 + P/2 <= P and |c_k| >= 15.5 P, so c_k/2 <= x <= 2 c_k (same sign): x - c_k is
 *     exact by Sterbenz's lemma, and the local box lies within [-P, P] on that axis.
 * Going back, x' + c_k is exact for the input's own coordinates and rounds a computed point (a
 * cut's vertex) to the model coordinates' spacing there, at most half an ulp of the largest
 * coordinate (acd_frame.spacing): outputs are then accurate to that spacing, which nothing in model
 * coordinates can beat.
 *
 * Coordinates that cannot resolve their own extent (a cube of side 1e-3 at 1e12, 8 ulps a side)
 * cannot hold an output to better than a large fraction of its size: acd_geom3_frame_check refuses
 * input whose extent is fewer than ACD_FRAME_MIN_STEPS spacings. */
#ifndef ACD_GEOM3_FRAME_H
#define ACD_GEOM3_FRAME_H

#include <stddef.h>

#include "acd/hull.h"
#include "acd/mesh.h"
#include "core/error.h"

/* An axis whose box centre is within this many P (the power of two >= the largest side) of the
 * origin is not moved. The data meshes reach 7.7 P (ChineseDragon-10kv along z; fold.off, 108 P,
 * has no faces): all of them run as before, bit for bit. */
#define ACD_FRAME_NEAR 16.0

/* The fewest steps of the model coordinates' spacing (the ulp of the largest coordinate) the
 * input's largest side must span: 2^16, so that an output rounded back to model coordinates is
 * within 1/131072 of the extent of where it was computed (1/3000 of the default tau's reach). fandisk
 * (extent 0.6) passes up to 1e11 extents away (7.9e4 steps) and is refused at 1e12 (4900 steps), where
 * its hulls lost 1.3e-5 of the volume to that rounding; far.off (8 steps) is refused. Real data is far
 * inside: a part of 1 mm in UTM metres (5e6) spans 1.1e6 steps. */
#define ACD_FRAME_MIN_STEPS 65536.0

typedef struct acd_frame {
    double c[3];       /* local = model - c, exact for every input coordinate */
    int moved;         /* some c[k] != 0 */
    double extent;     /* the box's largest side E */
    double spacing;    /* ulp of the largest coordinate magnitude (model coordinates): the resolution
                          of an output written there */
    size_t far_vertex; /* a vertex holding that largest magnitude */
} acd_frame;

/* The frame of n points (3 doubles each). Non-finite coordinates, n = 0 or a single point: no
 * translation (moved 0; the caller's own checks refuse bad coordinates). */
void acd_geom3_frame_of(const double *pts, size_t n, acd_frame *f);

/* ACD_ERR_INVALID_INPUT when the coordinates cannot resolve the extent (extent < ACD_FRAME_MIN_STEPS x
 * spacing; a box of no extent passes), naming the vertex holding the largest coordinate and the
 * ratio; what is the operation refusing, e.g. "solid decomposition". */
acd_status acd_geom3_frame_check(const acd_frame *f, const double *pts, const char *what, acd_error *err);

/* pts[3i+k] -= c[k] (to local; exact for the points the frame was taken of) or += c[k] (to model,
 * back). Nothing when !f->moved. */
void acd_geom3_frame_to_local(const acd_frame *f, double *pts, size_t n);
void acd_geom3_frame_to_model(const acd_frame *f, double *pts, size_t n);

/* A plane n.x + d = 0 of the local frame in model coordinates: d - n.c (rounded once). */
void acd_geom3_frame_plane_to_model(const acd_frame *f, double plane[4]);

/* Local views for functions that take a mesh or a hull in model coordinates: out shares every
 * array with the original but the vertices (translated by - c) and, for the hull, the planes
 * (offsets d + n.c, rounded once); free them with acd_geom3_frame_view_free. ACD_ERR_NOMEM only. */
acd_status acd_geom3_frame_mesh_view(const acd_frame *f, const acd_mesh *m, acd_mesh *out, acd_error *err);
acd_status acd_geom3_frame_hull_view(const acd_frame *f, const acd_hull *h, acd_hull *out, acd_error *err);
void acd_geom3_frame_view_free(acd_mesh *m, acd_hull *h); /* either may be NULL */

#endif
