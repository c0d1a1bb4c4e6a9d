/* jobstore_redis_worker.c: the Redis job store's workers (take a job from
 * the stream, or one whose worker's lease lapsed; run it; store the outcome)
 * and the lease keeper (renews the leases of running jobs, carries their
 * progress to Redis and cancels from Redis to the core). */
#include "jobstore_redis_private.h"

#include "deadline.h"
#include "job_runner.h"

#include <cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define BLOCK_MS "1000"       /* a worker waits this long for a job, then looks again */
#define WORKER_TIMEOUT_S 3.0  /* above the block */
#define RETRY_MS 500          /* after Redis failed */
#define MAX_PARAMS 64
#define OWN_LOOKS 16          /* deleted entries a worker forgets from its pending list per look */

/* Takes the job for consumer ARGV[3]: runs it (its input), or settles it:
 * gone, already final, cancelled, or lost once too often.  ARGV[8] is a
 * fresh token per take: a call whose token the hash holds already is the
 * same take retried after it ran, and counts no second loss (and answers
 * 'lost' again when its first run failed the job for it). */
static const char start_script[] =
    "local function drop() redis.call('XACK', KEYS[3], ARGV[1], ARGV[2])"
    "  redis.call('XDEL', KEYS[3], ARGV[2]) end\n"
    "local function final(state, status, err)\n"
    "  redis.call('HSET', KEYS[1], 'state', state, 'finished', ARGV[6], 'error_status', status, 'error', err)\n"
    "  redis.call('EXPIRE', KEYS[1], ARGV[7]) redis.call('DEL', KEYS[2]) drop() end\n"
    "local state = redis.call('HGET', KEYS[1], 'state')\n"
    "if not state then drop() return {'gone'} end\n"
    "local retried = redis.call('HGET', KEYS[1], 'take') == ARGV[8]\n"
    "if state ~= 'queued' and state ~= 'running' then drop()\n"
    "  if retried and state == 'failed' then return {'lost'} end\n"
    "  return {'final'} end\n"
    "if ARGV[4] == '1' and not retried then\n"
    "  local losses = redis.call('HINCRBY', KEYS[1], 'losses', 1)\n"
    "  if losses >= tonumber(ARGV[5]) then\n"
    "    redis.call('HSET', KEYS[1], 'take', ARGV[8])\n"
    "    final('failed', '500', 'the job lost its worker ' .. losses .. ' times (the replica running it"
    " stopped or lost Redis each time); it is not run again')\n"
    "    return {'lost'} end\n"
    "end\n"
    "if redis.call('HGET', KEYS[1], 'cancel') == '1' then final('cancelled', '0', '') return {'final'} end\n"
    "local body = redis.call('GET', KEYS[2])\n"
    "if not body then final('failed', '500', 'the input of the job expired') return {'final'} end\n"
    "redis.call('HSET', KEYS[1], 'state', 'running', 'started', ARGV[6], 'worker', ARGV[3],"
    "  'take', ARGV[8], 'phase', '0', 'fraction', '0')\n"
    "local f = redis.call('HMGET', KEYS[1], 'media', 'accept', 'params')\n"
    "return {'run', body, f[1] or 'points', f[2] or '', f[3] or '[]'}\n";

#define OWNER_CHECK \
    "local p = redis.call('XPENDING', KEYS[1], ARGV[1], ARGV[2], ARGV[2], 1)\n" \
    "if #p == 0 or p[1][2] ~= ARGV[3] then return -1 end\n"

/* -1: the lease is lost; 1: renewed, cancel asked; 0: renewed. */
static const char renew_script[] =
    OWNER_CHECK
    "if redis.call('EXISTS', KEYS[2]) == 0 then return -1 end\n"
    "redis.call('XCLAIM', KEYS[1], ARGV[1], ARGV[3], 0, ARGV[2], 'JUSTID')\n"
    "redis.call('HSET', KEYS[2], 'phase', ARGV[4], 'fraction', ARGV[5])\n"
    "if redis.call('HGET', KEYS[2], 'cancel') == '1' then return 1 end\n"
    "return 0\n";

/* A result leaves the index (and its bytes the sum); returns its job id. */
#define FORGET_RESULT \
    "local function forget(member)\n" \
    "  redis.call('DECRBY', KEYS[6], tonumber(string.match(member, ':(%d+)$')))\n" \
    "  redis.call('ZREM', KEYS[5], member)\n" \
    "  return string.match(member, '^(.*):%d+$') end\n"

/* Keeps the new result (ARGV[10] of job ARGV[13]) and the kept ones within
 * the byte budget ARGV[14]: results past their time leave the index, then
 * the oldest jobs go whole (their status too, as in the in-process store). */
#define KEEP_RESULT \
    "redis.call('SET', KEYS[4], ARGV[10], 'EX', ARGV[6])\n" \
    "redis.call('INCRBY', KEYS[6], #ARGV[10])\n" \
    "redis.call('ZADD', KEYS[5], ARGV[5], ARGV[13] .. ':' .. #ARGV[10])\n" \
    "local past = tonumber(ARGV[5]) - tonumber(ARGV[6])\n" \
    "for _, m in ipairs(redis.call('ZRANGEBYSCORE', KEYS[5], '-inf', '(' .. past)) do forget(m) end\n" \
    "while tonumber(redis.call('GET', KEYS[6])) > tonumber(ARGV[14]) do\n" \
    "  local oldest = redis.call('ZRANGE', KEYS[5], 0, 0)\n" \
    "  if #oldest == 0 then break end\n" \
    "  local id = forget(oldest[1])\n" \
    "  redis.call('DEL', '" PS_REDIS_JOB_PREFIX "' .. id, '" PS_REDIS_JOB_PREFIX "' .. id .. ':result')\n" \
    "end\n"

static const char finish_script[] =
    OWNER_CHECK
    FORGET_RESULT
    "redis.call('HSET', KEYS[2], 'state', ARGV[4], 'finished', ARGV[5], 'media_type', ARGV[7],"
    "  'error_status', ARGV[8], 'error', ARGV[9], 'phase', ARGV[11], 'fraction', ARGV[12])\n"
    "redis.call('EXPIRE', KEYS[2], ARGV[6])\n"
    "redis.call('DEL', KEYS[3])\n"
    "redis.call('XACK', KEYS[1], ARGV[1], ARGV[2])\n"
    "redis.call('XDEL', KEYS[1], ARGV[2])\n"
    "if ARGV[4] == 'done' then\n" KEEP_RESULT "end\n"
    "return 1\n";

static const char handback_script[] =
    OWNER_CHECK
    "redis.call('HSET', KEYS[2], 'state', 'queued', 'phase', '0', 'fraction', '0')\n"
    "redis.call('HDEL', KEYS[2], 'started', 'worker')\n"
    "redis.call('XACK', KEYS[1], ARGV[1], ARGV[2])\n"
    "redis.call('XDEL', KEYS[1], ARGV[2])\n"
    "redis.call('HSET', KEYS[2], 'entry', redis.call('XADD', KEYS[1], '*', 'job', ARGV[4]))\n"
    "return 1\n";

typedef struct taken {
    char entry[64];
    char id[96];
    int reclaimed;  /* taken over from a lost worker: START counts a loss */
    char take[40];  /* the token of this take (START's ARGV[8]) */
} taken;

int ps_redis_store_stopping(ps_redis_store *s) {
    pthread_mutex_lock(&s->lock);
    int stop = s->stopping;
    pthread_mutex_unlock(&s->lock);
    return stop;
}

static void pause_ms(ps_redis_store *s, long ms) {
    struct timespec ts = ps_deadline_in_ms(ms);
    pthread_mutex_lock(&s->lock);
    if (!s->stopping) pthread_cond_timedwait(&s->changed, &s->lock, &ts);
    pthread_mutex_unlock(&s->lock);
}

/* An entry [id, [field, value, ...]] into *t; 0, or -1 when it is not one
 * of ours (deleted, or no job field). */
static int read_entry(const redisReply *e, taken *t) {
    if (e->type != REDIS_REPLY_ARRAY || e->elements < 2 || e->element[0]->type != REDIS_REPLY_STRING)
        return -1;
    snprintf(t->entry, sizeof t->entry, "%s", e->element[0]->str);
    const redisReply *f = e->element[1];
    for (size_t i = 0; f->type == REDIS_REPLY_ARRAY && i + 1 < f->elements; i += 2)
        if (f->element[i]->type == REDIS_REPLY_STRING && !strcmp(f->element[i]->str, "job") &&
            f->element[i + 1]->type == REDIS_REPLY_STRING) {
            snprintf(t->id, sizeof t->id, "%s", f->element[i + 1]->str);
            return 0;
        }
    return -1;
}

static void forget_entry(ps_redis_link *l, const char *entry) {
    char why[512];
    redisReply *r = ps_redis_runv(l, why, sizeof why, "XACK", PS_REDIS_STREAM, PS_REDIS_GROUP, entry,
                                  (char *)NULL);
    if (r) freeReplyObject(r);
}

/* A job whose lease lapsed, scanning the pending list from *cursor: 1 taken,
 * 0 none, -1 Redis failed. */
static int take_lapsed(ps_redis_slot *w, ps_redis_link *l, char *cursor, size_t cap, taken *t) {
    char why[512], idle[32];
    snprintf(idle, sizeof idle, "%lld", (long long)w->store->cfg.lease_seconds * 1000);
    redisReply *r = ps_redis_runv(l, why, sizeof why, "XAUTOCLAIM", PS_REDIS_STREAM, PS_REDIS_GROUP,
                                  w->consumer, idle, cursor, "COUNT", "1", (char *)NULL);
    if (!r) {
        if (strstr(why, "NOGROUP")) ps_redis_ensure_group(l);
        return -1;
    }
    int got = 0;
    if (r->type == REDIS_REPLY_ARRAY && r->elements >= 2 && r->element[0]->type == REDIS_REPLY_STRING) {
        snprintf(cursor, cap, "%s", r->element[0]->str);
        const redisReply *list = r->element[1];
        if (list->type == REDIS_REPLY_ARRAY && list->elements) {
            got = read_entry(list->element[0], t) == 0;
            if (!got && list->element[0]->type == REDIS_REPLY_ARRAY && list->element[0]->elements)
                forget_entry(l, list->element[0]->element[0]->str);
        }
    }
    freeReplyObject(r);
    t->reclaimed = 1;
    return got;
}

/* An entry Redis gave this worker whose answer never reached it (a read
 * or takeover whose connection broke after Redis ran it), or one whose START
 * went unanswered: the oldest in its own pending list.  An entry delivered
 * more than once was taken over from a lost worker.  1 taken, 0 none, -1
 * Redis failed. */
static int take_own(ps_redis_slot *w, ps_redis_link *l, taken *t) {
    for (int looked = 0; looked < OWN_LOOKS; looked++) {
        char why[512], entry[64];
        redisReply *p = ps_redis_runv(l, why, sizeof why, "XPENDING", PS_REDIS_STREAM, PS_REDIS_GROUP, "-",
                                      "+", "1", w->consumer, (char *)NULL);
        if (!p) return -1;
        const redisReply *e = p->type == REDIS_REPLY_ARRAY && p->elements ? p->element[0] : NULL;
        int ok = e && e->type == REDIS_REPLY_ARRAY && e->elements == 4 &&
                 e->element[0]->type == REDIS_REPLY_STRING && e->element[3]->type == REDIS_REPLY_INTEGER;
        if (ok) {
            snprintf(entry, sizeof entry, "%s", e->element[0]->str);
            t->reclaimed = e->element[3]->integer > 1;
        }
        freeReplyObject(p);
        if (!ok) return 0;
        redisReply *r = ps_redis_runv(l, why, sizeof why, "XRANGE", PS_REDIS_STREAM, entry, entry, (char *)NULL);
        if (!r) return -1;
        int got = r->type == REDIS_REPLY_ARRAY && r->elements && read_entry(r->element[0], t) == 0;
        freeReplyObject(r);
        if (got) return 1;
        forget_entry(l, entry); /* deleted since: nothing to run */
    }
    return 0; /* the rest lapse and are taken over */
}

/* A new job from the stream, waiting up to BLOCK_MS: 1, 0 or -1. */
static int take_new(ps_redis_slot *w, ps_redis_link *l, taken *t) {
    char why[512];
    redisReply *r = ps_redis_runv(l, why, sizeof why, "XREADGROUP", "GROUP", PS_REDIS_GROUP, w->consumer,
                                  "COUNT", "1", "BLOCK", BLOCK_MS, "STREAMS", PS_REDIS_STREAM, ">",
                                  (char *)NULL);
    if (!r) {
        if (strstr(why, "NOGROUP")) ps_redis_ensure_group(l);
        return -1;
    }
    int got = 0;
    if (r->type == REDIS_REPLY_ARRAY && r->elements == 1) {
        const redisReply *stream = r->element[0];
        if (stream->type == REDIS_REPLY_ARRAY && stream->elements == 2 &&
            stream->element[1]->type == REDIS_REPLY_ARRAY && stream->element[1]->elements)
            got = read_entry(stream->element[1]->element[0], t) == 0;
    }
    freeReplyObject(r);
    t->reclaimed = 0;
    return got;
}

/* The stored text parameters: a JSON array of [name, value]. */
static int parse_params(const char *text, cJSON **doc, ps_text_param *items, size_t *n) {
    *doc = cJSON_Parse(text);
    *n = 0;
    if (!cJSON_IsArray(*doc)) return -1;
    for (cJSON *pair = (*doc)->child; pair && *n < MAX_PARAMS; pair = pair->next) {
        cJSON *name = cJSON_GetArrayItem(pair, 0), *value = cJSON_GetArrayItem(pair, 1);
        if (!cJSON_IsString(name) || !cJSON_IsString(value)) return -1;
        items[(*n)++] = (ps_text_param){name->valuestring, value->valuestring};
    }
    return 0;
}

/* The job's points and parameters from what START returned, as the HTTP
 * layer decoded them; 0 or -1 with err. */
static int decode_input(const redisReply *r, size_t max_points, ps_pointset *ps, ps_request_params *rp,
                        ps_api_error *err) {
    ps_text_param items[MAX_PARAMS];
    size_t n;
    cJSON *doc;
    ps_media media = !strcmp(r->element[2]->str, "json") ? PS_MEDIA_JSON : PS_MEDIA_POINTS;
    if (ps_intake_decode(r->element[1]->str, r->element[1]->len, media, max_points, ps, err)) return -1;
    int rc = parse_params(r->element[4]->str, &doc, items, &n)
                 ? ps_api_fail(err, 500, "the stored parameters of the job are unreadable")
                 : ps_intake_params(ps, r->element[3]->str[0] ? r->element[3]->str : NULL, items, n, rp, err);
    cJSON_Delete(doc);
    if (rc) ps_pointset_free(ps);
    return rc;
}

static void report_progress(void *user, ps_phase phase, double fraction) {
    ps_redis_slot *w = user;
    pthread_mutex_lock(&w->store->lock);
    w->phase = phase;
    w->fraction = fraction;
    pthread_mutex_unlock(&w->store->lock);
}

/* Runs a script on the job that checks this worker still holds it; retries
 * while Redis is down, for up to a lease (after that another worker may
 * have it).  Returns the script's integer, or -1. */
static long long run_owned(ps_redis_slot *w, ps_redis_link *l, const char *script, int n_keys,
                           const char *const *args, const size_t *lens, int n_args) {
    char why[512];
    double tries = w->store->cfg.lease_seconds * 1000.0 / RETRY_MS;
    for (int i = 0; i <= (int)tries; i++) {
        redisReply *r = ps_redis_eval(l, script, n_keys, n_args, args, lens, why, sizeof why);
        if (r) {
            long long v = r->type == REDIS_REPLY_INTEGER ? r->integer : -1;
            freeReplyObject(r);
            return v;
        }
        struct timespec ts = {0, RETRY_MS * 1000000L};
        nanosleep(&ts, NULL);
    }
    return -1;
}

static void store_outcome(ps_redis_slot *w, ps_redis_link *l, const taken *t, const ps_run_outcome *out) {
    static const char *const state_names[] = {"done", "failed", "cancelled"};
    char hash[160], body[160], result[160], now[32], ttl[32], status[16], phase[16], fraction[32],
        budget[32];
    ps_redis_job_key(t->id, NULL, hash, sizeof hash);
    ps_redis_job_key(t->id, ":body", body, sizeof body);
    ps_redis_job_key(t->id, ":result", result, sizeof result);
    ps_redis_now_text(now, sizeof now);
    snprintf(ttl, sizeof ttl, "%d", w->store->cfg.job_ttl > 0 ? w->store->cfg.job_ttl : 1);
    snprintf(status, sizeof status, "%d", out->error_status);
    snprintf(budget, sizeof budget, "%zu", w->store->cfg.max_kept_bytes);
    pthread_mutex_lock(&w->store->lock);
    snprintf(phase, sizeof phase, "%d", (int)w->phase);
    snprintf(fraction, sizeof fraction, "%.4f", w->fraction);
    pthread_mutex_unlock(&w->store->lock);
    const char *args[] = {PS_REDIS_STREAM, hash, body, result, PS_REDIS_RESULTS, PS_REDIS_RESULT_BYTES,
                          PS_REDIS_GROUP, t->entry, w->consumer, state_names[out->state], now, ttl,
                          out->media_type ? out->media_type : "", status, out->error,
                          out->doc ? out->doc : "", phase, fraction, t->id, budget};
    enum { N_ARGS = sizeof args / sizeof args[0], DOC_ARG = 15 };
    size_t lens[N_ARGS];
    for (int i = 0; i < N_ARGS; i++) lens[i] = i == DOC_ARG ? out->doc_len : strlen(args[i]);
    run_owned(w, l, finish_script, 6, args, lens, N_ARGS);
}

static void hand_back(ps_redis_slot *w, ps_redis_link *l, const taken *t) {
    char hash[160];
    ps_redis_job_key(t->id, NULL, hash, sizeof hash);
    const char *args[] = {PS_REDIS_STREAM, hash, PS_REDIS_GROUP, t->entry, w->consumer, t->id};
    if (run_owned(w, l, handback_script, 2, args, NULL, 6) == 1) {
        pthread_mutex_lock(&w->store->lock);
        w->store->handed_back++;
        pthread_mutex_unlock(&w->store->lock);
    }
}

static void set_active(ps_redis_slot *w, const taken *t, int active) {
    pthread_mutex_lock(&w->store->lock);
    w->active = active;
    if (active) {
        snprintf(w->entry, sizeof w->entry, "%s", t->entry);
        snprintf(w->id, sizeof w->id, "%s", t->id);
        w->phase = PS_PHASE_KNN;
        w->fraction = 0;
        w->lost = 0;
        w->cancel = w->store->stopping;
        w->handback = w->store->stopping;
    }
    pthread_cond_broadcast(&w->store->changed);
    pthread_mutex_unlock(&w->store->lock);
}

static void run_taken(ps_redis_slot *w, ps_redis_link *l, const redisReply *input, const taken *t) {
    ps_pointset ps;
    ps_request_params rp;
    ps_run_outcome out = {.state = PS_RUN_FAILED};
    set_active(w, t, 1);
    if (decode_input(input, w->store->cfg.max_points, &ps, &rp, &(ps_api_error){0}) == 0) {
        ps_control ctl = {report_progress, w, &w->cancel};
        ps_job_run(&ps, &rp, &ctl, &out);
        ps_pointset_free(&ps);
    } else {
        out.error_status = 422;
        snprintf(out.error, sizeof out.error, "the stored input of the job no longer decodes");
    }
    pthread_mutex_lock(&w->store->lock);
    int lost = w->lost, handback = w->handback && out.state == PS_RUN_CANCELLED;
    pthread_mutex_unlock(&w->store->lock);
    if (handback) hand_back(w, l, t);
    else if (!lost) store_outcome(w, l, t, &out);
    free(out.doc);
    set_active(w, t, 0);
}

static void count_start(ps_redis_store *s, const taken *t, const redisReply *r) {
    if (!t->reclaimed) return;
    pthread_mutex_lock(&s->lock);
    s->reclaimed++;
    s->lost_failed += r->type == REDIS_REPLY_ARRAY && r->elements && !strcmp(r->element[0]->str, "lost");
    pthread_mutex_unlock(&s->lock);
}

/* START on a taken entry, then the job if it is to run; -1 when START
 * went unanswered. */
static int settle_taken(ps_redis_slot *w, ps_redis_link *l, const taken *t) {
    char hash[160], body[160], now[32], ttl[32], losses[16], why[512];
    ps_redis_store *s = w->store;
    ps_redis_job_key(t->id, NULL, hash, sizeof hash);
    ps_redis_job_key(t->id, ":body", body, sizeof body);
    ps_redis_now_text(now, sizeof now);
    snprintf(ttl, sizeof ttl, "%d", s->cfg.job_ttl > 0 ? s->cfg.job_ttl : 1);
    snprintf(losses, sizeof losses, "%d", s->cfg.max_losses);
    const char *args[] = {hash, body, PS_REDIS_STREAM, PS_REDIS_GROUP, t->entry, w->consumer,
                          t->reclaimed ? "1" : "0", losses, now, ttl, t->take};
    redisReply *r = ps_redis_eval(l, start_script, 3, 11, args, NULL, why, sizeof why);
    if (!r) return -1; /* taken again from the pending list, with the same token */
    count_start(s, t, r);
    if (r->type == REDIS_REPLY_ARRAY && r->elements == 5 && !strcmp(r->element[0]->str, "run"))
        run_taken(w, l, r, t);
    freeReplyObject(r);
    return 0;
}

/* The next entry to settle: this worker's own unanswered ones first (while
 * *own is raised), then one whose lease lapsed, then a new one; a call
 * whose connection broke raises *own and ends the look.  A take retried
 * from the pending list keeps the token of its unanswered START. */
static int take_next(ps_redis_slot *w, ps_redis_link *l, char *cursor, size_t cap, int *own,
                     const taken *unanswered, taken *t) {
    unsigned long drops = ps_redis_link_drops(l);
    int got = *own ? take_own(w, l, t) : 0;
    *own = got != 0;
    if (got == 0) got = take_lapsed(w, l, cursor, cap, t);
    if (got == 0 && ps_redis_link_drops(l) == drops && !ps_redis_store_stopping(w->store))
        got = take_new(w, l, t);
    *own |= ps_redis_link_drops(l) != drops;
    if (got > 0 && !strcmp(t->entry, unanswered->entry)) snprintf(t->take, sizeof t->take, "%s", unanswered->take);
    else if (got > 0) ps_job_make_id(NULL, t->take, sizeof t->take);
    return got;
}

static void *worker_main(void *arg) {
    ps_redis_slot *w = arg;
    ps_redis_store *s = w->store;
    char cursor[64] = "0-0";
    taken unanswered = {.entry = ""};
    int own = 0;
    ps_redis_link *l = ps_redis_link_new(&s->cfg.url, WORKER_TIMEOUT_S);
    if (!l) return NULL;
    while (!ps_redis_store_stopping(s)) {
        taken t;
        int got = take_next(w, l, cursor, sizeof cursor, &own, &unanswered, &t);
        if (got < 0) pause_ms(s, RETRY_MS);
        if (got <= 0) continue;
        unsigned long drops = ps_redis_link_drops(l);
        if (settle_taken(w, l, &t)) {
            unanswered = t;
            own = 1;
        }
        own |= ps_redis_link_drops(l) != drops; /* an outcome unstored: the entry is still ours */
    }
    ps_redis_link_free(l);
    return NULL;
}

/* Renews one running job's lease; -1 lost, 1 cancel asked, 0, or -2 when
 * Redis did not answer. */
static int renew(ps_redis_link *l, const ps_redis_slot *w, const char *entry, const char *id,
                 ps_phase phase, double fraction) {
    char hash[160], ph[16], fr[32], why[512];
    ps_redis_job_key(id, NULL, hash, sizeof hash);
    snprintf(ph, sizeof ph, "%d", (int)phase);
    snprintf(fr, sizeof fr, "%.4f", fraction);
    const char *args[] = {PS_REDIS_STREAM, hash, PS_REDIS_GROUP, entry, w->consumer, ph, fr};
    redisReply *r = ps_redis_eval(l, renew_script, 2, 7, args, NULL, why, sizeof why);
    if (!r) return -2;
    int v = r->type == REDIS_REPLY_INTEGER ? (int)r->integer : -2;
    freeReplyObject(r);
    return v;
}

static void renew_all(ps_redis_store *s, ps_redis_link *l) {
    for (int i = 0; i < s->n_threads; i++) {
        ps_redis_slot *w = &s->slots[i];
        pthread_mutex_lock(&s->lock);
        char entry[64], id[96];
        int active = w->active;
        ps_phase phase = w->phase;
        double fraction = w->fraction;
        snprintf(entry, sizeof entry, "%s", w->entry);
        snprintf(id, sizeof id, "%s", w->id);
        pthread_mutex_unlock(&s->lock);
        if (!active) continue;
        int v = renew(l, w, entry, id, phase, fraction);
        pthread_mutex_lock(&s->lock);
        if (w->active && !strcmp(w->entry, entry) && (v == 1 || v == -1)) {
            ps_cancel_raise(&w->cancel);
            w->lost = v == -1;
        }
        pthread_mutex_unlock(&s->lock);
    }
}

/* The keeper renews a few times per lease, and often enough that a cancel
 * reaches the core within a second. */
static long keeper_period_ms(const ps_redis_store *s) {
    long ms = s->cfg.lease_seconds * 1000L / 3;
    return ms < 500 ? ms : 500;
}

static void *keeper_main(void *arg) {
    ps_redis_store *s = arg;
    ps_redis_link *l = ps_redis_link_new(&s->cfg.url, 1.0);
    if (!l) return NULL;
    for (;;) {
        struct timespec ts = ps_deadline_in_ms(keeper_period_ms(s));
        pthread_mutex_lock(&s->lock);
        int busy = 0;
        for (int i = 0; i < s->n_threads; i++) busy |= s->slots[i].active;
        if (s->stopping && !busy) {
            pthread_mutex_unlock(&s->lock);
            break;
        }
        pthread_cond_timedwait(&s->changed, &s->lock, &ts);
        pthread_mutex_unlock(&s->lock);
        renew_all(s, l);
    }
    ps_redis_link_free(l);
    return NULL;
}

static void name_consumers(ps_redis_store *s) {
    char host[64] = "pointsegd";
    unsigned tag = 0;
    gethostname(host, sizeof host - 1);
    host[sizeof host - 1] = 0;
    ps_job_make_id(NULL, s->slots[0].consumer, 9);
    tag = (unsigned)strtoul(s->slots[0].consumer, NULL, 16);
    for (int i = 0; i < s->cfg.workers; i++)
        snprintf(s->slots[i].consumer, sizeof s->slots[i].consumer, "%s-%s-%ld-%08x-%d",
                 s->cfg.name && s->cfg.name[0] ? s->cfg.name : "pointsegd", host, (long)getpid(), tag, i);
}

int ps_redis_workers_start(ps_redis_store *s) {
    ps_redis_link *l = ps_redis_link_new(&s->cfg.url, 1.0);
    if (!l) return -1;
    ps_redis_ensure_group(l);
    ps_redis_link_free(l);
    if (s->cfg.workers <= 0) return 0;
    name_consumers(s);
    for (; s->n_threads < s->cfg.workers; s->n_threads++) {
        s->slots[s->n_threads].store = s;
        if (pthread_create(&s->slots[s->n_threads].thread, NULL, worker_main, &s->slots[s->n_threads])) break;
    }
    s->has_keeper = s->n_threads == s->cfg.workers && !pthread_create(&s->keeper, NULL, keeper_main, s);
    return s->has_keeper ? 0 : -1;
}

static int any_active_locked(const ps_redis_store *s) {
    for (int i = 0; i < s->n_threads; i++)
        if (s->slots[i].active) return 1;
    return 0;
}

void ps_redis_workers_stop(ps_redis_store *s, double seconds) {
    struct timespec deadline = ps_deadline_in_ms((long)(seconds * 1000));
    pthread_mutex_lock(&s->lock);
    s->stopping = 1;
    pthread_cond_broadcast(&s->changed);
    while (any_active_locked(s) && pthread_cond_timedwait(&s->changed, &s->lock, &deadline) == 0) continue;
    for (int i = 0; i < s->n_threads; i++)
        if (s->slots[i].active) {
            s->slots[i].handback = 1;
            ps_cancel_raise(&s->slots[i].cancel);
        }
    pthread_mutex_unlock(&s->lock);
    for (int i = 0; i < s->n_threads; i++) pthread_join(s->slots[i].thread, NULL);
    if (s->has_keeper) pthread_join(s->keeper, NULL); /* it reads n_threads */
    s->has_keeper = 0;
    s->n_threads = 0;
}
