/*
 * nearest.c: nearest points of a set (nearest.h).  One kd-tree over the
 * set; the queries go in blocks, the workers of ps_parallel_for side by
 * side on the shared index, each with its own result buffers.
 */
#include "nearest.h"

#include "kdtree_params.h"
#include "parallel.h"

#include <stdatomic.h>
#include <stdlib.h>

#define BLOCK 1024 /* queries per hand-out */

struct ps_nearest_index {
    flann_index_t flann;
    int dim;
};

typedef struct job {
    flann_index_t index;
    const double *queries;
    size_t m;
    int dim;
    uint32_t *nearest;
    int **found;       /* #threads by BLOCK */
    double **squared;  /* #threads by BLOCK */
    atomic_int failed;
} job;

static void query_block(job *j, size_t b, int worker) {
    struct FLANNParameters fp = ps_kd_parameters();
    size_t first = b * BLOCK, rows = j->m - first < BLOCK ? j->m - first : BLOCK;
    double *q = (double *)j->queries + first * (size_t)j->dim;
    if (flann_find_nearest_neighbors_index_double(j->index, q, (int)rows, j->found[worker],
                                                  j->squared[worker], 1, &fp) != 0) {
        atomic_store(&j->failed, 1);
        return;
    }
    for (size_t r = 0; r < rows; r++) j->nearest[first + r] = (uint32_t)j->found[worker][r];
}

static void query_blocks(void *ctx, size_t begin, size_t end, int worker) {
    for (size_t b = begin; b < end; b++) query_block(ctx, b, worker);
}

static int scratch_alloc(job *j, int threads) {
    j->found = calloc((size_t)threads, sizeof *j->found);
    j->squared = calloc((size_t)threads, sizeof *j->squared);
    if (!j->found || !j->squared) return 0;
    for (int t = 0; t < threads; t++) {
        j->found[t] = malloc(BLOCK * sizeof *j->found[t]);
        j->squared[t] = malloc(BLOCK * sizeof *j->squared[t]);
        if (!j->found[t] || !j->squared[t]) return 0;
    }
    return 1;
}

static void scratch_free(job *j, int threads) {
    for (int t = 0; t < threads; t++) {
        if (j->found) free(j->found[t]);
        if (j->squared) free(j->squared[t]);
    }
    free(j->found), free(j->squared);
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
    if (m == 0) return PS_OK;
    job j = {.index = index->flann, .queries = queries, .m = m, .dim = index->dim,
             .nearest = nearest};
    atomic_init(&j.failed, 0);
    ps_status st = PS_OK;
    if (!scratch_alloc(&j, threads)) st = ps_fail(err, PS_ERR_NOMEM, "nearest: out of memory");
    if (st == PS_OK) {
        ps_parallel_for(threads, (m + BLOCK - 1) / BLOCK, 1, query_blocks, &j);
        if (atomic_load(&j.failed))
            st = ps_fail(err, PS_ERR_INTERNAL, "nearest: FLANN search failed");
    }
    scratch_free(&j, threads);
    return st;
}
