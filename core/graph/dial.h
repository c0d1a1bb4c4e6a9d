/*
 * dial.h: single-source shortest paths without a heap, on a graph whose
 * edges all have about the same length (Dial's algorithm): the coarse
 * graph of the two-level centrality (coarse_graph.h), whose seeds are
 * more than a cell radius apart, runs one search per sample, and one
 * lowering per sample while it chooses them.
 *
 * Vertices wait in buckets of width delta, half the graph's shortest
 * edge; an edge leaves its bucket by two buckets at least, so every vertex
 * of the lowest nonempty bucket has its final distance and relaxes its
 * edges once, in any order.  The distances are bit-identical to
 * ps_dijkstra_run's (dijkstra.h): both are the one solution of dist[v] =
 * min over edges (u, v) of dist[u] + w(u, v), each vertex relaxing every
 * edge from its final distance.  O(V + E + longest distance / delta) a
 * run.  A graph whose longest edge is over PS_DIAL_MAX_SPAN times its
 * shortest, or with an edge of length 0, is run by the heap instead.
 */
#ifndef PS_DIAL_H
#define PS_DIAL_H

#include "graph/knn_graph.h"

#define PS_DIAL_MAX_SPAN 512.0 /* longest / shortest edge the buckets take */

typedef struct ps_dial ps_dial;

/* A workspace for runs on g (#P vertices, weights >= 0), which must
 * outlive it and not change; one per thread.  NULL when out of memory. */
ps_dial *ps_dial_new(const ps_graph *g);
void ps_dial_free(ps_dial *w);

/* dist #P out: the distance from source to every vertex (INFINITY where
 * unreachable), as ps_dijkstra_run from that one source gives it. */
void ps_dial_run(ps_dial *w, uint32_t source, double *dist);

/* Lowers dist (#P, current values) to min(dist, distance from source),
 * reaching only the vertices it lowers, as ps_dijkstra_lower does (the
 * farthest-point sampling step). */
void ps_dial_lower(ps_dial *w, uint32_t source, double *dist);

#endif
