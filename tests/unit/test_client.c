/*
 * test_client.c: the C client's pieces that need no daemon (the calls that
 * do are tested against a live pointsegd in tests/integration/test_daemon.c),
 * ps_client_wait against a stand-in server that answers slowly, long
 * requests against one that keeps the request head it reads, and long
 * answer headers from one that sends them.
 */
#include "pointseg_client.h"
#include "testlib.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

static void test_final_states(void) {
    CHECK(ps_client_job_is_final("done"));
    CHECK(ps_client_job_is_final("failed"));
    CHECK(ps_client_job_is_final("cancelled"));
    CHECK(!ps_client_job_is_final("queued"));
    CHECK(!ps_client_job_is_final("running"));
    CHECK(!ps_client_job_is_final(""));
    CHECK(!ps_client_job_is_final("Done"));
}

/* A loopback server answering every request, one connection at a time,
 * with a "running" job status after delay_ms; ends when fd is shut down. */
typedef struct slow_server {
    int fd;
    long delay_ms;
} slow_server;

static void *serve_slowly(void *arg) {
    const slow_server *s = arg;
    static const char answer[] = "HTTP/1.1 200 OK\r\nContent-Type: application/json\r\n"
                                 "Content-Length: 20\r\nConnection: close\r\n\r\n"
                                 "{\"status\":\"running\"}";
    struct timespec delay = {s->delay_ms / 1000, (s->delay_ms % 1000) * 1000000L};
    char head[4096];
    int conn;
    while ((conn = accept(s->fd, NULL, NULL)) >= 0) {
        ssize_t got = recv(conn, head, sizeof head, 0);
        nanosleep(&delay, NULL);
        if (got > 0) (void)send(conn, answer, sizeof answer - 1, MSG_NOSIGNAL);
        close(conn);
    }
    return NULL;
}

/* Listens on a free loopback port (*fd); its URL into url.  0 or -1. */
static int listen_loopback(int *fd, char *url, size_t cap) {
    struct sockaddr_in a = {0};
    socklen_t len = sizeof a;
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    *fd = socket(AF_INET, SOCK_STREAM, 0);
    if (*fd < 0) return -1;
    if (bind(*fd, (struct sockaddr *)&a, sizeof a) || listen(*fd, 8) ||
        getsockname(*fd, (struct sockaddr *)&a, &len)) {
        close(*fd);
        return -1;
    }
    snprintf(url, cap, "http://127.0.0.1:%d", ntohs(a.sin_port));
    return 0;
}

static double seconds_since(const struct timespec *t0) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)(t.tv_sec - t0->tv_sec) + (double)(t.tv_nsec - t0->tv_nsec) * 1e-9;
}

/* The timeout is time on the clock: polls that take 1 s each do not stretch
 * a 200 ms wait (it counted only its 20 ms pauses: 10 polls, over 10 s). */
static void test_wait_timeout_counts_slow_polls(void) {
    slow_server s = {-1, 1000};
    char url[64], state[32] = "";
    pthread_t thread;
    REQUIRE(ps_client_global_init() == 0);
    REQUIRE(listen_loopback(&s.fd, url, sizeof url) == 0);
    REQUIRE(pthread_create(&thread, NULL, serve_slowly, &s) == 0);
    ps_client c = {url, NULL, 0};
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    CHECK(ps_client_wait(&c, "job", 200, state, sizeof state) == -1);
    double took = seconds_since(&t0);
    CHECK_MSG(took < 0.9, "a 200 ms wait took %.2f s", took);
    shutdown(s.fd, SHUT_RDWR);
    pthread_join(thread, NULL);
    close(s.fd);
}

/* A loopback server answering one request with answer (NULL: 200 "{}"),
 * the request's head (up to its blank line) kept in head. */
typedef struct recording_server {
    int fd;
    const char *answer;
    char head[16384];
    size_t len;
} recording_server;

static void *serve_recording(void *arg) {
    recording_server *s = arg;
    static const char plain[] = "HTTP/1.1 200 OK\r\nContent-Length: 2\r\n"
                                "Connection: close\r\n\r\n{}";
    const char *answer = s->answer ? s->answer : plain;
    int conn = accept(s->fd, NULL, NULL);
    if (conn < 0) return NULL;
    ssize_t got = 1;
    while (got > 0 && s->len < sizeof s->head - 1 && !strstr(s->head, "\r\n\r\n")) {
        got = recv(conn, s->head + s->len, sizeof s->head - 1 - s->len, 0);
        if (got > 0) s->len += (size_t)got;
        s->head[s->len] = 0;
    }
    (void)send(conn, answer, strlen(answer), MSG_NOSIGNAL);
    close(conn);
    return NULL;
}

/* Starts s (emptied here, answering answer) on a free loopback port; its
 * URL into url.  0 or -1. */
static int start_server(recording_server *s, const char *answer, char *url, size_t cap,
                        pthread_t *thread) {
    memset(s, 0, sizeof *s);
    s->answer = answer;
    if (listen_loopback(&s->fd, url, cap)) return -1;
    if (pthread_create(thread, NULL, serve_recording, s) == 0) return 0;
    close(s->fd);
    return -1;
}

static void stop_server(recording_server *s, pthread_t thread) {
    shutdown(s->fd, SHUT_RDWR);
    pthread_join(thread, NULL);
    close(s->fd);
}

/* Sends one request with client c (its base_url set here) to a recording
 * server s: POST /segment?query, or with query NULL GET /jobs/{id}.  0 when
 * it was answered 200; its head is then in s->head. */
static int record_request(recording_server *s, ps_client *c, const char *id, const char *query) {
    char url[64];
    pthread_t thread;
    ps_client_response r;
    if (start_server(s, NULL, url, sizeof url, &thread)) return -1;
    c->base_url = url;
    int rc = query ? ps_client_segment(c, NULL, query, &r) : ps_client_poll(c, id, &r);
    rc = rc == 0 && r.status == 200 ? 0 : -1;
    ps_client_response_free(&r);
    stop_server(s, thread);
    c->base_url = NULL;
    return rc;
}

/* prefix, n times fill, then suffix into out. */
static void long_text(char *out, size_t cap, const char *prefix, char fill, size_t n,
                      const char *suffix) {
    size_t at = (size_t)snprintf(out, cap, "%s", prefix);
    for (size_t i = 0; i < n && at + 1 < cap; i++) out[at++] = fill;
    snprintf(out + at, cap - at, "%s", suffix);
}

/* A long query, token or job id goes out whole (they were cut at the
 * client's 512- and 1024-byte buffers: the daemon got another request). */
static void test_long_requests_sent_whole(void) {
    static recording_server s;
    char query[3001], token[2001], id[1501], want[3200];
    long_text(query, sizeof query, "", 'q', 3000, "");
    long_text(token, sizeof token, "", 't', 2000, "");
    long_text(id, sizeof id, "", 'i', 1500, "");
    REQUIRE(ps_client_global_init() == 0);
    ps_client c = {NULL, token, 0};
    REQUIRE(record_request(&s, &c, NULL, query) == 0);
    long_text(want, sizeof want, "POST /segment?", 'q', 3000, " HTTP/1.1\r\n");
    CHECK_MSG(strstr(s.head, want) != NULL, "request line cut: %.80s...", s.head);
    long_text(want, sizeof want, "\r\nAuthorization: Bearer ", 't', 2000, "\r\n");
    CHECK_MSG(strstr(s.head, want) != NULL, "token cut (%zu head bytes)", s.len);
    REQUIRE(record_request(&s, &c, id, NULL) == 0);
    long_text(want, sizeof want, "GET /jobs/", 'i', 1500, " HTTP/1.1\r\n");
    CHECK_MSG(strstr(s.head, want) != NULL, "job path cut: %.80s...", s.head);
}

/* GET /jobs/j answered by a recording server s with answer: what
 * ps_client_request returned (-2 when the server did not start), the
 * response in *r. */
static int answered_request(recording_server *s, const char *answer, ps_client_response *r) {
    char url[64];
    pthread_t thread;
    if (start_server(s, answer, url, sizeof url, &thread)) return -2;
    ps_client c = {url, NULL, 0};
    int rc = ps_client_request(&c, "GET", "/jobs/j", NULL, NULL, r);
    stop_server(s, thread);
    return rc;
}

/* An answer head: Location (location), then n filler lines of 100 bytes,
 * then Content-Type (type), Allow (allow) and Retry-After: 120.  Its
 * length, or 0 when it does not fit cap. */
static size_t answer_head(char *out, size_t cap, const char *location, int n, const char *type,
                          const char *allow) {
    char filler[101];
    long_text(filler, sizeof filler, "", 'f', 100, "");
    size_t at = (size_t)snprintf(out, cap, "HTTP/1.1 202 Accepted\r\nLocation: %s\r\n", location);
    for (int i = 0; i < n && at < cap; i++)
        at += (size_t)snprintf(out + at, cap - at, "X-Filler-%d: %s\r\n", i, filler);
    if (at < cap)
        at += (size_t)snprintf(out + at, cap - at,
                               "Content-Type: %s\r\nAllow: %s\r\nRetry-After: 120\r\n"
                               "Content-Length: 2\r\nConnection: close\r\n\r\n{}", type, allow);
    return at < cap ? at : 0;
}

/* Long answer headers, after many others, are read whole (they were cut
 * to the response's 128- and 256-byte fields); an answer whose header
 * lines pass 64 KiB is refused, saying so. */
static void test_long_answer_headers_read_whole(void) {
    static recording_server s;
    static char answer[100000];
    char location[4101], type[1101], allow[1201];
    long_text(location, sizeof location, "/jobs/", 'j', 4000, "");
    long_text(type, sizeof type, "application/problem+json; profile=\"", 'p', 1000, "\"");
    long_text(allow, sizeof allow, "GET, HEAD", 'A', 1000, ", OPTIONS");
    REQUIRE(ps_client_global_init() == 0);
    REQUIRE(answer_head(answer, sizeof answer, location, 300, type, allow) > 0);
    ps_client_response r;
    int rc = answered_request(&s, answer, &r);
    REQUIRE(rc != -2);
    CHECK_MSG(rc == 0 && r.status == 202, "rc %d, status %ld: %s", rc, r.status, r.error);
    CHECK_MSG(!strcmp(r.location, location), "Location: %zu of %zu bytes", strlen(r.location),
              strlen(location));
    CHECK_MSG(!strcmp(r.content_type, type), "Content-Type: %zu of %zu bytes", strlen(r.content_type),
              strlen(type));
    CHECK_MSG(!strcmp(r.allow, allow), "Allow: %zu of %zu bytes", strlen(r.allow), strlen(allow));
    CHECK_MSG(!strcmp(r.retry_after, "120"), "Retry-After: '%s'", r.retry_after);
    ps_client_response_free(&r);
    REQUIRE(answer_head(answer, sizeof answer, location, 700, type, allow) > 0);
    rc = answered_request(&s, answer, &r);
    REQUIRE(rc != -2);
    CHECK_MSG(rc == -1 && r.status == 0 && strstr(r.error, "65536"),
              "over 64 KiB of header lines: rc %d, status %ld, error '%s'", rc, r.status, r.error);
    ps_client_response_free(&r);
}

PS_TEST_MAIN(TEST(test_final_states), TEST(test_wait_timeout_counts_slow_polls),
             TEST(test_long_requests_sent_whole), TEST(test_long_answer_headers_read_whole))
