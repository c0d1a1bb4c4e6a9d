/*
 * job_runner.h: running one segmentation job, shared by both job stores
 * (the in-process queue of jobs.c and the Redis queue of
 * jobstore_redis_worker.c): ps_segment on the points with the request's
 * parameters, then the document the request asked for (JSON, labels or
 * PLY) as ready-to-send bytes.
 */
#ifndef PS_JOB_RUNNER_H
#define PS_JOB_RUNNER_H

#include <stddef.h>

#include "params_table.h"
#include "pointset.h"
#include "pointseg.h"

typedef enum ps_run_state { PS_RUN_DONE = 0, PS_RUN_FAILED, PS_RUN_CANCELLED } ps_run_state;

typedef struct ps_run_outcome {
    ps_run_state state;
    char *doc;               /* DONE: the encoded document (malloc'ed; the caller frees) */
    size_t doc_len;
    const char *media_type;  /* DONE: its media type (static) */
    int error_status;        /* FAILED: HTTP status of the error */
    char error[512];         /* FAILED: why */
} ps_run_outcome;

/* Segments points with params under ctl (progress, cancel flag), on the
 * cores core_share.h gives the job when params leave threads at 0, and fills
 * *out. */
void ps_job_run(const ps_pointset *points, const ps_request_params *params,
                const ps_control *ctl, ps_run_outcome *out);

#endif
