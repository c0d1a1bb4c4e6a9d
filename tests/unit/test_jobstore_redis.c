/* test_jobstore_redis.c: the Redis job store against a real redis-server
 * (started by the test on a free loopback port): any store reads any job
 * (and an id naming another key of a job, "ID:result", is no job: 404),
 * cancels reach the worker running the job, lapsed leases are taken over,
 * the third loss fails a job, a takeover whose answer is lost and retried
 * counts its loss once (and a lost answer failing a job still counts
 * it as failed by losses), a worker whose read or takeover lost its answer
 * runs the job at once from its own pending list, Redis going away gives 503s and coming back
 * heals by itself, a submit retried after Redis stalled queues its job
 * once, shutdown hands running jobs back, a job cancelled while queued
 * leaves the queue, kept results stay within their byte budget. */
#include "daemon_proc.h"
#include "job_runner.h"
#include "jobstore_redis.h"
#include "redis_proc.h"
#include "reply_cut.h"
#include "testlib.h"

#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define LEASE_S 2
#define SMALL_POINTS 400
#define SLOW_POINTS 6000 /* exact centrality: seconds of work */

static ps_test_redis server;
static int server_up;
static char skip_why[256];

static void stop_server(void) { ps_test_redis_cleanup(&server); }

/* Starts the one redis-server of this file on first use; stopped at exit. */
static int need_server(void) {
    if (server_up) return 1;
    if (skip_why[0]) return 0;
    server_up = ps_test_redis_start(&server, skip_why, sizeof skip_why) == 0;
    if (server_up) atexit(stop_server);
    return server_up;
}

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* m points on a sphere (golden spiral) as XYZ text. */
static char *sphere_text(int m, size_t *len) {
    size_t cap = (size_t)m * 40 + 1, n = 0;
    char *text = malloc(cap);
    double golden = atan2(0, -1) * (3 - sqrt(5));
    for (int i = 0; text && i < m; i++) {
        double y = 1 - 2 * (i + 0.5) / m, r = sqrt(1 - y * y), t = golden * i;
        n += (size_t)snprintf(text + n, cap - n, "%.6f %.6f %.6f\n", r * cos(t), y, r * sin(t));
    }
    *len = n;
    return text;
}

typedef struct upload {
    char *text;
    ps_pointset points;
    ps_request_params params;
    ps_text_param extra[2];
    ps_job_upload up;
} upload;

/* An upload of m sphere points with output=labels (and centrality=exact
 * when slow), as the HTTP layer hands it over. */
static int make_upload(upload *u, int m, int slow) {
    ps_api_error err;
    size_t len;
    memset(u, 0, sizeof *u);
    u->text = sphere_text(m, &len);
    u->extra[0] = (ps_text_param){"output", "labels"};
    u->extra[1] = (ps_text_param){"centrality", slow ? "exact" : "auto"};
    if (ps_intake_decode(u->text, len, PS_MEDIA_POINTS, 10000000, &u->points, &err)) return -1;
    if (ps_intake_params(&u->points, NULL, u->extra, 2, &u->params, &err)) return -1;
    u->up = (ps_job_upload){&u->points, &u->params, u->text, len, PS_MEDIA_POINTS, NULL, u->extra, 2};
    return 0;
}

static void free_upload(upload *u) {
    ps_pointset_free(&u->points);
    free(u->text);
}

/* A store on the Redis at port whose finished jobs stay ttl seconds, their
 * results within budget bytes. */
static ps_jobstore *open_store_on(int port, int workers, int ttl, size_t budget) {
    char why[256];
    ps_redis_store_config cfg = {.workers = workers, .job_ttl = ttl, .max_kept_bytes = budget,
                                 .lease_seconds = LEASE_S, .max_losses = 3, .max_points = 10000000,
                                 .name = "test"};
    snprintf(cfg.url.host, sizeof cfg.url.host, "127.0.0.1");
    cfg.url.port = port;
    ps_jobstore *s = ps_jobstore_redis_new(&cfg, why, sizeof why);
    if (!s) fprintf(stderr, "store: %s\n", why);
    return s;
}

static ps_jobstore *open_store_keeping(int workers, int ttl, size_t budget) {
    return open_store_on(server.port, workers, ttl, budget);
}

static ps_jobstore *open_store(int workers) { return open_store_keeping(workers, 60, (size_t)1 << 30); }

/* Polls until the job is in one of the final states or `seconds` pass. */
static ps_job_state wait_state(ps_jobstore *s, const char *id, ps_job_state want, double seconds) {
    ps_job_status st = {.state = PS_JOB_QUEUED};
    ps_api_error err;
    for (double end = now_s() + seconds; now_s() < end; ps_test_sleep_ms(50))
        if (ps_jobstore_status(s, id, &st, &err) == 0 && (st.state == want || st.state >= PS_JOB_DONE))
            return st.state;
    return st.state;
}

/* The labels a local run gives for the upload. */
static char *local_labels(upload *u, size_t *len) {
    ps_run_outcome out;
    ps_control ctl = {0};
    ps_job_run(&u->points, &u->params, &ctl, &out);
    *len = out.doc_len;
    return out.doc;
}

static long long hash_integer(const char *id, const char *field) {
    redisContext *c = ps_test_redis_connect(&server);
    redisReply *r = c ? redisCommand(c, "HGET pointseg:job:%s %s", id, field) : NULL;
    long long v = r && r->type == REDIS_REPLY_STRING ? atoll(r->str) : -1;
    if (r) freeReplyObject(r);
    if (c) redisFree(c);
    return v;
}

static void test_url_parse(void) {
    ps_redis_url u;
    char why[256];
    CHECK(ps_redis_url_parse("redis://cache", &u, why, sizeof why) == 0);
    CHECK(!strcmp(u.host, "cache") && u.port == 6379 && u.db == 0 && !u.password[0]);
    CHECK(ps_redis_url_parse("redis://:s3cr@t@10.0.0.2:6380/2", &u, why, sizeof why) == 0);
    CHECK(!strcmp(u.host, "10.0.0.2") && u.port == 6380 && u.db == 2 && !strcmp(u.password, "s3cr@t"));
    CHECK(ps_redis_url_parse("http://cache", &u, why, sizeof why) == -1 && strstr(why, "redis://"));
    CHECK(ps_redis_url_parse("redis://cache:0", &u, why, sizeof why) == -1 && strstr(why, "port"));
    CHECK(ps_redis_url_parse("redis://cache:6379/x", &u, why, sizeof why) == -1);
    CHECK(ps_redis_url_parse("redis://", &u, why, sizeof why) == -1 && strstr(why, "host"));
    CHECK(ps_redis_url_parse("redis://user@cache", &u, why, sizeof why) == -1);
}

/* Submitted on a store without workers, run by another, read from both:
 * the labels of a local run. */
static void test_any_store_serves_any_job(void) {
    if (!need_server()) SKIP("%s", skip_why);
    upload u;
    ps_api_error err;
    char id[96];
    size_t want_len;
    REQUIRE(make_upload(&u, SMALL_POINTS, 0) == 0);
    ps_jobstore *front = open_store(0), *worker = open_store(1);
    REQUIRE(front && worker);
    REQUIRE(ps_jobstore_submit(front, &u.up, id, sizeof id, &err) == 0);
    CHECK(strlen(id) == 32);
    CHECK(wait_state(front, id, PS_JOB_DONE, 30) == PS_JOB_DONE);
    char *want = local_labels(&u, &want_len);
    for (int i = 0; i < 2; i++) {
        ps_job_doc doc;
        REQUIRE(ps_jobstore_result(i ? worker : front, id, &doc, &err) == 0);
        CHECK(doc.len == want_len && !memcmp(doc.doc, want, want_len));
        CHECK(!strncmp(doc.media_type, "text/plain", 10));
        free(doc.doc);
    }
    ps_job_status st;
    CHECK(ps_jobstore_status(front, id, &st, &err) == 0 && st.n_points == SMALL_POINTS);
    CHECK(ps_jobstore_status(front, "0123", &st, &err) == -1 && err.http_status == 404);
    ps_job_doc none;
    CHECK(ps_jobstore_result(front, "0123", &none, &err) == -1 && err.http_status == 404);
    static const char *const other_keys[] = {":result", ":body"}; /* keys of the job, not jobs */
    for (size_t i = 0; i < sizeof other_keys / sizeof other_keys[0]; i++) {
        char other[128];
        snprintf(other, sizeof other, "%s%s", id, other_keys[i]);
        CHECK_MSG(ps_jobstore_status(front, other, &st, &err) == -1 && err.http_status == 404,
                  "status of %s: %d %s", other, err.http_status, err.message);
        CHECK_MSG(ps_jobstore_result(front, other, &none, &err) == -1 && err.http_status == 404,
                  "result of %s: %d %s", other, err.http_status, err.message);
        CHECK_MSG(ps_jobstore_cancel(front, other, &st, &err) == -1 && err.http_status == 404,
                  "cancel of %s: %d %s", other, err.http_status, err.message);
    }
    free(want);
    ps_jobstore_free(front);
    ps_jobstore_free(worker);
    free_upload(&u);
}

/* A cancel on one store stops the job the other store's worker runs; a
 * queued job is cancelled at once. */
static void test_cancel_reaches_worker(void) {
    if (!need_server()) SKIP("%s", skip_why);
    upload slow;
    ps_api_error err;
    ps_job_status st;
    char id[96], queued[96];
    REQUIRE(make_upload(&slow, SLOW_POINTS, 1) == 0);
    ps_jobstore *front = open_store(0), *worker = open_store(1);
    REQUIRE(front && worker);
    REQUIRE(ps_jobstore_submit(front, &slow.up, id, sizeof id, &err) == 0);
    REQUIRE(ps_jobstore_submit(front, &slow.up, queued, sizeof queued, &err) == 0);
    REQUIRE(wait_state(front, id, PS_JOB_RUNNING, 20) == PS_JOB_RUNNING);
    CHECK(ps_jobstore_cancel(front, queued, &st, &err) == 0 && st.state == PS_JOB_CANCELLED);
    double t0 = now_s();
    CHECK(ps_jobstore_cancel(front, id, &st, &err) == 0);
    CHECK(wait_state(front, id, PS_JOB_CANCELLED, 5) == PS_JOB_CANCELLED);
    CHECK_MSG(now_s() - t0 < 3, "cancel took %.1f s", now_s() - t0);
    ps_job_doc doc;
    CHECK(ps_jobstore_result(worker, id, &doc, &err) == -1 && err.http_status == 409);
    ps_jobstore_free(front);
    ps_jobstore_free(worker);
    free_upload(&slow);
}

/* Submits u on front, records prior_losses earlier losses, and lets a
 * consumer that never renews ("ghost": a SIGKILLed replica) take it.
 * Returns 0, or -1 when Redis refused. */
static int submit_abandoned(ps_jobstore *front, upload *u, char *id, size_t cap, int prior_losses) {
    ps_api_error err;
    if (ps_jobstore_submit(front, &u->up, id, cap, &err)) return -1;
    redisContext *c = ps_test_redis_connect(&server);
    if (!c) return -1;
    redisReply *r = redisCommand(c, "HSET pointseg:job:%s losses %d", id, prior_losses);
    int ok = r && r->type == REDIS_REPLY_INTEGER;
    if (r) freeReplyObject(r);
    r = redisCommand(c, "XREADGROUP GROUP pointseg ghost COUNT 10 STREAMS pointseg:jobs >");
    ok = ok && r && r->type == REDIS_REPLY_ARRAY;
    if (r) freeReplyObject(r);
    redisFree(c);
    return ok ? 0 : -1;
}

/* What happened to an abandoned job once a store with a worker came up. */
typedef struct abandoned {
    char id[96];
    ps_job_status status;      /* final (or last seen) */
    ps_jobstore_stats stats;   /* of the store that took it over */
    double seconds;            /* from the worker's start to the end */
    long long losses;
    int answer_lost;           /* behind a relay: its answer was cut */
} abandoned;

/* A job taken by a consumer that goes silent (a SIGKILLed replica) after
 * prior_losses earlier losses; then a store with one worker starts, on the
 * Redis at worker_port. */
static int run_abandoned_via(int worker_port, int prior_losses, ps_job_state want, abandoned *out) {
    upload u;
    ps_api_error err;
    memset(out, 0, sizeof *out);
    if (make_upload(&u, SMALL_POINTS, 0)) return -1;
    ps_jobstore *front = open_store(0), *worker = NULL;
    int rc = front && submit_abandoned(front, &u, out->id, sizeof out->id, prior_losses) == 0 ? 0 : -1;
    double t0 = now_s();
    if (rc == 0 && (worker = open_store_on(worker_port, 1, 60, (size_t)1 << 30))) {
        wait_state(front, out->id, want, 30);
        out->seconds = now_s() - t0;
        rc = ps_jobstore_status(front, out->id, &out->status, &err);
        ps_jobstore_get_stats(worker, &out->stats);
        out->losses = hash_integer(out->id, "losses");
    }
    ps_jobstore_free(worker);
    ps_jobstore_free(front);
    free_upload(&u);
    return worker ? rc : -1;
}

static int run_abandoned(int prior_losses, ps_job_state want, abandoned *out) {
    return run_abandoned_via(server.port, prior_losses, want, out);
}

/* The same with the worker behind a relay that loses the answer to the
 * first call holding `marker` (after Redis ran it); out->answer_lost says
 * whether it did. */
static int run_abandoned_behind_cut(const char *marker, int prior_losses, ps_job_state want,
                                    abandoned *out) {
    ps_reply_cut *cut = ps_reply_cut_start(server.port, marker);
    if (!cut) return -1;
    int rc = run_abandoned_via(ps_reply_cut_port(cut), prior_losses, want, out);
    out->answer_lost = ps_reply_cut_done(cut);
    ps_reply_cut_stop(cut);
    return rc;
}

/* The store's worker takes the job over once the lease lapses, and
 * finishes it. */
static void test_lapsed_lease_is_taken_over(void) {
    if (!need_server()) SKIP("%s", skip_why);
    abandoned a;
    REQUIRE(run_abandoned(0, PS_JOB_DONE, &a) == 0);
    CHECK(a.status.state == PS_JOB_DONE);
    CHECK_MSG(a.seconds >= LEASE_S - 0.5, "taken over after %.1f s, before the lease lapsed", a.seconds);
    CHECK(a.losses == 1);
    CHECK(a.stats.shared && a.stats.reachable && a.stats.reclaimed >= 1 && a.stats.pending == 0);
}

/* A job that already lost two workers and loses a third is failed, saying
 * why, and not run again. */
static void test_third_loss_fails_job(void) {
    if (!need_server()) SKIP("%s", skip_why);
    abandoned a;
    REQUIRE(run_abandoned(2, PS_JOB_FAILED, &a) == 0);
    CHECK(a.status.state == PS_JOB_FAILED && a.status.started == 0 && a.status.error_status == 500);
    CHECK_MSG(strstr(a.status.error, "lost its worker 3 times") != NULL, "error: %s", a.status.error);
    CHECK(a.losses == 3 && a.stats.lost_failed == 1);
    ps_jobstore *front = open_store(0);
    REQUIRE(front);
    ps_job_doc doc;
    ps_api_error err;
    CHECK(ps_jobstore_result(front, a.id, &doc, &err) == -1 && err.http_status == 500 &&
          strstr(err.message, "lost its worker"));
    ps_jobstore_free(front);
}

/* A job that lost one worker is taken over, and the answer to the
 * takeover's START call is lost after Redis ran it (a call timeout): the
 * link runs it again on a new connection.  The job counts two losses, not
 * three, and runs to its end. */
static void test_takeover_retried_counts_one_loss(void) {
    if (!need_server()) SKIP("%s", skip_why);
    abandoned a;
    REQUIRE(run_abandoned_behind_cut("HINCRBY", 1, PS_JOB_DONE, &a) == 0);
    CHECK_MSG(a.answer_lost, "the takeover's answer was not lost: the test did not test");
    CHECK_MSG(a.status.state == PS_JOB_DONE, "state %s: %s", ps_job_state_name(a.status.state),
              a.status.error);
    CHECK_MSG(a.losses == 2, "losses %lld", a.losses);
    CHECK(a.stats.reclaimed == 1 && a.stats.lost_failed == 0);
}

/* A job is queued, then a store starts whose worker reaches Redis through a
 * relay that loses the answer to the first call holding `marker` (after
 * Redis ran it); waits for the job's end.  With lapsed, the job is first
 * taken by a silent consumer and its lease left to lapse. */
static int run_behind_cut(const char *marker, int lapsed, abandoned *out) {
    upload u;
    ps_api_error err;
    memset(out, 0, sizeof *out);
    if (make_upload(&u, SMALL_POINTS, 0)) return -1;
    ps_jobstore *front = open_store(0), *worker = NULL;
    int rc = !front ? -1
             : lapsed ? submit_abandoned(front, &u, out->id, sizeof out->id, 0)
                      : ps_jobstore_submit(front, &u.up, out->id, sizeof out->id, &err);
    if (rc == 0 && lapsed) ps_test_sleep_ms(LEASE_S * 1000 + 300);
    ps_reply_cut *cut = rc == 0 ? ps_reply_cut_start(server.port, marker) : NULL;
    double t0 = now_s();
    if (cut && (worker = open_store_on(ps_reply_cut_port(cut), 1, 60, (size_t)1 << 30))) {
        wait_state(front, out->id, PS_JOB_DONE, 30);
        out->seconds = now_s() - t0;
        rc = ps_jobstore_status(front, out->id, &out->status, &err);
        ps_jobstore_get_stats(worker, &out->stats);
        out->losses = hash_integer(out->id, "losses");
        out->answer_lost = ps_reply_cut_done(cut);
    }
    ps_jobstore_free(worker);
    if (cut) ps_reply_cut_stop(cut);
    ps_jobstore_free(front);
    free_upload(&u);
    return worker ? rc : -1;
}

/* A job that lost two workers loses a third, and the answer to the START
 * call that fails it is lost (after Redis ran it): the retried call finds
 * its own take and says so.  Three losses, and the replica's
 * lost_failed counter counts the job (it did not when the retry saw only
 * a failed job). */
static void test_lost_failure_answer_still_counted(void) {
    if (!need_server()) SKIP("%s", skip_why);
    abandoned a;
    REQUIRE(run_abandoned_behind_cut("HINCRBY", 2, PS_JOB_FAILED, &a) == 0);
    CHECK_MSG(a.answer_lost, "the START's answer was not lost: the test did not test");
    CHECK(a.status.state == PS_JOB_FAILED && strstr(a.status.error, "lost its worker 3 times"));
    CHECK_MSG(a.losses == 3, "losses %lld", a.losses);
    CHECK_MSG(a.stats.reclaimed == 1 && a.stats.lost_failed == 1, "reclaimed %llu, lost_failed %llu",
              (unsigned long long)a.stats.reclaimed, (unsigned long long)a.stats.lost_failed);
}

/* The answer to the worker's read of a new job is lost after Redis handed
 * it the job: the worker finds the job in its own pending list and runs it
 * at once, counting no loss (before, the job waited for its lease to lapse
 * and was taken over as lost). */
static void test_lost_read_runs_without_loss(void) {
    if (!need_server()) SKIP("%s", skip_why);
    abandoned a;
    REQUIRE(run_behind_cut("XREADGROUP", 0, &a) == 0);
    CHECK_MSG(a.answer_lost, "the read's answer was not lost: the test did not test");
    CHECK_MSG(a.status.state == PS_JOB_DONE, "state %s: %s", ps_job_state_name(a.status.state), a.status.error);
    CHECK_MSG(a.losses == 0, "losses %lld", a.losses);
    CHECK(a.stats.reclaimed == 0 && a.stats.lost_failed == 0);
}

/* The answer to a takeover (XAUTOCLAIM of a lapsed job) is lost after
 * Redis gave the job to the worker: the worker runs it from its own pending
 * list as a takeover (one loss), without waiting for a second lease. */
static void test_lost_takeover_runs_at_once(void) {
    if (!need_server()) SKIP("%s", skip_why);
    abandoned a;
    REQUIRE(run_behind_cut("XAUTOCLAIM", 1, &a) == 0);
    CHECK_MSG(a.answer_lost, "the takeover's answer was not lost: the test did not test");
    CHECK_MSG(a.status.state == PS_JOB_DONE, "state %s: %s", ps_job_state_name(a.status.state), a.status.error);
    CHECK_MSG(a.losses == 1, "losses %lld", a.losses);
    CHECK(a.stats.reclaimed == 1 && a.stats.lost_failed == 0);
    CHECK_MSG(a.seconds < LEASE_S - 0.5, "run %.1f s after the takeover: it waited for a second lease", a.seconds);
}

/* Redis stops: every call is a prompt 503; it comes back (same data, it
 * keeps an append-only file): the stores recover alone and run new jobs. */
static void test_redis_down_then_back(void) {
    if (!need_server()) SKIP("%s", skip_why);
    upload u;
    ps_api_error err;
    ps_job_status st;
    char id[96], before[96];
    REQUIRE(make_upload(&u, SMALL_POINTS, 0) == 0);
    ps_jobstore *store = open_store(1);
    REQUIRE(store);
    REQUIRE(ps_jobstore_submit(store, &u.up, before, sizeof before, &err) == 0);
    REQUIRE(wait_state(store, before, PS_JOB_DONE, 30) == PS_JOB_DONE);
    ps_test_redis_stop(&server);
    double t0 = now_s();
    CHECK(ps_jobstore_ready(store, &err) == -1 && err.http_status == 503);
    CHECK(ps_jobstore_submit(store, &u.up, id, sizeof id, &err) == -1 && err.http_status == 503);
    CHECK(strstr(err.message, "unreachable") != NULL);
    CHECK(ps_jobstore_status(store, before, &st, &err) == -1 && err.http_status == 503);
    CHECK_MSG(now_s() - t0 < 3, "the 503s took %.1f s", now_s() - t0);
    ps_jobstore_stats stats;
    ps_jobstore_get_stats(store, &stats);
    CHECK(stats.shared && !stats.reachable);
    REQUIRE(ps_test_redis_restart(&server) == 0);
    int ready = 0;
    for (double end = now_s() + 5; !ready && now_s() < end; ps_test_sleep_ms(100))
        ready = ps_jobstore_ready(store, &err) == 0;
    CHECK(ready);
    CHECK(ps_jobstore_status(store, before, &st, &err) == 0 && st.state == PS_JOB_DONE);
    REQUIRE(ps_jobstore_submit(store, &u.up, id, sizeof id, &err) == 0);
    CHECK(wait_state(store, id, PS_JOB_DONE, 30) == PS_JOB_DONE);
    ps_jobstore_free(store);
    free_upload(&u);
}

/* A Redis restart between two calls breaks the pooled connection: the next
 * call reconnects and succeeds instead of answering 503. */
static void test_restart_between_calls(void) {
    if (!need_server()) SKIP("%s", skip_why);
    ps_api_error err;
    ps_jobstore *store = open_store(0);
    REQUIRE(store);
    CHECK(ps_jobstore_ready(store, &err) == 0);
    REQUIRE(ps_test_redis_restart(&server) == 0);
    CHECK_MSG(ps_jobstore_ready(store, &err) == 0, "first call after the restart: %d %s",
              err.http_status, err.message);
    ps_jobstore_free(store);
}

/* The entries of the shared stream that name job id. */
static int stream_entries_of(const char *id) {
    redisContext *c = ps_test_redis_connect(&server);
    redisReply *r = c ? redisCommand(c, "XRANGE pointseg:jobs - +") : NULL;
    int n = 0;
    for (size_t i = 0; r && r->type == REDIS_REPLY_ARRAY && i < r->elements; i++) {
        const redisReply *fields = r->element[i]->element[1];
        n += fields->elements == 2 && !strcmp(fields->element[1]->str, id);
    }
    if (r) freeReplyObject(r);
    if (c) redisFree(c);
    return n;
}

static void *wake_redis_later(void *arg) {
    (void)arg;
    ps_test_sleep_ms(2500);
    kill(server.pid, SIGCONT);
    return NULL;
}

/* Submits u on s while Redis is stopped (SIGSTOP) for 2.5 s, past the
 * store's 2 s call timeout; the submit's answer. */
static int submit_during_stall(ps_jobstore *s, upload *u, char *id, size_t cap, ps_api_error *err) {
    pthread_t waker;
    if (kill(server.pid, SIGSTOP) || pthread_create(&waker, NULL, wake_redis_later, NULL)) {
        kill(server.pid, SIGCONT);
        return ps_api_fail(err, 500, "cannot stall Redis");
    }
    int rc = ps_jobstore_submit(s, &u->up, id, cap, err);
    pthread_join(waker, NULL);
    return rc;
}

/* Redis stalls past the call timeout while a job is submitted: the call
 * times out, the store retries on a new connection, and Redis, awake
 * again, runs both.  The job is queued once, and the submit succeeds. */
static void test_submit_retried_after_stall_queues_once(void) {
    if (!need_server()) SKIP("%s", skip_why);
    upload u;
    ps_api_error err;
    char id[96];
    REQUIRE(make_upload(&u, SMALL_POINTS, 0) == 0);
    ps_jobstore *front = open_store(0);
    REQUIRE(front && ps_jobstore_ready(front, &err) == 0); /* the pooled connection is open */
    int rc = submit_during_stall(front, &u, id, sizeof id, &err);
    CHECK_MSG(rc == 0, "submit: %d %s", err.http_status, err.message);
    CHECK_MSG(rc || stream_entries_of(id) == 1, "job %s queued %d times", id, stream_entries_of(id));
    ps_jobstore_free(front);
    free_upload(&u);
}

/* Shutdown with a job running past the drain time: the job goes back to the
 * queue (not counted as a loss) and another store's worker finishes it. */
static void test_drain_hands_back(void) {
    if (!need_server()) SKIP("%s", skip_why);
    upload slow;
    ps_api_error err;
    char id[96];
    REQUIRE(make_upload(&slow, SLOW_POINTS, 1) == 0);
    ps_jobstore *leaving = open_store(1);
    REQUIRE(leaving);
    REQUIRE(ps_jobstore_submit(leaving, &slow.up, id, sizeof id, &err) == 0);
    REQUIRE(wait_state(leaving, id, PS_JOB_RUNNING, 20) == PS_JOB_RUNNING);
    ps_jobstore_drain(leaving, 0.2);
    ps_job_status st;
    CHECK(ps_jobstore_status(leaving, id, &st, &err) == 0 && st.state == PS_JOB_QUEUED);
    ps_jobstore_stats stats;
    ps_jobstore_get_stats(leaving, &stats);
    CHECK(stats.handed_back == 1 && stats.queue_length == 1);
    ps_jobstore *staying = open_store(1);
    REQUIRE(staying);
    CHECK(wait_state(staying, id, PS_JOB_DONE, 120) == PS_JOB_DONE);
    CHECK(hash_integer(id, "losses") == 0);
    ps_jobstore_free(staying);
    ps_jobstore_free(leaving);
    free_upload(&slow);
}

static size_t queue_length(ps_jobstore *s) {
    ps_jobstore_stats stats;
    ps_jobstore_get_stats(s, &stats);
    return stats.queue_length;
}

/* A job cancelled while queued leaves the shared queue at once (its stream
 * entry goes), also one a leaving replica handed back: the queue's length
 * counts only jobs that will run. */
static void test_cancel_leaves_shared_queue(void) {
    if (!need_server()) SKIP("%s", skip_why);
    upload small, slow;
    ps_api_error err;
    ps_job_status st;
    char kept[96], cancelled[96], handed[96];
    REQUIRE(make_upload(&small, SMALL_POINTS, 0) == 0 && make_upload(&slow, SLOW_POINTS, 1) == 0);
    ps_jobstore *front = open_store(0), *leaving = open_store(1);
    REQUIRE(front && leaving);
    REQUIRE(ps_jobstore_submit(leaving, &slow.up, handed, sizeof handed, &err) == 0);
    REQUIRE(wait_state(leaving, handed, PS_JOB_RUNNING, 20) == PS_JOB_RUNNING);
    ps_jobstore_drain(leaving, 0.2);
    size_t before = queue_length(front);
    REQUIRE(ps_jobstore_submit(front, &small.up, kept, sizeof kept, &err) == 0);
    REQUIRE(ps_jobstore_submit(front, &small.up, cancelled, sizeof cancelled, &err) == 0);
    CHECK(queue_length(front) == before + 2);
    CHECK(ps_jobstore_cancel(front, cancelled, &st, &err) == 0 && st.state == PS_JOB_CANCELLED);
    CHECK(ps_jobstore_cancel(front, handed, &st, &err) == 0 && st.state == PS_JOB_CANCELLED);
    CHECK_MSG(queue_length(front) == before, "queue length %zu, want %zu", queue_length(front), before);
    CHECK(stream_entries_of(cancelled) == 0 && stream_entries_of(handed) == 0 && stream_entries_of(kept) == 1);
    ps_jobstore *worker = open_store(1);
    REQUIRE(worker);
    CHECK(wait_state(front, kept, PS_JOB_DONE, 30) == PS_JOB_DONE);
    CHECK(ps_jobstore_status(front, cancelled, &st, &err) == 0 && st.state == PS_JOB_CANCELLED);
    ps_jobstore_free(worker);
    ps_jobstore_free(leaving);
    ps_jobstore_free(front);
    free_upload(&small);
    free_upload(&slow);
}

/* Runs the upload on s to the end; 0 when it is done. */
static int run_to_done(ps_jobstore *s, upload *u, char *id, size_t cap) {
    ps_api_error err;
    if (ps_jobstore_submit(s, &u->up, id, cap, &err)) return -1;
    return wait_state(s, id, PS_JOB_DONE, 30) == PS_JOB_DONE ? 0 : -1;
}

static long long kept_results(void) {
    redisContext *c = ps_test_redis_connect(&server);
    redisReply *r = c ? redisCommand(c, "ZCARD pointseg:results") : NULL;
    long long n = r && r->type == REDIS_REPLY_INTEGER ? r->integer : -1;
    if (r) freeReplyObject(r);
    if (c) redisFree(c);
    return n;
}

/* Four results where two and a half fit: the two oldest jobs are gone
 * (404, as in the in-process store), the two newest kept, and the shared
 * figure is their bytes.  Results past their TTL leave the sum. */
static void test_result_byte_budget(void) {
    if (!need_server()) SKIP("%s", skip_why);
    upload u;
    ps_api_error err;
    ps_job_status st;
    ps_jobstore_stats stats;
    char ids[4][96];
    size_t doc_len;
    REQUIRE(make_upload(&u, SMALL_POINTS, 0) == 0);
    free(local_labels(&u, &doc_len));
    ps_jobstore *store = open_store_keeping(1, 60, doc_len * 5 / 2);
    REQUIRE(store);
    for (int i = 0; i < 4; i++) REQUIRE(run_to_done(store, &u, ids[i], sizeof ids[i]) == 0);
    for (int i = 0; i < 2; i++)
        CHECK(ps_jobstore_status(store, ids[i], &st, &err) == -1 && err.http_status == 404);
    for (int i = 2; i < 4; i++) {
        ps_job_doc doc;
        int found = ps_jobstore_result(store, ids[i], &doc, &err) == 0;
        CHECK(found && doc.len == doc_len);
        if (found) free(doc.doc);
    }
    ps_jobstore_get_stats(store, &stats);
    CHECK_MSG(stats.result_bytes == 2 * doc_len, "%zu bytes kept, not 2 x %zu", stats.result_bytes, doc_len);
    CHECK(kept_results() == 2);
    ps_jobstore_free(store);
    store = open_store_keeping(1, 1, (size_t)1 << 30);
    REQUIRE(store);
    REQUIRE(run_to_done(store, &u, ids[0], sizeof ids[0]) == 0);
    ps_test_sleep_ms(1500);
    REQUIRE(run_to_done(store, &u, ids[1], sizeof ids[1]) == 0);
    ps_jobstore_get_stats(store, &stats);
    CHECK_MSG(stats.result_bytes == doc_len, "%zu bytes kept, not %zu", stats.result_bytes, doc_len);
    CHECK(kept_results() == 1);
    ps_jobstore_free(store);
    free_upload(&u);
}

PS_TEST_MAIN(TEST(test_url_parse), TEST(test_any_store_serves_any_job), TEST(test_cancel_reaches_worker),
             TEST(test_lapsed_lease_is_taken_over), TEST(test_third_loss_fails_job),
             TEST(test_takeover_retried_counts_one_loss), TEST(test_lost_failure_answer_still_counted),
             TEST(test_lost_read_runs_without_loss),
             TEST(test_lost_takeover_runs_at_once),
             TEST(test_redis_down_then_back), TEST(test_restart_between_calls),
             TEST(test_submit_retried_after_stall_queues_once),
             TEST(test_drain_hands_back), TEST(test_cancel_leaves_shared_queue), TEST(test_result_byte_budget))
