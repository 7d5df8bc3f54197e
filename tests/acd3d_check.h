/* Shared checks for the acd3d tests (included by tests/test_acd3_*.c; header-only, static inline). */
#ifndef ACD_TESTS_ACD3D_CHECK_H
#define ACD_TESTS_ACD3D_CHECK_H

#include "testutil.h"

#include "acd/acd3d.h"

/* Two results of the same input and parameters (e.g. 1 and 2 threads): the same parts, their
 * vertex coordinates bit for bit. */
static inline void ck3_same_parts(const acd3d_result *a, const acd3d_result *b) {
    assert_int_equal(a->nparts, b->nparts);
    for (size_t i = 0; i < a->nparts; i++) {
        assert_int_equal(a->parts[i].mesh.nvertices, b->parts[i].mesh.nvertices);
        assert_memory_equal(a->parts[i].mesh.vertices, b->parts[i].mesh.vertices,
                            3 * a->parts[i].mesh.nvertices * sizeof(double));
    }
}

/* Two results that must have the same hulls: the same parts, each hull's vertex coordinates bit for
 * bit and its volume. */
static inline void ck3_same_hulls(const acd3d_result *a, const acd3d_result *b) {
    assert_int_equal(a->nparts, b->nparts);
    for (size_t i = 0; i < a->nparts; i++) {
        assert_true(a->parts[i].hull_volume == b->parts[i].hull_volume);
        assert_int_equal(a->parts[i].hull.nvertices, b->parts[i].hull.nvertices);
        assert_memory_equal(a->parts[i].hull.vertices, b->parts[i].hull.vertices,
                            3 * a->parts[i].hull.nvertices * sizeof(double));
    }
}

#endif
