/*
 * graph.h: the graph the phases walk, in compressed sparse row (CSR) form
 * (the kNN graph of knn_graph.h and the graphs derived from it), its
 * release and its connected components.
 */
#ifndef PS_GRAPH_H
#define PS_GRAPH_H

#include "pointseg.h"

typedef struct ps_graph {
    size_t n;            /* #P vertices */
    size_t *offsets;     /* #P+1; row p is [offsets[p], offsets[p+1]) */
    uint32_t *neighbors; /* #E (= offsets[n]) neighbour indices */
    double *weights;     /* #E edge lengths */
} ps_graph;

/* Frees g's arrays and zeroes it; g may be NULL. */
void ps_graph_free(ps_graph *g);

/* Connected components: component #P gets 0..count-1, numbered in order of
 * their lowest vertex.  Returns count. */
int ps_graph_components(const ps_graph *g, int *component);

#endif
