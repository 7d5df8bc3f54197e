/* acd/verify3d.h: independent check of a 3D decomposition (an acd3d_result), what `acd 3d --verify`
 * runs (docs/acd3d.md "Verification").
 *
 * Solid mode, from the result's parts and hulls alone (not the driver's bookkeeping):
 *   - every part encloses a positive volume (a flat leaf: not below the rounding), and the parts'
 *     volumes add up to the input's (result.input_volume) within a tolerance relative to the sum of
 *     the parts' tetrahedra's absolute volumes (1e-12) and the input's volume (1e-9);
 *   - every part meets its bound: a tau leaf tau, a joined (merge pass) or budget part the merge
 *     tolerance, any other part (no_cut, depth, hull_distance) tau, and with a part budget the merge
 *     tolerance too (a no_cut or depth part fails there: the budget pass brings every part within);
 *   - every part's hull, rebuilt from its vertices, encloses the part (no part vertex beyond a facet
 *     plane by more than 1e-9 of the input's radius). With trim_coverage > 0 the hulls were trimmed
 *     on purpose: instead the parts' volume outside their hulls (each part cut by its hull's facet
 *     planes, exactly; an upper bound where that cut fails) is at most trim_coverage of the input's.
 * Far from the origin the parts and hulls are moved into a local frame first (geom3/frame), and the
 * tolerances grow by the rounding of the outputs to model coordinates.
 * Surface mode: the parts hold as many faces as the input and their areas add up to its area
 * (1e-9 relative), and every tau leaf meets tau.
 * The per-part checks run in parallel (params.threads), the verdict is read in part order: the same
 * report for any thread count. */
#ifndef ACD_VERIFY3D_H
#define ACD_VERIFY3D_H

#include <stddef.h>

#include "acd/acd3d.h"
#include "acd/base.h"
#include "acd/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct acd3d_verify_report {
    double outside; /* trim_coverage > 0: the parts' volume outside their hulls (exact, or bounds) */
    size_t nbound;  /* of the parts, those where it is the upper bound (the exact cut failed) */
} acd3d_verify_report;

/* Checks result r of acd3d_decompose(input, params, ...) as above. input: the mesh that was
 * decomposed (surface mode compares the parts with it; solid mode reads r->input_volume); params: the
 * run's (mode, budget_parts, trim_coverage, threads). Returns ACD_OK, or ACD_ERR_VERIFY with the first
 * failing check in err (the part and the figures), ACD_ERR_NOMEM, ACD_ERR_INVALID_ARGUMENT for a NULL
 * argument. report may be NULL. */
acd_status acd3d_verify(const acd_mesh *input, const acd3d_params *params, const acd3d_result *r,
                        acd3d_verify_report *report, acd_error *err);

#ifdef __cplusplus
}
#endif

#endif
