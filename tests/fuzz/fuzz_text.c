/* fuzz_text.c: libFuzzer target for format detection, the OFF, OBJ and
 * XYZ/CSV decoders and the labels decoder (`pointseg score`'s .seg files);
 * every input goes through all of them and ps_decode (tests/fuzz/run.sh). */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "decode.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    typedef int (*decoder)(const char *, size_t, const ps_decode_limits *, ps_pointset *,
                           ps_api_error *);
    static const decoder decoders[] = {ps_decode_off, ps_decode_obj, ps_decode_xyz};
    ps_decode_limits lim = {1u << 20, 64};
    ps_pointset ps;
    ps_api_error err;
    for (size_t i = 0; i < sizeof decoders / sizeof decoders[0]; i++)
        if (decoders[i]((const char *)data, size, &lim, &ps, &err) == 0)
            ps_pointset_free(&ps);
    if (ps_decode((const char *)data, size, &lim, &ps, &err) == 0) ps_pointset_free(&ps);
    int *labels = NULL;
    size_t count = 0;
    if (ps_decode_labels((const char *)data, size, &labels, &count, &err) == 0) free(labels);
    return 0;
}
