/*
 * redis_proc.h: a real redis-server for the tests, as a child process on a
 * free loopback port with its own scratch directory and append-only file
 * (so a restart keeps the data, as in production), stopped and restarted on
 * the same port, and a plain hiredis connection to look inside.
 */
#ifndef PS_REDIS_PROC_H
#define PS_REDIS_PROC_H

#include <sys/types.h>

#include <hiredis/hiredis.h>

typedef struct ps_test_redis {
    pid_t pid;
    int port;
    char dir[256];
} ps_test_redis;

/* Starts one and waits until it answers.  0, or -1 with why (redis-server
 * missing, or not answering). */
int ps_test_redis_start(ps_test_redis *r, char *why, size_t why_cap);

/* SIGTERM and wait (it writes its append-only file). */
void ps_test_redis_stop(ps_test_redis *r);

/* Starts it again on the same port and directory; 0 or -1. */
int ps_test_redis_restart(ps_test_redis *r);

/* Stops it and removes its directory. */
void ps_test_redis_cleanup(ps_test_redis *r);

/* A connection to it (redisFree), or NULL. */
redisContext *ps_test_redis_connect(const ps_test_redis *r);

#endif
