/* acd/mesh.h: indexed triangle meshes: reading and writing (OBJ, OFF, PLY, STL, optionally
 * gzip-compressed), multi-part OBJ (o/g groups), validation report and repair.
 *
 * Readers take what real files contain (open, non-manifold, badly oriented meshes, polygon
 * soups): polygons are fanned into triangles, STL soups are welded on exact coordinates, and the
 * result is reported on by acd_mesh_validate rather than refused. A reader fails only on a file
 * it cannot make sense of (malformed syntax, an unknown OBJ statement, index out of range, NaN/Inf
 * coordinate), with a message naming the file and the line (text formats) or byte offset (binary
 * formats). What a reader skips that may be geometry (OBJ points, lines, free-form curves and
 * surfaces; PLY elements such as edge) is told to the warning callback of the _ex readers (acd_mesh_read_options). */
#ifndef ACD_MESH_H
#define ACD_MESH_H

#include "acd/base.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct acd_mesh {
    double *vertices;     /* 3 * nvertices */
    size_t nvertices;
    uint32_t *triangles;  /* 3 * ntriangles, counterclockwise seen from outside */
    size_t ntriangles;
} acd_mesh;

/* Frees the arrays of m (not m itself) and zeroes it. NULL is allowed. */
void acd_mesh_free(acd_mesh *m);

/* Deep copy; dst is overwritten (not freed first). */
acd_status acd_mesh_copy(acd_mesh *dst, const acd_mesh *src, acd_error *err);

/* ---------------------------------------------------------------------------------------
 * Reading and writing */

typedef enum acd_mesh_format {
    ACD_MESH_FORMAT_AUTO = 0,  /* read: from the content; write: from the file name's extension */
    ACD_MESH_FORMAT_OBJ,       /* Wavefront OBJ (write: %.17g coordinates) */
    ACD_MESH_FORMAT_OFF,       /* Geomview OFF (write: %.17g coordinates) */
    ACD_MESH_FORMAT_PLY,       /* read: any PLY; write: binary little-endian, double xyz, uint32 indices */
    ACD_MESH_FORMAT_PLY_ASCII, /* write: ASCII PLY with %.17g coordinates */
    ACD_MESH_FORMAT_STL,       /* read: ASCII or binary STL; write: binary STL (float32) */
    ACD_MESH_FORMAT_STL_ASCII  /* write: ASCII STL with %.17g coordinates (not rounded to float) */
} acd_mesh_format;

/* Static name of a format ("obj", "off", "ply", "ply-ascii", "stl", "stl-ascii", "auto"). */
const char *acd_mesh_format_name(acd_mesh_format f);

/* Format from a file name's extension (.obj .off .ply .stl, optionally followed by .gz);
 * ACD_MESH_FORMAT_AUTO when unknown. */
acd_mesh_format acd_mesh_format_from_path(const char *path);

/* Reads a mesh file. The format is detected from the content (gzip is decompressed first); the
 * extension is used only when the content is not conclusive (e.g. a truncated binary STL).
 * Every o/g group of an OBJ goes into the one mesh. *out is overwritten; free with
 * acd_mesh_free. On failure *out is empty and err says what and where. */
acd_status acd_mesh_read(const char *path, acd_mesh *out, acd_error *err);

/* Same from memory. hint: the format if known, else AUTO. name: used in error messages (may be
 * NULL). data need not be NUL-terminated. */
acd_status acd_mesh_read_memory(const void *data, size_t size, acd_mesh_format hint, const char *name,
                                acd_mesh *out, acd_error *err);

/* Options of the _ex readers. Zero-initialised (or acd_mesh_read_default_options) they read as
 * the plain functions do. */
typedef struct acd_mesh_read_options {
    acd_warning_fn warning; /* optional: told about what was read but not used (OBJ: point, line and
                               free-form elements, docs/mesh.md "OBJ statements"; PLY: elements
                               other than vertex, face and tristrips), one message per
                               kind of statement, naming the file, the first line and the count */
    void *warning_user;
} acd_mesh_read_options;

acd_mesh_read_options acd_mesh_read_default_options(void);

/* acd_mesh_read, acd_mesh_read_memory, acd_mesh_read_parts and acd_mesh_read_parts_memory with
 * options (opt may be NULL: the defaults). */
acd_status acd_mesh_read_ex(const char *path, const acd_mesh_read_options *opt, acd_mesh *out, acd_error *err);
acd_status acd_mesh_read_memory_ex(const void *data, size_t size, acd_mesh_format hint, const char *name,
                                   const acd_mesh_read_options *opt, acd_mesh *out, acd_error *err);

/* Writes m to path. fmt AUTO: from the extension. A path ending in ".gz" is gzip-compressed.
 * Indices must be < nvertices (checked: ACD_ERR_INVALID_ARGUMENT). */
acd_status acd_mesh_write(const char *path, const acd_mesh *m, acd_mesh_format fmt, acd_error *err);

/* Same into a malloc'd buffer (*data, *size; caller frees *data). fmt must not be AUTO. */
acd_status acd_mesh_write_memory(const acd_mesh *m, acd_mesh_format fmt, void **data, size_t *size,
                                 acd_error *err);

/* The volume of the solid bounded by the closed, outward mesh m beyond the plane n.x + d = 0
 * (plane = {n, d}; the side n.x + d > 0; n need not be unit): the divergence theorem over the
 * triangles clipped to that side. 0 for an empty mesh; NaN for a zero or non-finite plane. */
double acd_mesh_volume_beyond(const acd_mesh *m, const double plane[4]);

/* ---------------------------------------------------------------------------------------
 * Multi-part meshes: one mesh per OBJ o/g group, e.g. the convex parts written by V-HACD or
 * CoACD. */

typedef struct acd_mesh_part {
    char *name;     /* the o/g statement's name ("" for faces before any o/g); owned */
    acd_mesh mesh;  /* only the vertices this part uses, in order of first use */
} acd_mesh_part;

typedef struct acd_mesh_parts {
    acd_mesh_part *parts;
    size_t count;
} acd_mesh_parts;

void acd_mesh_parts_free(acd_mesh_parts *p);

/* Reads a mesh as parts. OBJ: every o or g statement starts a new part (in file order); parts
 * without faces are dropped; a name that appears again starts another part of that name.
 * Other formats: one part named "". */
acd_status acd_mesh_read_parts(const char *path, acd_mesh_parts *out, acd_error *err);
acd_status acd_mesh_read_parts_memory(const void *data, size_t size, acd_mesh_format hint, const char *name,
                                      acd_mesh_parts *out, acd_error *err);
acd_status acd_mesh_read_parts_ex(const char *path, const acd_mesh_read_options *opt, acd_mesh_parts *out,
                                  acd_error *err);
acd_status acd_mesh_read_parts_memory_ex(const void *data, size_t size, acd_mesh_format hint, const char *name,
                                         const acd_mesh_read_options *opt, acd_mesh_parts *out, acd_error *err);
/* acd_mesh_read_parts restricted to OBJ files (another format is ACD_ERR_UNSUPPORTED). */
acd_status acd_mesh_read_obj_groups(const char *path, acd_mesh_parts *out, acd_error *err);

/* Writes parts as one OBJ ("o NAME" per part, %.17g coordinates); ".gz" compresses. */
acd_status acd_mesh_write_obj_parts(const char *path, const acd_mesh_parts *parts, acd_error *err);

/* ---------------------------------------------------------------------------------------
 * Validation report (src/mesh/validate.c; definitions in docs/mesh.md) */

/* One connected component: triangles joined through shared edges (non-manifold ones too). */
typedef struct acd_mesh_component {
    size_t faces, vertices, edges; /* vertices: distinct vertices used */
    size_t boundary_edges, nonmanifold_edges;
    int closed;     /* no boundary edge and no non-manifold edge */
    int orientable; /* a consistent orientation of its faces exists */
    int oriented;   /* its faces are consistently oriented as stored */
    long genus;     /* closed and orientable: (2 - chi) / 2, with chi = fans - edges + faces
                       (a vertex counts once per fan of faces around it); otherwise -1 */
    double volume;  /* signed volume enclosed as stored (> 0: outward; meaningful when closed) */
    double area;
} acd_mesh_component;

typedef struct acd_mesh_report {
    size_t vertices, faces, edges;
    size_t unused_vertices;      /* referenced by no face */
    size_t boundary_edges;       /* edges with one face */
    size_t nonmanifold_edges;    /* edges with three or more faces */
    size_t nonmanifold_vertices; /* vertices whose faces form more than one fan */
    size_t components;           /* edge-connected components (faces repeating an index excluded) */
    size_t closed_components;
    long genus;                  /* sum over the closed orientable components */
    int closed;                  /* has faces, no boundary and no non-manifold edge */
    int orientable;              /* every component orientable */
    int oriented;                /* every manifold edge used in opposite directions by its two faces */
    size_t orientation_conflicts;/* manifold edges used in the same direction by both faces */
    size_t inward_components;    /* closed components with negative volume (inside out) */
    size_t degenerate_faces;     /* a repeated vertex index or zero area (exact test) */
    size_t duplicate_faces;      /* same vertex set as an earlier face (either orientation) */
    double volume;               /* signed, sum over all faces (divergence theorem) */
    double area;
    double bbox_min[3], bbox_max[3];
    int self_intersections_checked;
    size_t self_intersections;   /* pairs of faces meeting other than at shared vertices/edges */
    uint32_t first_intersection[2]; /* the first such pair (when self_intersections > 0) */
    acd_mesh_component *component;  /* `components` entries, numbered by their first face; owned */
} acd_mesh_report;

/* Computes the report. check_self_intersections: run the exact triangle-pair test (with a
 * bounding volume hierarchy; the most expensive part). Fails with ACD_ERR_INVALID_INPUT on an
 * index out of range or a non-finite coordinate. Free with acd_mesh_report_free. */
acd_status acd_mesh_validate(const acd_mesh *m, int check_self_intersections, acd_mesh_report *r, acd_error *err);
void acd_mesh_report_free(acd_mesh_report *r);

/* Counts the pairs of faces that intersect other than in the vertices or the edge they share
 * (shared means equal coordinates, so unwelded meshes are judged correctly). Faces of zero area
 * are skipped. Decisions are exact (acd_orient3d). pairs (may be NULL) receives the first
 * max_pairs pairs (2 indices each, in a deterministic order). */
acd_status acd_mesh_self_intersections(const acd_mesh *m, size_t *count, uint32_t *pairs, size_t max_pairs,
                                       acd_error *err);

/* ---------------------------------------------------------------------------------------
 * Repair (src/mesh/weld.c, src/mesh/repair.c) */

/* Merges vertices: tol_rel == 0 merges exactly equal coordinates; tol_rel > 0 merges vertices
 * within tol_rel * (bounding-box diagonal) in every coordinate, chained transitively, each cluster
 * keeping its first vertex's position. Triangles are remapped; the vertices left are numbered in
 * order of first occurrence. *merged (may be NULL) gets the number of vertices removed. */
acd_status acd_mesh_weld(acd_mesh *m, double tol_rel, size_t *merged, acd_error *err);

typedef struct acd_repair_options {
    int weld;                    /* merge vertices first (default 1) */
    double weld_tolerance;       /* relative to the bounding-box diagonal; 0: exact (default 0) */
    int drop_degenerate;         /* drop faces with a repeated vertex or zero area (default 1) */
    int drop_duplicates;         /* drop faces with the vertex set of an earlier face (default 1) */
    int orient;                  /* orient consistently, closed parts outward (default 1) */
    size_t fill_holes_max_edges; /* fill boundary loops of at most this many edges (default 0: none) */
    int drop_unused_vertices;    /* remove vertices no face uses (default 1) */
    int split_nonmanifold;       /* after orienting: faces around an edge of more than two faces are
                                    paired into the wedges of separate solids (by angle about the
                                    edge), and every vertex whose faces form several fans gets a copy
                                    per fan (default 1): bodies touching along an edge or at a point
                                    become separate closed shells sharing positions */
    acd_progress_fn progress;    /* optional (default NULL): called from the calling thread with fraction -1
                                    and the step as stage ("repair: orienting", ...) between the steps
                                    and every ACD_REPAIR_POLL_ITEMS faces (half-edges, vertices) of
                                    their passes; non-zero stops the repair: ACD_ERR_CANCELLED, the mesh
                                    then valid (indices in range) but partly repaired. The repair is
                                    the same with or without a callback */
    void *progress_user;
} acd_repair_options;

/* Faces (half-edges, vertices) between two calls of acd_repair_options.progress within a step's
 * pass: some 0.03-0.1 s on this project's VM (docs/results/3d-large.md). */
#define ACD_REPAIR_POLL_ITEMS ((size_t)1 << 16)

acd_repair_options acd_repair_default_options(void);

typedef struct acd_repair_stats {
    size_t vertices_merged;
    size_t degenerate_dropped;
    size_t duplicates_dropped;
    size_t faces_flipped;          /* faces whose orientation was reversed */
    size_t nonorientable_parts;    /* parts oriented as far as possible (a spanning tree) */
    size_t holes_filled;
    size_t hole_faces_added;
    size_t hole_vertices_added;    /* centroids of loops closed by a fan (long loops) */
    size_t unused_vertices_dropped;
    size_t cavities;               /* closed parts oriented inward: inside an odd number of other closed parts */
    size_t nonmanifold_edges_split; /* edges of more than two faces whose faces were paired (split_nonmanifold) */
    size_t vertices_split;         /* vertex copies made by split_nonmanifold */
} acd_repair_stats;

/* Repairs m in place, in this order: weld, drop degenerate faces, drop duplicate faces, orient,
 * fill holes (minimum-area triangulations without repeated edges; long loops get a fan around
 * a new centroid vertex), orient again (closed parts outward),
 * drop unused vertices. Orientation: within each part connected through manifold edges, faces
 * are flipped to agree with the part's first face; a closed part then faces outward (positive
 * volume) unless it lies inside an odd number of other closed parts (a cavity: it faces inward);
 * an open part keeps the orientation of the majority of its faces. stats may be NULL. */
acd_status acd_mesh_repair(acd_mesh *m, const acd_repair_options *opt, acd_repair_stats *stats, acd_error *err);

#ifdef __cplusplus
}
#endif
#endif
