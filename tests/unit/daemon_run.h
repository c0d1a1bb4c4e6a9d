/*
 * daemon_run.h: a pointsegd child process for the integration tests: started
 * on a free loopback port with extra flags (stderr to
 * /tmp/pointsegd-itest-<pid>.log), a client for it, a health check, and a
 * raw-socket exchange for requests libcurl would not send.
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
} ps_daemon;

/* Starts BUILD/pointsegd with args (NULL-terminated, may be NULL) and waits
 * until /healthz answers; 0 or -1. */
int ps_daemon_start(ps_daemon *d, const char *const *args);

/* SIGTERM and the exit status (see ps_test_daemon_stop). */
int ps_daemon_stop(ps_daemon *d, double timeout_s);

int ps_daemon_healthy(const ps_daemon *d);

/* A connected loopback socket to the daemon with a receive timeout, or -1. */
int ps_daemon_connect(const ps_daemon *d, double timeout_s);

/* Sends request on a new connection and reads the answer until the daemon
 * closes or timeout_s passes: the status of the first answer, or 0. */
int ps_raw_status(const ps_daemon *d, const char *request, size_t len);

#endif
