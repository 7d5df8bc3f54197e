/* corise/cage: cages from a decomposition's hulls (acd/cage.h; CoRiSe paper §7.2, spec corise.md
 * §5): each hull is simplified to a corner budget by a subset of its own support planes
 * (geom3/hull_outer, enclosing by construction), its planes are pushed outward by the offset, and
 * the polytopes are unioned exactly into one closed mesh (geom3/polyunion). Enclosure of the mesh is checked with exact ray winding
 * numbers (geom3/spatial). */
#define _POSIX_C_SOURCE 200809L
#include "acd/cage.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "acd/hull.h"
#include "core/error.h"
#include "geom3/frame.h"
#include "geom3/hull_outer.h"
#include "geom3/polyunion.h"
#include "geom3/spatial.h"

/* Support directions of a flat part: the 26 unit vectors of {-1, 0, 1}^3 \ 0. */
#define CAGE_NDIRS 26

acd_cage_params acd_cage_default_params(void) {
    acd_cage_params p;
    memset(&p, 0, sizeof p);
    p.cookie = ACD_CAGE_PARAMS_COOKIE;
    p.offset = 0.01;
    p.max_vertices = 32;
    p.check_enclosure = 1;
    return p;
}

void acd_cage_result_free(acd_cage_result *r) {
    if (!r) return;
    acd_mesh_free(&r->cage);
    memset(r, 0, sizeof *r);
}

static double now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The 26 unit directions of {-1, 0, 1}^3 \ 0, as planes (d unused): the support planes that make
 * a flat part's polytope solid once pushed by the offset. */
static void direction_planes(double *pl) {
    size_t n = 0;
    for (int x = -1; x <= 1; x++)
        for (int y = -1; y <= 1; y++)
            for (int z = -1; z <= 1; z++) {
                if (!x && !y && !z) continue;
                double l = sqrt((double)(x * x + y * y + z * z));
                pl[4 * n] = x / l;
                pl[4 * n + 1] = y / l;
                pl[4 * n + 2] = z / l;
                pl[4 * n + 3] = 0;
                n++;
            }
}

/* One part's polytope: hull of its points; solid: the hull's planes, or with a budget a subset
 * of them (geom3/hull_outer); flat (offset > 0 only): the 26 directions and the plane's normals.
 * *planes is malloc'd when *owned. poly->npoints = 0: nothing (empty, or flat with offset 0). */
static acd_status part_polytope(const double *pts, size_t n, double off, size_t max_vertices, acd_hull *h0,
                                acd_polyunion_polytope *poly, double **owned, size_t *corners, acd_error *err) {
    memset(poly, 0, sizeof *poly);
    *corners = 0;
    *owned = NULL;
    memset(h0, 0, sizeof *h0);
    if (!n) return ACD_OK;
    acd_status st = acd_hull_compute(pts, n, h0, err);
    if (st != ACD_OK) return st;
    if (h0->dim == 3) {
        if (max_vertices && h0->nvertices > max_vertices) {
            size_t np, nc;
            st = acd_hull_outer(h0, max_vertices, off, owned, &np, &nc, err);
            if (st != ACD_OK) return st;
            poly->planes = *owned;
            poly->nplanes = np;
            *corners = nc;
        } else {
            poly->planes = h0->planes;
            poly->nplanes = h0->ntriangles;
            *corners = h0->nvertices;
        }
    } else if (h0->dim >= 0 && off > 0) {
        double *pl = malloc(4 * (CAGE_NDIRS + 2) * sizeof *pl);
        if (!pl) return acd_fail(err, ACD_ERR_NOMEM, "cage: out of memory");
        direction_planes(pl);
        size_t np = CAGE_NDIRS;
        if (h0->dim == 2 && h0->ntriangles) {
            for (int j = 0; j < 4; j++) {
                pl[4 * np + j] = h0->planes[j];
                pl[4 * (np + 1) + j] = -h0->planes[j];
            }
            np += 2;
        }
        *owned = pl;
        poly->planes = pl;
        poly->nplanes = np;
    } else {
        return ACD_OK;
    }
    poly->points = h0->vertices;
    poly->npoints = h0->nvertices;
    return ACD_OK;
}

acd_status acd_cage_build(const acd_mesh *mesh, const acd_mesh *hulls, size_t nhulls, const acd_cage_params *params,
                          acd_cage_result *out, acd_error *err) {
    if (!out) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "cage: out is NULL");
    memset(out, 0, sizeof *out);
    if (!mesh || !params || (nhulls && !hulls))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "cage: mesh, params or hulls is NULL");
    if (params->cookie != ACD_CAGE_PARAMS_COOKIE)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "cage: params not initialized (use acd_cage_default_params)");
    if (!(params->offset >= 0) || !isfinite(params->offset))
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "cage: offset %g must be finite and >= 0", params->offset);
    if (params->max_vertices && params->max_vertices < 4)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "cage: max_vertices %zu must be 0 or >= 4", params->max_vertices);
    double t0 = now_seconds();

    /* scale: bounding box of the vertices the mesh's faces use (all vertices if it has none) */
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t t = 0; t < 3 * mesh->ntriangles; t++)
        if (mesh->triangles[t] >= mesh->nvertices)
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "cage: face %zu uses vertex %u of %zu", t / 3, mesh->triangles[t],
                            mesh->nvertices);
    for (size_t v = 0; v < mesh->nvertices; v++)
        for (int k = 0; k < 3; k++) {
            double x = mesh->vertices[3 * v + k];
            if (!isfinite(x)) return acd_fail(err, ACD_ERR_INVALID_INPUT, "cage: mesh vertex %zu is not finite", v);
            if (x < lo[k]) lo[k] = x;
            if (x > hi[k]) hi[k] = x;
        }
    double diag = 0;
    if (mesh->nvertices)
        diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
    out->diagonal = diag;
    out->offset = params->offset * diag;

    acd_hull *h0 = calloc(nhulls ? nhulls : 1, sizeof *h0);
    acd_polyunion_polytope *pp = calloc(nhulls ? nhulls : 1, sizeof *pp);
    double **owned = calloc(nhulls ? nhulls : 1, sizeof *owned);
    acd_status st = ACD_OK;
    if (!h0 || !pp || !owned) st = acd_fail(err, ACD_ERR_NOMEM, "cage: out of memory");
    for (size_t h = 0; h < nhulls && st == ACD_OK; h++) {
        for (size_t v = 0; v < 3 * hulls[h].nvertices; v++)
            if (!isfinite(hulls[h].vertices[v])) {
                st = acd_fail(err, ACD_ERR_INVALID_INPUT, "cage: hull %zu vertex %zu is not finite", h, v / 3);
                break;
            }
        if (st != ACD_OK) break;
        size_t nc = 0;
        st = part_polytope(hulls[h].vertices, hulls[h].nvertices, out->offset, params->max_vertices, &h0[h], &pp[h],
                           &owned[h], &nc, err);
        if (st == ACD_OK) {
            out->chosen_corners += nc;
            if (pp[h].npoints) out->hulls++;
            else out->skipped++;
        }
    }
    acd_polyunion_stats ps;
    if (st == ACD_OK) st = acd_polyunion(pp, nhulls, out->offset, &out->cage, &ps, err);
    for (size_t h = 0; h < nhulls && h0 && owned; h++) {
        acd_hull_free(&h0[h]);
        free(owned[h]);
    }
    free(h0);
    free(pp);
    free(owned);
    if (st != ACD_OK) {
        acd_cage_result_free(out);
        return st;
    }
    out->corners = ps.corners;
    const acd_mesh *cg = &out->cage;
    double vol = 0;
    /* about the local frame's origin (geom3/frame: the model's origin near it, as before) */
    acd_frame fr;
    acd_geom3_frame_of(cg->vertices, cg->nvertices, &fr);
    for (size_t t = 0; t < cg->ntriangles; t++) {
        double a[3], b[3], c[3];
        for (int k = 0; k < 3; k++) {
            a[k] = cg->vertices[3 * (size_t)cg->triangles[3 * t] + k] - fr.c[k];
            b[k] = cg->vertices[3 * (size_t)cg->triangles[3 * t + 1] + k] - fr.c[k];
            c[k] = cg->vertices[3 * (size_t)cg->triangles[3 * t + 2] + k] - fr.c[k];
        }
        vol += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    out->volume = vol / 6;

    if (params->check_enclosure) {
        acd_spatial sp;
        st = acd_spatial_build(&sp, cg->vertices, cg->nvertices, cg->triangles, cg->ntriangles, err);
        if (st != ACD_OK) {
            acd_cage_result_free(out);
            return st;
        }
        unsigned char *used = calloc(mesh->nvertices ? mesh->nvertices : 1, 1);
        if (!used) {
            acd_spatial_free(&sp);
            acd_cage_result_free(out);
            return acd_fail(err, ACD_ERR_NOMEM, "cage: out of memory");
        }
        for (size_t t = 0; t < 3 * mesh->ntriangles; t++) used[mesh->triangles[t]] = 1;
        for (size_t v = 0; v < mesh->nvertices; v++) {
            if (!used[v]) continue;
            out->checked_vertices++;
            int c = acd_spatial_classify(&sp, mesh->vertices + 3 * v);
            if (c == ACD_SPATIAL_OUTSIDE) out->outside_vertices++;
            else if (c == ACD_SPATIAL_ON_SURFACE) out->surface_vertices++;
        }
        free(used);
        acd_spatial_free(&sp);
    }
    out->seconds = now_seconds() - t0;
    return ACD_OK;
}

acd_status acd_cage_from_segment(const acd_mesh *mesh, const acd_segment_result *seg, const acd_cage_params *params,
                                 acd_cage_result *out, acd_error *err) {
    if (!out) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "cage: out is NULL");
    memset(out, 0, sizeof *out);
    if (!mesh || !seg) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "cage: mesh or segmentation is NULL");
    if (seg->nfaces != mesh->ntriangles)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "cage: %zu labels for %zu faces", seg->nfaces, mesh->ntriangles);
    size_t np = seg->nparts, nt = mesh->ntriangles;
    size_t *count = calloc(np + 1, sizeof *count);
    uint32_t *stamp = malloc((mesh->nvertices ? mesh->nvertices : 1) * sizeof *stamp);
    acd_mesh *sets = calloc(np ? np : 1, sizeof *sets);
    double *pool = NULL;
    acd_status st = ACD_OK;
    if (!count || !stamp || !sets) {
        st = acd_fail(err, ACD_ERR_NOMEM, "cage: out of memory");
        goto done;
    }
    for (size_t f = 0; f < nt; f++)
        if (seg->labels[f] >= np) {
            st = acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "cage: face %zu has label %u of %zu parts", f, seg->labels[f], np);
            goto done;
        }
    /* distinct vertices per part (stamped), counted then filled */
    for (size_t v = 0; v < mesh->nvertices; v++) stamp[v] = UINT32_MAX;
    for (size_t f = 0; f < nt; f++)
        for (int c = 0; c < 3; c++) {
            uint32_t v = mesh->triangles[3 * f + c];
            if (v >= mesh->nvertices) {
                st = acd_fail(err, ACD_ERR_INVALID_INPUT, "cage: face %zu uses vertex %u of %zu", f, v, mesh->nvertices);
                goto done;
            }
            (void)v;
        }
    size_t total = 0;
    for (size_t k = 0; k < np; k++) {
        for (size_t f = 0; f < nt; f++) {
            if (seg->labels[f] != k) continue;
            for (int c = 0; c < 3; c++) {
                uint32_t v = mesh->triangles[3 * f + c];
                if (stamp[v] != (uint32_t)k) {
                    stamp[v] = (uint32_t)k;
                    count[k]++;
                }
            }
        }
        total += count[k];
    }
    pool = malloc(3 * (total ? total : 1) * sizeof *pool);
    if (!pool) {
        st = acd_fail(err, ACD_ERR_NOMEM, "cage: out of memory");
        goto done;
    }
    for (size_t v = 0; v < mesh->nvertices; v++) stamp[v] = UINT32_MAX;
    size_t at = 0;
    for (size_t k = 0; k < np; k++) {
        sets[k].vertices = pool + 3 * at;
        for (size_t f = 0; f < nt; f++) {
            if (seg->labels[f] != k) continue;
            for (int c = 0; c < 3; c++) {
                uint32_t v = mesh->triangles[3 * f + c];
                if (stamp[v] != (uint32_t)k) {
                    stamp[v] = (uint32_t)k;
                    memcpy(pool + 3 * (at + sets[k].nvertices++), mesh->vertices + 3 * (size_t)v, 3 * sizeof *pool);
                }
            }
        }
        at += sets[k].nvertices;
    }
    st = acd_cage_build(mesh, sets, np, params, out, err);
done:
    free(pool);
    free(sets);
    free(stamp);
    free(count);
    return st;
}
