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

/* 1 when the first answer in answer[0..len) is not problem+json, or its
 * body (Content-Length bytes after the head) is a JSON object in valid
 * UTF-8.  Answers to pipelined requests may follow it in the buffer.  An
 * answer to HEAD has a Content-Length but no body, so when nothing or the
 * next answer follows the head there is nothing to judge (this needs no
 * guess at how libmicrohttpd reads the request line). */
static int problem_is_sound(const char *answer, size_t len) {
    char *first = strndup(answer, len);
    char *body = first ? strstr(first, "\r\n\r\n") : NULL;
    int sound = 1;
    if (body && strstr(first, PS_PROBLEM_MEDIA_TYPE) && strstr(first, PS_PROBLEM_MEDIA_TYPE) < body) {
        const char *length = strstr(first, "\r\nContent-Length: ");
        body += 4;
        if (length && length < body) {
            size_t declared = strtoul(length + strlen("\r\nContent-Length: "), NULL, 10);
            if (declared < strlen(body)) body[declared] = '\0';
        }
        if (*body && strncmp(body, "HTTP/1.", 7)) {
            cJSON *doc = cJSON_Parse(body);
            char *clean = ps_problem_utf8(body);
            sound = cJSON_IsObject(doc) && clean && !strcmp(clean, body);
            cJSON_Delete(doc);
            free(clean);
        }
    }
    free(first);
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
        (whole && !problem_is_sound(answer, whole))) {
        fprintf(stderr, "fuzz_head: status %d after %.3f s: %.300s\n", status, took, answer);
        __builtin_trap();
    }
    return 0;
}
