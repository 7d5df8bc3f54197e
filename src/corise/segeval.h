/* corise/segeval: segmentation benchmark metrics (public API in acd/segment.h). Internal helpers
 * shared with the tests. */
#ifndef ACD_CORISE_SEGEVAL_H
#define ACD_CORISE_SEGEVAL_H

#include <stddef.h>
#include <stdint.h>

#include "acd/segment.h"

/* Marks the cut vertices of a labelling: both endpoints of every mesh edge whose incident
 * triangles (two or more) do not all carry the same label. Boundary edges (one triangle) are
 * never cut edges. is_cut: m->nvertices bytes, set to 0/1. *ncut (may be NULL) gets the count.
 * Triangle indices must be < nvertices (ACD_ERR_INVALID_INPUT names the triangle otherwise). */
acd_status acd_segeval_cut_vertices(const acd_mesh *m, const int *labels, uint8_t *is_cut, size_t *ncut,
                                    acd_error *err);

/* Area-weighted mean distance of the face centroids to the area-weighted centroid of the
 * surface (the benchmark's normalisation of the cut discrepancy); 0 for a zero-area mesh. */
double acd_segeval_avg_radius(const acd_mesh *m);

#endif
