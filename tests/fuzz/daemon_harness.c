/* daemon_harness.c: the in-process server and raw exchange of daemon_harness.h. */
#include "daemon_harness.h"

#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <poll.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include "config.h"
#include "http.h"
#include "jobs.h"
#include "jobstore.h"

#define ANSWER_CAP 65536

int ps_fuzz_server_port(void) {
    static ps_config cfg;
    static int port;
    if (port) return port;
    char *argv[] = {"fuzz", "--port", "0", "--bind", "127.0.0.1", "--quiet", "--max-points", "64",
                    "--threads", "1", NULL};
    char why[256];
    if (ps_config_load(&cfg, 10, argv, stdout, stderr)) abort();
    ps_jobs_config jc = {cfg.threads, cfg.queue_size, cfg.job_ttl, cfg.max_jobs_kept, cfg.max_kept_bytes,
                         NULL};
    ps_jobs *jobs = ps_jobs_start(&jc);
    ps_jobstore *store = jobs ? ps_jobstore_memory_new(jobs) : NULL;
    ps_http *http = store ? ps_http_start(&cfg, jobs, store, why, sizeof why) : NULL;
    if (!http) {
        fprintf(stderr, "fuzz: cannot start the server\n");
        abort();
    }
    port = ps_http_port(http);
    return port;
}

/* A connect interrupted by libFuzzer's SIGALRM timer goes on in the
 * background: 1 once it has succeeded. */
static int connect_finished(int fd) {
    struct pollfd p = {fd, POLLOUT, 0};
    int error = 0;
    socklen_t len = sizeof error;
    while (poll(&p, 1, PS_FUZZ_ANSWER_TIMEOUT_S * 1000) < 0 && errno == EINTR) continue;
    return (p.revents & POLLOUT) && getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &len) == 0 && error == 0;
}

int ps_fuzz_connect(int port) {
    struct sockaddr_in a = {.sin_family = AF_INET, .sin_port = htons((uint16_t)port),
                            .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    struct timeval tv = {PS_FUZZ_ANSWER_TIMEOUT_S, 0};
    struct linger reset = {1, 0}; /* close with RST: no TIME_WAIT pile-up */
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0) return -1;
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
    setsockopt(fd, SOL_SOCKET, SO_LINGER, &reset, sizeof reset);
    if (connect(fd, (struct sockaddr *)&a, sizeof a) && !(errno == EINTR && connect_finished(fd))) {
        close(fd);
        return -1;
    }
    return fd;
}

int ps_fuzz_send_all(int fd, const void *data, size_t len) {
    const char *p = data;
    while (len) {
        ssize_t n = send(fd, p, len, MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR) continue; /* libFuzzer's SIGALRM timer */
        if (n <= 0) return -1;
        p += n;
        len -= (size_t)n;
    }
    return 0;
}

/* The final answer in buf: past any interim 1xx answer. */
static const char *final_answer(const char *buf) {
    while (!strncmp(buf, "HTTP/1.1 1", 10) && strstr(buf, "\r\n\r\n")) buf = strstr(buf, "\r\n\r\n") + 4;
    return buf;
}

/* Bytes of the answer in buf[0..len) once complete, else 0. */
static size_t answer_length(const char *buf, size_t len) {
    const char *end = strstr(buf, "\r\n\r\n");
    if (!end) return 0;
    size_t head = (size_t)(end - buf) + 4, body = 0;
    for (const char *h = buf; h && h < end; h = strstr(h, "\r\n"), h = h ? h + 2 : NULL)
        if (!strncasecmp(h, "Content-Length:", 15)) body = strtoul(h + 15, NULL, 10);
    return head + body <= len ? head + body : 0;
}

size_t ps_fuzz_read_answer(int fd, const char **text) {
    static char buf[ANSWER_CAP + 1];
    size_t len = 0, whole = 0;
    const char *answer = buf;
    buf[0] = 0;
    while (len < ANSWER_CAP && !whole) {
        ssize_t n = recv(fd, buf + len, ANSWER_CAP - len, 0);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        len += (size_t)n;
        buf[len] = 0;
        answer = final_answer(buf);
        whole = answer_length(answer, len - (size_t)(answer - buf));
    }
    *text = answer;
    return whole;
}
