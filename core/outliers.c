/*
 * outliers.c: stray points found by a median local outlier factor on the
 * kNN graph, and their removal from the distinct points (outliers.h).
 * O(E) for the medians (quickselect on each row), O(P) for the remapping.
 */
#include "outliers.h"

#include "sort_util.h"

#include <stdlib.h>
#include <string.h>

/* scale #U out: each point's median edge length (0 without edges). */
static void median_edges(const ps_graph *g, double *scale, double *row) {
    for (size_t p = 0; p < g->n; p++) {
        size_t n = g->offsets[p + 1] - g->offsets[p];
        memcpy(row, g->weights + g->offsets[p], n * sizeof *row);
        scale[p] = n ? ps_select_kth(row, n, n / 2) : 0;
    }
}

/* outlier #U out: 1 when the point's scale is over PS_OUTLIER_RATIO times
 * the median of its neighbours' scales. */
static void mark_outliers(const ps_graph *g, const double *scale, double *row,
                          unsigned char *outlier) {
    for (size_t p = 0; p < g->n; p++) {
        size_t n = 0;
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
            row[n++] = scale[g->neighbors[e]];
        outlier[p] = n > 0 && scale[p] > PS_OUTLIER_RATIO * ps_select_kth(row, n, n / 2);
    }
}

/* keep_for[p]: p itself, or for an outlier its nearest neighbour that is
 * no outlier (ties: the lowest index); an outlier with none stays. */
static size_t nearest_kept(const ps_graph *g, const unsigned char *outlier, uint32_t *keep_for) {
    size_t count = 0;
    for (size_t p = 0; p < g->n; p++) {
        keep_for[p] = (uint32_t)p;
        if (!outlier[p]) continue;
        double best = 0;
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            uint32_t q = g->neighbors[e];
            if (outlier[q] || (keep_for[p] != p && g->weights[e] >= best)) continue;
            keep_for[p] = q, best = g->weights[e];
        }
        count += keep_for[p] != p;
    }
    return count;
}

static size_t max_degree(const ps_graph *g) {
    size_t most = 0;
    for (size_t p = 0; p < g->n; p++)
        if (g->offsets[p + 1] - g->offsets[p] > most) most = g->offsets[p + 1] - g->offsets[p];
    return most;
}

ps_status ps_outliers_find(const ps_graph *g, uint32_t *keep_for, size_t *count,
                           ps_error *err) {
    double *scale = malloc((g->n ? g->n : 1) * sizeof *scale);
    double *row = malloc((max_degree(g) + 1) * sizeof *row);
    unsigned char *outlier = malloc(g->n ? g->n : 1);
    ps_status st = scale && row && outlier ? PS_OK
                                           : ps_fail(err, PS_ERR_NOMEM, "outliers: out of memory");
    if (st == PS_OK) {
        median_edges(g, scale, row);
        mark_outliers(g, scale, row, outlier);
        *count = nearest_kept(g, outlier, keep_for);
    }
    free(scale), free(row), free(outlier);
    return st;
}

ps_status ps_outliers_drop(ps_dedup *d, size_t n_points, const uint32_t *keep_for,
                           ps_error *err) {
    size_t *new_index = malloc((d->n_unique ? d->n_unique : 1) * sizeof *new_index);
    if (!new_index) return ps_fail(err, PS_ERR_NOMEM, "outliers: out of memory");
    size_t kept = 0;
    for (size_t u = 0; u < d->n_unique; u++)
        if (keep_for[u] == u) new_index[u] = kept, d->first[kept++] = d->first[u];
    for (size_t u = 0; u < d->n_unique; u++) new_index[u] = new_index[keep_for[u]];
    for (size_t i = 0; i < n_points; i++) d->unique_of[i] = new_index[d->unique_of[i]];
    d->n_unique = kept;
    free(new_index);
    return PS_OK;
}
