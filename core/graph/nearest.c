/*
 * nearest.c: nearest points of a set (nearest.h).  One kd-tree over the
 * set, queried in blocks on all workers (kdtree_query.h).
 */
#include "graph/nearest.h"

#include "graph/kdtree_query.h"

#include <stdlib.h>
#include <string.h>

#define BLOCK 1024 /* queries per hand-out */

struct ps_nearest_index {
    flann_index_t flann;
    int dim;
};

/* The queries of one call and where their nearest points go. */
typedef struct job {
    const double *queries; /* #Q by dim */
    int dim;
    uint32_t *nearest;     /* #Q */
} job;

static void gather_queries(void *ctx, size_t first, size_t rows, double *out) {
    const job *j = ctx;
    memcpy(out, j->queries + first * (size_t)j->dim, rows * (size_t)j->dim * sizeof *out);
}

static int take_nearest(void *ctx, size_t first, size_t rows, const int *found) {
    const job *j = ctx;
    for (size_t r = 0; r < rows; r++) {
        if (found[r] < 0) return -1;
        j->nearest[first + r] = (uint32_t)found[r];
    }
    return 0;
}

ps_nearest_index *ps_nearest_build(const double *points, size_t n, int dim) {
    struct FLANNParameters fp = ps_kd_parameters();
    float speedup = 0.0f;
    ps_nearest_index *index = malloc(sizeof *index);
    if (!index) return NULL;
    index->dim = dim;
    index->flann = flann_build_index_double((double *)points, (int)n, dim, &speedup, &fp);
    if (!index->flann) free(index), index = NULL;
    return index;
}

void ps_nearest_free(ps_nearest_index *index) {
    if (!index) return;
    struct FLANNParameters fp = ps_kd_parameters();
    flann_free_index_double(index->flann, &fp);
    free(index);
}

ps_status ps_nearest_query(const ps_nearest_index *index, const double *queries, size_t m,
                           int threads, uint32_t *nearest, ps_error *err) {
    job j = {.queries = queries, .dim = index->dim, .nearest = nearest};
    ps_kd_batch batch = {.index = index->flann, .dim = index->dim, .neighbours = 1, .count = m,
                         .block = BLOCK, .gather = gather_queries, .take = take_nearest,
                         .ctx = &j};
    ps_progress_span untracked = {NULL, PS_PHASE_REFINE, 0.0, 0.0};
    ps_status st = ps_kd_query(&batch, threads, &untracked);
    if (st == PS_ERR_NOMEM) return ps_fail(err, st, "nearest: out of memory");
    if (st != PS_OK) return ps_fail(err, PS_ERR_INTERNAL, "nearest: FLANN search failed");
    return PS_OK;
}
