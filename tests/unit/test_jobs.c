/* test_jobs.c: the in-process job backend (server/jobs.c) without a daemon:
 * a job runs to its document, the bounded queue refuses when full, a queued
 * job is cancelled at once, failures carry their status, the registry keeps
 * finished jobs within its count and time limits while a held reference
 * keeps a result readable, and a drain finishes what was queued.
 *
 * To hold the only worker still, a job's on_done callback (run by the
 * worker after the job is final and before it takes the next one) waits
 * on a gate the test opens. */
#include "jobs.h"
#include "shapes.h"
#include "testlib.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct gate {
    pthread_mutex_t lock;
    pthread_cond_t changed;
    int entered, open;
} gate;

static void gate_init(gate *g) {
    pthread_mutex_init(&g->lock, NULL);
    pthread_cond_init(&g->changed, NULL);
    g->entered = g->open = 0;
}

/* on_done: the worker enters the gate and waits there until it opens. */
static void gate_hold(void *user) {
    gate *g = user;
    pthread_mutex_lock(&g->lock);
    g->entered = 1;
    pthread_cond_broadcast(&g->changed);
    while (!g->open) pthread_cond_wait(&g->changed, &g->lock);
    pthread_mutex_unlock(&g->lock);
}

static void gate_wait_entered(gate *g) {
    pthread_mutex_lock(&g->lock);
    while (!g->entered) pthread_cond_wait(&g->changed, &g->lock);
    pthread_mutex_unlock(&g->lock);
}

static void gate_open(gate *g) {
    pthread_mutex_lock(&g->lock);
    g->open = 1;
    pthread_cond_broadcast(&g->changed);
    pthread_mutex_unlock(&g->lock);
}

static void gate_destroy(gate *g) {
    pthread_mutex_destroy(&g->lock);
    pthread_cond_destroy(&g->changed);
}

/* A small dumbbell (about 1,000 points): segments in milliseconds. */
static ps_pointset dumbbell(void) {
    ps_pointset ps = {0};
    int *part = NULL;
    ps.points = ps_shape_dumbbell(60, &ps.n, &part);
    ps.dim = 3;
    free(part);
    return ps;
}

static int contains(const char *bytes, size_t len, const char *needle) {
    size_t k = strlen(needle);
    for (size_t i = 0; i + k <= len; i++)
        if (memcmp(bytes + i, needle, k) == 0) return 1;
    return 0;
}

static ps_jobs_config config(int queue_size, int max_finished, int ttl_seconds) {
    return (ps_jobs_config){.workers = 1, .queue_size = queue_size, .ttl_seconds = ttl_seconds,
                            .max_finished = max_finished, .max_kept_bytes = (size_t)1 << 30,
                            .id_prefix = "t"};
}

static ps_job *submit(ps_jobs *q, ps_pointset ps, ps_job_done_fn on_done, void *user) {
    ps_request_params rp;
    ps_request_params_default(&rp);
    ps_job *job = NULL;
    ps_api_error err;
    return ps_jobs_submit(q, &ps, &rp, on_done, user, &job, &err) == 0 ? job : NULL;
}

/* Submits a job that must be refused: 1 when it is, with err set and the
 * points freed. */
static int refused(ps_jobs *q, ps_api_error *err) {
    ps_request_params rp;
    ps_request_params_default(&rp);
    ps_pointset ps = dumbbell();
    ps_job *job = NULL;
    return ps_jobs_submit(q, &ps, &rp, NULL, NULL, &job, err) == -1 && job == NULL && ps.points == NULL;
}

/* Polls until the job is final (at most 60 s); returns its state. */
static ps_job_state wait_final(ps_job *job) {
    ps_job_status st;
    for (int i = 0; i < 60000; i++) {
        ps_job_get_status(job, &st);
        if (st.state >= PS_JOB_DONE) return st.state;
        nanosleep(&(struct timespec){0, 1000000}, NULL);
    }
    return st.state;
}

static void test_job_runs_to_its_document(void) {
    ps_jobs_config cfg = config(4, 10, 600);
    ps_jobs *q = ps_jobs_start(&cfg);
    REQUIRE(q != NULL);
    ps_pointset ps = dumbbell();
    size_t n = ps.n;
    ps_job *job = submit(q, ps, NULL, NULL);
    REQUIRE(job != NULL);
    CHECK(strncmp(ps_job_id(job), "t-", 2) == 0);
    CHECK(wait_final(job) == PS_JOB_DONE);
    size_t len = 0;
    const char *media = NULL;
    const char *doc = ps_job_result(job, &len, &media);
    REQUIRE(doc != NULL);
    CHECK(media && strcmp(media, "application/json") == 0);
    CHECK(len > 0 && doc[0] == '{' && contains(doc, len, "\"labels\""));
    ps_job *found = ps_jobs_find(q, ps_job_id(job));
    CHECK(found == job);
    ps_job_release(found);
    ps_jobs_stats st;
    ps_jobs_get_stats(q, &st);
    CHECK(st.jobs_done == 1 && st.points_segmented == n && st.kept == 1 && st.kept_bytes == len);
    ps_job_release(job);
    ps_jobs_drain(q, 10);
    ps_jobs_free(q);
}

/* queue_size 2, the worker held: two jobs wait, a third is refused (503);
 * a queued job cancelled is final at once and frees its slot for another
 * job (the queue is no longer full), and the worker skips it. */
static void test_full_queue_and_queued_cancel(void) {
    ps_jobs_config cfg = config(2, 10, 600);
    ps_jobs *q = ps_jobs_start(&cfg);
    REQUIRE(q != NULL);
    gate g;
    gate_init(&g);
    ps_job *holder = submit(q, dumbbell(), gate_hold, &g);
    REQUIRE(holder != NULL);
    gate_wait_entered(&g);
    ps_job *a = submit(q, dumbbell(), NULL, NULL), *b = submit(q, dumbbell(), NULL, NULL);
    REQUIRE(a && b);
    ps_api_error err;
    CHECK(ps_jobs_refuses(q, &err) == -1 && err.http_status == 503 && strstr(err.message, "queue is full"));
    CHECK(refused(q, &err) && err.http_status == 503 &&
          !strcmp(err.message, "the job queue is full (2 waiting)"));
    ps_job_cancel(b);
    ps_job_status st;
    ps_job_get_status(b, &st);
    CHECK(st.state == PS_JOB_CANCELLED);
    ps_jobs_stats stats;
    ps_jobs_get_stats(q, &stats);
    CHECK(stats.queued == 1 && stats.running == 0 && stats.jobs_cancelled == 1);
    CHECK(ps_jobs_refuses(q, &err) == 0);
    ps_job *c = submit(q, dumbbell(), NULL, NULL);
    CHECK(c != NULL && ps_jobs_refuses(q, &err) == -1);
    gate_open(&g);
    CHECK(wait_final(a) == PS_JOB_DONE);
    CHECK(c && wait_final(c) == PS_JOB_DONE);
    ps_job_get_status(b, &st);
    CHECK(st.state == PS_JOB_CANCELLED);
    ps_job_release(holder), ps_job_release(a), ps_job_release(b), ps_job_release(c);
    ps_jobs_drain(q, 10);
    ps_jobs_free(q);
    gate_destroy(&g);
}

/* An input the core refuses ends FAILED with its HTTP status and reason. */
static void test_failure_carries_status(void) {
    ps_jobs_config cfg = config(2, 10, 600);
    ps_jobs *q = ps_jobs_start(&cfg);
    REQUIRE(q != NULL);
    ps_pointset empty = {.dim = 3};
    ps_job *job = submit(q, empty, NULL, NULL);
    REQUIRE(job != NULL);
    CHECK(wait_final(job) == PS_JOB_FAILED);
    ps_job_status st;
    ps_job_get_status(job, &st);
    CHECK(st.error_status == 422 && strstr(st.error, "no points") != NULL);
    size_t len;
    const char *media;
    CHECK(ps_job_result(job, &len, &media) == NULL);
    ps_jobs_stats stats;
    ps_jobs_get_stats(q, &stats);
    CHECK(stats.jobs_failed == 1 && stats.jobs_done == 0);
    ps_job_release(job);
    ps_jobs_drain(q, 10);
    ps_jobs_free(q);
}

/* max_finished 1: the older of two finished jobs leaves the registry, but
 * a reference held on it keeps its result readable until released. */
static void test_registry_keeps_within_count(void) {
    ps_jobs_config cfg = config(4, 1, 600);
    ps_jobs *q = ps_jobs_start(&cfg);
    REQUIRE(q != NULL);
    ps_job *first = submit(q, dumbbell(), NULL, NULL);
    REQUIRE(first != NULL);
    CHECK(wait_final(first) == PS_JOB_DONE);
    size_t len = 0;
    const char *media, *doc = ps_job_result(first, &len, &media);
    REQUIRE(doc != NULL);
    char *copy = malloc(len);
    REQUIRE(copy != NULL);
    memcpy(copy, doc, len);
    char id[96];
    snprintf(id, sizeof id, "%s", ps_job_id(first));
    ps_job *second = submit(q, dumbbell(), NULL, NULL);
    REQUIRE(second != NULL);
    CHECK(strcmp(ps_job_id(second), id) != 0);
    CHECK(wait_final(second) == PS_JOB_DONE);
    CHECK(ps_jobs_find(q, id) == NULL);
    ps_job *kept = ps_jobs_find(q, ps_job_id(second));
    CHECK(kept == second);
    ps_job_release(kept);
    size_t len_again = 0;
    const char *again = ps_job_result(first, &len_again, &media);
    CHECK(again && len_again == len && memcmp(again, copy, len) == 0);
    free(copy);
    ps_jobs_stats stats;
    ps_jobs_get_stats(q, &stats);
    CHECK(stats.kept == 1 && stats.jobs_done == 2);
    ps_job_release(first), ps_job_release(second);
    ps_jobs_drain(q, 10);
    ps_jobs_free(q);
}

/* ttl 0: a finished job is gone at the next look; a job whose request
 * waited for it (on_done) is not kept either. */
static void test_registry_forgets_expired(void) {
    ps_jobs_config cfg = config(4, 10, 0);
    ps_jobs *q = ps_jobs_start(&cfg);
    REQUIRE(q != NULL);
    ps_job *job = submit(q, dumbbell(), NULL, NULL);
    REQUIRE(job != NULL);
    CHECK(wait_final(job) == PS_JOB_DONE);
    nanosleep(&(struct timespec){0, 10000000}, NULL);
    CHECK(ps_jobs_find(q, ps_job_id(job)) == NULL);
    ps_job_release(job);
    ps_jobs_stats stats;
    ps_jobs_get_stats(q, &stats);
    CHECK(stats.kept == 0 && stats.jobs_done == 1);
    ps_jobs_drain(q, 10);
    ps_jobs_free(q);
}

/* A drain lets queued jobs finish, then refuses new ones, saying the
 * service is shutting down. */
static void test_drain_finishes_queued(void) {
    ps_jobs_config cfg = config(4, 10, 600);
    ps_jobs *q = ps_jobs_start(&cfg);
    REQUIRE(q != NULL);
    ps_job *jobs[3];
    for (int i = 0; i < 3; i++) REQUIRE((jobs[i] = submit(q, dumbbell(), NULL, NULL)) != NULL);
    ps_jobs_drain(q, 60);
    for (int i = 0; i < 3; i++) {
        ps_job_status st;
        ps_job_get_status(jobs[i], &st);
        CHECK_MSG(st.state == PS_JOB_DONE, "job %d state %s", i, ps_job_state_name(st.state));
        ps_job_release(jobs[i]);
    }
    ps_api_error err;
    CHECK(ps_jobs_refuses(q, &err) == -1 && err.http_status == 503 &&
          !strcmp(err.message, "the service is shutting down"));
    CHECK(refused(q, &err) && err.http_status == 503 &&
          !strcmp(err.message, "the service is shutting down"));
    ps_jobs_free(q);
}

PS_TEST_MAIN(TEST(test_job_runs_to_its_document), TEST(test_full_queue_and_queued_cancel),
             TEST(test_failure_carries_status), TEST(test_registry_keeps_within_count),
             TEST(test_registry_forgets_expired), TEST(test_drain_finishes_queued))
