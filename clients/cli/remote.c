/*
 * remote.c: segmentation on a pointsegd daemon for `pointseg segment
 * --server URL` (remote.h): POST /segment, or POST /jobs, polling
 * GET /jobs/{id} every POLL_MS until the job is final, then
 * GET /jobs/{id}/result.  Parameters travel in the query string.
 */
#include "remote.h"

#include "commands.h"
#include "pointseg_client.h"

#include <cjson/cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { POLL_MS = 100, DETAIL_MAX = 300 };

/* Appends text to q percent-encoding all but unreserved characters; q has
 * room (3 bytes per input byte were reserved). */
static char *append_encoded(char *q, const char *text) {
    static const char hex[] = "0123456789ABCDEF";
    for (const unsigned char *p = (const unsigned char *)text; *p; p++) {
        if ((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') ||
            strchr("-_.~", *p)) {
            *q++ = (char)*p;
        } else {
            *q++ = '%';
            *q++ = hex[*p >> 4];
            *q++ = hex[*p & 15];
        }
    }
    return q;
}

/* "name=value&..." of the parameters (malloc'ed), or NULL. */
static char *make_query(const cli_remote *r) {
    size_t cap = 1;
    for (int i = 0; i < r->n_params; i++)
        cap += 3 * (strlen(r->params[i].name) + strlen(r->params[i].value)) + 2;
    char *query = malloc(cap), *q = query;
    if (!query) return NULL;
    for (int i = 0; i < r->n_params; i++) {
        if (i) *q++ = '&';
        q = append_encoded(q, r->params[i].name);
        *q++ = '=';
        q = append_encoded(q, r->params[i].value);
    }
    *q = 0;
    return query;
}

/* A string member of a JSON object body into out ("" when absent). */
static void json_text(const char *body, const char *name, char *out, size_t cap) {
    cJSON *doc = body ? cJSON_Parse(body) : NULL;
    const cJSON *item = cJSON_GetObjectItemCaseSensitive(doc, name);
    snprintf(out, cap, "%s", cJSON_IsString(item) ? item->valuestring : "");
    cJSON_Delete(doc);
}

/* Reports a response that is not the expected success; returns the exit
 * status. */
static int report_failure(const char *what, const char *server, const ps_client_response *res) {
    char detail[DETAIL_MAX];
    if (res->status == 0) {
        fprintf(stderr, "pointseg: %s: no answer from %s: %s\n", what, server, res->error);
        return EXIT_INTERNAL;
    }
    json_text(res->body, "detail", detail, sizeof detail);
    fprintf(stderr, "pointseg: %s: %s answered %ld: %s\n", what, server, res->status,
            detail[0] ? detail : "(no detail)");
    return res->status >= 400 && res->status < 500 ? EXIT_USAGE : EXIT_INTERNAL;
}

/* Takes the body of a 200 answer; otherwise reports it. */
static int take_answer(const char *what, const char *server, ps_client_response *res,
                       char **answer, size_t *answer_len) {
    if (res->status != 200) {
        int rc = report_failure(what, server, res);
        ps_client_response_free(res);
        return rc;
    }
    *answer = res->body;
    *answer_len = res->len;
    res->body = NULL;
    return 0;
}

/* Polls job id until it is done, failed or cancelled; 0 or an exit status. */
static int wait_for_job(const ps_client *c, const char *id, const char *what) {
    struct timespec pause = {0, POLL_MS * 1000L * 1000L};
    char state[32];
    for (;;) {
        ps_client_response res;
        ps_client_poll(c, id, &res);
        if (res.status != 200) {
            int rc = report_failure(what, c->base_url, &res);
            ps_client_response_free(&res);
            return rc;
        }
        json_text(res.body, "status", state, sizeof state);
        ps_client_response_free(&res);
        if (ps_client_job_is_final(state)) return 0;
        nanosleep(&pause, NULL);
    }
}

static int run_async(const ps_client *c, const ps_client_body *body, const char *query,
                     const char *what, char **answer, size_t *answer_len) {
    char id[128];
    ps_client_response res;
    ps_client_submit(c, body, query, id, sizeof id, &res);
    if (res.status != 202) return take_answer(what, c->base_url, &res, answer, answer_len);
    ps_client_response_free(&res);
    int rc = wait_for_job(c, id, what);
    if (rc) return rc;
    ps_client_result(c, id, &res);
    return take_answer(what, c->base_url, &res, answer, answer_len);
}

int cli_remote_segment(const cli_remote *r, const char *bytes, size_t len, const char *what,
                       char **answer, size_t *answer_len) {
    ps_client c = {r->server, r->token, 0};
    ps_client_body body = {bytes, len, NULL, NULL};
    ps_client_response res;
    char *query = make_query(r);
    if (!query || ps_client_global_init() != 0) {
        free(query);
        fprintf(stderr, "pointseg: %s: cannot set up the HTTP client\n", what);
        return EXIT_INTERNAL;
    }
    int rc;
    if (r->async) {
        rc = run_async(&c, &body, query, what, answer, answer_len);
    } else {
        ps_client_segment(&c, &body, query, &res);
        rc = take_answer(what, r->server, &res, answer, answer_len);
    }
    free(query);
    return rc;
}
