/* corise/segment_api: the public segmentation API (acd/segment.h) over the CoRiSe loop of
 * corise/corise (Liu, Xi, Lien, CAD 2016, §3 and §5.2; spec corise.md §2.1, §2.10): parameters,
 * per-part concavity (the loop's own valley test of each final part), per-part convex hulls
 * (acd_hull_compute) and volumes. */
#define _POSIX_C_SOURCE 200809L
#include "acd/segment.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "acd/hull.h"
#include "core/error.h"
#include "core/tolerance.h"
#include "corise/corise.h"
#include "corise/valley.h"
#include "geom3/frame.h"
#ifdef _OPENMP
#include <omp.h>
#endif

acd_segment_params acd_segment_default_params(void) {
    acd_segment_params p;
    memset(&p, 0, sizeof p);
    p.cookie = ACD_SEGMENT_PARAMS_COOKIE;
    acd_corise_params c = acd_corise_default_params();
    p.tau = c.tau;
    p.alpha = c.cut.alpha;
    p.concave_weight = c.cut.concave_weight;
    p.clamp_hull_depth = 1; /* docs/corise.md, "Default of clamp_hull_depth" */
    p.max_depth = c.max_depth;
    p.threads = 1; /* docs/corise.md, "Speed": 2 threads measured slower on the shared machine */
    p.prepare = 1; /* docs/corise.md, "Input preparation" */
    return p;
}

void acd_segment_result_free(acd_segment_result *r) {
    if (!r) return;
    if (r->parts)
        for (size_t k = 0; k < r->nparts; k++) acd_mesh_free(&r->parts[k].hull);
    free(r->parts);
    free(r->labels);
    acd_mesh_free(&r->mesh);
    memset(r, 0, sizeof *r);
}

static double now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Hull of the corners of the faces face[0..n) (increasing; three points per face, in face order,
 * as before: the same point list, so the same hull) into part->hull. pts: scratch of 9 n doubles. */
static acd_status part_hull(const acd_mesh *m, const uint32_t *face, size_t n, double *pts, acd_segment_part *part,
                            acd_error *err) {
    size_t np = 0;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            memcpy(pts + 3 * np++, m->vertices + 3 * (size_t)m->triangles[3 * (size_t)face[i] + c], 3 * sizeof *pts);
    acd_hull h;
    acd_status st = acd_hull_compute(pts, np, &h, err);
    if (st != ACD_OK) {
        acd_hull_free(&h);
        return st;
    }
    part->hull_dim = h.dim;
    if (h.dim == 3) {
        part->hull_volume = h.volume;
        part->hull.vertices = h.vertices;
        part->hull.nvertices = h.nvertices;
        part->hull.triangles = h.triangles;
        part->hull.ntriangles = h.ntriangles;
        h.vertices = NULL;
        h.triangles = NULL;
    }
    acd_hull_free(&h);
    return ACD_OK;
}

/* ACD_ERR_CANCELLED when the poll says stop (acd3/poll: the callback from the calling thread). */
static acd_status poll_stop(acd3_poll *poll, acd_error *err) {
    if (acd3_poll_stop(poll)) return acd_fail(err, ACD_ERR_CANCELLED, "segment: cancelled by the progress callback");
    return ACD_OK;
}

/* acd_mesh_repair's progress callback in prepare: the segment's poll, telling the repair's step */
static int repair_progress(void *user, double fraction, const char *stage) {
    (void)fraction;
    acd3_poll *poll = user;
    acd3_poll_set_stage(poll, stage);
    return acd3_poll_stop(poll);
}

/* The mesh to segment (docs/corise.md, "Input preparation") into out->mesh: a copy of m, welded
 * and oriented when on. Faces keep their order and count, so the labels are the input's faces'.
 * A mesh the loop refuses (no faces, an index out of range) is copied as is, for the loop's own
 * message. */
static acd_status prepare(const acd_mesh *m, int on, acd3_poll *poll, acd_segment_result *out, acd_error *err) {
    acd_status st;
    int usable = on && m->ntriangles > 0 && m->ntriangles <= UINT32_MAX / 3;
    for (size_t t = 0; usable && t < 3 * m->ntriangles; t++) usable = m->triangles[t] < m->nvertices;
    if (!usable) return acd_mesh_copy(&out->mesh, m, err);
    /* a triangle soup (OBJ or OFF with every face its own vertices) or a mesh with vertices split
     * at texture seams: without welding every face was its own part (the torus soup: 72 parts for
     * its 72 quads). Vertices with the same coordinates are merged; a mesh without such vertices
     * keeps its numbering. Only an open mesh is welded: shells that are closed with their own
     * vertices (a model given twice, coincident) stay apart instead of becoming non-manifold */
    acd_mesh w;
    size_t merged = 0;
    if ((st = acd_mesh_copy(&w, m, err)) != ACD_OK) return st;
    if ((st = acd_mesh_weld(&w, 0, &merged, err)) != ACD_OK || (st = poll_stop(poll, err)) != ACD_OK) {
        acd_mesh_free(&w);
        return st;
    }
    int open = 0;
    if (merged > 0) {
        acd_mesh_report rep;
        acd_error verr;
        if (acd_mesh_validate(m, 0, &rep, &verr) == ACD_OK) {
            open = rep.boundary_edges > 0;
            acd_mesh_report_free(&rep);
        }
    }
    if (merged > 0 && open) {
        out->mesh = w;
        out->vertices_merged = merged;
    } else {
        acd_mesh_free(&w);
        if ((st = acd_mesh_copy(&out->mesh, m, err)) != ACD_OK) return st;
    }
    if ((st = poll_stop(poll, err)) != ACD_OK) return st;
    /* faces oriented against their neighbours, or a closed mesh inside out: valleys and ridges
     * swap (mpi_triang with all faces reversed: 3 parts, one unresolved; half of them: a valley
     * 2.3 tau left). Faces are flipped to agree, closed parts outward (cavities inward), open
     * parts as most of their faces; nothing else changes (no face dropped or moved) */
    acd_repair_options ro = acd_repair_default_options();
    ro.weld = 0;
    ro.drop_degenerate = 0;
    ro.drop_duplicates = 0;
    ro.fill_holes_max_edges = 0;
    ro.drop_unused_vertices = 0;
    ro.split_nonmanifold = 0;
    ro.progress = poll ? repair_progress : NULL; /* 0.7-0.8 CPU-s at 832k faces */
    ro.progress_user = poll;
    acd_repair_stats rs;
    const char *stage = poll ? poll->stage : NULL;
    st = acd_mesh_repair(&out->mesh, &ro, &rs, err);
    acd3_poll_set_stage(poll, stage);
    if (st != ACD_OK) return st;
    if ((st = poll_stop(poll, err)) != ACD_OK) return st;
    out->faces_flipped = rs.faces_flipped;
    out->nonorientable_parts = rs.nonorientable_parts;
    return ACD_OK;
}

acd_status acd_segment(const acd_mesh *input, const acd_segment_params *params, acd_segment_result *out,
                       acd_error *err) {
    if (!out) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "segment: NULL result");
    memset(out, 0, sizeof *out);
    if (!input || (input->nvertices && !input->vertices) || (input->ntriangles && !input->triangles))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "segment: NULL mesh");
    if (!params || params->cookie != ACD_SEGMENT_PARAMS_COOKIE)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT,
                        "segment: params not initialised by acd_segment_default_params (cookie missing)");
    if (!isfinite(params->tau) || params->tau < 0)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "segment: tau %g must be finite and >= 0", params->tau);
    if (!isfinite(params->alpha) || params->alpha < 0 || params->alpha > 1)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "segment: alpha %g must be in [0, 1]", params->alpha);
    if (!isfinite(params->concave_weight) || params->concave_weight <= 0)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "segment: concave_weight %g must be finite and > 0",
                        params->concave_weight);
    if (params->max_depth == 0)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "segment: max_depth must be at least 1");
    if (params->threads > 1024) /* as acd3d_decompose: a huge count crashes inside libgomp */
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "segment: threads %d: at most 1024 (0: as many as cores)",
                        params->threads);
    /* coordinates beyond ACD_COORD_MAX overflow the radius and volumes (a 1e300 tetrahedron gave
     * scale 1 and null volumes): refused as acd3d_decompose and acd_mesh_validate refuse them */
    if (input->nvertices) {
        acd_error ce;
        if (acd_check_coordinates(input->vertices, input->nvertices, 3, &ce) != ACD_OK ||
            acd_check_extent(input->vertices, input->nvertices, 3, &ce) != ACD_OK)
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "segment: %s", ce.message);
    }
    double t0 = now_seconds();
    /* the poll of the preparation and of the parts' hulls (the loop has its own) */
    acd_corise_poll_ctx pctx;
    acd3_poll poll_obj;
    acd3_poll *poll =
        acd_corise_poll_init(&poll_obj, &pctx, params->progress, params->progress_user, 0.0, "segment: preparing");
    acd_status st = poll_stop(poll, err);
    if (st == ACD_OK) st = prepare(input, params->prepare, poll, out, err);
    if (st != ACD_OK) {
        acd_segment_result_free(out);
        return st;
    }
    const acd_mesh *mesh = &out->mesh;
    acd_corise_params c = acd_corise_default_params();
    c.tau = params->tau;
    c.cut.alpha = params->alpha;
    c.cut.concave_weight = params->concave_weight;
    c.clamp_hull_depth = params->clamp_hull_depth;
    c.max_depth = params->max_depth;
    c.threads = params->threads;
    c.progress = params->progress;
    c.progress_user = params->progress_user;
    acd_corise_stats stats;
    double *conc = NULL, *pts = NULL;
    size_t *start = NULL;
    uint32_t *byface = NULL;
    acd_status *hst = NULL;
    acd_error *herr = NULL;
    out->labels = malloc((mesh->ntriangles ? mesh->ntriangles : 1) * sizeof *out->labels);
    if (!out->labels) goto nomem;
    st = acd_corise_segment_ex(mesh, &c, out->labels, &conc, &stats, err);
    if (st != ACD_OK) goto fail;
    pctx.fraction = 1.0;
    acd3_poll_set_stage(poll, "segment: hulls");
    out->nfaces = mesh->ntriangles;
    out->tau = params->tau;
    out->scale = stats.scale > 0 ? 1.0 / stats.scale : 1.0;
    out->cuts = stats.cuts;
    out->depth = stats.depth;
    out->unresolved = stats.unresolved;
    out->parts = calloc(stats.parts ? stats.parts : 1, sizeof *out->parts);
    pts = malloc(9 * mesh->ntriangles * sizeof *pts);
    if (!out->parts || !pts) goto nomem;
    out->nparts = stats.parts;
    /* conc: the loop's own valley test of each final part (acd_corise_segment_ex), the value
       acd_corise_parts_concavity would re-measure */
    /* the volume about the local frame's origin (geom3/frame: the model's origin near it, as
       before; far from it a triple product of coordinates 1e6 times the extent cancelled the volume
       away: fandisk's hull/mesh ratio came out 0.00013) */
    acd_frame fr;
    acd_geom3_frame_of(mesh->vertices, mesh->nvertices, &fr);
    for (size_t f = 0; f < mesh->ntriangles; f++) {
        acd_segment_part *p = &out->parts[out->labels[f]];
        const uint32_t *T = mesh->triangles + 3 * f;
        double a[3], b[3], d[3];
        for (int k = 0; k < 3; k++) {
            a[k] = mesh->vertices[3 * (size_t)T[0] + k] - fr.c[k];
            b[k] = mesh->vertices[3 * (size_t)T[1] + k] - fr.c[k];
            d[k] = mesh->vertices[3 * (size_t)T[2] + k] - fr.c[k];
        }
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        double x[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        p->nfaces++;
        p->area += 0.5 * sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        out->mesh_volume += (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
                             a[2] * (b[0] * d[1] - b[1] * d[0])) / 6.0;
    }
    /* the faces of each part in increasing order (counting sort), then the parts' hulls, in
       parallel: each depends on its part alone; the first failure in part order is reported */
    size_t np = out->nparts;
    start = calloc(np + 1, sizeof *start);
    byface = malloc((mesh->ntriangles ? mesh->ntriangles : 1) * sizeof *byface);
    hst = calloc(np ? np : 1, sizeof *hst);
    herr = calloc(np ? np : 1, sizeof *herr);
    if (!start || !byface || !hst || !herr) goto nomem;
    for (size_t f = 0; f < mesh->ntriangles; f++) start[out->labels[f] + 1]++;
    for (size_t k = 0; k < np; k++) start[k + 1] += start[k];
    for (size_t f = 0; f < mesh->ntriangles; f++) byface[start[out->labels[f]]++] = (uint32_t)f;
    for (size_t k = np; k > 0; k--) start[k] = start[k - 1];
    start[0] = 0;
    int nt = 1;
#ifdef _OPENMP
    nt = params->threads > 0 ? params->threads : omp_get_num_procs();
    if (nt < 1) nt = 1;
#endif
    /* pts: 9 doubles per face, each part's faces in their own range of it */
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt) if (nt > 1 && np > 1 && mesh->ntriangles >= ACD_CORISE_PARALLEL_MIN_FACES)
#endif
    for (long k = 0; k < (long)np; k++)
        hst[k] = acd3_poll_stop(poll) ? ACD_ERR_CANCELLED
                                      : part_hull(mesh, byface + start[k], start[k + 1] - start[k], pts + 9 * start[k],
                                                  &out->parts[k], &herr[k]);
    if (acd3_poll_stopped(poll)) {
        st = acd_fail(err, ACD_ERR_CANCELLED, "segment: cancelled by the progress callback computing the parts' hulls");
        goto fail;
    }
    for (size_t k = 0; k < np; k++) {
        acd_segment_part *p = &out->parts[k];
        if (hst[k] != ACD_OK) {
            st = hst[k];
            if (err) *err = herr[k];
            goto fail;
        }
        p->concavity_rel = conc[k];
        p->concavity = conc[k] * out->scale;
        out->hull_volume += p->hull_volume;
    }
    free(start);
    free(byface);
    free(hst);
    free(herr);
    free(conc);
    free(pts);
    out->seconds = now_seconds() - t0;
    return ACD_OK;
nomem:
    st = acd_fail(err, ACD_ERR_NOMEM, "segment: out of memory for a mesh of %zu faces", mesh->ntriangles);
fail:
    free(conc);
    free(pts);
    free(start);
    free(byface);
    free(hst);
    free(herr);
    acd_segment_result_free(out);
    return st;
}
