/*
 * knn_graph.h: the symmetrized k-nearest-neighbour graph of a point set, in
 * compressed sparse row (CSR) form, built with FLANN's kd-tree.
 *
 * p ~ q is an edge when q is among p's k nearest neighbours or p among q's
 * (nearest by exact double distance, ties to the lower index);
 * its weight is the Euclidean distance |p - q| (> 0: the caller removes
 * duplicate points first, see dedup.h).  Each row is sorted by neighbour
 * index, so the graph is the same for any thread count.  The graph type is
 * graph.h's.
 */
#ifndef PS_KNN_GRAPH_H
#define PS_KNN_GRAPH_H

#include "graph/graph.h"
#include "pointseg.h"
#include "util/parallel.h"

/* points: #P by dim, distinct; 1 <= k < n.  On success g owns its arrays. */
ps_status ps_knn_graph_build(const double *points, size_t n, int dim, int k,
                             int threads, ps_graph *g, ps_error *err);

typedef struct ps_knn_graph_input {
    const double *points;          /* #P by dim, distinct */
    size_t n;                      /* #P */
    int dim;
    int k;                         /* 1 <= k < n */
    int threads;                   /* ps_parallel_threads; the graph is the same for any count */
    const ps_progress_span *span;  /* progress from span->lo to span->hi as the queries go
                                      (span->ctl may be NULL); not NULL */
} ps_knn_graph_input;

/* ps_knn_graph_build on in, reporting progress over in->span and stopping
 * with PS_ERR_CANCELLED when its cancel flag is raised.  On success g owns
 * its arrays. */
ps_status ps_knn_graph_build_tracked(const ps_knn_graph_input *in, ps_graph *g, ps_error *err);

/* What ps_knn_graph_prune needs of a build: its search index and each
 * row's own k nearest (knn_memo.h, private). */
typedef struct ps_knn_memo ps_knn_memo;

/* ps_knn_graph_build_tracked that also keeps *memo (freed with
 * ps_knn_memo_free) for ps_knn_graph_prune, when memo is not NULL. */
ps_status ps_knn_graph_build_memo(const ps_knn_graph_input *in, ps_graph *g, ps_knn_memo **memo,
                                  ps_error *err);
void ps_knn_memo_free(ps_knn_memo *memo);

/* Removes from g (and memo, from the build of g or an earlier prune) the
 * points p with keep_for[p] != p; the others keep their order, renumbered
 * 0..kept-1.  points: g's #P points, as they were before the removal.  g
 * becomes the graph ps_knn_graph_build gives on the kept points, edge for
 * edge (as exactly as the build itself: for tie sets that fit its
 * candidates, knn_graph.c): only the rows that lost one of their k nearest (or whose k-th
 * nearest ties with what lies beyond) are searched again, on memo's index
 * with the removed points taken out of it.  *pruned out: 0 when it could
 * not (memo NULL, or fewer than k + 4 points kept, where the candidates
 * per row change): g is then unchanged and the caller builds anew. */
ps_status ps_knn_graph_prune(ps_graph *g, ps_knn_memo *memo, const double *points,
                             const uint32_t *keep_for, int threads, const ps_progress_span *span,
                             int *pruned, ps_error *err);


#endif
