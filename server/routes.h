/*
 * routes.h: what each route does.  The HTTP layer calls ps_routes_match
 * once a request's head is in, ps_routes_begin then (a request with a body)
 * or on the next callback (one without), ps_routes_upload_done once its
 * body is in, and ps_routes_resumed when its synchronous job has ended.
 * Each returns the libmicrohttpd result to hand back.
 */
#ifndef PS_ROUTES_H
#define PS_ROUTES_H

#include <microhttpd.h>

#include "request.h"

/* Sets r->route and, for /jobs/{id}..., r->job_id (from r->path). */
void ps_routes_match(ps_request *r);

/* After ps_routes_match: answers at once, or (POST /segment, /jobs) sets r->body for the upload. */
enum MHD_Result ps_routes_begin(ps_request *r);

/* Decodes, then answers 202 (/jobs) or suspends the connection until the
 * job ends (/segment). */
enum MHD_Result ps_routes_upload_done(ps_request *r);

/* Answers a resumed /segment request from its job. */
enum MHD_Result ps_routes_resumed(ps_request *r);

#endif
