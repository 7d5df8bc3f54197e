/* acd3/region_cut: glue back every section region but the selected one; see region_cut.h. */
#include "acd3/region_cut.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/union_find.h"
#include "geom3/bvh.h"

typedef struct region {
    size_t piece;
    double key[3];      /* lexicographically smallest vertex: the same point on both sides */
    size_t nverts;      /* with key, identifies the region across the two sides */
    double dist;        /* squared distance from x to the region's triangles */
    int side;
} region;

/* Orders by the leading uint64_t key (edge keys). */
static int cmp_u64(const void *a, const void *b) {
    const uint64_t ka = *(const uint64_t *)a, kb = *(const uint64_t *)b;
    return (ka > kb) - (ka < kb);
}

/* Orders by the leading three doubles (point coordinates), then by the index that follows. */
static int cmp_vec3(const void *a, const void *b) {
    const double *p = a, *q = b;
    for (int k = 0; k < 3; k++)
        if (p[k] != q[k]) return p[k] < q[k] ? -1 : 1;
    const size_t *i = (const size_t *)(p + 3), *j = (const size_t *)(q + 3);
    return (*i > *j) - (*i < *j);
}

static int lex_less(const double *a, const double *b) {
    for (int k = 0; k < 3; k++)
        if (a[k] != b[k]) return a[k] < b[k];
    return 0;
}

/* Cap regions of one piece: connected components of its cap triangles across shared edges.
 * Appends to *regs; region_of[t] gets the region index (global) of cap triangle t. */
static acd_status piece_regions(const acd_cut_piece *pc, size_t piece, const double x[3], region **regs, size_t *nreg,
                                size_t *capreg, uint32_t *region_of) {
    const acd_mesh *m = &pc->mesh;
    size_t nt = m->ntriangles;
    /* union-find over cap triangles through shared vertex pairs: sort the cap half-edges by
     * undirected key */
    size_t ncap = 0;
    for (size_t t = 0; t < nt; t++) ncap += pc->is_cap[t] != 0;
    if (!ncap) return ACD_OK;
    uint64_t *key = malloc(3 * ncap * sizeof *key);
    size_t *tri = malloc(3 * ncap * sizeof *tri), *par = malloc(nt * sizeof *par);
    if (!key || !tri || !par) {
        free(key), free(tri), free(par);
        return ACD_ERR_NOMEM;
    }
    for (size_t t = 0; t < nt; t++) par[t] = t;
    size_t n = 0;
    for (size_t t = 0; t < nt; t++) {
        if (!pc->is_cap[t]) continue;
        for (int k = 0; k < 3; k++) {
            uint64_t a = m->triangles[3 * t + k], b = m->triangles[3 * t + (k + 1) % 3];
            key[n] = a < b ? (a << 32 | b) : (b << 32 | a);
            tri[n] = t;
            n++;
        }
    }
    /* sort indices by key (insertion into an index array with qsort on pairs) */
    typedef struct kt {
        uint64_t k;
        size_t t;
    } kt;
    kt *arr = malloc(n * sizeof *arr);
    if (!arr) {
        free(key), free(tri), free(par);
        return ACD_ERR_NOMEM;
    }
    for (size_t i = 0; i < n; i++) arr[i] = (kt){key[i], tri[i]};
    qsort(arr, n, sizeof *arr, cmp_u64);
    for (size_t i = 1; i < n; i++)
        if (arr[i].k == arr[i - 1].k) acd_uf_union_z(par, arr[i].t, arr[i - 1].t);
    free(arr), free(key), free(tri);
    /* one region per root */
    for (size_t t = 0; t < nt; t++) {
        if (!pc->is_cap[t] || acd_uf_find_z(par, t) != t) continue;
        if (*nreg == *capreg) {
            size_t nc = *capreg ? 2 * *capreg : 16;
            region *nr = realloc(*regs, nc * sizeof *nr);
            if (!nr) {
                free(par);
                return ACD_ERR_NOMEM;
            }
            *regs = nr;
            *capreg = nc;
        }
        region *r = &(*regs)[*nreg];
        r->piece = piece;
        r->side = pc->side;
        r->nverts = 0;
        r->dist = INFINITY;
        r->key[0] = r->key[1] = r->key[2] = INFINITY;
        region_of[t] = (uint32_t)*nreg;
        (*nreg)++;
    }
    for (size_t t = 0; t < nt; t++) {
        if (!pc->is_cap[t]) continue;
        size_t root = acd_uf_find_z(par, t);
        uint32_t ri = region_of[root];
        region_of[t] = ri;
        region *r = &(*regs)[ri];
        const double *p[3];
        for (int k = 0; k < 3; k++) {
            p[k] = m->vertices + 3 * (size_t)m->triangles[3 * t + k];
            if (lex_less(p[k], r->key)) memcpy(r->key, p[k], sizeof r->key);
        }
        r->nverts += 3; /* corner count: equal on both sides since the caps mirror each other */
        double q[3];
        double d = acd_closest_point_triangle(x, p[0], p[1], p[2], q); /* squared: only compared */
        if (d < r->dist) r->dist = d;
    }
    free(par);
    return ACD_OK;
}

/* Merges the pieces of one group: their triangles minus the dropped caps, vertices welded on
 * exact coordinates. */
static acd_status merge_group(const acd_cut_result *cut, const size_t *members, size_t nm, uint32_t *const *region_of,
                              const uint8_t *drop, acd_cut_piece *out) {
    size_t nv = 0, nt = 0;
    for (size_t i = 0; i < nm; i++) {
        nv += cut->pieces[members[i]].mesh.nvertices;
        nt += cut->pieces[members[i]].mesh.ntriangles;
    }
    typedef struct vref {
        double p[3];
        size_t idx;
    } vref;
    vref *vs = malloc((nv ? nv : 1) * sizeof *vs);
    uint32_t *remap = malloc((nv ? nv : 1) * sizeof *remap);
    double *V = malloc(3 * (nv ? nv : 1) * sizeof *V);
    uint32_t *T = malloc(3 * (nt ? nt : 1) * sizeof *T);
    uint32_t *src = malloc((nv ? nv : 1) * sizeof *src);
    if (!vs || !remap || !V || !T || !src) {
        free(vs), free(remap), free(V), free(T), free(src);
        return ACD_ERR_NOMEM;
    }
    size_t k = 0;
    for (size_t i = 0; i < nm; i++) {
        const acd_mesh *m = &cut->pieces[members[i]].mesh;
        for (size_t v = 0; v < m->nvertices; v++, k++) {
            memcpy(vs[k].p, m->vertices + 3 * v, sizeof vs[k].p);
            vs[k].idx = k;
        }
    }
    qsort(vs, nv, sizeof *vs, cmp_vec3);
    size_t nout = 0;
    for (size_t i = 0; i < nv; i++) {
        if (i == 0 || memcmp(vs[i].p, vs[i - 1].p, sizeof vs[i].p) != 0) {
            memcpy(V + 3 * nout, vs[i].p, sizeof vs[i].p);
            nout++;
        }
        remap[vs[i].idx] = (uint32_t)(nout - 1);
    }
    /* sources: first piece's source for each welded vertex */
    for (size_t i = 0; i < nout; i++) src[i] = ACD_CUT_NEW_VERTEX;
    size_t base = 0, ntri = 0;
    for (size_t i = 0; i < nm; i++) {
        const acd_cut_piece *pc = &cut->pieces[members[i]];
        const acd_mesh *m = &pc->mesh;
        for (size_t v = 0; v < m->nvertices; v++)
            if (pc->source && pc->source[v] != ACD_CUT_NEW_VERTEX) src[remap[base + v]] = pc->source[v];
        for (size_t t = 0; t < m->ntriangles; t++) {
            if (pc->is_cap[t] && drop[region_of[members[i]][t]]) continue;
            for (int c = 0; c < 3; c++) T[3 * ntri + c] = remap[base + m->triangles[3 * t + c]];
            ntri++;
        }
        base += m->nvertices;
    }
    free(vs), free(remap);
    /* drop vertices no triangle uses (the interior of dropped caps has none: caps use loop
     * vertices only, but be safe) */
    uint32_t *use = calloc(nout ? nout : 1, sizeof *use);
    if (!use) {
        free(V), free(T), free(src);
        return ACD_ERR_NOMEM;
    }
    for (size_t i = 0; i < 3 * ntri; i++) use[T[i]] = 1;
    size_t nk = 0;
    for (size_t i = 0; i < nout; i++) {
        if (!use[i]) continue;
        memmove(V + 3 * nk, V + 3 * i, sizeof(double[3]));
        src[nk] = src[i];
        use[i] = (uint32_t)nk + 1;
        nk++;
    }
    for (size_t i = 0; i < 3 * ntri; i++) T[i] = use[T[i]] - 1;
    free(use);
    memset(out, 0, sizeof *out);
    out->mesh.vertices = V;
    out->mesh.nvertices = nk;
    out->mesh.triangles = T;
    out->mesh.ntriangles = ntri;
    out->side = cut->pieces[members[0]].side;
    out->source = src;
    out->is_cap = malloc(ntri ? ntri : 1);
    if (!out->is_cap) {
        acd_mesh_free(&out->mesh);
        free(src);
        return ACD_ERR_NOMEM;
    }
    /* remaining caps keep their flag */
    size_t tt = 0;
    for (size_t i = 0; i < nm; i++) {
        const acd_cut_piece *pc = &cut->pieces[members[i]];
        for (size_t t = 0; t < pc->mesh.ntriangles; t++) {
            if (pc->is_cap[t] && drop[region_of[members[i]][t]]) continue;
            out->is_cap[tt++] = pc->is_cap[t];
        }
    }
    return ACD_OK;
}

acd_status acd3_restrict_cut(acd_cut_result *cut, const double x[3], acd_error *err) {
    size_t np = cut->npieces;
    if (np < 2) return ACD_OK;
    region *regs = NULL;
    size_t nreg = 0, capreg = 0;
    uint32_t **region_of = calloc(np, sizeof *region_of);
    size_t *par = malloc(np * sizeof *par);
    uint8_t *drop = NULL;
    acd_status st = ACD_OK;
    if (!region_of || !par) {
        st = ACD_ERR_NOMEM;
        goto done;
    }
    for (size_t i = 0; i < np && st == ACD_OK; i++) {
        region_of[i] = malloc((cut->pieces[i].mesh.ntriangles + 1) * sizeof **region_of);
        if (!region_of[i]) st = ACD_ERR_NOMEM;
        else st = piece_regions(&cut->pieces[i], i, x, &regs, &nreg, &capreg, region_of[i]);
    }
    if (st != ACD_OK) goto done;
    if (nreg == 0) goto done;
    /* the selected region: nearest to x (its twin on the other side has the same key) */
    size_t sel = 0;
    for (size_t r = 1; r < nreg; r++)
        if (regs[r].dist < regs[sel].dist) sel = r;
    drop = calloc(nreg, 1);
    if (!drop) {
        st = ACD_ERR_NOMEM;
        goto done;
    }
    for (size_t i = 0; i < np; i++) par[i] = i;
    size_t glued = 0;
    for (size_t r = 0; r < nreg; r++) {
        int selected = regs[r].nverts == regs[sel].nverts && !memcmp(regs[r].key, regs[sel].key, sizeof regs[r].key);
        if (selected || regs[r].side < 0) continue;
        /* find the twin on the - side */
        for (size_t q = 0; q < nreg; q++) {
            if (regs[q].side > 0 || regs[q].nverts != regs[r].nverts || memcmp(regs[q].key, regs[r].key, sizeof regs[r].key))
                continue;
            drop[r] = drop[q] = 1;
            acd_uf_union_z(par, regs[r].piece, regs[q].piece);
            glued++;
            break;
        }
    }
    if (!glued) goto done;
    /* rebuild the piece list: groups in order of their lowest piece */
    acd_cut_piece *np_list = calloc(np, sizeof *np_list);
    size_t *members = malloc(np * sizeof *members);
    if (!np_list || !members) {
        free(np_list), free(members);
        st = ACD_ERR_NOMEM;
        goto done;
    }
    size_t nout = 0;
    for (size_t i = 0; i < np && st == ACD_OK; i++) {
        if (acd_uf_find_z(par, i) != i) continue;
        size_t nm = 0;
        for (size_t j = i; j < np; j++)
            if (acd_uf_find_z(par, j) == i) members[nm++] = j;
        if (nm == 1) {
            np_list[nout] = cut->pieces[i];
            memset(&cut->pieces[i], 0, sizeof cut->pieces[i]);
            nout++;
        } else {
            st = merge_group(cut, members, nm, region_of, drop, &np_list[nout]);
            if (st == ACD_OK) nout++;
        }
    }
    free(members);
    if (st != ACD_OK) {
        for (size_t i = 0; i < nout; i++) {
            acd_mesh_free(&np_list[i].mesh);
            free(np_list[i].is_cap);
            free(np_list[i].source);
        }
        free(np_list);
        goto done;
    }
    for (size_t i = 0; i < np; i++) {
        acd_mesh_free(&cut->pieces[i].mesh);
        free(cut->pieces[i].is_cap);
        free(cut->pieces[i].source);
    }
    free(cut->pieces);
    cut->pieces = np_list;
    cut->npieces = nout;
done:
    if (region_of)
        for (size_t i = 0; i < np; i++) free(region_of[i]);
    free(region_of), free(par), free(regs), free(drop);
    if (st != ACD_OK) {
        acd_cut_result_free(cut);
        return acd_fail(err, st, "out of memory restricting a cut to its section region");
    }
    return ACD_OK;
}
