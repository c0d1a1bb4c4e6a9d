/*
 * jobstore_redis.h: the job store shared by every replica (--redis): a job's
 * input (the body as received, after gzip, and its text parameters), its
 * status, progress, error and result live in Redis under its id and expire
 * after the job TTL, or earlier when the results kept exceed the byte budget
 * (oldest first, as the in-process store does); jobs queue on a Redis Stream
 * read by one consumer group of every replica's workers.
 *
 * A worker holds a lease on its job (the stream's pending entry, renewed
 * while it runs); a job whose lease lapses is taken over by another worker
 * and runs again from its stored input, at most max_losses - 1 times: the
 * max_losses-th loss fails it.  A cancel sets a flag in the job that the
 * worker running it polls.  Redis being down makes calls fail with 503 and
 * never crashes or blocks past the timeouts; connections come back by
 * themselves.
 */
#ifndef PS_JOBSTORE_REDIS_H
#define PS_JOBSTORE_REDIS_H

#include <stddef.h>

#include "jobstore.h"
#include "redis_link.h"

typedef struct ps_redis_store_config {
    ps_redis_url url;
    int workers;          /* threads taking jobs; 0 = submit and read only */
    int job_ttl;          /* seconds a finished job is kept */
    size_t max_kept_bytes; /* results kept in Redis at most (all replicas): the oldest go first */
    int lease_seconds;    /* a worker that has not renewed for this long has lost its job */
    int max_losses;       /* losses that fail a job */
    size_t max_points;    /* what the workers decode at most */
    const char *name;     /* this replica, in the workers' consumer names (may be NULL) */
} ps_redis_store_config;

/* Starts the store and its workers (Redis need not be up yet).  NULL when
 * out of memory or threads (why says so). */
ps_jobstore *ps_jobstore_redis_new(const ps_redis_store_config *cfg, char *why, size_t why_cap);

#endif
