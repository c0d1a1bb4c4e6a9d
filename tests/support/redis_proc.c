/* redis_proc.c: the redis-server child process of redis_proc.h. */
#include "redis_proc.h"

#include "daemon_proc.h"

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#define READY_TRIES 100 /* of 50 ms */

static const char *server_path(void) {
    static const char *const candidates[] = {"/usr/bin/redis-server", "/usr/local/bin/redis-server"};
    for (size_t i = 0; i < sizeof candidates / sizeof candidates[0]; i++)
        if (access(candidates[i], X_OK) == 0) return candidates[i];
    return NULL;
}

redisContext *ps_test_redis_connect(const ps_test_redis *r) {
    struct timeval tv = {1, 0};
    redisContext *c = redisConnectWithTimeout("127.0.0.1", r->port, tv);
    if (c && c->err) {
        redisFree(c);
        return NULL;
    }
    if (c) redisSetTimeout(c, tv);
    return c;
}

static int answers(const ps_test_redis *r) {
    redisContext *c = ps_test_redis_connect(r);
    redisReply *reply = c ? redisCommand(c, "PING") : NULL;
    int ok = reply && reply->type == REDIS_REPLY_STATUS;
    if (reply) freeReplyObject(reply);
    if (c) redisFree(c);
    return ok;
}

static int spawn(ps_test_redis *r) {
    const char *path = server_path();
    char port[16], log[300];
    if (!path) return -1;
    snprintf(port, sizeof port, "%d", r->port);
    snprintf(log, sizeof log, "%s/redis.log", r->dir);
    r->pid = fork();
    if (r->pid < 0) return -1;
    if (r->pid == 0) {
        execl(path, path, "--port", port, "--bind", "127.0.0.1", "--dir", r->dir, "--appendonly", "yes",
              "--save", "", "--logfile", log, "--daemonize", "no", (char *)NULL);
        _exit(127);
    }
    for (int i = 0; i < READY_TRIES; i++) {
        if (answers(r)) return 0;
        ps_test_sleep_ms(50);
    }
    return -1;
}

int ps_test_redis_start(ps_test_redis *r, char *why, size_t why_cap) {
    memset(r, 0, sizeof *r);
    if (!server_path()) {
        snprintf(why, why_cap, "redis-server is not installed (apt-get install redis-server; make test does)");
        return -1;
    }
    snprintf(r->dir, sizeof r->dir, "/tmp/pointseg-redis-XXXXXX");
    if (!mkdtemp(r->dir) || (r->port = ps_test_free_port()) <= 0) {
        snprintf(why, why_cap, "no scratch directory or free port");
        return -1;
    }
    if (spawn(r) == 0) return 0;
    snprintf(why, why_cap, "redis-server on port %d did not answer (see %s/redis.log)", r->port, r->dir);
    return -1;
}

void ps_test_redis_stop(ps_test_redis *r) {
    if (r->pid <= 0) return;
    kill(r->pid, SIGTERM);
    waitpid(r->pid, NULL, 0);
    r->pid = 0;
}

int ps_test_redis_restart(ps_test_redis *r) {
    ps_test_redis_stop(r);
    return spawn(r);
}

void ps_test_redis_cleanup(ps_test_redis *r) {
    char cmd[300];
    ps_test_redis_stop(r);
    if (!r->dir[0]) return;
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", r->dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", r->dir);
    r->dir[0] = 0;
}
