/* acd/cage.h: a cage for cage-based deformation from a decomposition's convex hulls (CoRiSe paper
 * §7.2: "convex hulls are computed for each part ... slightly expanded and simplified. The final
 * cage is the union of the convex hulls"). src/corise/cage.c, docs/corise.md "Cages".
 *
 * Usage (after acd_segment):
 *   acd_cage_params cp = acd_cage_default_params();
 *   acd_cage_result cage;
 *   if (acd_cage_build(&mesh, hull_meshes, nhulls, &cp, &cage, &err) == ACD_OK) {
 *       acd_mesh_write("cage.obj", &cage.cage, ACD_MESH_OBJ, &err); acd_cage_result_free(&cage);
 *   } */
#ifndef ACD_CAGE_H
#define ACD_CAGE_H

#include "acd/base.h"
#include "acd/mesh.h"
#include "acd/segment.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ACD_CAGE_PARAMS_COOKIE 0x41434347u

typedef struct acd_cage_params {
    uint32_t cookie;        /* set by acd_cage_default_params */
    double offset;          /* outward offset of every hull, relative to the mesh's bounding-box
                               diagonal (>= 0; default 0.01): every facet plane (and the six axis
                               support planes) moves out by it, so the polytope holds every point
                               within that distance of the hull */
    size_t max_vertices;    /* simplify each hull to at most this many corners by an enclosing
                               polytope made of a subset of its support planes (0: no
                               simplification, else >= 4; default 32). Pushing the planes and the
                               exact quantization can split a corner, so the final count may exceed
                               it by a few (reported in corners) */
    int check_enclosure;    /* count the mesh vertices not inside the cage (default 1) */
} acd_cage_params;

acd_cage_params acd_cage_default_params(void);

typedef struct acd_cage_result {
    acd_mesh cage;            /* closed, outward, no interior faces (docs/corise.md "Cages") */
    size_t hulls;             /* hulls used (solid, or flat with a positive offset) */
    size_t skipped;           /* hulls left out: flat with offset 0, or empty */
    size_t chosen_corners;    /* sum of the simplified hulls' corners as chosen (floating point, with
                                 the planes pushed; a solid part's hull within the budget: its own
                                 vertex count); <= max_vertices per solid part when simplifying */
    size_t corners;           /* sum of the corners of the polytopes actually unioned: with the exact
                                 plane quantization a corner where more than three planes meet
                                 splits into nearby corners (about 1e-6 of the extent apart), and
                                 the axis planes cap sharp pushed corners */
    double offset;            /* the offset in model units */
    double diagonal;          /* the mesh's bounding-box diagonal */
    double volume;            /* of the cage (divergence theorem) */
    size_t checked_vertices;  /* mesh vertices used by faces, when check_enclosure */
    size_t outside_vertices;  /* of those, outside the cage (exact ray winding number; 0 expected) */
    size_t surface_vertices;  /* of those, exactly on the cage (possible with offset 0) */
    double seconds;
} acd_cage_result;

/* Cage around mesh from the convex hulls hulls[0..nhulls) (each an acd_mesh; only its vertices are
 * read: the hull of its vertices is taken, so a part's own faces work too). Bad params:
 * ACD_ERR_INVALID_ARGUMENT; non-finite coordinates: ACD_ERR_INVALID_INPUT; no solid hull:
 * ACD_ERR_DEGENERATE. out is caller-owned, freed with acd_cage_result_free (also after a failure). */
acd_status acd_cage_build(const acd_mesh *mesh, const acd_mesh *hulls, size_t nhulls, const acd_cage_params *params,
                          acd_cage_result *out, acd_error *err);
/* The same from a segmentation of mesh (acd_segment): one point set per part, the vertices of its
 * faces (flat parts included, which the result's hulls leave empty). Pass seg->mesh, the mesh
 * acd_segment segmented (the input welded and oriented: the same faces in the same order), so
 * that the inside tests see the orientation the labels were made with. */
acd_status acd_cage_from_segment(const acd_mesh *mesh, const acd_segment_result *seg, const acd_cage_params *params,
                                 acd_cage_result *out, acd_error *err);
void acd_cage_result_free(acd_cage_result *r);

#ifdef __cplusplus
}
#endif
#endif
