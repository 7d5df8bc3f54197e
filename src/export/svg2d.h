/* export/svg2d: an SVG picture of 2D decompositions (`acd 2d --svg`): the input polygons (grey,
 * holes cut out), the components in distinct colours (hues spaced by the golden angle), their
 * convex hulls as dashed outlines and the cuts in red with dotted ends, scaled to fit a box of
 * `width` x `max_height` pixels with the y axis pointing up as in the input. */
#ifndef ACD_EXPORT_SVG2D_H
#define ACD_EXPORT_SVG2D_H

#include "acd/acd2d.h"

typedef struct acd_svg2d_options {
    double width;       /* picture width in pixels (default 800) */
    double max_height;  /* at most this high (default 800); the scale fits both */
    int draw_input;     /* default 1 */
    int draw_hulls;     /* default 1 */
    int draw_cuts;      /* default 1 */
    const char *title;  /* optional caption written at the top (may be NULL) */
} acd_svg2d_options;

acd_svg2d_options acd_svg2d_default_options(void);

/* Draws count input polygons and their results (results may be NULL: input only) into path. */
acd_status acd_svg2d_write(const char *path, const acd_polygon *inputs, const acd2d_result *results, size_t count,
                           const acd_svg2d_options *opt, acd_error *err);

#endif
