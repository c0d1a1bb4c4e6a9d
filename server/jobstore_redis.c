/* jobstore_redis.c: the Redis job store's calls from the HTTP layer: submit,
 * status, result, cancel, readiness and the shared queue's figures, each on a
 * connection of the pool. */
#include "jobstore_redis_private.h"

#include <cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define POOL_SIZE 8
#define CALL_TIMEOUT_S 2.0
#define QUEUED_KEEP_S 86400 /* a job no worker took for a day is dropped */

/* Queues a job under a fresh id; when its hash exists already, this is the
 * same submit retried after a call that timed out but ran, and it is not
 * queued again. */
static const char submit_script[] =
    "if redis.call('EXISTS', KEYS[1]) == 1 then return 0 end\n"
    "redis.call('HSET', KEYS[1], 'state', 'queued', 'phase', '0', 'fraction', '0',"
    "  'created', ARGV[7], 'points', ARGV[6], 'media', ARGV[3], 'accept', ARGV[4],"
    "  'params', ARGV[5], 'losses', '0', 'cancel', '0')\n"
    "redis.call('EXPIRE', KEYS[1], ARGV[8])\n"
    "redis.call('SET', KEYS[2], ARGV[2], 'EX', ARGV[8])\n"
    "redis.call('HSET', KEYS[1], 'entry', redis.call('XADD', KEYS[3], '*', 'job', ARGV[1]))\n"
    "return 1\n";

/* A queued job is cancelled at once, and its stream entry deleted (a worker
 * that read the entry already finds the job final and drops it); a running
 * one is cancelled when its worker polls. */
static const char cancel_script[] =
    "local state = redis.call('HGET', KEYS[1], 'state')\n"
    "if not state then return 0 end\n"
    "if state == 'queued' or state == 'running' then redis.call('HSET', KEYS[1], 'cancel', '1') end\n"
    "if state == 'queued' then\n"
    "  redis.call('HSET', KEYS[1], 'state', 'cancelled', 'finished', ARGV[1])\n"
    "  redis.call('EXPIRE', KEYS[1], ARGV[2])\n"
    "  redis.call('DEL', KEYS[2])\n"
    "  local entry = redis.call('HGET', KEYS[1], 'entry')\n"
    "  if entry then redis.call('XDEL', KEYS[3], entry) end\n"
    "end\n"
    "return 1\n";

static ps_redis_store *store_of(ps_jobstore *s) { return (ps_redis_store *)s; }

void ps_redis_job_key(const char *id, const char *suffix, char *out, size_t cap) {
    snprintf(out, cap, PS_REDIS_JOB_PREFIX "%s%s", id, suffix ? suffix : "");
}

void ps_redis_now_text(char *out, size_t cap) {
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    snprintf(out, cap, "%.3f", (double)ts.tv_sec + ts.tv_nsec * 1e-9);
}

redisReply *ps_redis_eval(ps_redis_link *l, const char *script, int n_keys, int n_args,
                          const char *const *args, const size_t *lens, char *why, size_t why_cap) {
    enum { MAX = 24 };
    const char *argv[MAX];
    size_t argl[MAX];
    char keys[16];
    if (n_args + 3 > MAX) return NULL;
    snprintf(keys, sizeof keys, "%d", n_keys);
    argv[0] = "EVAL", argl[0] = 4;
    argv[1] = script, argl[1] = strlen(script);
    argv[2] = keys, argl[2] = strlen(keys);
    for (int i = 0; i < n_args; i++) {
        argv[3 + i] = args[i];
        argl[3 + i] = lens ? lens[i] : strlen(args[i]);
    }
    return ps_redis_run(l, n_args + 3, argv, argl, why, why_cap);
}

void ps_redis_ensure_group(ps_redis_link *l) {
    char why[512];
    redisReply *r = ps_redis_runv(l, why, sizeof why, "XGROUP", "CREATE", PS_REDIS_STREAM,
                                  PS_REDIS_GROUP, "0", "MKSTREAM", (char *)NULL);
    if (r) freeReplyObject(r);
}

static int unavailable(ps_api_error *err, const char *why) {
    return ps_api_fail(err, 503, "the shared job queue is unavailable: %s", why);
}

/* The text parameters as a JSON array of [name, value] pairs. */
static char *params_text(const ps_job_upload *up) {
    cJSON *list = cJSON_CreateArray();
    for (size_t i = 0; list && i < up->n_extra; i++) {
        const char *pair[2] = {up->extra[i].name, up->extra[i].value ? up->extra[i].value : ""};
        cJSON_AddItemToArray(list, cJSON_CreateStringArray(pair, 2));
    }
    char *text = list ? cJSON_PrintUnformatted(list) : NULL;
    cJSON_Delete(list);
    return text;
}

static int submit(ps_jobstore *js, const ps_job_upload *up, char *id, size_t id_cap,
                  ps_api_error *err) {
    ps_redis_store *s = store_of(js);
    char hash[160], body[160], points[32], created[32], keep[32], why[512];
    if (ps_redis_store_stopping(s)) return ps_api_fail(err, 503, "the service is shutting down");
    char *params = params_text(up);
    if (!params) return ps_api_fail(err, 500, "out of memory");
    ps_job_make_id(NULL, id, id_cap);
    ps_redis_job_key(id, NULL, hash, sizeof hash);
    ps_redis_job_key(id, ":body", body, sizeof body);
    snprintf(points, sizeof points, "%zu", up->points->n);
    snprintf(keep, sizeof keep, "%d", QUEUED_KEEP_S + s->cfg.job_ttl);
    ps_redis_now_text(created, sizeof created);
    const char *args[] = {hash, body, PS_REDIS_STREAM, id, up->body,
                          up->media == PS_MEDIA_JSON ? "json" : "points", up->accept ? up->accept : "",
                          params, points, created, keep};
    size_t lens[11];
    for (int i = 0; i < 11; i++) lens[i] = i == 4 ? up->body_len : strlen(args[i]);
    ps_redis_link *l = ps_redis_pool_take(s->pool);
    redisReply *r = ps_redis_eval(l, submit_script, 3, 11, args, lens, why, sizeof why);
    ps_redis_pool_give(s->pool, l);
    free(params);
    if (!r) return unavailable(err, why);
    freeReplyObject(r);
    return 0;
}

static double number_of(const redisReply *v) {
    return v->type == REDIS_REPLY_STRING ? strtod(v->str, NULL) : 0;
}

static ps_job_state state_of(const char *name) {
    for (int s = PS_JOB_QUEUED; s <= PS_JOB_CANCELLED; s++)
        if (!strcmp(name, ps_job_state_name((ps_job_state)s))) return (ps_job_state)s;
    return PS_JOB_FAILED;
}

/* One field of HGETALL into *st (and the result's media type). */
static void read_field(const char *name, const redisReply *v, ps_job_status *st, char *media, size_t cap) {
    const char *text = v->type == REDIS_REPLY_STRING ? v->str : "";
    if (!strcmp(name, "state")) st->state = state_of(text);
    else if (!strcmp(name, "phase")) st->phase = (ps_phase)(int)number_of(v);
    else if (!strcmp(name, "fraction")) st->fraction = number_of(v);
    else if (!strcmp(name, "created")) st->created = number_of(v);
    else if (!strcmp(name, "started")) st->started = number_of(v);
    else if (!strcmp(name, "finished")) st->finished = number_of(v);
    else if (!strcmp(name, "points")) st->n_points = (size_t)number_of(v);
    else if (!strcmp(name, "error_status")) st->error_status = (int)number_of(v);
    else if (!strcmp(name, "error")) snprintf(st->error, sizeof st->error, "%s", text);
    else if (!strcmp(name, "media_type") && media) snprintf(media, cap, "%s", text);
}

static int no_job(ps_api_error *err, const char *id) {
    return ps_api_fail(err, 404, "no job '%s' (unknown or expired)", id);
}

/* An id holding ':' (ids are hex) would name another key of a job, its
 * body or result, not a job: Redis refuses the calls on it (WRONGTYPE),
 * which would read as the store being unavailable (503). */
static int bad_id(const char *id, ps_api_error *err) {
    return strchr(id, ':') ? no_job(err, id) : 0;
}

/* The job's status (and media type) from one link; 0, or -1 with err. */
static int load_status(ps_redis_link *l, const char *id, ps_job_status *st, char *media, size_t cap,
                       ps_api_error *err) {
    char hash[160], why[512];
    ps_redis_job_key(id, NULL, hash, sizeof hash);
    redisReply *r = ps_redis_runv(l, why, sizeof why, "HGETALL", hash, (char *)NULL);
    if (!r) return unavailable(err, why);
    memset(st, 0, sizeof *st);
    snprintf(st->id, sizeof st->id, "%s", id);
    int found = r->type == REDIS_REPLY_ARRAY && r->elements >= 2;
    for (size_t i = 0; found && i + 1 < r->elements; i += 2)
        if (r->element[i]->type == REDIS_REPLY_STRING)
            read_field(r->element[i]->str, r->element[i + 1], st, media, cap);
    freeReplyObject(r);
    return found ? 0 : no_job(err, id);
}

static int status(ps_jobstore *js, const char *id, ps_job_status *st, ps_api_error *err) {
    ps_redis_store *s = store_of(js);
    if (bad_id(id, err)) return -1;
    ps_redis_link *l = ps_redis_pool_take(s->pool);
    int rc = load_status(l, id, st, NULL, 0, err);
    ps_redis_pool_give(s->pool, l);
    return rc;
}

static int load_document(ps_redis_link *l, const char *id, ps_job_doc *doc, ps_api_error *err) {
    char key[160], why[512];
    ps_redis_job_key(id, ":result", key, sizeof key);
    redisReply *r = ps_redis_runv(l, why, sizeof why, "GET", key, (char *)NULL);
    if (!r) return unavailable(err, why);
    int rc = 0;
    if (r->type != REDIS_REPLY_STRING) rc = ps_api_fail(err, 404, "the result of job '%s' expired", id);
    else if (!(doc->doc = malloc(r->len ? r->len : 1))) rc = ps_api_fail(err, 500, "out of memory");
    else {
        memcpy(doc->doc, r->str, r->len);
        doc->len = r->len;
    }
    freeReplyObject(r);
    return rc;
}

static int result(ps_jobstore *js, const char *id, ps_job_doc *doc, ps_api_error *err) {
    ps_redis_store *s = store_of(js);
    ps_job_status st;
    memset(doc, 0, sizeof *doc);
    if (bad_id(id, err)) return -1;
    ps_redis_link *l = ps_redis_pool_take(s->pool);
    int rc = load_status(l, id, &st, doc->media_type, sizeof doc->media_type, err);
    if (rc == 0 && st.state != PS_JOB_DONE) rc = ps_job_result_error(&st, 409, err);
    else if (rc == 0) rc = load_document(l, id, doc, err);
    ps_redis_pool_give(s->pool, l);
    return rc;
}

static int cancel(ps_jobstore *js, const char *id, ps_job_status *st, ps_api_error *err) {
    ps_redis_store *s = store_of(js);
    char hash[160], body[160], now[32], ttl[32], why[512];
    if (bad_id(id, err)) return -1;
    ps_redis_job_key(id, NULL, hash, sizeof hash);
    ps_redis_job_key(id, ":body", body, sizeof body);
    ps_redis_now_text(now, sizeof now);
    snprintf(ttl, sizeof ttl, "%d", s->cfg.job_ttl > 0 ? s->cfg.job_ttl : 1);
    const char *args[] = {hash, body, PS_REDIS_STREAM, now, ttl};
    ps_redis_link *l = ps_redis_pool_take(s->pool);
    redisReply *r = ps_redis_eval(l, cancel_script, 3, 5, args, NULL, why, sizeof why);
    int rc = r ? load_status(l, id, st, NULL, 0, err) : unavailable(err, why);
    ps_redis_pool_give(s->pool, l);
    if (r) freeReplyObject(r);
    return rc;
}

static int ready(ps_jobstore *js, ps_api_error *err) {
    ps_redis_store *s = store_of(js);
    char why[512];
    ps_redis_link *l = ps_redis_pool_take(s->pool);
    redisReply *r = ps_redis_runv(l, why, sizeof why, "PING", (char *)NULL);
    ps_redis_pool_give(s->pool, l);
    if (!r) return unavailable(err, why);
    freeReplyObject(r);
    return 0;
}

/* XLEN counts entries not yet finished (finished and cancelled ones are
 * deleted); those the group's pending list holds are running. */
static int queue_figures(ps_redis_link *l, ps_jobstore_stats *st) {
    char why[512];
    redisReply *len = ps_redis_runv(l, why, sizeof why, "XLEN", PS_REDIS_STREAM, (char *)NULL);
    redisReply *pend = len ? ps_redis_runv(l, why, sizeof why, "XPENDING", PS_REDIS_STREAM,
                                           PS_REDIS_GROUP, (char *)NULL) : NULL;
    redisReply *kept = pend ? ps_redis_runv(l, why, sizeof why, "GET", PS_REDIS_RESULT_BYTES, (char *)NULL)
                            : NULL;
    int ok = len && len->type == REDIS_REPLY_INTEGER;
    size_t pending = pend && pend->type == REDIS_REPLY_ARRAY && pend->elements &&
                     pend->element[0]->type == REDIS_REPLY_INTEGER ? (size_t)pend->element[0]->integer : 0;
    if (ok) {
        st->pending = pending;
        st->queue_length = (size_t)len->integer > pending ? (size_t)len->integer - pending : 0;
        st->result_bytes = kept && kept->type == REDIS_REPLY_STRING ? (size_t)strtoull(kept->str, NULL, 10) : 0;
    }
    if (len) freeReplyObject(len);
    if (pend) freeReplyObject(pend);
    if (kept) freeReplyObject(kept);
    return ok;
}

static void stats(ps_jobstore *js, ps_jobstore_stats *st) {
    ps_redis_store *s = store_of(js);
    memset(st, 0, sizeof *st);
    st->shared = 1;
    ps_redis_link *l = ps_redis_pool_take(s->pool);
    st->reachable = queue_figures(l, st);
    ps_redis_pool_give(s->pool, l);
    pthread_mutex_lock(&s->lock);
    st->reclaimed = s->reclaimed;
    st->lost_failed = s->lost_failed;
    st->handed_back = s->handed_back;
    pthread_mutex_unlock(&s->lock);
}

static void drain(ps_jobstore *js, double seconds) { ps_redis_workers_stop(store_of(js), seconds); }

static void destroy(ps_jobstore *js) {
    ps_redis_store *s = store_of(js);
    ps_redis_workers_stop(s, 0);
    ps_redis_pool_free(s->pool);
    pthread_mutex_destroy(&s->lock);
    pthread_cond_destroy(&s->changed);
    free(s->slots);
    free(s);
}

static const ps_jobstore_ops redis_ops = {submit, status, result, cancel, ready, stats, drain, destroy};

ps_jobstore *ps_jobstore_redis_new(const ps_redis_store_config *cfg, char *why, size_t why_cap) {
    ps_redis_store *s = calloc(1, sizeof *s);
    if (!s) return snprintf(why, why_cap, "out of memory"), NULL;
    s->base.ops = &redis_ops;
    s->cfg = *cfg;
    pthread_mutex_init(&s->lock, NULL);
    pthread_cond_init(&s->changed, NULL);
    s->pool = ps_redis_pool_new(&cfg->url, POOL_SIZE, CALL_TIMEOUT_S);
    s->slots = calloc((size_t)(cfg->workers > 0 ? cfg->workers : 1), sizeof *s->slots);
    if (!s->pool || !s->slots || ps_redis_workers_start(s)) {
        snprintf(why, why_cap, "cannot start %d Redis job workers", cfg->workers);
        destroy(&s->base);
        return NULL;
    }
    return &s->base;
}
