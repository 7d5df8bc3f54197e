/* Shared checks for the acd3d tests (included by tests/test_acd3_*.c; header-only, static). */
#ifndef ACD_TESTS_ACD3D_CHECK_H
#define ACD_TESTS_ACD3D_CHECK_H

#include "testutil.h"

#include "acd/acd3d.h"

/* Two results of the same input and parameters (e.g. 1 and 2 threads): the same parts, their
 * vertex coordinates bit for bit. */
static void ck3_same_parts(const acd3d_result *a, const acd3d_result *b) {
    assert_int_equal(a->nparts, b->nparts);
    for (size_t i = 0; i < a->nparts; i++) {
        assert_int_equal(a->parts[i].mesh.nvertices, b->parts[i].mesh.nvertices);
        assert_memory_equal(a->parts[i].mesh.vertices, b->parts[i].mesh.vertices,
                            3 * a->parts[i].mesh.nvertices * sizeof(double));
    }
}

#endif
