/*
 * bench_load.c: pointsegd under load, from a second process on loopback.
 * Starts BUILD/pointsegd (beside BUILD/bench/) with default settings on a
 * free port, then
 *   a) POST /segment of PSB-sized models (PSB dev off/ID.off with 4,000 to
 *      10,000 vertices, else synthetic shapes as XYZ text) over 64
 *      concurrent keep-alive connections (libcurl multi) for a fixed number
 *      of requests: requests per second, p50/p90/p99 latency, errors
 *      (transport failures, non-200, bad JSON or a wrong point count), and
 *      the daemon's VmRSS at the start, middle and end (plus its VmHWM);
 *   b) the horse: median of 11 POST /segment against the median of 11
 *      in-process decode + ps_segment + encode with the daemon's parameters,
 *      alternated, giving the HTTP overhead in percent (target: under 10%);
 *   c) a soak of a fresh daemon: --soak N (default 20,000) mixed valid and
 *      invalid requests (tests/support/load_soak.h) over 8 connections, every
 *      status checked, VmRSS at the start, middle and end (the end must be
 *      within 20% of the middle).
 *
 *   bench_load [--requests N] [--connections N] [--timeout SECONDS] [--soak N] [--soak-only]
 *              [--synthetic]
 *
 * --synthetic uses the synthetic shapes even when the PSB files are there;
 * --soak-only runs c) alone.
 * Exit status 0 when every request succeeded (and the soak's memory held),
 * 1 otherwise, 2 on a bad option.  See docs/benchmarks-load.md.
 */
#include <cJSON.h>
#include <curl/curl.h>
#include <arpa/inet.h>
#include <fcntl.h>
#include <libgen.h>
#include <netinet/in.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "daemon_proc.h"
#include "decode.h"
#include "encode.h"
#include "load_soak.h"
#include "params_table.h"
#include "pointseg.h"
#include "psb_data.h"
#include "shapes.h"
#include "testlib.h"

#define MIN_POINTS 4000
#define MAX_POINTS 10000
#define MAX_BODIES 64
#define HORSE_RUNS 11
#define REQUEST_TIMEOUT_S 300L
#define RSS_SAMPLES 3
#define SOAK_CONNECTIONS 8
#define SOAK_MAX_GROWTH 0.20

typedef struct body {
    char name[32];
    char *bytes;
    size_t len;
    size_t n_points;
} body;

typedef struct body_set {
    body items[MAX_BODIES];
    size_t n;
    const char *source;
} body_set;

typedef struct options {
    size_t requests;
    int connections;
    double timeout_s;
    size_t soak;
    int synthetic;
    int soak_only;
} options;

typedef struct daemon_proc {
    pid_t pid;
    char url[64];
} daemon_proc;

/* One connection of the load run: its handle, its reply, its current body. */
typedef struct slot {
    CURL *easy;
    char *reply;
    size_t len, cap;
    const body *sent;
    int overflow;
} slot;

typedef struct load_stats {
    size_t done, transport_errors, non_200, bad_json;
    double *latency_ms; /* #done */
    double seconds;
    long rss_kb[RSS_SAMPLES], hwm_kb;
    int timed_out;
} load_stats;

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

static int parse_options(int argc, char **argv, options *o) {
    *o = (options){2000, 64, 3600, 20000, 0, 0};
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--synthetic")) {
            o->synthetic = 1;
            continue;
        }
        if (!strcmp(argv[i], "--soak-only")) {
            o->soak_only = 1;
            continue;
        }
        const char *value = i + 1 < argc ? argv[i + 1] : NULL;
        double v = value ? strtod(value, NULL) : 0;
        if (!value || v < 1) {
            fprintf(stderr, "usage: %s [--requests N] [--connections N] [--timeout SECONDS] "
                            "[--soak N] [--soak-only] [--synthetic]\n", argv[0]);
            return -1;
        }
        if (!strcmp(argv[i], "--requests")) o->requests = (size_t)v;
        else if (!strcmp(argv[i], "--connections")) o->connections = (int)v;
        else if (!strcmp(argv[i], "--timeout")) o->timeout_s = v;
        else if (!strcmp(argv[i], "--soak")) o->soak = (size_t)v;
        else return fprintf(stderr, "%s: unknown option %s\n", argv[0], argv[i]), -1;
        i++;
    }
    return 0;
}

static void print_machine(const options *o) {
    char line[512], cpu[256] = "unknown", date[64];
    FILE *f = fopen("/proc/cpuinfo", "r");
    while (f && fgets(line, sizeof line, f)) {
        char *colon = strchr(line, ':');
        if (strncmp(line, "model name", 10) || !colon) continue;
        snprintf(cpu, sizeof cpu, "%s", colon + 2);
        cpu[strcspn(cpu, "\n")] = 0;
        break;
    }
    if (f) fclose(f);
    time_t t = time(NULL);
    struct tm tm;
    strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S UTC", gmtime_r(&t, &tm));
    printf("pointseg %s bench_load, %s, libcurl %s\nmachine: nproc %ld, CPU %s\n", PS_VERSION,
           date, curl_version_info(CURLVERSION_NOW)->version, sysconf(_SC_NPROCESSORS_ONLN), cpu);
    printf("load: %zu requests over %d connections, timeout %.0f s\n\n", o->requests,
           o->connections, o->timeout_s);
}

/* ---- request bodies ------------------------------------------------------ */

/* Keeps bytes as a body when they decode to MIN_POINTS..MAX_POINTS points. */
static void add_body(body_set *set, const char *name, char *bytes, size_t len) {
    ps_pointset ps;
    ps_api_error err;
    if (set->n < MAX_BODIES && ps_decode(bytes, len, NULL, &ps, &err) == 0) {
        size_t n = ps.n;
        ps_pointset_free(&ps);
        if (n >= MIN_POINTS && n <= MAX_POINTS) {
            body *b = &set->items[set->n++];
            *b = (body){.bytes = bytes, .len = len, .n_points = n};
            snprintf(b->name, sizeof b->name, "%s", name);
            return;
        }
    }
    free(bytes);
}

static void load_psb_bodies(body_set *set) {
    char dir[4096];
    size_t count = 0;
    if (!ps_psb_find_dir(NULL, dir, sizeof dir)) return;
    int *ids = ps_psb_model_ids(dir, &count);
    for (size_t i = 0; i < count; i++) {
        char path[4200], name[32];
        char *bytes = NULL;
        size_t len = 0;
        ps_api_error err;
        snprintf(path, sizeof path, "%s/off/%d.off", dir, ids[i]);
        snprintf(name, sizeof name, "%d.off", ids[i]);
        if (ps_read_file(path, &bytes, &len, &err) == 0) add_body(set, name, bytes, len);
    }
    free(ids);
    set->source = "PSB dev off/*.off with 4,000 to 10,000 vertices";
}

static char *xyz_text(const double *pts, size_t n, size_t *len) {
    char *text = malloc(n * 3 * 18 + 1);
    size_t at = 0;
    for (size_t i = 0; text && i < n; i++)
        at += (size_t)sprintf(text + at, "%.9g %.9g %.9g\n", pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]);
    *len = at;
    return text;
}

/* The synthetic shapes, each at a density giving about 6,000 points (the
 * count is proportional to the density). */
static void make_synthetic_bodies(body_set *set) {
    static const struct { const char *name; double *(*make)(double, size_t *, int **); } shapes[] = {
        {"hand", ps_shape_hand}, {"star", ps_shape_star}, {"dumbbell", ps_shape_dumbbell}};
    for (size_t s = 0; s < sizeof shapes / sizeof shapes[0]; s++) {
        size_t n = 0, len = 0;
        double *pts = shapes[s].make(1, &n, NULL);
        free(pts);
        pts = n ? shapes[s].make(6000.0 / (double)n, &n, NULL) : NULL;
        char *text = pts ? xyz_text(pts, n, &len) : NULL;
        free(pts);
        if (text) add_body(set, shapes[s].name, text, len);
    }
    set->source = "synthetic shapes (tests/support/shapes.h) as XYZ text";
}

static void free_bodies(body_set *set) {
    for (size_t i = 0; i < set->n; i++) free(set->items[i].bytes);
    set->n = 0;
}

/* ---- the daemon ---------------------------------------------------------- */

static int get_ok(const char *url) {
    CURL *c = curl_easy_init();
    long status = 0;
    if (!c) return 0;
    curl_easy_setopt(c, CURLOPT_URL, url);
    curl_easy_setopt(c, CURLOPT_NOBODY, 1L);
    curl_easy_setopt(c, CURLOPT_TIMEOUT_MS, 1000L);
    if (curl_easy_perform(c) == CURLE_OK) curl_easy_getinfo(c, CURLINFO_RESPONSE_CODE, &status);
    curl_easy_cleanup(c);
    return status == 200;
}

/* The child: dies with the bench, logs to /tmp, runs with default settings. */
static void exec_daemon(const char *path, int port) {
    char port_text[16], log[64];
    snprintf(port_text, sizeof port_text, "%d", port);
    snprintf(log, sizeof log, "/tmp/pointsegd-bench-%d.log", (int)getppid());
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    int fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) dup2(fd, 2);
    execl(path, path, "--port", port_text, "--bind", "127.0.0.1", (char *)NULL);
    _exit(127);
}

static int daemon_stop(daemon_proc *d) {
    char how[128];
    int status = ps_test_daemon_stop(&d->pid, 10.0, how, sizeof how);
    if (status) fprintf(stderr, "bench_load: pointsegd %s\n", how);
    return status;
}

static int daemon_start(daemon_proc *d) {
    char path[4200], health[96];
    int port = ps_test_free_port();
    d->pid = 0;
    if (ps_test_daemon_path(path, sizeof path) || access(path, X_OK) || port <= 0) {
        fprintf(stderr, "bench_load: cannot run %s\n", path);
        return -1;
    }
    snprintf(d->url, sizeof d->url, "http://127.0.0.1:%d", port);
    snprintf(health, sizeof health, "%s/healthz", d->url);
    d->pid = fork();
    if (d->pid < 0) return -1;
    if (d->pid == 0) exec_daemon(path, port);
    for (int i = 0; i < 400; i++) {
        if (get_ok(health)) return 0;
        if (waitpid(d->pid, NULL, WNOHANG) == d->pid) break;
        ps_test_sleep_ms(25);
    }
    fprintf(stderr, "bench_load: %s did not become healthy\n", path);
    daemon_stop(d);
    return -1;
}

/* ---- replies ------------------------------------------------------------- */

static size_t on_reply(char *data, size_t size, size_t count, void *user) {
    slot *s = user;
    size_t n = size * count;
    if (s->len + n + 1 > s->cap) {
        size_t cap = s->cap ? s->cap : 1 << 16;
        while (cap < s->len + n + 1) cap *= 2;
        char *p = realloc(s->reply, cap);
        if (!p) return s->overflow = 1, 0;
        s->reply = p;
        s->cap = cap;
    }
    memcpy(s->reply + s->len, data, n);
    s->len += n;
    s->reply[s->len] = 0;
    return n;
}

/* 1 when reply is a segmentation document of n_points labels. */
static int good_document(const char *reply, size_t n_points) {
    cJSON *doc = cJSON_Parse(reply);
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(doc, "n_points");
    const cJSON *labels = cJSON_GetObjectItemCaseSensitive(doc, "labels");
    int ok = cJSON_IsNumber(n) && n->valuedouble == (double)n_points && cJSON_IsArray(labels) &&
             (size_t)cJSON_GetArraySize(labels) == n_points;
    cJSON_Delete(doc);
    return ok;
}

static int compare_double(const void *x, const void *y) {
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* Nearest-rank percentile p (0..100) of sorted[0..n). */
static double percentile(const double *sorted, size_t n, double p) {
    if (!n) return 0;
    size_t rank = (size_t)(p / 100.0 * (double)n + 0.999999);
    return sorted[rank ? (rank > n ? n - 1 : rank - 1) : 0];
}

/* ---- a) the load run ----------------------------------------------------- */

static struct curl_slist *upload_headers(void) {
    struct curl_slist *h = curl_slist_append(NULL, "Content-Type: application/octet-stream");
    return curl_slist_append(h, "Expect:"); /* no 100-continue round trip */
}

static int slot_init(slot *s, const char *url, struct curl_slist *headers) {
    memset(s, 0, sizeof *s);
    s->easy = curl_easy_init();
    if (!s->easy) return -1;
    curl_easy_setopt(s->easy, CURLOPT_URL, url);
    curl_easy_setopt(s->easy, CURLOPT_HTTPHEADER, headers);
    curl_easy_setopt(s->easy, CURLOPT_WRITEFUNCTION, on_reply);
    curl_easy_setopt(s->easy, CURLOPT_WRITEDATA, s);
    curl_easy_setopt(s->easy, CURLOPT_PRIVATE, s);
    curl_easy_setopt(s->easy, CURLOPT_TIMEOUT, REQUEST_TIMEOUT_S);
    curl_easy_setopt(s->easy, CURLOPT_NOSIGNAL, 1L);
    return 0;
}

static void slot_send(CURLM *multi, slot *s, const body *b) {
    s->sent = b;
    s->len = 0;
    s->overflow = 0;
    curl_easy_setopt(s->easy, CURLOPT_POSTFIELDS, b->bytes);
    curl_easy_setopt(s->easy, CURLOPT_POSTFIELDSIZE_LARGE, (curl_off_t)b->len);
    curl_multi_add_handle(multi, s->easy);
}

/* Counts one finished request of s into st. */
static void slot_finish(CURLM *multi, slot *s, CURLcode result, load_stats *st) {
    long status = 0;
    curl_off_t total_us = 0;
    curl_easy_getinfo(s->easy, CURLINFO_RESPONSE_CODE, &status);
    curl_easy_getinfo(s->easy, CURLINFO_TOTAL_TIME_T, &total_us);
    curl_multi_remove_handle(multi, s->easy);
    st->latency_ms[st->done++] = (double)total_us / 1e3;
    if (result != CURLE_OK || s->overflow) st->transport_errors++;
    else if (status != 200) st->non_200++;
    else if (!good_document(s->reply, s->sent->n_points)) st->bad_json++;
}

/* Runs the multi loop until every request is done or the deadline passes. */
static void drive(CURLM *multi, slot *slots, const body_set *bodies, const options *o,
                  pid_t daemon_pid, load_stats *st) {
    size_t started = (size_t)o->connections < o->requests ? (size_t)o->connections : o->requests;
    double deadline = now_s() + o->timeout_s;
    int running = 1, mid_sampled = 0;
    for (size_t i = 0; i < started; i++) slot_send(multi, &slots[i], &bodies->items[i % bodies->n]);
    while (st->done < o->requests) {
        if (now_s() > deadline) {
            st->timed_out = 1;
            break;
        }
        curl_multi_perform(multi, &running);
        CURLMsg *msg;
        int left;
        while ((msg = curl_multi_info_read(multi, &left))) {
            if (msg->msg != CURLMSG_DONE) continue;
            slot *s;
            CURLcode result = msg->data.result;
            curl_easy_getinfo(msg->easy_handle, CURLINFO_PRIVATE, (char **)&s);
            slot_finish(multi, s, result, st);
            if (started < o->requests) slot_send(multi, s, &bodies->items[started++ % bodies->n]);
        }
        if (!mid_sampled && st->done >= o->requests / 2) {
            st->rss_kb[1] = ps_proc_status_kb(daemon_pid, "VmRSS");
            mid_sampled = 1;
        }
        if (st->done < o->requests) curl_multi_poll(multi, NULL, 0, 100, NULL);
    }
}

static int run_load(const daemon_proc *d, const body_set *bodies, const options *o, load_stats *st) {
    char url[128];
    struct curl_slist *headers = upload_headers();
    slot *slots = calloc((size_t)o->connections, sizeof *slots);
    CURLM *multi = curl_multi_init();
    memset(st, 0, sizeof *st);
    st->latency_ms = malloc(o->requests * sizeof *st->latency_ms);
    int rc = headers && slots && multi && st->latency_ms ? 0 : -1;
    snprintf(url, sizeof url, "%s/segment", d->url);
    for (int i = 0; !rc && i < o->connections; i++) rc = slot_init(&slots[i], url, headers);
    if (!rc) {
        curl_multi_setopt(multi, CURLMOPT_MAX_HOST_CONNECTIONS, (long)o->connections);
        st->rss_kb[0] = ps_proc_status_kb(d->pid, "VmRSS");
        double start = now_s();
        drive(multi, slots, bodies, o, d->pid, st);
        st->seconds = now_s() - start;
        st->rss_kb[2] = ps_proc_status_kb(d->pid, "VmRSS");
        st->hwm_kb = ps_proc_status_kb(d->pid, "VmHWM");
    }
    for (int i = 0; slots && i < o->connections; i++) {
        if (slots[i].easy) curl_multi_remove_handle(multi, slots[i].easy);
        curl_easy_cleanup(slots[i].easy);
        free(slots[i].reply);
    }
    curl_multi_cleanup(multi);
    curl_slist_free_all(headers);
    free(slots);
    return rc;
}

static void print_bodies(const body_set *bodies) {
    size_t lo = (size_t)-1, hi = 0, sum = 0;
    for (size_t i = 0; i < bodies->n; i++) {
        size_t n = bodies->items[i].n_points;
        lo = n < lo ? n : lo;
        hi = n > hi ? n : hi;
        sum += n;
    }
    printf("a) POST /segment of %zu models (%s)\n   points: min %zu, mean %zu, max %zu; models:",
           bodies->n, bodies->source, lo, sum / bodies->n, hi);
    for (size_t i = 0; i < bodies->n; i++) printf(" %s", bodies->items[i].name);
    printf("\n\n");
}

static void print_load(const load_stats *st, const options *o) {
    qsort(st->latency_ms, st->done, sizeof *st->latency_ms, compare_double);
    size_t errors = st->transport_errors + st->non_200 + st->bad_json + (o->requests - st->done);
    double mid = (double)st->rss_kb[1], end = (double)st->rss_kb[2];
    printf("   %-34s %12zu\n", "requests completed", st->done);
    printf("   %-34s %12.1f\n", "wall time (s)", st->seconds);
    printf("   %-34s %12.1f\n", "requests per second", st->done / (st->seconds > 0 ? st->seconds : 1));
    printf("   %-34s %12.1f\n", "latency p50 (ms)", percentile(st->latency_ms, st->done, 50));
    printf("   %-34s %12.1f\n", "latency p90 (ms)", percentile(st->latency_ms, st->done, 90));
    printf("   %-34s %12.1f\n", "latency p99 (ms)", percentile(st->latency_ms, st->done, 99));
    printf("   %-34s %12.1f\n", "latency max (ms)", st->done ? st->latency_ms[st->done - 1] : 0);
    printf("   %-34s %12zu\n", "errors", errors);
    printf("   %-34s %12zu\n", "  transport (timeout, reset)", st->transport_errors);
    printf("   %-34s %12zu\n", "  status not 200", st->non_200);
    printf("   %-34s %12zu\n", "  bad JSON or wrong point count", st->bad_json);
    printf("   %-34s %12zu%s\n", "  not sent (bench timeout)", o->requests - st->done,
           st->timed_out ? "  TIMED OUT" : "");
    printf("   %-34s %8.1f MB %8.1f MB %8.1f MB\n", "daemon VmRSS start / middle / end",
           st->rss_kb[0] / 1024.0, mid / 1024.0, end / 1024.0);
    printf("   %-34s %12.1f MB\n", "daemon VmHWM (peak RSS)", st->hwm_kb / 1024.0);
    printf("   %-34s %11.1f%%\n\n", "RSS growth middle -> end", mid > 0 ? 100.0 * (end - mid) / mid : 0);
}

/* ---- b) the horse -------------------------------------------------------- */

static double median(double *v, int n) {
    qsort(v, (size_t)n, sizeof *v, compare_double);
    return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

/* One POST /segment of the horse; its milliseconds, or -1. */
static double horse_http_ms(const daemon_proc *d, const char *bytes, size_t len, size_t n_points) {
    char url[128];
    slot s;
    struct curl_slist *headers = curl_slist_append(NULL, "Content-Type: application/ply");
    headers = curl_slist_append(headers, "Expect:");
    snprintf(url, sizeof url, "%s/segment", d->url);
    if (!headers || slot_init(&s, url, headers)) return curl_slist_free_all(headers), -1;
    curl_easy_setopt(s.easy, CURLOPT_POSTFIELDS, bytes);
    curl_easy_setopt(s.easy, CURLOPT_POSTFIELDSIZE_LARGE, (curl_off_t)len);
    long status = 0;
    double start = now_s();
    CURLcode rc = curl_easy_perform(s.easy);
    double ms = (now_s() - start) * 1e3;
    curl_easy_getinfo(s.easy, CURLINFO_RESPONSE_CODE, &status);
    int ok = rc == CURLE_OK && status == 200 && !s.overflow && good_document(s.reply, n_points);
    curl_easy_cleanup(s.easy);
    curl_slist_free_all(headers);
    free(s.reply);
    return ok ? ms : -1;
}

/* One in-process decode + segment + JSON encode with the daemon's default
 * request parameters (threads 0: every core, as an idle daemon's job takes
 * them, server/core_share.c); its milliseconds, or -1. */
static double horse_library_ms(const char *bytes, size_t len, size_t *n_points) {
    ps_request_params rp;
    ps_pointset ps;
    ps_api_error api_err;
    ps_error err;
    ps_result *r = NULL;
    char *doc = NULL;
    size_t doc_len = 0;
    ps_request_params_default(&rp);
    double start = now_s();
    if (ps_decode(bytes, len, NULL, &ps, &api_err)) return -1;
    ps_input in = ps_pointset_input(&ps);
    if (ps_segment(&in, &rp.core, NULL, &r, &err) == PS_OK) doc = ps_encode_json(&ps, r, rp.include, &doc_len);
    double ms = (now_s() - start) * 1e3;
    *n_points = ps.n;
    free(doc);
    ps_result_free(r);
    ps_pointset_free(&ps);
    return doc ? ms : -1;
}

/* Returns 0, or -1 when a run failed. */
static int run_horse(const daemon_proc *d) {
    const char *shared = ps_test_shared_dir();
    char path[4096];
    char *bytes = NULL;
    size_t len = 0, n_points = 0;
    ps_api_error err;
    snprintf(path, sizeof path, "%s/models/horse.ply", shared ? shared : "../shared/data");
    if (!shared || ps_read_file(path, &bytes, &len, &err)) {
        printf("b) horse: SKIP: %s not found\n", path);
        return 0;
    }
    double http[HORSE_RUNS], lib[HORSE_RUNS];
    int failed = 0;
    for (int i = 0; i < HORSE_RUNS; i++) {
        lib[i] = horse_library_ms(bytes, len, &n_points);
        http[i] = horse_http_ms(d, bytes, len, n_points);
        failed |= lib[i] < 0 || http[i] < 0;
    }
    free(bytes);
    printf("b) horse.ply (%zu points, %zu bytes), median of %d, default daemon parameters\n", n_points,
           len, HORSE_RUNS);
    if (failed) return printf("   FAILED: a request or a library run failed\n"), -1;
    double h = median(http, HORSE_RUNS), l = median(lib, HORSE_RUNS), overhead = 100.0 * (h - l) / l;
    printf("   %-34s %12.1f\n", "POST /segment over HTTP (ms)", h);
    printf("   %-34s %12.1f\n", "library decode+segment+encode (ms)", l);
    printf("   %-34s %11.1f%%  (target < 10%%: %s)\n", "HTTP overhead (http - lib) / lib", overhead,
           overhead < 10 ? "met" : "NOT met");
    return 0;
}

/* c) the soak, on a daemon of its own; returns 0 when every request got
 * its status and the RSS at the end is within SOAK_MAX_GROWTH of the middle. */
static int run_soak(const options *o) {
    daemon_proc d;
    ps_soak_stats st;
    if (daemon_start(&d)) return -1;
    int rc = ps_soak_run(d.url, d.pid, o->soak, SOAK_CONNECTIONS, &st);
    double mid = (double)st.rss_kb[1], end = (double)st.rss_kb[2];
    double growth = mid > 0 ? (end - mid) / mid : 1;
    int exit_status = daemon_stop(&d);
    printf("c) soak: %zu requests cycling %zu kinds (valid, async, health, malformed) over %d "
           "connections, fresh daemon\n", o->soak, st.kinds, SOAK_CONNECTIONS);
    printf("   %-34s %12zu\n", "requests completed", st.done);
    printf("   %-34s %12.1f\n", "wall time (s)", st.seconds);
    printf("   %-34s %12.1f\n", "requests per second", st.done / (st.seconds > 0 ? st.seconds : 1));
    printf("   %-34s %12zu\n", "  wrong status", st.wrong_status);
    printf("   %-34s %12zu\n", "  transport (timeout, reset)", st.transport_errors);
    printf("   %-34s %8.1f MB %8.1f MB %8.1f MB\n", "daemon VmRSS start / middle / end",
           st.rss_kb[0] / 1024.0, mid / 1024.0, end / 1024.0);
    printf("   %-34s %12.1f MB\n", "daemon VmHWM (peak RSS)", st.hwm_kb / 1024.0);
    printf("   %-34s %11.1f%%  (limit %.0f%%: %s)\n", "RSS growth middle -> end", 100 * growth,
           100 * SOAK_MAX_GROWTH, growth <= SOAK_MAX_GROWTH ? "met" : "NOT met");
    printf("   daemon stopped on SIGTERM with exit status %d\n", exit_status);
    int ok = !rc && st.done == o->soak && !st.wrong_status && !st.transport_errors &&
             growth <= SOAK_MAX_GROWTH && exit_status == 0;
    return ok ? 0 : -1;
}

/* a) and b) on one daemon; returns 0 when every request succeeded. */
static int run_load_and_horse(const options *o) {
    body_set bodies = {.n = 0};
    daemon_proc d;
    load_stats st = {.done = 0};
    if (!o->synthetic) load_psb_bodies(&bodies);
    if (!bodies.n) make_synthetic_bodies(&bodies);
    if (!bodies.n || daemon_start(&d)) return free_bodies(&bodies), -1;
    printf("daemon: %s (default settings)\n\n", d.url);
    print_bodies(&bodies);
    int failed = run_load(&d, &bodies, o, &st) != 0;
    print_load(&st, o);
    failed |= st.done != o->requests || st.transport_errors || st.non_200 || st.bad_json;
    failed |= run_horse(&d) != 0;
    int exit_status = daemon_stop(&d);
    printf("\ndaemon stopped on SIGTERM with exit status %d\n\n", exit_status);
    free(st.latency_ms);
    free_bodies(&bodies);
    return failed || exit_status != 0 ? -1 : 0;
}

int main(int argc, char **argv) {
    options o;
    if (parse_options(argc, argv, &o)) return 2;
    if (curl_global_init(CURL_GLOBAL_ALL)) return 1;
    signal(SIGPIPE, SIG_IGN);
    print_machine(&o);
    int failed = !o.soak_only && run_load_and_horse(&o) != 0;
    failed |= run_soak(&o) != 0;
    curl_global_cleanup();
    return failed;
}
