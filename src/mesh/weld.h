/* mesh/weld: merging vertices with equal coordinates (exactly, or within a tolerance). Internal
 * part; the public entry point is acd_mesh_weld in acd/mesh.h. */
#ifndef ACD_MESH_WELD_H
#define ACD_MESH_WELD_H

#include <stddef.h>
#include <stdint.h>

/* Exact weld of n points (3 doubles each; -0 equals +0): remap[i] is the new index of point i,
 * unique points numbered in order of first occurrence (so remap[i] <= i); *nunique their
 * count. 0 when out of memory. */
int acd_weld_exact(const double *v, size_t n, uint32_t *remap, size_t *nunique);

/* Tolerance weld: points closer than tol (per coordinate box of side tol around each point,
 * chained transitively) get the index of the first of them. Same output convention. */
int acd_weld_tolerance(const double *v, size_t n, double tol, uint32_t *remap, size_t *nunique);

/* Compacts v in place following remap from the functions above (first occurrence kept). */
void acd_weld_compact(double *v, size_t n, const uint32_t *remap);

#endif
