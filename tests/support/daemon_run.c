/* daemon_run.c: the pointsegd child process of daemon_run.h. */
#include "daemon_run.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#define MAX_ARGS 32

int ps_daemon_healthy(const ps_daemon *d) {
    ps_client_response r;
    int ok = ps_client_request(&d->client, "GET", "/healthz", NULL, NULL, &r) == 0 && r.status == 200;
    ps_client_response_free(&r);
    return ok;
}

/* In the child: pointsegd on a port the kernel picks (--port 0), stderr to
 * the log file open as log_fd. */
static void exec_daemon(const char *path, int log_fd, const char *const *args) {
    const char *argv[MAX_ARGS + 8] = {path, "--port", "0", "--bind", "127.0.0.1"};
    size_t n = 5;
    for (; args && *args && n < MAX_ARGS; args++) argv[n++] = *args;
    argv[n] = NULL;
    dup2(log_fd, 2);
    execv(path, (char *const *)(uintptr_t)argv);
    _exit(127);
}

/* 1 when the child has exited (it stays waitable for ps_daemon_stop). */
static int has_exited(pid_t pid) {
    siginfo_t info;
    memset(&info, 0, sizeof info);
    return waitid(P_PID, (id_t)pid, &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid;
}

/* The port the daemon says it listens on (its log's "listening on" line),
 * or 0 when it has not said so yet. */
static int announced_port(const char *log) {
    char text[4096];
    ps_test_log_tail(log, 20, text, sizeof text);
    const char *at = strstr(text, "listening on http://127.0.0.1:");
    return at ? atoi(at + strlen("listening on http://127.0.0.1:")) : 0;
}

int ps_daemon_start(ps_daemon *d, const char *const *args) {
    char path[4200];
    memset(d, 0, sizeof *d);
    snprintf(d->log, sizeof d->log, "/tmp/pointsegd-itest-XXXXXX");
    int log_fd = mkstemp(d->log);
    if (ps_test_daemon_path(path, sizeof path) || access(path, X_OK) || log_fd < 0) {
        snprintf(d->why, sizeof d->why, "no %.900s, or no log file", path);
        if (log_fd >= 0) close(log_fd), remove(d->log);
        return -1;
    }
    d->pid = fork();
    if (d->pid == 0) exec_daemon(path, log_fd, args);
    close(log_fd);
    if (d->pid < 0) return snprintf(d->why, sizeof d->why, "fork failed"), -1;
    for (int i = 0; i < 800 && !d->port && !has_exited(d->pid); i++) {
        d->port = announced_port(d->log);
        if (!d->port) ps_test_sleep_ms(25);
    }
    snprintf(d->base_url, sizeof d->base_url, "http://127.0.0.1:%d", d->port);
    d->client = (ps_client){d->base_url, NULL, 60000};
    if (d->port && ps_daemon_healthy(d)) return 0;
    const char *what = d->port ? "GET /healthz failed" : "it announced no port";
    if (ps_daemon_stop(d, 1) == 0) snprintf(d->why, sizeof d->why, "%s", what);
    return -1;
}

int ps_daemon_stop(ps_daemon *d, double timeout_s) {
    char how[128], tail[768];
    int status = ps_test_daemon_stop(&d->pid, timeout_s, how, sizeof how);
    if (status == 0) {
        remove(d->log);
        return 0;
    }
    ps_test_log_tail(d->log, 8, tail, sizeof tail);
    snprintf(d->why, sizeof d->why, "pointsegd %s; the end of %s:\n%s", how, d->log, tail);
    return -1;
}

int ps_daemon_connect(const ps_daemon *d, double timeout_s) {
    struct sockaddr_in a = {.sin_family = AF_INET, .sin_port = htons((uint16_t)d->port),
                            .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0) return -1;
    struct timeval tv = {(time_t)timeout_s, (suseconds_t)((timeout_s - (double)(time_t)timeout_s) * 1e6)};
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    if (connect(fd, (struct sockaddr *)&a, sizeof a)) {
        close(fd);
        return -1;
    }
    return fd;
}

int ps_raw_status(const ps_daemon *d, const char *request, size_t len) {
    char reply[256] = {0};
    int code = 0, fd = ps_daemon_connect(d, 5);
    if (fd < 0) return 0;
    if (send(fd, request, len, MSG_NOSIGNAL) == (ssize_t)len && recv(fd, reply, sizeof reply - 1, 0) > 0)
        sscanf(reply, "HTTP/1.%*d %d", &code);
    close(fd);
    return code;
}
