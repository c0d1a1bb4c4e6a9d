/*
 * body.h: a request body as it arrives in pieces: optionally gzip-inflated
 * (Content-Encoding: gzip), optionally split by multipart/form-data (the
 * `file` part is the body, other parts are text fields), and bounded: more
 * than max_body bytes after inflating is a 413.
 */
#ifndef PS_BODY_H
#define PS_BODY_H

#include <stddef.h>

#include "api_error.h"

struct MHD_Connection;
typedef struct ps_body ps_body;

typedef struct ps_body_field {
    char *name;
    char *value;
} ps_body_field;

/* conn is needed only for multipart (libmicrohttpd's post processor reads
 * the boundary from its headers); reserve is a size hint (Content-Length).
 * Returns NULL and sets err when memory runs out or multipart has no
 * boundary. */
ps_body *ps_body_new(struct MHD_Connection *conn, size_t max_body, size_t reserve,
                     int gzip, int multipart, ps_api_error *err);

/* Takes the next len bytes.  Returns 0, or -1 with err (400 bad gzip or
 * multipart, 413 too large); after an error further data is ignored. */
int ps_body_feed(ps_body *b, const char *data, size_t len, ps_api_error *err);

/* The upload is complete: checks the gzip stream ended and the multipart
 * body reached its closing boundary and had a `file` part.  Returns 0 or -1
 * with err (400). */
int ps_body_finish(ps_body *b, ps_api_error *err);

/* The body bytes (the `file` part for multipart) and the fields. */
const char *ps_body_data(const ps_body *b, size_t *len);
const ps_body_field *ps_body_fields(const ps_body *b, size_t *count);

void ps_body_free(ps_body *b);

#endif
