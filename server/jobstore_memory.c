/* jobstore_memory.c: the default job store: asynchronous jobs on the
 * daemon's own in-process queue (jobs.h), lost when the daemon stops. */
#include "jobstore.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct memory_store {
    ps_jobstore base;
    ps_jobs *q;
} memory_store;

static ps_jobs *queue_of(ps_jobstore *s) { return ((memory_store *)s)->q; }

static ps_job *find(ps_jobstore *s, const char *id, ps_api_error *err) {
    ps_job *job = ps_jobs_find(queue_of(s), id);
    if (!job) ps_api_fail(err, 404, "no job '%s' (unknown or expired)", id);
    return job;
}

static int submit(ps_jobstore *s, const ps_job_upload *up, char *id, size_t id_cap,
                  ps_api_error *err) {
    ps_job *job;
    if (ps_jobs_submit(queue_of(s), up->points, up->params, NULL, NULL, &job, err)) return -1;
    snprintf(id, id_cap, "%s", ps_job_id(job));
    ps_job_release(job);
    return 0;
}

static int status(ps_jobstore *s, const char *id, ps_job_status *st, ps_api_error *err) {
    ps_job *job = find(s, id, err);
    if (!job) return -1;
    ps_job_get_status(job, st);
    ps_job_release(job);
    return 0;
}

static int result(ps_jobstore *s, const char *id, ps_job_doc *doc, ps_api_error *err) {
    ps_job *job = find(s, id, err);
    if (!job) return -1;
    const char *media, *bytes = ps_job_result(job, &doc->len, &media);
    int rc = 0;
    if (bytes) {
        doc->doc = malloc(doc->len ? doc->len : 1);
        if (doc->doc) memcpy(doc->doc, bytes, doc->len);
        else rc = ps_api_fail(err, 500, "out of memory");
        snprintf(doc->media_type, sizeof doc->media_type, "%s", media);
    } else {
        ps_job_status st;
        ps_job_get_status(job, &st);
        rc = ps_job_result_error(&st, 409, err);
    }
    ps_job_release(job);
    return rc;
}

static int cancel(ps_jobstore *s, const char *id, ps_job_status *st, ps_api_error *err) {
    ps_job *job = find(s, id, err);
    if (!job) return -1;
    ps_job_cancel(job);
    ps_job_get_status(job, st);
    ps_job_release(job);
    return 0;
}

static int ready(ps_jobstore *s, ps_api_error *err) {
    return ps_jobs_refuses(queue_of(s), err);
}

static void stats(ps_jobstore *s, ps_jobstore_stats *st) {
    (void)s;
    memset(st, 0, sizeof *st);
}

/* The queue is shared with synchronous requests: its owner drains it. */
static void drain(ps_jobstore *s, double seconds) {
    (void)s;
    (void)seconds;
}

static void destroy(ps_jobstore *s) { free(s); }

static const ps_jobstore_ops memory_ops = {submit, status, result, cancel, ready, stats, drain, destroy};

ps_jobstore *ps_jobstore_memory_new(ps_jobs *q) {
    memory_store *m = calloc(1, sizeof *m);
    if (!m) return NULL;
    m->base.ops = &memory_ops;
    m->q = q;
    return &m->base;
}
