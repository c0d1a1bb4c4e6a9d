/*
 * fuzz_multipart.c: libFuzzer target for the multipart/form-data path of
 * pointsegd (server/body.c on libmicrohttpd's post processor, then intake
 * and, for a well-formed body, a job).  The post processor reads the
 * boundary from a live connection's headers, so the daemon's HTTP layer is
 * started in-process once (loopback, any free port, at most 64 points per
 * request so a job is quick) and each input is sent as the body of
 * POST /segment with a fixed boundary over a raw socket.
 *
 * Besides the sanitizers, every input must get a complete HTTP answer with
 * one of the statuses the route documents for such bodies (200, 400, 413,
 * 415 for a file part in no known format, 422); anything else (no answer, 500, a malformed answer) traps.
 */
#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <time.h>
#include <unistd.h>

#include "config.h"
#include "http.h"
#include "jobs.h"

#define BOUNDARY "psfuzzboundary"
#define ANSWER_TIMEOUT_S 8 /* under run.sh's -timeout=10 */
#define ANSWER_CAP 65536

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int server_port(void) {
    static ps_config cfg;
    static int port;
    if (port) return port;
    char *argv[] = {"fuzz", "--port", "0", "--bind", "127.0.0.1", "--quiet", "--max-points", "64",
                    "--threads", "1", NULL};
    char why[256];
    if (ps_config_load(&cfg, 10, argv, stdout, stderr)) abort();
    ps_jobs_config jc = {cfg.threads, cfg.queue_size, cfg.job_ttl, cfg.max_jobs_kept, cfg.max_kept_bytes, NULL};
    ps_jobs *jobs = ps_jobs_start(&jc);
    ps_http *http = jobs ? ps_http_start(&cfg, jobs, why, sizeof why) : NULL;
    if (!http) {
        fprintf(stderr, "fuzz_multipart: cannot start the server\n");
        abort();
    }
    port = ps_http_port(http);
    return port;
}

static int connect_loopback(int port) {
    struct sockaddr_in a = {.sin_family = AF_INET, .sin_port = htons((uint16_t)port),
                            .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    struct timeval tv = {ANSWER_TIMEOUT_S, 0};
    struct linger reset = {1, 0}; /* close with RST: no TIME_WAIT pile-up */
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0) return -1;
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
    setsockopt(fd, SOL_SOCKET, SO_LINGER, &reset, sizeof reset);
    if (connect(fd, (struct sockaddr *)&a, sizeof a)) {
        close(fd);
        return -1;
    }
    return fd;
}

static int send_all(int fd, const void *data, size_t len) {
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

/* Bytes of the answer in buf[0..len) once complete (headers and
 * Content-Length bytes of body), else 0. */
static size_t answer_length(const char *buf, size_t len) {
    const char *end = strstr(buf, "\r\n\r\n");
    if (!end) return 0;
    size_t head = (size_t)(end - buf) + 4, body = 0;
    for (const char *h = buf; h && h < end; h = strstr(h, "\r\n"), h = h ? h + 2 : NULL)
        if (!strncasecmp(h, "Content-Length:", 15)) body = strtoul(h + 15, NULL, 10);
    return head + body <= len ? head + body : 0;
}

/* Reads one whole answer; its HTTP status, or -1. */
static int read_status(int fd) {
    static char buf[ANSWER_CAP + 1];
    size_t len = 0;
    while (len < ANSWER_CAP) {
        ssize_t n = recv(fd, buf + len, ANSWER_CAP - len, 0);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        len += (size_t)n;
        buf[len] = 0;
        if (answer_length(buf, len)) break;
    }
    buf[len] = 0;
    if (!answer_length(buf, len) || strncmp(buf, "HTTP/1.1 ", 9)) return -1;
    return atoi(buf + 9);
}

static int expected(int status) {
    return status == 200 || status == 400 || status == 413 || status == 415 || status == 422;
}

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    char head[256];
    double start = now_s();
    int len = snprintf(head, sizeof head,
                       "POST /segment HTTP/1.1\r\nHost: fuzz\r\n"
                       "Content-Type: multipart/form-data; boundary=" BOUNDARY "\r\n"
                       "Content-Length: %zu\r\n\r\n", size);
    int fd = connect_loopback(server_port());
    if (fd < 0) abort();
    int status = -1;
    if (!send_all(fd, head, (size_t)len) && !send_all(fd, data, size)) status = read_status(fd);
    close(fd);
    if (!expected(status)) {
        fprintf(stderr, "fuzz_multipart: answer status %d after %.3f s (-1: none or incomplete)\n",
                status, now_s() - start);
        __builtin_trap();
    }
    return 0;
}
