/* api_error.c: filling in a ps_api_error (status plus formatted message). */
#include "api_error.h"

#include <stdarg.h>
#include <stdio.h>

int ps_api_fail(ps_api_error *err, int http_status, const char *fmt, ...) {
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
        err->http_status = http_status;
    }
    return -1;
}
