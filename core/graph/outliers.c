/*
 * outliers.c: stray points found by a median local outlier factor on the
 * kNN graph, and their removal from the distinct points (outliers.h).
 * O(E) for the medians (ranks counted in a short row, quickselect for a
 * hub's long one; points in parallel) and for the test against the
 * neighbours' median (a count, no selection), O(P) for the remapping.
 */
#include "graph/outliers.h"

#include "util/parallel.h"
#include "util/sort_util.h"

#include <stdlib.h>
#include <string.h>

/* The three passes, each over the points in parallel; a worker's row
 * scratch holds one row's values (#max degree). */
typedef struct outlier_job {
    const ps_graph *g;
    double **row;           /* #threads */
    double *scale;          /* #U each point's median edge length */
    unsigned char *outlier; /* #U */
    uint32_t *keep_for;     /* #U out */
} outlier_job;

/* Rows up to this long take their median by counting ranks. */
#define SHORT_ROW 32

/* The median (the element of rank n / 2) of the n > 0 values x: in a
 * short row a value with exactly n / 2 values below it, or, failing that
 * (ties), one with at most n / 2 below it and more at or below it; else by
 * quickselect through row (#n scratch). */
static double median_of(const double *x, size_t n, double *row) {
    size_t k = n / 2;
    for (size_t i = 0; n <= SHORT_ROW && i < n; i++) {
        size_t below = 0;
        for (size_t j = 0; j < n; j++) below += x[j] < x[i];
        if (below == k) return x[i];
    }
    for (size_t i = 0; n <= SHORT_ROW && i < n; i++) {
        size_t below = 0, at_most = 0;
        for (size_t j = 0; j < n; j++) below += x[j] < x[i], at_most += x[j] <= x[i];
        if (below <= k && k < at_most) return x[i];
    }
    memcpy(row, x, n * sizeof *row);
    return ps_select_kth(row, n, k);
}

/* scale: each point's median edge length (0 without edges). */
static void median_edges(void *ctx, size_t begin, size_t end, int worker) {
    const outlier_job *j = ctx;
    const ps_graph *g = j->g;
    for (size_t p = begin; p < end; p++) {
        size_t n = g->offsets[p + 1] - g->offsets[p];
        j->scale[p] = n ? median_of(g->weights + g->offsets[p], n, j->row[worker]) : 0;
    }
}

/* outlier: 1 when the point's scale s is over PS_OUTLIER_RATIO times the
 * median m of its n neighbours' scales.  As x -> PS_OUTLIER_RATIO x rounds
 * monotonically, s > PS_OUTLIER_RATIO m exactly when more than n / 2 of
 * the neighbours' scales v have PS_OUTLIER_RATIO v < s: a count, with no
 * selection. */
static void mark_outliers(void *ctx, size_t begin, size_t end, int worker) {
    (void)worker;
    const outlier_job *j = ctx;
    const ps_graph *g = j->g;
    for (size_t p = begin; p < end; p++) {
        size_t n = g->offsets[p + 1] - g->offsets[p], below = 0;
        double s = j->scale[p];
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
            below += PS_OUTLIER_RATIO * j->scale[g->neighbors[e]] < s;
        j->outlier[p] = below > n / 2;
    }
}

/* keep_for[p]: p itself, or for an outlier its nearest neighbour that is
 * no outlier (ties: the lowest index); an outlier with none stays. */
static void nearest_kept(void *ctx, size_t begin, size_t end, int worker) {
    (void)worker;
    const outlier_job *j = ctx;
    const ps_graph *g = j->g;
    for (size_t p = begin; p < end; p++) {
        j->keep_for[p] = (uint32_t)p;
        if (!j->outlier[p]) continue;
        double best = 0;
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            uint32_t q = g->neighbors[e];
            if (j->outlier[q] || (j->keep_for[p] != p && g->weights[e] >= best)) continue;
            j->keep_for[p] = q, best = g->weights[e];
        }
    }
}

static size_t max_degree(const ps_graph *g) {
    size_t most = 0;
    for (size_t p = 0; p < g->n; p++)
        if (g->offsets[p + 1] - g->offsets[p] > most) most = g->offsets[p + 1] - g->offsets[p];
    return most;
}

static int rows_alloc(outlier_job *j, int threads, size_t width) {
    j->row = calloc((size_t)threads, sizeof *j->row);
    for (int t = 0; j->row && t < threads; t++)
        if (!(j->row[t] = malloc(width * sizeof *j->row[t]))) return 0;
    return j->row != NULL;
}

static void rows_free(outlier_job *j, int threads) {
    for (int t = 0; j->row && t < threads; t++) free(j->row[t]);
    free(j->row);
}

ps_status ps_outliers_find(const ps_graph *g, int threads, uint32_t *keep_for, size_t *count,
                           ps_error *err) {
    threads = ps_parallel_threads(threads);
    outlier_job j = {g, NULL, malloc((g->n ? g->n : 1) * sizeof *j.scale), malloc(g->n ? g->n : 1),
                     keep_for};
    ps_status st = j.scale && j.outlier && rows_alloc(&j, threads, max_degree(g) + 1)
                       ? PS_OK
                       : ps_fail(err, PS_ERR_NOMEM, "outliers: out of memory");
    if (st == PS_OK) {
        ps_parallel_for(threads, g->n, 0, median_edges, &j);
        ps_parallel_for(threads, g->n, 0, mark_outliers, &j);
        ps_parallel_for(threads, g->n, 0, nearest_kept, &j);
        *count = 0;
        for (size_t p = 0; p < g->n; p++) *count += keep_for[p] != p;
    }
    rows_free(&j, threads);
    free(j.scale), free(j.outlier);
    return st;
}

ps_status ps_outliers_drop(ps_dedup *d, size_t n_points, const uint32_t *keep_for,
                           ps_error *err) {
    uint32_t *new_index = malloc((d->n_unique ? d->n_unique : 1) * sizeof *new_index);
    if (!new_index) return ps_fail(err, PS_ERR_NOMEM, "outliers: out of memory");
    size_t kept = 0;
    for (size_t u = 0; u < d->n_unique; u++)
        if (keep_for[u] == u) new_index[u] = (uint32_t)kept, d->first[kept++] = d->first[u];
    for (size_t u = 0; u < d->n_unique; u++) new_index[u] = new_index[keep_for[u]];
    for (size_t i = 0; i < n_points; i++) d->unique_of[i] = new_index[d->unique_of[i]];
    d->n_unique = kept;
    free(new_index);
    return PS_OK;
}
