/*
 * test_multipart.c: pointsegd's multipart/form-data bodies at the edges the
 * multipart fuzz target (tests/fuzz/fuzz_multipart.c) looks at: a complete
 * body is segmented, a body cut before its closing boundary is a 400 (even
 * when the cut falls between two lines of the file part, which would
 * otherwise decode to fewer points), a body without a `file` part or with
 * an empty one is a 400, a boundary parameter anywhere in the Content-Type
 * is found.
 * Starts BUILD/pointsegd (beside BUILD/itests/) on a free port.
 */
#include "daemon_proc.h"
#include "pointseg_client.h"
#include "testlib.h"

#include <arpa/inet.h>
#include <cJSON.h>
#include <fcntl.h>
#include <libgen.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <time.h>
#include <unistd.h>

#define BOUNDARY "testboundary"
#define N_POINTS 40

static pid_t daemon_pid;
static char base_url[64];

/* POSTs body to /segment as content_type; the status, or 0. */
static long request_as(const char *body, size_t len, const char *content_type, ps_client_response *r) {
    ps_client c = {base_url, NULL, 30000};
    ps_client_body b = {body, len, content_type, NULL};
    return ps_client_segment(&c, &b, NULL, r) == 0 ? r->status : 0;
}

static long request(const char *body, size_t len, ps_client_response *r) {
    return request_as(body, len, "multipart/form-data; boundary=" BOUNDARY, r);
}

/* Starts pointsegd once for every test; 0 or -1. */
static int need_daemon(void) {
    char path[4200], port_text[16];
    if (daemon_pid > 0) return 0;
    int port = ps_test_free_port();
    if (port <= 0 || ps_test_daemon_path(path, sizeof path) != 0) return -1;
    snprintf(port_text, sizeof port_text, "%d", port);
    snprintf(base_url, sizeof base_url, "http://127.0.0.1:%d", port);
    daemon_pid = fork();
    if (daemon_pid == 0) {
        int fd = open("/dev/null", O_WRONLY);
        if (fd >= 0) dup2(fd, 2);
        execl(path, path, "--port", port_text, "--bind", "127.0.0.1", (char *)NULL);
        _exit(127);
    }
    for (int i = 0; daemon_pid > 0 && i < 200; i++) {
        ps_client c = {base_url, NULL, 1000};
        ps_client_response r;
        int up = ps_client_request(&c, "GET", "/healthz", NULL, NULL, &r) == 0 && r.status == 200;
        ps_client_response_free(&r);
        if (up) return 0;
        ps_test_sleep_ms(25);
    }
    return -1;
}

/* A form with a field k=6 and a `file` part of N_POINTS XYZ lines; *file_end
 * is the offset just after the file's last line. */
static char *make_form(size_t *len, size_t *file_end) {
    char *s = malloc(8192);
    size_t at = 0;
    if (!s) return NULL;
    at += (size_t)sprintf(s + at, "--" BOUNDARY "\r\nContent-Disposition: form-data; name=\"k\"\r\n\r\n6\r\n"
                          "--" BOUNDARY "\r\nContent-Disposition: form-data; name=\"file\"; "
                          "filename=\"p.xyz\"\r\nContent-Type: text/plain\r\n\r\n");
    for (int i = 0; i < N_POINTS; i++)
        at += (size_t)sprintf(s + at, "%d %d %d\n", i % 7, (i * 3) % 11, (i * 5) % 13);
    *file_end = at;
    at += (size_t)sprintf(s + at, "\r\n--" BOUNDARY "--\r\n");
    *len = at;
    return s;
}

static int problem_says(const ps_client_response *r, const char *words) {
    return r->body && strstr(r->content_type, "application/problem+json") && strstr(r->body, words);
}

static void test_complete_form_is_segmented(void) {
    size_t len, file_end;
    ps_client_response r;
    char *form = make_form(&len, &file_end);
    REQUIRE(form && need_daemon() == 0);
    CHECK(request(form, len, &r) == 200);
    cJSON *doc = cJSON_Parse(r.body);
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(doc, "n_points");
    CHECK(cJSON_IsNumber(n) && n->valueint == N_POINTS);
    cJSON_Delete(doc);
    ps_client_response_free(&r);
    free(form);
}

static void test_form_cut_before_closing_boundary_is_400(void) {
    size_t len, file_end;
    ps_client_response r;
    char *form = make_form(&len, &file_end);
    REQUIRE(form && need_daemon() == 0);
    size_t cuts[] = {file_end / 2, file_end, len - 4};
    for (size_t i = 0; i < sizeof cuts / sizeof cuts[0]; i++) {
        size_t cut = cuts[i];
        while (i == 0 && form[cut - 1] != '\n') cut++; /* between two lines of the file */
        CHECK_MSG(request(form, cut, &r) == 400 && problem_says(&r, "truncated"),
                  "cut at %zu of %zu: status %ld, %s", cut, len, r.status, r.body ? r.body : "");
        ps_client_response_free(&r);
    }
    free(form);
}

/* The boundary parameter need not come last, nor in lower case (RFC 9110
 * 5.6.6): Apache HttpClient sends "boundary=...; charset=UTF-8". */
static void test_boundary_anywhere_in_the_type(void) {
    static const char *const types[] = {"multipart/form-data; boundary=" BOUNDARY "; charset=UTF-8",
                                        "multipart/form-data; BOUNDARY=" BOUNDARY,
                                        "multipart/form-data; charset=UTF-8; Boundary=\"" BOUNDARY "\"",
                                        "multipart/form-data;boundary=" BOUNDARY " ;charset=UTF-8"};
    size_t len, file_end;
    ps_client_response r;
    char *form = make_form(&len, &file_end);
    REQUIRE(form && need_daemon() == 0);
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++) {
        CHECK_MSG(request_as(form, len, types[i], &r) == 200, "%s: status %ld, %s", types[i], r.status,
                  r.body ? r.body : "");
        ps_client_response_free(&r);
    }
    free(form);
}

/* Posting the #len bytes of form gets a 400 whose problem says `words`. */
static void check_form_is_400(const char *form, size_t len, const char *words) {
    ps_client_response r;
    REQUIRE(need_daemon() == 0);
    CHECK(request(form, len, &r) == 400 && problem_says(&r, words));
    ps_client_response_free(&r);
}

static void test_form_without_file_is_400(void) {
    static const char form[] = "--" BOUNDARY "\r\nContent-Disposition: form-data; name=\"k\"\r\n\r\n6\r\n"
                               "--" BOUNDARY "--\r\n";
    check_form_is_400(form, sizeof form - 1, "no 'file' part");
}

static void test_empty_file_part_is_400(void) {
    static const char form[] = "--" BOUNDARY "\r\nContent-Disposition: form-data; name=\"file\"\r\n\r\n"
                               "\r\n--" BOUNDARY "--\r\n";
    check_form_is_400(form, sizeof form - 1, "empty");
}

/* Sends a POST /segment of the #len bytes of form over a raw socket in two
 * writes, the second `split` bytes in and 50 ms after the first, so that
 * the daemon reads the body in two pieces; the answer (malloc'ed, NUL
 * terminated) in *reply, the status as the result (0: no answer). */
static int post_in_two_writes(const char *form, size_t len, size_t split, char **reply) {
    char head[256];
    struct sockaddr_in a = {.sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    int port = 0, status = 0, one = 1;
    sscanf(base_url, "http://127.0.0.1:%d", &port);
    a.sin_port = htons((uint16_t)port);
    int head_len = snprintf(head, sizeof head, "POST /segment HTTP/1.1\r\nHost: x\r\nConnection: close\r\n"
                            "Content-Type: multipart/form-data; boundary=" BOUNDARY "\r\n"
                            "Content-Length: %zu\r\n\r\n", len);
    struct timeval tv = {30, 0};
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    *reply = NULL;
    if (fd < 0) return 0;
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    if (!connect(fd, (struct sockaddr *)&a, sizeof a) &&
        send(fd, head, (size_t)head_len, MSG_NOSIGNAL) == head_len &&
        send(fd, form, split, MSG_NOSIGNAL) == (ssize_t)split) {
        ps_test_sleep_ms(50);
        if (send(fd, form + split, len - split, MSG_NOSIGNAL) == (ssize_t)(len - split)) {
            size_t cap = 1 << 16, at = 0;
            ssize_t n = 1;
            *reply = calloc(cap + 1, 1);
            while (*reply && at < cap && (n = recv(fd, *reply + at, cap - at, 0)) > 0) at += (size_t)n;
            if (*reply) sscanf(*reply, "HTTP/1.%*d %d", &status);
        }
    }
    close(fd);
    return status;
}

/* A form with parameter fields before and after the file part, numbers and
 * text: k=6, centrality=exact, file, persistence=0.25, minima=false. */
static const char *const split_fields[][2] = {
    {"k", "6"}, {"centrality", "exact"}, {"persistence", "0.25"}, {"minima", "false"}};

static char *make_fields_form(size_t *len, size_t value_end[4]) {
    char *s = malloc(8192);
    size_t at = 0;
    if (!s) return NULL;
    for (int i = 0; i < 4; i++) {
        if (i == 2) {
            at += (size_t)sprintf(s + at, "--" BOUNDARY "\r\nContent-Disposition: form-data; name=\"file\"; "
                                  "filename=\"p.xyz\"\r\nContent-Type: text/plain\r\n\r\n");
            for (int p = 0; p < N_POINTS; p++)
                at += (size_t)sprintf(s + at, "%d %d %d\n", p % 7, (p * 3) % 11, (p * 5) % 13);
            at += (size_t)sprintf(s + at, "\r\n");
        }
        at += (size_t)sprintf(s + at, "--" BOUNDARY "\r\nContent-Disposition: form-data; name=\"%s\"\r\n\r\n%s",
                              split_fields[i][0], split_fields[i][1]);
        value_end[i] = at;
        at += (size_t)sprintf(s + at, "\r\n");
    }
    at += (size_t)sprintf(s + at, "--" BOUNDARY "--\r\n");
    *len = at;
    return s;
}

/* The JSON answer's "params" has the four fields' values. */
static int params_are_the_fields(const char *reply) {
    const char *body = reply ? strstr(reply, "\r\n\r\n") : NULL;
    cJSON *doc = body ? cJSON_Parse(body + 4) : NULL;
    const cJSON *params = cJSON_GetObjectItemCaseSensitive(doc, "params");
    const cJSON *k = cJSON_GetObjectItemCaseSensitive(params, "k");
    const cJSON *c = cJSON_GetObjectItemCaseSensitive(params, "centrality");
    const cJSON *p = cJSON_GetObjectItemCaseSensitive(params, "persistence");
    const cJSON *m = cJSON_GetObjectItemCaseSensitive(params, "minima");
    int ok = cJSON_IsNumber(k) && k->valueint == 6 && cJSON_IsString(c) && !strcmp(c->valuestring, "exact") &&
             cJSON_IsNumber(p) && p->valuedouble == 0.25 && cJSON_IsFalse(m);
    cJSON_Delete(doc);
    return ok;
}

/* A browser's FormData upload arrives in pieces; a piece that ends right
 * after a field's value must not cut the field in two (libmicrohttpd then
 * calls back twice at offset 0: empty, then the value). */
static void test_fields_split_after_their_value(void) {
    size_t len, value_end[4];
    char *form = make_fields_form(&len, value_end);
    REQUIRE(form && need_daemon() == 0);
    size_t splits[] = {0, value_end[0], value_end[1], value_end[2], value_end[3],
                       value_end[0] - 1, value_end[3] + 2};
    for (size_t i = 0; i < sizeof splits / sizeof splits[0]; i++) {
        char *reply;
        int status = post_in_two_writes(form, len, splits[i], &reply);
        CHECK_MSG(status == 200 && params_are_the_fields(reply), "split at %zu of %zu: status %d, %.300s",
                  splits[i], len, status, reply ? reply : "(no answer)");
        free(reply);
    }
    free(form);
}

static void test_zz_stop_daemon(void) {
    char how[128];
    REQUIRE(daemon_pid > 0);
    CHECK_MSG(ps_test_daemon_stop(&daemon_pid, 10, how, sizeof how) == 0, "pointsegd %s", how);
}

int main(int argc, char **argv) {
    static const ps_test_case tests[] = {
        TEST(test_complete_form_is_segmented), TEST(test_form_cut_before_closing_boundary_is_400),
        TEST(test_form_without_file_is_400), TEST(test_empty_file_part_is_400),
        TEST(test_fields_split_after_their_value), TEST(test_boundary_anywhere_in_the_type),
        TEST(test_zz_stop_daemon)};
    if (ps_client_global_init()) return 1;
    int rc = ps_test_main(__FILE__, tests, sizeof tests / sizeof tests[0], argc, argv);
    if (daemon_pid > 0) kill(daemon_pid, SIGKILL);
    return rc;
}
