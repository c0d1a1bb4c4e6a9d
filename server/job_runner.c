/* job_runner.c: one job: ps_segment on its share of the cores
 * (core_share.h), then its document in the requested format. */
#include "job_runner.h"

#include "core_share.h"
#include "encode.h"

#include <stdio.h>
#include <string.h>

static int status_of(ps_status s) {
    return s == PS_ERR_INVALID ? 422 : 500;
}

/* ps_segment with params' thread count resolved to the job's share. */
static ps_status segment_on_share(const ps_input *in, const ps_request_params *params,
                                  const ps_control *ctl, ps_result **r, ps_error *err) {
    ps_params core = params->core;
    core.threads = ps_core_share_take(params->core.threads);
    ps_status s = ps_segment(in, &core, ctl, r, err);
    ps_core_share_give(core.threads);
    return s;
}

void ps_job_run(const ps_pointset *points, const ps_request_params *params,
                const ps_control *ctl, ps_run_outcome *out) {
    ps_input in = ps_pointset_input(points);
    ps_result *r = NULL;
    ps_error err = {0};
    memset(out, 0, sizeof *out);
    ps_status s = segment_on_share(&in, params, ctl, &r, &err);
    if (s == PS_ERR_CANCELLED) {
        out->state = PS_RUN_CANCELLED;
        return;
    }
    if (s != PS_OK) {
        out->state = PS_RUN_FAILED;
        out->error_status = status_of(s);
        snprintf(out->error, sizeof out->error, "%s", err.message);
        return;
    }
    out->doc = ps_encode(points, r, params, &out->doc_len, &out->media_type);
    ps_result_free(r);
    out->state = out->doc ? PS_RUN_DONE : PS_RUN_FAILED;
    if (!out->doc) {
        out->error_status = 500;
        snprintf(out->error, sizeof out->error, "out of memory encoding the result");
    }
}
