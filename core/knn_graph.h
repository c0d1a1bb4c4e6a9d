/*
 * knn_graph.h: the symmetrized k-nearest-neighbour graph of a point set, in
 * compressed sparse row (CSR) form, built with FLANN's kd-tree.
 *
 * p ~ q is an edge when q is among p's k nearest neighbours or p among q's
 * (nearest by exact double distance, ties to the lower index);
 * its weight is the Euclidean distance |p - q| (> 0: the caller removes
 * duplicate points first, see dedup.h).  Each row is sorted by neighbour
 * index, so the graph is the same for any thread count.
 */
#ifndef PS_KNN_GRAPH_H
#define PS_KNN_GRAPH_H

#include "parallel.h"
#include "pointseg.h"

typedef struct ps_graph {
    size_t n;            /* #P vertices */
    size_t *offsets;     /* #P+1; row p is [offsets[p], offsets[p+1]) */
    uint32_t *neighbors; /* #E (= offsets[n]) neighbour indices */
    double *weights;     /* #E edge lengths */
} ps_graph;

/* points: #P by dim, distinct; 1 <= k < n.  On success g owns its arrays. */
ps_status ps_knn_graph_build(const double *points, size_t n, int dim, int k,
                             int threads, ps_graph *g, ps_error *err);

/* The same, reporting progress from span->lo to span->hi as the queries
 * go (span->ctl may be NULL) and stopping with PS_ERR_CANCELLED when its
 * cancel flag is raised. */
ps_status ps_knn_graph_build_tracked(const double *points, size_t n, int dim, int k, int threads,
                                     const ps_progress_span *span, ps_graph *g, ps_error *err);
void ps_graph_free(ps_graph *g);

/* Connected components: component #P gets 0..count-1, numbered in order of
 * their lowest vertex.  Returns count. */
int ps_graph_components(const ps_graph *g, int *component);

#endif
