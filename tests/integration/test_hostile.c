/*
 * test_hostile.c: pointsegd against hostile and sloppy clients (issue 17):
 * results freed once sent and a byte budget for kept ones, connection
 * limits and slow-client deadlines, prompt answers to refused requests and
 * to endless bodies over the size limit, static files confined to their
 * directory, no silent loss in bodies (gzip members, BOM, two file parts),
 * strict parameters and headers, problem+json that is valid UTF-8,
 * keep-alive after GETs and early errors, and half-closed clients.  Each
 * test starts BUILD/pointsegd on a free port; most talk over raw sockets,
 * for requests libcurl would not send.
 */
#include "daemon_run.h"
#include "gzip_body.h"
#include "shapes.h"
#include "testlib.h"

#include <cJSON.h>
#include <errno.h>
#include <poll.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

static double seconds_now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* ---- raw exchanges ------------------------------------------------------- */

typedef struct reply {
    char text[65536];
    size_t len;
    int closed;     /* the daemon closed the connection */
    double seconds; /* until closed or timed out */
} reply;

/* Reads from fd until the daemon closes it or timeout_s passes. */
static void read_reply(int fd, double timeout_s, reply *out) {
    double t0 = seconds_now();
    out->len = 0;
    out->closed = 0;
    while (seconds_now() - t0 < timeout_s) {
        struct pollfd p = {fd, POLLIN, 0};
        if (poll(&p, 1, 50) <= 0) continue;
        ssize_t n = recv(fd, out->text + out->len, sizeof out->text - 1 - out->len, 0);
        if (n <= 0) {
            out->closed = n == 0 || errno == ECONNRESET;
            if (out->closed) break;
            continue;
        }
        out->len += (size_t)n;
    }
    out->text[out->len] = 0;
    out->seconds = seconds_now() - t0;
}

/* Sends request on a new connection and reads for up to timeout_s. */
static int exchange(const ps_daemon *d, const char *request, size_t len, double timeout_s, reply *out) {
    int fd = ps_daemon_connect(d, 5);
    if (fd < 0) return -1;
    int sent = send(fd, request, len, MSG_NOSIGNAL) == (ssize_t)len;
    read_reply(fd, timeout_s, out);
    close(fd);
    return sent ? 0 : -1;
}

static int count_answers(const reply *r) {
    int n = 0;
    for (const char *p = r->text; (p = strstr(p, "HTTP/1.1 ")); p++) n++;
    return n;
}

static int first_status(const reply *r) {
    int code = 0;
    return sscanf(r->text, "HTTP/1.%*d %d", &code) == 1 ? code : 0;
}

/* The JSON body after the first answer's headers, parsed; NULL if none. */
static cJSON *reply_json(const reply *r) {
    const char *body = strstr(r->text, "\r\n\r\n");
    return body ? cJSON_Parse(body + 4) : NULL;
}

/* ---- bodies --------------------------------------------------------------- */

/* A sphere as XYZ text: 176 points at density 14, 3,200 at 60. */
static char *sphere_xyz(double density, size_t *len, size_t *n_points) {
    double *pts = ps_shape_sphere(density, n_points, NULL);
    char *text = pts ? malloc(*n_points * 3 * 26 + 1) : NULL;
    size_t at = 0;
    for (size_t i = 0; text && i < *n_points; i++)
        at += (size_t)sprintf(text + at, "%.9g %.9g %.9g\n", pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]);
    free(pts);
    *len = at;
    return text;
}

static size_t count_lines(const char *text) {
    size_t n = 0;
    for (; text && *text; text++) n += *text == '\n';
    return n;
}

static long metric(const ps_daemon *d, const char *name) {
    ps_client_response r;
    char needle[128];
    long v = -1;
    snprintf(needle, sizeof needle, "\n%s ", name);
    if (ps_client_request(&d->client, "GET", "/metrics", NULL, NULL, &r) == 0 && r.body) {
        const char *at = strstr(r.body, needle);
        if (at) v = strtol(at + strlen(needle), NULL, 10);
    }
    ps_client_response_free(&r);
    return v;
}

/* The metric once it reaches want, or its value after timeout_s: the
 * daemon's watch thread counts a cut just after it closes the socket. */
static long metric_reaching(const ps_daemon *d, const char *name, long want, double timeout_s) {
    double t0 = seconds_now();
    long v = metric(d, name);
    while (v < want && seconds_now() - t0 < timeout_s) {
        ps_test_sleep_ms(50);
        v = metric(d, name);
    }
    return v;
}

/* ---- 1: results in memory ------------------------------------------------ */

static void test_sync_results_freed_once_sent(void) {
    ps_daemon d;
    size_t len, n;
    char *xyz = sphere_xyz(14, &len, &n);
    REQUIRE(xyz);
    REQUIRE_STARTS(d, NULL);
    ps_client_body body = {xyz, len, NULL, NULL};
    for (int i = 0; i < 5; i++) {
        ps_client_response r;
        CHECK(ps_client_segment(&d.client, &body, "include=centrality,point_supernode", &r) == 0 &&
              r.status == 200);
        ps_client_response_free(&r);
    }
    CHECK_MSG(metric(&d, "pointseg_jobs_kept") == 0, "%ld synchronous jobs kept after their answers",
              metric(&d, "pointseg_jobs_kept"));
    CHECK(metric(&d, "pointseg_jobs_kept_bytes") == 0);
    free(xyz);
    CHECK_STOPS(d, 10);
}

static int wait_done(const ps_daemon *d, const char *id) {
    char state[32];
    return ps_client_wait(&d->client, id, 30000, state, sizeof state) == 0 && !strcmp(state, "done");
}

static void test_kept_results_byte_budget(void) {
    ps_daemon d;
    ps_client_response r;
    size_t len, n;
    char *xyz = sphere_xyz(14, &len, &n), budget[32], ids[4][128];
    REQUIRE(xyz);
    ps_client_body body = {xyz, len, NULL, NULL};
    /* one result is n label lines of at most 3 bytes: the budget holds two */
    snprintf(budget, sizeof budget, "%zu", 2 * n * 2 + n);
    REQUIRE_STARTS(d, "--max-kept-bytes", budget, NULL);
    for (int i = 0; i < 4; i++) {
        REQUIRE(ps_client_submit(&d.client, &body, "output=labels", ids[i], sizeof ids[i], &r) == 0);
        ps_client_response_free(&r);
        CHECK(wait_done(&d, ids[i]));
    }
    CHECK(ps_client_result(&d.client, ids[0], &r) == 0 && r.status == 404);
    ps_client_response_free(&r);
    CHECK(ps_client_result(&d.client, ids[3], &r) == 0 && r.status == 200 && count_lines(r.body) == n);
    ps_client_response_free(&r);
    long kept = metric(&d, "pointseg_jobs_kept_bytes");
    CHECK_MSG(kept > 0 && kept <= atol(budget), "kept %ld bytes, budget %s", kept, budget);
    free(xyz);
    CHECK_STOPS(d, 10);
}

/* ---- 2: connections ------------------------------------------------------- */

/* 1 when the daemon closed fd (or reset it) within timeout_s. */
static int closed_within(int fd, double timeout_s) {
    reply r;
    read_reply(fd, timeout_s, &r);
    return r.closed;
}

static void test_per_ip_connection_limit(void) {
    ps_daemon d;
    int fds[4];
    REQUIRE_STARTS(d, "--max-connections-per-ip", "3", NULL);
    ps_test_sleep_ms(100); /* the health check's connection is gone */
    for (int i = 0; i < 3; i++) fds[i] = ps_daemon_connect(&d, 2);
    ps_test_sleep_ms(100);
    fds[3] = ps_daemon_connect(&d, 2);
    CHECK_MSG(fds[3] < 0 || closed_within(fds[3], 1), "a fourth connection from one address was kept");
    for (int i = 0; i < 4; i++)
        if (fds[i] >= 0) close(fds[i]);
    ps_test_sleep_ms(100);
    CHECK(ps_daemon_healthy(&d));
    CHECK_STOPS(d, 10);
}

static void test_health_checks_get_room(void) {
    enum { LIMIT = 8 };
    ps_daemon d;
    int fds[LIMIT];
    reply r;
    static const char version[] = "GET /version HTTP/1.1\r\nHost: x\r\n\r\n";
    static const char health[] = "GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n";
    REQUIRE_STARTS(d, "--max-connections", "8", NULL);
    ps_test_sleep_ms(200); /* the health check's connection is gone */
    for (int i = 0; i < LIMIT; i++) fds[i] = ps_daemon_connect(&d, 2);
    ps_test_sleep_ms(200);
    CHECK(exchange(&d, health, sizeof health - 1, 1.5, &r) == 0 && first_status(&r) == 200);
    CHECK_MSG(exchange(&d, version, sizeof version - 1, 1.5, &r) == 0 && first_status(&r) == 503 &&
              strstr(r.text, "Retry-After"), "over the limit, /version got '%.60s'", r.text);
    for (int i = 0; i < LIMIT; i++)
        if (fds[i] >= 0) close(fds[i]);
    ps_test_sleep_ms(200);
    CHECK(exchange(&d, version, sizeof version - 1, 1.5, &r) == 0 && first_status(&r) == 200);
    CHECK_STOPS(d, 10);
}

/* Sends prefix, then drip one byte every interval_ms (cycling) until the
 * daemon closes: the seconds that took, or -1 after limit_s. */
static double trickle_until_closed(const ps_daemon *d, const char *prefix, const char *drip,
                                   long interval_ms, double limit_s) {
    int fd = ps_daemon_connect(d, 1);
    if (fd < 0) return -1;
    double t0 = seconds_now(), took = -1;
    int open = send(fd, prefix, strlen(prefix), MSG_NOSIGNAL) == (ssize_t)strlen(prefix);
    for (size_t i = 0; open && seconds_now() - t0 < limit_s; i = (i + 1) % strlen(drip)) {
        char buf[512];
        struct pollfd p = {fd, POLLIN, 0};
        open = send(fd, drip + i, 1, MSG_NOSIGNAL) == 1 &&
               !(poll(&p, 1, (int)interval_ms) > 0 && recv(fd, buf, sizeof buf, 0) <= 0);
        if (!open) took = seconds_now() - t0;
    }
    close(fd);
    return took;
}

static void test_slow_headers_and_bodies_cut(void) {
    ps_daemon d;
    REQUIRE_STARTS(d, "--header-timeout", "2", "--min-upload-rate", "1000",
                                                     NULL);
    double headers = trickle_until_closed(&d, "", "GET /healthz HTTP/1.1\r\nX-Slow: aaaaaaaaaaaaaaaaaaaa",
                                          300, 8);
    CHECK_MSG(headers > 1.5 && headers < 4, "headers trickled for %.1f s (want a cut after 2 s)", headers);
    double body = trickle_until_closed(&d, "POST /segment HTTP/1.1\r\nHost: x\r\nContent-Length: 100000\r\n\r\n",
                                       "0", 500, 8);
    CHECK_MSG(body > 1.5 && body < 4, "a body at 2 bytes/s went on for %.1f s (want a cut after 2 s)", body);
    CHECK(metric_reaching(&d, "pointseg_connections_cut_total", 2, 2.0) == 2);
    CHECK(ps_daemon_healthy(&d));
    CHECK_STOPS(d, 10);
}

/* ---- 3: refused requests are answered at once ---------------------------- */

static void test_refused_requests_answered_promptly(void) {
    ps_daemon d;
    reply r;
    char request[8192];
    size_t at = (size_t)sprintf(request, "GET /healthz?");
    for (int i = 0; i < 500; i++) at += (size_t)sprintf(request + at, "%sa%d=1", i ? "&" : "", i);
    at += (size_t)sprintf(request + at, " HTTP/1.1\r\nHost: x\r\n\r\n");
    REQUIRE_STARTS(d, NULL);
    CHECK(exchange(&d, request, at, 3, &r) == 0);
    CHECK_MSG(first_status(&r) >= 400 && first_status(&r) < 500 && r.seconds < 2,
              "500 query parameters: '%.40s' after %.1f s", r.text, r.seconds);
    static const char gzip_te[] = "POST /segment HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: gzip\r\n\r\nabc";
    CHECK(exchange(&d, gzip_te, sizeof gzip_te - 1, 3, &r) == 0);
    CHECK_MSG(first_status(&r) == 501 && r.seconds < 2, "Transfer-Encoding gzip: '%.40s' after %.1f s",
              r.text, r.seconds);
    /* A client waiting for 100 Continue is refused at once, not invited to
     * send a body that would be read in vain. */
    static const char waits[] = "POST /segment HTTP/1.1\r\nHost: x\r\nContent-Type: image/png\r\n"
                                "Expect: 100-continue\r\nContent-Length: 500000\r\n\r\n";
    CHECK(exchange(&d, waits, sizeof waits - 1, 3, &r) == 0);
    CHECK_MSG(first_status(&r) == 415 && r.closed && r.seconds < 2, "Expect: 100-continue: '%.40s' after %.1f s",
              r.text, r.seconds);
    CHECK(ps_daemon_healthy(&d));
    CHECK_STOPS(d, 10);
}

/* A body cut short by the end of the client's input can never complete:
 * the connection is closed at once, not after a timeout.  Neither client
 * got an answer (the second's 415 waits for its body): both are counted
 * as gone (499), none as answered. */
static void test_truncated_body_closed_promptly(void) {
    ps_daemon d;
    reply r;
    static const char *const cuts[] = {
        "POST /segment HTTP/1.1\r\nHost: x\r\nContent-Length: 7\r\n\r\n0 0 0\n",
        "POST /segment HTTP/1.1\r\nHost: x\r\nContent-Type: image/png\r\nContent-Length: 7\r\n\r\n0 0 0\n"};
    REQUIRE_STARTS(d, NULL);
    for (size_t i = 0; i < sizeof cuts / sizeof cuts[0]; i++) {
        int fd = ps_daemon_connect(&d, 5);
        REQUIRE(fd >= 0);
        CHECK(send(fd, cuts[i], strlen(cuts[i]), MSG_NOSIGNAL) == (ssize_t)strlen(cuts[i]));
        shutdown(fd, SHUT_WR);
        read_reply(fd, 5, &r);
        close(fd);
        CHECK_MSG(r.closed && r.seconds < 2.5, "a truncated body kept its connection %.1f s", r.seconds);
    }
    CHECK(metric_reaching(&d, "pointseg_http_requests_total{route=\"/segment\",status=\"499\"}", 2, 2) == 2);
    CHECK(metric(&d, "pointseg_http_requests_total{route=\"/segment\",status=\"415\"}") == -1);
    CHECK(ps_daemon_healthy(&d));
    CHECK_STOPS(d, 10);
}

typedef struct endless_upload {
    int fd;
    atomic_int stop;
    size_t sent;
} endless_upload;

/* Sends chunks of XYZ text on u->fd until told to stop or the daemon
 * closes the connection. */
static void *send_chunks(void *arg) {
    endless_upload *u = arg;
    char chunk[8200];
    int at = sprintf(chunk, "1f40\r\n");
    for (int i = 0; i < 8000; i++) chunk[at + i] = i % 6 == 5 ? '\n' : i % 2 ? ' ' : '0';
    memcpy(chunk + at + 8000, "\r\n", 2);
    size_t len = (size_t)at + 8002;
    while (!atomic_load(&u->stop) && send(u->fd, chunk, len, MSG_NOSIGNAL) == (ssize_t)len) u->sent += len;
    return NULL;
}

/* A chunked body that goes on past --max-body is answered with the 413 at
 * once, and the connection closed, instead of being read to its end. */
static void test_endless_chunked_body_answered(void) {
    static const char head[] = "POST /segment HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n";
    ps_daemon d;
    reply x;
    pthread_t sender;
    REQUIRE_STARTS(d, "--max-body", "100000", NULL);
    endless_upload u = {.fd = ps_daemon_connect(&d, 5), .sent = 0};
    atomic_init(&u.stop, 0);
    REQUIRE(u.fd >= 0 && send(u.fd, head, sizeof head - 1, MSG_NOSIGNAL) == (ssize_t)(sizeof head - 1));
    REQUIRE(pthread_create(&sender, NULL, send_chunks, &u) == 0);
    read_reply(u.fd, 5, &x);
    atomic_store(&u.stop, 1);
    shutdown(u.fd, SHUT_RDWR);
    pthread_join(sender, NULL);
    close(u.fd);
    CHECK_MSG(first_status(&x) == 413 && strstr(x.text, "application/problem+json") && x.closed,
              "after %.1f s and %zu bytes sent: %.100s", x.seconds, u.sent, x.text);
    CHECK(ps_daemon_healthy(&d));
    CHECK_STOPS(d, 10);
}

/* ---- 4: static files ------------------------------------------------------ */

static void test_static_files_stay_inside(void) {
    ps_daemon d;
    ps_client_response r;
    char dir[] = "/tmp/pointsegd-static-XXXXXX", path[128], link_path[128], url[600];
    REQUIRE(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/index.html", dir);
    snprintf(link_path, sizeof link_path, "%s/passwd.txt", dir);
    FILE *f = fopen(path, "w");
    REQUIRE(f);
    fputs("<html>viewer</html>", f);
    fclose(f);
    REQUIRE(symlink("/etc/passwd", link_path) == 0);
    REQUIRE_STARTS(d, "--static-dir", dir, NULL);
    CHECK(ps_client_request(&d.client, "GET", "/index.html", NULL, NULL, &r) == 0 && r.status == 200);
    ps_client_response_free(&r);
    CHECK(ps_client_request(&d.client, "GET", "/passwd.txt", NULL, NULL, &r) == 0 && r.status == 404 &&
          !strstr(r.body, "root:"));
    ps_client_response_free(&r);
    size_t at = (size_t)sprintf(url, "/");
    while (at < 254 - strlen("index.html")) url[at++] = '/';
    sprintf(url + at, "index.html-does-not-exist");
    CHECK(ps_client_request(&d.client, "GET", url, NULL, NULL, &r) == 0 &&
          (r.status == 404 || r.status == 414) && !strstr(r.body, "viewer"));
    ps_client_response_free(&r);
    CHECK_STOPS(d, 10);
    remove(link_path);
    remove(path);
    rmdir(dir);
}

/* ---- 5: bodies ------------------------------------------------------------ */

static long labels_of(const ps_daemon *d, const char *body, size_t len, const char *ct, const char *ce,
                      size_t *n_labels) {
    ps_client_response r;
    ps_client_body b = {body, len, ct, ce};
    long status = ps_client_segment(&d->client, &b, "output=labels&k=3", &r) == 0 ? r.status : 0;
    *n_labels = status == 200 ? count_lines(r.body) : 0;
    ps_client_response_free(&r);
    return status;
}

static void test_gzip_members_all_read(void) {
    ps_daemon d;
    size_t len, n, la, lb, got;
    char *xyz = sphere_xyz(14, &len, &n);
    REQUIRE(xyz);
    size_t half = (size_t)(strchr(xyz + len / 2, '\n') + 1 - xyz);
    char *a = ps_test_gzip(xyz, half, &la), *b = ps_test_gzip(xyz + half, len - half, &lb);
    char *both = malloc(la + lb);
    memcpy(both, a, la);
    memcpy(both + la, b, lb);
    REQUIRE_STARTS(d, NULL);
    CHECK(labels_of(&d, both, la + lb, NULL, "gzip", &got) == 200);
    CHECK_MSG(got == n, "two gzip members: %zu labels for %zu points", got, n);
    CHECK(labels_of(&d, both, la + lb - 3, NULL, "gzip", &got) == 400);
    free(a), free(b), free(both), free(xyz);
    CHECK_STOPS(d, 10);
}

static void test_bom_keeps_first_point(void) {
    ps_daemon d;
    size_t got;
    static const char xyz[] = "\xEF\xBB\xBF" "0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 0\n1 0 1\n0 1 1\n1 1 1\n";
    static const char csv[] = "\xEF\xBB\xBF" "0,0,0\n1,0,0\n0,1,0\n0,0,1\n1,1,0\n1,0,1\n0,1,1\n1,1,1\n";
    static const char json[] = "\xEF\xBB\xBF" "{\"points\": [[0,0,0],[1,0,0],[0,1,0],[0,0,1],[1,1,0],"
                               "[1,0,1],[0,1,1],[1,1,1]]}";
    static const char off[] = "\xEF\xBB\xBF" "OFF\n8 0 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 0\n1 0 1\n0 1 1\n1 1 1\n";
    REQUIRE_STARTS(d, NULL);
    const char *const bodies[][2] = {{xyz, "text/plain"}, {csv, "text/plain"}, {json, "application/json"},
                                     {off, "application/octet-stream"}};
    for (size_t i = 0; i < 4; i++) {
        long status = labels_of(&d, bodies[i][0], strlen(bodies[i][0]), bodies[i][1], NULL, &got);
        CHECK_MSG(status == 200 && got == 8, "body %zu with a BOM: status %ld, %zu labels for 8 points", i,
                  status, got);
    }
    CHECK_STOPS(d, 10);
}

static void test_two_file_parts_refused(void) {
    ps_daemon d;
    ps_client_response r;
    static const char body[] =
        "--b7\r\nContent-Disposition: form-data; name=\"file\"; filename=\"a.xyz\"\r\n\r\n"
        "0 0 0\n1 0 0\n0 1 0\n0 0 1\n\r\n"
        "--b7\r\nContent-Disposition: form-data; name=\"file\"; filename=\"b.xyz\"\r\n\r\n"
        "1 1 0\n1 0 1\n0 1 1\n1 1 1\n\r\n--b7--\r\n";
    ps_client_body b = {body, sizeof body - 1, "multipart/form-data; boundary=b7", NULL};
    REQUIRE_STARTS(d, NULL);
    CHECK(ps_client_segment(&d.client, &b, NULL, &r) == 0 && r.status == 400 && strstr(r.body, "file"));
    ps_client_response_free(&r);
    CHECK_STOPS(d, 10);
}

/* ---- 6: strict parameters and headers ------------------------------------ */

static void test_strict_parameters_and_headers(void) {
    ps_daemon d;
    ps_client_response r;
    reply x;
    size_t len, n;
    char *xyz = sphere_xyz(14, &len, &n);
    REQUIRE(xyz);
    ps_client_body b = {xyz, len, NULL, NULL};
    REQUIRE_STARTS(d, NULL);
    const char *const queries[] = {"k=0x10", "k=8%00junk", "k=%2B8", "k=%208", "persistence=0x1p-3",
                                   "persistence=0.1%00"};
    for (size_t i = 0; i < sizeof queries / sizeof queries[0]; i++) {
        CHECK_MSG(ps_client_segment(&d.client, &b, queries[i], &r) == 0 && r.status >= 400 && r.status < 500,
                  "?%s: status %ld", queries[i], r.status);
        ps_client_response_free(&r);
    }
    CHECK(ps_client_segment(&d.client, &b, "k=3&persistence=0.05", &r) == 0 && r.status == 200);
    ps_client_response_free(&r);
    static const char two_lengths[] = "POST /segment HTTP/1.1\r\nHost: x\r\nContent-Length: 24\r\n"
                                      "Content-Length: 12\r\n\r\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
    CHECK(exchange(&d, two_lengths, sizeof two_lengths - 1, 2, &x) == 0 && first_status(&x) == 400);
    /* Both framings: a proxy in front may have read a different body
     * (RFC 9112 6.3), so the request is refused and the connection closed
     * before the pipelined GET behind it is read. */
    static const char both_framings[] = "POST /segment HTTP/1.1\r\nHost: x\r\nContent-Length: 5\r\n"
                                        "Transfer-Encoding: chunked\r\n\r\n5\r\n0 0 0\r\n0\r\n\r\n"
                                        "GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n";
    CHECK(exchange(&d, both_framings, sizeof both_framings - 1, 2, &x) == 0);
    CHECK_MSG(first_status(&x) == 400 && count_answers(&x) == 1 && x.closed &&
                  strstr(x.text, "application/problem+json"),
              "Content-Length and chunked: %d answers, closed %d: %.200s", count_answers(&x), x.closed, x.text);
    /* Two codings (a body gzipped twice, or gzip then another): not a
     * Content-Encoding the service takes, so a 415, not a 400 on bytes
     * inflated once. */
    static const char two_codings[] = "POST /segment HTTP/1.1\r\nHost: x\r\nContent-Encoding: gzip\r\n"
                                      "Content-Encoding: gzip\r\nContent-Length: 6\r\n\r\n0 0 0\n";
    CHECK(exchange(&d, two_codings, sizeof two_codings - 1, 2, &x) == 0);
    CHECK_MSG(first_status(&x) == 415 && strstr(x.text, "Content-Encoding"), "two codings: %.300s", x.text);
    static const char no_host[] = "GET /healthz HTTP/1.1\r\n\r\n";
    CHECK(exchange(&d, no_host, sizeof no_host - 1, 2, &x) == 0 && first_status(&x) == 400);
    static const char old_no_host[] = "GET /healthz HTTP/1.0\r\n\r\n";
    CHECK(exchange(&d, old_no_host, sizeof old_no_host - 1, 2, &x) == 0 && first_status(&x) == 200);
    free(xyz);
    CHECK_STOPS(d, 10);
}

/* An encoded NUL in the path would end it where libmicrohttpd decodes it:
 * "/healthz%00x" must not be served as "/healthz", nor "/%00x" as the
 * viewer at "/".  A %00 in the query is the parameters' business (above). */
static void test_nul_in_path_refused(void) {
    ps_daemon d;
    reply x;
    REQUIRE_STARTS(d, NULL);
    const char *const paths[] = {"/healthz%00x", "/%00segment", "/jobs%00/abc"};
    char request[128];
    for (size_t i = 0; i < sizeof paths / sizeof paths[0]; i++) {
        int len = snprintf(request, sizeof request, "GET %s HTTP/1.1\r\nHost: x\r\n\r\n", paths[i]);
        CHECK_MSG(exchange(&d, request, (size_t)len, 2, &x) == 0 && first_status(&x) == 400 &&
                      strstr(x.text, "NUL") && strstr(x.text, "application/problem+json"),
                  "%s: %.60s", paths[i], x.text);
    }
    static const char in_query[] = "GET /healthz?x=%00 HTTP/1.1\r\nHost: x\r\n\r\n";
    CHECK(exchange(&d, in_query, sizeof in_query - 1, 2, &x) == 0 && first_status(&x) == 200);
    CHECK(ps_daemon_healthy(&d));
    CHECK_STOPS(d, 10);
}

/* ---- 7: problem+json is valid JSON --------------------------------------- */

static void test_problem_detail_valid_utf8(void) {
    ps_daemon d;
    reply x;
    static const char bad_name[] = "POST /segment?%ff%fe=1 HTTP/1.1\r\nHost: x\r\nContent-Length: 6\r\n\r\n0 0 0\n";
    REQUIRE_STARTS(d, NULL);
    CHECK(exchange(&d, bad_name, sizeof bad_name - 1, 2, &x) == 0 && first_status(&x) == 400);
    cJSON *doc = reply_json(&x);
    const cJSON *detail = cJSON_GetObjectItemCaseSensitive(doc, "detail");
    int valid = cJSON_IsString(detail);
    for (const unsigned char *p = valid ? (const unsigned char *)detail->valuestring : NULL; p && *p; p++)
        if (*p == 0xff || *p == 0xfe) valid = 0;
    CHECK_MSG(valid && strstr(detail->valuestring, "\xEF\xBF\xBD"), "detail: %.100s", x.text);
    cJSON_Delete(doc);
    CHECK_STOPS(d, 10);
}

/* ---- 8: keep-alive -------------------------------------------------------- */

/* Sends text on one connection, then shuts down the write side when
 * half_close is set; reads for timeout_s. */
static int send_on_one(const ps_daemon *d, const char *text, int half_close, double timeout_s, reply *x) {
    int fd = ps_daemon_connect(d, 5);
    if (fd < 0) return -1;
    int sent = send(fd, text, strlen(text), MSG_NOSIGNAL) == (ssize_t)strlen(text);
    if (half_close) shutdown(fd, SHUT_WR);
    read_reply(fd, timeout_s, x);
    close(fd);
    return sent ? 0 : -1;
}

static void test_keep_alive_after_gets_and_errors(void) {
    ps_daemon d;
    reply x;
    char text[512];
    static const char health[] = "GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n";
    static const char early_error[] = "POST /segment HTTP/1.1\r\nHost: x\r\nContent-Type: image/png\r\n"
                                      "Content-Length: 6\r\n\r\n0 0 0\n";
    static const char not_found[] = "GET /no/such/route HTTP/1.1\r\nHost: x\r\n\r\n";
    static const char version[] = "GET /version HTTP/1.1\r\nHost: x\r\n\r\n";
    REQUIRE_STARTS(d, NULL);
    snprintf(text, sizeof text, "%s%s%s%s", health, early_error, not_found, version);
    CHECK(send_on_one(&d, text, 0, 1.5, &x) == 0);
    CHECK_MSG(count_answers(&x) == 4 && strstr(x.text, "415") && strstr(x.text, "\"pointseg\":"),
              "%d answers to 4 pipelined requests: %.300s", count_answers(&x), x.text);
    CHECK_MSG(!strstr(x.text, "Connection: close"), "an answer closes the connection");
    snprintf(text, sizeof text, "%s%s%s", health, not_found, version); /* then the write side shut down */
    CHECK(send_on_one(&d, text, 1, 3, &x) == 0);
    CHECK_MSG(count_answers(&x) == 3 && x.closed, "%d answers to 3 pipelined requests and an EOF",
              count_answers(&x));
    CHECK_STOPS(d, 10);
}

/* ---- 9: half-closed clients ----------------------------------------------- */

/* Sends body to /segment, shuts down the write side, and reads the answer:
 * 1 when it is a 200 with n labels. */
static int half_closed_request(const ps_daemon *d, const char *xyz, size_t len, size_t n) {
    char head[256];
    reply x;
    int hl = snprintf(head, sizeof head, "POST /segment?output=labels&centrality=exact HTTP/1.1\r\nHost: x\r\n"
                      "Content-Length: %zu\r\n\r\n", len);
    int fd = ps_daemon_connect(d, 10);
    if (fd < 0) return 0;
    int sent = send(fd, head, (size_t)hl, MSG_NOSIGNAL) == hl && send(fd, xyz, len, MSG_NOSIGNAL) == (ssize_t)len;
    shutdown(fd, SHUT_WR);
    read_reply(fd, 10, &x);
    close(fd);
    const char *answer = strstr(x.text, "HTTP/1.1 200 "); /* after an interim 102, if any */
    const char *body = answer ? strstr(answer, "\r\n\r\n") : NULL;
    int ok = sent && body && count_lines(body + 4) == n;
    if (!ok) fprintf(stderr, "  half-closed client got: %.200s\n", x.text);
    return ok;
}

/* A job long enough for the watcher to see the EOF (and send its 102), and
 * a quick one (about 10 ms) that mostly ends before it looks: both answered
 * whole.  Under libmicrohttpd's poll mode the resumed connection was closed
 * on the EOF before the answer (direct_answer.h). */
static void test_half_closed_client_answered(void) {
    ps_daemon d;
    size_t len, n, quick_len, quick_n;
    char *xyz = sphere_xyz(60, &len, &n), *quick = sphere_xyz(30, &quick_len, &quick_n);
    REQUIRE(xyz && quick);
    REQUIRE_STARTS(d, "--threads", "1", NULL);
    for (int i = 0; i < 3; i++) CHECK(half_closed_request(&d, xyz, len, n));
    for (int i = 0; i < 5; i++) CHECK(half_closed_request(&d, quick, quick_len, quick_n));
    free(xyz);
    free(quick);
    CHECK_STOPS(d, 10);
}

int main(int argc, char **argv) {
    static const ps_test_case tests[] = {
        TEST(test_sync_results_freed_once_sent), TEST(test_kept_results_byte_budget),
        TEST(test_per_ip_connection_limit), TEST(test_health_checks_get_room),
        TEST(test_slow_headers_and_bodies_cut), TEST(test_refused_requests_answered_promptly),
        TEST(test_truncated_body_closed_promptly), TEST(test_endless_chunked_body_answered),
        TEST(test_static_files_stay_inside), TEST(test_gzip_members_all_read), TEST(test_bom_keeps_first_point),
        TEST(test_two_file_parts_refused), TEST(test_strict_parameters_and_headers),
        TEST(test_nul_in_path_refused),
        TEST(test_problem_detail_valid_utf8), TEST(test_keep_alive_after_gets_and_errors),
        TEST(test_half_closed_client_answered)};
    if (ps_client_global_init()) return 1;
    return ps_test_main(__FILE__, tests, sizeof tests / sizeof tests[0], argc, argv);
}
