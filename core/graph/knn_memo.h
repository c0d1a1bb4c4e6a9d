/*
 * knn_memo.h: PRIVATE to the kNN graph, not part of the public API; only
 * knn_graph.c (the build) and knn_prune.c (points removed from a built
 * graph) include it.  The public interface is knn_graph.h.
 *
 * It holds what a build keeps for a later prune (ps_knn_memo) and the
 * query step both use: FLANN's k + EXTRA nearest candidates of a row,
 * sorted by (distance to single precision, index), the k first kept.
 */
#ifndef PS_KNN_MEMO_H
#define PS_KNN_MEMO_H

#include "graph/knn_graph.h"

#include <flann/flann.h>

#define PS_KNN_EXTRA 3     /* candidates beyond k + 1, for exact tie breaks */
#define PS_KNN_GONE UINT32_MAX

struct ps_knn_memo {
    flann_index_t index;      /* over the n_first points of the first build */
    size_t n_first;
    int dim, k, m;            /* m candidates per query row (self included) */
    uint32_t *knn;            /* #P by k: each row's own k nearest, current numbering */
    unsigned char *saturated; /* #P 1 when a row's last candidate ties its k-th in
                               * single precision: a point beyond the candidates
                               * could then take a place in its k */
    uint32_t *current_of;     /* #n_first current number of each first point, or
                               * PS_KNN_GONE once removed (from the index too) */
};

/* Rows rows[0..n_rows) of the current points (#P by dim) are queried on
 * memo's index and their k nearest written to memo->knn (current
 * numbering), with memo->saturated; progress over span (may have a NULL
 * ctl).  PS_OK, or an error with err set. */
ps_status ps_knn_query_rows(ps_knn_memo *memo, const double *points, const uint32_t *rows,
                            size_t n_rows, int threads, const ps_progress_span *span,
                            ps_error *err);

/* |a - b| over dim coordinates, the weight of a graph edge. */
double ps_knn_distance(const double *a, const double *b, int dim);

#endif
