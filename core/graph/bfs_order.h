/*
 * bfs_order.h: a copy of a ps_graph relabelled in breadth-first order, for
 * cache-friendly repeated traversals (the centrality's many Dijkstras).
 *
 * Components are visited in order of their lowest vertex, each by BFS from
 * that vertex (neighbours in row order), so every component occupies one
 * contiguous range of new ids and its root (the lowest old vertex) comes
 * first.  Shortest-path distances do not depend on the labelling.
 */
#ifndef PS_BFS_ORDER_H
#define PS_BFS_ORDER_H

#include "graph/knn_graph.h"

typedef struct ps_bfs_order {
    ps_graph g;          /* #P vertices in new ids; rows in the old row order */
    uint32_t *old_of;    /* #P old id of each new id */
    uint32_t *new_of;    /* #P new id of each old id */
    int n_components;
    size_t *start;       /* #n_components+1: component c is new ids
                            [start[c], start[c+1]), numbered as ps_graph_components */
} ps_bfs_order;

/* g: the graph to relabel.  On success o owns its arrays. */
ps_status ps_bfs_order_build(const ps_graph *g, ps_bfs_order *o, ps_error *err);
void ps_bfs_order_free(ps_bfs_order *o);

/* The same, moving g's arrays into o instead of copying them (rows copied
 * on threads, as ps_parallel_threads): g is freed (empty) on return, and no
 * more than one graph and one of its edge arrays are alive at once.  On
 * failure (out of memory) g is lost too. */
ps_status ps_bfs_order_take(ps_graph *g, int threads, ps_bfs_order *o, ps_error *err);

/* The inverse: g is rebuilt from o, byte-identical to the graph taken
 * (rows, their order and weights), and o is freed.  On failure (out of
 * memory) both are freed. */
ps_status ps_bfs_order_give_back(ps_bfs_order *o, int threads, ps_graph *g, ps_error *err);

#endif
