/*
 * bench_quality.c: segmentation quality on the Princeton Segmentation
 * Benchmark (PSB).  Reads one or more PSB folders (psb-dev, the unpacked
 * psb-train), segments every model in each input mode (`vertices`: the mesh
 * vertices; `surface:N`: the vertices, then points sampled uniformly by
 * area until N in all, only the vertices scored; `uneven:N`: the same with
 * the samples' density falling tenfold along the model's longest axis, a
 * scan from one side; `seen:N`: only what six views along the axes see,
 * the seen vertices and samples on the seen surface until N in all, scored
 * on the faces whose three vertices are seen; `view:N`: the same from the
 * front alone, one depth image), turns vertex labels into
 * face labels by majority and prints the Rand Index error against the
 * model's human segmentations, and its two parts: over-segmentation (face
 * pairs a human joins and the method splits) and under-segmentation (the
 * reverse).  Models run in parallel, one per core.
 *
 * The split that keeps tuning honest: ids with (ID-1) % 20 in {15..18} are
 * validation models.  Their figures are printed only as a mean per mode and
 * method, never per model or per category; every per-model row and the
 * category table cover the development models alone.
 *
 * --stability also segments a rotated, scaled and shifted copy of every
 * development model and prints those whose partition moved (Rand index
 * below 0.99 or another segment count).  --noise and --strays make the
 * input a noisy or outlier-ridden scan (--noise moves the mesh's vertices,
 * so surface samples lie on the noisy triangles; --scan-noise moves every
 * input point, as a scanner's noise does); --seed N draws the random inputs
 * (surface samples, noise, strays) anew, --seeds K runs K draws of each
 * mode that has any and prints their mean and range, how far two draws'
 * labels disagree and what the medoid draw scores.  See
 * tests/bench/README.md.
 */
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "draw_agreement.h"
#include "mesh_sample.h"
#include "mesh_seen.h"
#include "params_table.h"
#include "pointseg.h"
#include "psb_data.h"
#include "random_bits.h"
#include "shapes.h"

#define N_CATEGORIES 20
#define MAX_RUNS 2   /* the given parameters, then method=paper */
#define MAX_DIRS 8
#define MAX_MODES 32
#define UNEVEN_FAR 0.1 /* uneven:N: the samples' density at the far end, over the near end's */
#define MAX_SEEDS 8
enum { SEEN_ALL, SEEN_SIX, SEEN_FRONT };
#define STABLE_RI 0.99 /* the least Rand index a moved copy must keep */
#define PAIRED_SAME 5e-5 /* a smaller change of a model's 1 - RI counts as none */

typedef struct input_mode {
    char name[32];
    size_t surface_points; /* 0: the vertices alone */
    double far;            /* uneven:N: the density at the far end (UNEVEN_FAR), else 1 */
    int seen;              /* what a scan sees (mesh_seen.h): SEEN_ALL, SEEN_SIX (seen:N),
                              SEEN_FRONT (view:N) */
    uint64_t seed;         /* the draw of its random inputs (--seed, --seeds) */
    int first;             /* the mode that its other draws repeat (itself) */
} input_mode;

typedef struct quality_options {
    const char *dirs[MAX_DIRS]; /* PSB folders given on the command line */
    int n_dirs;
    input_mode modes[MAX_MODES];
    int n_modes;
    const char *ids_arg;       /* --ids list, or NULL for every model */
    const char *out_dir;       /* --out: write ID.lab predictions here */
    const char *against_dir;   /* --against: an earlier --out folder to compare with */
    int baseline_none;         /* --baseline none: every vertex labelled 0 */
    int runs;                  /* 1 with --single (or a baseline), else 2 */
    int jobs;                  /* models segmented at once */
    int stability;             /* --stability: also a moved copy per dev model */
    int dev_only;              /* --dev-only: skip the validation models */
    double noise;              /* --noise: sigma in mean mesh edge lengths */
    double scan_noise;         /* --scan-noise: sigma in the input's mean spacing */
    double strays;             /* --strays: stray points per vertex */
    uint64_t seed;             /* --seed: another draw of the random inputs */
    int seeds;                 /* --seeds: draws of each mode that has any */
    ps_request_params params;  /* defaults + --param + --threads */
} quality_options;

typedef struct model_row {
    const char *dir;
    int id;
    int validation;
    int failed;
    size_t points;             /* vertices */
    double human_segments;
    double people;             /* people among themselves (ps_psb_human_agreement) */
    int segments[MAX_RUNS];
    double error[MAX_RUNS];
    double under[MAX_RUNS];    /* the error's parts (ps_psb_score_parts) */
    double over[MAX_RUNS];
    double ms[MAX_RUNS];
    double moved_ri;           /* --stability: RI between the copy and the original */
    int moved_segments;
    int compared;              /* --against: the earlier labels were found and scored */
    double earlier_error;      /* --against: their 1 - RI */
    int *kept;                 /* --seeds: the first run's labels (#points), for the draws'
                                  agreement; the caller takes them */
} model_row;

typedef struct pool {
    const quality_options *o;
    const input_mode *mode;
    model_row *rows;
    size_t n_rows;
    size_t next;
    pthread_mutex_t lock;
} pool;

static const char usage[] =
    "usage: bench_quality [PSB_DIR]... [--input vertices|surface:N|uneven:N|seen:N|view:N]... [--ids 1,2,21]\n"
    "                     [--param name=value]... [--threads N] [--jobs N] [--single]\n"
    "                     [--dev-only] [--stability] [--out DIR] [--baseline none]\n"
    "                     [--noise F] [--scan-noise F] [--strays F] [--seed N] [--seeds K] [--against DIR]\n"
    "Segments every model of the PSB folders (default: psb-dev and psb-train, see\n"
    "tests/bench/README.md) in each input mode (default: vertices), with the given\n"
    "parameters (default: method auto) and with method=paper.  Validation models\n"
    "((ID-1) % 20 in 15..18) are reported as a mean only.\n";

static double now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static int is_validation(int id) { return (id - 1) % 20 >= 15 && (id - 1) % 20 <= 18; }

/* Sets one parameter through the shared parameter table; 0 or -1. */
static int set_param(ps_request_params *rp, const char *name, const char *value) {
    ps_api_error err;
    if (ps_request_param_set(rp, name, value, &err) != 0) {
        fprintf(stderr, "bench_quality: %s\n", err.message);
        return -1;
    }
    return 0;
}

/* Applies "name=value"; 0 or -1. */
static int apply_assignment(ps_request_params *rp, const char *assignment) {
    char name[64];
    const char *eq = strchr(assignment, '=');
    if (!eq || eq == assignment || (size_t)(eq - assignment) >= sizeof name) {
        fprintf(stderr, "bench_quality: --param wants name=value, got '%s'\n", assignment);
        return -1;
    }
    memcpy(name, assignment, (size_t)(eq - assignment));
    name[eq - assignment] = 0;
    return set_param(rp, name, eq + 1);
}

/* Parses "vertices", "surface:N", "uneven:N", "seen:N" or "view:N" into the
 * next mode slot; 0 or -1. */
static int add_mode(quality_options *o, const char *text) {
    if (o->n_modes == MAX_MODES) return -1;
    input_mode *m = &o->modes[o->n_modes];
    char *end = NULL;
    if (!strcmp(text, "vertices")) {
        m->surface_points = 0;
        m->far = 1.0;
        m->seen = SEEN_ALL;
    } else if (!strncmp(text, "surface:", 8) || !strncmp(text, "uneven:", 7) ||
               !strncmp(text, "seen:", 5) || !strncmp(text, "view:", 5)) {
        const char *count = strchr(text, ':') + 1;
        long n = strtol(count, &end, 10);
        if (end == count || *end || n < 1 || n > 10000000) return -1;
        m->surface_points = (size_t)n;
        m->far = !strncmp(text, "uneven:", 7) ? UNEVEN_FAR : 1.0;
        m->seen = !strncmp(text, "seen:", 5)   ? SEEN_SIX
                  : !strncmp(text, "view:", 5) ? SEEN_FRONT
                                               : SEEN_ALL;
    } else {
        return -1;
    }
    snprintf(m->name, sizeof m->name, "%s", text);
    o->n_modes++;
    return 0;
}

/* The value of a flag that needs one, or NULL with a message. */
static const char *flag_value(int argc, char **argv, int *i) {
    if (*i + 1 >= argc) {
        fprintf(stderr, "bench_quality: %s needs a value\n%s", argv[*i], usage);
        return NULL;
    }
    return argv[++*i];
}

/* Handles the flags without a value; 1 if a was one of them. */
static int switch_flag(quality_options *o, const char *a) {
    if (!strcmp(a, "--single")) o->runs = 1;
    else if (!strcmp(a, "--stability")) o->stability = 1;
    else if (!strcmp(a, "--dev-only")) o->dev_only = 1;
    else return 0;
    return 1;
}

/* Handles a flag with value v; 0 or -1. */
static int value_flag(quality_options *o, const char *a, const char *v) {
    if (!strcmp(a, "--ids")) o->ids_arg = v;
    else if (!strcmp(a, "--out")) o->out_dir = v;
    else if (!strcmp(a, "--against")) o->against_dir = v;
    else if (!strcmp(a, "--input")) return add_mode(o, v);
    else if (!strcmp(a, "--param")) return apply_assignment(&o->params, v);
    else if (!strcmp(a, "--threads")) return set_param(&o->params, "threads", v);
    else if (!strcmp(a, "--jobs") && (o->jobs = atoi(v)) >= 1 && o->jobs <= 64) return 0;
    else if (!strcmp(a, "--baseline") && !strcmp(v, "none")) o->baseline_none = 1, o->runs = 1;
    else if (!strcmp(a, "--noise") && (o->noise = atof(v)) >= 0 && o->noise <= 100) return 0;
    else if (!strcmp(a, "--scan-noise") && (o->scan_noise = atof(v)) >= 0 && o->scan_noise <= 100)
        return 0;
    else if (!strcmp(a, "--strays") && (o->strays = atof(v)) >= 0 && o->strays <= 1) return 0;
    else if (!strcmp(a, "--seed")) o->seed = strtoull(v, NULL, 10);
    else if (!strcmp(a, "--seeds") && (o->seeds = atoi(v)) >= 1 && o->seeds <= MAX_SEEDS) return 0;
    else return -1;
    return 0;
}

/* Seeds every mode with --seed and, with --seeds K, appends K - 1 more
 * draws (seeds --seed + 1 ...) of each mode that draws anything (surface
 * samples, --noise, --strays), named "MODE#J"; 0 or -1. */
static int add_draws(quality_options *o) {
    int given = o->n_modes;
    for (int m = 0; m < given; m++) o->modes[m].seed = o->seed, o->modes[m].first = m;
    for (int m = 0; m < given; m++) {
        const input_mode *base = &o->modes[m];
        if (!base->surface_points && o->noise == 0 && o->scan_noise == 0 && o->strays == 0)
            continue;
        for (int j = 1; j < o->seeds; j++) {
            if (o->n_modes == MAX_MODES) return -1;
            input_mode *draw = &o->modes[o->n_modes++];
            *draw = *base;
            draw->seed = o->seed + (uint64_t)j;
            snprintf(draw->name, sizeof draw->name, "%.24s#%c", base->name, (char)('0' + j));
        }
    }
    return 0;
}

static int parse_options(int argc, char **argv, quality_options *o) {
    memset(o, 0, sizeof *o);
    ps_request_params_default(&o->params);
    o->runs = MAX_RUNS;
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    o->jobs = cores > 0 && cores < 64 ? (int)cores : 1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) { fputs(usage, stdout); exit(0); }
        if (switch_flag(o, a)) continue;
        if (a[0] != '-') {
            if (o->n_dirs == MAX_DIRS) return -1;
            o->dirs[o->n_dirs++] = a;
            continue;
        }
        if (!(v = flag_value(argc, argv, &i))) return -1;
        if (value_flag(o, a, v) != 0) {
            fprintf(stderr, "bench_quality: bad option %s %s\n%s", a, v, usage);
            return -1;
        }
    }
    if (o->n_modes == 0) add_mode(o, "vertices");
    /* Models run in parallel; each one single-threaded unless asked. */
    if (o->params.core.threads == 0 && o->jobs > 1) o->params.core.threads = 1;
    return add_draws(o);
}

/* The category slot of a benchmark id, or -1 outside 1..400. */
static int category_index(int id) { return id >= 1 && id <= 20 * N_CATEGORIES ? (id - 1) / 20 : -1; }

/* Whether id is in the comma-separated list (every id when list is NULL). */
static int id_selected(const char *list, int id) {
    if (!list) return 1;
    for (const char *p = list; *p;) {
        char *end;
        long v = strtol(p, &end, 10);
        if (end == p) return 0;
        if (v == id) return 1;
        p = *end == ',' ? end + 1 : end;
    }
    return 0;
}

static int write_labels(const char *dir, const char *mode, int id, const int *labels, size_t n) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%d.%s.lab", dir, id, mode);
    FILE *f = fopen(path, "w");
    if (!f) { perror(path); return -1; }
    for (size_t i = 0; i < n; i++) fprintf(f, "%d\n", labels[i]);
    if (fclose(f) != 0) { perror(path); return -1; }
    return 0;
}

/* n labels from dir/ID.MODE.lab (an earlier run's --out), or NULL when the
 * file is missing or holds another count. */
static int *read_labels(const char *dir, const char *mode, int id, size_t n) {
    char path[4096], msg[600];
    int *labels = NULL;
    size_t count = 0;
    snprintf(path, sizeof path, "%s/%d.%s.lab", dir, id, mode);
    if (ps_read_int_file(path, &labels, &count, msg, sizeof msg) != 0) return NULL;
    if (count == n) return labels;
    free(labels);
    return NULL;
}

/* --against: scores the earlier run's labels of this model and mode. */
static void score_earlier(const quality_options *o, const input_mode *mode,
                          const ps_pointset *mesh, const ps_psb_humans *humans, model_row *row) {
    int *labels = read_labels(o->against_dir, mode->name, row->id, mesh->n);
    if (!labels) return;
    row->earlier_error = ps_psb_score(mesh, labels, humans);
    row->compared = 1;
    free(labels);
}

/* The parameters of run `run`: the given ones, or the paper's method. */
static ps_params run_params(const quality_options *o, int run) {
    ps_params p = o->params.core;
    if (run == 1) p.method = PS_METHOD_PAPER;
    return p;
}

/* Segments `in` and copies the labels of its first n_scored points into a
 * malloc'ed array; *segments gets the segment count.  NULL on failure. */
static int *segment_labels(const ps_input *in, const ps_params *params, size_t n_scored,
                           int id, int *segments) {
    ps_result *r = NULL;
    ps_error err;
    if (ps_segment(in, params, NULL, &r, &err) != PS_OK) {
        fprintf(stderr, "model %d: %s\n", id, err.message);
        return NULL;
    }
    *segments = r->n_segments;
    int *labels = malloc(n_scored * sizeof *labels);
    if (labels) memcpy(labels, r->labels, n_scored * sizeof *labels);
    ps_result_free(r);
    return labels;
}

/* Mean length of the mesh's face edges (each edge counted once per face). */
static double mean_edge(const ps_pointset *mesh) {
    double sum = 0;
    for (size_t t = 0; t < mesh->n_faces; t++)
        for (int k = 0; k < 3; k++) {
            const double *a = mesh->points + 3 * (size_t)mesh->faces[3 * t + (size_t)k];
            const double *b = mesh->points + 3 * (size_t)mesh->faces[3 * t + (size_t)(k + 1) % 3];
            sum += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                        (a[2] - b[2]) * (a[2] - b[2]));
        }
    return mesh->n_faces ? sum / (3.0 * (double)mesh->n_faces) : 0;
}

/* A uniform number in (0, 1) from a xorshift64 state. */
static double uniform(uint64_t *state) {
    return ((double)(ps_random_bits(state) >> 11) + 0.5) / 9007199254740992.0;
}

/* The key of a model's random draws (surface samples, noise, strays): its
 * id, and with --seed N another draw for every N. */
static uint64_t draw_key(const input_mode *mode, int id) {
    return (uint64_t)id ^ (mode->seed * 0xD1B54A32D192ED03ull);
}

/* Gaussian noise of sigma on coordinates[0 .. count) (Box-Muller), the
 * same for a given key on every run. */
static void add_gaussian(double *coordinates, size_t count, double sigma, uint64_t key) {
    uint64_t state = 0x9E3779B97F4A7C15ull ^ key;
    for (size_t i = 0; i < count; i++)
        coordinates[i] += sigma * sqrt(-2 * log(uniform(&state))) *
                          cos(2 * 3.14159265358979323846 * uniform(&state));
}

/* --noise: sigma = noise x mean edge on every vertex coordinate. */
static void add_noise(ps_pointset *mesh, double noise, uint64_t key) {
    add_gaussian(mesh->points, 3 * mesh->n, noise * mean_edge(mesh), key);
}

/* Appends `extra` stray points, uniform in the vertices' bounding box grown
 * by 10% on every side (seeded by key), to points[0 .. 3 n). */
static void add_strays(double *points, size_t n_mesh, size_t n, uint64_t key) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < 3 * n_mesh; i++)
        lo[i % 3] = fmin(lo[i % 3], points[i]), hi[i % 3] = fmax(hi[i % 3], points[i]);
    uint64_t state = 0x2545F4914F6CDD1Dull ^ key;
    for (size_t i = 3 * n_mesh; i < 3 * n; i++) {
        double grow = 0.1 * (hi[i % 3] - lo[i % 3]);
        points[i] = lo[i % 3] - grow + (hi[i % 3] - lo[i % 3] + 2 * grow) * uniform(&state);
    }
}

/* The model's input points (malloc'ed #n by 3): mesh's vertices first, then
 * the mode's samples of its surface (in seen:N and view:N, where mesh is
 * the seen part, of the whole mesh's part that `seen` sees), then the stray
 * points; 0 or -1. */
static int build_input(const ps_pointset *mesh, const ps_seen *seen, const input_mode *mode,
                       double strays, double scan_noise, uint64_t key, double **points,
                       size_t *n) {
    size_t n_surface = mode->surface_points > mesh->n ? mode->surface_points - mesh->n : 0;
    size_t n_strays = (size_t)ceil(strays * (double)mesh->n);
    *n = mesh->n + n_surface + n_strays;
    double *all = malloc(3 * *n * sizeof *all), *samples = NULL;
    if (!all) return -1;
    memcpy(all, mesh->points, 3 * mesh->n * sizeof *all);
    if (n_surface) {
        uint64_t seed = 0x5851F42D4C957F2Dull ^ key;
        int rc = seen            ? ps_seen_sample(seen, n_surface, seed, &samples)
                 : mode->far < 1 ? ps_mesh_sample_graded(mesh, n_surface, mode->far, seed,
                                                         &samples)
                                 : ps_mesh_sample_surface(mesh, n_surface, seed, &samples);
        if (rc != 0) return free(all), -1;
        memcpy(all + 3 * mesh->n, samples, 3 * n_surface * sizeof *all);
        free(samples);
    }
    if (scan_noise > 0) /* sigma in the scan's mean spacing, sqrt(area / points) */
        add_gaussian(all, 3 * (mesh->n + n_surface),
                     scan_noise * sqrt(ps_mesh_area(mesh) / (double)(mesh->n + n_surface)),
                     key ^ 0x7F4A7C159E3779B9ull);
    add_strays(all, mesh->n + n_surface, *n, key);
    *points = all;
    return 0;
}

/* The points moved by a rotation of 1.1 rad about (1, 2, 3), a scale of
 * 1000 and a shift: the copy --stability segments. */
static double *moved_copy(const double *points, size_t n) {
    double *copy = malloc(3 * n * sizeof *copy);
    if (!copy) return NULL;
    memcpy(copy, points, 3 * n * sizeof *copy);
    const double shift[3] = {12.5, -7.25, 3.0};
    double r = sqrt(14.0);
    ps_shape_transform(copy, n, 1 / r, 2 / r, 3 / r, 1.1, 1000, shift);
    return copy;
}

/* --stability: segments the moved copy with the given parameters and
 * compares its labels with the original's on the scored points. */
static int check_moved(const ps_input *in, const ps_params *params, const int *labels,
                       size_t n_scored, model_row *row) {
    double *copy = moved_copy(in->points, in->n);
    if (!copy) return -1;
    ps_input moved = *in; /* the faces still hold; the normals no longer do */
    moved.points = copy;
    moved.normals = NULL;
    int *moved_labels = segment_labels(&moved, params, n_scored, row->id, &row->moved_segments);
    free(copy);
    if (!moved_labels) return -1;
    row->moved_ri = 1 - ps_rand_index_error(labels, moved_labels, n_scored);
    free(moved_labels);
    return 0;
}

/* Segments the input with each run's parameters and scores the vertices. */
static int score_runs(const quality_options *o, const input_mode *mode, const ps_input *in,
                      const ps_pointset *mesh, const ps_psb_humans *humans, model_row *row) {
    for (int run = 0; run < o->runs; run++) {
        ps_params params = run_params(o, run);
        double start = now_ms();
        int *labels = o->baseline_none ? calloc(mesh->n, sizeof *labels)
                                       : segment_labels(in, &params, mesh->n, row->id,
                                                        &row->segments[run]);
        row->ms[run] = now_ms() - start;
        if (o->baseline_none) row->segments[run] = 1;
        int rc = labels ? 0 : -1;
        if (rc == 0 && o->out_dir && run == 0)
            rc = write_labels(o->out_dir, mode->name, row->id, labels, mesh->n);
        if (rc == 0 && o->stability && run == 0 && !row->validation && !o->baseline_none)
            rc = check_moved(in, &params, labels, mesh->n, row);
        if (rc == 0)
            row->error[run] =
                ps_psb_score_parts(mesh, labels, humans, &row->under[run], &row->over[run]);
        if (rc == 0 && o->seeds > 1 && run == 0) row->kept = labels, labels = NULL;
        free(labels);
        if (rc != 0) return -1;
    }
    return 0;
}

/* seen:N, view:N: moves the whole mesh into *whole and leaves in *mesh its
 * part `seen` (built on the whole) sees: the seen vertices in their order,
 * the faces whose three vertices are seen; *kept_faces (malloc'ed
 * #mesh->n_faces) lists each kept face's index in the whole.  0 or -1. */
static int keep_seen_part(ps_pointset *mesh, const ps_seen *seen, ps_pointset *whole,
                          size_t **kept_faces) {
    *whole = *mesh;
    *mesh = (ps_pointset){.dim = 3};
    unsigned char *flags = malloc(whole->n ? whole->n : 1);
    uint32_t *index = malloc((whole->n ? whole->n : 1) * sizeof *index);
    mesh->points = malloc(3 * (whole->n ? whole->n : 1) * sizeof *mesh->points);
    mesh->faces = malloc(3 * (whole->n_faces ? whole->n_faces : 1) * sizeof *mesh->faces);
    *kept_faces = malloc((whole->n_faces ? whole->n_faces : 1) * sizeof **kept_faces);
    int rc = flags && index && mesh->points && mesh->faces && *kept_faces ? 0 : -1;
    if (rc == 0) ps_seen_flags(seen, whole->points, whole->n, flags);
    for (size_t i = 0; rc == 0 && i < whole->n; i++) {
        index[i] = (uint32_t)mesh->n;
        if (flags[i]) memcpy(mesh->points + 3 * mesh->n++, whole->points + 3 * i, 3 * sizeof(double));
    }
    for (size_t f = 0; rc == 0 && f < whole->n_faces; f++) {
        const uint32_t *t = whole->faces + 3 * f;
        if (!flags[t[0]] || !flags[t[1]] || !flags[t[2]]) continue;
        for (int k = 0; k < 3; k++) mesh->faces[3 * mesh->n_faces + (size_t)k] = index[t[k]];
        (*kept_faces)[mesh->n_faces++] = f;
    }
    free(flags);
    free(index);
    return rc;
}

/* Keeps of every human segmentation the labels of the kept faces. */
static void keep_human_faces(ps_psb_humans *humans, const size_t *kept_faces, size_t n_kept) {
    for (int h = 0; h < humans->n_humans; h++)
        for (size_t f = 0; f < n_kept; f++) humans->labels[h][f] = humans->labels[h][kept_faces[f]];
    humans->n_faces = n_kept;
}

/* Loads, segments and scores one model; 0 or -1. */
static int run_model(const quality_options *o, const input_mode *mode, model_row *row) {
    ps_pointset mesh, whole = {0};
    ps_psb_humans humans;
    size_t *kept_faces = NULL;
    if (ps_psb_load_mesh(row->dir, row->id, &mesh) != 0) return -1;
    if (o->noise > 0) add_noise(&mesh, o->noise, draw_key(mode, row->id));
    double *points = NULL;
    size_t n = 0;
    ps_seen *seen = NULL; /* seen:N, view:N: the views' depth buffers of the whole mesh */
    int rc = 0;
    if (mode->seen != SEEN_ALL) {
        unsigned views = mode->seen == SEEN_SIX ? PS_SEEN_SIX : ps_mesh_front_view(&mesh);
        seen = ps_seen_build(&mesh, views);
        rc = seen ? keep_seen_part(&mesh, seen, &whole, &kept_faces) : -1;
    }
    row->points = mesh.n;
    if (rc == 0 &&
        build_input(&mesh, seen, mode, o->strays, o->scan_noise, draw_key(mode, row->id),
                    &points, &n) == 0 &&
        ps_psb_load_humans(row->dir, row->id, seen ? whole.n_faces : mesh.n_faces,
                           &humans) == 0) {
        if (seen) keep_human_faces(&humans, kept_faces, mesh.n_faces);
        row->human_segments = ps_psb_mean_segments(&humans);
        row->people = ps_psb_human_agreement(&humans);
        ps_input in = {.points = points, .n = n, .dim = 3};
        if (n == mesh.n && !seen) { /* the mesh itself; a scan is points only */
            in.normals = mesh.normals;
            in.faces = mesh.faces;
            in.n_faces = mesh.n_faces;
        }
        rc = score_runs(o, mode, &in, &mesh, &humans, row);
        if (rc == 0 && o->against_dir) score_earlier(o, mode, &mesh, &humans, row);
        ps_psb_humans_free(&humans);
    } else {
        rc = -1;
    }
    free(points);
    free(kept_faces);
    ps_seen_free(seen);
    ps_pointset_free(&mesh);
    ps_pointset_free(&whole);
    return rc;
}

static void *pool_worker(void *arg) {
    pool *p = arg;
    for (;;) {
        pthread_mutex_lock(&p->lock);
        size_t i = p->next++;
        pthread_mutex_unlock(&p->lock);
        if (i >= p->n_rows) return NULL;
        p->rows[i].failed = run_model(p->o, p->mode, &p->rows[i]) != 0;
    }
}

/* Runs every row in one mode on o->jobs threads. */
static void run_rows(const quality_options *o, const input_mode *mode, model_row *rows, size_t n) {
    pool p = {.o = o, .mode = mode, .rows = rows, .n_rows = n};
    pthread_mutex_init(&p.lock, NULL);
    pthread_t threads[64];
    int started = 0;
    for (int t = 0; t < o->jobs; t++)
        if (pthread_create(&threads[started], NULL, pool_worker, &p) == 0) started++;
    if (started == 0) pool_worker(&p);
    for (int t = 0; t < started; t++) pthread_join(threads[t], NULL);
    pthread_mutex_destroy(&p.lock);
}

/* The psb-train folder: $POINTSEG_PSB_TRAIN, else ~/.cache/pointseg/psb-train. */
static int find_train_dir(char *out, size_t cap) {
    const char *env = getenv("POINTSEG_PSB_TRAIN"), *home = getenv("HOME");
    char given[4096];
    if (env) snprintf(given, sizeof given, "%s", env);
    else snprintf(given, sizeof given, "%s/.cache/pointseg/psb-train", home ? home : ".");
    return ps_psb_find_dir(given, out, cap);
}

/* Every selected model of every folder, in folder then id order. */
static model_row *collect_rows(const quality_options *o, char dirs[][4096], int n_dirs,
                               size_t *n_rows) {
    size_t cap = 0, n = 0;
    model_row *rows = NULL;
    for (int d = 0; d < n_dirs; d++) {
        size_t n_ids = 0;
        int *ids = ps_psb_model_ids(dirs[d], &n_ids);
        for (size_t m = 0; m < n_ids; m++) {
            if (!id_selected(o->ids_arg, ids[m])) continue;
            if (o->dev_only && is_validation(ids[m])) continue;
            if (n == cap) {
                cap = cap ? 2 * cap : 512;
                model_row *grown = realloc(rows, cap * sizeof *rows);
                if (!grown) { free(ids); free(rows); *n_rows = 0; return NULL; }
                rows = grown;
            }
            rows[n++] = (model_row){.dir = dirs[d], .id = ids[m], .validation = is_validation(ids[m])};
        }
        free(ids);
    }
    *n_rows = n;
    return rows;
}

static void print_params(const quality_options *o, char dirs[][4096], int n_dirs) {
    const ps_params *p = &o->params.core;
    for (int d = 0; d < n_dirs; d++) printf("PSB folder: %s\n", dirs[d]);
    if (o->baseline_none) {
        printf("labelling: baseline none (every vertex the same label)\n\n");
        return;
    }
    printf("params: method=%s k=%d centrality=%s samples=%d persistence=%g ncut_threshold=%g "
           "feature_threshold=%g minima=%d f2=%d threads=%d (models at once: %d)\n",
           ps_method_name(p->method), p->k, ps_centrality_name(p->centrality), p->samples,
           p->persistence, p->ncut_threshold, p->feature_threshold, p->use_minima, p->use_f2,
           p->threads, o->jobs);
    if (o->noise > 0) printf("noise: sigma %g mean edge lengths per coordinate\n", o->noise);
    if (o->scan_noise > 0)
        printf("scan noise: sigma %g mean input spacings (sqrt(area / points)) per coordinate\n",
               o->scan_noise);
    if (o->strays > 0) printf("strays: %g stray points per vertex (vertices scored)\n", o->strays);
    if (o->seed) printf("seed: %llu (surface samples, noise and strays drawn anew)\n", (unsigned long long)o->seed);
    if (o->runs > 1) printf("compared with: the same, method=paper\n");
    printf("validation models ((ID-1) %% 20 in 15..18): mean only\n");
}

static const char *run_name(const quality_options *o, int run) {
    if (o->baseline_none) return "none";
    return ps_method_name(run_params(o, run).method);
}

static void print_model_rows(const quality_options *o, const model_row *rows, size_t n) {
    printf("%5s %-10s %7s %10s", "id", "category", "points", "human segs");
    for (int run = 0; run < o->runs; run++)
        printf(" | %-6s %5s %7s %9s", run_name(o, run), "segs", "1-RI", "time ms");
    if (o->stability) printf(" | moved segs     RI");
    printf("\n");
    for (size_t i = 0; i < n; i++) {
        const model_row *row = &rows[i];
        if (row->validation) continue;
        printf("%5d %-10s", row->id, ps_psb_category(row->id));
        if (row->failed) { printf(" FAILED\n"); continue; }
        printf(" %7zu %10.1f", row->points, row->human_segments);
        for (int run = 0; run < o->runs; run++)
            printf(" | %-6s %5d %7.4f %9.1f", "", row->segments[run], row->error[run], row->ms[run]);
        if (o->stability) printf(" | %10d %6.4f", row->moved_segments, row->moved_ri);
        printf("\n");
    }
}

/* The category table over the development models. */
static void print_categories(const quality_options *o, const model_row *rows, size_t n) {
    double sum[MAX_RUNS][N_CATEGORIES] = {{0}}, over[MAX_RUNS][N_CATEGORIES] = {{0}};
    double people[N_CATEGORIES] = {0};
    int count[N_CATEGORIES] = {0}, people_count[N_CATEGORIES] = {0};
    for (size_t i = 0; i < n; i++) {
        int k = category_index(rows[i].id);
        if (rows[i].validation || rows[i].failed || k < 0) continue;
        for (int run = 0; run < o->runs; run++)
            sum[run][k] += rows[i].error[run], over[run][k] += rows[i].over[run];
        count[k]++;
        if (!isnan(rows[i].people)) people[k] += rows[i].people, people_count[k]++;
    }
    printf("\n%-10s %6s %7s", "category", "models", "people");
    for (int run = 0; run < o->runs; run++) printf(" %7s %7s %7s", run_name(o, run), "over", "under");
    printf("   (development models)\n");
    for (int k = 0; k < N_CATEGORIES; k++) {
        if (!count[k]) continue;
        printf("%-10s %6d", ps_psb_category(20 * k + 1), count[k]);
        if (people_count[k]) printf(" %7.4f", people[k] / people_count[k]);
        else printf(" %7s", "-");
        for (int run = 0; run < o->runs; run++)
            printf(" %7.4f %7.4f %7.4f", sum[run][k] / count[k], over[run][k] / count[k],
                   (sum[run][k] - over[run][k]) / count[k]);
        printf("\n");
    }
}

/* --against: the first run's change from the earlier labels, per split. */
typedef struct paired_change {
    int models;           /* models with earlier labels */
    double mean, se;      /* mean change of 1 - RI (negative: better) and its standard error */
    int better, worse;    /* models whose 1 - RI moved by over PAIRED_SAME either way */
    int categories_better, categories_worse; /* by the category sums (development) */
} paired_change;

typedef struct split_means {
    double mean[2][MAX_RUNS]; /* [validation][run] */
    double over[2][MAX_RUNS]; /* its part from over-segmentation; the rest is under */
    int models[2];
    double people[2];         /* [validation] people among themselves, over the models with two humans */
    int people_models[2];
    int failed;
    paired_change change[2];  /* [validation] */
} split_means;

static split_means split_summary(const quality_options *o, const model_row *rows, size_t n) {
    split_means s;
    memset(&s, 0, sizeof s);
    for (size_t i = 0; i < n; i++) {
        if (rows[i].failed) { s.failed++; continue; }
        int v = rows[i].validation;
        for (int run = 0; run < o->runs; run++)
            s.mean[v][run] += rows[i].error[run], s.over[v][run] += rows[i].over[run];
        s.models[v]++;
        if (!isnan(rows[i].people)) s.people[v] += rows[i].people, s.people_models[v]++;
    }
    for (int v = 0; v < 2; v++) {
        s.people[v] = s.people_models[v] ? s.people[v] / s.people_models[v] : NAN;
        for (int run = 0; run < o->runs; run++) {
            s.mean[v][run] = s.models[v] ? s.mean[v][run] / s.models[v] : NAN;
            s.over[v][run] = s.models[v] ? s.over[v][run] / s.models[v] : NAN;
        }
    }
    return s;
}

/* --against: per split, the mean change of the first run's 1 - RI from the
 * earlier labels, its standard error (the models' changes are paired:
 * their spread, not the models' own, bounds what the mean can show), how
 * many models and (development) categories moved each way. */
static void paired_summary(const model_row *rows, size_t n, paired_change change[2]) {
    double sum[2] = {0, 0}, sum2[2] = {0, 0}, category[N_CATEGORIES] = {0};
    memset(change, 0, 2 * sizeof *change);
    for (size_t i = 0; i < n; i++) {
        const model_row *row = &rows[i];
        if (row->failed || !row->compared) continue;
        double d = row->error[0] - row->earlier_error;
        paired_change *c = &change[row->validation];
        c->models++;
        sum[row->validation] += d, sum2[row->validation] += d * d;
        c->better += d < -PAIRED_SAME, c->worse += d > PAIRED_SAME;
        int k = category_index(row->id);
        if (!row->validation && k >= 0) category[k] += d;
    }
    for (int v = 0; v < 2; v++) {
        paired_change *c = &change[v];
        if (c->models == 0) continue;
        c->mean = sum[v] / c->models;
        double var = c->models > 1 ? (sum2[v] - c->models * c->mean * c->mean) / (c->models - 1) : 0;
        c->se = sqrt(fmax(var, 0) / c->models);
    }
    for (int k = 0; k < N_CATEGORIES; k++) {
        change[0].categories_better += category[k] < -PAIRED_SAME;
        change[0].categories_worse += category[k] > PAIRED_SAME;
    }
}

/* --against: each mode's change from the earlier run's labels.  Validation
 * models count only in the mean, as everywhere. */
static void print_changes(const quality_options *o, const split_means *s) {
    if (!o->against_dir) return;
    printf("\n== change of 1-RI against %s (%s; negative: better; +- one standard error of "
           "the paired mean) ==\n", o->against_dir, run_name(o, 0));
    printf("%-16s %-48s %s\n", "input", "development", "validation");
    for (int m = 0; m < o->n_modes; m++) {
        const paired_change *d = &s[m].change[0], *v = &s[m].change[1];
        printf("%-16s", o->modes[m].name);
        if (d->models)
            printf(" %+.4f +- %.4f (%3d: %3d better, %3d worse; categories %2d / %2d) ", d->mean,
                   d->se, d->models, d->better, d->worse, d->categories_better,
                   d->categories_worse);
        else
            printf(" %-48s", "- (no earlier labels)");
        if (v->models) printf(" %+.4f +- %.4f (%d)\n", v->mean, v->se, v->models);
        else printf(" -\n");
    }
}

/* --stability: the development models whose moved copy's partition moved. */
static int print_stability(const model_row *rows, size_t n) {
    int checked = 0, moved = 0;
    double least = 1;
    for (size_t i = 0; i < n; i++) {
        const model_row *row = &rows[i];
        if (row->validation || row->failed) continue;
        checked++;
        least = fmin(least, row->moved_ri);
        if (row->moved_ri >= STABLE_RI && row->moved_segments == row->segments[0]) continue;
        printf("  unstable: %d (%s, %zu vertices): RI %.4f, %d segments moved vs %d\n", row->id,
               ps_psb_category(row->id), row->points, row->moved_ri, row->moved_segments,
               row->segments[0]);
        moved++;
    }
    printf("stability (rotated 1.1 rad, scaled 1000, shifted): %d of %d development models "
           "keep RI >= %.2f and their segment count; least RI %.4f\n",
           checked - moved, checked, STABLE_RI, least);
    return moved;
}

/* "0.1234 (228)", or "   -   (  0)" for no models. */
static void print_mean(double mean, int models) {
    if (models) printf(" %7.4f (%3d)", mean, models);
    else printf(" %7s (%3d)", "-", models);
}

/* "0.1234 + 0.0567" (over + under), or "-" for no models. */
static void print_parts(double mean, double over, int models) {
    char text[40] = "-";
    if (models) snprintf(text, sizeof text, "%.4f + %.4f", over, mean - over);
    printf(" %-17s", text);
}

static void print_totals(const quality_options *o, const input_mode *modes, const split_means *s,
                         int n_modes) {
    printf("\n== mean 1-RI per input mode (development | validation | all) ==\n");
    printf("%-16s %-6s %12s %12s %12s\n", "input", "method", "development", "validation", "all");
    for (int m = 0; m < n_modes; m++)
        for (int run = 0; run < o->runs; run++) {
            int nd = s[m].models[0], nv = s[m].models[1];
            double all = ((nd ? s[m].mean[0][run] * nd : 0) + (nv ? s[m].mean[1][run] * nv : 0)) /
                         (nd + nv ? nd + nv : 1);
            printf("%-16s %-6s ", modes[m].name, run_name(o, run));
            print_mean(s[m].mean[0][run], nd);
            print_mean(s[m].mean[1][run], nv);
            print_mean(all, nd + nv);
            printf("\n");
        }
    int partial = 0; /* seen:N and view:N score the seen faces alone, people too */
    for (int m = 0; m < n_modes; m++) partial |= modes[m].seen != SEEN_ALL;
    for (int m = 0; m < (partial ? n_modes : 1); m++) {
        printf("people among themselves (each pair of a model's human segmentations, the same "
               "metric)%s%s:", partial ? " on " : "", partial ? modes[m].name : "");
        for (int v = 0; v < 2; v++)
            if (s[m].people_models[v])
                printf(" %s %.4f (%d)", v ? "validation" : "development", s[m].people[v],
                       s[m].people_models[v]);
        printf("\n");
    }
    printf("reference (1-RI): PCL CPC 0.124 (unseen PSB models, scan-like input; issue 14)\n");
    printf("\n== 1-RI = over + under: pairs of faces split where people join them, and joined "
           "where people split them ==\n");
    printf("%-16s %-6s %-17s %-17s\n", "input", "method", "development", "validation");
    for (int m = 0; m < n_modes; m++)
        for (int run = 0; run < o->runs; run++) {
            printf("%-16s %-6s", modes[m].name, run_name(o, run));
            for (int v = 0; v < 2; v++) print_parts(s[m].mean[v][run], s[m].over[v][run], s[m].models[v]);
            printf("\n");
        }
}

/* With --seeds: each mode's mean over its draws, with the least and the
 * most of them (how far one draw of the inputs moves the figure). */
static void print_draws(const quality_options *o, const split_means *s) {
    if (o->seeds < 2) return;
    printf("\n== over %d draws of the random inputs (seeds %llu to %llu): mean (least to most) ==\n",
           o->seeds, (unsigned long long)o->seed, (unsigned long long)(o->seed + o->seeds - 1));
    printf("%-16s %-6s %-26s %-26s\n", "input", "method", "development", "validation");
    for (int m = 0; m < o->n_modes; m++) {
        if (o->modes[m].first != m) continue;
        for (int run = 0; run < o->runs; run++) {
            double sum[2] = {0, 0}, lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
            int draws = 0;
            for (int d = 0; d < o->n_modes; d++) {
                if (o->modes[d].first != m) continue;
                draws++;
                for (int v = 0; v < 2; v++) {
                    double x = s[d].mean[v][run];
                    sum[v] += x, lo[v] = fmin(lo[v], x), hi[v] = fmax(hi[v], x);
                }
            }
            if (draws < 2) continue;
            printf("%-16s %-6s", o->modes[m].name, run_name(o, run));
            for (int v = 0; v < 2; v++)
                if (s[m].models[v]) printf(" %.4f (%.4f to %.4f)  ", sum[v] / draws, lo[v], hi[v]);
                else printf(" %-26s", "-");
            printf("\n");
        }
    }
}

/* The first run's labels and 1 - RI of every mode (row i of mode m at
 * m * n_rows + i), kept with --seeds for the draws' agreement. */
typedef struct kept_draws {
    int **labels;    /* NULL where the model failed */
    double *error;
    size_t n_rows;
} kept_draws;

/* Takes mode m's labels and errors off the rows. */
static void keep_draws(kept_draws *k, int m, model_row *rows) {
    for (size_t i = 0; i < k->n_rows; i++) {
        size_t at = (size_t)m * k->n_rows + i;
        k->labels[at] = rows[i].failed ? NULL : rows[i].kept;
        if (rows[i].failed) free(rows[i].kept);
        k->error[at] = rows[i].error[0];
        rows[i].kept = NULL;
    }
}

/* The draws of base mode m for row i, in draws[]; their count, or 0 when
 * one is missing. */
static int row_draws(const quality_options *o, const kept_draws *k, int m, size_t i,
                     const int *draws[], int at_mode[]) {
    int count = 0;
    for (int d = 0; d < o->n_modes; d++) {
        if (o->modes[d].first != m) continue;
        const int *labels = k->labels[(size_t)d * k->n_rows + i];
        if (!labels) return 0;
        at_mode[count] = d;
        draws[count++] = labels;
    }
    return count;
}

/* With --seeds: per mode and split, the mean over the models of the
 * draws' disagreement (1 - RI between two draws' labels: no people's
 * labels needed), of the medoid draw's 1 - RI and of a draw's. */
static void print_agreement(const quality_options *o, const model_row *rows, const kept_draws *k) {
    if (o->seeds < 2) return;
    printf("\n== agreement of the %d draws (%s): 1 - RI between two draws' labels; 1 - RI of the "
           "medoid draw (nearest the others) and of a draw ==\n", o->seeds, run_name(o, 0));
    printf("%-16s %-38s %-38s\n", "input", "development", "validation");
    for (int m = 0; m < o->n_modes; m++) {
        if (o->modes[m].first != m) continue;
        double sum[2][3] = {{0}}; /* [validation][disagreement, medoid, draw] */
        int models[2] = {0, 0}, draws = 0;
        for (size_t i = 0; i < k->n_rows; i++) {
            const int *labels[MAX_SEEDS];
            int at_mode[MAX_SEEDS];
            int count = row_draws(o, k, m, i, labels, at_mode);
            if (count < 2) continue;
            draws = count;
            ps_draw_agreement a = ps_draws_agree(labels, count, rows[i].points);
            int v = rows[i].validation;
            double mean = 0;
            for (int d = 0; d < count; d++) mean += k->error[(size_t)at_mode[d] * k->n_rows + i];
            sum[v][0] += a.disagreement;
            sum[v][1] += k->error[(size_t)at_mode[a.medoid] * k->n_rows + i];
            sum[v][2] += mean / count;
            models[v]++;
        }
        if (draws < 2) continue;
        printf("%-16s", o->modes[m].name);
        for (int v = 0; v < 2; v++) {
            char medoid[16] = "-     "; /* two draws are equally near each other */
            if (draws > 2) snprintf(medoid, sizeof medoid, "%.4f", sum[v][1] / models[v]);
            if (models[v])
                printf(" %.4f; medoid %s, draw %.4f (%3d) ", sum[v][0] / models[v], medoid,
                       sum[v][2] / models[v], models[v]);
            else printf(" %-38s", "-");
        }
        printf("\n");
    }
}

/* The folders to read: the given ones, else psb-dev and psb-train. */
static int resolve_dirs(const quality_options *o, char dirs[][4096]) {
    int n = 0;
    if (o->n_dirs) {
        for (int d = 0; d < o->n_dirs; d++)
            if (ps_psb_find_dir(o->dirs[d], dirs[n], sizeof dirs[n])) n++;
            else printf("SKIP: PSB folder %s not found (no off/ in it)\n", o->dirs[d]);
        return n;
    }
    if (ps_psb_find_dir(NULL, dirs[n], sizeof dirs[n])) n++;
    else printf("SKIP: PSB developer set %s not found\n", dirs[n]);
    if (find_train_dir(dirs[n], sizeof dirs[n])) n++;
    else printf("SKIP: PSB training set %s not found: unpack ../shared/data/psb-train.tar.xz "
                "there (see its README) or set POINTSEG_PSB_TRAIN\n", dirs[n]);
    return n;
}

/* Makes the --out folder and any missing parents (as mkdir -p); 0, or -1
 * with a message. */
static int make_out_dir(const char *dir) {
    if (!dir) return 0;
    char path[4096];
    if (snprintf(path, sizeof path, "%s", dir) >= (int)sizeof path) {
        fprintf(stderr, "bench_quality: --out %s: path too long\n", dir);
        return -1;
    }
    for (char *p = path + 1; *p; p++) {
        if (*p != '/') continue;
        *p = '\0';
        int made = mkdir(path, 0777) == 0 || errno == EEXIST;
        *p = '/';
        if (!made) break;
    }
    if (mkdir(path, 0777) == 0 || errno == EEXIST) return 0;
    fprintf(stderr, "bench_quality: --out %s: %s\n", dir, strerror(errno));
    return -1;
}

int main(int argc, char **argv) {
    quality_options o;
    static char dirs[MAX_DIRS][4096];
    if (parse_options(argc, argv, &o) != 0 || make_out_dir(o.out_dir) != 0) return 2;
    int n_dirs = resolve_dirs(&o, dirs);
    if (n_dirs == 0) return 0;
    size_t n = 0;
    model_row *rows = collect_rows(&o, dirs, n_dirs, &n);
    setvbuf(stdout, NULL, _IOLBF, 0);
    print_params(&o, dirs, n_dirs);
    split_means means[MAX_MODES];
    int failed = 0, unstable = 0;
    kept_draws kept = {.n_rows = n};
    if (o.seeds > 1) {
        kept.labels = calloc((size_t)o.n_modes * n + 1, sizeof *kept.labels);
        kept.error = calloc((size_t)o.n_modes * n + 1, sizeof *kept.error);
        if (!kept.labels || !kept.error) return 2;
    }
    for (int m = 0; m < o.n_modes; m++) {
        double start = now_ms();
        for (size_t i = 0; i < n; i++)
            rows[i] = (model_row){.dir = rows[i].dir, .id = rows[i].id, .validation = rows[i].validation};
        run_rows(&o, &o.modes[m], rows, n);
        printf("\n== input %s: %zu models, %.0f s ==\n", o.modes[m].name, n,
               (now_ms() - start) / 1e3);
        print_model_rows(&o, rows, n);
        print_categories(&o, rows, n);
        means[m] = split_summary(&o, rows, n);
        paired_summary(rows, n, means[m].change);
        if (o.seeds > 1) keep_draws(&kept, m, rows);
        failed += means[m].failed;
        if (o.stability) unstable += print_stability(rows, n);
    }
    print_totals(&o, o.modes, means, o.n_modes);
    print_draws(&o, means);
    print_agreement(&o, rows, &kept);
    print_changes(&o, means);
    printf("models failed: %d\n", failed);
    for (size_t i = 0; kept.labels && i < (size_t)o.n_modes * n; i++) free(kept.labels[i]);
    free(kept.labels), free(kept.error);
    free(rows);
    return failed || unstable ? 1 : 0;
}
