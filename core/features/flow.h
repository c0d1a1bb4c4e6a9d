/*
 * flow.h: gradient flow of a function on the kNN graph, and its sinks.
 *
 * Each vertex p points to its steepest-ascent neighbour q, the one with the
 * largest (f(q) - f(p)) / |p - q| among those with f(q) > f(p) (ties: lowest
 * index).  A vertex with no higher neighbour is a sink.  Following the
 * pointers leads every vertex to one sink; the vertices that reach a sink
 * form its supernode.  Descent (for minima) is the same on -f.
 * Only strictly higher neighbours count: on a plateau of equal f every
 * vertex without a strictly higher neighbour is a sink of its own.
 */
#ifndef PS_FLOW_H
#define PS_FLOW_H

#include "graph/knn_graph.h"

typedef struct ps_flow {
    int n_sinks;        /* #S */
    uint32_t *sinks;    /* #S sink vertices, increasing */
    int *sink_of;       /* #P index into sinks of each vertex's sink */
} ps_flow;

/* direction +1 ascends f (maxima), -1 descends (minima). */
ps_status ps_flow_build(const ps_graph *g, const double *f, int direction,
                        ps_flow *flow, ps_error *err);
void ps_flow_free(ps_flow *flow);

#endif
