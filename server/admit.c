/* admit.c: refusing malformed or unwelcome request heads (admit.h). */
#include "admit.h"

#include "respond.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>

int ps_admit_cut_query(const char *uri) {
    char *query = strchr(uri, '?');
    size_t params = 1;
    if (!query) return 0;
    for (const char *p = query; *p; p++) params += *p == '&';
    if (params <= PS_MAX_QUERY_PARAMS) return 0;
    query[1] = 0; /* libmicrohttpd's own read buffer, which it also cuts in place */
    return 1;
}

int ps_admit_path_has_nul(const char *uri) {
    for (const char *p = uri; *p && *p != '?'; p++)
        if (p[0] == '%' && p[1] == '0' && p[2] == '0') return 1;
    return 0;
}

typedef struct header_count {
    const char *name;
    const char *first;
    int n, differ;
} header_count;

static enum MHD_Result count_header(void *cls, enum MHD_ValueKind kind, const char *key, const char *value) {
    header_count *h = cls;
    (void)kind;
    if (strcasecmp(key, h->name)) return MHD_YES;
    if (h->n++ == 0) h->first = value;
    else if (strcmp(h->first, value ? value : "")) h->differ = 1;
    return MHD_YES;
}

/* The lines of the request's head that give header name. */
static header_count lines_giving(ps_request *r, const char *name) {
    header_count h = {name, "", 0, 0};
    MHD_get_connection_values(r->conn, MHD_HEADER_KIND, count_header, &h);
    return h;
}

int ps_admit_times_given(ps_request *r, const char *name) {
    return lines_giving(r, name).n;
}

static int conflicting_lengths(ps_request *r) {
    return lines_giving(r, MHD_HTTP_HEADER_CONTENT_LENGTH).differ;
}

static int is_health_route(ps_route route) {
    return route == PS_ROUTE_HEALTHZ || route == PS_ROUTE_READYZ || route == PS_ROUTE_METRICS;
}

static const char *header(ps_request *r, const char *name) {
    return MHD_lookup_connection_value(r->conn, MHD_HEADER_KIND, name);
}

int ps_admit_check(ps_request *r) {
    const char *te = header(r, MHD_HTTP_HEADER_TRANSFER_ENCODING);
    if (r->path_too_long)
        return ps_respond_problem(r, 414, NULL, "the URL path is longer than %zu bytes", sizeof r->path - 1);
    if (r->path_has_nul)
        return ps_respond_problem(r, 400, NULL, "the URL path holds an encoded NUL byte (%%00)");
    if (r->query_cut)
        return ps_respond_problem(r, 400, NULL, "more than %d query parameters", PS_MAX_QUERY_PARAMS);
    if (r->http11 && !header(r, MHD_HTTP_HEADER_HOST))
        return ps_respond_problem(r, 400, NULL, "an HTTP/1.1 request needs a Host header");
    if (conflicting_lengths(r))
        return ps_respond_problem(r, 400, NULL, "conflicting Content-Length headers");
    if (te && strcasecmp(te, "chunked"))
        return ps_respond_problem(r, 501, NULL, "Transfer-Encoding %.100s is not supported (use chunked, "
                                  "or Content-Encoding: gzip)", te);
    if (te && header(r, MHD_HTTP_HEADER_CONTENT_LENGTH))
        return ps_respond_problem(r, 400, NULL, "both Transfer-Encoding and Content-Length: the body's "
                                  "length is ambiguous (send one of them)");
    if (ps_guard_conn_in_health_room(r->guard_conn) && !is_health_route(r->route))
        return ps_respond_problem(r, 503, ps_retry_after_header,
                                  "too many connections (%d); only health checks are served",
                                  r->srv->cfg->max_connections);
    return -1;
}

int ps_admit_has_body(ps_request *r, unsigned long long *declared) {
    const char *cl = header(r, MHD_HTTP_HEADER_CONTENT_LENGTH);
    *declared = cl ? strtoull(cl, NULL, 10) : 0;
    return *declared > 0 || header(r, MHD_HTTP_HEADER_TRANSFER_ENCODING) != NULL;
}
