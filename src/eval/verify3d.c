/* eval/verify3d: the independent check of a 3D decomposition (include/acd/verify3d.h); `acd 3d
 * --verify` calls it. */
#include "acd/verify3d.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "acd/hull.h"
#include "core/error.h"
#include "geom3/frame.h"

/* Six times the signed volume of the tetrahedron (origin, triangle t of m). The check takes it in
 * its own local frame (verify_frame): about the origin, far coordinates (1e4 times the extent
 * already) cancelled the volume away. */
static double tet6(const acd_mesh *m, size_t t) {
    const double *a = m->vertices + 3 * m->triangles[3 * t], *b = m->vertices + 3 * m->triangles[3 * t + 1],
                 *c = m->vertices + 3 * m->triangles[3 * t + 2];
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

static double tri_area(const acd_mesh *m, size_t t) {
    const double *a = m->vertices + 3 * m->triangles[3 * t], *b = m->vertices + 3 * m->triangles[3 * t + 1],
                 *c = m->vertices + 3 * m->triangles[3 * t + 2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
    return 0.5 * sqrt(x * x + y * y + z * z);
}

/* Surface mode: the parts tile the input surface (face counts and areas add up). */
static int verify_surface(const acd_mesh *in, const acd3d_result *r, acd_error *err) {
    size_t faces = 0;
    double area = 0, ain = 0;
    for (size_t t = 0; t < in->ntriangles; t++) ain += tri_area(in, t);
    for (size_t i = 0; i < r->nparts; i++) {
        const acd_mesh *m = &r->parts[i].mesh;
        faces += m->ntriangles;
        for (size_t t = 0; t < m->ntriangles; t++) area += tri_area(m, t);
        const acd3d_node *n = &r->nodes[r->parts[i].node];
        if (n->leaf_reason == ACD3D_LEAF_TAU && r->parts[i].concavity > r->tau + r->tol)
            return acd_fail(err, ACD_ERR_VERIFY, "part %zu: concavity %.17g exceeds tau %.17g", i, r->parts[i].concavity,
                            r->tau);
    }
    if (faces != in->ntriangles)
        return acd_fail(err, ACD_ERR_VERIFY, "the parts hold %zu faces, the input %zu", faces, in->ntriangles);
    if (fabs(area - ain) > 1e-9 * ain)
        return acd_fail(err, ACD_ERR_VERIFY, "the parts' areas add up to %.17g, the input's is %.17g", area, ain);
    return ACD_OK;
}

/* The per-part checks that do not depend on the other parts: its volume, its hull rebuilt,
 * how far its vertices stick out of it, and (trimmed hulls) its volume outside. */
typedef struct verify_part {
    double v, worst, outside;
    acd_status hst; /* the hull's rebuild (herr its message) */
    acd_error herr;
    acd_status xst; /* the exact volume outside (acd_hull_volume_outside; xerr its message): outside is the
                       bound where it failed */
    acd_error xerr;
} verify_part;

/* The result as the check reads it: near the origin the result itself; far from it (geom3/frame) the
 * parts and hulls translated into a local frame (the parts' own box, exact for the coordinates in
 * it), where volumes and hull planes do not cancel. stick: how far a part vertex may lie beyond its
 * hull, vtol_area the volume per unit of area the parts may gain or lose: beyond the run's own
 * rounding, the outputs' rounding to model coordinates (half a spacing of the largest coordinate for
 * each computed point; a point of a part and one of its hull both moved: within 2 spacings). */
typedef struct verify_frame {
    acd_frame f;
    acd_mesh *parts; /* NULL when not moved */
    double **hulls;
    double stick, vtol_area;
} verify_frame;

static void verify_frame_free(verify_frame *vf, size_t n) {
    for (size_t i = 0; vf->parts && i < n; i++) free(vf->parts[i].vertices), free(vf->hulls[i]);
    free(vf->parts);
    free(vf->hulls);
}

static acd_status verify_frame_make(const acd3d_result *r, verify_frame *vf, acd_error *err) {
    memset(vf, 0, sizeof *vf);
    size_t n = 0;
    for (size_t i = 0; i < r->nparts; i++) n += r->parts[i].mesh.nvertices;
    double *all = malloc((n ? 3 * n : 3) * sizeof *all);
    if (!all) return acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    n = 0;
    for (size_t i = 0; i < r->nparts; i++) {
        memcpy(all + 3 * n, r->parts[i].mesh.vertices, 3 * r->parts[i].mesh.nvertices * sizeof *all);
        n += r->parts[i].mesh.nvertices;
    }
    acd_geom3_frame_of(all, n, &vf->f);
    free(all);
    vf->stick = 1e-9 * r->scale;
    if (!vf->f.moved) return ACD_OK;
    double big = 0; /* the hulls' magnitude too */
    for (size_t i = 0; i < r->nparts; i++)
        for (size_t k = 0; k < 3 * r->parts[i].hull.nvertices; k++) big = fmax(big, fabs(r->parts[i].hull.vertices[k]));
    double spacing = fmax(vf->f.spacing, nextafter(big, INFINITY) - big);
    vf->stick += 2 * spacing;
    vf->vtol_area = 2 * spacing;
    vf->parts = calloc(r->nparts ? r->nparts : 1, sizeof *vf->parts);
    vf->hulls = calloc(r->nparts ? r->nparts : 1, sizeof *vf->hulls);
    if (!vf->parts || !vf->hulls) {
        verify_frame_free(vf, 0);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    }
    for (size_t i = 0; i < r->nparts; i++) {
        const acd_mesh *m = &r->parts[i].mesh;
        const acd_mesh *h = &r->parts[i].hull;
        vf->parts[i] = *m;
        vf->parts[i].vertices = malloc((m->nvertices ? 3 * m->nvertices : 3) * sizeof(double));
        vf->hulls[i] = malloc((h->nvertices ? 3 * h->nvertices : 3) * sizeof(double));
        if (!vf->parts[i].vertices || !vf->hulls[i]) {
            verify_frame_free(vf, i + 1);
            return acd_fail(err, ACD_ERR_NOMEM, "out of memory");
        }
        memcpy(vf->parts[i].vertices, m->vertices, 3 * m->nvertices * sizeof(double));
        memcpy(vf->hulls[i], h->vertices, 3 * h->nvertices * sizeof(double));
        acd_geom3_frame_to_local(&vf->f, vf->parts[i].vertices, m->nvertices);
        acd_geom3_frame_to_local(&vf->f, vf->hulls[i], h->nvertices);
    }
    return ACD_OK;
}

static void verify_one(const acd3d_result *r, const verify_frame *vf, size_t i, double trim, verify_part *q) {
    const acd3d_part *p = &r->parts[i];
    const acd_mesh *m = vf->parts ? &vf->parts[i] : &p->mesh;
    const double *hv = vf->parts ? vf->hulls[i] : p->hull.vertices;
    double v = 0;
    for (size_t t = 0; t < m->ntriangles; t++) v += tet6(m, t);
    q->v = v / 6.0;
    q->worst = -INFINITY;
    q->outside = 0;
    q->xst = ACD_OK;
    /* inside its hull: every part vertex on the inner side of every hull facet plane */
    acd_hull h;
    q->hst = acd_hull_compute(hv, p->hull.nvertices, &h, &q->herr);
    if (q->hst != ACD_OK) return;
    for (size_t k = 0; k < m->nvertices; k++) {
        double d = acd_hull_plane_distance(&h, m->vertices + 3 * k);
        if (d > q->worst) q->worst = d;
    }
    /* trimmed hulls: the part's volume outside its hull, exactly (the part cut by the distinct
     * planes of the facets it sticks out of, the pieces beyond them summed; on a part the rounding
     * back to model coordinates left pinched, or one crossing itself, tetrahedron by tetrahedron:
     * acd_hull_volume_outside); where that fails (a part not closed, out of memory), an upper bound
     * (the part beyond each of those planes, summed; NaN: out of memory) */
    if (trim > 0 && q->worst > vf->stick) {
        q->xst = acd_hull_volume_outside(&h, m, vf->stick, r->scale, &q->outside, &q->xerr);
        if (q->xst != ACD_OK) q->outside = acd_hull_volume_outside_bound(&h, m, vf->stick, r->scale);
    }
    acd_hull_free(&h);
}

/* Solid mode: checks computed here from the result, independently of the driver's bookkeeping. The
 * parts' own checks (verify_one) run in parallel (threads; 0: OpenMP's default), the verdict is
 * then read in part order: the same report as one serial pass for any thread count. With trimmed
 * hulls: *outside_sum the parts' volume outside their hulls, *nbound the parts where it is the
 * bound (the exact cut failed). */
static int verify_solid(const acd3d_result *r, int budget, double trim, int threads, double *outside_sum,
                        size_t *nbound, acd_error *err) {
    /* Rounding in the volume sums grows with the sum of the tetrahedra's absolute volumes (not
     * with the net volume: a thin or tiny solid far from the origin cancels a lot), so the
     * tolerances are relative to that sum. */
    verify_frame vf;
    acd_status fst = verify_frame_make(r, &vf, err);
    if (fst != ACD_OK) return fst;
    double sum = 0, abs_sum = 0, area = 0;
    for (size_t i = 0; i < r->nparts; i++) {
        const acd_mesh *m = vf.parts ? &vf.parts[i] : &r->parts[i].mesh;
        for (size_t t = 0; t < m->ntriangles; t++) abs_sum += fabs(tet6(m, t)) / 6.0;
        if (vf.parts)
            for (size_t t = 0; t < m->ntriangles; t++) area += tri_area(m, t);
    }
    const double vtol = 1e-9 * fabs(r->input_volume) + 1e-12 * abs_sum + vf.vtol_area * area;
    verify_part *vp = malloc((r->nparts ? r->nparts : 1) * sizeof *vp);
    if (!vp) {
        verify_frame_free(&vf, r->nparts);
        return acd_fail(err, ACD_ERR_NOMEM, "out of memory");
    }
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads > 0 ? threads : omp_get_max_threads()) \
    if (r->nparts > 1 && threads != 1)
#endif
    for (long i = 0; i < (long)r->nparts; i++) verify_one(r, &vf, (size_t)i, trim, &vp[i]);
    verify_frame_free(&vf, r->nparts);
    double outside = 0; /* with trim: the parts' volume outside their hulls (exact, or bounds) */
    size_t nb = 0, first_bound = 0; /* parts measured by the bound, the first of them */
    int ret = ACD_OK;
    for (size_t i = 0; i < r->nparts && ret == ACD_OK; i++) {
        const acd3d_part *p = &r->parts[i];
        const acd3d_node *n = &r->nodes[p->node];
        const verify_part *q = &vp[i];
        double v = q->v;
        /* a flat part (its hull has no volume) may round to a tiny negative volume */
        if (n->leaf_reason == ACD3D_LEAF_FLAT ? !(v >= -vtol) : !(v > 0)) {
            ret = acd_fail(err, ACD_ERR_VERIFY, "part %zu has no positive volume (%g)", i, v);
            break;
        }
        sum += v;
        if (n->leaf_reason == ACD3D_LEAF_TAU && p->concavity > r->tau + r->tol)
            ret = acd_fail(err, ACD_ERR_VERIFY, "part %zu: concavity %.17g exceeds tau %.17g", i, p->concavity, r->tau);
        else if (n->leaf_reason == ACD3D_LEAF_JOINED && p->concavity > r->merge_tau + r->tol)
            ret = acd_fail(err, ACD_ERR_VERIFY, "joined part %zu: bound %.17g exceeds the merge tolerance %.17g", i,
                           p->concavity, r->merge_tau);
        else if (n->leaf_reason == ACD3D_LEAF_BUDGET && p->concavity > r->merge_tau + r->tol)
            ret = acd_fail(err, ACD_ERR_VERIFY, "budget part %zu: bound %.17g exceeds the merge tolerance %.17g", i,
                           p->concavity, r->merge_tau);
        /* a part left above the tolerance (no_cut, depth): in a budget run the merge tolerance, which
         * the budget pass brings every part within (no_cut there: a part it could not) */
        else if (n->leaf_reason != ACD3D_LEAF_TAU && n->leaf_reason != ACD3D_LEAF_FLAT && n->leaf_reason != ACD3D_LEAF_BUDGET &&
                 n->leaf_reason != ACD3D_LEAF_MERGED && n->leaf_reason != ACD3D_LEAF_JOINED &&
                 (p->concavity > r->tau + r->tol || (budget && p->concavity > r->merge_tau + r->tol) ||
                  (budget && (n->leaf_reason == ACD3D_LEAF_NO_CUT || n->leaf_reason == ACD3D_LEAF_DEPTH))))
            ret = acd_fail(err, ACD_ERR_VERIFY, "part %zu: concavity %.17g exceeds %s %.17g (%s)", i, p->concavity,
                           budget ? "the merge tolerance" : "tau", budget ? fmin(r->tau, r->merge_tau) : r->tau,
                           acd3d_leaf_reason_name(n->leaf_reason));
        else if (q->hst != ACD_OK)
            ret = acd_fail(err, ACD_ERR_VERIFY, "part %zu: its hull cannot be rebuilt: %s", i, q->herr.message);
        else if (trim > 0 && q->worst > vf.stick && isnan(q->outside))
            ret = acd_fail(err, ACD_ERR_NOMEM, "out of memory");
        else if (trim > 0 && q->worst > vf.stick) {
            outside += q->outside;
            if (q->xst != ACD_OK && nb++ == 0) first_bound = i;
        }
        else if (!(trim > 0) && q->worst > vf.stick)
            ret = acd_fail(err, ACD_ERR_VERIFY, "part %zu sticks out of its hull by %g", i, q->worst);
    }
    if (ret == ACD_OK) *outside_sum = outside, *nbound = nb;
    if (ret == ACD_OK && trim > 0 && outside > trim * r->input_volume * (1 + 1e-6) + vtol) {
        if (nb == 0)
            ret = acd_fail(err, ACD_ERR_VERIFY,
                           "the parts' volume outside their trimmed hulls, %.17g (exact: each part cut by its hull's "
                           "facet planes), exceeds %g of the input's %.17g",
                           outside, trim, r->input_volume);
        else
            ret = acd_fail(err, ACD_ERR_VERIFY,
                           "the parts' volume outside their trimmed hulls, up to %.17g (exact on all but %zu part(s), "
                           "on those an upper bound, the part beyond each facet plane summed, as the exact cut failed: "
                           "part %zu: %.200s), exceeds %g of the input's %.17g",
                           outside, nb, first_bound, vp[first_bound].xerr.message, trim, r->input_volume);
    }
    free(vp);
    if (ret != ACD_OK) return ret;
    if (fabs(sum - r->input_volume) > vtol)
        return acd_fail(err, ACD_ERR_VERIFY, "part volumes add up to %.17g, the input's is %.17g", sum,
                        r->input_volume);
    return ACD_OK;
}

acd_status acd3d_verify(const acd_mesh *input, const acd3d_params *params, const acd3d_result *r,
                        acd3d_verify_report *report, acd_error *err) {
    if (!input || !params || !r)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "acd3d_verify: NULL %s",
                        !input ? "input" : !params ? "params" : "result");
    acd3d_verify_report rep = {0, 0};
    acd_status st = params->mode == ACD3D_SOLID
                        ? (acd_status)verify_solid(r, params->budget_parts > 0, params->trim_coverage, params->threads,
                                                   &rep.outside, &rep.nbound, err)
                        : (acd_status)verify_surface(input, r, err);
    if (report) *report = rep;
    return st;
}
