/* acd2/tree: the decomposition tree (dissertation Ch. III, Fig. 9b) read at a coarser tau, and
 * the growable list of cut segments. */
#ifndef ACD_ACD2_TREE_H
#define ACD_ACD2_TREE_H

#include <stddef.h>

#include "acd/acd2d.h"

typedef struct acd2_cuts_list {
    acd_vec2 (*v)[2];
    size_t n, cap;
} acd2_cuts_list;

/* 0, or -1 when out of memory. */
int acd2_cuts_push(acd2_cuts_list *l, const acd_vec2 seg[2]);

#endif
