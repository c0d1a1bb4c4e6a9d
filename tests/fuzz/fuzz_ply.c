/* fuzz_ply.c: libFuzzer target for the PLY decoder (tests/fuzz/run.sh). */
#include <stddef.h>
#include <stdint.h>

#include "decode.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    ps_decode_limits lim = {1u << 20, 64};
    ps_pointset ps;
    ps_api_error err;
    if (ps_decode_ply((const char *)data, size, &lim, &ps, &err) == 0) ps_pointset_free(&ps);
    return 0;
}
