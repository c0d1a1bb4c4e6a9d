/* routes.c: routing, authorization, and the handler of every route. */
#include "routes.h"

#include "admit.h"
#include "direct_answer.h"
#include "respond.h"
#include "static_files.h"

#include <cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>
#include <unistd.h>

static const char *const allow_get[] = {MHD_HTTP_HEADER_ALLOW, "GET, HEAD, OPTIONS", NULL};
static const char *const allow_post[] = {MHD_HTTP_HEADER_ALLOW, "POST, OPTIONS", NULL};
static const char *const allow_job[] = {MHD_HTTP_HEADER_ALLOW, "GET, HEAD, DELETE, OPTIONS", NULL};

static int is(const ps_request *r, const char *method) { return !strcmp(r->method, method); }

void ps_routes_match(ps_request *r) {
    static const struct { const char *path; ps_route route; } fixed[] = {
        {"/segment", PS_ROUTE_SEGMENT}, {"/jobs", PS_ROUTE_JOBS}, {"/healthz", PS_ROUTE_HEALTHZ},
        {"/readyz", PS_ROUTE_READYZ}, {"/metrics", PS_ROUTE_METRICS},
        {"/openapi.json", PS_ROUTE_OPENAPI}, {"/version", PS_ROUTE_VERSION}};
    for (size_t i = 0; i < sizeof fixed / sizeof fixed[0]; i++)
        if (!strcmp(r->path, fixed[i].path)) {
            r->route = fixed[i].route;
            return;
        }
    r->route = PS_ROUTE_STATIC;
    if (strncmp(r->path, "/jobs/", 6)) return;
    const char *id = r->path + 6, *slash = strchr(id, '/');
    size_t len = slash ? (size_t)(slash - id) : strlen(id);
    if (!len || len >= sizeof r->job_id) return;
    if (slash && strcmp(slash, "/result")) return;
    memcpy(r->job_id, id, len);
    r->job_id[len] = 0;
    r->route = slash ? PS_ROUTE_JOB_RESULT : PS_ROUTE_JOB;
}

/* Compares in time independent of where they differ. */
static int same_secret(const char *a, const char *b) {
    size_t la = strlen(a), lb = strlen(b);
    unsigned char diff = (unsigned char)(la != lb);
    for (size_t i = 0; i < lb; i++) diff |= (unsigned char)(a[i < la ? i : 0] ^ b[i]);
    return la > 0 && diff == 0;
}

static int authorized(ps_request *r) {
    const char *token = r->srv->cfg->token;
    if (!*token || r->route == PS_ROUTE_HEALTHZ || r->route == PS_ROUTE_READYZ) return 1; /* probes */
    const char *h = MHD_lookup_connection_value(r->conn, MHD_HEADER_KIND, MHD_HTTP_HEADER_AUTHORIZATION);
    return h && !strncasecmp(h, "Bearer ", 7) && same_secret(h + 7, token);
}

static enum MHD_Result respond_json(ps_request *r, int status, cJSON *doc, const char *const *headers) {
    char *text = doc ? cJSON_PrintUnformatted(doc) : NULL;
    cJSON_Delete(doc);
    if (!text) return ps_respond_problem(r, 500, NULL, "out of memory");
    return ps_respond(r, status, "application/json", text, strlen(text), headers);
}

static void add_time(cJSON *o, const char *name, double t) {
    char text[32];
    time_t secs = (time_t)t;
    struct tm tm;
    if (t <= 0) return;
    gmtime_r(&secs, &tm);
    size_t n = strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &tm);
    snprintf(text + n, sizeof text - n, ".%03dZ", (int)((t - (double)secs) * 1000));
    cJSON_AddStringToObject(o, name, text);
}

static cJSON *status_document(const ps_job_status *job) {
    ps_job_status st = *job;
    cJSON *doc = cJSON_CreateObject(), *progress = cJSON_CreateObject();
    cJSON_AddStringToObject(doc, "id", st.id);
    cJSON_AddStringToObject(doc, "status", ps_job_state_name(st.state));
    cJSON_AddStringToObject(progress, "phase", ps_phase_name(st.phase));
    cJSON_AddNumberToObject(progress, "fraction", st.state == PS_JOB_DONE ? 1.0 : st.fraction);
    cJSON_AddItemToObject(doc, "progress", progress);
    cJSON_AddNumberToObject(doc, "points", (double)st.n_points);
    add_time(doc, "created", st.created);
    add_time(doc, "started", st.started);
    add_time(doc, "finished", st.finished);
    if (st.state == PS_JOB_FAILED) {
        cJSON *e = cJSON_CreateObject();
        cJSON_AddNumberToObject(e, "status", st.error_status);
        cJSON_AddStringToObject(e, "detail", st.error);
        cJSON_AddItemToObject(doc, "error", e);
    }
    return doc;
}

static enum MHD_Result job_route(ps_request *r) {
    ps_job_status st;
    int cancel = is(r, "DELETE");
    int rc = cancel ? ps_jobstore_cancel(r->srv->store, r->job_id, &st, &r->error)
                    : ps_jobstore_status(r->srv->store, r->job_id, &st, &r->error);
    if (rc) return ps_respond_error(r, &r->error);
    return respond_json(r, cancel ? 202 : 200, status_document(&st), NULL);
}

static enum MHD_Result result_route(ps_request *r) {
    ps_job_doc doc;
    if (ps_jobstore_result(r->srv->store, r->job_id, &doc, &r->error)) return ps_respond_error(r, &r->error);
    return ps_respond(r, 200, doc.media_type, doc.doc, doc.len, NULL);
}

/* The answer of a finished synchronous job (its document, or its error). */
static enum MHD_Result answer_from_job(ps_request *r, ps_job *job) {
    size_t len;
    const char *media;
    const char *doc = ps_job_result(job, &len, &media);
    if (doc) return ps_respond_copy(r, 200, media, doc, len, NULL);
    ps_job_status st;
    ps_job_get_status(job, &st);
    ps_job_result_error(&st, 503, &r->error);
    return ps_respond_error(r, &r->error);
}

/* Ready when a synchronous job and an asynchronous one would be taken. */
static enum MHD_Result readyz_route(ps_request *r) {
    ps_jobs_stats st;
    if (ps_jobs_refuses(r->srv->jobs, &r->error) || ps_jobstore_ready(r->srv->store, &r->error))
        return ps_respond_error(r, &r->error);
    ps_jobs_get_stats(r->srv->jobs, &st);
    cJSON *doc = cJSON_CreateObject();
    cJSON_AddStringToObject(doc, "status", "ready");
    cJSON_AddNumberToObject(doc, "queued", (double)st.queued);
    cJSON_AddNumberToObject(doc, "capacity", (double)st.capacity);
    return respond_json(r, 200, doc, NULL);
}

static enum MHD_Result metrics_route(ps_request *r) {
    ps_jobs_stats st;
    ps_jobstore_stats shared;
    size_t len = 0;
    ps_jobs_get_stats(r->srv->jobs, &st);
    ps_jobstore_get_stats(r->srv->store, &shared);
    char *text = ps_metrics_render(&st, &shared, &len);
    if (!text) return ps_respond_problem(r, 500, NULL, "out of memory");
    return ps_respond(r, 200, "text/plain; version=0.0.4", text, len, NULL);
}

static enum MHD_Result simple_route(ps_request *r) {
    cJSON *doc;
    switch (r->route) {
    case PS_ROUTE_HEALTHZ:
        doc = cJSON_CreateObject();
        cJSON_AddStringToObject(doc, "status", "ok");
        return respond_json(r, 200, doc, NULL);
    case PS_ROUTE_READYZ:
        return readyz_route(r);
    case PS_ROUTE_VERSION:
        doc = cJSON_CreateObject();
        cJSON_AddStringToObject(doc, "pointseg", PS_VERSION);
        cJSON_AddStringToObject(doc, "libmicrohttpd", MHD_get_version());
        return respond_json(r, 200, doc, NULL);
    case PS_ROUTE_METRICS:
        return metrics_route(r);
    default:
        return ps_respond_copy(r, 200, "application/json", r->srv->openapi,
                               r->srv->openapi_len, NULL);
    }
}

static enum MHD_Result static_route(ps_request *r) {
    size_t size;
    const char *media;
    int fd = ps_static_open(r->srv->cfg->static_dir, r->path, &size, &media);
    if (fd < 0) return ps_respond_problem(r, 404, NULL, "no route or file %s", r->path);
    if (!is(r, "GET") && !is(r, "HEAD")) {
        close(fd);
        return ps_respond_problem(r, 405, allow_get, "%s is not allowed on %s", r->method, r->path);
    }
    struct MHD_Response *resp = MHD_create_response_from_fd(size, fd);
    if (!resp) {
        close(fd);
        return MHD_NO;
    }
    MHD_add_response_header(resp, MHD_HTTP_HEADER_CONTENT_TYPE, media);
    r->status = 200;
    r->bytes = size;
    enum MHD_Result rc = MHD_queue_response(r->conn, 200, resp);
    MHD_destroy_response(resp);
    return rc;
}

static const char *const *allowed_methods(ps_route route) {
    switch (route) {
    case PS_ROUTE_SEGMENT: case PS_ROUTE_JOBS: return allow_post;
    case PS_ROUTE_JOB: return allow_job;
    default: return allow_get;
    }
}

static int method_allowed(const ps_request *r) {
    switch (r->route) {
    case PS_ROUTE_SEGMENT: case PS_ROUTE_JOBS: return is(r, "POST");
    case PS_ROUTE_JOB: return is(r, "GET") || is(r, "HEAD") || is(r, "DELETE");
    case PS_ROUTE_STATIC: return 1;
    default: return is(r, "GET") || is(r, "HEAD");
    }
}

/* What a 415 adds for application/x-www-form-urlencoded. */
#define CURL_FORM_ADVICE                                                                  \
    "; curl sends this type with --data-binary unless told otherwise: add -H "            \
    "'Content-Type: application/octet-stream'"

/* What is wrong with the upload's Content-Encoding ce, or NULL for gzip,
 * identity or none.  One given twice is a list ("gzip, gzip": a body coded
 * twice) the service does not take either. */
static const char *encoding_refusal(ps_request *r, const char *ce) {
    if (!ce) return NULL;
    if (ps_admit_times_given(r, MHD_HTTP_HEADER_CONTENT_ENCODING) > 1) return "given more than once";
    return strcasecmp(ce, "gzip") && strcasecmp(ce, "identity") ? "not supported" : NULL;
}

/* Checks the headers of an upload and prepares its body. */
static enum MHD_Result begin_upload(ps_request *r) {
    const ps_config *cfg = r->srv->cfg;
    const char *ct = MHD_lookup_connection_value(r->conn, MHD_HEADER_KIND, MHD_HTTP_HEADER_CONTENT_TYPE);
    const char *ce = MHD_lookup_connection_value(r->conn, MHD_HEADER_KIND, MHD_HTTP_HEADER_CONTENT_ENCODING);
    const char *cl = MHD_lookup_connection_value(r->conn, MHD_HEADER_KIND, MHD_HTTP_HEADER_CONTENT_LENGTH);
    unsigned long long declared = cl ? strtoull(cl, NULL, 10) : 0;
    if (declared > cfg->max_body)
        return ps_respond_problem(r, 413, NULL, "Content-Length %llu is over the limit of %zu bytes",
                                  declared, cfg->max_body);
    r->media = ps_intake_media(ct);
    if (r->media == PS_MEDIA_UNSUPPORTED)
        return ps_respond_problem(r, 415, NULL, "Content-Type %s is not supported (use application/ply, "
                                  "application/octet-stream, text/plain, model/obj, chemical/x-xyz, "
                                  "application/json or multipart/form-data)%s", ct,
                                  ps_intake_is_form(ct) ? CURL_FORM_ADVICE : "");
    const char *refusal = encoding_refusal(r, ce);
    if (refusal)
        return ps_respond_problem(r, 415, NULL, "Content-Encoding %s is %s (use gzip, once)", ce, refusal);
    int gzip = ce && !strcasecmp(ce, "gzip");
    r->body = ps_body_new(r->conn, cfg->max_body, gzip ? 0 : (size_t)declared, gzip,
                          r->media == PS_MEDIA_MULTIPART, &r->error);
    if (!r->body) return ps_respond_error(r, &r->error);
    return MHD_YES;
}

enum MHD_Result ps_routes_begin(ps_request *r) {
    if (is(r, "OPTIONS")) return ps_respond_preflight(r, allowed_methods(r->route)[1]);
    if (!authorized(r)) {
        static const char *const challenge[] = {MHD_HTTP_HEADER_WWW_AUTHENTICATE, "Bearer", NULL};
        return ps_respond_problem(r, 401, challenge, "a valid bearer token is required");
    }
    if (!method_allowed(r))
        return ps_respond_problem(r, 405, allowed_methods(r->route), "%s is not allowed on %s",
                                  r->method, ps_route_name(r->route));
    switch (r->route) {
    case PS_ROUTE_SEGMENT: case PS_ROUTE_JOBS: return begin_upload(r);
    case PS_ROUTE_JOB: return job_route(r);
    case PS_ROUTE_JOB_RESULT: return result_route(r);
    case PS_ROUTE_STATIC: return static_route(r);
    default: return simple_route(r);
    }
}

typedef struct query_params {
    ps_text_param items[PS_MAX_QUERY_PARAMS];
    size_t n;
    int overflow;
    int nul;      /* a name or value holds a NUL byte (%00) */
} query_params;

static enum MHD_Result collect_query(void *cls, enum MHD_ValueKind kind, const char *key, size_t key_size,
                                     const char *value, size_t value_size) {
    query_params *q = cls;
    (void)kind;
    if (!key_size && !value) return MHD_YES; /* an empty piece, "?&k=7" or "k=7&&output=ply" */
    if (strlen(key) != key_size || (value && strlen(value) != value_size)) {
        q->nul = 1;
        return MHD_NO;
    }
    if (q->n == PS_MAX_QUERY_PARAMS) {
        q->overflow = 1;
        return MHD_NO;
    }
    q->items[q->n++] = (ps_text_param){key, value};
    return MHD_YES;
}

/* Multipart fields, then the query string, into *q; then the parameters. */
static int gather_params(ps_request *r, const ps_pointset *ps, query_params *q, const char **accept,
                         ps_request_params *rp) {
    size_t n_fields;
    const ps_body_field *fields = ps_body_fields(r->body, &n_fields);
    *q = (query_params){.n = 0};
    for (size_t i = 0; i < n_fields && q->n < PS_MAX_QUERY_PARAMS; i++)
        q->items[q->n++] = (ps_text_param){fields[i].name, fields[i].value};
    MHD_get_connection_values_n(r->conn, MHD_GET_ARGUMENT_KIND, collect_query, q);
    if (q->nul) return ps_api_fail(&r->error, 400, "a query parameter holds a NUL byte (%%00)");
    if (q->overflow) return ps_api_fail(&r->error, 400, "more than %d parameters", PS_MAX_QUERY_PARAMS);
    *accept = MHD_lookup_connection_value(r->conn, MHD_HEADER_KIND, MHD_HTTP_HEADER_ACCEPT);
    return ps_intake_params(ps, *accept, q->items, q->n, rp, &r->error);
}

/* Resumes the request; a client that shut down its write side is answered
 * first, on its socket (direct_answer.h). */
static void job_ended(void *user) {
    ps_request *r = user;
    ps_server *s = r->srv;
    pthread_mutex_lock(&s->lock);
    if (r->waiting) {
        if (r->prev) r->prev->next = r->next;
        else s->waiting = r->next;
        if (r->next) r->next->prev = r->prev;
        r->waiting = 0;
    }
    r->answer_direct = r->probed || ps_peer_done_sending(ps_connection_fd(r->conn));
    pthread_mutex_unlock(&s->lock);
    if (r->answer_direct && r->job) answer_from_job(r, r->job);
    else if (r->answer_direct) ps_respond_error(r, &r->error);
    MHD_resume_connection(r->conn);
}

/* Suspends the connection and queues the job; job_ended resumes it. */
static enum MHD_Result wait_for_job(ps_request *r, ps_pointset *ps, const ps_request_params *rp) {
    ps_server *s = r->srv;
    pthread_mutex_lock(&s->lock);
    r->prev = NULL;
    r->next = s->waiting;
    if (s->waiting) s->waiting->prev = r;
    s->waiting = r;
    r->waiting = 1;
    pthread_mutex_unlock(&s->lock);
    r->suspended = 1;
    MHD_suspend_connection(r->conn);
    if (ps_jobs_submit(s->jobs, ps, rp, job_ended, r, &r->job, &r->error)) {
        r->failed = 1;
        job_ended(r);
        return MHD_YES;
    }
    pthread_mutex_lock(&s->lock);
    snprintf(r->job_id, sizeof r->job_id, "%s", ps_job_id(r->job));
    pthread_mutex_unlock(&s->lock);
    return MHD_YES;
}

static enum MHD_Result submit_async(ps_request *r, const ps_job_upload *up) {
    if (ps_jobstore_submit(r->srv->store, up, r->job_id, sizeof r->job_id, &r->error))
        return ps_respond_error(r, &r->error);
    char location[128];
    snprintf(location, sizeof location, "/jobs/%s", r->job_id);
    const char *const headers[] = {MHD_HTTP_HEADER_LOCATION, location, NULL};
    cJSON *doc = cJSON_CreateObject();
    cJSON_AddStringToObject(doc, "id", r->job_id);
    cJSON_AddStringToObject(doc, "status", "queued");
    return respond_json(r, 202, doc, headers);
}

enum MHD_Result ps_routes_upload_done(ps_request *r) {
    ps_pointset ps;
    ps_request_params rp;
    query_params q;
    const char *accept = NULL;
    size_t len;
    if (r->failed || ps_body_finish(r->body, &r->error)) return ps_respond_error(r, &r->error);
    const char *bytes = ps_body_data(r->body, &len);
    if (ps_intake_decode(bytes, len, r->media, r->srv->cfg->max_points, &ps, &r->error))
        return ps_respond_error(r, &r->error);
    if (gather_params(r, &ps, &q, &accept, &rp) ||
        ps_intake_check_memory(&ps, &rp, r->srv->cfg->max_memory, &r->error)) {
        ps_pointset_free(&ps);
        return ps_respond_error(r, &r->error);
    }
    if (r->route == PS_ROUTE_SEGMENT) {
        ps_body_free(r->body);
        r->body = NULL;
        return wait_for_job(r, &ps, &rp);
    }
    ps_job_upload up = {&ps, &rp, bytes, len, r->media, accept, q.items, q.n};
    enum MHD_Result rc = submit_async(r, &up);
    ps_pointset_free(&ps);
    return rc;
}

enum MHD_Result ps_routes_resumed(ps_request *r) {
    if (!r->job) return ps_respond_error(r, &r->error);
    return answer_from_job(r, r->job);
}
