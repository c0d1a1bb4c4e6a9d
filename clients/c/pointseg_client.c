/* pointseg_client.c: the libcurl client of pointsegd.  URLs and header
 * lines are sized to fit: a long query, token or job id goes out whole,
 * and an answer's header lines come in whole, up to PS_CLIENT_HEAD_MAX
 * bytes in all. */
#include "pointseg_client.h"

#include <cJSON.h>
#include <curl/curl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

int ps_client_global_init(void) {
    return curl_global_init(CURL_GLOBAL_DEFAULT) == CURLE_OK ? 0 : -1;
}

/* An empty response: no body, no header lines, every header value "". */
static void response_clear(ps_client_response *r) {
    memset(r, 0, sizeof *r);
    r->content_type = r->location = r->retry_after = r->allow = "";
}

/* Appends add bytes of data to the NUL-terminated *text of *len bytes;
 * -1 (and "out of memory" in r->error) when out of memory. */
static int append(ps_client_response *r, char **text, size_t *len, const char *data, size_t add) {
    char *grown = realloc(*text, *len + add + 1);
    if (!grown) return snprintf(r->error, sizeof r->error, "out of memory"), -1;
    memcpy(grown + *len, data, add);
    *text = grown;
    *len += add;
    grown[*len] = 0;
    return 0;
}

static size_t on_body(char *data, size_t size, size_t n, void *user) {
    ps_client_response *r = user;
    return append(r, &r->body, &r->len, data, size * n) ? 0 : size * n;
}

static size_t on_header(char *line, size_t size, size_t n, void *user) {
    ps_client_response *r = user;
    size_t len = size * n;
    if (len > PS_CLIENT_HEAD_MAX - r->head_len) {
        snprintf(r->error, sizeof r->error, "the answer's header lines pass %d bytes",
                 PS_CLIENT_HEAD_MAX);
        return 0;
    }
    return append(r, &r->head, &r->head_len, line, len) ? 0 : len;
}

/* When header line `line` (len bytes) is named `name`, its value, cut out
 * in place (NUL-terminated where its trailing blanks were), into *out. */
static void take_header(char *line, size_t len, const char *name, const char **out) {
    size_t n = strlen(name);
    if (len <= n + 1 || strncasecmp(line, name, n) || line[n] != ':') return;
    char *v = line + n + 1;
    size_t vlen = len - n - 1;
    while (vlen && (*v == ' ' || *v == '\t')) v++, vlen--;
    while (vlen && (v[vlen - 1] == '\r' || v[vlen - 1] == '\n' || v[vlen - 1] == ' ')) vlen--;
    v[vlen] = 0;
    *out = v;
}

/* Points r's header values at theirs in r->head (a name given twice: its
 * last line). */
static void point_headers(ps_client_response *r) {
    char *line = r->head;
    while (line && *line) {
        char *end = strchr(line, '\n');
        char *next = end ? end + 1 : line + strlen(line);
        size_t len = (size_t)(next - line);
        take_header(line, len, "Content-Type", &r->content_type);
        take_header(line, len, "Location", &r->location);
        take_header(line, len, "Retry-After", &r->retry_after);
        take_header(line, len, "Allow", &r->allow);
        line = next;
    }
}

/* The formatted text, malloc'ed to fit; NULL when out of memory. */
static char *text_of(const char *format, ...) {
    va_list args;
    va_start(args, format);
    int len = vsnprintf(NULL, 0, format, args);
    va_end(args);
    char *text = len < 0 ? NULL : malloc((size_t)len + 1);
    if (!text) return NULL;
    va_start(args, format);
    vsnprintf(text, (size_t)len + 1, format, args);
    va_end(args);
    return text;
}

/* Appends line (NULL: out of memory) to *h and frees it; -1 when out of
 * memory. */
static int append_line(struct curl_slist **h, char *line) {
    struct curl_slist *grown = line ? curl_slist_append(*h, line) : NULL;
    free(line);
    if (!grown) return -1;
    *h = grown;
    return 0;
}

/* The request's header lines into *out; -1 (and none) when out of memory. */
static int build_headers(const ps_client *c, const ps_client_body *body,
                         const char *const *extra, struct curl_slist **out) {
    struct curl_slist *h = NULL;
    int rc = 0;
    if (body) {
        const char *type = body->content_type ? body->content_type : "application/octet-stream";
        rc |= append_line(&h, text_of("Content-Type: %s", type));
        if (body->content_encoding)
            rc |= append_line(&h, text_of("Content-Encoding: %s", body->content_encoding));
    }
    if (c->token) rc |= append_line(&h, text_of("Authorization: Bearer %s", c->token));
    rc |= append_line(&h, text_of("Expect:"));
    for (; extra && *extra; extra++) rc |= append_line(&h, text_of("%s", *extra));
    if (rc) curl_slist_free_all(h);
    *out = rc ? NULL : h;
    return rc;
}

int ps_client_request(const ps_client *c, const char *method, const char *path,
                      const ps_client_body *body, const char *const *headers, ps_client_response *out) {
    response_clear(out);
    char *url = text_of("%s%s", c->base_url, path);
    struct curl_slist *h = NULL;
    CURL *curl = url && build_headers(c, body, headers, &h) == 0 ? curl_easy_init() : NULL;
    if (!curl) {
        curl_slist_free_all(h);
        free(url);
        return snprintf(out->error, sizeof out->error, "out of memory"), -1;
    }
    curl_easy_setopt(curl, CURLOPT_URL, url);
    curl_easy_setopt(curl, CURLOPT_CUSTOMREQUEST, method);
    curl_easy_setopt(curl, CURLOPT_NOSIGNAL, 1L);
    curl_easy_setopt(curl, CURLOPT_HTTPHEADER, h);
    curl_easy_setopt(curl, CURLOPT_WRITEFUNCTION, on_body);
    curl_easy_setopt(curl, CURLOPT_WRITEDATA, out);
    curl_easy_setopt(curl, CURLOPT_HEADERFUNCTION, on_header);
    curl_easy_setopt(curl, CURLOPT_HEADERDATA, out);
    if (!strcmp(method, "HEAD")) curl_easy_setopt(curl, CURLOPT_NOBODY, 1L);
    if (c->timeout_ms) curl_easy_setopt(curl, CURLOPT_TIMEOUT_MS, c->timeout_ms);
    if (body) {
        curl_easy_setopt(curl, CURLOPT_POSTFIELDS, body->data);
        curl_easy_setopt(curl, CURLOPT_POSTFIELDSIZE_LARGE, (curl_off_t)body->len);
    }
    CURLcode rc = curl_easy_perform(curl);
    if (rc == CURLE_OK) curl_easy_getinfo(curl, CURLINFO_RESPONSE_CODE, &out->status);
    else if (!out->error[0]) snprintf(out->error, sizeof out->error, "%s", curl_easy_strerror(rc));
    point_headers(out);
    curl_slist_free_all(h);
    curl_easy_cleanup(curl);
    free(url);
    return rc == CURLE_OK ? 0 : -1;
}

/* ps_client_request on path (malloc'ed, freed here; NULL: out of memory). */
static int request_path(const ps_client *c, const char *method, char *path,
                        const ps_client_body *body, ps_client_response *out) {
    if (!path) {
        response_clear(out);
        return snprintf(out->error, sizeof out->error, "out of memory"), -1;
    }
    int rc = ps_client_request(c, method, path, body, NULL, out);
    free(path);
    return rc;
}

static char *with_query(const char *path, const char *query) {
    return text_of("%s%s%s", path, query && *query ? "?" : "", query ? query : "");
}

int ps_client_segment(const ps_client *c, const ps_client_body *body, const char *query,
                      ps_client_response *out) {
    return request_path(c, "POST", with_query("/segment", query), body, out);
}

/* The string member `name` of a JSON object text into out. */
static int json_string(const char *text, const char *name, char *out, size_t cap) {
    cJSON *doc = text ? cJSON_Parse(text) : NULL;
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(doc, name);
    int ok = cJSON_IsString(v) && strlen(v->valuestring) < cap;
    if (ok) memcpy(out, v->valuestring, strlen(v->valuestring) + 1);
    cJSON_Delete(doc);
    return ok ? 0 : -1;
}

int ps_client_submit(const ps_client *c, const ps_client_body *body, const char *query,
                     char *id, size_t cap, ps_client_response *out) {
    if (request_path(c, "POST", with_query("/jobs", query), body, out)) return -1;
    if (out->status != 202) return 0;
    return json_string(out->body, "id", id, cap);
}

static int job_request(const ps_client *c, const char *method, const char *id, const char *suffix,
                       ps_client_response *out) {
    return request_path(c, method, text_of("/jobs/%s%s", id, suffix), NULL, out);
}

int ps_client_poll(const ps_client *c, const char *id, ps_client_response *out) {
    return job_request(c, "GET", id, "", out);
}

int ps_client_result(const ps_client *c, const char *id, ps_client_response *out) {
    return job_request(c, "GET", id, "/result", out);
}

int ps_client_cancel(const ps_client *c, const char *id, ps_client_response *out) {
    return job_request(c, "DELETE", id, "", out);
}

int ps_client_job_is_final(const char *state) {
    return !strcmp(state, "done") || !strcmp(state, "failed") || !strcmp(state, "cancelled");
}

static long ms_since(const struct timespec *start) {
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (long)(now.tv_sec - start->tv_sec) * 1000L + (now.tv_nsec - start->tv_nsec) / 1000000L;
}

int ps_client_wait(const ps_client *c, const char *id, long timeout_ms, char *state, size_t cap) {
    struct timespec pause = {0, 20 * 1000 * 1000}, start;
    clock_gettime(CLOCK_MONOTONIC, &start);
    for (;;) {
        /* Each poll gets at most the time left, so a slow answer cannot
         * carry the wait past timeout_ms. */
        long left = timeout_ms - ms_since(&start);
        ps_client polling = *c;
        if (!polling.timeout_ms || polling.timeout_ms > left) polling.timeout_ms = left > 1 ? left : 1;
        ps_client_response r;
        int rc = ps_client_poll(&polling, id, &r);
        int got = rc == 0 && r.status == 200 && json_string(r.body, "status", state, cap) == 0;
        ps_client_response_free(&r);
        if (got && ps_client_job_is_final(state)) return 0;
        if (ms_since(&start) >= timeout_ms) return -1;
        nanosleep(&pause, NULL);
    }
}

void ps_client_response_free(ps_client_response *r) {
    free(r->body);
    free(r->head);
    r->body = r->head = NULL;
    r->len = r->head_len = 0;
    r->content_type = r->location = r->retry_after = r->allow = "";
}
