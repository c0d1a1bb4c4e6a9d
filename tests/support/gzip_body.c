/* gzip_body.c: one gzip member (gzip_body.h), with zlib. */
#include "gzip_body.h"

#include <stdint.h>
#include <stdlib.h>
#include <zlib.h>

char *ps_test_gzip(const char *data, size_t n, size_t *len) {
    z_stream z = {0};
    uLong cap = compressBound((uLong)n) + 64;
    char *out = malloc(cap);
    if (!out || deflateInit2(&z, 6, Z_DEFLATED, 31, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
        free(out);
        return NULL;
    }
    z.next_in = (unsigned char *)(uintptr_t)data;
    z.avail_in = (uInt)n;
    z.next_out = (unsigned char *)out;
    z.avail_out = (uInt)cap;
    deflate(&z, Z_FINISH);
    *len = z.total_out;
    deflateEnd(&z);
    return out;
}
