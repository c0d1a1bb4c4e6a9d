/*
 * dijkstra.h: single- and multi-source shortest paths on a ps_graph.
 *
 * A workspace holds the heap and scratch arrays for one thread so repeated
 * runs allocate nothing.  Unreachable vertices get INFINITY.  A ball run
 * (ps_dijkstra_ball) stays within a radius and a region and lists the
 * vertices it reaches, so a caller can run many small searches on a large
 * graph and reset only what each one touched; it may start from several
 * sources and may measure edges as Euclidean lengths between 3-D points
 * instead of reading g->weights, so a caller needs no copy of the graph.
 */
#ifndef PS_DIJKSTRA_H
#define PS_DIJKSTRA_H

#include "graph/knn_graph.h"

#include <math.h>

/* |p - q| for 3-D points, the edge length of a ball run with points. */
static inline double ps_distance3(const double *p, const double *q) {
    double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

typedef struct ps_dijkstra ps_dijkstra;

ps_dijkstra *ps_dijkstra_new(size_t n);
void ps_dijkstra_free(ps_dijkstra *w);

/* dist #P: distance from the nearest of sources (#S vertex ids).  owner, if
 * not NULL, #P: index in sources of that nearest source (-1 unreachable);
 * ties go to the lower source index, so results are deterministic. */
void ps_dijkstra_run(ps_dijkstra *w, const ps_graph *g, const uint32_t *sources,
                     size_t n_sources, double *dist, int *owner);

/* The same, reporting progress from span->lo to span->hi (span->ctl may be
 * NULL) as the share of g's vertices settled grows; span may be NULL. */
void ps_dijkstra_run_tracked(ps_dijkstra *w, const ps_graph *g, const uint32_t *sources,
                             size_t n_sources, double *dist, int *owner,
                             const ps_progress_span *span);

/* Lowers dist (#P, current values) to min(dist, distance from source),
 * exploring only vertices it improves: the farthest-point sampling step. */
void ps_dijkstra_lower(ps_dijkstra *w, const ps_graph *g, uint32_t source,
                       double *dist);

/* Where a ball run may go: vertices at distance <= radius (inclusive;
 * INFINITY for no bound) and, when label is not NULL, only the vertices v
 * with mark[label[v]] == stamp (label #P, e.g. the cell of each vertex;
 * mark #L, e.g. a stamp on the cells the run may enter).  Labels are read with relaxed atomic loads, so another thread
 * may relabel vertices outside the region during a run (the boundary
 * cut's pairs side by side), as long as no vertex enters or leaves it.
 * points, when not NULL, #P by 3: an edge's length is then
 * ps_distance3 of its ends, and g->weights is not read (it may be NULL). */
typedef struct ps_dijkstra_limits {
    double radius;
    const uint32_t *label;
    const uint32_t *mark;
    uint32_t stamp;
    const double *points;
} ps_dijkstra_limits;

/* Dijkstra from source (always reached) within limits.  dist #P must be
 * INFINITY at every vertex on entry; on return it holds the distance of
 * each reached vertex and INFINITY elsewhere.  reached #P out: the reached
 * vertices in settling order (source first, distances nondecreasing).
 * Returns their count.  Setting dist[reached[i]] = INFINITY for i < count
 * readies dist for the next ball.
 * Or dist holds the distances from earlier sources (the minimum over
 * earlier balls' results, INFINITY where none reached): the run then
 * lowers dist to the minimum with source's ball and reaches only the
 * vertices it lowers strictly, as ps_dijkstra_lower does. */
size_t ps_dijkstra_ball(ps_dijkstra *w, const ps_graph *g, uint32_t source,
                        const ps_dijkstra_limits *limits, double *dist, uint32_t *reached);

/* The same from every one of sources (#S distinct vertices, all reached at
 * distance 0 and listed first in reached, in no set order). */
size_t ps_dijkstra_ball_from(ps_dijkstra *w, const ps_graph *g, const uint32_t *sources,
                             size_t n_sources, const ps_dijkstra_limits *limits, double *dist,
                             uint32_t *reached);

#endif
