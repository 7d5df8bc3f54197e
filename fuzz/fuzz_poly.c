/* fuzz/fuzz_poly: libFuzzer target for the 2D poly reader, validation and writers
 * (see fuzz_common_2d.h for the checks). */
#include "fuzz_common_2d.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fuzz_2d_one(data, size, ACD_POLY_FORMAT_POLY);
    return 0;
}
