/*
 * admit.h: the checks a request's head must pass before any route sees it:
 * a path that fits and holds no encoded NUL, at most PS_MAX_QUERY_PARAMS
 * query parameters, a Host header on HTTP/1.1 (RFC 9112), one
 * Content-Length, no transfer coding but chunked, not both a
 * Content-Length and a Transfer-Encoding (RFC 9112 6.3: a proxy in front
 * may have framed the body otherwise), and only health routes over the
 * connection limit.  Each refusal is answered at once with
 * problem+json, and the connection closes.  Also counts a header's lines,
 * for the routes' own checks.
 */
#ifndef PS_ADMIT_H
#define PS_ADMIT_H

#include <microhttpd.h>

#include "request.h"

/* Before libmicrohttpd splits the query string: 1 when uri has more than
 * PS_MAX_QUERY_PARAMS parameters, and then the query is dropped from the
 * request line (libmicrohttpd 0.9.75 runs out of connection memory on a
 * few hundred and then sends nothing at all). */
int ps_admit_cut_query(const char *uri);

/* 1 when the path of uri (before any '?') holds an encoded NUL byte
 * (%00): libmicrohttpd decodes it and the path would end there, so that
 * "/healthz%00x" would be served as "/healthz". */
int ps_admit_path_has_nul(const char *uri);

/* How many times the request's head gives header name (any case). */
int ps_admit_times_given(ps_request *r, const char *name);

/* MHD_YES/MHD_NO after answering a refused request; -1 when admitted. */
int ps_admit_check(ps_request *r);

/* 1 when the request announces a body (Content-Length > 0 or chunked), with
 * its declared length in *declared (0 when chunked). */
int ps_admit_has_body(ps_request *r, unsigned long long *declared);

#endif
