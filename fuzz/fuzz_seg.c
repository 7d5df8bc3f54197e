/* libFuzzer target: the .seg parser (corise/segio) and, on what it accepts, the region metrics of
 * the labels against their reverse (must stay within [0, 1]), and properties the metrics must
 * satisfy exactly (unit weights and under 4096 faces: every sum is an integer, so exact but for the
 * consistency errors' divisions):
 *  - labels against themselves, or against a relabelling (each label x renamed ~x = -x - 1:
 *    another name for every segment): Rand index 1, Hamming 0, GCE and LCE 0;
 *  - against a coarsening (label x / 2: segments merged in pairs): GCE and LCE 0 (one refines the
 *    other);
 *  - swapping the two segmentations (the labels against their rotation by one face): the same Rand
 *    index and GCE/LCE (to rounding), Hamming's missing and false rates exchanged.
 * A refusal must name the file and a line within the input. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "acd/segment.h"
#include "corise/segio.h"
#include "fuzz_refusal.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static acd_segeval_result regions(const int *a, const int *b, size_t n) {
    acd_segeval_result r;
    acd_error err;
    if (acd_segeval_regions(a, b, n, NULL, &r, &err) != ACD_OK) abort(); /* n > 0 unit weights: defined */
    if (!(r.rand_index >= 0 && r.rand_index <= 1 && r.gce >= 0 && r.gce <= 1 && r.lce >= 0 && r.lce <= r.gce + 1e-12 &&
          r.hamming >= 0 && r.hamming <= 1))
        abort();
    return r;
}

static void same_segmentation(const int *a, const int *b, size_t n) {
    acd_segeval_result r = regions(a, b, n);
    if (r.rand_index != 1 || r.hamming != 0 || r.gce != 0 || r.lce != 0) abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    int *lab = NULL;
    size_t n = 0;
    acd_error err;
    err.message[0] = '\0';
    if (acd_seg_parse((const char *)data, size, "fuzz.seg", ACD_SEG_ANY_COUNT, &lab, &n, &err) != ACD_OK) {
        fuzz_check_refusal(err.message, "fuzz.seg", data, size, 1);
        return 0;
    }
    if (n > 0 && n < 4096) {
        int *rev = malloc(n * sizeof *rev), *rel = malloc(n * sizeof *rel), *rot = malloc(n * sizeof *rot);
        if (rev && rel && rot) {
            for (size_t i = 0; i < n; i++) {
                rev[i] = lab[n - 1 - i];
                rot[i] = lab[(i + 1) % n];
                /* a bijection of int: -x - 1 (~x) maps INT_MIN..INT_MAX onto itself */
                rel[i] = ~lab[i];
            }
            regions(lab, rev, n);
            acd_segeval_result ab = regions(lab, rot, n), ba = regions(rot, lab, n);
            if (ab.rand_index != ba.rand_index || ab.hamming_rm != ba.hamming_rf || ab.hamming_rf != ba.hamming_rm ||
                fabs(ab.gce - ba.gce) > 1e-12 || fabs(ab.lce - ba.lce) > 1e-12 || ab.nsegments_a != ba.nsegments_b)
                abort();
            same_segmentation(lab, lab, n);
            same_segmentation(lab, rel, n);
            for (size_t i = 0; i < n; i++) rel[i] = lab[i] / 2;
            acd_segeval_result c = regions(lab, rel, n);
            if (c.gce != 0 || c.lce != 0) abort();
        }
        free(rev);
        free(rel);
        free(rot);
    }
    free(lab);
    return 0;
}
