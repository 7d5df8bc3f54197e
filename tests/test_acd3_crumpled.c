/* Crumpled parts (acd3/decompose: the halving planes, docs/acd3d.md "Crumpled parts"): a part that
 * no candidate plane splits, above tau and not within tau of its hull, is cut through the centroid
 * of its volume across its principal axes instead of being left above tau (exit 3 under `acd 3d
 * --verify` before). The inputs are valid meshes after a one-rounding perturbation (a non-exact
 * scale), where earlier cuts left such a piece.
 *  1. tests/data/meshes/crumpled_part.off: the piece itself (volume 1.85e-7 inside a hull of 0.178,
 *     24 degenerate faces, 47 self-intersecting face pairs), cut from double-torus-example.off
 *     scaled by 0.851262377128435; every witness plane left it whole. Decomposed at the run's tau.
 *  2. data/meshes/double-torus-example.off and rotor.off scaled (not by a power of two) by
 *     0.851262377128435 and 1e9, default settings: every part meets tau (or the merge tolerance),
 *     none is left with reason no_cut. Skipped with a message when data/meshes lacks them. */
// ctest: TIMEOUT 600
#include "testutil.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd/mesh.h"
#include "acd3/decompose.h"
#include "geom3/volume.h"
#include "acd3d_check.h"

/* Every part meets its tolerance as `acd 3d --verify` checks it (a tree leaf within tau, a joined
 * part within the merge tolerance), none stays above tau (no_cut, depth), and the parts' volumes add
 * up to the input's. */
static void check_parts(const acd_mesh *in, const acd3d_result *r) {
    double sum = 0, vin = acd_geom3_signed_volume(in);
    for (size_t i = 0; i < r->nparts; i++) {
        const acd3d_part *p = &r->parts[i];
        const acd3d_leaf_reason why = r->nodes[p->node].leaf_reason;
        if (why == ACD3D_LEAF_NO_CUT || why == ACD3D_LEAF_DEPTH)
            print_message("part %zu: concavity %.17g, tau %.17g, leaf reason %d, volume %g\n", i, p->concavity, r->tau,
                          (int)why, p->volume);
        assert_true(why != ACD3D_LEAF_NO_CUT && why != ACD3D_LEAF_DEPTH);
        if (why == ACD3D_LEAF_JOINED)
            assert_true(p->concavity <= r->merge_tau + r->tol);
        else
            assert_true(p->concavity <= r->tau + r->tol);
        assert_true(p->volume > 0);
        sum += acd_geom3_signed_volume(&p->mesh);
    }
    assert_true(fabs(sum - vin) <= 1e-9 * fabs(vin) + 1e-12);
}

/* An OFF file with every polygon fanned from its first vertex (0, k, k + 1), as
 * bench/audit_3d_transforms.py reads it (acd_mesh_read fans non-convex polygons otherwise): the
 * transformed copies the audit writes are these triangles. 0 on a malformed file. */
static int read_off_fan(const char *path, acd_mesh *m) {
    memset(m, 0, sizeof *m);
    FILE *f = fopen(path, "r");
    if (!f) return 0;
    char head[8];
    size_t nv, nf, ne, cap = 0, nt = 0;
    int ok = fscanf(f, "%7s %zu %zu %zu", head, &nv, &nf, &ne) == 4 && !strcmp(head, "OFF");
    m->vertices = ok ? malloc((3 * nv + 1) * sizeof *m->vertices) : NULL;
    ok = ok && m->vertices;
    for (size_t i = 0; ok && i < 3 * nv; i++) ok = fscanf(f, "%lf", &m->vertices[i]) == 1;
    m->nvertices = ok ? nv : 0;
    for (size_t i = 0; ok && i < nf; i++) {
        unsigned n, idx[64];
        ok = fscanf(f, "%u", &n) == 1 && n >= 3 && n <= 64;
        for (unsigned k = 0; ok && k < n; k++) ok = fscanf(f, "%u", &idx[k]) == 1 && idx[k] < nv;
        for (unsigned k = 1; ok && k + 1 < n; k++) {
            if (nt == cap) {
                cap = cap ? 2 * cap : 256;
                uint32_t *t = realloc(m->triangles, 3 * cap * sizeof *t);
                if (!t) {
                    ok = 0;
                    break;
                }
                m->triangles = t;
            }
            m->triangles[3 * nt] = idx[0], m->triangles[3 * nt + 1] = idx[k], m->triangles[3 * nt + 2] = idx[k + 1];
            nt++;
        }
    }
    fclose(f);
    m->ntriangles = nt;
    if (!ok) acd_mesh_free(m);
    return ok;
}

static int read_data(const char *rel, acd_mesh *m) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", ACD_SOURCE_DIR, rel);
    acd_error err;
    return acd_mesh_read(path, m, &err) == ACD_OK;
}

/* The crumpled piece alone, at the tau of the run that made it (0.05 of the scaled model's radius),
 * without the merge pass: before, one part of concavity 0.40 (no_cut: each witness plane left it
 * whole or shaved off a speck); now the halving planes split it and every part meets tau. The same
 * parts for 1 and 2 threads. */
static void test_crumpled_piece(void **state) {
    (void)state;
    acd_mesh m;
    assert_true(read_data("tests/data/meshes/crumpled_part.off", &m));
    acd3d_params p = acd3d_default_params();
    p.tau = 0.22588394913180726;
    p.tau_absolute = 1;
    p.merge = 0;
    p.threads = 1;
    acd3d_result r, r2;
    acd3_decompose_stats st = {0};
    acd_error err;
    assert_int_equal(acd3_decompose_screen(&m, &p, ACD3_VOLUME_SCREEN_REL, &st, &r, &err), ACD_OK);
    print_message("crumpled piece: %zu parts, max concavity %g (tau %g), %zu halved\n", r.nparts, r.max_concavity,
                  r.tau, st.halved);
    assert_true(r.nparts >= 2);
    assert_true(st.halved >= 1);
    check_parts(&m, &r);
    p.threads = 2;
    assert_int_equal(acd3d_decompose(&m, &p, &r2, &err), ACD_OK);
    ck3_same_parts(&r, &r2);
    acd3d_result_free(&r2);
    acd3d_result_free(&r);
    acd_mesh_free(&m);
}

/* The data meshes scaled by a factor that is not a power of two (rounding every coordinate once):
 * before, part 13 of the double torus stayed at 0.40 for tau 0.226 and part 62 of the rotor at 2.5
 * tau (no_cut, crumpled pieces). Default settings (tau 0.05, merge pass on), with and without the
 * merge pass. */
static void test_scaled_data(void **state) {
    (void)state;
    const char *names[2] = {"double-torus-example.off", "rotor.off"};
    const double scale[2] = {0.851262377128435, 1e9};
    int ran = 0;
    for (int k = 0; k < 2; k++) {
        char path[4096];
        acd_mesh m;
        acd_error err;
        if (!tu_mesh_data(path, sizeof path, names[k])) {
            print_message("data/meshes/%s missing (scripts/fetch-data.sh): not run on it\n", names[k]);
            continue;
        }
        assert_true(read_off_fan(path, &m));
        for (size_t v = 0; v < 3 * m.nvertices; v++) m.vertices[v] *= scale[k];
        for (int merge = 1; merge >= 0; merge--) {
            acd3d_params p = acd3d_default_params();
            p.merge = merge;
            acd3d_result r;
            acd3_decompose_stats st = {0};
            assert_int_equal(acd3_decompose_screen(&m, &p, ACD3_VOLUME_SCREEN_REL, &st, &r, &err), ACD_OK);
            print_message("%s x %.17g%s: %zu parts, max concavity %g (tau %g), %zu halved\n", names[k], scale[k],
                          merge ? "" : " (no merge)", r.nparts, r.max_concavity, r.tau, st.halved);
            /* the fallback was needed (else the input no longer tests it). Not on the rotor since the
             * edge planes hold its rounded planes (acd3/resolve, docs/results/3d-edgepair.md): at
             * 1e9 and at 3e9, 7e8, 1e-3, 123.456, 0.85126 no part needs the halving planes; it stays
             * here for check_parts (every part within tau) */
            if (k == 0) assert_true(st.halved >= 1);
            check_parts(&m, &r);
            acd3d_result_free(&r);
        }
        acd_mesh_free(&m);
        ran++;
    }
    if (!ran) TU_SKIP("no data/meshes/double-torus-example.off or rotor.off (scripts/fetch-data.sh)");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crumpled_piece),
        cmocka_unit_test(test_scaled_data),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
