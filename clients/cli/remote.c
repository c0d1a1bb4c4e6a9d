/*
 * remote.c: segmentation on a pointsegd daemon for `pointseg segment
 * --server URL` (remote.h): POST /segment, or POST /jobs, polling
 * GET /jobs/{id} every POLL_MS until the job is final, then
 * GET /jobs/{id}/result.  Parameters travel in the query string.  The
 * daemon refuses a parameter given twice, so what overrides what locally
 * (a later flag an earlier one, a flag the JSON input's "params") is
 * settled here: only the overriding one is sent.
 */
#include "remote.h"

#include "commands.h"
#include "params_table.h"
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

/* 1 when one of the parameters from #from on names the same table entry
 * as name ("ncut-threshold" and "ncut_threshold" are one). */
static int named_from(const cli_remote *r, int from, const char *name) {
    const ps_param_spec *spec = ps_param_find(name);
    for (int i = from; spec && i < r->n_params; i++)
        if (ps_param_find(r->params[i].name) == spec) return 1;
    return 0;
}

/* "name=value&..." of the parameters (malloc'ed), or NULL; of a parameter
 * given more than once only the last. */
static char *make_query(const cli_remote *r) {
    size_t cap = 1;
    for (int i = 0; i < r->n_params; i++)
        cap += 3 * (strlen(r->params[i].name) + strlen(r->params[i].value)) + 2;
    char *query = malloc(cap), *q = query;
    if (!query) return NULL;
    for (int i = 0; i < r->n_params; i++) {
        if (named_from(r, i + 1, r->params[i].name)) continue;
        if (q != query) *q++ = '&';
        q = append_encoded(q, r->params[i].name);
        *q++ = '=';
        q = append_encoded(q, r->params[i].value);
    }
    *q = 0;
    return query;
}

/* The input when it is a JSON object whose "params" name a parameter a
 * flag gives too: the same object without those (malloc'ed, #*out_len
 * bytes).  NULL otherwise: any other input, or nothing overridden. */
static char *without_overridden(const cli_remote *r, const char *bytes, size_t len,
                                size_t *out_len) {
    size_t skip = len >= 3 && memcmp(bytes, "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;
    while (skip < len && bytes[skip] && strchr(" \t\r\n", bytes[skip])) skip++;
    if (r->n_params == 0 || skip == len || bytes[skip] != '{') return NULL;
    cJSON *doc = cJSON_ParseWithLength(bytes + skip, len - skip);
    cJSON *params = cJSON_GetObjectItemCaseSensitive(doc, "params");
    cJSON *item = cJSON_IsObject(params) ? params->child : NULL;
    int dropped = 0;
    while (item) {
        cJSON *next = item->next;
        if (item->string && named_from(r, 0, item->string)) {
            cJSON_Delete(cJSON_DetachItemViaPointer(params, item));
            dropped = 1;
        }
        item = next;
    }
    char *text = dropped ? cJSON_PrintUnformatted(doc) : NULL;
    cJSON_Delete(doc);
    if (text) *out_len = strlen(text);
    return text;
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

/* Takes the body of a 200 answer; otherwise reports it.  Frees res. */
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
    ps_client_response_free(res);
    return 0;
}

/* Polls job id until it is done, failed or cancelled; 0 or an exit status.
 * A status answer without a readable status ends the wait: polling again
 * would not make it readable. */
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
        if (!state[0]) {
            fprintf(stderr, "pointseg: %s: %s answered GET /jobs/%s without a readable status\n",
                    what, c->base_url, id);
            return EXIT_INTERNAL;
        }
        if (ps_client_job_is_final(state)) return 0;
        nanosleep(&pause, NULL);
    }
}

static int run_async(const ps_client *c, const ps_client_body *body, const char *query,
                     const char *what, char **answer, size_t *answer_len) {
    char id[128];
    ps_client_response res;
    int id_unread = ps_client_submit(c, body, query, id, sizeof id, &res) != 0;
    if (res.status != 202) return take_answer(what, c->base_url, &res, answer, answer_len);
    ps_client_response_free(&res);
    if (id_unread) {
        fprintf(stderr, "pointseg: %s: %s answered 202 without a readable job id\n", what,
                c->base_url);
        return EXIT_INTERNAL;
    }
    int rc = wait_for_job(c, id, what);
    if (rc) return rc;
    ps_client_result(c, id, &res);
    return take_answer(what, c->base_url, &res, answer, answer_len);
}

int cli_remote_segment(const cli_remote *r, const char *bytes, size_t len, const char *what,
                       char **answer, size_t *answer_len) {
    ps_client c = {r->server, r->token, 0};
    size_t own_len = 0;
    char *own = without_overridden(r, bytes, len, &own_len);
    ps_client_body body = {own ? own : bytes, own ? own_len : len, NULL, NULL};
    ps_client_response res;
    char *query = make_query(r);
    if (!query || ps_client_global_init() != 0) {
        free(query);
        free(own);
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
    free(own);
    return rc;
}
