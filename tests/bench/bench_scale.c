/*
 * bench_scale.c: pointseg on big scans.  1M, 2M, 4M and 10M points (or
 * --sizes) sampled uniformly by area on the horse's triangles (seed 0,
 * made in memory, never stored), default parameters, all cores (or
 * --threads; --k N for another neighbour count).  Each size runs once in a child process of its own, so its
 * peak RSS (wait4) is its own: the sampled input, ps_segment and the
 * labels' encoding.  Printed: per-phase times, total, the child's CPU
 * time (user + system: comparable on a shared machine), peak RSS, bytes per
 * point and ps_segment_memory_estimate beside it, as the markdown table of
 * docs/benchmarks.md, then the growth from the smallest size to the
 * largest against linear, and each step's (its time summed over the
 * input's draws) against linear and against n log n.  --out DIR also
 * writes each size's labels as DIR/N.lab (one per line), for cmp against
 * another build's.  See tests/bench/README.md.
 */
#define _DEFAULT_SOURCE /* wait4 */

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench_machine.h"
#include "decode.h"
#include "encode.h"
#include "mesh_sample.h"
#include "pointseg.h"
#include "testlib.h"

#define MAX_SIZES 16

/* What a child measured, sent through a pipe. */
typedef struct scale_run {
    int ok;
    int segments;
    ps_timings timings; /* ps_segment's, per phase and per step */
    double encode_ms, total_ms; /* total: ps_segment and the encoding */
} scale_run;

typedef struct scale_row {
    size_t n;
    scale_run run;
    double cpu_s;  /* user + system time of the child, all its threads */
    double rss_mb;
    double estimate_mb;
} scale_row;

/* labels (len bytes) as out_dir/N.lab; 0, or -1 when it cannot. */
static int save_labels(const char *out_dir, size_t n, const char *labels, size_t len) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%zu.lab", out_dir, n);
    FILE *f = fopen(path, "wb");
    int ok = f && fwrite(labels, 1, len, f) == len;
    if (f && fclose(f) != 0) ok = 0;
    if (!ok) fprintf(stderr, "bench_scale: cannot write %s\n", path);
    return ok ? 0 : -1;
}

/* In the child: sample, segment, encode (and save when out_dir is set);
 * the figures go to fd. */
static void run_child(const ps_pointset *horse, size_t n, const ps_params *params,
                      const char *out_dir, int fd) {
    scale_run run = {0};
    double *points = NULL;
    ps_result *r = NULL;
    ps_error err;
    if (ps_mesh_sample_surface(horse, n, 0, &points) == 0) {
        ps_input in = {.points = points, .n = n, .dim = 3};
        double start = ps_bench_now_ms();
        if (ps_segment(&in, params, NULL, &r, &err) == PS_OK) {
            double segmented = ps_bench_now_ms();
            size_t len = 0;
            char *labels = ps_encode_labels(r, &len);
            run.encode_ms = ps_bench_now_ms() - segmented;
            run.total_ms = ps_bench_now_ms() - start;
            run.timings = r->timings;
            run.segments = r->n_segments;
            run.ok = labels != NULL && (!out_dir || save_labels(out_dir, n, labels, len) == 0);
            free(labels);
        } else {
            fprintf(stderr, "%zu points: %s\n", n, err.message);
        }
    }
    ssize_t wrote = write(fd, &run, sizeof run);
    _exit(wrote == (ssize_t)sizeof run && run.ok ? 0 : 1);
}

/* One size in a child; 0, or -1 when it failed. */
static int measure(const ps_pointset *horse, size_t n, const ps_params *params,
                   const char *out_dir, scale_row *row) {
    int fds[2];
    if (pipe(fds) != 0) return -1;
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        run_child(horse, n, params, out_dir, fds[1]);
    }
    close(fds[1]);
    memset(row, 0, sizeof *row);
    ssize_t got = pid > 0 ? read(fds[0], &row->run, sizeof row->run) : -1;
    close(fds[0]);
    int status = 0;
    struct rusage ru;
    if (pid < 0 || wait4(pid, &status, 0, &ru) != pid) return -1;
    row->n = n;
    row->rss_mb = ru.ru_maxrss / 1024.0; /* Linux: kilobytes */
    row->cpu_s = (double)ru.ru_utime.tv_sec + ru.ru_utime.tv_usec / 1e6 + (double)ru.ru_stime.tv_sec +
                 ru.ru_stime.tv_usec / 1e6;
    ps_input in = {.n = n, .dim = 3};
    row->estimate_mb = (ps_segment_memory_estimate(&in, params) + n * 24.0) / 1048576.0;
    return got == (ssize_t)sizeof row->run && WIFEXITED(status) && !WEXITSTATUS(status) ? 0 : -1;
}

static void print_header(const ps_params *params) {
    ps_bench_print_machine("bench_scale");
    printf("; threads %d (0 = all)\n"
           "points sampled on the horse (seed 0), default parameters but k = %d; times in s\n\n",
           params->threads, params->k);
    printf("| points | total |");
    for (int p = 0; p < PS_PHASE_COUNT; p++) printf(" %s |", ps_phase_name(p));
    printf(" labels | CPU | segments | peak RSS | bytes/point | estimate |\n|---:|---:|");
    for (int p = 0; p < PS_PHASE_COUNT; p++) printf("---:|");
    printf("---:|---:|---:|---:|---:|---:|\n");
}

static void print_row(const scale_row *r) {
    printf("| %zu | %.2f |", r->n, r->run.total_ms / 1e3);
    for (int p = 0; p < PS_PHASE_COUNT; p++) printf(" %.2f |", r->run.timings.ms[p] / 1e3);
    printf(" %.2f | %.1f | %d | %.0f MB | %.0f | %.0f MB |\n", r->run.encode_ms / 1e3, r->cpu_s,
           r->run.segments, r->rss_mb, r->rss_mb * 1048576.0 / (double)r->n, r->estimate_mb);
}

/* Time and memory from the first row to the last, against linear growth. */
static void print_growth(const scale_row *first, const scale_row *last) {
    double points = (double)last->n / (double)first->n;
    double wall = last->run.total_ms / first->run.total_ms, cpu = last->cpu_s / first->cpu_s,
           rss = last->rss_mb / first->rss_mb;
    printf("\n%zu -> %zu points (x%.1f): time x%.2f (%.2f of linear), CPU time x%.2f (%.2f), "
           "peak RSS x%.2f (%.2f)\n", first->n, last->n, points, wall, wall / points, cpu,
           cpu / points, rss, rss / points);
}

/* Each step's time at the first and last size, its growth over linear
 * and over n log n (steps under 1 ms at the first size are left out). */
static void print_step_growth(const scale_row *first, const scale_row *last) {
    double points = (double)last->n / (double)first->n;
    double nlogn = points * log((double)last->n) / log((double)first->n);
    printf("\n| step | s at %zu | s at %zu | growth | of linear | of n log n |\n"
           "|---|---:|---:|---:|---:|---:|\n", first->n, last->n);
    for (int s = 0; s < PS_STEP_COUNT; s++) {
        double a = first->run.timings.step_ms[s], b = last->run.timings.step_ms[s];
        if (a < 1) continue;
        printf("| %s | %.2f | %.2f | x%.1f | %.2f | %.2f |\n", ps_step_name((ps_step)s), a / 1e3,
               b / 1e3, b / a, b / a / points, b / a / nlogn);
    }
}

static size_t parse_sizes(const char *text, size_t *sizes) {
    size_t count = 0;
    char *end;
    while (*text && count < MAX_SIZES) {
        unsigned long long v = strtoull(text, &end, 10);
        if (end == text || v < 100) return 0;
        sizes[count++] = (size_t)v;
        text = *end == ',' ? end + 1 : end;
        if (*end && *end != ',') return 0;
    }
    return count;
}

static int load_horse(ps_pointset *horse) {
    const char *shared = ps_test_shared_dir();
    char path[4096], *bytes = NULL;
    size_t len = 0;
    ps_api_error err;
    snprintf(path, sizeof path, "%s/models/horse.ply", shared ? shared : ".");
    memset(horse, 0, sizeof *horse);
    if (!shared || ps_read_file(path, &bytes, &len, &err) != 0 ||
        ps_decode(bytes, len, NULL, horse, &err) != 0) {
        printf("SKIP: %s not readable\n", path);
        free(bytes);
        return -1;
    }
    free(bytes);
    return 0;
}

int main(int argc, char **argv) {
    size_t sizes[MAX_SIZES] = {1000000, 2000000, 4000000, 10000000}, n_sizes = 4;
    ps_params params;
    ps_params_default(&params);
    const char *out_dir = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--sizes") && i + 1 < argc) {
            n_sizes = parse_sizes(argv[++i], sizes);
        } else if (!strcmp(argv[i], "--threads") && i + 1 < argc) {
            params.threads = atoi(argv[++i]);
        } else if (!strcmp(argv[i], "--k") && i + 1 < argc) {
            params.k = atoi(argv[++i]);
        } else if (!strcmp(argv[i], "--out") && i + 1 < argc) {
            out_dir = argv[++i];
        } else {
            fprintf(stderr, "usage: bench_scale [--sizes N,N,...] [--threads N] [--k N] [--out DIR]\n");
            return strcmp(argv[i], "--help") ? 2 : 0;
        }
    }
    if (out_dir && mkdir(out_dir, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "bench_scale: cannot make %s\n", out_dir);
        return 2;
    }
    if (n_sizes == 0) {
        fprintf(stderr, "bench_scale: --sizes wants comma-separated counts of at least 100\n");
        return 2;
    }
    ps_pointset horse;
    if (load_horse(&horse) != 0) return 0;
    setvbuf(stdout, NULL, _IOLBF, 0);
    print_header(&params);
    scale_row rows[MAX_SIZES];
    size_t done = 0;
    for (size_t i = 0; i < n_sizes; i++) {
        if (measure(&horse, sizes[i], &params, out_dir, &rows[done]) != 0) {
            printf("| %zu | FAILED (out of memory or killed) |\n", sizes[i]);
            continue;
        }
        print_row(&rows[done++]);
    }
    if (done > 1) {
        print_growth(&rows[0], &rows[done - 1]);
        print_step_growth(&rows[0], &rows[done - 1]);
    }
    ps_pointset_free(&horse);
    return 0;
}
