/* libFuzzer target: the .seg parser (corise/segio) and, on what it accepts, the region metrics of
 * the labels against their reverse (must stay within [0, 1]). */
#include <stdint.h>
#include <stdlib.h>

#include "acd/segment.h"
#include "corise/segio.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    int *lab = NULL;
    size_t n = 0;
    acd_error err;
    if (acd_seg_parse((const char *)data, size, "fuzz.seg", ACD_SEG_ANY_COUNT, &lab, &n, &err) == ACD_OK && n > 0 &&
        n < 4096) {
        int *rev = malloc(n * sizeof *rev);
        if (rev) {
            for (size_t i = 0; i < n; i++) rev[i] = lab[n - 1 - i];
            acd_segeval_result r;
            if (acd_segeval_regions(lab, rev, n, NULL, &r, &err) == ACD_OK) {
                if (!(r.rand_index >= 0 && r.rand_index <= 1 && r.gce >= 0 && r.gce <= 1 && r.lce <= r.gce + 1e-12 &&
                      r.hamming >= 0 && r.hamming <= 1))
                    abort();
            }
            free(rev);
        }
    }
    free(lab);
    return 0;
}
