/* redis_link.c: Redis connections that reconnect by themselves, their pool,
 * the --redis URL, and the counters. */
#include "redis_link.h"

#include "deadline.h"

#include <errno.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define RETRY_AFTER_S 0.25 /* after a failed connect, callers fail fast this long */
#define MAX_ARGS 32

struct ps_redis_link {
    ps_redis_url url;
    double timeout_s;
    redisContext *ctx;
    double retry_at;          /* monotonic seconds: no connect attempt before */
    char last_error[640];
    unsigned long drops;      /* calls whose connection broke under them */
    int in_use;               /* pool bookkeeping */
};

struct ps_redis_pool {
    pthread_mutex_t lock;
    pthread_cond_t freed;
    ps_redis_link **links;
    int size;
};

static pthread_mutex_t counters_lock = PTHREAD_MUTEX_INITIALIZER;
static ps_redis_counters counters;

void ps_redis_counters_get(ps_redis_counters *c) {
    pthread_mutex_lock(&counters_lock);
    *c = counters;
    pthread_mutex_unlock(&counters_lock);
}

/* A blocking read (XREADGROUP ... BLOCK) waits for work by design: it is
 * counted, but its time is no latency. */
static void count(const char *command, double seconds, int failed) {
    int blocking = !strcmp(command, "XREADGROUP");
    pthread_mutex_lock(&counters_lock);
    counters.commands++;
    counters.errors += failed != 0;
    counters.seconds += blocking ? 0 : seconds;
    pthread_mutex_unlock(&counters_lock);
}

static int parse_port_db(const char *p, ps_redis_url *url, char *why, size_t cap) {
    char *end;
    if (*p == ':') {
        long port = strtol(p + 1, &end, 10);
        if (end == p + 1 || port < 1 || port > 65535) {
            snprintf(why, cap, "--redis: the port must be 1-65535");
            return -1;
        }
        url->port = (int)port;
        p = end;
    }
    if (*p == '/' && p[1]) {
        long db = strtol(p + 1, &end, 10);
        if (end == p + 1 || *end || db < 0 || db > 1000000) {
            snprintf(why, cap, "--redis: the database must be a number");
            return -1;
        }
        url->db = (int)db;
        p = end;
    }
    if (*p && strcmp(p, "/")) {
        snprintf(why, cap, "--redis: unexpected '%s' (redis://[:password@]host[:port][/db])", p);
        return -1;
    }
    return 0;
}

int ps_redis_url_parse(const char *text, ps_redis_url *url, char *why, size_t cap) {
    static const char scheme[] = "redis://";
    memset(url, 0, sizeof *url);
    url->port = 6379;
    if (strncmp(text, scheme, sizeof scheme - 1)) {
        snprintf(why, cap, "--redis: '%s' does not start with redis://", text);
        return -1;
    }
    const char *p = text + sizeof scheme - 1, *at = strrchr(p, '@');
    if (at) {
        size_t n = (size_t)(at - p);
        if (*p != ':' || n - 1 >= sizeof url->password) {
            snprintf(why, cap, "--redis: the password goes as redis://:password@host");
            return -1;
        }
        memcpy(url->password, p + 1, n - 1);
        p = at + 1;
    }
    size_t host_len = strcspn(p, ":/");
    if (!host_len || host_len >= sizeof url->host) {
        snprintf(why, cap, "--redis: no host in '%s'", text);
        return -1;
    }
    memcpy(url->host, p, host_len);
    return parse_port_db(p + host_len, url, why, cap);
}

ps_redis_link *ps_redis_link_new(const ps_redis_url *url, double timeout_s) {
    ps_redis_link *l = calloc(1, sizeof *l);
    if (!l) return NULL;
    l->url = *url;
    l->timeout_s = timeout_s;
    return l;
}

/* why may point into the context: it is copied before the context goes. */
static void disconnect(ps_redis_link *l, const char *why) {
    snprintf(l->last_error, sizeof l->last_error, "Redis at %s:%d is unreachable: %s", l->url.host,
             l->url.port, why);
    if (l->ctx) redisFree(l->ctx);
    l->ctx = NULL;
}

void ps_redis_link_free(ps_redis_link *l) {
    if (!l) return;
    if (l->ctx) redisFree(l->ctx);
    free(l);
}

static struct timeval timeval_of(double s) {
    struct timeval tv = {(time_t)s, (suseconds_t)((s - (double)(time_t)s) * 1e6)};
    return tv;
}

/* AUTH and SELECT on a fresh connection; 0 or -1 (disconnected, why set). */
static int introduce(ps_redis_link *l) {
    char db[16];
    redisReply *r = NULL;
    if (l->url.password[0]) {
        r = redisCommand(l->ctx, "AUTH %s", l->url.password);
        if (!r || r->type == REDIS_REPLY_ERROR) goto failed;
        freeReplyObject(r);
    }
    if (l->url.db) {
        snprintf(db, sizeof db, "%d", l->url.db);
        r = redisCommand(l->ctx, "SELECT %s", db);
        if (!r || r->type == REDIS_REPLY_ERROR) goto failed;
        freeReplyObject(r);
    }
    return 0;
failed:
    disconnect(l, r ? r->str : l->ctx->errstr);
    if (r) freeReplyObject(r);
    return -1;
}

static int ensure_connected(ps_redis_link *l) {
    if (l->ctx) return 0;
    double now = ps_monotonic_seconds();
    if (now < l->retry_at) return -1;
    l->retry_at = now + RETRY_AFTER_S;
    l->ctx = redisConnectWithTimeout(l->url.host, l->url.port, timeval_of(l->timeout_s));
    if (!l->ctx || l->ctx->err) {
        disconnect(l, l->ctx ? l->ctx->errstr : "out of memory");
        return -1;
    }
    redisSetTimeout(l->ctx, timeval_of(l->timeout_s));
    redisEnableKeepAlive(l->ctx);
    return introduce(l);
}

/* One attempt: NULL (disconnected, why in last_error) or the reply. */
static redisReply *attempt(ps_redis_link *l, int argc, const char **argv, const size_t *lens) {
    if (ensure_connected(l)) return NULL;
    redisReply *r = redisCommandArgv(l->ctx, argc, argv, lens);
    if (!r) {
        l->drops++;
        disconnect(l, l->ctx->errstr[0] ? l->ctx->errstr : strerror(errno));
    }
    return r;
}

redisReply *ps_redis_run(ps_redis_link *l, int argc, const char **argv, const size_t *lens,
                         char *why, size_t why_cap) {
    double t0 = ps_monotonic_seconds();
    int was_connected = l->ctx != NULL;
    redisReply *r = attempt(l, argc, argv, lens);
    if (!r && was_connected) { /* a connection from before a Redis restart: once more, on a new one */
        l->retry_at = 0;
        r = attempt(l, argc, argv, lens);
    }
    if (!r) snprintf(why, why_cap, "%s", l->last_error);
    else if (r->type == REDIS_REPLY_ERROR) {
        snprintf(why, why_cap, "Redis: %s", r->str);
        freeReplyObject(r);
        r = NULL;
    }
    count(argv[0], ps_monotonic_seconds() - t0, r == NULL);
    return r;
}

unsigned long ps_redis_link_drops(const ps_redis_link *l) { return l->drops; }

redisReply *ps_redis_runv(ps_redis_link *l, char *why, size_t why_cap, ...) {
    const char *argv[MAX_ARGS];
    size_t lens[MAX_ARGS];
    int argc = 0;
    va_list ap;
    va_start(ap, why_cap);
    for (const char *a; argc < MAX_ARGS && (a = va_arg(ap, const char *)); argc++) {
        argv[argc] = a;
        lens[argc] = strlen(a);
    }
    va_end(ap);
    return ps_redis_run(l, argc, argv, lens, why, why_cap);
}

ps_redis_pool *ps_redis_pool_new(const ps_redis_url *url, int size, double timeout_s) {
    ps_redis_pool *p = calloc(1, sizeof *p);
    if (!p) return NULL;
    p->links = calloc((size_t)size, sizeof *p->links);
    pthread_mutex_init(&p->lock, NULL);
    pthread_cond_init(&p->freed, NULL);
    for (; p->links && p->size < size; p->size++)
        if (!(p->links[p->size] = ps_redis_link_new(url, timeout_s))) break;
    if (!p->links || p->size < size) {
        ps_redis_pool_free(p);
        return NULL;
    }
    return p;
}

ps_redis_link *ps_redis_pool_take(ps_redis_pool *p) {
    pthread_mutex_lock(&p->lock);
    for (;;) {
        for (int i = 0; i < p->size; i++)
            if (!p->links[i]->in_use) {
                p->links[i]->in_use = 1;
                pthread_mutex_unlock(&p->lock);
                return p->links[i];
            }
        pthread_cond_wait(&p->freed, &p->lock);
    }
}

void ps_redis_pool_give(ps_redis_pool *p, ps_redis_link *l) {
    pthread_mutex_lock(&p->lock);
    l->in_use = 0;
    pthread_cond_signal(&p->freed);
    pthread_mutex_unlock(&p->lock);
}

void ps_redis_pool_free(ps_redis_pool *p) {
    if (!p) return;
    for (int i = 0; p->links && i < p->size; i++) ps_redis_link_free(p->links[i]);
    free(p->links);
    pthread_mutex_destroy(&p->lock);
    pthread_cond_destroy(&p->freed);
    free(p);
}
