/* bench_3d_leaves: what the leaves of a 3D decomposition are (docs/results/3d-fg.md, "Table 5:
 * the armadillo"). Runs acd3d_decompose without the merge pass and prints, per leaf, its volume
 * (fraction of the input's), its measured concavity (acd3/measure: depth below the bridge patch),
 * its "true" concavity (the largest distance from a vertex of the part to the boundary of its
 * convex hull: the paper's definition, measured at the vertices), its centroid, depth, the number
 * of pieces its parent's cut made, and the share of its area lying in cut planes (caps); then, per
 * split node, whether the split was needed under the true concavity (true > tau), and a summary.
 *
 * usage: bench_3d_leaves MESH TAU [solid|surface] [ARGS...]   ARGS: --no-fg (the A14 variant),
 *        --region-cuts, --resolver witness, --leaves (print every leaf)
 * Every vertex of a descendant leaf lies on its ancestor's boundary (section loops run on the
 * ancestor's surface, caps are triangulated without inner points), so a node's true concavity is
 * computed from its descendant leaves' vertices and the hull of them. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd/hull.h"
#include "acd/mesh.h"

typedef struct acc {
    double *pts;
    size_t n, cap;
} acc;

static void acc_add(acc *a, const double *p, size_t n) {
    if (a->n + n > a->cap) {
        a->cap = 2 * (a->n + n);
        a->pts = realloc(a->pts, 3 * a->cap * sizeof(double));
        if (!a->pts) exit(5);
    }
    memcpy(a->pts + 3 * a->n, p, 3 * n * sizeof(double));
    a->n += n;
}

static void collect(const acd3d_result *r, int node, acc *a) {
    const acd3d_node *nd = &r->nodes[node];
    if (nd->first_child < 0) {
        if (nd->part >= 0) acc_add(a, r->parts[nd->part].mesh.vertices, r->parts[nd->part].mesh.nvertices);
        return;
    }
    for (int c = 0; c < nd->nchildren; c++) collect(r, nd->first_child + c, a);
}

/* The largest distance from the points to the boundary of their hull. */
static double true_concavity(const acc *a) {
    acd_hull h;
    acd_error err;
    if (acd_hull_compute(a->pts, a->n, &h, &err) != ACD_OK || h.dim < 3) {
        acd_hull_free(&h);
        return 0;
    }
    double worst = 0;
    for (size_t i = 0; i < a->n; i++) {
        double d = -acd_hull_plane_distance(&h, a->pts + 3 * i);
        if (d > worst) worst = d;
    }
    acd_hull_free(&h);
    return worst;
}

static double tri_area(const acd_mesh *m, size_t t, double c[3]) {
    const double *a = m->vertices + 3 * (size_t)m->triangles[3 * t], *b = m->vertices + 3 * (size_t)m->triangles[3 * t + 1],
                 *d = m->vertices + 3 * (size_t)m->triangles[3 * t + 2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    for (int k = 0; k < 3; k++) c[k] = (a[k] + b[k] + d[k]) / 3;
    return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/* Share of the leaf's area in its ancestors' cut planes. */
static double cap_share(const acd3d_result *r, int node, double scale) {
    const acd_mesh *m = &r->parts[r->nodes[node].part].mesh;
    double all = 0, cap = 0;
    for (size_t t = 0; t < m->ntriangles; t++) {
        double c[3], ar = tri_area(m, t, c);
        all += ar;
        for (int a = r->nodes[node].parent; a >= 0; a = r->nodes[a].parent) {
            const double *pl = r->nodes[a].cut_plane;
            int on = 1;
            for (int k = 0; k < 3 && on; k++) {
                const double *p = m->vertices + 3 * (size_t)m->triangles[3 * t + k];
                on = fabs(pl[0] * p[0] + pl[1] * p[1] + pl[2] * p[2] + pl[3]) <= 1e-9 * scale;
            }
            if (on) {
                cap += ar;
                break;
            }
        }
    }
    return all > 0 ? cap / all : 0;
}

int main(int argc, char **argv) {
    if (argc < 3) {
        fprintf(stderr, "usage: bench_3d_leaves MESH TAU [solid|surface] [--no-fg] [--region-cuts] [--resolver witness] [--leaves]\n");
        return 2;
    }
    acd_mesh m;
    acd_error err;
    if (acd_mesh_read(argv[1], &m, &err) != ACD_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    acd3d_params p = acd3d_default_params();
    p.tau = atof(argv[2]);
    p.merge = 0;
    int print_leaves = 0;
    for (int i = 3; i < argc; i++) {
        if (!strcmp(argv[i], "surface")) p.mode = ACD3D_SURFACE;
        else if (!strcmp(argv[i], "solid")) p.mode = ACD3D_SOLID;
        else if (!strcmp(argv[i], "--no-fg")) p.eps_ratio = 0, p.resolver = ACD3D_RESOLVER_NOTCH, p.region_cuts = 1;
        else if (!strcmp(argv[i], "--region-cuts")) p.region_cuts = 1;
        else if (!strcmp(argv[i], "--resolver") && i + 1 < argc && !strcmp(argv[i + 1], "witness")) p.resolver = ACD3D_RESOLVER_WITNESS, i++;
        else if (!strcmp(argv[i], "--leaves")) print_leaves = 1;
        else {
            fprintf(stderr, "bench_3d_leaves: unknown argument %s\n", argv[i]);
            return 2;
        }
    }
    acd3d_result r;
    if (acd3d_decompose(&m, &p, &r, &err) != ACD_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    int solid = p.mode == ACD3D_SOLID;
    double tau = r.tau, vin = r.input_volume, scale = r.scale;
    size_t nn = r.nnodes;
    double *tc = calloc(nn, sizeof *tc);
    size_t *nvert = calloc(nn, sizeof *nvert);
    if (!tc || !nvert) return 5;
    for (size_t n = 0; n < nn; n++) {
        acc a = {0};
        collect(&r, (int)n, &a);
        nvert[n] = a.n;
        tc[n] = a.n >= 4 ? true_concavity(&a) : 0;
        free(a.pts);
    }
    printf("# %s tau %g (%g model units, radius %g), %s, %zu parts (no merge pass)\n", argv[1], p.tau, tau, scale,
           solid ? "solid" : "surface", r.nparts);
    if (print_leaves)
        printf("leaf node depth vol_frac measured/tau true/tau centroid_x centroid_y centroid_z extent/radius "
               "parent_pieces cap_share\n");
    size_t tiny = 0, small = 0, over = 0, extra = 0, splits = 0, needless = 0, needless_leaves = 0, chips = 0;
    double sum_ratio = 0;
    size_t nratio = 0;
    for (size_t i = 0; i < r.nparts; i++) {
        int n = r.parts[i].node;
        const acd3d_node *nd = &r.nodes[n];
        const acd_mesh *pm = &r.parts[i].mesh;
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, c[3] = {0, 0, 0};
        for (size_t v = 0; v < pm->nvertices; v++)
            for (int k = 0; k < 3; k++) {
                double x = pm->vertices[3 * v + k];
                lo[k] = fmin(lo[k], x), hi[k] = fmax(hi[k], x), c[k] += x / (double)pm->nvertices;
            }
        double ext = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
        double vf = solid ? nd->volume / vin : 0;
        int depth = 0;
        for (int a = nd->parent; a >= 0; a = r.nodes[a].parent) depth++;
        int pp = nd->parent >= 0 ? r.nodes[nd->parent].nchildren : 0;
        double cs = solid ? cap_share(&r, n, scale) : 0;
        if (solid && vf < 1e-4) tiny++;
        if (solid && vf < 1e-3) small++;
        if (solid && cs > 0.5) chips++;
        if (pp > 2) extra++;
        if (nd->concavity > tau * (1 + 1e-9)) over++;
        if (nd->concavity > 0.05 * tau) {
            sum_ratio += tc[n] / nd->concavity;
            nratio++;
        }
        if (print_leaves)
            printf("%zu %d %d %.3g %.3f %.3f %.2f %.2f %.2f %.3f %d %.2f\n", i, n, depth, vf, nd->concavity / tau, tc[n] / tau,
                   c[0], c[1], c[2], ext / scale, pp, cs);
    }
    for (size_t n = 0; n < nn; n++) {
        const acd3d_node *nd = &r.nodes[n];
        if (nd->first_child < 0) continue;
        splits++;
        if (tc[n] <= tau) {
            needless++;
            /* leaves below a needless split whose own ancestors all needed theirs */
            int top = 1;
            for (int a = nd->parent; a >= 0; a = r.nodes[a].parent)
                if (tc[a] <= tau) top = 0;
            if (top) { /* count the leaves under n */
                size_t cnt = 0;
                int stack[4096], sp = 0;
                stack[sp++] = (int)n;
                while (sp) {
                    int x = stack[--sp];
                    if (r.nodes[x].first_child < 0) {
                        cnt++;
                        continue;
                    }
                    for (int k = 0; k < r.nodes[x].nchildren && sp < 4096; k++) stack[sp++] = r.nodes[x].first_child + k;
                }
                needless_leaves += cnt - 1; /* one part would have done */
            }
        }
    }
    printf("leaves %zu; solid: below 1e-4 of the volume %zu, below 1e-3 %zu, more than half of the area in caps %zu; "
           "leaves whose parent's cut made more than 2 pieces %zu; above tau %zu\n",
           r.nparts, tiny, small, chips, extra, over);
    printf("splits %zu, of which %zu split a part whose true concavity (vertex distance to its hull's boundary) was "
           "already <= tau; without those splits (the topmost such nodes kept whole) %zu leaves fewer\n",
           splits, needless, needless_leaves);
    printf("mean true/measured concavity over the leaves with measured > 0.05 tau: %.3f (%zu leaves)\n",
           nratio ? sum_ratio / nratio : 0, nratio);
    free(tc);
    free(nvert);
    acd3d_result_free(&r);
    acd_mesh_free(&m);
    return 0;
}
