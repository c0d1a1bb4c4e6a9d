/* fuzz_redis_url.c: libFuzzer target for ps_redis_url_parse (--redis): any
 * text either parses into a host, a port in 1-65535 and a database >= 0, or
 * is refused with a reason; never a crash or an unterminated field. */
#include "redis_link.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = 0;
    ps_redis_url url;
    char why[256];
    if (ps_redis_url_parse(text, &url, why, sizeof why) == 0) {
        if (!url.host[0] || url.port < 1 || url.port > 65535 || url.db < 0) abort();
        if (strnlen(url.host, sizeof url.host) == sizeof url.host) abort();
        if (strnlen(url.password, sizeof url.password) == sizeof url.password) abort();
    } else if (!why[0]) {
        abort();
    }
    free(text);
    return 0;
}
