/* main.c: pointsegd start-up: configuration, the job backend, the HTTP
 * server; then waits for SIGTERM or SIGINT and drains: stop accepting, let
 * jobs finish (bounded by --drain-seconds), answer, exit 0. */
#include "config.h"
#include "http.h"
#include "jobs.h"

#include <signal.h>
#include <stdio.h>

#define ANSWER_SECONDS 5.0

static void block_stop_signals(sigset_t *set) {
    sigemptyset(set);
    sigaddset(set, SIGTERM);
    sigaddset(set, SIGINT);
    pthread_sigmask(SIG_BLOCK, set, NULL);
    signal(SIGPIPE, SIG_IGN);
}

int main(int argc, char **argv) {
    ps_config cfg;
    sigset_t stop;
    int sig = 0;
    char why[256];
    int rc = ps_config_load(&cfg, argc, argv, stdout, stderr);
    if (rc) return rc > 0 ? 0 : 2;
    block_stop_signals(&stop); /* before any thread starts: all inherit the mask */
    ps_jobs_config jc = {cfg.threads, cfg.queue_size, cfg.job_ttl, cfg.max_jobs_kept, cfg.replica_name};
    ps_jobs *jobs = ps_jobs_start(&jc);
    if (!jobs) {
        fprintf(stderr, "pointsegd: cannot start %d worker threads\n", cfg.threads);
        return 1;
    }
    ps_http *http = ps_http_start(&cfg, jobs, why, sizeof why);
    if (!http) {
        fprintf(stderr, "pointsegd: %s\n", why);
        ps_jobs_drain(jobs, 0);
        ps_jobs_free(jobs);
        return 1;
    }
    fprintf(stderr, "pointsegd: listening on http://%s:%d (%d workers, queue %d)\n", cfg.bind,
            ps_http_port(http), cfg.threads, cfg.queue_size);
    sigwait(&stop, &sig);
    fprintf(stderr, "pointsegd: signal %d, draining\n", sig);
    ps_http_quiesce(http);
    ps_jobs_drain(jobs, cfg.drain_seconds);
    ps_http_wait_idle(http, ANSWER_SECONDS);
    ps_http_stop(http);
    ps_jobs_free(jobs);
    fprintf(stderr, "pointsegd: stopped\n");
    return 0;
}
