/*
 * test_daemon.c: pointsegd over HTTP: every endpoint and content type, the
 * same labels through /segment, /jobs and the library, bad inputs of every
 * kind (right status, problem+json, daemon healthy afterwards), every
 * core for a job on an idle daemon, --max-memory, 32
 * concurrent clients, a full queue (503), DELETE of a running exact job,
 * token, CORS, static files, and SIGTERM draining.  Each test starts
 * pointsegd (BUILD/pointsegd beside BUILD/itests/) on a free port.
 */
#include "params_table.h"
#include "pointseg.h"
#include "pointseg_client.h"
#include "shapes.h"
#include "daemon_proc.h"
#include "testlib.h"

#include <arpa/inet.h>
#include <cJSON.h>
#include <fcntl.h>
#include <libgen.h>
#include <netinet/in.h>
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include <zlib.h>

typedef struct ps_daemon {
    pid_t pid;
    int port;
    char base_url[64];
    ps_client client;
} ps_daemon;

#define MAX_ARGS 32

static int ps_daemon_stop(ps_daemon *d, double timeout_s);


static int ps_daemon_healthy(const ps_daemon *d) {
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

static int ps_daemon_start(ps_daemon *d, const char *const *args) {
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

static int ps_daemon_stop(ps_daemon *d, double timeout_s) {
    return ps_test_daemon_stop(&d->pid, timeout_s);
}

static char *ps_points_xyz(const double *pts, size_t n, size_t *len) {
    char *text = malloc(n * 3 * 26 + 1);
    size_t at = 0;
    if (!text) return NULL;
    for (size_t i = 0; i < n; i++)
        at += (size_t)sprintf(text + at, "%.17g %.17g %.17g\n", pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]);
    *len = at;
    return text;
}

static int *ps_json_labels(const char *doc, size_t *n) {
    cJSON *root = doc ? cJSON_Parse(doc) : NULL;
    const cJSON *labels = cJSON_GetObjectItemCaseSensitive(root, "labels");
    int *out = NULL;
    if (cJSON_IsArray(labels) && (*n = (size_t)cJSON_GetArraySize(labels)) > 0 &&
        (out = malloc(*n * sizeof *out))) {
        size_t i = 0;
        for (const cJSON *v = labels->child; v; v = v->next) out[i++] = v->valueint;
    }
    cJSON_Delete(root);
    return out;
}

static int ps_raw_status(const ps_daemon *d, const char *request, size_t len) {
    struct sockaddr_in a = {.sin_family = AF_INET, .sin_port = htons((uint16_t)d->port),
                            .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    char reply[256] = {0};
    int code = 0, fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0) return 0;
    struct timeval tv = {5, 0};
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    if (!connect(fd, (struct sockaddr *)&a, sizeof a) && send(fd, request, len, MSG_NOSIGNAL) == (ssize_t)len &&
        recv(fd, reply, sizeof reply - 1, 0) > 0)
        sscanf(reply, "HTTP/1.%*d %d", &code);
    close(fd);
    return code;
}

/* ---- request bodies ------------------------------------------------------ */

typedef struct sample {
    double *pts;
    size_t n;
    char *xyz;
    size_t xyz_len;
    int *labels; /* from the library, default parameters */
} sample;

static int make_sample(sample *s, double density) {
    ps_params p;
    ps_result *r = NULL;
    memset(s, 0, sizeof *s);
    s->pts = ps_shape_dumbbell(density, &s->n, NULL);
    if (!s->pts) return -1;
    s->xyz = ps_points_xyz(s->pts, s->n, &s->xyz_len);
    ps_params_default(&p);
    p.threads = 1;
    ps_input in = {s->pts, s->n, 3, NULL};
    if (!s->xyz || ps_segment(&in, &p, NULL, &r, NULL) != PS_OK) return -1;
    s->labels = malloc(s->n * sizeof *s->labels);
    if (s->labels) memcpy(s->labels, r->labels, s->n * sizeof *s->labels);
    ps_result_free(r);
    return s->labels ? 0 : -1;
}

static void free_sample(sample *s) {
    free(s->pts);
    free(s->xyz);
    free(s->labels);
}

static char *json_body(const sample *s, size_t *len) {
    char *text = malloc(s->n * 3 * 26 + 64);
    size_t at = (size_t)sprintf(text, "{\"points\": [");
    for (size_t i = 0; i < s->n; i++)
        at += (size_t)sprintf(text + at, "%s[%.17g,%.17g,%.17g]", i ? "," : "", s->pts[3 * i],
                              s->pts[3 * i + 1], s->pts[3 * i + 2]);
    at += (size_t)sprintf(text + at, "], \"params\": {\"k\": 7}}");
    *len = at;
    return text;
}

static char *binary_ply(const sample *s, size_t *len) {
    char header[128];
    int h = snprintf(header, sizeof header, "ply\nformat binary_little_endian 1.0\nelement vertex %zu\n"
                     "property double x\nproperty double y\nproperty double z\nend_header\n", s->n);
    char *out = malloc((size_t)h + s->n * 24);
    memcpy(out, header, (size_t)h);
    memcpy(out + h, s->pts, s->n * 24); /* little-endian hosts only, as the test machines are */
    *len = (size_t)h + s->n * 24;
    return out;
}

#define BOUNDARY "pointsegTestBoundary7"

static char *multipart_body(const char *file, size_t file_len, size_t *len) {
    static const char head[] = "--" BOUNDARY "\r\nContent-Disposition: form-data; name=\"k\"\r\n\r\n7\r\n"
                               "--" BOUNDARY "\r\nContent-Disposition: form-data; name=\"file\"; "
                               "filename=\"s.xyz\"\r\nContent-Type: application/octet-stream\r\n\r\n";
    static const char tail[] = "\r\n--" BOUNDARY "--\r\n";
    char *out = malloc(sizeof head + file_len + sizeof tail);
    memcpy(out, head, sizeof head - 1);
    memcpy(out + sizeof head - 1, file, file_len);
    memcpy(out + sizeof head - 1 + file_len, tail, sizeof tail - 1);
    *len = sizeof head - 1 + file_len + sizeof tail - 1;
    return out;
}

static char *gzip_bytes(const char *data, size_t n, size_t *len) {
    z_stream z = {0};
    uLong cap = compressBound((uLong)n) + 64;
    char *out = malloc(cap);
    deflateInit2(&z, 6, Z_DEFLATED, 31, 8, Z_DEFAULT_STRATEGY);
    z.next_in = (unsigned char *)(uintptr_t)data;
    z.avail_in = (uInt)n;
    z.next_out = (unsigned char *)out;
    z.avail_out = (uInt)cap;
    deflate(&z, Z_FINISH);
    *len = z.total_out;
    deflateEnd(&z);
    return out;
}

/* ---- checks -------------------------------------------------------------- */

static int same_labels(const ps_client_response *r, const sample *s) {
    size_t n = 0;
    int *labels = ps_json_labels(r->body, &n);
    int same = labels && n == s->n && !memcmp(labels, s->labels, n * sizeof *labels);
    free(labels);
    return same;
}

static int is_problem(const ps_client_response *r, long status) {
    cJSON *doc = r->body ? cJSON_Parse(r->body) : NULL;
    const cJSON *st = cJSON_GetObjectItemCaseSensitive(doc, "status");
    int ok = r->status == status && strstr(r->content_type, "application/problem+json") &&
             cJSON_IsNumber(st) && st->valueint == status &&
             cJSON_IsString(cJSON_GetObjectItemCaseSensitive(doc, "title"));
    cJSON_Delete(doc);
    return ok;
}

static long get_status(const ps_daemon *d, const char *path, ps_client_response *r) {
    if (ps_client_request(&d->client, "GET", path, NULL, NULL, r)) return 0;
    return r->status;
}

static sample small; /* shared by the tests: made once */

static int need_small(void) {
    return small.labels || make_sample(&small, 30) == 0;
}

/* ---- tests --------------------------------------------------------------- */

static void test_content_types_give_library_labels(void) {
    ps_daemon d;
    REQUIRE(need_small());
    REQUIRE(ps_daemon_start(&d, NULL) == 0);
    size_t json_len, ply_len, mp_len, gz_len;
    char *json = json_body(&small, &json_len), *ply = binary_ply(&small, &ply_len);
    char *mp = multipart_body(small.xyz, small.xyz_len, &mp_len);
    char *gz = gzip_bytes(mp, mp_len, &gz_len);
    const ps_client_body bodies[] = {
        {small.xyz, small.xyz_len, "application/octet-stream", NULL},
        {small.xyz, small.xyz_len, "text/plain", NULL},
        {ply, ply_len, "application/ply", NULL},
        {json, json_len, "application/json", NULL},
        {mp, mp_len, "multipart/form-data; boundary=" BOUNDARY, NULL},
        {gz, gz_len, "multipart/form-data; boundary=" BOUNDARY, "gzip"}};
    for (size_t i = 0; i < sizeof bodies / sizeof bodies[0]; i++) {
        ps_client_response r;
        CHECK_MSG(ps_client_segment(&d.client, &bodies[i], NULL, &r) == 0 && r.status == 200 &&
                      strstr(r.content_type, "application/json") && same_labels(&r, &small),
                  "body %zu (%s): status %ld %.200s", i, bodies[i].content_type, r.status, r.body);
        ps_client_response_free(&r);
    }
    free(json), free(ply), free(mp), free(gz);
    CHECK(ps_daemon_stop(&d, 10) == 0);
}

static void test_jobs_api_matches_segment(void) {
    ps_daemon d;
    char id[128], state[32];
    ps_client_response r;
    REQUIRE(need_small());
    REQUIRE(ps_daemon_start(&d, (const char *const[]){"--replica-name", "east", NULL}) == 0);
    ps_client_body body = {small.xyz, small.xyz_len, NULL, NULL};
    REQUIRE(ps_client_submit(&d.client, &body, "k=7", id, sizeof id, &r) == 0);
    CHECK(r.status == 202);
    CHECK(!strncmp(id, "east-", 5) && strlen(id) == 5 + 32);
    CHECK(!strncmp(r.location, "/jobs/", 6) && !strcmp(r.location + 6, id));
    ps_client_response_free(&r);
    REQUIRE(ps_client_wait(&d.client, id, 30000, state, sizeof state) == 0);
    CHECK(!strcmp(state, "done"));
    CHECK(ps_client_poll(&d.client, id, &r) == 0 && r.status == 200 && strstr(r.body, "\"finished\"") &&
          strstr(r.body, "\"fraction\":1"));
    ps_client_response_free(&r);
    CHECK(ps_client_result(&d.client, id, &r) == 0 && r.status == 200 && same_labels(&r, &small));
    ps_client_response_free(&r);
    CHECK(ps_client_poll(&d.client, "east-0123", &r) == 0 && is_problem(&r, 404));
    ps_client_response_free(&r);
    CHECK(ps_client_result(&d.client, "nope", &r) == 0 && is_problem(&r, 404));
    ps_client_response_free(&r);
    CHECK(ps_daemon_stop(&d, 10) == 0);
}

static void test_outputs_and_includes(void) {
    ps_daemon d;
    ps_client_response r;
    REQUIRE(need_small());
    REQUIRE(ps_daemon_start(&d, NULL) == 0);
    ps_client_body body = {small.xyz, small.xyz_len, NULL, NULL};
    CHECK(ps_client_segment(&d.client, &body, "output=ply", &r) == 0 && r.status == 200 &&
          strstr(r.content_type, "application/ply") && r.len > 3 && !memcmp(r.body, "ply", 3));
    ps_client_response_free(&r);
    const char *const accept[] = {"Accept: application/ply", NULL};
    CHECK(ps_client_request(&d.client, "POST", "/segment", &body, accept, &r) == 0 && r.status == 200 &&
          strstr(r.content_type, "application/ply"));
    ps_client_response_free(&r);
    CHECK(ps_client_segment(&d.client, &body, "include=centrality,point_supernode", &r) == 0 &&
          r.status == 200 && strstr(r.body, "\"centrality\"") && strstr(r.body, "\"point_supernode\"") &&
          same_labels(&r, &small));
    ps_client_response_free(&r);
    CHECK(ps_client_segment(&d.client, &body, "output=labels", &r) == 0 && r.status == 200 &&
          strstr(r.content_type, "text/plain"));
    ps_client_response_free(&r);
    CHECK(ps_daemon_stop(&d, 10) == 0);
}

/* params.threads of a JSON document, or -1. */
static int document_threads(const ps_client_response *r) {
    cJSON *doc = r->body ? cJSON_Parse(r->body) : NULL;
    const cJSON *t = cJSON_GetObjectItemCaseSensitive(
        cJSON_GetObjectItemCaseSensitive(doc, "params"), "threads");
    int threads = cJSON_IsNumber(t) ? t->valueint : -1;
    cJSON_Delete(doc);
    return threads;
}

/* Alone on an idle daemon a job runs on every core, as the CLI does; an
 * explicit threads parameter is kept. */
static void test_idle_daemon_job_gets_every_core(void) {
    ps_daemon d;
    ps_client_response r;
    REQUIRE(need_small());
    REQUIRE(ps_daemon_start(&d, NULL) == 0);
    ps_client_body body = {small.xyz, small.xyz_len, NULL, NULL};
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    CHECK(ps_client_segment(&d.client, &body, NULL, &r) == 0 && r.status == 200);
    CHECK_MSG(document_threads(&r) == cores, "threads %d on %ld cores", document_threads(&r), cores);
    ps_client_response_free(&r);
    CHECK(ps_client_segment(&d.client, &body, "threads=1", &r) == 0 && r.status == 200 &&
          document_threads(&r) == 1 && same_labels(&r, &small));
    ps_client_response_free(&r);
    CHECK(ps_daemon_stop(&d, 10) == 0);
}

static void test_service_endpoints(void) {
    ps_daemon d;
    ps_client_response r;
    REQUIRE(ps_daemon_start(&d, (const char *const[]){"--cors-origin", "http://viewer.example", NULL}) == 0);
    CHECK(get_status(&d, "/readyz", &r) == 200 && strstr(r.body, "ready"));
    ps_client_response_free(&r);
    CHECK(get_status(&d, "/version", &r) == 200 && strstr(r.body, PS_VERSION));
    ps_client_response_free(&r);
    CHECK(get_status(&d, "/healthz", &r) == 200);
    ps_client_response_free(&r);
    CHECK(get_status(&d, "/metrics", &r) == 200 && strstr(r.body, "pointseg_queue_depth 0") &&
          strstr(r.body, "pointseg_http_requests_total{route=\"/healthz\",status=\"200\"}") &&
          strstr(r.body, "pointseg_http_request_duration_seconds_bucket"));
    ps_client_response_free(&r);
    REQUIRE(get_status(&d, "/openapi.json", &r) == 200);
    cJSON *doc = cJSON_Parse(r.body);
    size_t n;
    const ps_param_spec *table = ps_param_table(&n);
    CHECK(doc && !strcmp(cJSON_GetObjectItem(doc, "openapi")->valuestring, "3.1.0"));
    for (size_t i = 0; i < n; i++) {
        char needle[128];
        snprintf(needle, sizeof needle, "\"name\":\"%s\"", table[i].name);
        CHECK_MSG(strstr(r.body, needle), "openapi lacks parameter %s", table[i].name);
    }
    CHECK(cJSON_GetObjectItem(cJSON_GetObjectItem(doc, "paths"), "/jobs/{id}/result"));
    cJSON_Delete(doc);
    ps_client_response_free(&r);
    CHECK(get_status(&d, "/no/such/route", &r) == 404 && is_problem(&r, 404));
    ps_client_response_free(&r);
    CHECK(ps_client_request(&d.client, "DELETE", "/segment", NULL, NULL, &r) == 0 && is_problem(&r, 405) &&
          strstr(r.allow, "POST"));
    ps_client_response_free(&r);
    const char *const preflight[] = {"Origin: http://viewer.example", "Access-Control-Request-Method: POST", NULL};
    CHECK(ps_client_request(&d.client, "OPTIONS", "/segment", NULL, preflight, &r) == 0 && r.status == 204);
    ps_client_response_free(&r);
    int exit_status = ps_daemon_stop(&d, 10);
    CHECK_MSG(exit_status == 0, "pointsegd exited with %d", exit_status);
}

/* A job whose memory estimate is over --max-memory is refused before it
 * runs, on /segment and /jobs alike, with a 413 naming the limit. */
static void test_memory_limit(void) {
    ps_daemon d;
    ps_client_response r;
    char id[128];
    REQUIRE(need_small());
    REQUIRE(ps_daemon_start(&d, (const char *const[]){"--max-memory", "1000000", NULL}) == 0);
    ps_client_body body = {small.xyz, small.xyz_len, NULL, NULL};
    CHECK(ps_client_segment(&d.client, &body, NULL, &r) == 0 && is_problem(&r, 413) &&
          strstr(r.body, "--max-memory") && strstr(r.body, "estimate"));
    ps_client_response_free(&r);
    CHECK(ps_client_submit(&d.client, &body, NULL, id, sizeof id, &r) == 0 && is_problem(&r, 413));
    ps_client_response_free(&r);
    CHECK(ps_daemon_healthy(&d));
    CHECK(ps_daemon_stop(&d, 10) == 0);
}

static void test_token_and_static_files(void) {
    ps_daemon d;
    ps_client_response r;
    char dir[] = "/tmp/pointsegd-static-XXXXXX", path[128];
    REQUIRE(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/index.html", dir);
    FILE *f = fopen(path, "w");
    REQUIRE(f);
    fputs("<html>viewer</html>", f);
    fclose(f);
    REQUIRE(ps_daemon_start(&d, (const char *const[]){"--token", "s3cret", "--static-dir", dir, NULL}) == 0);
    CHECK(get_status(&d, "/healthz", &r) == 200);
    ps_client_response_free(&r);
    CHECK(get_status(&d, "/version", &r) == 401 && is_problem(&r, 401));
    ps_client_response_free(&r);
    d.client.token = "wrong!";
    CHECK(get_status(&d, "/version", &r) == 401);
    ps_client_response_free(&r);
    d.client.token = "s3cret";
    CHECK(get_status(&d, "/version", &r) == 200);
    ps_client_response_free(&r);
    CHECK(get_status(&d, "/", &r) == 200 && strstr(r.body, "viewer") && strstr(r.content_type, "text/html"));
    ps_client_response_free(&r);
    CHECK(get_status(&d, "/../../etc/passwd", &r) == 404);
    ps_client_response_free(&r);
    CHECK(ps_daemon_stop(&d, 10) == 0);
    remove(path);
    rmdir(dir);
}

typedef struct bad_case {
    const char *what, *body, *content_type, *encoding, *query;
    long status;
} bad_case;

static void test_bad_inputs_get_problems(void) {
    static const char truncated_ply[] = "ply\nformat ascii 1.0\nelement vertex 100\nproperty float x\n"
                                        "property float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n";
    static const char lying_ply[] = "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\n"
                                    "property float x\nproperty float y\nproperty float z\nend_header\nabcdefgh";
    const bad_case cases[] = {
        {"truncated ply", truncated_ply, "application/ply", NULL, NULL, 400},
        {"lying count", lying_ply, "application/ply", NULL, NULL, 400},
        {"nan", "0 0 0\n1 0 0\nnan 1 0\n0 1 1\n", "text/plain", NULL, NULL, 422},
        {"wrong content type", "0 0 0\n", "image/png", NULL, NULL, 415},
        {"unknown parameter", "0 0 0\n1 0 0\n0 1 0\n", NULL, NULL, "colour=red", 400},
        {"out of range", "0 0 0\n1 0 0\n0 1 0\n", NULL, NULL, "k=100000", 422},
        {"bad enum", "0 0 0\n1 0 0\n0 1 0\n", NULL, NULL, "centrality=psychic", 422},
        {"malformed json", "{\"points\": [[0,0,0], [1,", "application/json", NULL, NULL, 400},
        {"json unknown param", "{\"points\": [[0,0,0],[1,0,0],[0,1,0]], \"params\": {\"zz\": 1}}",
         "application/json", NULL, NULL, 400},
        {"multipart without file", "--" BOUNDARY "\r\nContent-Disposition: form-data; name=\"k\"\r\n\r\n7\r\n--"
         BOUNDARY "--\r\n", "multipart/form-data; boundary=" BOUNDARY, NULL, NULL, 400},
        {"multipart garbage", "this is not multipart at all", "multipart/form-data; boundary=" BOUNDARY,
         NULL, NULL, 400},
        {"multipart no boundary", "x", "multipart/form-data", NULL, NULL, 400},
        {"bad gzip", "definitely not gzip", NULL, "gzip", NULL, 400},
        {"unknown encoding", "0 0 0\n", NULL, "br", NULL, 415},
        {"empty body", "", NULL, NULL, NULL, 400},
        {"too many points", NULL, NULL, NULL, NULL, 413},
    };
    ps_daemon d;
    REQUIRE(ps_daemon_start(&d, (const char *const[]){"--max-points", "50", NULL}) == 0);
    char many[2000];
    size_t at = 0;
    for (int i = 0; i < 60; i++) at += (size_t)sprintf(many + at, "%d %d %d\n", i, i * i % 7, i % 3);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *text = cases[i].body ? cases[i].body : many;
        ps_client_body body = {text, strlen(text), cases[i].content_type, cases[i].encoding};
        ps_client_response r;
        ps_client_segment(&d.client, &body, cases[i].query, &r);
        CHECK_MSG(is_problem(&r, cases[i].status), "%s: status %ld (want %ld) %s: %.200s", cases[i].what,
                  r.status, cases[i].status, r.content_type, r.body ? r.body : "");
        ps_client_response_free(&r);
        CHECK_MSG(ps_daemon_healthy(&d), "unhealthy after %s", cases[i].what);
    }
    CHECK(ps_daemon_stop(&d, 10) == 0);
}

static void test_size_limits(void) {
    ps_daemon d;
    ps_client_response r;
    REQUIRE(ps_daemon_start(&d, (const char *const[]){"--max-body", "100000", NULL}) == 0);
    static const char huge[] = "POST /segment HTTP/1.1\r\nHost: x\r\nContent-Type: application/ply\r\n"
                               "Content-Length: 99999999999\r\n\r\nply\n";
    CHECK(ps_raw_status(&d, huge, sizeof huge - 1) == 413);
    size_t n = 300000, gz_len;
    char *zeros = calloc(n, 1), *gz = gzip_bytes(zeros, n, &gz_len);
    ps_client_body plain = {zeros, n, NULL, NULL}, bomb = {gz, gz_len, NULL, "gzip"};
    CHECK(ps_client_segment(&d.client, &plain, NULL, &r) == 0 && is_problem(&r, 413));
    ps_client_response_free(&r);
    CHECK(gz_len < 100000 && ps_client_segment(&d.client, &bomb, NULL, &r) == 0 && is_problem(&r, 413));
    ps_client_response_free(&r);
    CHECK(ps_daemon_healthy(&d));
    free(zeros), free(gz);
    CHECK(ps_daemon_stop(&d, 10) == 0);
}

typedef struct client_run {
    const ps_daemon *d;
    int ok;
} client_run;

static void *one_client(void *arg) {
    client_run *c = arg;
    ps_client_response r;
    ps_client_body body = {small.xyz, small.xyz_len, "text/plain", NULL};
    c->ok = ps_client_segment(&c->d->client, &body, NULL, &r) == 0 && r.status == 200 && same_labels(&r, &small);
    ps_client_response_free(&r);
    return NULL;
}

static void test_32_concurrent_clients(void) {
    enum { N = 32 };
    ps_daemon d;
    pthread_t threads[N];
    client_run runs[N];
    REQUIRE(need_small());
    REQUIRE(ps_daemon_start(&d, (const char *const[]){"--threads", "2", NULL}) == 0);
    for (int i = 0; i < N; i++) {
        runs[i] = (client_run){&d, 0};
        pthread_create(&threads[i], NULL, one_client, &runs[i]);
    }
    int ok = 0;
    for (int i = 0; i < N; i++) {
        pthread_join(threads[i], NULL);
        ok += runs[i].ok;
    }
    CHECK_MSG(ok == N, "%d of %d clients got the right labels", ok, N);
    CHECK(ps_daemon_stop(&d, 10) == 0);
}

static double seconds_now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* Waits until the job reports `state`; returns 1 when it did. */
static int wait_state(const ps_daemon *d, const char *id, const char *state, double timeout_s) {
    char needle[64];
    snprintf(needle, sizeof needle, "\"status\":\"%s\"", state);
    for (double t0 = seconds_now(); seconds_now() - t0 < timeout_s; ps_test_sleep_ms(20)) {
        ps_client_response r;
        int hit = ps_client_poll(&d->client, id, &r) == 0 && r.body && strstr(r.body, needle);
        ps_client_response_free(&r);
        if (hit) return 1;
    }
    return 0;
}

static void test_full_queue_and_cancel(void) {
    ps_daemon d;
    ps_client_response r;
    size_t n, len;
    char slow_id[128], queued_id[128];
    double *pts = ps_shape_dumbbell(700, &n, NULL);
    REQUIRE(pts);
    char *xyz = ps_points_xyz(pts, n, &len);
    free(pts);
    REQUIRE(ps_daemon_start(&d, (const char *const[]){"--threads", "1", "--queue-size", "1", NULL}) == 0);
    ps_client_body slow = {xyz, len, NULL, NULL};
    REQUIRE(ps_client_submit(&d.client, &slow, "centrality=exact", slow_id, sizeof slow_id, &r) == 0);
    ps_client_response_free(&r);
    CHECK_MSG(wait_state(&d, slow_id, "running", 20), "the %zu-point exact job never ran", n);
    CHECK(ps_client_submit(&d.client, &slow, "centrality=exact", queued_id, sizeof queued_id, &r) == 0 &&
          r.status == 202);
    ps_client_response_free(&r);
    CHECK(ps_client_segment(&d.client, &slow, NULL, &r) == 0 && is_problem(&r, 503) && r.retry_after[0]);
    ps_client_response_free(&r);
    CHECK(get_status(&d, "/readyz", &r) == 503);
    ps_client_response_free(&r);
    double t0 = seconds_now();
    CHECK(ps_client_cancel(&d.client, queued_id, &r) == 0 && r.status == 202 && strstr(r.body, "cancelled"));
    ps_client_response_free(&r);
    CHECK(ps_client_cancel(&d.client, slow_id, &r) == 0 && r.status == 202);
    ps_client_response_free(&r);
    CHECK_MSG(wait_state(&d, slow_id, "cancelled", 5), "DELETE did not stop the running job");
    CHECK_MSG(seconds_now() - t0 < 3, "cancelling took %.1f s", seconds_now() - t0);
    CHECK(ps_client_result(&d.client, slow_id, &r) == 0 && is_problem(&r, 409));
    ps_client_response_free(&r);
    CHECK(get_status(&d, "/readyz", &r) == 200);
    ps_client_response_free(&r);
    free(xyz);
    CHECK(ps_daemon_stop(&d, 10) == 0);
}

static void test_client_going_away_cancels(void) {
    ps_daemon d;
    ps_client_response r;
    size_t n, len;
    double *pts = ps_shape_dumbbell(500, &n, NULL);
    REQUIRE(pts);
    char *xyz = ps_points_xyz(pts, n, &len);
    free(pts);
    REQUIRE(ps_daemon_start(&d, (const char *const[]){"--threads", "1", NULL}) == 0);
    ps_client impatient = d.client;
    impatient.timeout_ms = 500;
    ps_client_body body = {xyz, len, NULL, NULL};
    CHECK(ps_client_segment(&impatient, &body, "centrality=exact", &r) != 0);
    ps_client_response_free(&r);
    int cancelled = 0;
    for (double t0 = seconds_now(); !cancelled && seconds_now() - t0 < 5; ps_test_sleep_ms(50)) {
        cancelled = get_status(&d, "/metrics", &r) == 200 &&
                    strstr(r.body, "pointseg_jobs_finished_total{outcome=\"cancelled\"} 1");
        ps_client_response_free(&r);
    }
    CHECK_MSG(cancelled, "the job of a client that went away was not cancelled");
    free(xyz);
    CHECK(ps_daemon_stop(&d, 10) == 0);
}

static void *drained_client(void *arg) {
    one_client(arg);
    return NULL;
}

static void test_sigterm_drains(void) {
    ps_daemon d;
    pthread_t t;
    REQUIRE(need_small());
    REQUIRE(ps_daemon_start(&d, (const char *const[]){"--threads", "1", NULL}) == 0);
    client_run run = {&d, 0};
    pthread_create(&t, NULL, drained_client, &run);
    ps_test_sleep_ms(60); /* the request is in: its job is queued or running */
    int status = ps_daemon_stop(&d, 20);
    pthread_join(t, NULL);
    CHECK_MSG(status == 0, "pointsegd exited with %d", status);
    CHECK_MSG(run.ok, "the request under way at SIGTERM was not answered correctly");
}

static void test_help_lists_flags(void) {
    char cmd[4200], path[4096], out[8192];
    ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
    REQUIRE(n > 0);
    path[n] = 0;
    snprintf(cmd, sizeof cmd, "%s/../pointsegd --help", dirname(path));
    FILE *p = popen(cmd, "r");
    REQUIRE(p);
    size_t len = fread(out, 1, sizeof out - 1, p);
    out[len] = 0;
    CHECK(pclose(p) == 0);
    const char *flags[] = {"--port", "--bind", "--threads", "--queue-size", "--max-body", "--max-points", "--max-memory",
                           "--job-ttl", "--token", "--cors-origin", "--static-dir", "POINTSEG_PORT"};
    for (size_t i = 0; i < sizeof flags / sizeof flags[0]; i++)
        CHECK_MSG(strstr(out, flags[i]), "--help lacks %s", flags[i]);
}

/* A second pointsegd on a port in use must fail, not share the port (a
 * job polled there would go to the wrong daemon). */
static void test_port_in_use_refused(void) {
    ps_daemon d;
    char path[4200], cmd[4400];
    REQUIRE(ps_daemon_start(&d, NULL) == 0);
    REQUIRE(ps_test_daemon_path(path, sizeof path) == 0);
    snprintf(cmd, sizeof cmd, "timeout 10 %s --port %d --bind 127.0.0.1 --quiet 2>/dev/null",
             path, d.port);
    int status = system(cmd);
    CHECK_MSG(WIFEXITED(status) && WEXITSTATUS(status) == 1,
              "second daemon on port %d: status %d", d.port, status);
    CHECK(ps_daemon_healthy(&d));
    CHECK(ps_daemon_stop(&d, 20) == 0);
}

static void test_zz_cleanup(void) {
    free_sample(&small);
    CHECK(1);
}

int main(int argc, char **argv) {
    static const ps_test_case tests[] = {
        TEST(test_help_lists_flags), TEST(test_service_endpoints), TEST(test_content_types_give_library_labels),
        TEST(test_jobs_api_matches_segment), TEST(test_outputs_and_includes),
        TEST(test_idle_daemon_job_gets_every_core), TEST(test_bad_inputs_get_problems),
        TEST(test_size_limits), TEST(test_memory_limit), TEST(test_token_and_static_files), TEST(test_32_concurrent_clients),
        TEST(test_full_queue_and_cancel), TEST(test_client_going_away_cancels),
        TEST(test_sigterm_drains), TEST(test_port_in_use_refused), TEST(test_zz_cleanup)};
    signal(SIGPIPE, SIG_IGN);
    if (ps_client_global_init()) return 1;
    return ps_test_main(__FILE__, tests, sizeof tests / sizeof tests[0], argc, argv);
}
