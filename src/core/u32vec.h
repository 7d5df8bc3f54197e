/* core/u32vec: a growable array of uint32_t (doubling, starting at 256). Zero-initialise, push,
 * free(v.a). acd_u32vec_push returns 0 on allocation failure (the vector is then unchanged). */
#ifndef ACD_CORE_U32VEC_H
#define ACD_CORE_U32VEC_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

typedef struct acd_u32vec {
    uint32_t *a;
    size_t n, cap;
} acd_u32vec;

static inline int acd_u32vec_push(acd_u32vec *v, uint32_t x) {
    if (v->n == v->cap) {
        size_t nc = v->cap ? 2 * v->cap : 256;
        uint32_t *na = realloc(v->a, nc * sizeof *na);
        if (!na) return 0;
        v->a = na;
        v->cap = nc;
    }
    v->a[v->n++] = x;
    return 1;
}

#endif
