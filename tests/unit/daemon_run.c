/* daemon_run.c: the pointsegd child process of daemon_run.h. */
#include "daemon_run.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <stdint.h>
#include <stdio.h>
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

static void exec_daemon(const char *path, int port, const char *const *args) {
    char port_text[16], log[64];
    const char *argv[MAX_ARGS + 8] = {path, "--port", port_text, "--bind", "127.0.0.1"};
    size_t n = 5;
    snprintf(port_text, sizeof port_text, "%d", port);
    for (; args && *args && n < MAX_ARGS; args++) argv[n++] = *args;
    argv[n] = NULL;
    snprintf(log, sizeof log, "/tmp/pointsegd-itest-%d.log", (int)getpid());
    int fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) dup2(fd, 2);
    execv(path, (char *const *)(uintptr_t)argv);
    _exit(127);
}

int ps_daemon_start(ps_daemon *d, const char *const *args) {
    char path[4200];
    memset(d, 0, sizeof *d);
    if (ps_test_daemon_path(path, sizeof path) || access(path, X_OK)) return -1;
    d->port = ps_test_free_port();
    if (d->port <= 0) return -1;
    snprintf(d->base_url, sizeof d->base_url, "http://127.0.0.1:%d", d->port);
    d->client = (ps_client){d->base_url, NULL, 60000};
    d->pid = fork();
    if (d->pid < 0) return -1;
    if (d->pid == 0) exec_daemon(path, d->port, args);
    for (int i = 0; i < 200; i++) {
        if (ps_daemon_healthy(d)) return 0;
        if (waitpid(d->pid, NULL, WNOHANG) == d->pid) return d->pid = 0, -1;
        ps_test_sleep_ms(25);
    }
    ps_daemon_stop(d, 1);
    return -1;
}

int ps_daemon_stop(ps_daemon *d, double timeout_s) {
    return ps_test_daemon_stop(&d->pid, timeout_s);
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
