/* metrics.c: request counters and latency histograms in Prometheus text format. */
#include "metrics.h"

#include "redis_link.h"

#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

static const double bucket_bounds[] = {0.001, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25,
                                       0.5, 1, 2.5, 5, 10, 30, 60};
#define N_BUCKETS (sizeof bucket_bounds / sizeof bucket_bounds[0])
#define MIN_STATUS 100
#define N_STATUS 500 /* 100..599 */

typedef struct histogram {
    unsigned long long bucket[N_BUCKETS]; /* cumulative at render time */
    unsigned long long count;
    double sum;
} histogram;

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static unsigned long long requests[PS_ROUTE_COUNT][N_STATUS];
static histogram latency[PS_ROUTE_COUNT];
static unsigned long long connections_cut;

const char *ps_route_name(ps_route r) {
    static const char *const names[PS_ROUTE_COUNT] = {
        "/segment", "/jobs", "/jobs/{id}", "/jobs/{id}/result", "/healthz", "/readyz",
        "/metrics", "/openapi.json", "/version", "static", "other"};
    return (unsigned)r < PS_ROUTE_COUNT ? names[r] : "other";
}

void ps_metrics_observe(ps_route route, int status, double seconds) {
    if ((unsigned)route >= PS_ROUTE_COUNT) route = PS_ROUTE_OTHER;
    if (status < MIN_STATUS || status >= MIN_STATUS + N_STATUS) status = 500;
    size_t b = 0;
    while (b < N_BUCKETS && seconds > bucket_bounds[b]) b++;
    pthread_mutex_lock(&lock);
    requests[route][status - MIN_STATUS]++;
    if (b < N_BUCKETS) latency[route].bucket[b]++;
    latency[route].count++;
    latency[route].sum += seconds;
    pthread_mutex_unlock(&lock);
}

void ps_metrics_connections_cut(size_t n) {
    if (!n) return;
    pthread_mutex_lock(&lock);
    connections_cut += n;
    pthread_mutex_unlock(&lock);
}

typedef struct text {
    char *buf;
    size_t len, cap;
    int failed;
} text;

static void put(text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void put(text *t, const char *fmt, ...) {
    va_list ap;
    for (;;) {
        if (t->failed) return;
        va_start(ap, fmt);
        int n = vsnprintf(t->buf + t->len, t->cap - t->len, fmt, ap);
        va_end(ap);
        if (n >= 0 && (size_t)n < t->cap - t->len) {
            t->len += (size_t)n;
            return;
        }
        char *grown = realloc(t->buf, t->cap * 2 + (size_t)(n > 0 ? n : 0));
        if (!grown) {
            t->failed = 1;
            return;
        }
        t->cap = t->cap * 2 + (size_t)(n > 0 ? n : 0);
        t->buf = grown;
    }
}

static void render_requests(text *t) {
    put(t, "# HELP pointseg_http_requests_total HTTP requests answered, by route and status.\n"
           "# TYPE pointseg_http_requests_total counter\n");
    for (int r = 0; r < PS_ROUTE_COUNT; r++)
        for (int s = 0; s < N_STATUS; s++)
            if (requests[r][s])
                put(t, "pointseg_http_requests_total{route=\"%s\",status=\"%d\"} %llu\n",
                    ps_route_name((ps_route)r), s + MIN_STATUS, requests[r][s]);
}

static void render_latency(text *t) {
    put(t, "# HELP pointseg_http_request_duration_seconds Time from request to answer.\n"
           "# TYPE pointseg_http_request_duration_seconds histogram\n");
    for (int r = 0; r < PS_ROUTE_COUNT; r++) {
        const histogram *h = &latency[r];
        if (!h->count) continue;
        const char *name = ps_route_name((ps_route)r);
        unsigned long long cumulative = 0;
        for (size_t b = 0; b < N_BUCKETS; b++) {
            cumulative += h->bucket[b];
            put(t, "pointseg_http_request_duration_seconds_bucket{route=\"%s\",le=\"%g\"} %llu\n",
                name, bucket_bounds[b], cumulative);
        }
        put(t, "pointseg_http_request_duration_seconds_bucket{route=\"%s\",le=\"+Inf\"} %llu\n"
               "pointseg_http_request_duration_seconds_sum{route=\"%s\"} %.6f\n"
               "pointseg_http_request_duration_seconds_count{route=\"%s\"} %llu\n",
            name, h->count, name, h->sum, name, h->count);
    }
}

static void render_jobs(text *t, const ps_jobs_stats *j) {
    put(t, "# HELP pointseg_queue_depth Jobs waiting for a worker.\n# TYPE pointseg_queue_depth gauge\n"
           "pointseg_queue_depth %zu\n"
           "# HELP pointseg_queue_capacity Jobs that may wait.\n# TYPE pointseg_queue_capacity gauge\n"
           "pointseg_queue_capacity %zu\n"
           "# HELP pointseg_jobs_running Jobs being segmented.\n# TYPE pointseg_jobs_running gauge\n"
           "pointseg_jobs_running %zu\n"
           "# HELP pointseg_jobs_kept Jobs in the registry.\n# TYPE pointseg_jobs_kept gauge\n"
           "pointseg_jobs_kept %zu\n"
           "# HELP pointseg_jobs_kept_bytes Result bytes held by kept jobs.\n"
           "# TYPE pointseg_jobs_kept_bytes gauge\n"
           "pointseg_jobs_kept_bytes %zu\n",
        j->queued, j->capacity, j->running, j->kept, j->kept_bytes);
    put(t, "# HELP pointseg_jobs_finished_total Jobs finished, by outcome.\n"
           "# TYPE pointseg_jobs_finished_total counter\n"
           "pointseg_jobs_finished_total{outcome=\"done\"} %llu\n"
           "pointseg_jobs_finished_total{outcome=\"failed\"} %llu\n"
           "pointseg_jobs_finished_total{outcome=\"cancelled\"} %llu\n"
           "# HELP pointseg_points_segmented_total Points in successfully segmented jobs.\n"
           "# TYPE pointseg_points_segmented_total counter\n"
           "pointseg_points_segmented_total %llu\n",
        j->jobs_done, j->jobs_failed, j->jobs_cancelled, j->points_segmented);
}

static void render_shared_queue(text *t, const ps_jobstore_stats *s) {
    ps_redis_counters c;
    ps_redis_counters_get(&c);
    put(t, "# HELP pointseg_redis_up Redis answered the last look at the shared queue.\n"
           "# TYPE pointseg_redis_up gauge\npointseg_redis_up %d\n", s->reachable);
    if (s->reachable)
        put(t, "# HELP pointseg_shared_queue_length Jobs in the shared queue no worker took yet.\n"
               "# TYPE pointseg_shared_queue_length gauge\npointseg_shared_queue_length %zu\n"
               "# HELP pointseg_shared_pending Jobs taken by a worker (any replica), not finished.\n"
               "# TYPE pointseg_shared_pending gauge\npointseg_shared_pending %zu\n"
               "# HELP pointseg_shared_result_bytes Result bytes kept in Redis (any replica's jobs).\n"
               "# TYPE pointseg_shared_result_bytes gauge\npointseg_shared_result_bytes %zu\n",
            s->queue_length, s->pending, s->result_bytes);
    put(t, "# HELP pointseg_jobs_reclaimed_total Jobs this replica took over from a lost worker.\n"
           "# TYPE pointseg_jobs_reclaimed_total counter\npointseg_jobs_reclaimed_total %llu\n"
           "# HELP pointseg_jobs_lost_failed_total Jobs failed for losing their worker too often.\n"
           "# TYPE pointseg_jobs_lost_failed_total counter\npointseg_jobs_lost_failed_total %llu\n"
           "# HELP pointseg_jobs_handed_back_total Running jobs given back to the queue on shutdown.\n"
           "# TYPE pointseg_jobs_handed_back_total counter\npointseg_jobs_handed_back_total %llu\n",
        s->reclaimed, s->lost_failed, s->handed_back);
    put(t, "# HELP pointseg_redis_commands_total Redis commands sent.\n"
           "# TYPE pointseg_redis_commands_total counter\npointseg_redis_commands_total %llu\n"
           "# HELP pointseg_redis_errors_total Redis commands that failed (unreachable, timeout, error).\n"
           "# TYPE pointseg_redis_errors_total counter\npointseg_redis_errors_total %llu\n"
           "# HELP pointseg_redis_command_seconds Time spent in Redis commands.\n"
           "# TYPE pointseg_redis_command_seconds summary\n"
           "pointseg_redis_command_seconds_sum %.6f\npointseg_redis_command_seconds_count %llu\n",
        c.commands, c.errors, c.seconds, c.commands);
}

char *ps_metrics_render(const ps_jobs_stats *jobs, const ps_jobstore_stats *store, size_t *len) {
    text t = {malloc(4096), 0, 4096, 0};
    if (!t.buf) return NULL;
    pthread_mutex_lock(&lock);
    render_requests(&t);
    render_latency(&t);
    put(&t, "# HELP pointseg_connections_cut_total Connections closed for a slow request head or body, "
            "or idle too long.\n# TYPE pointseg_connections_cut_total counter\npointseg_connections_cut_total %llu\n",
        connections_cut);
    pthread_mutex_unlock(&lock);
    render_jobs(&t, jobs);
    if (store->shared) render_shared_queue(&t, store);
    if (t.failed) {
        free(t.buf);
        return NULL;
    }
    *len = t.len;
    return t.buf;
}
