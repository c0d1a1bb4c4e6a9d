/* load_soak.c: the mixed-request soak of load_soak.h, on libcurl multi. */
#include "load_soak.h"

#include "shapes.h"

#include <curl/curl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define SOAK_TIMEOUT_S 60L
#define MAX_SLOTS 64

typedef struct soak_kind {
    const char *method, *path, *content_type, *encoding;
    const char *body; /* NULL: the small scan */
    long status;
} soak_kind;

#define TWO_FILES "--b7\r\nContent-Disposition: form-data; name=\"file\"\r\n\r\n0 0 0\n\r\n" \
                  "--b7\r\nContent-Disposition: form-data; name=\"file\"\r\n\r\n1 1 1\n\r\n--b7--\r\n"

static const soak_kind kinds[] = {
    {"POST", "/segment?include=centrality,point_supernode", NULL, NULL, NULL, 200},
    {"POST", "/segment?output=labels", "text/plain", NULL, NULL, 200},
    {"POST", "/jobs?output=labels", NULL, NULL, NULL, 202},
    {"GET", "/healthz", NULL, NULL, NULL, 200},
    {"GET", "/metrics", NULL, NULL, NULL, 200},
    {"POST", "/segment", "image/png", NULL, NULL, 415},
    {"POST", "/segment", "application/json", NULL, "{\"points\": [[0,0,0], [1,", 400},
    {"POST", "/segment?colour=red", NULL, NULL, NULL, 400},
    {"POST", "/segment?%ff%fe=1", NULL, NULL, NULL, 400},
    {"POST", "/segment", NULL, "gzip", "definitely not gzip", 400},
    {"POST", "/segment?k=0x10", NULL, NULL, NULL, 422},
    {"POST", "/segment", "multipart/form-data; boundary=b7", NULL, TWO_FILES, 400},
    {"POST", "/segment", NULL, NULL, "", 400},
    {"GET", "/no/such/route", NULL, NULL, NULL, 404},
    {"GET", "/jobs/0123456789abcdef", NULL, NULL, NULL, 404},
};
#define N_KINDS (sizeof kinds / sizeof kinds[0])

typedef struct soak_slot {
    CURL *easy;
    struct curl_slist *headers;
    const soak_kind *kind;
} soak_slot;

typedef struct soak_run {
    const char *base_url;
    char *scan;        /* the small scan, XYZ text */
    size_t scan_len;
    soak_slot slots[MAX_SLOTS];
    int n_slots;
    CURLM *multi;
} soak_run;

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

long ps_proc_status_kb(pid_t pid, const char *name) {
    char path[64], line[256];
    long kb = -1;
    size_t n = strlen(name);
    snprintf(path, sizeof path, "/proc/%d/status", (int)pid);
    FILE *f = fopen(path, "r");
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, name, n) && line[n] == ':') kb = strtol(line + n + 1, NULL, 10);
    if (f) fclose(f);
    return kb;
}

static size_t discard(char *data, size_t size, size_t count, void *user) {
    (void)data, (void)user;
    return size * count;
}

/* A sphere of about 180 points: a segmentation of a few milliseconds. */
static char *small_scan(size_t *len) {
    size_t n;
    double *pts = ps_shape_sphere(14, &n, NULL);
    char *text = pts ? malloc(n * 3 * 18 + 1) : NULL;
    size_t at = 0;
    for (size_t i = 0; text && i < n; i++)
        at += (size_t)sprintf(text + at, "%.6f %.6f %.6f\n", pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]);
    free(pts);
    *len = at;
    return text;
}

static void slot_send(soak_run *run, soak_slot *s, const soak_kind *k) {
    char url[256], line[128];
    snprintf(url, sizeof url, "%s%s", run->base_url, k->path);
    curl_easy_reset(s->easy); /* keeps the connection */
    curl_slist_free_all(s->headers);
    s->headers = curl_slist_append(NULL, "Expect:");
    if (k->content_type) snprintf(line, sizeof line, "Content-Type: %s", k->content_type);
    else snprintf(line, sizeof line, "Content-Type: application/octet-stream");
    s->headers = curl_slist_append(s->headers, line);
    if (k->encoding) {
        snprintf(line, sizeof line, "Content-Encoding: %s", k->encoding);
        s->headers = curl_slist_append(s->headers, line);
    }
    s->kind = k;
    curl_easy_setopt(s->easy, CURLOPT_URL, url);
    curl_easy_setopt(s->easy, CURLOPT_WRITEFUNCTION, discard);
    curl_easy_setopt(s->easy, CURLOPT_PRIVATE, s);
    curl_easy_setopt(s->easy, CURLOPT_TIMEOUT, SOAK_TIMEOUT_S);
    curl_easy_setopt(s->easy, CURLOPT_NOSIGNAL, 1L);
    if (!strcmp(k->method, "POST")) {
        const char *body = k->body ? k->body : run->scan;
        curl_easy_setopt(s->easy, CURLOPT_HTTPHEADER, s->headers);
        curl_easy_setopt(s->easy, CURLOPT_POSTFIELDS, body);
        curl_easy_setopt(s->easy, CURLOPT_POSTFIELDSIZE_LARGE,
                         (curl_off_t)(k->body ? strlen(k->body) : run->scan_len));
    }
    curl_multi_add_handle(run->multi, s->easy);
}

static void slot_finish(soak_run *run, soak_slot *s, CURLcode result, ps_soak_stats *st) {
    long status = 0;
    curl_easy_getinfo(s->easy, CURLINFO_RESPONSE_CODE, &status);
    curl_multi_remove_handle(run->multi, s->easy);
    st->done++;
    if (result != CURLE_OK) st->transport_errors++;
    else if (status != s->kind->status) st->wrong_status++;
}

static void drive(soak_run *run, pid_t pid, size_t requests, ps_soak_stats *st) {
    size_t started = 0;
    int running = 1, mid_sampled = 0;
    for (int i = 0; i < run->n_slots && started < requests; i++, started++)
        slot_send(run, &run->slots[i], &kinds[started % N_KINDS]);
    while (st->done < requests) {
        curl_multi_perform(run->multi, &running);
        CURLMsg *msg;
        int left;
        while ((msg = curl_multi_info_read(run->multi, &left))) {
            if (msg->msg != CURLMSG_DONE) continue;
            soak_slot *s;
            CURLcode result = msg->data.result;
            curl_easy_getinfo(msg->easy_handle, CURLINFO_PRIVATE, (char **)&s);
            slot_finish(run, s, result, st);
            if (started < requests) slot_send(run, s, &kinds[started++ % N_KINDS]);
        }
        if (!mid_sampled && st->done >= requests / 2) {
            st->rss_kb[1] = ps_proc_status_kb(pid, "VmRSS");
            mid_sampled = 1;
        }
        if (st->done < requests) curl_multi_poll(run->multi, NULL, 0, 100, NULL);
    }
}

int ps_soak_run(const char *base_url, pid_t pid, size_t requests, int connections, ps_soak_stats *st) {
    soak_run run = {.base_url = base_url, .n_slots = connections < MAX_SLOTS ? connections : MAX_SLOTS};
    memset(st, 0, sizeof *st);
    st->kinds = N_KINDS;
    run.scan = small_scan(&run.scan_len);
    run.multi = curl_multi_init();
    int rc = run.scan && run.multi ? 0 : -1;
    for (int i = 0; !rc && i < run.n_slots; i++) rc = (run.slots[i].easy = curl_easy_init()) ? 0 : -1;
    if (!rc) {
        st->rss_kb[0] = ps_proc_status_kb(pid, "VmRSS");
        double start = now_s();
        drive(&run, pid, requests, st);
        st->seconds = now_s() - start;
        st->rss_kb[2] = ps_proc_status_kb(pid, "VmRSS");
        st->hwm_kb = ps_proc_status_kb(pid, "VmHWM");
    }
    for (int i = 0; i < run.n_slots; i++) {
        curl_easy_cleanup(run.slots[i].easy);
        curl_slist_free_all(run.slots[i].headers);
    }
    curl_multi_cleanup(run.multi);
    free(run.scan);
    return rc;
}
