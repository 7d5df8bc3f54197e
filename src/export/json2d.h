/* export/json2d: the JSON report of a 2D decomposition (`acd 2d --json`; docs/cli-2d.md).
 *
 * One document for all the polygons of an input file:
 *   {"tau", "measure", "params": {...},
 *    "input": {"polygons", "vertices", "notches", "holes", "area"},
 *    "components": [[[x,y],...], ...]    counterclockwise, first point not repeated,
 *    "hulls": [...]                      one per component, counterclockwise,
 *    "concavities": [...]                one per component, under the measure,
 *    "cuts": [[[x1,y1],[x2,y2]], ...]    every cut (and hole-merging diagonal), in order,
 *    "polygons": [{"vertices", "notches", "holes", "first_component", "components", "cuts",
 *                  "seconds"}, ...]      per input polygon,
 *    "tree": [[{"id", "parent", "children", "concavity", "cut", "hole_merge", "component"},...],...]
 *                                        one decomposition tree per input polygon (Fig. 9b),
 *    "stats": {"components", "max_concavity", "seconds"},
 *    "verify": {"passed", "message"}     only when verification ran} */
#ifndef ACD_EXPORT_JSON2D_H
#define ACD_EXPORT_JSON2D_H

#include "acd/acd2d.h"

typedef struct acd_json2d_doc {
    const acd2d_params *params;     /* may be NULL */
    const acd_polygon *inputs;      /* the decomposed polygons */
    const acd2d_result *results;    /* one per input polygon */
    size_t count;
    int verified;                   /* 0: not run, 1: passed, -1: failed */
    const char *verify_message;     /* may be NULL */
} acd_json2d_doc;

/* The document as a NUL-terminated string (caller frees with free()), or NULL when out of memory. */
char *acd_json2d_string(const acd_json2d_doc *doc);

/* Writes the document to path ("-" = standard output). */
acd_status acd_json2d_write(const char *path, const acd_json2d_doc *doc, acd_error *err);

#endif
