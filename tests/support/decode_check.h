/*
 * decode_check.h: the checks the decoder tests share: a text decodes, or a
 * decoder fails with the expected status and message and leaves nothing
 * allocated; a file of the shared data decodes.  They print what they got on
 * stderr when it is not expected.
 */
#ifndef PS_DECODE_CHECK_H
#define PS_DECODE_CHECK_H

#include "decode.h"

typedef int (*ps_decode_fn)(const char *bytes, size_t len, const ps_decode_limits *lim,
                            ps_pointset *out, ps_api_error *err);

/* ps_decode of a NUL-terminated text succeeds (ps filled; free it). */
int ps_check_decodes(const char *text, ps_pointset *ps);

/* decode(bytes) fails with http status `status`, a message containing
 * `needle`, and an empty point set. */
int ps_check_decode_fails(ps_decode_fn decode, const char *bytes, size_t len,
                          const ps_decode_limits *lim, int status, const char *needle);

/* Reads `rel` below ps_test_shared_dir() and decodes it into ps (free it);
 * *ms (if not NULL) gets the decode time in milliseconds.  Returns 1 when
 * decoded, 0 after reporting SKIP (no shared data or the file unreadable;
 * the test should return), -1 when the decode failed. */
int ps_decode_shared_file(const char *rel, ps_pointset *ps, double *ms);

#endif
