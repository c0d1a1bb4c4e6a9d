/*
 * respond.h: answering a request: a body with its media type, the CORS
 * headers the configuration asks for, extra headers, and problem+json
 * errors.  Each records status and size for the request log.
 */
#ifndef PS_RESPOND_H
#define PS_RESPOND_H

#include <microhttpd.h>
#include <stddef.h>

#include "request.h"

/* The headers list of a 503 answer: Retry-After: 1 (NULL-terminated, as the
 * headers argument below). */
extern const char *const ps_retry_after_header[];

/* Queues status with body (malloc'ed; taken and freed; may be NULL when len
 * is 0).  headers: NULL or a NULL-terminated list of name, value, ... */
enum MHD_Result ps_respond(ps_request *r, int status, const char *media_type, char *body,
                           size_t len, const char *const *headers);

/* Same, copying the body. */
enum MHD_Result ps_respond_copy(ps_request *r, int status, const char *media_type,
                                const char *body, size_t len, const char *const *headers);

/* A problem+json answer; detail is printf-like. */
enum MHD_Result ps_respond_problem(ps_request *r, int status, const char *const *headers,
                                   const char *fmt, ...) __attribute__((format(printf, 4, 5)));

/* A problem+json answer from an api error (503 gets Retry-After). */
enum MHD_Result ps_respond_error(ps_request *r, const ps_api_error *err);

/* The answer to OPTIONS (a CORS preflight): methods, the route's, in Allow
 * and, for an allowed origin, Access-Control-Allow-Methods. */
enum MHD_Result ps_respond_preflight(ps_request *r, const char *methods);

/* 1 when the request's Origin may read answers (and which value to echo). */
const char *ps_cors_allowed_origin(ps_request *r);

#endif
