/* decode_check.c: the shared decoder checks of decode_check.h. */
#include "decode_check.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "testlib.h"

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

static double seconds_now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int ps_decode_shared_file(const char *rel, ps_pointset *ps, double *ms) {
    const char *shared = ps_test_shared_dir();
    char path[1024];
    char *bytes;
    size_t len;
    ps_api_error err = {0, ""};
    if (!shared) {
        ps_test_skip("no shared data directory");
        return 0;
    }
    snprintf(path, sizeof path, "%s/%s", shared, rel);
    if (ps_read_file(path, &bytes, &len, &err)) {
        ps_test_skip("%s", err.message);
        return 0;
    }
    double t0 = seconds_now();
    int rc = ps_decode(bytes, len, NULL, ps, &err);
    if (ms) *ms = 1e3 * (seconds_now() - t0);
    free(bytes);
    if (rc) fprintf(stderr, "  %s: error %d: %s\n", rel, err.http_status, err.message);
    return rc == 0 ? 1 : -1;
}
