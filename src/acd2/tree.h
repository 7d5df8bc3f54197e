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

/* Appends the cut a-b; 0, or -1 when out of memory. (The ends by value: GCC 12 with ASan at -O2
 * took a node's cut[2] passed as an array parameter for an 8-byte region and failed the build with
 * -Werror=stringop-overread.) */
int acd2_cuts_push(acd2_cuts_list *l, acd_vec2 a, acd_vec2 b);

#endif
