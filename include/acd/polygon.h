/* acd/polygon.h: polygons with holes; reading (.poly, GeoJSON, TopoJSON, WKT), validation, writing.
 *
 * A polygon is one outer ring followed by zero or more hole rings, stored as one point array
 * with ring offsets. After acd_polygon_normalize (done by every reader) the outer ring is
 * counterclockwise, holes clockwise, consecutive repeated vertices are dropped and no ring
 * repeats its first point at its end. An island inside a hole is a separate polygon of the set.
 * Formats, messages and decisions: docs/formats-2d.md. */
#ifndef ACD_POLYGON_H
#define ACD_POLYGON_H

#include "acd/base.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct acd_vec2 {
    double x, y;
} acd_vec2;

typedef struct acd_polygon {
    acd_vec2 *points;   /* all rings, one after the other */
    size_t *ring_start; /* ring r is points[ring_start[r] .. ring_start[r+1]-1]; nrings+1 entries */
    size_t nrings;      /* 1 outer + holes; 0 for an empty polygon */
} acd_polygon;

typedef struct acd_polygon_set {
    acd_polygon *polygons;
    size_t count;
} acd_polygon_set;

/* Input formats. ACD_FORMAT_AUTO detects from the content. */
typedef enum acd_polygon_format {
    ACD_POLY_FORMAT_AUTO = 0,
    ACD_POLY_FORMAT_POLY,    /* Lien's .poly */
    ACD_POLY_FORMAT_GEOJSON, /* Polygon, MultiPolygon, Feature, FeatureCollection, GeometryCollection */
    ACD_POLY_FORMAT_WKT,     /* POLYGON, MULTIPOLYGON */
    ACD_POLY_FORMAT_TOPOJSON /* Topology: Polygon, MultiPolygon, GeometryCollection over shared arcs */
} acd_polygon_format;

/* Options of acd_polygon_set_parse_opts / acd_polygon_set_read_file_opts. Zero-initialized
 * options read everything with format detection (what acd_polygon_set_parse does). */
typedef struct acd_polygon_read_options {
    acd_polygon_format format; /* ACD_POLY_FORMAT_AUTO: detected from the content */
    /* GeoJSON Features / TopoJSON geometries to keep (NULL: all). "VALUE" keeps those whose "id"
     * or any property equals VALUE (e.g. "South Africa"); "KEY=VALUE" those whose property KEY
     * (or "id") equals VALUE (e.g. "name=Italy", "id=710"). Numbers compare as doubles. Nothing
     * selected is an error (ACD_ERR_INVALID_INPUT); .poly and WKT refuse a selector. */
    const char *feature;
    /* TopoJSON: read only this member of "objects" (e.g. "countries"; NULL: all). */
    const char *object;
} acd_polygon_read_options;

/* What normalization changed, so a verbose CLI can say so. */
typedef struct acd_polygon_fixes {
    size_t repeated_dropped;   /* consecutive duplicate vertices removed (incl. closing repeat) */
    size_t rings_reversed;     /* rings whose orientation was flipped */
    size_t chains_ignored;     /* .poly: well-formed chains after the declared number of chains,
                                  read and ignored as the reference reader does (simple5.poly) */
} acd_polygon_fixes;

/* Builds a polygon from rings given as arrays (ring 0 outer). Copies the data. */
acd_status acd_polygon_from_rings(acd_polygon *out, const acd_vec2 *const *rings, const size_t *ring_sizes,
                                  size_t nrings, acd_error *err);
void acd_polygon_free(acd_polygon *p);
void acd_polygon_set_free(acd_polygon_set *s);
acd_status acd_polygon_copy(acd_polygon *dst, const acd_polygon *src);

static inline size_t acd_polygon_ring_size(const acd_polygon *p, size_t r) {
    return p->ring_start[r + 1] - p->ring_start[r];
}
static inline const acd_vec2 *acd_polygon_ring(const acd_polygon *p, size_t r) {
    return p->points + p->ring_start[r];
}
static inline size_t acd_polygon_num_points(const acd_polygon *p) {
    return p->nrings ? p->ring_start[p->nrings] : 0;
}

/* Signed area (outer minus holes once normalized). */
double acd_polygon_area(const acd_polygon *p);

/* Parses text in the given format: at most len bytes, stopping early at a NUL byte (so a
 * NUL-terminated string may be passed with len = SIZE_MAX). `name` is used in messages (a file
 * name; NULL gives "<input>"). Every polygon found is normalized (not validated: call
 * acd_polygon_validate on each); fixes are added to *fixes (zero it first; may be NULL). Input with no polygon at all
 * (only EMPTY or non-polygonal geometries) fails with ACD_ERR_DEGENERATE. */
acd_status acd_polygon_set_parse(acd_polygon_set *out, const char *text, size_t len, acd_polygon_format fmt,
                                 const char *name, acd_polygon_fixes *fixes, acd_error *err);
acd_status acd_polygon_set_read_file(acd_polygon_set *out, const char *path, acd_polygon_format fmt,
                                     acd_polygon_fixes *fixes, acd_error *err);
/* The same with options (opts may be NULL: defaults). With detection, JSON whose top-level
 * "type" is "Topology" is read as TopoJSON, other JSON as GeoJSON. */
acd_status acd_polygon_set_parse_opts(acd_polygon_set *out, const char *text, size_t len,
                                      const acd_polygon_read_options *opts, const char *name,
                                      acd_polygon_fixes *fixes, acd_error *err);
acd_status acd_polygon_set_read_file_opts(acd_polygon_set *out, const char *path,
                                          const acd_polygon_read_options *opts, acd_polygon_fixes *fixes,
                                          acd_error *err);

/* Normalizes in place: drops consecutive repeated vertices and closing repeats of the first
 * vertex, makes the outer ring CCW and holes CW (exact orientation test). Idempotent. Changes are
 * added to *fixes (may be NULL). Rings that are too small or degenerate are left for
 * acd_polygon_validate to report. */
acd_status acd_polygon_normalize(acd_polygon *p, acd_polygon_fixes *fixes, acd_error *err);

/* Checks that p is a valid polygon with holes: every ring has >= 3 distinct vertices, all
 * coordinates finite, no ring self-intersects or touches itself, no two rings intersect or
 * touch, every hole lies inside the outer ring, no hole lies inside another. The message names
 * the ring ("chain") and vertex indices and coordinates. `index` names the polygon in messages. */
acd_status acd_polygon_validate(const acd_polygon *p, size_t index, acd_error *err);

/* Writers. Coordinates are written with 17 significant digits, so reading the output back gives
 * the same doubles. A path of "-" writes to standard output. */
/* Lien's .poly: one "N out" chain per polygon followed by its "N in" holes, order line 1..N. */
acd_status acd_polygon_set_write_poly(const acd_polygon_set *s, const char *path, acd_error *err);
/* GeoJSON FeatureCollection: one Feature (properties {"index": i}) with a Polygon per polygon;
 * rings closed (first position repeated), outer counterclockwise, holes clockwise (RFC 7946). */
acd_status acd_polygon_set_write_geojson(const acd_polygon_set *s, const char *path, acd_error *err);

/* The same as text in a malloc'd NUL-terminated buffer (*len its length without the NUL; len may
 * be NULL). multipolygon != 0 gives one MultiPolygon geometry instead of a FeatureCollection. */
acd_status acd_polygon_set_to_poly_text(const acd_polygon_set *s, char **text, size_t *len, acd_error *err);
acd_status acd_polygon_set_to_geojson_text(const acd_polygon_set *s, int multipolygon, char **text, size_t *len,
                                           acd_error *err);
/* WKT: POLYGON for a single polygon, else MULTIPOLYGON; rings closed. */
acd_status acd_polygon_set_to_wkt_text(const acd_polygon_set *s, char **text, size_t *len, acd_error *err);
/* Writes len bytes of text to path ("-" = standard output). */
acd_status acd_polygon_write_text_file(const char *path, const char *text, size_t len, acd_error *err);

#ifdef __cplusplus
}
#endif
#endif
