/* acd2/exact_pieces: the internal result of the exact decompositions (pieces as lists of input
 * point indices, plus the diagonals), shared by exact_hm and exact_mcd. */
#ifndef ACD_ACD2_EXACT_PIECES_H
#define ACD_ACD2_EXACT_PIECES_H

#include <stddef.h>

#include "acd/base.h"

typedef struct acd_index_pieces {
    size_t *idx;        /* concatenated point indices, each piece counterclockwise */
    size_t *start;      /* npieces + 1 offsets into idx */
    size_t npieces;
    size_t (*diag)[2];  /* diagonals as point index pairs */
    size_t ndiag;
} acd_index_pieces;

void acd_index_pieces_free(acd_index_pieces *p);

#endif
