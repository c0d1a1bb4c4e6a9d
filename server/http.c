/* http.c: libmicrohttpd start-up and shut-down, the request callbacks
 * (first call, upload pieces, resume), the request log, and the watcher
 * that cuts slow connections (guard.h) and cancels the job of a client
 * that went away. */
#include "http.h"

#include "admit.h"
#include "deadline.h"
#include "direct_answer.h"
#include "openapi.h"
#include "request.h"
#include "respond.h"
#include "routes.h"

#include <arpa/inet.h>
#include <errno.h>
#include <microhttpd.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#define WATCH_PERIOD_MS 100
#define IO_THREADS 4
#define HEALTH_ROOM 8                  /* connections over --max-connections, for health checks */
#define DRAIN_LIMIT (1u << 20)         /* body bytes read to keep the connection after an error */
#define PROCESSING "HTTP/1.1 102 Processing\r\n\r\n"

struct ps_http {
    ps_server srv;
    int port;
};

static ps_request *request_new(ps_server *s, struct MHD_Connection *conn) {
    ps_request *r = calloc(1, sizeof *r);
    if (!r) return NULL;
    r->srv = s;
    r->conn = conn;
    r->t0 = ps_monotonic_seconds();
    r->route = PS_ROUTE_OTHER;
    pthread_mutex_lock(&s->lock);
    s->in_flight++;
    pthread_mutex_unlock(&s->lock);
    return r;
}

/* The request line is in: the request starts here, before libmicrohttpd
 * splits the query string. */
static void *on_uri(void *cls, const char *uri, struct MHD_Connection *conn) {
    ps_request *r = request_new(cls, conn);
    if (r) {
        r->path_has_nul = ps_admit_path_has_nul(uri);
        r->query_cut = ps_admit_cut_query(uri);
    }
    return r;
}

static ps_guard_conn *guard_conn_of(struct MHD_Connection *conn) {
    const union MHD_ConnectionInfo *info = MHD_get_connection_info(conn, MHD_CONNECTION_INFO_SOCKET_CONTEXT);
    return info ? info->socket_context : NULL;
}

/* 1 when the client waits for a 100 Continue before sending its body. */
static int expects_continue(ps_request *r) {
    const char *expect = MHD_lookup_connection_value(r->conn, MHD_HEADER_KIND, MHD_HTTP_HEADER_EXPECT);
    return r->http11 && expect && !strcasecmp(expect, "100-continue");
}

/* The head is in.  A request without a body is answered on the next call:
 * libmicrohttpd closes the connection after an answer queued on the first
 * one.  Early errors on a body of up to DRAIN_LIMIT bytes wait until it is
 * read, for the same reason, unless the client waits for a 100 Continue:
 * it gets the error instead of an invitation to send the body in vain. */
static enum MHD_Result head_received(ps_request *r, const char *url, const char *method, const char *version) {
    unsigned long long declared;
    r->seen = 1;
    snprintf(r->method, sizeof r->method, "%s", method);
    snprintf(r->path, sizeof r->path, "%s", url);
    r->path_too_long = strlen(url) >= sizeof r->path;
    r->http11 = version && !strcmp(version, MHD_HTTP_VERSION_1_1);
    r->guard_conn = guard_conn_of(r->conn);
    ps_guard_request_begun(r->srv->guard, r->guard_conn);
    ps_routes_match(r);
    int refused = ps_admit_check(r);
    if (refused >= 0) return (enum MHD_Result)refused;
    if (!ps_admit_has_body(r, &declared)) return MHD_YES;
    r->routed = 1;
    r->defer_answer = declared > 0 && declared <= DRAIN_LIMIT && !expects_continue(r);
    enum MHD_Result rc = ps_routes_begin(r);
    r->defer_answer = 0;
    return rc;
}

static enum MHD_Result queue_pending(ps_request *r) {
    enum MHD_Result rc = MHD_queue_response(r->conn, (unsigned)r->status, r->pending);
    MHD_destroy_response(r->pending);
    r->pending = NULL;
    return rc;
}

/* A piece of the body.  A body that failed (over --max-body, bad gzip or
 * multipart) is read on to its end, so that the connection stays open,
 * for DRAIN_LIMIT bytes at most: a longer one, or an endless chunked one,
 * gets its answer on the socket at once and the connection closes (no
 * answer may be queued while a body is still coming). */
static enum MHD_Result body_piece(ps_request *r, const char *upload, size_t size) {
    ps_guard_received(r->srv->guard, r->guard_conn, size);
    if (r->status || !r->body) return MHD_YES;
    if (r->failed) r->read_after_failure += size;
    else if (ps_body_feed(r->body, upload, size, &r->error)) r->failed = 1;
    if (r->read_after_failure <= DRAIN_LIMIT) return MHD_YES;
    r->answer_direct = 1;
    return ps_respond_error(r, &r->error);
}

static enum MHD_Result on_request(void *cls, struct MHD_Connection *conn, const char *url,
                                  const char *method, const char *version, const char *upload,
                                  size_t *upload_size, void **state) {
    ps_request *r = *state;
    if (!r) {
        r = request_new(cls, conn);
        if (!r) return MHD_NO;
        *state = r;
    }
    if (!r->seen) return head_received(r, url, method, version);
    if (*upload_size) {
        size_t size = *upload_size;
        *upload_size = 0;
        return body_piece(r, upload, size);
    }
    ps_guard_upload_done(r->srv->guard, r->guard_conn);
    if (r->pending) return queue_pending(r);
    if (!r->routed) {
        r->routed = 1;
        return ps_routes_begin(r);
    }
    if (r->answer_direct) return MHD_NO; /* answered on the socket: close */
    if (r->status) return MHD_YES;
    if (r->suspended) return ps_routes_resumed(r);
    if (r->body) return ps_routes_upload_done(r);
    return ps_respond_problem(r, 500, NULL, "request in an unexpected state");
}

/* The status a request is logged and counted with: 499 when its client
 * went away unanswered: before any answer, before a deferred one went out,
 * while its job ran (the watcher cancelled it: its 503 reached no one), or
 * while an answer was on its way. */
static int status_seen(const ps_request *r, enum MHD_RequestTerminationCode toe) {
    if (!r->status || r->pending || r->cancel_sent) return 499;
    if (toe != MHD_REQUEST_TERMINATED_COMPLETED_OK && r->status < 400 && !r->sent_direct) return 499;
    return r->status;
}

static void on_completed(void *cls, struct MHD_Connection *conn, void **state,
                         enum MHD_RequestTerminationCode toe) {
    ps_server *s = cls;
    ps_request *r = *state;
    (void)conn;
    if (!r) return;
    double seconds = ps_monotonic_seconds() - r->t0;
    int status = status_seen(r, toe);
    ps_metrics_observe(r->route, status, seconds);
    if (!s->cfg->quiet)
        fprintf(stderr, "%s %s %d %zu %.1fms%s%s\n", r->method, r->path, status, r->bytes,
                seconds * 1e3, r->job_id[0] ? " job=" : "", r->job_id);
    if (r->pending) MHD_destroy_response(r->pending);
    ps_guard_answered(s->guard, r->guard_conn);
    ps_job_release(r->job);
    ps_body_free(r->body);
    free(r);
    *state = NULL;
    pthread_mutex_lock(&s->lock);
    s->in_flight--;
    pthread_cond_broadcast(&s->changed);
    pthread_mutex_unlock(&s->lock);
}

/* 1 when the socket has a pending error (a reset after the peer's FIN is
 * only seen there: recv keeps answering the FIN). */
static int socket_failed(int fd) {
    int error = 0;
    socklen_t len = sizeof error;
    return getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &len) == 0 && error != 0;
}

/* 1 when the client of a suspended request is gone.  A read EOF alone is
 * no proof: a client may shut down its write side and wait for the answer.
 * So on EOF an HTTP/1.1 client gets an interim 102 (which clients skip);
 * a peer that closed for good answers it with a reset, seen as a socket
 * error on a later call.  The caller holds the server lock. */
static int client_gone(ps_request *r) {
    char c;
    int fd = ps_connection_fd(r->conn);
    if (fd < 0) return 0;
    ssize_t n = recv(fd, &c, 1, MSG_PEEK | MSG_DONTWAIT);
    if (n > 0 || (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR))) return 0;
    if (n < 0) return 1;
    if (!r->http11) return 0;
    if (r->probed) return socket_failed(fd);
    r->probed = 1;
    return send(fd, PROCESSING, sizeof PROCESSING - 1, MSG_NOSIGNAL | MSG_DONTWAIT) != sizeof PROCESSING - 1;
}

static void cancel_abandoned(ps_server *s) {
    char ids[64][96];
    size_t n = 0;
    pthread_mutex_lock(&s->lock);
    for (ps_request *r = s->waiting; r && n < 64; r = r->next) {
        if (r->cancel_sent || !r->job_id[0] || !client_gone(r)) continue;
        r->cancel_sent = 1;
        memcpy(ids[n++], r->job_id, sizeof ids[0]);
    }
    pthread_mutex_unlock(&s->lock);
    for (size_t i = 0; i < n; i++) {
        ps_job *job = ps_jobs_find(s->jobs, ids[i]);
        if (job) ps_job_cancel(job);
        ps_job_release(job);
    }
}

static void *watch_main(void *arg) {
    ps_server *s = arg;
    pthread_mutex_lock(&s->lock);
    while (!s->stop_watch) {
        struct timespec ts = ps_deadline_in_ms(WATCH_PERIOD_MS);
        pthread_cond_timedwait(&s->changed, &s->lock, &ts);
        if (s->stop_watch) break;
        pthread_mutex_unlock(&s->lock);
        ps_metrics_connections_cut(ps_guard_sweep(s->guard));
        cancel_abandoned(s);
        pthread_mutex_lock(&s->lock);
    }
    pthread_mutex_unlock(&s->lock);
    return NULL;
}

static void on_connection(void *cls, struct MHD_Connection *conn, void **socket_context,
                          enum MHD_ConnectionNotificationCode code) {
    ps_server *s = cls;
    if (code == MHD_CONNECTION_NOTIFY_STARTED) {
        int fd = ps_connection_fd(conn);
        *socket_context = fd >= 0 ? ps_guard_opened(s->guard, fd) : NULL;
    } else {
        ps_guard_closed(s->guard, *socket_context);
        *socket_context = NULL;
    }
}

/* poll(), not epoll: with epoll worker threads, libmicrohttpd's
 * MHD_quiesce_daemon (SIGTERM's first step) races with the workers over
 * removing the listening socket from their epoll sets, and the loser
 * aborts the process (about 1 stop in 300 under incoming connections). */
static struct MHD_Daemon *start_daemon(ps_http *h, const struct sockaddr_in *addr) {
    const ps_config *cfg = h->srv.cfg;
    unsigned flags = MHD_USE_POLL_INTERNAL_THREAD | MHD_ALLOW_SUSPEND_RESUME | MHD_USE_ERROR_LOG;
    unsigned pool = IO_THREADS;
    return MHD_start_daemon(flags, (uint16_t)cfg->port, NULL, NULL, on_request, &h->srv,
                            MHD_OPTION_SOCK_ADDR, addr,
                            MHD_OPTION_THREAD_POOL_SIZE, pool,
                            MHD_OPTION_URI_LOG_CALLBACK, on_uri, &h->srv,
                            MHD_OPTION_NOTIFY_COMPLETED, on_completed, &h->srv,
                            MHD_OPTION_NOTIFY_CONNECTION, on_connection, &h->srv,
                            MHD_OPTION_CONNECTION_LIMIT, (unsigned)(cfg->max_connections + HEALTH_ROOM),
                            MHD_OPTION_PER_IP_CONNECTION_LIMIT, (unsigned)cfg->max_connections_per_ip,
                            MHD_OPTION_CONNECTION_TIMEOUT, (unsigned)120,
                            MHD_OPTION_END);
}

ps_http *ps_http_start(const ps_config *cfg, ps_jobs *jobs, ps_jobstore *store, char *why,
                       size_t why_cap) {
    struct sockaddr_in addr = {.sin_family = AF_INET, .sin_port = htons((uint16_t)cfg->port)};
    if (inet_pton(AF_INET, cfg->bind, &addr.sin_addr) != 1) {
        snprintf(why, why_cap, "--bind %s is not an IPv4 address", cfg->bind);
        return NULL;
    }
    ps_http *h = calloc(1, sizeof *h);
    if (!h) return snprintf(why, why_cap, "out of memory"), NULL;
    h->srv.cfg = cfg;
    h->srv.jobs = jobs;
    h->srv.store = store;
    pthread_mutex_init(&h->srv.lock, NULL);
    pthread_cond_init(&h->srv.changed, NULL);
    h->srv.openapi = ps_openapi_json(&h->srv.openapi_len);
    h->srv.guard = ps_guard_new(cfg->max_connections, cfg->header_timeout, (double)cfg->min_upload_rate);
    if (!h->srv.openapi || !h->srv.guard) {
        snprintf(why, why_cap, "out of memory");
        ps_http_stop(h);
        return NULL;
    }
    h->srv.mhd = start_daemon(h, &addr);
    if (!h->srv.mhd) {
        snprintf(why, why_cap, "cannot listen on %s:%d", cfg->bind, cfg->port);
        ps_http_stop(h);
        return NULL;
    }
    const union MHD_DaemonInfo *info = MHD_get_daemon_info(h->srv.mhd, MHD_DAEMON_INFO_BIND_PORT);
    h->port = info ? info->port : cfg->port;
    h->srv.has_watcher = pthread_create(&h->srv.watcher, NULL, watch_main, &h->srv) == 0;
    return h;
}

int ps_http_port(ps_http *h) { return h->port; }

void ps_http_quiesce(ps_http *h) {
    MHD_socket fd = MHD_quiesce_daemon(h->srv.mhd);
    if (fd != MHD_INVALID_SOCKET) close(fd);
}

void ps_http_wait_idle(ps_http *h, double seconds) {
    double deadline = ps_monotonic_seconds() + seconds;
    pthread_mutex_lock(&h->srv.lock);
    while (h->srv.in_flight && ps_monotonic_seconds() < deadline) {
        struct timespec ts = ps_deadline_in_ms(50);
        pthread_cond_timedwait(&h->srv.changed, &h->srv.lock, &ts);
    }
    pthread_mutex_unlock(&h->srv.lock);
}

void ps_http_stop(ps_http *h) {
    if (!h) return;
    if (h->srv.has_watcher) {
        pthread_mutex_lock(&h->srv.lock);
        h->srv.stop_watch = 1;
        pthread_cond_broadcast(&h->srv.changed);
        pthread_mutex_unlock(&h->srv.lock);
        pthread_join(h->srv.watcher, NULL);
    }
    if (h->srv.mhd) MHD_stop_daemon(h->srv.mhd);
    ps_guard_free(h->srv.guard);
    pthread_cond_destroy(&h->srv.changed);
    pthread_mutex_destroy(&h->srv.lock);
    free(h->srv.openapi);
    free(h);
}
