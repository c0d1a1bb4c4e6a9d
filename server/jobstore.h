/*
 * jobstore.h: where asynchronous jobs live (POST /jobs, GET and DELETE
 * /jobs/{id}, GET /jobs/{id}/result).  Two stores implement it:
 * jobstore_memory.c, the default, on the daemon's in-process queue (jobs.h),
 * and jobstore_redis.c (--redis), a queue shared by every replica.
 * Synchronous requests (POST /segment) always run on the in-process queue.
 *
 * Every call answers 0, or -1 with err set to the answer to give: 404 no
 * such job, 409 not done, 503 the store is unreachable or full (Retry-After),
 * or a failed job's own status.
 */
#ifndef PS_JOBSTORE_H
#define PS_JOBSTORE_H

#include <stddef.h>

#include "api_error.h"
#include "intake.h"
#include "jobs.h"

/* What a store needs of an accepted upload: the decoded points and their
 * effective parameters (the in-process store runs these), and what they
 * were made from (the Redis store keeps these, and its workers decode them
 * again): the body as received after gzip, its media, the Accept header and
 * the text parameters (multipart fields, then the query string). */
typedef struct ps_job_upload {
    ps_pointset *points;                /* a store may take it (then zeroed) */
    const ps_request_params *params;
    const char *body;
    size_t body_len;
    ps_media media;
    const char *accept;                 /* may be NULL */
    const ps_text_param *extra;
    size_t n_extra;
} ps_job_upload;

/* A finished job's document (doc malloc'ed; the caller frees it). */
typedef struct ps_job_doc {
    char *doc;
    size_t len;
    char media_type[64];
} ps_job_doc;

/* What a store adds to /metrics (the Redis store; zero for the other). */
typedef struct ps_jobstore_stats {
    int shared;                        /* 1: a Redis store */
    int reachable;                     /* Redis answered just now */
    size_t queue_length;               /* jobs in the shared queue no worker took yet */
    size_t pending;                    /* taken by a worker, not finished */
    size_t result_bytes;               /* results kept in the shared store (all replicas) */
    unsigned long long reclaimed;      /* jobs this replica took over from a lost worker */
    unsigned long long lost_failed;    /* jobs failed for having lost their worker too often */
    unsigned long long handed_back;    /* jobs given back to the queue on shutdown */
} ps_jobstore_stats;

typedef struct ps_jobstore ps_jobstore;

typedef struct ps_jobstore_ops {
    int (*submit)(ps_jobstore *s, const ps_job_upload *up, char *id, size_t id_cap, ps_api_error *err);
    int (*status)(ps_jobstore *s, const char *id, ps_job_status *st, ps_api_error *err);
    int (*result)(ps_jobstore *s, const char *id, ps_job_doc *doc, ps_api_error *err);
    int (*cancel)(ps_jobstore *s, const char *id, ps_job_status *st, ps_api_error *err);
    int (*ready)(ps_jobstore *s, ps_api_error *err);
    void (*stats)(ps_jobstore *s, ps_jobstore_stats *st);
    void (*drain)(ps_jobstore *s, double seconds);
    void (*destroy)(ps_jobstore *s);
} ps_jobstore_ops;

struct ps_jobstore {
    const ps_jobstore_ops *ops;
};

/* Queues the upload; *id (id_cap >= 64) names the job. */
int ps_jobstore_submit(ps_jobstore *s, const ps_job_upload *up, char *id, size_t id_cap,
                       ps_api_error *err);
int ps_jobstore_status(ps_jobstore *s, const char *id, ps_job_status *st, ps_api_error *err);
/* DONE: the document; otherwise -1 with the job's error, or 409 not done. */
int ps_jobstore_result(ps_jobstore *s, const char *id, ps_job_doc *doc, ps_api_error *err);
/* Asks the job to stop (wherever it runs); *st is its status after that. */
int ps_jobstore_cancel(ps_jobstore *s, const char *id, ps_job_status *st, ps_api_error *err);
/* 0 when a submit would be taken now. */
int ps_jobstore_ready(ps_jobstore *s, ps_api_error *err);
void ps_jobstore_get_stats(ps_jobstore *s, ps_jobstore_stats *st);
/* Takes no new job; lets running ones finish for up to `seconds`; then
 * gives them up (the Redis store hands them back to the queue). */
void ps_jobstore_drain(ps_jobstore *s, double seconds);
void ps_jobstore_free(ps_jobstore *s);

/* The error a result request gets for a job that is not DONE (st->state):
 * its own error when FAILED, cancelled_status when CANCELLED, else 409. */
int ps_job_result_error(const ps_job_status *st, int cancelled_status, ps_api_error *err);

/* A new random job id: 32 hex digits, after "<prefix>-" when prefix is set. */
void ps_job_make_id(const char *prefix, char *out, size_t cap);

/* The in-process store on q (not owned: the caller drains and frees q). */
ps_jobstore *ps_jobstore_memory_new(ps_jobs *q);

#endif
