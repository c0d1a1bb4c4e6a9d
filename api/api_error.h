/*
 * api_error.h: the error every api/ function reports: an HTTP status that
 * fits the problem (the daemon answers with it, the CLI exits 2) and a
 * message naming the problem and, for decoders, where it is (line or byte
 * offset).
 */
#ifndef PS_API_ERROR_H
#define PS_API_ERROR_H

typedef struct ps_api_error {
    int http_status;   /* 400 malformed (bytes in no known format included),
                          413 too large, 422 well-formed but unusable,
                          500 internal */
    char message[512];
} ps_api_error;

/* Sets err (if not NULL); returns -1 so callers can `return ps_api_fail(..)`. */
int ps_api_fail(ps_api_error *err, int http_status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

#endif
