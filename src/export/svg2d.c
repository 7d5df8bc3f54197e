/* export/svg2d: SVG picture of 2D decompositions (see svg2d.h). */
#include "export/svg2d.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"

acd_svg2d_options acd_svg2d_default_options(void) {
    acd_svg2d_options o;
    memset(&o, 0, sizeof o);
    o.width = 800;
    o.max_height = 800;
    o.draw_input = 1;
    o.draw_hulls = 1;
    o.draw_cuts = 1;
    o.title = NULL;
    return o;
}

typedef struct view {
    double x0, y1, s, m;
} view;

static double px(const view *v, double x) {
    return v->m + (x - v->x0) * v->s;
}
static double py(const view *v, double y) {
    return v->m + (v->y1 - y) * v->s;
}

static void ring_path(FILE *f, const view *v, const acd_vec2 *p, size_t n) {
    for (size_t i = 0; i < n; i++) fprintf(f, "%c%.3f %.3f", i ? 'L' : 'M', px(v, p[i].x), py(v, p[i].y));
    if (n) fputc('Z', f);
}

static void xml_text(FILE *f, const char *s) {
    for (; *s; s++) {
        switch (*s) {
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '&': fputs("&amp;", f); break;
        default: fputc(*s, f);
        }
    }
}

acd_status acd_svg2d_write(const char *path, const acd_polygon *inputs, const acd2d_result *results, size_t count,
                           const acd_svg2d_options *optp, acd_error *err) {
    acd_svg2d_options o = optp ? *optp : acd_svg2d_default_options();
    if (!(o.width > 0)) o.width = 800;
    if (!(o.max_height > 0)) o.max_height = o.width;
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (size_t i = 0; i < count; i++) {
        size_t n = acd_polygon_num_points(&inputs[i]);
        for (size_t k = 0; k < n; k++) {
            acd_vec2 p = inputs[i].points[k];
            x0 = fmin(x0, p.x);
            y0 = fmin(y0, p.y);
            x1 = fmax(x1, p.x);
            y1 = fmax(y1, p.y);
        }
    }
    if (!(x1 >= x0)) x0 = y0 = 0, x1 = y1 = 1;
    double w = x1 - x0, h = y1 - y0;
    view v;
    v.m = 10;
    double top = o.title ? 24 : 0;
    double sx = w > 0 ? (o.width - 2 * v.m) / w : INFINITY, sy = h > 0 ? (o.max_height - 2 * v.m - top) / h : INFINITY;
    v.s = fmin(sx, sy);
    if (!isfinite(v.s) || !(v.s > 0)) v.s = 1;
    v.x0 = x0;
    v.y1 = y1;
    double W = 2 * v.m + w * v.s, H = 2 * v.m + h * v.s + top;

    FILE *f = fopen(path, "w");
    if (!f) return acd_fail(err, ACD_ERR_IO, "cannot write the SVG picture '%s': %s", path, strerror(errno));
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.3f %.3f\">\n",
            ceil(W), ceil(H), W, H);
    fprintf(f, "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n");
    if (o.title) {
        fprintf(f, "<text x=\"%.1f\" y=\"17\" font-family=\"sans-serif\" font-size=\"13\">", v.m);
        xml_text(f, o.title);
        fprintf(f, "</text>\n<g transform=\"translate(0 %.1f)\">\n", top);
    } else {
        fprintf(f, "<g>\n");
    }
    if (o.draw_input) {
        fprintf(f, "<g id=\"input\" fill=\"#e6e6e6\" stroke=\"#222\" stroke-width=\"1.6\" fill-rule=\"evenodd\">\n");
        for (size_t i = 0; i < count; i++) {
            fprintf(f, "<path d=\"");
            for (size_t r = 0; r < inputs[i].nrings; r++)
                ring_path(f, &v, acd_polygon_ring(&inputs[i], r), acd_polygon_ring_size(&inputs[i], r));
            fprintf(f, "\"/>\n");
        }
        fprintf(f, "</g>\n");
    }
    if (results) {
        size_t k = 0;
        fprintf(f, "<g id=\"components\" stroke=\"#333\" stroke-width=\"0.6\" stroke-linejoin=\"round\">\n");
        for (size_t i = 0; i < count; i++)
            for (size_t c = 0; c < results[i].ncomponents; c++, k++) {
                double hue = fmod((double)k * 137.50776405, 360.0);
                fprintf(f, "<path fill=\"hsl(%.1f,62%%,%d%%)\" d=\"", hue, 58 + (int)(k % 3) * 6);
                ring_path(f, &v, results[i].components[c].points, results[i].components[c].npoints);
                fprintf(f, "\"/>\n");
            }
        fprintf(f, "</g>\n");
        if (o.draw_hulls) {
            fprintf(f, "<g id=\"hulls\" fill=\"none\" stroke=\"#444\" stroke-width=\"0.5\" stroke-dasharray=\"3 2\">\n");
            for (size_t i = 0; i < count; i++)
                for (size_t c = 0; c < results[i].ncomponents; c++) {
                    if (results[i].components[c].nhull < 2) continue;
                    fprintf(f, "<path d=\"");
                    ring_path(f, &v, results[i].components[c].hull, results[i].components[c].nhull);
                    fprintf(f, "\"/>\n");
                }
            fprintf(f, "</g>\n");
        }
        if (o.draw_cuts) {
            fprintf(f, "<g id=\"cuts\" stroke=\"#d00000\" stroke-width=\"1.2\" fill=\"#d00000\">\n");
            for (size_t i = 0; i < count; i++)
                for (size_t c = 0; c < results[i].ncuts; c++) {
                    const acd_vec2 *s = results[i].cuts[c];
                    fprintf(f, "<line x1=\"%.3f\" y1=\"%.3f\" x2=\"%.3f\" y2=\"%.3f\"/>", px(&v, s[0].x), py(&v, s[0].y),
                            px(&v, s[1].x), py(&v, s[1].y));
                    fprintf(f, "<circle cx=\"%.3f\" cy=\"%.3f\" r=\"1.6\" stroke=\"none\"/>\n", px(&v, s[0].x),
                            py(&v, s[0].y));
                }
            fprintf(f, "</g>\n");
        }
    }
    fprintf(f, "</g>\n</svg>\n");
    int bad = ferror(f);
    bad |= fclose(f) != 0;
    if (bad) return acd_fail(err, ACD_ERR_IO, "error writing the SVG picture '%s'", path);
    return ACD_OK;
}
