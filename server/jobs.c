/* jobs.c: the in-process job backend: a bounded ring of queued jobs, a fixed
 * pool of worker threads running them (job_runner.c), and the registry of
 * jobs by id. */
#include "jobs.h"

#include "deadline.h"
#include "job_runner.h"
#include "jobstore.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

struct ps_job {
    ps_jobs *owner;
    char id[96];
    int refs;                   /* under owner->lock, like every field below */
    ps_job_state state;
    ps_phase phase;
    double fraction;
    double created, started, finished;
    volatile int cancel;        /* read by the core with relaxed loads; raised with
                                   ps_cancel_raise */
    ps_pointset points;         /* freed once the job is final */
    size_t n_points;
    ps_request_params params;
    ps_job_done_fn on_done;
    void *user;
    int waited_for;             /* submitted with on_done: not kept once final */
    char *doc;                  /* DONE: the encoded document */
    size_t doc_len;
    const char *media_type;
    int error_status;
    char error[512];
    ps_job *prev, *next;        /* registry, oldest first */
};

struct ps_jobs {
    ps_jobs_config cfg;
    char prefix[64];
    pthread_mutex_t lock;
    pthread_cond_t work;        /* a job was queued, or stopping */
    pthread_cond_t idle;        /* a job finished */
    ps_job **ring;              /* #cfg.queue_size */
    size_t head, count;
    pthread_t *threads;
    int n_threads;
    int stopping;
    size_t running;
    ps_job *first, *last;
    size_t registered;
    unsigned long long points_segmented, n_done, n_failed, n_cancelled;
};

static double now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

const char *ps_job_state_name(ps_job_state s) {
    static const char *const names[] = {"queued", "running", "done", "failed", "cancelled"};
    return (unsigned)s < sizeof names / sizeof names[0] ? names[s] : "unknown";
}

static void job_free(ps_job *job) {
    ps_pointset_free(&job->points);
    free(job->doc);
    free(job);
}

/* Drops one reference; the caller holds the lock.  Returns the job when it
 * must be freed (outside the lock). */
static ps_job *unref_locked(ps_job *job) {
    return --job->refs == 0 ? job : NULL;
}

/* Drops one reference; the caller holds the lock.  When it was the last,
 * pushes the job onto *dead (chained by next) for free_chain outside it. */
static void release_locked(ps_job *job, ps_job **dead) {
    if (!unref_locked(job)) return;
    job->next = *dead;
    *dead = job;
}

void ps_job_release(ps_job *job) {
    if (!job) return;
    ps_jobs *q = job->owner;
    pthread_mutex_lock(&q->lock);
    ps_job *dead = unref_locked(job);
    pthread_mutex_unlock(&q->lock);
    if (dead) job_free(dead);
}

static void unlink_locked(ps_jobs *q, ps_job *job) {
    if (job->prev) job->prev->next = job->next;
    else q->first = job->next;
    if (job->next) job->next->prev = job->prev;
    else q->last = job->prev;
    job->prev = job->next = NULL;
    q->registered--;
}

static int is_final(ps_job_state s) { return s >= PS_JOB_DONE; }

/* 1 when a finished job must leave the registry: its request took its
 * result, or it is past its time. */
static int expired(const ps_job *j, double limit) { return j->waited_for || j->finished <= limit; }

/* Unlinks finished jobs that expired, or beyond the count or the byte
 * budget, oldest first, onto *dead (chained by next) for freeing outside
 * the lock. */
static void purge_locked(ps_jobs *q, ps_job **dead) {
    size_t finished = 0, bytes = 0;
    double limit = now_seconds() - q->cfg.ttl_seconds;
    for (ps_job *j = q->first; j; j = j->next)
        if (is_final(j->state)) finished++, bytes += j->doc_len;
    for (ps_job *j = q->first, *next; j; j = next) {
        next = j->next;
        if (!is_final(j->state)) continue;
        if (!expired(j, limit) && finished <= (size_t)q->cfg.max_finished && bytes <= q->cfg.max_kept_bytes)
            continue;
        finished--;
        bytes -= j->doc_len;
        unlink_locked(q, j);
        release_locked(j, dead);
    }
}

static void free_chain(ps_job *dead) {
    while (dead) {
        ps_job *next = dead->next;
        job_free(dead);
        dead = next;
    }
}

static void report_progress(void *user, ps_phase phase, double fraction) {
    ps_job *job = user;
    pthread_mutex_lock(&job->owner->lock);
    job->phase = phase;
    job->fraction = fraction;
    pthread_mutex_unlock(&job->owner->lock);
}

static ps_job_state job_state_of(ps_run_state s) {
    return s == PS_RUN_DONE ? PS_JOB_DONE : s == PS_RUN_FAILED ? PS_JOB_FAILED : PS_JOB_CANCELLED;
}

/* Runs the job outside the lock (a status read meanwhile sees RUNNING). */
static void run_job(ps_job *job, ps_run_outcome *out) {
    ps_control ctl = {report_progress, job, &job->cancel};
    ps_job_run(&job->points, &job->params, &ctl, out);
}

/* Records the outcome in the job; the caller holds the lock, so that a
 * status read never meets a half-written error.  Returns the final state. */
static ps_job_state record_outcome_locked(ps_job *job, const ps_run_outcome *out) {
    job->doc = out->doc;
    job->doc_len = out->doc_len;
    job->media_type = out->media_type;
    job->error_status = out->error_status;
    memcpy(job->error, out->error, sizeof job->error);
    return job_state_of(out->state);
}

/* Records a final state; the caller holds the lock.  Returns the callback
 * to call outside the lock (user in *user). */
static ps_job_done_fn finish_locked(ps_jobs *q, ps_job *job, ps_job_state state, void **user) {
    ps_job_done_fn fn = job->on_done;
    job->state = state;
    job->finished = now_seconds();
    if (state == PS_JOB_DONE) {
        q->n_done++;
        q->points_segmented += job->n_points;
    } else {
        q->n_failed += state == PS_JOB_FAILED;
        q->n_cancelled += state == PS_JOB_CANCELLED;
    }
    ps_pointset_free(&job->points);
    *user = job->user;
    job->on_done = NULL;
    pthread_cond_broadcast(&q->idle);
    return fn;
}

/* Waits for the next queued job; NULL when stopping and the queue is empty. */
static ps_job *next_job_locked(ps_jobs *q) {
    while (!q->count && !q->stopping) pthread_cond_wait(&q->work, &q->lock);
    if (!q->count) return NULL;
    ps_job *job = q->ring[q->head];
    q->head = (q->head + 1) % (size_t)q->cfg.queue_size;
    q->count--;
    return job;
}

/* Takes a queued job out of the ring, the others keeping their order, so
 * that its slot is free at once.  The ring's reference is dropped; the
 * caller's and the registry's remain. */
static void dequeue_locked(ps_jobs *q, ps_job *job) {
    size_t cap = (size_t)q->cfg.queue_size, i = 0;
    while (i < q->count && q->ring[(q->head + i) % cap] != job) i++;
    if (i == q->count) return;
    for (; i + 1 < q->count; i++) q->ring[(q->head + i) % cap] = q->ring[(q->head + i + 1) % cap];
    q->count--;
    job->refs--;
}

static void *worker_main(void *arg) {
    ps_jobs *q = arg;
    pthread_mutex_lock(&q->lock);
    for (ps_job *job; (job = next_job_locked(q));) {
        void *user;
        ps_job_done_fn done;
        ps_job *dead = NULL;
        if (job->cancel) {
            done = finish_locked(q, job, PS_JOB_CANCELLED, &user);
        } else {
            job->state = PS_JOB_RUNNING;
            job->started = now_seconds();
            q->running++;
            pthread_mutex_unlock(&q->lock);
            ps_run_outcome out;
            run_job(job, &out);
            pthread_mutex_lock(&q->lock);
            q->running--;
            done = finish_locked(q, job, record_outcome_locked(job, &out), &user);
        }
        purge_locked(q, &dead);
        release_locked(job, &dead);
        pthread_mutex_unlock(&q->lock);
        if (done) done(user);
        free_chain(dead);
        pthread_mutex_lock(&q->lock);
    }
    pthread_mutex_unlock(&q->lock);
    return NULL;
}

ps_jobs *ps_jobs_start(const ps_jobs_config *cfg) {
    ps_jobs *q = calloc(1, sizeof *q);
    if (!q) return NULL;
    q->cfg = *cfg;
    snprintf(q->prefix, sizeof q->prefix, "%s", cfg->id_prefix ? cfg->id_prefix : "");
    q->ring = calloc((size_t)cfg->queue_size, sizeof *q->ring);
    q->threads = calloc((size_t)cfg->workers, sizeof *q->threads);
    pthread_mutex_init(&q->lock, NULL);
    pthread_cond_init(&q->work, NULL);
    pthread_cond_init(&q->idle, NULL);
    if (!q->ring || !q->threads) {
        ps_jobs_free(q);
        return NULL;
    }
    for (; q->n_threads < cfg->workers; q->n_threads++)
        if (pthread_create(&q->threads[q->n_threads], NULL, worker_main, q)) break;
    if (q->n_threads < cfg->workers) {
        ps_jobs_drain(q, 0);
        ps_jobs_free(q);
        return NULL;
    }
    return q;
}

static ps_job *new_job(ps_jobs *q, ps_pointset *points, const ps_request_params *params,
                       ps_job_done_fn on_done, void *user) {
    ps_job *job = calloc(1, sizeof *job);
    if (!job) return NULL;
    job->owner = q;
    ps_job_make_id(q->prefix, job->id, sizeof job->id);
    job->state = PS_JOB_QUEUED;
    job->created = now_seconds();
    job->points = *points;
    job->n_points = points->n;
    memset(points, 0, sizeof *points);
    job->params = *params;
    job->on_done = on_done;
    job->user = user;
    job->waited_for = on_done != NULL;
    job->refs = 3; /* registry, ring, caller */
    return job;
}

static int refuses_locked(const ps_jobs *q, ps_api_error *err) {
    if (q->stopping) return ps_api_fail(err, 503, "the service is shutting down");
    if (q->count >= (size_t)q->cfg.queue_size)
        return ps_api_fail(err, 503, "the job queue is full (%d waiting)", q->cfg.queue_size);
    return 0;
}

int ps_jobs_submit(ps_jobs *q, ps_pointset *points, const ps_request_params *params,
                   ps_job_done_fn on_done, void *user, ps_job **out, ps_api_error *err) {
    ps_job *dead = NULL;
    *out = NULL;
    pthread_mutex_lock(&q->lock);
    int refused = refuses_locked(q, err);
    ps_job *job = refused ? NULL : new_job(q, points, params, on_done, user);
    if (!job) {
        pthread_mutex_unlock(&q->lock);
        ps_pointset_free(points);
        return refused ? -1 : ps_api_fail(err, 500, "out of memory");
    }
    q->ring[(q->head + q->count) % (size_t)q->cfg.queue_size] = job;
    q->count++;
    job->prev = q->last;
    if (q->last) q->last->next = job;
    else q->first = job;
    q->last = job;
    q->registered++;
    purge_locked(q, &dead);
    *out = job; /* before any worker can finish it and call on_done */
    pthread_cond_signal(&q->work);
    pthread_mutex_unlock(&q->lock);
    free_chain(dead);
    return 0;
}

ps_job *ps_jobs_find(ps_jobs *q, const char *id) {
    ps_job *dead = NULL, *found = NULL;
    pthread_mutex_lock(&q->lock);
    purge_locked(q, &dead);
    for (ps_job *j = q->first; j && !found; j = j->next)
        if (!strcmp(j->id, id)) found = j;
    if (found) found->refs++;
    pthread_mutex_unlock(&q->lock);
    free_chain(dead);
    return found;
}

const char *ps_job_id(const ps_job *job) { return job->id; }

void ps_job_get_status(ps_job *job, ps_job_status *st) {
    pthread_mutex_lock(&job->owner->lock);
    memset(st, 0, sizeof *st);
    memcpy(st->id, job->id, sizeof st->id);
    st->state = job->state;
    st->phase = job->phase;
    st->fraction = job->fraction;
    st->created = job->created;
    st->started = job->started;
    st->finished = job->finished;
    st->n_points = job->n_points;
    st->error_status = job->error_status;
    memcpy(st->error, job->error, sizeof st->error);
    pthread_mutex_unlock(&job->owner->lock);
}

const char *ps_job_result(ps_job *job, size_t *len, const char **media_type) {
    pthread_mutex_lock(&job->owner->lock);
    int done = job->state == PS_JOB_DONE;
    pthread_mutex_unlock(&job->owner->lock);
    if (!done) return NULL;
    *len = job->doc_len;
    *media_type = job->media_type;
    return job->doc;
}

void ps_job_cancel(ps_job *job) {
    ps_jobs *q = job->owner;
    ps_job_done_fn done = NULL;
    void *user = NULL;
    pthread_mutex_lock(&q->lock);
    ps_cancel_raise(&job->cancel);
    if (job->state == PS_JOB_QUEUED) {
        dequeue_locked(q, job);
        done = finish_locked(q, job, PS_JOB_CANCELLED, &user);
    }
    pthread_mutex_unlock(&q->lock);
    if (done) done(user);
}

void ps_jobs_get_stats(ps_jobs *q, ps_jobs_stats *st) {
    pthread_mutex_lock(&q->lock);
    st->queued = q->count;
    st->running = q->running;
    st->kept = q->registered;
    st->kept_bytes = 0;
    for (ps_job *j = q->first; j; j = j->next) st->kept_bytes += is_final(j->state) ? j->doc_len : 0;
    st->capacity = (size_t)q->cfg.queue_size;
    st->points_segmented = q->points_segmented;
    st->jobs_done = q->n_done;
    st->jobs_failed = q->n_failed;
    st->jobs_cancelled = q->n_cancelled;
    pthread_mutex_unlock(&q->lock);
}

int ps_jobs_refuses(ps_jobs *q, ps_api_error *err) {
    pthread_mutex_lock(&q->lock);
    int refused = refuses_locked(q, err);
    pthread_mutex_unlock(&q->lock);
    return refused;
}

static void wait_idle_locked(ps_jobs *q, double seconds) {
    double deadline = now_seconds() + seconds;
    while ((q->count || q->running) && now_seconds() < deadline) {
        struct timespec ts = ps_deadline_in_ms(100);
        pthread_cond_timedwait(&q->idle, &q->lock, &ts);
    }
}

void ps_jobs_stop_taking(ps_jobs *q) {
    pthread_mutex_lock(&q->lock);
    q->stopping = 1;
    pthread_cond_broadcast(&q->work);
    pthread_mutex_unlock(&q->lock);
}

void ps_jobs_drain(ps_jobs *q, double drain_seconds) {
    ps_jobs_stop_taking(q);
    pthread_mutex_lock(&q->lock);
    wait_idle_locked(q, drain_seconds);
    for (ps_job *j = q->first; j; j = j->next) ps_cancel_raise(&j->cancel);
    pthread_mutex_unlock(&q->lock);
    for (int i = 0; i < q->n_threads; i++) pthread_join(q->threads[i], NULL);
    q->n_threads = 0;
}

void ps_jobs_free(ps_jobs *q) {
    if (!q) return;
    ps_job *dead = NULL;
    while (q->first) {
        ps_job *j = q->first;
        unlink_locked(q, j);
        release_locked(j, &dead);
    }
    free_chain(dead);
    pthread_mutex_destroy(&q->lock);
    pthread_cond_destroy(&q->work);
    pthread_cond_destroy(&q->idle);
    free(q->ring);
    free(q->threads);
    free(q);
}
