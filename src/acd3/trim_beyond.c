/* acd3/trim_beyond: the volumes beyond a candidate plane's levels (see trim_beyond.h). */
#include "acd3/trim_beyond.h"

#include <stdlib.h>
#include <string.h>

#include "geom3/vec3.h"

void acd3_trim_tree_free(acd3_trim_tree *R) {
    free(R->node);
    free(R->corner);
    memset(R, 0, sizeof *R);
}

int acd3_trim_tree_build(acd3_trim_tree *R, const acd_bvh *b) {
    memset(R, 0, sizeof *R);
    const size_t nn = b->nnodes;
    if (nn == 0) return 1;
    uint32_t *size = malloc(nn * sizeof *size), *stack = malloc(nn * sizeof *stack);
    R->node = malloc(nn * sizeof *R->node);
    R->corner = malloc(9 * b->ntriangles * sizeof *R->corner);
    if (!size || !stack || !R->node || !R->corner) {
        free(size), free(stack);
        acd3_trim_tree_free(R);
        return 0;
    }
    for (size_t i = nn; i-- > 0;) { /* subtree sizes (a node's children come after it) */
        const acd_bvh_node *nd = &b->nodes[i];
        size[i] = nd->count ? 1 : 1 + size[nd->first] + size[nd->first + 1];
    }
    /* the query's traversal: a stack, the first child pushed first (the second popped first) */
    size_t sp = 0, ct = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const uint32_t id = stack[--sp];
        const acd_bvh_node *nd = &b->nodes[id];
        acd3_trim_tree_node *o = &R->node[R->nnode];
        memcpy(o->box[0], nd->lo, sizeof o->box[0]);
        memcpy(o->box[1], nd->hi, sizeof o->box[1]);
        o->skip = (uint32_t)(R->nnode + size[id]);
        o->first = (uint32_t)ct;
        o->count = nd->count;
        R->nnode++;
        for (uint32_t i = 0; i < nd->count; i++, ct++) {
            const uint32_t *tr = b->triangles + 3 * (size_t)b->order[nd->first + i];
            for (int c = 0; c < 3; c++)
                memcpy(R->corner + 9 * ct + 3 * c, b->vertices + 3 * (size_t)tr[c], 3 * sizeof(double));
        }
        if (!nd->count) {
            stack[sp++] = nd->first;
            stack[sp++] = nd->first + 1;
        }
    }
    free(size), free(stack);
    return 1;
}

/* A tree node's box's largest n.x, summed as acd_box_max_dot sums it (from 0; c0..c2: the box corner
 * of each coordinate, chosen by n's signs once by the caller). */
static inline double node_top(const acd3_trim_tree_node *nd, const double n[3], int c0, int c1, int c2) {
    double top = 0;
    top += n[0] * nd->box[c0][0];
    top += n[1] * nd->box[c1][1];
    top += n[2] * nd->box[c2][2];
    return top;
}

/* (The query also tests each triangle's box; every triangle reaching beyond passes it: the box's
 * n.x is rounded from products no smaller than each corner's, term by term, so it is no smaller
 * than the corner's n.x. The triangles it drops add nothing here.) */
void acd3_trim_tree_beyond(const acd3_trim_tree *R, const double n[3], const acd3_trim_levels *L, size_t k_lo,
                           double *v, double *top) {
    double hi = -INFINITY;
    const double deepest = L->off[ACD3_TRIM_NDEPTHS - 1];
    double acc[ACD3_TRIM_NDEPTHS]; /* (v's sums, kept apart from the tree for the compiler) */
    memcpy(acc, v, sizeof acc);
    /* a node's box's largest n.x as acd_box_max_dot sums it (from 0, the corner of each coordinate
     * chosen by n's sign once here) */
    const int c0 = n[0] >= 0, c1 = n[1] >= 0, c2 = n[2] >= 0;
    size_t i = 0;
    while (i < R->nnode) {
        const acd3_trim_tree_node *nd = &R->node[i];
        if (!(node_top(nd, n, c0, c1, c2) > deepest)) {
            i = nd->skip;
            continue;
        }
        for (uint32_t q = 0; q < nd->count; q++) {
            const double *c = R->corner + 9 * ((size_t)nd->first + q);
            const double *const p[3] = {c, c + 3, c + 6};
            const double d[3] = {acd_dot3(n, p[0]), acd_dot3(n, p[1]), acd_dot3(n, p[2])};
            const double dt = acd3_trim_top(d);
            if (dt > deepest) {
                acd3_trim_tri_beyond(p, d, L, k_lo, acc);
                hi = dt > hi ? dt : hi;
            }
        }
        i++;
    }
    memcpy(v, acc, sizeof acc);
    if (top) *top = hi;
}

/* ---- the exact charge (acd3_trim_tree_charge) ----
 *
 * A convex polytope as its faces' directed edges (each face counterclockwise seen from outside, its
 * edges in any order): clipping it by a plane needs no ordering (each face cut keeps its edges' parts
 * on the kept side and gains the edge from where its boundary leaves the side to where it comes back;
 * the section is those edges reversed), and its volume is, for any point r, the sum over the faces f
 * and their edges (a, b) of det(c_f - r, a - r, b - r) / 6, c_f a point of f's plane (each face the
 * fan from c_f over its boundary, coned to r). */

typedef struct trim_cpoly {
    double (*e)[2][3]; /* edges (start, end) */
    uint16_t *f;       /* per edge its face */
    int ne, nf;
} trim_cpoly;

#define CPOLY_EDGES 1024
#define CPOLY_FACES 200

static void cpoly_edge(trim_cpoly *P, const double *a, const double *b, int f) {
    memcpy(P->e[P->ne][0], a, 3 * sizeof(double));
    memcpy(P->e[P->ne][1], b, 3 * sizeof(double));
    P->f[P->ne++] = (uint16_t)f;
}

/* the point where s crosses 0 on the segment a b (s_a, s_b of opposite signs or one 0), computed
 * from the lexicographically lower end so that a face and its neighbour get the same point */
static void cpoly_cross(const double *a, double sa, const double *b, double sb, double o[3]) {
    if (memcmp(a, b, 3 * sizeof(double)) > 0) {
        const double *t = a;
        a = b, b = t;
        const double u = sa;
        sa = sb, sb = u;
    }
    const double x = sa / (sa - sb);
    for (int q = 0; q < 3; q++) o[q] = a[q] + x * (b[q] - a[q]);
}

/* P clipped to pl[0..2].x + pl[3] > 0 into Q (Q's arrays given); 0 when more than the capacities */
static int cpoly_clip(const trim_cpoly *P, const double pl[4], trim_cpoly *Q) {
    Q->ne = 0, Q->nf = 0;
    double sec[CPOLY_FACES][2][3]; /* the section's edges */
    int nsec = 0;
    for (int i = 0; i < P->ne;) {
        const int f = P->f[i];
        int j = i;
        while (j < P->ne && P->f[j] == f) j++;
        double ex[3], en[3];
        int has_ex = 0, has_en = 0, kept = 0;
        const int f0 = Q->ne;
        for (int k = i; k < j; k++) {
            const double *a = P->e[k][0], *b = P->e[k][1];
            const double sa = acd_dot3(pl, a) + pl[3], sb = acd_dot3(pl, b) + pl[3];
            if (Q->ne + 2 > CPOLY_EDGES) return 0;
            if (sa > 0 && sb > 0) {
                cpoly_edge(Q, a, b, Q->nf);
            } else if (sa > 0) {
                cpoly_cross(a, sa, b, sb, ex);
                has_ex = 1;
                cpoly_edge(Q, a, ex, Q->nf);
            } else if (sb > 0) {
                cpoly_cross(a, sa, b, sb, en);
                has_en = 1;
                cpoly_edge(Q, en, b, Q->nf);
            }
        }
        kept = Q->ne > f0;
        if (has_ex && has_en) {
            cpoly_edge(Q, ex, en, Q->nf);
            if (nsec == CPOLY_FACES) return 0;
            memcpy(sec[nsec][0], en, sizeof en);
            memcpy(sec[nsec][1], ex, sizeof ex);
            nsec++;
        }
        if (kept) {
            if (Q->nf + 2 > CPOLY_FACES) return 0;
            Q->nf++;
        }
        i = j;
    }
    if (nsec >= 3) {
        if (Q->ne + nsec > CPOLY_EDGES) return 0;
        for (int k = 0; k < nsec; k++) cpoly_edge(Q, sec[k][0], sec[k][1], Q->nf);
        Q->nf++;
    }
    return 1;
}

static double cpoly_volume(const trim_cpoly *P, const double r[3]) {
    double v = 0;
    for (int i = 0; i < P->ne;) {
        const int f = P->f[i];
        const double c[3] = {P->e[i][0][0] - r[0], P->e[i][0][1] - r[1], P->e[i][0][2] - r[2]};
        for (; i < P->ne && P->f[i] == f; i++) {
            const double a[3] = {P->e[i][0][0] - r[0], P->e[i][0][1] - r[1], P->e[i][0][2] - r[2]};
            const double b[3] = {P->e[i][1][0] - r[0], P->e[i][1][1] - r[1], P->e[i][1][2] - r[2]};
            v += c[0] * (a[1] * b[2] - a[2] * b[1]) + c[1] * (a[2] * b[0] - a[0] * b[2]) +
                 c[2] * (a[0] * b[1] - a[1] * b[0]);
        }
    }
    return v / 6.0;
}

double acd3_trim_tree_charge(const acd3_trim_tree *R, const double n[3], double off, const double apex[3],
                             const double *cuts, size_t ncuts) {
    double (*ebuf)[2][3] = malloc(2 * (size_t)CPOLY_EDGES * sizeof *ebuf);
    uint16_t *fbuf = malloc(2 * (size_t)CPOLY_EDGES * sizeof *fbuf);
    if (!ebuf || !fbuf) {
        free(ebuf), free(fbuf);
        return NAN;
    }
    trim_cpoly A = {ebuf, fbuf, 0, 0}, B = {ebuf + CPOLY_EDGES, fbuf + CPOLY_EDGES, 0, 0};
    double sum = 0;
    const int c0 = n[0] >= 0, c1 = n[1] >= 0, c2 = n[2] >= 0;
    size_t i = 0;
    while (i < R->nnode) {
        const acd3_trim_tree_node *nd = &R->node[i];
        if (!(node_top(nd, n, c0, c1, c2) > off)) {
            i = nd->skip;
            continue;
        }
        for (uint32_t q = 0; q < nd->count; q++) {
            const double *c = R->corner + 9 * ((size_t)nd->first + q);
            if (!(acd_dot3(n, c) > off || acd_dot3(n, c + 3) > off || acd_dot3(n, c + 6) > off)) continue;
            const double a[3] = {c[0] - apex[0], c[1] - apex[1], c[2] - apex[2]};
            const double b[3] = {c[3] - apex[0], c[4] - apex[1], c[5] - apex[2]};
            const double e[3] = {c[6] - apex[0], c[7] - apex[1], c[8] - apex[2]};
            const double det = a[0] * (b[1] * e[2] - b[2] * e[1]) + a[1] * (b[2] * e[0] - b[0] * e[2]) +
                               a[2] * (b[0] * e[1] - b[1] * e[0]);
            if (det == 0) continue; /* a flat tetrahedron: no volume */
            /* the tetrahedron's part beyond the plane is the cone from the apex (on the plane) over
             * the triangle's part beyond it: when the apex and that polygon's corners are inside
             * every cut, so is the cone (convex), and its volume is the clipped cone's */
            const double *const p[3] = {c, c + 3, c + 6};
            const double s[3] = {acd_dot3(n, c) - off, acd_dot3(n, c + 3) - off, acd_dot3(n, c + 6) - off};
            double poly[4][3];
            int np = 0;
            for (int k = 0; k < 3; k++) {
                const int k1 = k == 2 ? 0 : k + 1;
                if (s[k] > 0) memcpy(poly[np++], p[k], sizeof poly[0]);
                if ((s[k] > 0) != (s[k1] > 0)) cpoly_cross(p[k], s[k], p[k1], s[k1], poly[np++]);
            }
            int inside = 1;
            for (size_t k = 0; k < ncuts && inside; k++) {
                const double *pl = cuts + 4 * k;
                inside = acd_dot3(pl, apex) < pl[3];
                for (int m = 0; m < np && inside; m++) inside = acd_dot3(pl, poly[m]) < pl[3];
            }
            if (inside) {
                double ed[3][3];
                for (int k = 0; k < 3; k++)
                    for (int q = 0; q < 3; q++) ed[k][q] = p[k == 2 ? 0 : k + 1][q] - p[k][q];
                sum += acd3_trim_clip_cone(p, (const double(*)[3])ed, s, apex);
                continue;
            }
            /* the cone as a polytope: the polygon (counterclockwise seen from outside: reversed when
             * the apex lies on the triangle's outer side) and a triangle to the apex on each edge */
            int ord[4];
            for (int k = 0; k < np; k++) ord[k] = det > 0 ? k : np - 1 - k;
            A.ne = 0, A.nf = np + 1;
            for (int k = 0; k < np; k++) cpoly_edge(&A, poly[ord[k]], poly[ord[(k + 1) % np]], 0);
            for (int k = 0; k < np; k++) {
                const double *q0 = poly[ord[k]], *q1 = poly[ord[(k + 1) % np]];
                cpoly_edge(&A, apex, q1, k + 1);
                cpoly_edge(&A, q1, q0, k + 1);
                cpoly_edge(&A, q0, apex, k + 1);
            }
            trim_cpoly *cur = &A, *nxt = &B;
            for (size_t k = 0; k < ncuts && cur->ne > 0; k++) {
                const double *pl = cuts + 4 * k;
                const double neg[4] = {-pl[0], -pl[1], -pl[2], pl[3]}; /* kept: n_c.x < off_c */
                int out = 0;
                for (int m = 0; m < cur->ne && !out; m++) out = !(acd_dot3(neg, cur->e[m][0]) + neg[3] > 0);
                if (!out) continue; /* inside the cut: kept whole */
                if (!cpoly_clip(cur, neg, nxt)) goto overflow;
                trim_cpoly *sw = cur;
                cur = nxt, nxt = sw;
            }
            const double v = cur->ne > 0 ? cpoly_volume(cur, apex) : 0;
            sum += det > 0 ? v : -v;
        }
        i++;
    }
    free(ebuf), free(fbuf);
    return sum;
overflow:
    free(ebuf), free(fbuf);
    return NAN;
}
