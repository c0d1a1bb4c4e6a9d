/*
 * bench_speed.c: how fast pointseg is, phase by phase and end to end
 * (file bytes -> ps_decode -> ps_segment -> ps_encode_json), on the scan
 * models horse.ply and bunny.ply (approx centrality), on a ~4,700-point
 * model with exact centrality (PSB 1.off, or a synthetic hand), and on
 * 1,000,000 points sampled from the horse's surface, with peak RSS.  Small
 * cases print the median of 5 runs, the 1M case one run.  Then the horse's
 * cost of method auto over method paper, from interleaved pairs of runs (a
 * drift of the machine's speed then moves both alike).  See
 * tests/bench/README.md.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include "bench_machine.h"
#include "decode.h"
#include "encode.h"
#include "mesh_sample.h"
#include "pointseg.h"
#include "shapes.h"
#include "testlib.h"

#define SMALL_RUNS 5
#define RATIO_PAIRS 11 /* interleaved auto / paper runs of the horse */
#define LARGE_POINTS 1000000

/* Columns of one measured run, in milliseconds (segments, points: counts). */
enum { COL_DECODE, COL_PHASE0, COL_SEGMENT = COL_PHASE0 + PS_PHASE_COUNT,
       COL_ENCODE, COL_TOTAL, COL_SEGMENTS, COL_POINTS, N_COLS };

typedef struct run_times { double v[N_COLS]; } run_times;

/* One benchmark case: a file to decode, or points already in memory. */
typedef struct speed_case {
    const char *name;
    const char *path;          /* file to read and decode, or NULL */
    const ps_pointset *points; /* used when path is NULL */
    ps_centrality_mode mode;
    int runs;
    ps_method method;          /* PS_METHOD_AUTO unless a case says paper */
} speed_case;

static double peak_rss_mb(void) {
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss / 1024.0; /* Linux reports kilobytes */
}

static void print_machine(void) {
    ps_bench_print_machine("bench_speed");
    printf("\n");
    printf("times in ms (median of %d runs; the 1M case runs once), peak RSS of the "
           "process so far in MB\n\n", SMALL_RUNS);
}

static int load_file(const char *path, ps_pointset *ps) {
    char *bytes = NULL;
    size_t len = 0;
    ps_api_error err;
    memset(ps, 0, sizeof *ps);
    if (ps_read_file(path, &bytes, &len, &err) != 0 || ps_decode(bytes, len, NULL, ps, &err) != 0) {
        fprintf(stderr, "%s: %s\n", path, err.message);
        free(bytes);
        return -1;
    }
    free(bytes);
    return 0;
}

/* Segments and encodes ps, filling the segment, phase and encode columns. */
static int segment_and_encode(const ps_pointset *ps, const speed_case *c, run_times *t) {
    ps_params params;
    ps_params_default(&params);
    params.centrality = c->mode;
    params.method = c->method;
    params.threads = 0;
    ps_input in = ps_pointset_input(ps);
    ps_result *r = NULL;
    ps_error err;
    double start = ps_bench_now_ms();
    if (ps_segment(&in, &params, NULL, &r, &err) != PS_OK) {
        fprintf(stderr, "ps_segment: %s\n", err.message);
        return -1;
    }
    double segmented = ps_bench_now_ms();
    size_t len = 0;
    char *json = ps_encode_json(ps, r, 0, &len);
    t->v[COL_ENCODE] = ps_bench_now_ms() - segmented;
    t->v[COL_SEGMENT] = segmented - start;
    for (int p = 0; p < PS_PHASE_COUNT; p++) t->v[COL_PHASE0 + p] = r->timings.ms[p];
    t->v[COL_SEGMENTS] = r->n_segments;
    t->v[COL_POINTS] = (double)ps->n;
    free(json);
    ps_result_free(r);
    return json ? 0 : -1;
}

/* One end-to-end run of a case; 0 or -1. */
static int run_once(const speed_case *c, run_times *t) {
    ps_pointset decoded;
    const ps_pointset *ps = c->points;
    double start = ps_bench_now_ms();
    memset(t, 0, sizeof *t);
    if (c->path) {
        if (load_file(c->path, &decoded) != 0) return -1;
        ps = &decoded;
    }
    t->v[COL_DECODE] = ps_bench_now_ms() - start;
    int rc = segment_and_encode(ps, c, t);
    t->v[COL_TOTAL] = ps_bench_now_ms() - start;
    if (c->path) ps_pointset_free(&decoded);
    return rc;
}

static int compare_double(const void *x, const void *y) {
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* Column-wise median of runs[0..n) into *out. */
static void median_times(const run_times *runs, int n, run_times *out) {
    double column[SMALL_RUNS];
    for (int c = 0; c < N_COLS; c++) {
        for (int i = 0; i < n; i++) column[i] = runs[i].v[c];
        qsort(column, (size_t)n, sizeof column[0], compare_double);
        out->v[c] = n % 2 ? column[n / 2] : (column[n / 2 - 1] + column[n / 2]) / 2;
    }
}

static void print_header(void) {
    printf("%-24s %8s %4s %8s", "case", "points", "runs", "decode");
    for (int p = 0; p < PS_PHASE_COUNT; p++) printf(" %10s", ps_phase_name(p));
    printf(" %9s %8s %9s %5s %8s\n", "segment", "encode", "total", "segs", "RSS MB");
}

static void run_case(const speed_case *c) {
    run_times runs[SMALL_RUNS], median;
    for (int i = 0; i < c->runs; i++) {
        if (run_once(c, &runs[i]) != 0) {
            printf("%-24s FAILED\n", c->name);
            return;
        }
    }
    median_times(runs, c->runs, &median);
    printf("%-24s %8.0f %4d ", c->name, median.v[COL_POINTS], c->runs);
    if (c->path) printf("%8.1f", median.v[COL_DECODE]);
    else printf("%8s", "-");
    for (int p = 0; p < PS_PHASE_COUNT; p++) printf(" %10.1f", median.v[COL_PHASE0 + p]);
    printf(" %9.1f %8.1f %9.1f %5.0f %8.1f\n", median.v[COL_SEGMENT], median.v[COL_ENCODE],
           median.v[COL_TOTAL], median.v[COL_SEGMENTS], peak_rss_mb());
}

static int file_exists(const char *path) { return access(path, R_OK) == 0; }

/* The scan model cases (horse, bunny: approx centrality; the horse also
 * with method paper, the reference for auto's cost). */
static void run_scan_models(const char *shared) {
    static const char *const names[] = {"horse", "bunny", "horse"};
    static const ps_method methods[] = {PS_METHOD_AUTO, PS_METHOD_AUTO, PS_METHOD_PAPER};
    for (int i = 0; i < 3; i++) {
        char path[4096], label[64];
        snprintf(path, sizeof path, "%s/models/%s.ply", shared ? shared : ".", names[i]);
        snprintf(label, sizeof label, "%s.ply approx%s", names[i],
                 methods[i] == PS_METHOD_PAPER ? " paper" : "");
        if (!shared || !file_exists(path)) {
            printf("%-24s SKIP: %s not found\n", label, path);
            continue;
        }
        speed_case c = {label, path, NULL, PS_CENTRALITY_APPROX, SMALL_RUNS, methods[i]};
        run_case(&c);
    }
}

/* The horse end to end with method auto over method paper, in RATIO_PAIRS
 * interleaved pairs of runs: the median ratio and the least and most. */
static void run_ratio(const char *shared) {
    char path[4096];
    snprintf(path, sizeof path, "%s/models/horse.ply", shared ? shared : ".");
    if (!shared || !file_exists(path)) {
        printf("horse auto / paper: SKIP: %s not found\n", path);
        return;
    }
    speed_case cases[2] = {{"horse auto", path, NULL, PS_CENTRALITY_APPROX, 1, PS_METHOD_AUTO},
                           {"horse paper", path, NULL, PS_CENTRALITY_APPROX, 1, PS_METHOD_PAPER}};
    double ratio[RATIO_PAIRS];
    for (int i = 0; i < RATIO_PAIRS; i++) {
        run_times t[2];
        if (run_once(&cases[0], &t[0]) != 0 || run_once(&cases[1], &t[1]) != 0) {
            printf("horse auto / paper: FAILED\n");
            return;
        }
        ratio[i] = t[0].v[COL_TOTAL] / t[1].v[COL_TOTAL];
    }
    qsort(ratio, RATIO_PAIRS, sizeof ratio[0], compare_double);
    printf("\nhorse auto / paper, end to end, %d interleaved pairs: median %.2f (%.2f to %.2f)\n",
           RATIO_PAIRS, ratio[RATIO_PAIRS / 2], ratio[0], ratio[RATIO_PAIRS - 1]);
}

/* Exact centrality on PSB 1.off (4,706 vertices), or a synthetic hand. */
static void run_exact(const char *shared) {
    char path[4096];
    snprintf(path, sizeof path, "%s/psb-dev/off/1.off", shared ? shared : ".");
    if (shared && file_exists(path)) {
        speed_case c = {"PSB 1.off exact", path, NULL, PS_CENTRALITY_EXACT, SMALL_RUNS, PS_METHOD_AUTO};
        run_case(&c);
        return;
    }
    ps_pointset hand;
    memset(&hand, 0, sizeof hand);
    hand.dim = 3;
    hand.points = ps_shape_hand(0, &hand.n, NULL);
    if (!hand.points) { printf("%-24s FAILED: out of memory\n", "synthetic hand exact"); return; }
    speed_case c = {"synthetic hand exact", NULL, &hand, PS_CENTRALITY_EXACT, SMALL_RUNS, PS_METHOD_AUTO};
    run_case(&c);
    ps_pointset_free(&hand);
}

/* 1,000,000 points sampled from the horse's triangles, run once. */
static void run_large(const char *shared) {
    char path[4096];
    ps_pointset horse, sampled;
    snprintf(path, sizeof path, "%s/models/horse.ply", shared ? shared : ".");
    if (!shared || !file_exists(path)) {
        printf("%-24s SKIP: %s not found\n", "horse 1M sampled", path);
        return;
    }
    if (load_file(path, &horse) != 0) return;
    memset(&sampled, 0, sizeof sampled);
    int rc = ps_mesh_sample_surface(&horse, LARGE_POINTS, 0, &sampled.points);
    sampled.n = LARGE_POINTS, sampled.dim = 3;
    ps_pointset_free(&horse);
    if (rc != 0) { printf("%-24s FAILED: no faces or out of memory\n", "horse 1M sampled"); return; }
    speed_case c = {"horse 1M sampled auto", NULL, &sampled, PS_CENTRALITY_AUTO, 1, PS_METHOD_AUTO};
    run_case(&c);
    ps_pointset_free(&sampled);
}

int main(int argc, char **argv) {
    int skip_large = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--skip-1m")) {
            skip_large = 1;
        } else {
            fprintf(stderr, "usage: bench_speed [--skip-1m]\n");
            return strcmp(argv[i], "--help") ? 2 : 0;
        }
    }
    const char *shared = ps_test_shared_dir();
    setvbuf(stdout, NULL, _IOLBF, 0);
    print_machine();
    print_header();
    run_scan_models(shared);
    run_exact(shared);
    if (!skip_large) run_large(shared);
    run_ratio(shared);
    return 0;
}
