/*
 * coarse_graph.h: the coarse level of the two-level approximate centrality
 * (centrality_coarse.h): the kNN graph cut into small cells of nearby
 * points, the geodesic distances from each cell's seed to the points around
 * it, and a graph on the seeds.
 *
 * Cells: the vertices are walked in order 0..n-1 (a breadth-first order,
 * bfs_order.h); an uncovered vertex becomes a seed and covers every vertex
 * within geodesic distance r of it, r = PS_CELL_RADIUS_EDGES x the median
 * edge length of its component (x sqrt(size / PS_CELL_SCALE_POINTS) for a
 * component bigger than that).  Every vertex's cell is that of its
 * nearest seed (ties to the lower cell), read off the cover's balls (the
 * nearest seed is within r, so its ball reached the vertex): the cells a
 * multi-source Dijkstra from all seeds gives.  Cells are connected (in
 * exact arithmetic: a shortest path from a seed stays in its cell), never
 * span two components, and are numbered in the order of their seeds.
 * Near cells: cell a and cell b are adjacent when a graph edge joins them;
 * near(a) is a with its adjacent cells, increasing.
 * Local distances: for each vertex p and each cell c in near(cell of p),
 * g(c, p) = the geodesic distance from c's seed to p through the vertices
 * of near(c) only (a bounded Dijkstra per seed; exact for c = cell of p).
 * Coarse graph: one vertex per cell, an edge between adjacent cells a, b of
 * weight min(g(a, seed b), g(b, seed a)).
 */
#ifndef PS_COARSE_GRAPH_H
#define PS_COARSE_GRAPH_H

#include "graph/bfs_order.h"
#include "util/parallel.h"

#ifndef PS_CELL_RADIUS_EDGES
#define PS_CELL_RADIUS_EDGES 3.0 /* cell radius in median kNN edge lengths (-D to tune) */
#endif
/* Above this many points a component's cell radius grows by sqrt(points /
 * PS_CELL_SCALE_POINTS), so its cell count (~35,000 here) stops growing: the
 * coarse Dijkstras' cost is then bounded, and the cells keep the size in
 * the model's own units they have at this many points. */
#ifndef PS_CELL_SCALE_POINTS
#define PS_CELL_SCALE_POINTS 500000
#endif

/* The factor on the cell radius of a component of size points. */
double ps_cell_radius_growth(size_t size);

typedef struct ps_coarse_graph {
    size_t n_cells;         /* #M */
    uint32_t *seed;         /* #M seed vertex of each cell, increasing */
    uint32_t *cell_of;      /* #P cell of each vertex */
    size_t *cell_start;     /* #components+1: component k owns the cells
                               [cell_start[k], cell_start[k+1]) */
    size_t *near_offsets;   /* #M+1: near(a) = near[near_offsets[a] ..
                               near_offsets[a+1]) */
    uint32_t *near;         /* near cells, each list increasing, a included */
    size_t *local_offsets;  /* #P+1: vertex p's row of local distances */
    float *local;           /* local[local_offsets[p] + j] = g(c, p) for the
                               j-th cell c of near(cell_of[p]) */
    ps_graph graph;         /* #M vertices: the coarse graph, rows increasing */
} ps_coarse_graph;

/* o: the breadth-first relabelled graph (its vertex ids are used
 * throughout).  threads as ps_parallel_threads.  span (may be NULL, and so
 * may its ctl): progress from span->lo to span->hi as the cover and the
 * local distances go; when its cancel flag is raised the build stops with
 * PS_ERR_CANCELLED.  On success cg owns its arrays; on failure it holds
 * none. */
ps_status ps_coarse_graph_build(const ps_bfs_order *o, int threads, const ps_progress_span *span,
                                ps_coarse_graph *cg, ps_error *err);
void ps_coarse_graph_free(ps_coarse_graph *cg);

#endif
