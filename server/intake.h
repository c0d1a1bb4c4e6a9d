/*
 * intake.h: a request's bytes and text parameters into what a job needs: the
 * decoded point set and the effective ps_request_params.  Knows nothing of
 * sockets; the HTTP layer collects the pieces.
 */
#ifndef PS_INTAKE_H
#define PS_INTAKE_H

#include <stddef.h>

#include "api_error.h"
#include "params_table.h"
#include "pointset.h"

typedef enum ps_media {
    PS_MEDIA_POINTS = 0,  /* application/octet-stream, text/plain, and the types a client
                             guesses from a file's name (model/obj for .obj, chemical/x-xyz
                             for .xyz: Python's mimetypes, /etc/mime.types): any format,
                             by content */
    PS_MEDIA_PLY,         /* application/ply: a PLY file */
    PS_MEDIA_JSON,        /* application/json */
    PS_MEDIA_MULTIPART,   /* multipart/form-data */
    PS_MEDIA_UNSUPPORTED
} ps_media;

/* From a Content-Type header value (NULL = octet-stream). */
ps_media ps_intake_media(const char *content_type);

/* 1 when content_type is application/x-www-form-urlencoded: what curl
 * sends with --data-binary unless told otherwise, so a 415 says how to fix
 * it. */
int ps_intake_is_form(const char *content_type);

typedef struct ps_text_param {
    const char *name;
    const char *value;
} ps_text_param;

/* Decodes len bytes (multipart: the `file` part, recognized by content) into
 * *out, at most max_points points.  Returns 0 or -1 with err: bytes that
 * are not what the media type says (no known format; not PLY for
 * application/ply; not JSON) are a 400, as any other malformed body. */
int ps_intake_decode(const char *bytes, size_t len, ps_media media, size_t max_points,
                     ps_pointset *out, ps_api_error *err);

/* The parameters of a request: defaults (threads = 0: the job runner gives
 * the job the cores no other job holds, core_share.h), the Accept header
 * (PLY output when it names application/ply with a quality over 0 and not
 * below application/json's, unless `output` says otherwise; may be NULL),
 * then the body's own params and the extra pairs (multipart fields,
 * the query string), which together give each parameter once.  Returns 0 or
 * -1 with err (400 unknown name or one given twice, in any spelling; 422 bad
 * value). */
int ps_intake_params(const ps_pointset *body, const char *accept, const ps_text_param *extra,
                     size_t n_extra, ps_request_params *rp, ps_api_error *err);

/* 0 when the job's memory estimate (ps_segment_memory_estimate, plus the
 * decoded input) is within max_memory bytes; else -1 with a 413 naming the
 * estimate and the limit. */
int ps_intake_check_memory(const ps_pointset *ps, const ps_request_params *rp, size_t max_memory,
                           ps_api_error *err);

#endif
