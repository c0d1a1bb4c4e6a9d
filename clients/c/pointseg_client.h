/*
 * pointseg_client.h: a small libcurl client of pointsegd: synchronous
 * segmentation, the asynchronous job API (submit, poll, result, cancel),
 * and a generic request for anything else.  Each call is independent and
 * thread safe (call ps_client_global_init once first).
 */
#ifndef PS_CLIENT_H
#define PS_CLIENT_H

#include <stddef.h>

typedef struct ps_client {
    const char *base_url; /* "http://127.0.0.1:8080" */
    const char *token;    /* bearer token, or NULL */
    long timeout_ms;      /* whole request; 0 = none */
} ps_client;

/* Most bytes of an answer's header lines: past them the call fails. */
#define PS_CLIENT_HEAD_MAX 65536

typedef struct ps_client_response {
    long status;          /* HTTP status, 0 when the transfer failed */
    char *body;           /* malloc'ed, NUL-terminated (free with ps_client_response_free) */
    size_t len;
    char *head;           /* its status and header lines as received, malloc'ed like body */
    size_t head_len;
    /* These headers' values, whole, in head: "" when absent (never NULL). */
    const char *content_type;
    const char *location;
    const char *retry_after;
    const char *allow;
    char error[256];      /* why, when status is 0: libcurl's message or the client's */
} ps_client_response;

typedef struct ps_client_body {
    const void *data;
    size_t len;
    const char *content_type;     /* NULL = application/octet-stream */
    const char *content_encoding; /* NULL or "gzip" */
} ps_client_body;

/* Once per process, before any thread uses the client. */
int ps_client_global_init(void);

/* Any request; body may be NULL; headers: NULL-terminated "Name: value"
 * lines.  Returns 0 when an answer came (any status), -1 otherwise. */
int ps_client_request(const ps_client *c, const char *method, const char *path_and_query,
                      const ps_client_body *body, const char *const *headers, ps_client_response *out);

/* POST /segment?query (query may be NULL or ""). */
int ps_client_segment(const ps_client *c, const ps_client_body *body, const char *query,
                      ps_client_response *out);

/* POST /jobs?query; on 202 copies the job id into id (cap bytes). */
int ps_client_submit(const ps_client *c, const ps_client_body *body, const char *query,
                     char *id, size_t cap, ps_client_response *out);

int ps_client_poll(const ps_client *c, const char *id, ps_client_response *out);   /* GET /jobs/{id} */
int ps_client_result(const ps_client *c, const char *id, ps_client_response *out); /* GET /jobs/{id}/result */
int ps_client_cancel(const ps_client *c, const char *id, ps_client_response *out); /* DELETE /jobs/{id} */

/* Polls until the job is done, failed or cancelled, or timeout_ms passes
 * (measured on the clock, polls included); copies its final status
 * ("done", ...) into state.  Returns 0 when final. */
int ps_client_wait(const ps_client *c, const char *id, long timeout_ms, char *state, size_t cap);

/* 1 when a job status ("queued", "running", "done", ...) will not change
 * any more: done, failed or cancelled. */
int ps_client_job_is_final(const char *state);

/* Frees the body and header lines; the header values are "" again. */
void ps_client_response_free(ps_client_response *r);

#endif
