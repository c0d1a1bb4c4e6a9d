/* jobstore.c: the job-store calls (dispatch to the store in use) and what
 * both stores share: job ids and the error of a result that is not there. */
#include "jobstore.h"

#include <errno.h>
#include <stdio.h>
#include <sys/random.h>

int ps_jobstore_submit(ps_jobstore *s, const ps_job_upload *up, char *id, size_t id_cap,
                       ps_api_error *err) {
    return s->ops->submit(s, up, id, id_cap, err);
}

int ps_jobstore_status(ps_jobstore *s, const char *id, ps_job_status *st, ps_api_error *err) {
    return s->ops->status(s, id, st, err);
}

int ps_jobstore_result(ps_jobstore *s, const char *id, ps_job_doc *doc, ps_api_error *err) {
    return s->ops->result(s, id, doc, err);
}

int ps_jobstore_cancel(ps_jobstore *s, const char *id, ps_job_status *st, ps_api_error *err) {
    return s->ops->cancel(s, id, st, err);
}

int ps_jobstore_ready(ps_jobstore *s, ps_api_error *err) { return s->ops->ready(s, err); }

void ps_jobstore_get_stats(ps_jobstore *s, ps_jobstore_stats *st) { s->ops->stats(s, st); }

void ps_jobstore_drain(ps_jobstore *s, double seconds) { s->ops->drain(s, seconds); }

void ps_jobstore_free(ps_jobstore *s) {
    if (s) s->ops->destroy(s);
}

int ps_job_result_error(const ps_job_status *st, int cancelled_status, ps_api_error *err) {
    if (st->state == PS_JOB_FAILED) return ps_api_fail(err, st->error_status, "%s", st->error);
    if (st->state == PS_JOB_CANCELLED)
        return ps_api_fail(err, cancelled_status, "job %s was cancelled", st->id);
    return ps_api_fail(err, 409, "job %s is %s, not done", st->id, ps_job_state_name(st->state));
}

void ps_job_make_id(const char *prefix, char *out, size_t cap) {
    unsigned char raw[16];
    size_t got = 0;
    while (got < sizeof raw) {
        ssize_t r = getrandom(raw + got, sizeof raw - got, 0);
        if (r > 0) got += (size_t)r;
        else if (errno != EINTR) break;
    }
    size_t n = prefix && prefix[0] ? (size_t)snprintf(out, cap, "%s-", prefix) : 0;
    for (size_t i = 0; i < sizeof raw && n + 2 < cap; i++) n += (size_t)snprintf(out + n, cap - n, "%02x", raw[i]);
}
