/*
 * bench_quality.c: segmentation quality on the PSB developer set.  Segments
 * the vertices of every off/ID.off with ps_segment, turns vertex labels
 * into face labels by majority, and prints the Rand Index error against the
 * model's human segmentations: one row per model, the category means, the
 * overall means and the published references.  See tests/bench/README.md.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "params_table.h"
#include "pointseg.h"
#include "psb_data.h"

#define N_CATEGORIES 20

typedef struct quality_options {
    const char *dir_arg;       /* PSB directory given on the command line */
    const char *ids_arg;       /* --ids list, or NULL for every model */
    const char *out_dir;       /* --out: write ID.lab predictions here */
    int baseline_none;         /* --baseline none: every vertex labelled 0 */
    ps_request_params params;  /* defaults + --param + --threads */
} quality_options;

typedef struct model_row {
    int id;
    size_t points;
    int segments;
    double human_segments;
    double error;
    double ms;
} model_row;

typedef struct category_sums {
    double error[N_CATEGORIES];
    int models[N_CATEGORIES];
} category_sums;

static const char usage[] =
    "usage: bench_quality [PSB_DIR] [--ids 1,2,21] [--param name=value]...\n"
    "                     [--threads N] [--out DIR] [--baseline none]\n"
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
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) { fputs(usage, stdout); exit(0); }
        if (a[0] != '-') { o->dir_arg = a; continue; }
        if (!(v = flag_value(argc, argv, &i))) return -1;
        if (!strcmp(a, "--ids")) o->ids_arg = v;
        else if (!strcmp(a, "--out")) o->out_dir = v;
        else if (!strcmp(a, "--param")) { if (apply_assignment(&o->params, v)) return -1; }
        else if (!strcmp(a, "--threads")) { if (set_param(&o->params, "threads", v)) return -1; }
        else if (!strcmp(a, "--baseline") && !strcmp(v, "none")) o->baseline_none = 1;
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

/* Vertex labels of the mesh (malloc'ed #P) by ps_segment, or all 0 for the
 * "none" baseline; fills the row's segment count and time.  NULL on failure. */
static int *label_vertices(const ps_pointset *mesh, const quality_options *o,
                           model_row *row) {
    double start = now_ms();
    if (o->baseline_none) {
        row->segments = 1;
        int *zeros = calloc(mesh->n, sizeof *zeros);
        row->ms = now_ms() - start;
        return zeros;
    }
    ps_input in = {mesh->points, mesh->n, mesh->dim, mesh->normals};
    ps_result *r = NULL;
    ps_error err;
    if (ps_segment(&in, &o->params.core, NULL, &r, &err) != PS_OK) {
        fprintf(stderr, "model %d: %s\n", row->id, err.message);
        return NULL;
    }
    row->ms = now_ms() - start;
    row->segments = r->n_segments;
    int *labels = malloc(mesh->n * sizeof *labels);
    if (labels) memcpy(labels, r->labels, mesh->n * sizeof *labels);
    ps_result_free(r);
    return labels;
}

/* Segments and scores one model; 0 or -1. */
static int run_model(const char *dir, const quality_options *o, model_row *row) {
    ps_pointset mesh;
    ps_psb_humans humans;
    if (ps_psb_load_mesh(dir, row->id, &mesh) != 0) return -1;
    int rc = -1;
    row->points = mesh.n;
    if (ps_psb_load_humans(dir, row->id, mesh.n_faces, &humans) == 0) {
        int *labels = label_vertices(&mesh, o, row);
        if (labels && (!o->out_dir || write_labels(o->out_dir, row->id, labels, mesh.n) == 0)) {
            row->human_segments = ps_psb_mean_segments(&humans);
            row->error = ps_psb_score(&mesh, labels, &humans);
            rc = 0;
        }
        free(labels);
        ps_psb_humans_free(&humans);
    }
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
    printf("params: k=%d centrality=%s samples=%d ncut_threshold=%g "
           "feature_threshold=%g minima=%d f2=%d threads=%d\n\n",
           p->k, ps_centrality_name(p->centrality), p->samples, p->ncut_threshold,
           p->feature_threshold, p->use_minima, p->use_f2, p->threads);
}

static void print_summary(const category_sums *c, double total, int models, int failed) {
    double category_total = 0;
    int categories = 0;
    printf("\n%-10s %6s %7s\n", "category", "models", "1-RI");
    for (int k = 0; k < N_CATEGORIES; k++) {
        if (!c->models[k]) continue;
        double mean = c->error[k] / c->models[k];
        printf("%-10s %6d %7.4f\n", ps_psb_category(20 * k + 1), c->models[k], mean);
        category_total += mean;
        categories++;
    }
    printf("\nmodels scored:          %d (failed: %d)\n", models, failed);
    printf("mean over models:       %.4f\n", models ? total / models : 0.0);
    printf("mean of category means: %.4f\n", categories ? category_total / categories : 0.0);
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
    double total = 0;
    int models = 0, failed = 0;
    setvbuf(stdout, NULL, _IOLBF, 0);
    print_params(dir, &o);
    printf("%5s %-10s %7s %6s %10s %7s %10s\n", "id", "category", "points", "segs",
           "human segs", "1-RI", "time ms");
    for (size_t m = 0; m < n_ids; m++) {
        model_row row = {.id = ids[m]};
        if (!id_selected(o.ids_arg, row.id)) continue;
        if (run_model(dir, &o, &row) != 0) {
            printf("%5d %-10s FAILED\n", row.id, ps_psb_category(row.id));
            failed++;
            continue;
        }
        printf("%5d %-10s %7zu %6d %10.1f %7.4f %10.1f\n", row.id, ps_psb_category(row.id),
               row.points, row.segments, row.human_segments, row.error, row.ms);
        int k = category_index(row.id);
        if (k >= 0) {
            cats.error[k] += row.error;
            cats.models[k]++;
        }
        total += row.error;
        models++;
    }
    free(ids);
    print_summary(&cats, total, models, failed);
    return failed ? 1 : 0;
}
