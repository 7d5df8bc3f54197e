/* core/tolerance: scale of an input, from which every tolerance is derived. */
#include "core/tolerance.h"

#include <float.h>
#include <math.h>

acd_scale acd_scale_of_points(const double *pts, size_t n, int dim) {
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < dim; k++) {
            double v = pts[i * (size_t)dim + (size_t)k];
            if (i == 0 || v < lo[k]) lo[k] = v;
            if (i == 0 || v > hi[k]) hi[k] = v;
        }
    double d2 = 0;
    for (int k = 0; k < dim; k++) d2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    acd_scale s;
    s.extent = sqrt(d2);
    if (!(s.extent > DBL_MIN)) s.extent = 1.0; /* a single point: any unit will do */
    s.weld = ACD_TOL_REL_WELD * s.extent;
    s.dist = ACD_TOL_REL_DIST * s.extent;
    return s;
}

acd_status acd_check_coordinates(const double *pts, size_t n, int dim, acd_error *err) {
    for (size_t i = 0; i < n * (size_t)dim; i++) {
        double v = pts[i];
        if (!isfinite(v))
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "vertex %zu has a non-finite coordinate", i / (size_t)dim);
        if (fabs(v) > ACD_COORD_MAX)
            return acd_fail(err, ACD_ERR_INVALID_INPUT,
                            "vertex %zu has coordinate %g, beyond the supported magnitude %g (the exact predicates "
                            "would overflow); scale the input down",
                            i / (size_t)dim, v, ACD_COORD_MAX);
    }
    return ACD_OK;
}

acd_status acd_check_extent(const double *pts, size_t n, int dim, acd_error *err) {
    double ext = 0;
    for (int k = 0; k < dim && n > 0; k++) {
        double lo = pts[k], hi = lo;
        for (size_t i = 1; i < n; i++) {
            double x = pts[(size_t)dim * i + (size_t)k];
            lo = x < lo ? x : lo;
            hi = x > hi ? x : hi;
        }
        if (hi - lo > ext) ext = hi - lo;
    }
    if (ext > 0 && ext < ACD_EXTENT_MIN)
        return acd_fail(err, ACD_ERR_INVALID_INPUT,
                        "the model's size (largest bounding-box extent %g) is below the supported %g (the exact "
                        "predicates' products and the volumes would underflow); scale the input up",
                        ext, ACD_EXTENT_MIN);
    return ACD_OK;
}
