/*
 * bench_quality.c: segmentation quality on the PSB developer set.  Segments
 * the vertices of every off/ID.off with ps_segment, turns vertex labels
 * into face labels by majority, and prints the Rand Index error against the
 * model's human segmentations: one row per model, the category means, the
 * overall means and the published references.  Unless --single, every
 * model is segmented twice, with the given parameters and with the paper's
 * method (method=paper), printed side by side.  --noise F first moves every
 * vertex by Gaussian noise of F mean mesh edge lengths per axis (the same
 * noise for both methods, seeded by the model id): how the segmentation
 * holds up on noisy scans.  --strays F adds F times the vertex count of
 * stray points, uniform in the bounding box grown by 10% (seeded by the
 * model id), segments them with the vertices and scores the vertices only:
 * how it holds up against a scanner's outliers.  See tests/bench/README.md.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "params_table.h"
#include "pointseg.h"
#include "psb_data.h"

#define N_CATEGORIES 20
#define MAX_RUNS 2 /* the given parameters, then method=paper */

typedef struct quality_options {
    const char *dir_arg;       /* PSB directory given on the command line */
    const char *ids_arg;       /* --ids list, or NULL for every model */
    const char *out_dir;       /* --out: write ID.lab predictions here */
    int baseline_none;         /* --baseline none: every vertex labelled 0 */
    int runs;                  /* 1 with --single (or a baseline), else 2 */
    double noise;              /* --noise: sigma in mean mesh edge lengths */
    double strays;             /* --strays: stray points per vertex */
    ps_request_params params;  /* defaults + --param + --threads */
} quality_options;

typedef struct model_row {
    int id;
    size_t points;
    double human_segments;
    int segments[MAX_RUNS];
    double error[MAX_RUNS];
    double ms[MAX_RUNS];
} model_row;

typedef struct category_sums {
    double error[MAX_RUNS][N_CATEGORIES];
    int models[N_CATEGORIES];
} category_sums;

static const char usage[] =
    "usage: bench_quality [PSB_DIR] [--ids 1,2,21] [--param name=value]...\n"
    "                     [--threads N] [--out DIR] [--baseline none] [--single]\n"
    "                     [--noise F] [--strays F]\n"
    "Prints the given parameters (default: method auto) next to method=paper;\n"
    "--single runs the given parameters only; --noise F moves the vertices by\n"
    "Gaussian noise of F mean edge lengths first; --strays F adds F stray points\n"
    "per vertex in the grown bounding box (the vertices alone are scored).\n"
    "PSB_DIR defaults to $POINTSEG_SHARED/psb-dev, else ../shared/data/psb-dev.\n";

static double now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

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

/* The value of a flag that needs one, or NULL with a message. */
static const char *flag_value(int argc, char **argv, int *i) {
    if (*i + 1 >= argc) {
        fprintf(stderr, "bench_quality: %s needs a value\n%s", argv[*i], usage);
        return NULL;
    }
    return argv[++*i];
}

static int parse_options(int argc, char **argv, quality_options *o) {
    memset(o, 0, sizeof *o);
    ps_request_params_default(&o->params);
    o->runs = MAX_RUNS;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) { fputs(usage, stdout); exit(0); }
        if (!strcmp(a, "--single")) { o->runs = 1; continue; }
        if (a[0] != '-') { o->dir_arg = a; continue; }
        if (!(v = flag_value(argc, argv, &i))) return -1;
        if (!strcmp(a, "--ids")) o->ids_arg = v;
        else if (!strcmp(a, "--out")) o->out_dir = v;
        else if (!strcmp(a, "--param")) { if (apply_assignment(&o->params, v)) return -1; }
        else if (!strcmp(a, "--threads")) { if (set_param(&o->params, "threads", v)) return -1; }
        else if (!strcmp(a, "--baseline") && !strcmp(v, "none")) o->baseline_none = 1, o->runs = 1;
        else if (!strcmp(a, "--noise") && (o->noise = atof(v)) >= 0 && o->noise <= 100) continue;
        else if (!strcmp(a, "--strays") && (o->strays = atof(v)) >= 0 && o->strays <= 1) continue;
        else { fprintf(stderr, "bench_quality: unknown option %s %s\n%s", a, v, usage); return -1; }
    }
    return 0;
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

static int write_labels(const char *dir, int id, const int *labels, size_t n) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%d.lab", dir, id);
    FILE *f = fopen(path, "w");
    if (!f) { perror(path); return -1; }
    for (size_t i = 0; i < n; i++) fprintf(f, "%d\n", labels[i]);
    if (fclose(f) != 0) { perror(path); return -1; }
    return 0;
}

/* The parameters of run `run`: the given ones, or the paper's method. */
static ps_params run_params(const quality_options *o, int run) {
    ps_params p = o->params.core;
    if (run == 1) p.method = PS_METHOD_PAPER;
    return p;
}

/* Vertex labels of the mesh (malloc'ed #P) by ps_segment, or all 0 for the
 * "none" baseline; fills the row's segment count and time.  strays, if not
 * NULL, is the input to segment instead: the vertices first, then stray
 * points.  NULL on failure. */
static int *label_vertices(const ps_pointset *mesh, const ps_input *strays,
                           const quality_options *o, int run, model_row *row) {
    double start = now_ms();
    if (o->baseline_none) {
        row->segments[run] = 1;
        int *zeros = calloc(mesh->n, sizeof *zeros);
        row->ms[run] = now_ms() - start;
        return zeros;
    }
    ps_input in = {mesh->points, mesh->n, mesh->dim, mesh->normals};
    if (strays) in = *strays;
    ps_params params = run_params(o, run);
    ps_result *r = NULL;
    ps_error err;
    if (ps_segment(&in, &params, NULL, &r, &err) != PS_OK) {
        fprintf(stderr, "model %d: %s\n", row->id, err.message);
        return NULL;
    }
    row->ms[run] = now_ms() - start;
    row->segments[run] = r->n_segments;
    int *labels = malloc(mesh->n * sizeof *labels);
    if (labels) memcpy(labels, r->labels, mesh->n * sizeof *labels);
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
    *state ^= *state << 13, *state ^= *state >> 7, *state ^= *state << 17;
    return ((double)(*state >> 11) + 0.5) / 9007199254740992.0;
}

/* Gaussian noise of sigma = noise x mean edge on every coordinate
 * (Box-Muller), the same for a given model id on every run. */
static void add_noise(ps_pointset *mesh, double noise, int id) {
    double sigma = noise * mean_edge(mesh);
    uint64_t state = 0x9E3779B97F4A7C15ull ^ (uint64_t)id;
    for (size_t i = 0; i < 3 * mesh->n; i++)
        mesh->points[i] += sigma * sqrt(-2 * log(uniform(&state))) *
                           cos(2 * 3.14159265358979323846 * uniform(&state));
}

/* The mesh's vertices followed by fraction x #P stray points, uniform in
 * the bounding box grown by 10% on every side (the same for a given model
 * id on every run); normals, when the mesh has them, +z for the strays.
 * 0 or -1 (out of memory). */
static int with_strays(const ps_pointset *mesh, double fraction, int id, ps_input *in) {
    size_t extra = (size_t)ceil(fraction * (double)mesh->n), n = mesh->n + extra;
    double *points = malloc(3 * n * sizeof *points);
    double *normals = mesh->normals ? calloc(3 * n, sizeof *normals) : NULL;
    if (!points || (mesh->normals && !normals)) return free(points), free(normals), -1;
    memcpy(points, mesh->points, 3 * mesh->n * sizeof *points);
    if (normals) memcpy(normals, mesh->normals, 3 * mesh->n * sizeof *normals);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < 3 * mesh->n; i++)
        lo[i % 3] = fmin(lo[i % 3], points[i]), hi[i % 3] = fmax(hi[i % 3], points[i]);
    uint64_t state = 0x2545F4914F6CDD1Dull ^ (uint64_t)id;
    for (size_t i = 3 * mesh->n; i < 3 * n; i++) {
        double grow = 0.1 * (hi[i % 3] - lo[i % 3]);
        points[i] = lo[i % 3] - grow + (hi[i % 3] - lo[i % 3] + 2 * grow) * uniform(&state);
        if (normals && i % 3 == 2) normals[i] = 1;
    }
    *in = (ps_input){points, n, 3, normals};
    return 0;
}

/* Segments and scores one model; 0 or -1. */
static int run_model(const char *dir, const quality_options *o, model_row *row) {
    ps_pointset mesh;
    ps_psb_humans humans;
    if (ps_psb_load_mesh(dir, row->id, &mesh) != 0) return -1;
    if (o->noise > 0) add_noise(&mesh, o->noise, row->id);
    ps_input strays = {0};
    int rc = -1;
    row->points = mesh.n;
    if (o->strays > 0 && with_strays(&mesh, o->strays, row->id, &strays) != 0) {
        ps_pointset_free(&mesh);
        return -1;
    }
    if (ps_psb_load_humans(dir, row->id, mesh.n_faces, &humans) == 0) {
        row->human_segments = ps_psb_mean_segments(&humans);
        rc = 0;
        for (int run = 0; run < o->runs && rc == 0; run++) {
            int *labels = label_vertices(&mesh, o->strays > 0 ? &strays : NULL, o, run, row);
            int write = o->out_dir && run == 0;
            rc = labels && (!write || write_labels(o->out_dir, row->id, labels, mesh.n) == 0)
                     ? 0
                     : -1;
            if (rc == 0) row->error[run] = ps_psb_score(&mesh, labels, &humans);
            free(labels);
        }
        ps_psb_humans_free(&humans);
    }
    free((double *)strays.points), free((double *)strays.normals);
    ps_pointset_free(&mesh);
    return rc;
}

static void print_params(const char *dir, const quality_options *o) {
    const ps_params *p = &o->params.core;
    printf("PSB developer set: %s\n", dir);
    if (o->baseline_none) {
        printf("labelling: baseline none (every vertex the same label)\n\n");
        return;
    }
    printf("params: method=%s k=%d centrality=%s samples=%d persistence=%g ncut_threshold=%g "
           "feature_threshold=%g minima=%d f2=%d threads=%d\n",
           ps_method_name(p->method), p->k, ps_centrality_name(p->centrality), p->samples,
           p->persistence, p->ncut_threshold, p->feature_threshold, p->use_minima, p->use_f2,
           p->threads);
    if (o->noise > 0) printf("noise: sigma %g mean edge lengths per coordinate\n", o->noise);
    if (o->strays > 0) printf("strays: %g stray points per vertex (vertices scored)\n", o->strays);
    if (o->runs > 1) printf("compared with: the same, method=paper\n");
    printf("\n");
}

static const char *run_name(const quality_options *o, int run) {
    if (o->baseline_none) return "none";
    return ps_method_name(run_params(o, run).method);
}

static void print_header(const quality_options *o) {
    printf("%5s %-10s %7s %10s", "id", "category", "points", "human segs");
    for (int run = 0; run < o->runs; run++)
        printf(" | %-6s %5s %7s %9s", run_name(o, run), "segs", "1-RI", "time ms");
    printf("\n");
}

static void print_row(const quality_options *o, const model_row *row) {
    printf("%5d %-10s %7zu %10.1f", row->id, ps_psb_category(row->id), row->points,
           row->human_segments);
    for (int run = 0; run < o->runs; run++)
        printf(" | %-6s %5d %7.4f %9.1f", "", row->segments[run], row->error[run], row->ms[run]);
    printf("\n");
}

static void print_summary(const quality_options *o, const category_sums *c,
                          const double *total, int models, int failed) {
    double category_total[MAX_RUNS] = {0};
    int categories = 0;
    printf("\n%-10s %6s", "category", "models");
    for (int run = 0; run < o->runs; run++) printf(" %7s", run_name(o, run));
    printf("\n");
    for (int k = 0; k < N_CATEGORIES; k++) {
        if (!c->models[k]) continue;
        printf("%-10s %6d", ps_psb_category(20 * k + 1), c->models[k]);
        for (int run = 0; run < o->runs; run++) {
            double mean = c->error[run][k] / c->models[k];
            printf(" %7.4f", mean);
            category_total[run] += mean;
        }
        printf("\n");
        categories++;
    }
    printf("\nmodels scored:          %d (failed: %d)\n", models, failed);
    for (int run = 0; run < o->runs; run++) {
        printf("%-6s mean over models:       %.4f\n", run_name(o, run),
               models ? total[run] / models : 0.0);
        printf("%-6s mean of category means: %.4f\n", run_name(o, run),
               categories ? category_total[run] / categories : 0.0);
    }
    printf("references (1-RI, mean over the 38 dev models): human 0.092, "
           "k-means 0.268, none 0.6645\n");
}

int main(int argc, char **argv) {
    quality_options o;
    char dir[4096];
    if (parse_options(argc, argv, &o) != 0) return 2;
    if (!ps_psb_find_dir(o.dir_arg, dir, sizeof dir)) {
        printf("SKIP: PSB developer set %s not found\n", dir);
        return 0;
    }
    size_t n_ids = 0;
    int *ids = ps_psb_model_ids(dir, &n_ids);
    category_sums cats;
    memset(&cats, 0, sizeof cats);
    double total[MAX_RUNS] = {0};
    int models = 0, failed = 0;
    setvbuf(stdout, NULL, _IOLBF, 0);
    print_params(dir, &o);
    print_header(&o);
    for (size_t m = 0; m < n_ids; m++) {
        model_row row = {.id = ids[m]};
        if (!id_selected(o.ids_arg, row.id)) continue;
        if (run_model(dir, &o, &row) != 0) {
            printf("%5d %-10s FAILED\n", row.id, ps_psb_category(row.id));
            failed++;
            continue;
        }
        print_row(&o, &row);
        int k = category_index(row.id);
        for (int run = 0; run < o.runs; run++) {
            if (k >= 0) cats.error[run][k] += row.error[run];
            total[run] += row.error[run];
        }
        if (k >= 0) cats.models[k]++;
        models++;
    }
    free(ids);
    print_summary(&o, &cats, total, models, failed);
    return failed ? 1 : 0;
}
