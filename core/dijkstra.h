/*
 * dijkstra.h: single- and multi-source shortest paths on a ps_graph.
 *
 * A workspace holds the heap and scratch arrays for one thread so repeated
 * runs allocate nothing.  Unreachable vertices get INFINITY.
 */
#ifndef PS_DIJKSTRA_H
#define PS_DIJKSTRA_H

#include "knn_graph.h"

typedef struct ps_dijkstra ps_dijkstra;

ps_dijkstra *ps_dijkstra_new(size_t n);
void ps_dijkstra_free(ps_dijkstra *w);

/* dist #P: distance from the nearest of sources (#S vertex ids).  owner, if
 * not NULL, #P: index in sources of that nearest source (-1 unreachable);
 * ties go to the lower source index, so results are deterministic. */
void ps_dijkstra_run(ps_dijkstra *w, const ps_graph *g, const uint32_t *sources,
                     size_t n_sources, double *dist, int *owner);

/* Lowers dist (#P, current values) to min(dist, distance from source),
 * exploring only vertices it improves: the farthest-point sampling step. */
void ps_dijkstra_lower(ps_dijkstra *w, const ps_graph *g, uint32_t source,
                       double *dist);

/* The same from several sources (#S vertex ids) at once: dist (#P) becomes
 * min(dist, distance from the nearest source).  Initialize dist to a cap R
 * to explore only the vertices closer than R. */
void ps_dijkstra_lower_many(ps_dijkstra *w, const ps_graph *g, const uint32_t *sources,
                            size_t n_sources, double *dist);

#endif
