/*
 * jobstore_redis_private.h: what the two halves of the Redis job store share,
 * private to them: jobstore_redis.c (the calls of the HTTP layer, on a pool
 * of connections) and jobstore_redis_worker.c (the workers taking jobs from
 * the stream and the lease keeper renewing their leases).
 *
 * Redis keys: PS_REDIS_STREAM (entries {job: id}) read by consumer group
 * PS_REDIS_GROUP; per job a hash (state, phase, fraction, created, started,
 * finished, points, media, accept, params, losses, cancel, worker, take
 * (the token of the worker's take), entry (its stream entry), error_status,
 * error, media_type), its input (":body") and its document
 * (":result").  The kept documents are indexed in PS_REDIS_RESULTS (members
 * "<id>:<bytes>" scored by their finish time) and their bytes summed in
 * PS_REDIS_RESULT_BYTES, so the oldest go first when over the byte budget.
 */
#ifndef PS_JOBSTORE_REDIS_PRIVATE_H
#define PS_JOBSTORE_REDIS_PRIVATE_H

#include <pthread.h>

#include "jobstore_redis.h"

#define PS_REDIS_STREAM "pointseg:jobs"
#define PS_REDIS_GROUP "pointseg"
#define PS_REDIS_JOB_PREFIX "pointseg:job:"
#define PS_REDIS_RESULTS "pointseg:results"
#define PS_REDIS_RESULT_BYTES "pointseg:result_bytes"

typedef struct ps_redis_store ps_redis_store;

/* One worker thread and the job it runs (fields under store->lock). */
typedef struct ps_redis_slot {
    ps_redis_store *store;
    pthread_t thread;
    char consumer[160];   /* its name in the consumer group */
    int active;           /* running a job: the keeper renews its lease */
    char entry[64];       /* the job's stream entry */
    char id[96];          /* and its id */
    ps_phase phase;
    double fraction;
    int lost;             /* another worker took the job over */
    int handback;         /* shutting down: give the job back */
    volatile int cancel;  /* polled by the core; raised with ps_cancel_raise */
} ps_redis_slot;

struct ps_redis_store {
    ps_jobstore base;
    ps_redis_store_config cfg;
    ps_redis_pool *pool;
    pthread_mutex_t lock;
    pthread_cond_t changed;   /* a slot went idle, or stopping */
    int stopping;
    ps_redis_slot *slots;
    int n_threads;
    pthread_t keeper;
    int has_keeper;
    unsigned long long reclaimed, lost_failed, handed_back;
};

/* The job's hash key, or with suffix (":body", ":result") its input or
 * document. */
void ps_redis_job_key(const char *id, const char *suffix, char *out, size_t cap);

/* Runs a Lua script on n_keys keys then the other arguments (binary safe). */
redisReply *ps_redis_eval(ps_redis_link *l, const char *script, int n_keys, int n_args,
                          const char *const *args, const size_t *lens, char *why, size_t why_cap);

/* Creates the consumer group (and the stream) unless it exists. */
void ps_redis_ensure_group(ps_redis_link *l);

/* Unix seconds as Redis keeps them. */
void ps_redis_now_text(char *out, size_t cap);

/* 1 once ps_redis_workers_stop has begun: no job is taken or queued. */
int ps_redis_store_stopping(ps_redis_store *s);

/* Starts the workers and the lease keeper; 0 or -1. */
int ps_redis_workers_start(ps_redis_store *s);

/* Stops taking jobs, waits up to `seconds` for running ones, hands the rest
 * back to the queue and joins the threads. */
void ps_redis_workers_stop(ps_redis_store *s, double seconds);

#endif
