/* acd3/region_cut: restricting a plane cut to the one section region at the feature being
 * resolved (spec acd3d.md §5.3, decision A13, after Chazelle's cut as summarised in the
 * dissertation §II.B.2: "split only the edges and faces that meet E within s").
 *
 * acd_plane_cut splits a solid along every section of the plane. Here the cap regions (connected
 * sets of cap triangles: one outer loop with its holes) are matched between the two sides; every
 * region but the one nearest to the witness is glued back: the pieces it separates are merged,
 * their two caps over that region dropped and the section vertices (identical on both sides)
 * welded. Only the selected region stays cut. */
#ifndef ACD_ACD3_REGION_CUT_H
#define ACD_ACD3_REGION_CUT_H

#include "acd/base.h"
#include "geom3/plane_cut.h"

/* Rewrites cut in place so that only the section region nearest to point x stays cut.
 * Pieces may merge (npieces decreases, possibly to 1). Returns ACD_ERR_NOMEM on allocation
 * failure (cut is then freed). */
acd_status acd3_restrict_cut(acd_cut_result *cut, const double x[3], acd_error *err);

#endif
