/*
 * kdtree_query.h: PRIVATE to the core's FLANN users (knn_graph.c,
 * nearest.c), not part of the public API: a batch of nearest-point queries
 * on one shared kd-tree (kdtree_params.h), in blocks handed to the workers
 * of ps_parallel_for, each worker with buffers of its own.  The caller says
 * where each block's query points come from and what to do with their
 * nearest points; the results do not depend on the thread count.
 */
#ifndef PS_KDTREE_QUERY_H
#define PS_KDTREE_QUERY_H

#include "graph/kdtree_params.h"
#include "util/parallel.h"

typedef struct ps_kd_batch {
    flann_index_t index;
    int dim;         /* coordinates per point */
    int neighbours;  /* nearest points asked per query */
    size_t count;    /* queries */
    size_t block;    /* queries per hand-out */
    /* out: #rows by dim, the points of queries [first, first + rows) */
    void (*gather)(void *ctx, size_t first, size_t rows, double *out);
    /* found: #rows by neighbours, their nearest indexed points, nearest
     * first (-1 where FLANN found none); 0, or -1 to fail the batch */
    int (*take)(void *ctx, size_t first, size_t rows, const int *found);
    void *ctx;
} ps_kd_batch;

/* Runs batch b on threads (ps_parallel_threads) workers, progress through
 * span.  PS_OK; PS_ERR_NOMEM for the buffers; PS_ERR_CANCELLED when span's
 * control cancelled (some blocks not run); PS_ERR_INTERNAL when FLANN's
 * search or a take failed.  Writes no message: the caller names what
 * failed. */
ps_status ps_kd_query(const ps_kd_batch *b, int threads, const ps_progress_span *span);

#endif
