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
        double top = 0;
        top += n[0] * nd->box[c0][0];
        top += n[1] * nd->box[c1][1];
        top += n[2] * nd->box[c2][2];
        if (!(top > deepest)) {
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
