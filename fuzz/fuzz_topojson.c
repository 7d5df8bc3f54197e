/* fuzz/fuzz_topojson: libFuzzer target for the 2D TopoJSON reader, validation and writers
 * (see fuzz_common_2d.h for the checks). */
#include "fuzz_common_2d.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fuzz_2d_one(data, size, ACD_POLY_FORMAT_TOPOJSON);
    return 0;
}
