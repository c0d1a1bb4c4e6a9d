/*
 * hand_graph.h: small weighted graphs (ps_graph, CSR) written out by hand
 * for the unit tests, in fixed arrays so a test needs no allocation: from a
 * list of undirected edges, or a path.  Rows are sorted by neighbour.
 */
#ifndef PS_HAND_GRAPH_H
#define PS_HAND_GRAPH_H

#include "graph/knn_graph.h"

#include <stddef.h>
#include <stdint.h>

#define PS_HAND_GRAPH_MAX_V 64                         /* vertices at most */
#define PS_HAND_GRAPH_MAX_ARCS (4 * PS_HAND_GRAPH_MAX_V) /* 2 * edges at most */

typedef struct ps_hand_graph {
    ps_graph g; /* points into the arrays below */
    size_t offsets[PS_HAND_GRAPH_MAX_V + 1];
    uint32_t neighbors[PS_HAND_GRAPH_MAX_ARCS];
    double weights[PS_HAND_GRAPH_MAX_ARCS];
} ps_hand_graph;

/* edges: #n_edges by 2 vertex pairs in [0, n), each edge once, each of
 * weight `weight`; n <= PS_HAND_GRAPH_MAX_V, 2 * n_edges <=
 * PS_HAND_GRAPH_MAX_ARCS (beyond that the test aborts). */
void ps_hand_graph_edges(ps_hand_graph *h, size_t n, const int (*edges)[2], int n_edges,
                         double weight);

/* The path 0 - 1 - ... - n-1 with edge lengths `length`, except that no
 * edge joins cut_before - 1 and cut_before (0: none cut). */
void ps_hand_graph_path(ps_hand_graph *h, size_t n, double length, size_t cut_before);

#endif
