/* main.c: pointsegd start-up: configuration, the job backend, the HTTP
 * server; then waits for SIGTERM or SIGINT and drains: stop accepting, let
 * jobs finish (bounded by --drain-seconds), answer, exit 0.
 *
 * The stop signals get a handler that posts a semaphore main waits on,
 * rather than being blocked for sigwait: libraries start threads before
 * main runs (OpenBLAS does, in its constructor), and a blocked-everywhere
 * scheme cannot reach those; a signal landing there would kill the
 * process.  With a handler, whichever thread takes it, main wakes.
 *
 * Blocks of 1 MiB and more (points, results, bodies) are mmap'ed and go
 * back to the system when freed: with glibc's default sliding threshold
 * they end up in the heaps, and the resident size of a daemon serving
 * large requests keeps growing (120 synchronous horse requests with
 * include=centrality,point_supernode: 62 MB instead of 28 MB). */
#include "config.h"
#include "deadline.h"
#include "http.h"
#include "jobs.h"
#include "jobstore_redis.h"

#include <errno.h>
#include <malloc.h>
#include <semaphore.h>
#include <signal.h>
#include <stdio.h>

#define ANSWER_SECONDS 5.0
#define MAX_WORKER_LOSSES 3
#define MMAP_THRESHOLD (1 << 20)

static sem_t stop_posted;
static volatile sig_atomic_t stop_signal;

static void on_stop_signal(int sig) {
    stop_signal = sig;
    sem_post(&stop_posted); /* async-signal-safe */
}

static int catch_stop_signals(void) {
    struct sigaction sa = {.sa_handler = on_stop_signal, .sa_flags = SA_RESTART};
    sigemptyset(&sa.sa_mask);
    signal(SIGPIPE, SIG_IGN);
    return sem_init(&stop_posted, 0, 0) == 0 && sigaction(SIGTERM, &sa, NULL) == 0 &&
           sigaction(SIGINT, &sa, NULL) == 0;
}

static int wait_for_stop_signal(void) {
    while (sem_wait(&stop_posted) != 0 && errno == EINTR) continue;
    return stop_signal;
}

/* Lets the running jobs of both queues (the shared store's and the
 * in-process one's, which run side by side) finish within one budget of
 * `seconds`; the store hands its unfinished jobs back, the rest are
 * cancelled. */
static void drain(ps_jobs *jobs, ps_jobstore *store, double seconds) {
    double start = ps_monotonic_seconds();
    ps_jobs_stop_taking(jobs);
    ps_jobstore_drain(store, seconds);
    double left = seconds - (ps_monotonic_seconds() - start);
    ps_jobs_drain(jobs, left > 0 ? left : 0);
}

/* The store of asynchronous jobs: Redis with --redis, else the in-process
 * queue.  NULL after saying why on stderr. */
static ps_jobstore *open_store(const ps_config *cfg, ps_jobs *jobs) {
    char why[512];
    if (!cfg->redis[0]) return ps_jobstore_memory_new(jobs);
    ps_redis_store_config rc = {.workers = cfg->threads, .job_ttl = cfg->job_ttl,
                                .max_kept_bytes = cfg->max_kept_bytes,
                                .lease_seconds = cfg->job_lease, .max_losses = MAX_WORKER_LOSSES,
                                .max_points = cfg->max_points, .name = cfg->replica_name};
    if (ps_redis_url_parse(cfg->redis, &rc.url, why, sizeof why)) {
        fprintf(stderr, "pointsegd: %s\n", why);
        return NULL;
    }
    ps_jobstore *store = ps_jobstore_redis_new(&rc, why, sizeof why);
    if (!store) fprintf(stderr, "pointsegd: %s\n", why);
    else fprintf(stderr, "pointsegd: jobs on Redis at %s:%d (lease %d s)\n", rc.url.host, rc.url.port,
                 cfg->job_lease);
    return store;
}

int main(int argc, char **argv) {
    ps_config cfg;
    char why[256];
    int rc = ps_config_load(&cfg, argc, argv, stdout, stderr);
    if (rc) return rc > 0 ? 0 : 2;
    mallopt(M_MMAP_THRESHOLD, MMAP_THRESHOLD);
    if (!catch_stop_signals()) {
        fprintf(stderr, "pointsegd: cannot install the SIGTERM handler\n");
        return 1;
    }
    ps_jobs_config jc = {cfg.threads, cfg.queue_size, cfg.job_ttl, cfg.max_jobs_kept, cfg.max_kept_bytes,
                         cfg.replica_name};
    ps_jobs *jobs = ps_jobs_start(&jc);
    if (!jobs) {
        fprintf(stderr, "pointsegd: cannot start %d worker threads\n", cfg.threads);
        return 1;
    }
    ps_jobstore *store = open_store(&cfg, jobs);
    ps_http *http = store ? ps_http_start(&cfg, jobs, store, why, sizeof why) : NULL;
    if (!http) {
        if (store) fprintf(stderr, "pointsegd: %s\n", why);
        ps_jobstore_free(store);
        ps_jobs_drain(jobs, 0);
        ps_jobs_free(jobs);
        return store ? 1 : 2;
    }
    fprintf(stderr, "pointsegd: listening on http://%s:%d (%d workers, queue %d)\n", cfg.bind,
            ps_http_port(http), cfg.threads, cfg.queue_size);
    int sig = wait_for_stop_signal();
    fprintf(stderr, "pointsegd: signal %d, draining\n", sig);
    ps_http_quiesce(http);
    drain(jobs, store, cfg.drain_seconds);
    ps_http_wait_idle(http, ANSWER_SECONDS);
    ps_http_stop(http);
    ps_jobstore_free(store);
    ps_jobs_free(jobs);
    fprintf(stderr, "pointsegd: stopped\n");
    return 0;
}
