/*
 * redis_link.h: pointsegd's connections to Redis (hiredis): the --redis URL,
 * a connection that connects on first use and again after any failure (with
 * a short back-off, so a Redis that is down costs a caller no more than the
 * timeouts), a small pool of them for the HTTP threads, and the command,
 * error and latency counters /metrics shows.
 *
 * A connection is used by one thread at a time.
 */
#ifndef PS_REDIS_LINK_H
#define PS_REDIS_LINK_H

#include <stddef.h>

#include <hiredis/hiredis.h>

typedef struct ps_redis_url {
    char host[256];
    int port;            /* default 6379 */
    char password[256];  /* "" = no AUTH */
    int db;              /* SELECT db when not 0 */
} ps_redis_url;

/* redis://[:password@]host[:port][/db].  Returns 0, or -1 with why. */
int ps_redis_url_parse(const char *text, ps_redis_url *url, char *why, size_t why_cap);

typedef struct ps_redis_counters {
    unsigned long long commands;  /* commands sent (answered or not) */
    unsigned long long errors;    /* unreachable, timed out, or an error reply */
    double seconds;               /* summed time of the commands (not of blocking reads) */
} ps_redis_counters;

/* The process's counters over every connection. */
void ps_redis_counters_get(ps_redis_counters *c);

typedef struct ps_redis_link ps_redis_link;

/* A connection (not yet connected); timeout_s bounds connecting and each
 * command.  NULL when out of memory. */
ps_redis_link *ps_redis_link_new(const ps_redis_url *url, double timeout_s);
void ps_redis_link_free(ps_redis_link *l);

/* Runs one command (once more on a new connection when the one it had
 * broke: Redis restarted since).  Returns the reply (freeReplyObject), or
 * NULL with why ("Redis at host:port is unreachable: ...", or the error
 * reply's text). */
redisReply *ps_redis_run(ps_redis_link *l, int argc, const char **argv, const size_t *lens,
                         char *why, size_t why_cap);

/* The same with NUL-terminated arguments, NULL-terminated. */
redisReply *ps_redis_runv(ps_redis_link *l, char *why, size_t why_cap, ...);

/* How many calls lost their connection after sending: each may have run in
 * Redis without its answer coming back. */
unsigned long ps_redis_link_drops(const ps_redis_link *l);

typedef struct ps_redis_pool ps_redis_pool;

ps_redis_pool *ps_redis_pool_new(const ps_redis_url *url, int size, double timeout_s);
/* A free connection of the pool (waits for one); give it back after use. */
ps_redis_link *ps_redis_pool_take(ps_redis_pool *p);
void ps_redis_pool_give(ps_redis_pool *p, ps_redis_link *l);
void ps_redis_pool_free(ps_redis_pool *p);

#endif
