/* Tests of the decomposition's hull volume screen (the cut choice by volume, solid mode; docs/acd3d.md
 * "Cut choice by volume", screen_decide in src/acd3/split.c): a candidate whose pieces' hull
 * volume estimates are above the final best's hull volume by ACD3_VOLUME_SCREEN_REL is dropped before
 * its pieces' qhull hulls, as their sum would drop it. Through acd3_decompose_screen (acd3/decompose.h)
 * the screen is turned off: the same tree, parts and hulls, bit for bit, at 1 and 4 threads, on meshes
 * where the screen drops candidates (counted: the test is not vacuous), and at one thread every
 * candidate the screen drops is one whose qhull hulls the run without it computes. The control: a
 * screen 3% wrong (it drops candidates whose estimates are merely above 0.97 x the best's) changes
 * some result, so the comparison can fail. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "acd/acd3d.h"
#include "acd/mesh.h"
#include "acd3/decompose.h"
#include "shapes.h"

/* Whether a and b are the same tree and parts, bit for bit (the nodes' links, leaf reasons,
 * concavities and cut planes; the parts' vertices, triangles, concavities and hulls). */
static int same_result(const acd3d_result *a, const acd3d_result *b) {
    if (a->nnodes != b->nnodes || a->nparts != b->nparts) return 0;
    for (size_t i = 0; i < a->nnodes; i++) {
        const acd3d_node *x = &a->nodes[i], *y = &b->nodes[i];
        if (x->parent != y->parent || x->first_child != y->first_child || x->nchildren != y->nchildren ||
            x->leaf_reason != y->leaf_reason || x->merged_into != y->merged_into ||
            memcmp(&x->concavity, &y->concavity, sizeof x->concavity) ||
            memcmp(x->cut_plane, y->cut_plane, sizeof x->cut_plane))
            return 0;
    }
    for (size_t j = 0; j < a->nparts; j++) {
        const acd3d_part *p = &a->parts[j], *q = &b->parts[j];
        const acd_mesh *ms[2][2] = {{&p->mesh, &q->mesh}, {&p->hull, &q->hull}};
        if (memcmp(&p->concavity, &q->concavity, sizeof p->concavity) ||
            memcmp(&p->hull_volume, &q->hull_volume, sizeof p->hull_volume) || p->node != q->node)
            return 0;
        for (int k = 0; k < 2; k++) {
            const acd_mesh *x = ms[k][0], *y = ms[k][1];
            if (x->nvertices != y->nvertices || x->ntriangles != y->ntriangles ||
                memcmp(x->vertices, y->vertices, 3 * x->nvertices * sizeof(double)) ||
                memcmp(x->triangles, y->triangles, 3 * x->ntriangles * sizeof(uint32_t)))
                return 0;
        }
    }
    return 1;
}

typedef struct screen_case {
    const char *name;
    acd_mesh mesh;
    double tau;
} screen_case;

/* The cut choice by volume (the tight settings' choice; without the merge pass, which takes the tree
 * as it is: the same tree gives the same merge) with the screen and without it, on the bumpy sphere
 * (hull excess everywhere: many candidates per split) and the npm bunny. */
static void test_screen_off_same_output(void **state) {
    (void)state;
    screen_case cs[3];
    size_t n = 0;
    memset(cs, 0, sizeof cs);
    cs[n].name = "bumpy sphere";
    assert_true(mg_radial(&cs[n].mesh, 24, 16, mg_bumpy_r, NULL));
    cs[n].tau = 0.1;
    n++;
    char path[4096];
    acd_error err;
    if (tu_mesh_data(path, sizeof path, "bunny.obj")) {
        assert_int_equal(acd_mesh_read(path, &cs[n].mesh, &err), ACD_OK);
        cs[n].name = "npm bunny";
        cs[n].tau = 0.1;
        n++;
    } else {
        print_message("data/meshes/bunny.obj missing (scripts/fetch-data.sh): not run on it\n");
    }
    size_t screened = 0, differ = 0;
    for (size_t i = 0; i < n; i++) {
        acd3d_params p = acd3d_default_params();
        p.tau = cs[i].tau;
        p.cut_choice = ACD3D_CHOICE_VOLUME;
        p.merge_order = ACD3D_MERGE_VOLUME;
        p.merge = 0;
        static const int th[2] = {1, 4};
        acd3d_result on[2], off[2], wrong;
        acd3_decompose_stats son[2], soff[2], swrong;
        for (int t = 0; t < 2; t++) {
            p.threads = th[t];
            assert_int_equal(acd3_decompose_screen(&cs[i].mesh, &p, ACD3_VOLUME_SCREEN_REL, &son[t], &on[t], &err),
                             ACD_OK);
            /* no screen: NaN, or any margin <= -1 */
            assert_int_equal(acd3_decompose_screen(&cs[i].mesh, &p, t ? -1.0 : NAN, &soff[t], &off[t], &err), ACD_OK);
            print_message("%s, %d thread(s): %zu nodes, %zu parts; screen on: %zu candidates dropped, %zu hulled; "
                          "off: %zu dropped, %zu hulled\n",
                          cs[i].name, th[t], on[t].nnodes, on[t].nparts, son[t].screened, son[t].hulled,
                          soff[t].screened, soff[t].hulled);
            assert_int_equal(soff[t].screened, 0);
            assert_true(same_result(&on[t], &off[t]));
        }
        assert_true(same_result(&on[0], &on[1]));
        /* at one thread the runs evaluate the same candidates: those the screen drops get qhull hulls
         * without it, the others in both */
        assert_int_equal(son[0].hulled + son[0].screened, soff[0].hulled);
        assert_true(son[0].screened > 0); /* the screen was used */
        screened += son[0].screened;
        /* the control: a screen 3% wrong drops candidates that would have won */
        p.threads = 1;
        assert_int_equal(acd3_decompose_screen(&cs[i].mesh, &p, -0.03, &swrong, &wrong, &err), ACD_OK);
        const int d = !same_result(&wrong, &off[0]);
        print_message("%s: a screen 3%% wrong drops %zu candidates and %s\n", cs[i].name, swrong.screened,
                      d ? "changes the output" : "changes nothing");
        differ += (size_t)d;
        acd3d_result_free(&wrong);
        for (int t = 0; t < 2; t++) {
            acd3d_result_free(&on[t]);
            acd3d_result_free(&off[t]);
        }
    }
    print_message("the screen dropped %zu candidates at one thread; a screen 3%% wrong changed %zu of %zu outputs\n",
                  screened, differ, n);
    assert_true(differ > 0);
    for (size_t i = 0; i < n; i++) acd_mesh_free(&cs[i].mesh);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_screen_off_same_output),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
