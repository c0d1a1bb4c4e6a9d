/*
 * remote.h: `pointseg segment --server URL`: sends the input to a pointsegd
 * daemon (clients/c/pointseg_client.h) instead of segmenting locally.
 */
#ifndef PS_CLI_REMOTE_H
#define PS_CLI_REMOTE_H

#include <stddef.h>

typedef struct cli_remote_param {
    const char *name;  /* a parameter name ("ncut-threshold" or "ncut_threshold") */
    const char *value; /* as text */
} cli_remote_param;

typedef struct cli_remote {
    const char *server;            /* "http://127.0.0.1:8080" */
    const char *token;             /* bearer token, or NULL */
    int async;                     /* 1: POST /jobs and poll; 0: POST /segment */
    const cli_remote_param *params; /* #n_params, sent in the query string; as
                                       locally, a later one overrides an earlier
                                       one and the JSON input's "params" */
    int n_params;
} cli_remote;

/* Sends the input bytes (#len, any format the daemon reads) and on success
 * sets *answer (malloc'ed, #*answer_len bytes) to the daemon's document.
 * what names the input in messages ("pointseg: WHAT: ..." on stderr).
 * Returns 0, 2 when the daemon refused the input or parameters (4xx), 1
 * otherwise (no answer, 5xx, job failed). */
int cli_remote_segment(const cli_remote *r, const char *bytes, size_t len, const char *what,
                       char **answer, size_t *answer_len);

#endif
