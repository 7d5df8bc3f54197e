/* corise/segeval: the four segmentation metrics of X. Chen, A. Golovinskiy, T. Funkhouser,
 * "A benchmark for 3D mesh segmentation", ACM TOG 28(3) 2009, §4.1-4.4 (spec corise.md §4.5):
 * Rand index (§4.4), Hamming distance with missing and false-alarm rates (§4.3), global and
 * local consistency error (§4.3, after Martin et al. 2001), cut discrepancy (§4.1).
 *
 * Region metrics work on the weighted contingency table N_ab = total weight of the faces that
 * A labels a and B labels b (weights: face areas or 1). With A_a = sum_b N_ab, B_b = sum_a N_ab,
 * W = sum N_ab (formulas in docs/segeval.md):
 *   1 - RI = [sum_a (A_a^2 - sum_b N_ab^2) + sum_b (B_b^2 - sum_a N_ab^2)] / (W^2 - sum_f w_f^2)
 *   Rm = sum_b (B_b - max_a N_ab) / W,  Rf = sum_a (A_a - max_b N_ab) / W
 *   GCE = min(sum_ab N_ab (A_a - N_ab)/A_a, sum_ab N_ab (B_b - N_ab)/B_b) / W
 *   LCE = sum_ab N_ab min((A_a - N_ab)/A_a, (B_b - N_ab)/B_b) / W
 * With unit weights these are exactly the benchmark's face-count formulas. Each bracketed term
 * is computed per segment so that identical segmentations give exact zeros. */
#include "corise/segeval.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "geom3/dijkstra.h"

acd_segeval_options acd_segeval_default_options(void) {
    acd_segeval_options o;
    memset(&o, 0, sizeof o);
    o.weighting = ACD_SEGEVAL_WEIGHT_AREA;
    return o;
}

/* ---- label compaction and contingency table ----------------------------------------------- */

typedef struct lab_idx {
    int label;
    size_t idx;
} lab_idx;

static int cmp_lab_idx(const void *x, const void *y) {
    const lab_idx *a = x, *b = y;
    if (a->label != b->label) return a->label < b->label ? -1 : 1;
    return (a->idx > b->idx) - (a->idx < b->idx);
}

/* ids[i] = rank of labels[i] among the distinct labels; returns the number of distinct labels,
 * or (size_t)-1 when out of memory. */
static size_t compact_labels(const int *labels, size_t n, size_t *ids) {
    lab_idx *t = malloc((n ? n : 1) * sizeof *t);
    if (!t) return (size_t)-1;
    for (size_t i = 0; i < n; i++) t[i] = (lab_idx){labels[i], i};
    qsort(t, n, sizeof *t, cmp_lab_idx);
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        if (i > 0 && t[i].label != t[i - 1].label) k++;
        ids[t[i].idx] = k;
    }
    free(t);
    return n ? k + 1 : 0;
}

typedef struct cell_key {
    size_t a, b, face;
} cell_key;

static int cmp_cell_key(const void *x, const void *y) {
    const cell_key *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return (p->face > q->face) - (p->face < q->face);
}

static double clamp01(double x) { return x < 0 ? 0 : x > 1 ? 1 : x; }

acd_status acd_segeval_regions(const int *a, const int *b, size_t n, const double *weights,
                               acd_segeval_result *out, acd_error *err) {
    if (!a || !b || !out) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "segeval: NULL argument");
    memset(out, 0, sizeof *out);
    if (n == 0) return acd_fail(err, ACD_ERR_DEGENERATE, "segeval: no faces to compare");
    double sumw2 = 0;
    if (weights) {
        for (size_t i = 0; i < n; i++) {
            if (!isfinite(weights[i]) || weights[i] < 0)
                return acd_fail(err, ACD_ERR_INVALID_INPUT, "segeval: weight of face %zu is %g (must be finite, >= 0)",
                                i, weights[i]);
            sumw2 += weights[i] * weights[i];
        }
    } else {
        sumw2 = (double)n;
    }
    acd_status st = ACD_OK;
    size_t *ia = malloc(n * sizeof *ia), *ib = malloc(n * sizeof *ib);
    cell_key *keys = malloc(n * sizeof *keys);
    size_t *cell_a = NULL, *cell_b = NULL;
    double *cell_w = NULL, *A = NULL, *B = NULL, *sumsq_a = NULL, *sumsq_b = NULL, *max_a = NULL, *max_b = NULL;
    if (!ia || !ib || !keys) goto nomem;
    size_t ka = compact_labels(a, n, ia), kb = compact_labels(b, n, ib);
    if (ka == (size_t)-1 || kb == (size_t)-1) goto nomem;
    for (size_t i = 0; i < n; i++) keys[i] = (cell_key){ia[i], ib[i], i};
    qsort(keys, n, sizeof *keys, cmp_cell_key);
    cell_a = malloc(n * sizeof *cell_a);
    cell_b = malloc(n * sizeof *cell_b);
    cell_w = malloc(n * sizeof *cell_w);
    A = calloc(ka, sizeof *A);
    B = calloc(kb, sizeof *B);
    sumsq_a = calloc(ka, sizeof *sumsq_a);
    sumsq_b = calloc(kb, sizeof *sumsq_b);
    max_a = calloc(ka, sizeof *max_a);
    max_b = calloc(kb, sizeof *max_b);
    if (!cell_a || !cell_b || !cell_w || !A || !B || !sumsq_a || !sumsq_b || !max_a || !max_b) goto nomem;
    size_t nc = 0;
    for (size_t i = 0; i < n; i++) {
        double w = weights ? weights[keys[i].face] : 1.0;
        if (i == 0 || keys[i].a != keys[i - 1].a || keys[i].b != keys[i - 1].b) {
            cell_a[nc] = keys[i].a;
            cell_b[nc] = keys[i].b;
            cell_w[nc] = 0;
            nc++;
        }
        cell_w[nc - 1] += w;
    }
    double W = 0;
    for (size_t c = 0; c < nc; c++) {
        double w = cell_w[c];
        A[cell_a[c]] += w;
        B[cell_b[c]] += w;
        sumsq_a[cell_a[c]] += w * w;
        sumsq_b[cell_b[c]] += w * w;
        if (w > max_a[cell_a[c]]) max_a[cell_a[c]] = w;
        if (w > max_b[cell_b[c]]) max_b[cell_b[c]] = w;
    }
    for (size_t k = 0; k < ka; k++) W += A[k];
    if (!(W > 0)) {
        st = acd_fail(err, ACD_ERR_DEGENERATE, "segeval: the faces' total weight (area) is zero");
        goto done;
    }
    /* Rand index */
    double disagree = 0;
    for (size_t k = 0; k < ka; k++) {
        double d = A[k] * A[k] - sumsq_a[k];
        if (d > 0) disagree += d;
    }
    for (size_t k = 0; k < kb; k++) {
        double d = B[k] * B[k] - sumsq_b[k];
        if (d > 0) disagree += d;
    }
    double pairs = W * W - sumw2;
    out->rand_index = pairs > 0 ? clamp01(1.0 - disagree / pairs) : 1.0;
    /* Hamming distance */
    double dab = 0, dba = 0;
    for (size_t k = 0; k < kb; k++) dab += B[k] - max_b[k];
    for (size_t k = 0; k < ka; k++) dba += A[k] - max_a[k];
    out->hamming_rm = clamp01(dab / W);
    out->hamming_rf = clamp01(dba / W);
    out->hamming = 0.5 * (out->hamming_rm + out->hamming_rf);
    /* consistency errors */
    double s_ab = 0, s_ba = 0, l = 0;
    for (size_t c = 0; c < nc; c++) {
        double w = cell_w[c], Aa = A[cell_a[c]], Bb = B[cell_b[c]];
        double eab = Aa > 0 ? (Aa - w) / Aa : 0.0, eba = Bb > 0 ? (Bb - w) / Bb : 0.0;
        s_ab += w * eab;
        s_ba += w * eba;
        l += w * (eab < eba ? eab : eba);
    }
    out->gce = clamp01((s_ab < s_ba ? s_ab : s_ba) / W);
    out->lce = clamp01(l / W);
    out->nfaces = n;
    out->nsegments_a = ka;
    out->nsegments_b = kb;
    out->total_weight = W;
    out->cd_defined = 0;
    out->cut_discrepancy = out->cut_discrepancy_pooled = NAN;
    out->dcd_ab = out->dcd_ba = NAN;
    goto done;
nomem:
    st = acd_fail(err, ACD_ERR_NOMEM, "segeval: out of memory for %zu faces", n);
done:
    free(ia);
    free(ib);
    free(keys);
    free(cell_a);
    free(cell_b);
    free(cell_w);
    free(A);
    free(B);
    free(sumsq_a);
    free(sumsq_b);
    free(max_a);
    free(max_b);
    return st;
}

/* ---- cut discrepancy ---------------------------------------------------------------------- */

typedef struct edge_face {
    uint32_t lo, hi;
    size_t face;
} edge_face;

static int cmp_edge_face(const void *x, const void *y) {
    const edge_face *p = x, *q = y;
    if (p->lo != q->lo) return p->lo < q->lo ? -1 : 1;
    if (p->hi != q->hi) return p->hi < q->hi ? -1 : 1;
    return (p->face > q->face) - (p->face < q->face);
}

static acd_status check_triangles(const acd_mesh *m, acd_error *err) {
    for (size_t t = 0; t < m->ntriangles; t++)
        for (int k = 0; k < 3; k++)
            if (m->triangles[3 * t + k] >= m->nvertices)
                return acd_fail(err, ACD_ERR_INVALID_INPUT, "segeval: triangle %zu uses vertex %u, but the mesh has %zu",
                                t, m->triangles[3 * t + k], m->nvertices);
    return ACD_OK;
}

acd_status acd_segeval_cut_vertices(const acd_mesh *m, const int *labels, uint8_t *is_cut, size_t *ncut,
                                    acd_error *err) {
    if (!m || !labels || !is_cut) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "segeval: NULL argument");
    acd_status st = check_triangles(m, err);
    if (st != ACD_OK) return st;
    memset(is_cut, 0, m->nvertices);
    size_t ne = 3 * m->ntriangles;
    edge_face *e = malloc((ne ? ne : 1) * sizeof *e);
    if (!e) return acd_fail(err, ACD_ERR_NOMEM, "segeval: out of memory for %zu edges", ne);
    for (size_t t = 0; t < m->ntriangles; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t u = m->triangles[3 * t + k], v = m->triangles[3 * t + (k + 1) % 3];
            e[3 * t + k] = (edge_face){u < v ? u : v, u < v ? v : u, t};
        }
    qsort(e, ne, sizeof *e, cmp_edge_face);
    for (size_t i = 0; i < ne;) {
        size_t j = i + 1;
        int differs = 0;
        while (j < ne && e[j].lo == e[i].lo && e[j].hi == e[i].hi) {
            if (labels[e[j].face] != labels[e[i].face]) differs = 1;
            j++;
        }
        if (differs && e[i].lo != e[i].hi) {
            is_cut[e[i].lo] = 1;
            is_cut[e[i].hi] = 1;
        }
        i = j;
    }
    free(e);
    if (ncut) {
        size_t c = 0;
        for (size_t v = 0; v < m->nvertices; v++) c += is_cut[v];
        *ncut = c;
    }
    return ACD_OK;
}

static double tri_area(const acd_mesh *m, size_t t, double centroid[3]) {
    const double *p = m->vertices + 3 * m->triangles[3 * t], *q = m->vertices + 3 * m->triangles[3 * t + 1],
                 *r = m->vertices + 3 * m->triangles[3 * t + 2];
    double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    if (centroid)
        for (int k = 0; k < 3; k++) centroid[k] = (p[k] + q[k] + r[k]) / 3.0;
    return 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

double acd_segeval_avg_radius(const acd_mesh *m) {
    if (!m) return 0;
    double total = 0, cen[3] = {0, 0, 0}, fc[3];
    for (size_t t = 0; t < m->ntriangles; t++) {
        double a = tri_area(m, t, fc);
        total += a;
        for (int k = 0; k < 3; k++) cen[k] += a * fc[k];
    }
    if (!(total > 0)) return 0;
    for (int k = 0; k < 3; k++) cen[k] /= total;
    double s = 0;
    for (size_t t = 0; t < m->ntriangles; t++) {
        double a = tri_area(m, t, fc);
        double d[3] = {fc[0] - cen[0], fc[1] - cen[1], fc[2] - cen[2]};
        s += a * sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
    return s / total;
}

/* Sum and count of distances from the cut vertices `from` to the nearest vertex of `to`. */
static acd_status directed_cut_distance(const acd_edge_graph *g, const uint8_t *from, const uint8_t *to,
                                        size_t nto, double *sum, size_t *count, size_t *unreachable,
                                        acd_error *err) {
    *sum = 0;
    *count = 0;
    uint32_t *src = malloc((nto ? nto : 1) * sizeof *src);
    if (!src) return acd_fail(err, ACD_ERR_NOMEM, "segeval: out of memory for %zu cut vertices", nto);
    size_t k = 0;
    for (size_t v = 0; v < g->nvertices; v++)
        if (to[v]) src[k++] = (uint32_t)v;
    acd_sp_tree tree;
    memset(&tree, 0, sizeof tree);
    acd_status st = acd_dijkstra(g, src, k, NULL, &tree, err);
    free(src);
    if (st != ACD_OK) {
        acd_sp_tree_free(&tree);
        return st;
    }
    for (size_t v = 0; v < g->nvertices; v++) {
        if (!from[v]) continue;
        if (isinf(tree.dist[v])) {
            (*unreachable)++;
            continue;
        }
        *sum += tree.dist[v];
        (*count)++;
    }
    acd_sp_tree_free(&tree);
    return ACD_OK;
}

acd_status acd_segeval(const acd_mesh *m, const int *a, const int *b, const acd_segeval_options *opts,
                       acd_segeval_result *out, acd_error *err) {
    if (!m || !a || !b || !out) return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "segeval: NULL argument");
    memset(out, 0, sizeof *out);
    acd_segeval_options o = opts ? *opts : acd_segeval_default_options();
    if (o.weighting != ACD_SEGEVAL_WEIGHT_AREA && o.weighting != ACD_SEGEVAL_WEIGHT_FACES)
        return acd_fail(err, ACD_ERR_INVALID_ARGUMENT, "segeval: unknown weighting %d", (int)o.weighting);
    if (m->ntriangles == 0) return acd_fail(err, ACD_ERR_DEGENERATE, "segeval: the mesh has no faces");
    acd_status st = check_triangles(m, err);
    if (st != ACD_OK) return st;
    for (size_t i = 0; i < 3 * m->nvertices; i++)
        if (!isfinite(m->vertices[i]))
            return acd_fail(err, ACD_ERR_INVALID_INPUT, "segeval: vertex %zu has a non-finite coordinate", i / 3);
    size_t n = m->ntriangles;
    double *w = NULL;
    if (o.weighting == ACD_SEGEVAL_WEIGHT_AREA) {
        w = malloc(n * sizeof *w);
        if (!w) return acd_fail(err, ACD_ERR_NOMEM, "segeval: out of memory for %zu face areas", n);
        for (size_t t = 0; t < n; t++) w[t] = tri_area(m, t, NULL);
    }
    st = acd_segeval_regions(a, b, n, w, out, err);
    free(w);
    if (st != ACD_OK) return st;

    uint8_t *cut_a = malloc(m->nvertices ? m->nvertices : 1), *cut_b = malloc(m->nvertices ? m->nvertices : 1);
    acd_edge_graph g;
    memset(&g, 0, sizeof g);
    if (!cut_a || !cut_b) {
        st = acd_fail(err, ACD_ERR_NOMEM, "segeval: out of memory for %zu vertices", m->nvertices);
        goto done;
    }
    if ((st = acd_segeval_cut_vertices(m, a, cut_a, &out->ncut_a, err)) != ACD_OK) goto done;
    if ((st = acd_segeval_cut_vertices(m, b, cut_b, &out->ncut_b, err)) != ACD_OK) goto done;
    out->avg_radius = acd_segeval_avg_radius(m);
    if (out->ncut_a == 0 || out->ncut_b == 0 || !(out->avg_radius > 0)) goto done;
    st = acd_edge_graph_from_mesh(m->vertices, m->nvertices, m->triangles, m->ntriangles, &g, err);
    if (st != ACD_OK) goto done;
    double sab, sba;
    size_t cab, cba;
    if ((st = directed_cut_distance(&g, cut_a, cut_b, out->ncut_b, &sab, &cab, &out->cd_unreachable, err)) != ACD_OK)
        goto done;
    if ((st = directed_cut_distance(&g, cut_b, cut_a, out->ncut_a, &sba, &cba, &out->cd_unreachable, err)) != ACD_OK)
        goto done;
    if (cab == 0 || cba == 0) goto done;
    out->dcd_ab = sab / (double)cab;
    out->dcd_ba = sba / (double)cba;
    out->cut_discrepancy = (out->dcd_ab + out->dcd_ba) / out->avg_radius;
    out->cut_discrepancy_pooled = (sab + sba) / (double)(cab + cba) / out->avg_radius;
    out->cd_defined = 1;
done:
    free(cut_a);
    free(cut_b);
    acd_edge_graph_free(&g);
    return st;
}
