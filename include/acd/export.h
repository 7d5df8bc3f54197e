/* acd/export.h: writing a 3D decomposition for other tools: one OBJ with a group per hull, one
 * file per hull, per-part meshes, a JSON summary, and the collision snippets robot simulators read
 * (URDF: one <collision> per hull; MuJoCo MJCF: one mesh asset and one geom per hull). Hulls can be
 * simplified to a vertex budget first (physics engines cap it; the result still encloses the hull).
 * Formats and layout: docs/eval.md, "Exports". Coordinates are written with %.17g. */
#ifndef ACD_EXPORT_H
#define ACD_EXPORT_H

#include "acd/base.h"
#include "acd/eval.h"
#include "acd/hull.h"
#include "acd/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct acd_export_options {
    const char *name;          /* robot / model name (URDF, MJCF, file names); default "acd" */
    const char *hull_stem;     /* per-hull files are <hull_stem>_<i>.<ext>; default "hull" */
    const char *part_stem;     /* per-part files; default "part" */
    const char *mesh_ext;      /* extension (and format) of per-hull and per-part files: "obj"
                                  (default), "stl", "off", "ply" */
    size_t max_hull_vertices;  /* 0: hulls as they are; >= 4: simplified to at most that many
                                  vertices, still enclosing (acd_export_simplify_hulls) */
} acd_export_options;

acd_export_options acd_export_default_options(void);

/* Simplifies each dim-3 hull to at most max_vertices (>= 4) vertices, enclosing the original hull
 * (within ACD_TOL_REL_DIST of its diagonal); others are copied. out: n hulls, caller frees each. */
acd_status acd_export_simplify_hulls(const acd_hull *hulls, size_t n, size_t max_vertices, acd_hull *out,
                                     acd_error *err);

/* One OBJ with "o <hull_stem>_<i>" per hull (dim 3 hulls; flat ones are written as their polygons). */
acd_status acd_export_hulls_obj(const char *path, const acd_hull *hulls, size_t n, const acd_export_options *o,
                                acd_error *err);
/* <dir>/<hull_stem>_<i>.<ext>, i = 000, 001, ...; dir is created if missing. */
acd_status acd_export_hull_files(const char *dir, const acd_hull *hulls, size_t n, const acd_export_options *o,
                                 acd_error *err);
/* <dir>/<part_stem>_<i>.<ext>. */
acd_status acd_export_part_files(const char *dir, const acd_mesh_parts *parts, const acd_export_options *o,
                                 acd_error *err);
/* JSON summary: per hull its part's name and size, hull vertices, triangles, volume, area,
 * centroid and box; totals; the evaluation report when rep is not NULL. parts may be NULL. */
acd_status acd_export_summary_json(const char *path, const acd_mesh_parts *parts, const acd_hull *hulls, size_t n,
                                   const acd_eval_report *rep, const acd_export_options *o, acd_error *err);
/* URDF robot with one link holding one <collision> per hull, each a mesh
 * "<mesh_dir>/<hull_stem>_<i>.<ext>" (mesh_dir relative to the URDF file; may be ""). */
acd_status acd_export_urdf(const char *path, const char *mesh_dir, size_t n, const acd_export_options *o,
                           acd_error *err);
/* MuJoCo MJCF model: one <mesh> asset and one <geom type="mesh"> per hull, in one body. */
acd_status acd_export_mjcf(const char *path, const char *mesh_dir, size_t n, const acd_export_options *o,
                           acd_error *err);

/* Everything into dir (created if missing): decomposition.obj (hulls), hulls/<hull_stem>_<i>.<ext>,
 * parts/<part_stem>_<i>.<ext> (when parts is not NULL), summary.json, <name>.urdf, <name>.xml.
 * Hulls are simplified first when o->max_hull_vertices is set. */
acd_status acd_export_all(const char *dir, const acd_mesh_parts *parts, const acd_hull *hulls, size_t n,
                          const acd_eval_report *rep, const acd_export_options *o, acd_error *err);

#ifdef __cplusplus
}
#endif
#endif
