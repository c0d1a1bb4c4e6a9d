/*
 * fuzz_head.c: libFuzzer target for whole requests to pointsegd, head and
 * body as the client sends them (server/admit.c's checks, the guard, the
 * routes, keep-alive and deferred answers, problem+json).  Each input goes
 * over a raw socket to the in-process server (daemon_harness.h), then the
 * write side is shut down.
 *
 * Besides the sanitizers: the daemon must answer or close within the
 * timeout (a hang traps); an answer must not be a 5xx other than 501, 503
 * and libmicrohttpd's own 505 (HTTP version); a problem+json answer must be a JSON object whose bytes are valid
 * UTF-8.
 */
#include <cJSON.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "daemon_harness.h"
#include "problem.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* 1 when a problem+json answer's body is a JSON object in valid UTF-8. */
static int problem_is_sound(const char *answer) {
    const char *body = strstr(answer, "\r\n\r\n");
    if (!strstr(answer, PS_PROBLEM_MEDIA_TYPE) || !body) return 1;
    cJSON *doc = cJSON_Parse(body + 4);
    char *clean = ps_problem_utf8(body + 4);
    int sound = cJSON_IsObject(doc) && clean && !strcmp(clean, body + 4);
    cJSON_Delete(doc);
    free(clean);
    return sound;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const char *answer = "";
    double start = now_s();
    int fd = ps_fuzz_connect(ps_fuzz_server_port());
    if (fd < 0) abort();
    size_t whole = ps_fuzz_send_all(fd, data, size) ? 0 : (shutdown(fd, SHUT_WR), ps_fuzz_read_answer(fd, &answer));
    close(fd);
    double took = now_s() - start;
    int status = whole && !strncmp(answer, "HTTP/1.", 7) ? atoi(answer + 9) : 0;
    if (took > PS_FUZZ_ANSWER_TIMEOUT_S - 1 || (status >= 500 && status != 501 && status != 503 && status != 505) ||
        (whole && !problem_is_sound(answer))) {
        fprintf(stderr, "fuzz_head: status %d after %.3f s: %.300s\n", status, took, answer);
        __builtin_trap();
    }
    return 0;
}
