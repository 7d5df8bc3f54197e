/* corise/edgesort: sorting facet-edge records (lo, hi, face) by (lo, hi, face), the step that
 * finds the facets sharing an edge in the CoRiSe loop (corise.c) and the cut's dual graph (cut.c).
 * A least-significant-digit radix sort (16-bit digits, digits constant over the array skipped)
 * for large arrays, qsort below ACD_CORISE_EDGESORT_RADIX_MIN records; both give the one order
 * the key defines (records with equal keys are equal), so callers see the same array. Records
 * whose faces do not decrease along the array (made in facet order) are radix-sorted by (lo, hi)
 * only: the sort is stable, so that is the same order, in two thirds of the passes. */
#ifndef ACD_CORISE_EDGESORT_H
#define ACD_CORISE_EDGESORT_H

#include <stddef.h>
#include <stdint.h>

typedef struct acd_corise_ef {
    uint32_t lo, hi, face;
} acd_corise_ef;

#define ACD_CORISE_EDGESORT_RADIX_MIN 2048

int acd_corise_ef_cmp(const void *x, const void *y);

/* Sorts e[0..n) by (lo, hi, face). Returns 0 when out of memory (e unchanged), else 1. */
int acd_corise_ef_sort(acd_corise_ef *e, size_t n);

#endif
