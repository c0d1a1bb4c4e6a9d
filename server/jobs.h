/*
 * jobs.h: the job queue behind the daemon: a bounded queue of segmentation
 * jobs served by a fixed pool of worker threads, and a registry of jobs by
 * id (finished jobs are kept for a time, a count and a byte budget, then
 * freed).  A job submitted with an on_done callback belongs to a waiting
 * request: it leaves the registry once final, and its result is freed with
 * the request's reference, once the answer is sent.
 *
 * This header is the whole interface the HTTP layer uses, so another backend
 * (a distributed queue) can implement it later; jobs.c is the in-process
 * one.  Jobs are reference counted: ps_jobs_submit and ps_jobs_find hand out
 * a reference the caller gives back with ps_job_release.
 *
 * A worker decodes nothing: it runs ps_segment on the job's points with its
 * parameters and encodes the document (JSON, labels or PLY) the request
 * asked for, so results are ready-to-send bytes.
 */
#ifndef PS_JOBS_H
#define PS_JOBS_H

#include <stddef.h>

#include "params_table.h"
#include "pointset.h"
#include "pointseg.h"

typedef enum ps_job_state {
    PS_JOB_QUEUED = 0,
    PS_JOB_RUNNING,
    PS_JOB_DONE,
    PS_JOB_FAILED,
    PS_JOB_CANCELLED
} ps_job_state;

const char *ps_job_state_name(ps_job_state s); /* "queued", "running", ... */

typedef struct ps_jobs ps_jobs;
typedef struct ps_job ps_job;

/* Called once when the job reaches a final state: from a worker thread, or
 * from the thread cancelling a job that was still queued. */
typedef void (*ps_job_done_fn)(void *user);

typedef struct ps_jobs_config {
    int workers;       /* threads running jobs (>= 1) */
    int queue_size;    /* jobs waiting at most (>= 1) */
    int ttl_seconds;   /* finished jobs are freed after this */
    int max_finished;  /* and when more are kept than this, oldest first */
    size_t max_kept_bytes; /* and when their results hold more bytes than this */
    const char *id_prefix; /* prepended to ids as "<prefix>-"; NULL or "" = none */
} ps_jobs_config;

/* A snapshot of a job's status. */
typedef struct ps_job_status {
    char id[96];
    ps_job_state state;
    ps_phase phase;          /* last progress report */
    double fraction;         /* within the phase, [0, 1] */
    double created, started, finished; /* Unix seconds; 0 = not yet */
    size_t n_points;
    int error_status;        /* FAILED: HTTP status of the error */
    char error[512];         /* FAILED: why */
} ps_job_status;

typedef struct ps_jobs_stats {
    size_t queued, running, kept, capacity;
    size_t kept_bytes; /* result bytes held by the registry */
    unsigned long long points_segmented, jobs_done, jobs_failed, jobs_cancelled;
} ps_jobs_stats;

/* Starts the workers; NULL when out of memory or threads. */
ps_jobs *ps_jobs_start(const ps_jobs_config *cfg);

/* Queues a job on points (moved into the job: *points is zeroed) with params.
 * on_done (may be NULL) is called with user once the job is final, and *job
 * is set before it is.  Returns 0 and a referenced *job, or -1 with err (as
 * ps_jobs_refuses, or 500 when out of memory; points are then freed). */
int ps_jobs_submit(ps_jobs *q, ps_pointset *points, const ps_request_params *params,
                   ps_job_done_fn on_done, void *user, ps_job **job, ps_api_error *err);

/* The job with this id (a new reference), or NULL. */
ps_job *ps_jobs_find(ps_jobs *q, const char *id);

void ps_job_release(ps_job *job);
void ps_job_get_status(ps_job *job, ps_job_status *st);
const char *ps_job_id(const ps_job *job);

/* DONE: the document, its length and media type (valid while referenced);
 * otherwise returns NULL. */
const char *ps_job_result(ps_job *job, size_t *len, const char **media_type);

/* Asks the job to stop: a queued job is cancelled at once, a running one
 * within a fraction of a second (the core polls the flag). */
void ps_job_cancel(ps_job *job);

void ps_jobs_get_stats(ps_jobs *q, ps_jobs_stats *st);
/* 0 when a submit would be taken; else -1 with a 503 in err saying why: the
 * queue is full, or the service is shutting down (draining). */
int ps_jobs_refuses(ps_jobs *q, ps_api_error *err);

/* Refuses every submit from now on ("the service is shutting down"); queued
 * and running jobs go on. */
void ps_jobs_stop_taking(ps_jobs *q);

/* Stops taking jobs, lets queued and running ones finish for up to
 * drain_seconds, cancels what is left and joins the workers.  Every on_done
 * has been called when it returns; references may still be held. */
void ps_jobs_drain(ps_jobs *q, double drain_seconds);

/* Frees the registry after ps_jobs_drain, once no reference is held. */
void ps_jobs_free(ps_jobs *q);

#endif
