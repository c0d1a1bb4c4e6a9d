/*
 * daemon_run.h: a pointsegd child process for the integration tests: started
 * on a port it picks itself (--port 0, read back from its log) with extra
 * flags, its stderr in a log file kept when it does not stop well, a client
 * for it, a health check, and a raw-socket exchange for requests libcurl
 * would not send.
 */
#ifndef PS_DAEMON_RUN_H
#define PS_DAEMON_RUN_H

#include <stddef.h>
#include <sys/types.h>

#include "daemon_proc.h"
#include "pointseg_client.h"

typedef struct ps_daemon {
    pid_t pid;
    int port;
    char base_url[64];
    ps_client client;
    char log[64];    /* its stderr; removed when it stops well */
    char why[1024];  /* how it ended and its last log lines, when not well */
} ps_daemon;

/* Starts BUILD/pointsegd with args (NULL-terminated, may be NULL) on the
 * loopback port it announces in its log (so no other process can be
 * answering in its place) and waits until /healthz answers; 0, or -1 with
 * d->why. */
int ps_daemon_start(ps_daemon *d, const char *const *args);

/* SIGTERM; 0 when d exited 0, else -1 with d->why. */
int ps_daemon_stop(ps_daemon *d, double timeout_s);

/* Starts d with the NULL-terminated args, or fails the test saying why
 * (testlib.h). */
#define REQUIRE_STARTS(d, ...)                                                        \
    do {                                                                              \
        if (ps_daemon_start(&(d), (const char *const[]){__VA_ARGS__}) != 0) {         \
            ps_test_fail(__FILE__, __LINE__, "pointsegd did not start: %s", (d).why); \
            return;                                                                   \
        }                                                                             \
    } while (0)

/* Stops d and checks that it exited 0; the failure says how it ended. */
#define CHECK_STOPS(d, timeout_s) CHECK_MSG(ps_daemon_stop(&(d), timeout_s) == 0, "%s", (d).why)

int ps_daemon_healthy(const ps_daemon *d);

/* A connected loopback socket to the daemon with a receive timeout, or -1. */
int ps_daemon_connect(const ps_daemon *d, double timeout_s);

/* Sends request on a new connection and reads the answer until the daemon
 * closes or timeout_s passes: the status of the first answer, or 0. */
int ps_raw_status(const ps_daemon *d, const char *request, size_t len);

#endif
