/*
 * hand_graph.c: the hand-made test graphs of hand_graph.h.
 */
#include "hand_graph.h"

#include <stdlib.h>

/* Inserts q into p's row, whose filled part ends at *end, keeping it sorted. */
static void insert_sorted(ps_hand_graph *h, size_t p, size_t *end, uint32_t q) {
    size_t at = (*end)++;
    while (at > h->offsets[p] && h->neighbors[at - 1] > q) {
        h->neighbors[at] = h->neighbors[at - 1];
        at--;
    }
    h->neighbors[at] = q;
}

void ps_hand_graph_edges(ps_hand_graph *h, size_t n, const int (*edges)[2], int n_edges,
                         double weight) {
    if (n > PS_HAND_GRAPH_MAX_V || 2 * (size_t)n_edges > PS_HAND_GRAPH_MAX_ARCS) abort();
    size_t fill[PS_HAND_GRAPH_MAX_V + 1] = {0};
    for (int e = 0; e < n_edges; e++) fill[edges[e][0] + 1]++, fill[edges[e][1] + 1]++;
    for (size_t p = 0; p < n; p++) fill[p + 1] += fill[p];
    for (size_t p = 0; p <= n; p++) h->offsets[p] = fill[p];
    for (int e = 0; e < n_edges; e++)
        for (int end = 0; end < 2; end++)
            insert_sorted(h, (size_t)edges[e][end], &fill[edges[e][end]],
                          (uint32_t)edges[e][1 - end]);
    for (size_t e = 0; e < h->offsets[n]; e++) h->weights[e] = weight;
    h->g = (ps_graph){.n = n, .offsets = h->offsets, .neighbors = h->neighbors,
                      .weights = h->weights};
}

void ps_hand_graph_path(ps_hand_graph *h, size_t n, double length, size_t cut_before) {
    int edges[PS_HAND_GRAPH_MAX_V][2];
    int m = 0;
    for (size_t p = 1; p < n && p < PS_HAND_GRAPH_MAX_V; p++)
        if (p != cut_before) edges[m][0] = (int)p - 1, edges[m][1] = (int)p, m++;
    ps_hand_graph_edges(h, n, (const int(*)[2])edges, m, length);
}
