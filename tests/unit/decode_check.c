/* decode_check.c: the shared decoder checks of decode_check.h. */
#include "decode_check.h"

#include <stdio.h>
#include <string.h>

int ps_check_decodes(const char *text, ps_pointset *ps) {
    ps_api_error err = {0, ""};
    int rc = ps_decode(text, strlen(text), NULL, ps, &err);
    if (rc) fprintf(stderr, "  unexpected error %d: %s\n", err.http_status, err.message);
    return rc == 0;
}

int ps_check_decode_fails(ps_decode_fn decode, const char *bytes, size_t len,
                          const ps_decode_limits *lim, int status, const char *needle) {
    ps_pointset ps;
    ps_api_error err = {0, ""};
    int rc = decode(bytes, len, lim, &ps, &err);
    int ok = rc == -1 && err.http_status == status && strstr(err.message, needle) &&
             !ps.points && ps.n == 0 && !ps.params;
    if (!ok) fprintf(stderr, "  got %d %d \"%s\", wanted %d \"%s\"\n", rc, err.http_status,
                     err.message, status, needle);
    if (rc == 0) ps_pointset_free(&ps);
    return ok;
}
