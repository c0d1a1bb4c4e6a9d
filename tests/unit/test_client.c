/*
 * test_client.c: the C client's pieces that need no daemon (the calls that
 * do are tested against a live pointsegd in tests/integration/test_daemon.c),
 * and ps_client_wait against a stand-in server that answers slowly.
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

/* Listens on a free loopback port; its URL into url.  0 or -1. */
static int slow_server_listen(slow_server *s, char *url, size_t cap) {
    struct sockaddr_in a = {0};
    socklen_t len = sizeof a;
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    s->fd = socket(AF_INET, SOCK_STREAM, 0);
    if (s->fd < 0) return -1;
    if (bind(s->fd, (struct sockaddr *)&a, sizeof a) || listen(s->fd, 8) ||
        getsockname(s->fd, (struct sockaddr *)&a, &len)) {
        close(s->fd);
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
    REQUIRE(slow_server_listen(&s, url, sizeof url) == 0);
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

PS_TEST_MAIN(TEST(test_final_states), TEST(test_wait_timeout_counts_slow_polls))
