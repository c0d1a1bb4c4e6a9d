/* respond.c: queuing answers with their headers; problem+json errors; CORS. */
#include "respond.h"

#include "direct_answer.h"
#include "problem.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DIRECT_ANSWER_SECONDS 10.0

const char *const ps_retry_after_header[] = {MHD_HTTP_HEADER_RETRY_AFTER, "1", NULL};

const char *ps_cors_allowed_origin(ps_request *r) {
    const char *allowed = r->srv->cfg->cors_origin;
    const char *origin = MHD_lookup_connection_value(r->conn, MHD_HEADER_KIND, "Origin");
    if (!*allowed || !origin) return NULL;
    if (!strcmp(allowed, "*")) return "*";
    size_t n = strlen(origin);
    for (const char *p = allowed; *p;) {
        const char *comma = strchr(p, ',');
        size_t len = comma ? (size_t)(comma - p) : strlen(p);
        while (len && *p == ' ') p++, len--;
        while (len && p[len - 1] == ' ') len--;
        if (len == n && !strncmp(p, origin, n)) return origin;
        p += len;
        while (*p == ' ' || *p == ',') p++;
    }
    return NULL;
}

static void add_cors(ps_request *r, struct MHD_Response *resp) {
    const char *origin = ps_cors_allowed_origin(r);
    if (!origin) return;
    MHD_add_response_header(resp, "Access-Control-Allow-Origin", origin);
    MHD_add_response_header(resp, "Access-Control-Expose-Headers", "Location, Retry-After");
    if (strcmp(origin, "*")) MHD_add_response_header(resp, "Vary", "Origin");
}

static enum MHD_Result queue(ps_request *r, int status, const char *media_type, struct MHD_Response *resp,
                             const char *body, size_t len, const char *const *headers) {
    if (!resp) return MHD_NO;
    if (media_type) MHD_add_response_header(resp, MHD_HTTP_HEADER_CONTENT_TYPE, media_type);
    for (; headers && headers[0] && headers[1]; headers += 2) MHD_add_response_header(resp, headers[0], headers[1]);
    add_cors(r, resp);
    r->status = status;
    r->bytes = len;
    if (r->answer_direct) {
        r->sent_direct = !ps_direct_answer(ps_connection_fd(r->conn), status, resp, body, len,
                                           DIRECT_ANSWER_SECONDS);
        MHD_destroy_response(resp);
        return MHD_NO;
    }
    if (r->defer_answer) {
        r->pending = resp;
        return MHD_YES;
    }
    enum MHD_Result rc = MHD_queue_response(r->conn, (unsigned)status, resp);
    MHD_destroy_response(resp);
    return rc;
}

enum MHD_Result ps_respond(ps_request *r, int status, const char *media_type, char *body,
                           size_t len, const char *const *headers) {
    struct MHD_Response *resp = MHD_create_response_from_buffer(len, body, MHD_RESPMEM_MUST_FREE);
    if (!resp) free(body);
    return queue(r, status, media_type, resp, body, len, headers);
}

enum MHD_Result ps_respond_copy(ps_request *r, int status, const char *media_type,
                                const char *body, size_t len, const char *const *headers) {
    struct MHD_Response *resp =
        MHD_create_response_from_buffer(len, (void *)(uintptr_t)body, MHD_RESPMEM_MUST_COPY);
    return queue(r, status, media_type, resp, body, len, headers);
}

enum MHD_Result ps_respond_problem(ps_request *r, int status, const char *const *headers,
                                   const char *fmt, ...) {
    char detail[600];
    size_t len = 0;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(detail, sizeof detail, fmt, ap);
    va_end(ap);
    char *doc = ps_problem_json(status, detail, &len);
    if (!doc) return MHD_NO;
    return ps_respond(r, status, PS_PROBLEM_MEDIA_TYPE, doc, len, headers);
}

enum MHD_Result ps_respond_error(ps_request *r, const ps_api_error *err) {
    int status = err->http_status >= 400 && err->http_status < 600 ? err->http_status : 500;
    return ps_respond_problem(r, status, status == 503 ? ps_retry_after_header : NULL, "%s", err->message);
}

enum MHD_Result ps_respond_preflight(ps_request *r, const char *methods) {
    const char *const headers[] = {
        "Access-Control-Allow-Methods", methods,
        "Access-Control-Allow-Headers", "Authorization, Content-Type, Content-Encoding, Accept",
        "Access-Control-Max-Age", "600",
        MHD_HTTP_HEADER_ALLOW, methods, NULL};
    return ps_respond(r, 204, NULL, NULL, 0, ps_cors_allowed_origin(r) ? headers : headers + 6);
}
