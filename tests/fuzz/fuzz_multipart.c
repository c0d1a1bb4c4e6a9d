/*
 * fuzz_multipart.c: libFuzzer target for the multipart/form-data path of
 * pointsegd (server/body.c on libmicrohttpd's post processor, then intake
 * and, for a well-formed body, a job).  The post processor reads the
 * boundary from a live connection's headers, so the daemon's HTTP layer is
 * started in-process once (daemon_harness.h) and each input is sent as the body of
 * POST /segment with a fixed boundary over a raw socket.
 *
 * Besides the sanitizers, every input must get a complete HTTP answer with
 * one of the statuses the route documents for such bodies (200, 400, 413,
 * 422; a file part in no known format is a 400); anything else (no answer,
 * 415, 500, a malformed answer) traps.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "daemon_harness.h"

#define BOUNDARY "psfuzzboundary"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The HTTP status of a whole answer, or -1. */
static int read_status(int fd) {
    const char *text;
    if (!ps_fuzz_read_answer(fd, &text) || strncmp(text, "HTTP/1.1 ", 9)) return -1;
    return atoi(text + 9);
}

static int expected(int status) {
    return status == 200 || status == 400 || status == 413 || status == 422;
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
    int fd = ps_fuzz_connect(ps_fuzz_server_port());
    if (fd < 0) abort();
    int status = -1;
    if (!ps_fuzz_send_all(fd, head, (size_t)len) && !ps_fuzz_send_all(fd, data, size)) status = read_status(fd);
    close(fd);
    if (!expected(status)) {
        fprintf(stderr, "fuzz_multipart: answer status %d after %.3f s (-1: none or incomplete)\n",
                status, now_s() - start);
        __builtin_trap();
    }
    return 0;
}
