/* http.c: libmicrohttpd start-up and shut-down, the request callbacks
 * (first call, upload pieces, resume), the request log, and the watcher
 * that cancels the job of a client that went away. */
#include "http.h"

#include "deadline.h"
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
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#define WATCH_PERIOD_MS 100
#define IO_THREADS 4

struct ps_http {
    ps_server srv;
    int port;
};

static double monotonic_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

static ps_request *request_new(ps_server *s, struct MHD_Connection *conn, const char *url,
                               const char *method) {
    ps_request *r = calloc(1, sizeof *r);
    if (!r) return NULL;
    r->srv = s;
    r->conn = conn;
    r->t0 = monotonic_seconds();
    snprintf(r->method, sizeof r->method, "%s", method);
    snprintf(r->path, sizeof r->path, "%s", url);
    r->route = PS_ROUTE_OTHER;
    pthread_mutex_lock(&s->lock);
    s->in_flight++;
    pthread_mutex_unlock(&s->lock);
    return r;
}

static enum MHD_Result on_request(void *cls, struct MHD_Connection *conn, const char *url,
                                  const char *method, const char *version, const char *upload,
                                  size_t *upload_size, void **state) {
    ps_request *r = *state;
    (void)version;
    if (!r) {
        r = request_new(cls, conn, url, method);
        if (!r) return MHD_NO;
        *state = r;
        return ps_routes_begin(r);
    }
    if (*upload_size) {
        if (!r->status && r->body && !r->failed && ps_body_feed(r->body, upload, *upload_size, &r->error))
            r->failed = 1;
        *upload_size = 0;
        return MHD_YES;
    }
    if (r->status) return MHD_YES;
    if (r->suspended) return ps_routes_resumed(r);
    if (r->body) return ps_routes_upload_done(r);
    return ps_respond_problem(r, 500, NULL, "request in an unexpected state");
}

static void on_completed(void *cls, struct MHD_Connection *conn, void **state,
                         enum MHD_RequestTerminationCode toe) {
    ps_server *s = cls;
    ps_request *r = *state;
    (void)conn;
    if (!r) return;
    double seconds = monotonic_seconds() - r->t0;
    int status = r->status ? r->status : 499; /* answered nothing: the client went away */
    if (toe != MHD_REQUEST_TERMINATED_COMPLETED_OK && status < 400) status = 499;
    ps_metrics_observe(r->route, status, seconds);
    if (!s->cfg->quiet)
        fprintf(stderr, "%s %s %d %zu %.1fms%s%s\n", r->method, r->path, status, r->bytes,
                seconds * 1e3, r->job_id[0] ? " job=" : "", r->job_id);
    ps_job_release(r->job);
    ps_body_free(r->body);
    free(r);
    *state = NULL;
    pthread_mutex_lock(&s->lock);
    s->in_flight--;
    pthread_cond_broadcast(&s->changed);
    pthread_mutex_unlock(&s->lock);
}

/* 1 when the peer of a suspended connection closed it. */
static int peer_closed(struct MHD_Connection *conn) {
    const union MHD_ConnectionInfo *info = MHD_get_connection_info(conn, MHD_CONNECTION_INFO_CONNECTION_FD);
    char c;
    if (!info) return 0;
    ssize_t n = recv(info->connect_fd, &c, 1, MSG_PEEK | MSG_DONTWAIT);
    return n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR);
}

static void cancel_abandoned(ps_server *s) {
    char ids[64][96];
    size_t n = 0;
    pthread_mutex_lock(&s->lock);
    for (ps_request *r = s->waiting; r && n < 64; r = r->next) {
        if (r->cancel_sent || !r->job_id[0] || !peer_closed(r->conn)) continue;
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
        cancel_abandoned(s);
        pthread_mutex_lock(&s->lock);
    }
    pthread_mutex_unlock(&s->lock);
    return NULL;
}

/* poll(), not epoll: with epoll worker threads, libmicrohttpd's
 * MHD_quiesce_daemon (SIGTERM's first step) races with the workers over
 * removing the listening socket from their epoll sets, and the loser
 * aborts the process (about 1 stop in 300 under incoming connections). */
static struct MHD_Daemon *start_daemon(ps_http *h, const struct sockaddr_in *addr) {
    unsigned flags = MHD_USE_POLL_INTERNAL_THREAD | MHD_ALLOW_SUSPEND_RESUME | MHD_USE_ERROR_LOG;
    unsigned pool = IO_THREADS;
    return MHD_start_daemon(flags, (uint16_t)h->srv.cfg->port, NULL, NULL, on_request, &h->srv,
                            MHD_OPTION_SOCK_ADDR, addr,
                            MHD_OPTION_THREAD_POOL_SIZE, pool,
                            MHD_OPTION_NOTIFY_COMPLETED, on_completed, &h->srv,
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
    if (!h->srv.openapi) {
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
    double deadline = monotonic_seconds() + seconds;
    pthread_mutex_lock(&h->srv.lock);
    while (h->srv.in_flight && monotonic_seconds() < deadline) {
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
    pthread_cond_destroy(&h->srv.changed);
    pthread_mutex_destroy(&h->srv.lock);
    free(h->srv.openapi);
    free(h);
}
