/* gzip_body.h: request bodies compressed as one gzip member, for the tests
 * that send Content-Encoding: gzip. */
#ifndef PS_GZIP_BODY_H
#define PS_GZIP_BODY_H

#include <stddef.h>

/* data (#n) as one malloc'ed gzip member of *len bytes; NULL when out of memory. */
char *ps_test_gzip(const char *data, size_t n, size_t *len);

#endif
