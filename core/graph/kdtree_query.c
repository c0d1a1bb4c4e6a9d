/*
 * kdtree_query.c: blocked, parallel queries on a shared kd-tree
 * (kdtree_query.h).
 */
#include "graph/kdtree_query.h"

#include <stdatomic.h>
#include <stdlib.h>

typedef struct worker_buffers {
    double *points;   /* block by dim */
    int *found;       /* block by neighbours */
    double *squared;  /* block by neighbours */
} worker_buffers;

typedef struct kd_job {
    const ps_kd_batch *b;
    worker_buffers *buffers; /* #threads */
    atomic_int failed;
} kd_job;

static void query_block(void *ctx, size_t item, int worker) {
    kd_job *j = ctx;
    const ps_kd_batch *b = j->b;
    worker_buffers *w = &j->buffers[worker];
    struct FLANNParameters fp = ps_kd_parameters();
    size_t first = item * b->block, rows = b->count - first < b->block ? b->count - first : b->block;
    b->gather(b->ctx, first, rows, w->points);
    if (flann_find_nearest_neighbors_index_double(b->index, w->points, (int)rows, w->found,
                                                  w->squared, b->neighbours, &fp) != 0 ||
        b->take(b->ctx, first, rows, w->found) != 0)
        atomic_store(&j->failed, 1);
}

static void buffers_free(worker_buffers *buffers, int threads) {
    for (int t = 0; buffers && t < threads; t++)
        free(buffers[t].points), free(buffers[t].found), free(buffers[t].squared);
    free(buffers);
}

static worker_buffers *buffers_new(const ps_kd_batch *b, int threads) {
    worker_buffers *buffers = calloc((size_t)threads, sizeof *buffers);
    if (!buffers) return NULL;
    size_t results = b->block * (size_t)b->neighbours;
    for (int t = 0; t < threads; t++) {
        buffers[t].points = malloc(b->block * (size_t)b->dim * sizeof *buffers[t].points);
        buffers[t].found = malloc(results * sizeof *buffers[t].found);
        buffers[t].squared = malloc(results * sizeof *buffers[t].squared);
        if (!buffers[t].points || !buffers[t].found || !buffers[t].squared) {
            buffers_free(buffers, threads);
            return NULL;
        }
    }
    return buffers;
}

ps_status ps_kd_query(const ps_kd_batch *b, int threads, const ps_progress_span *span) {
    if (b->count == 0) return PS_OK;
    threads = ps_parallel_threads(threads);
    kd_job j = {.b = b, .buffers = buffers_new(b, threads)};
    if (!j.buffers) return PS_ERR_NOMEM;
    atomic_init(&j.failed, 0);
    ps_status st = ps_parallel_for_tracked(threads, (b->count + b->block - 1) / b->block, 1,
                                           query_block, &j, span);
    if (st == PS_OK && atomic_load(&j.failed)) st = PS_ERR_INTERNAL;
    buffers_free(j.buffers, threads);
    return st;
}
