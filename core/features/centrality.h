/*
 * centrality.h: the paper's centrality f(p) = mean geodesic distance from p
 * to the points of its connected component.
 *
 * exact:  Dijkstra from every vertex (O(n^2 log n); small inputs, checks).
 * approx: farthest-point samples per component (start at the component's
 *         lowest vertex, add the vertex farthest from all samples so far),
 *         f = mean distance to the samples.  samples = S in total, shared
 *         among components in proportion to their sizes (at least 1 each).
 *         Below PS_COARSE_MIN_POINTS vertices: one full Dijkstra per sample.
 *         From there on: the two-level scheme of centrality_coarse.h
 *         (samples are seeds of cells of ~10-30 points, sampled on the
 *         coarse graph, at most one per cell; distances through the coarse
 *         graph plus local geodesics), ~10x faster on 50k points.
 * Uses `threads` workers; the result is bit-identical for any thread count
 * (fine path: per-vertex sums in 64-bit fixed point; two-level: each vertex
 * summed by one worker in a fixed order).  A single-vertex component gets
 * f = 0.
 */
#ifndef PS_CENTRALITY_H
#define PS_CENTRALITY_H

#include "graph/knn_graph.h"

#ifndef PS_COARSE_MIN_POINTS
#define PS_COARSE_MIN_POINTS 20000 /* approx uses the two-level scheme from here (-D to tune) */
#endif

#ifndef PS_MAX_DEFAULT_SAMPLES
#define PS_MAX_DEFAULT_SAMPLES 512 /* the default sample count's cap */
#endif

/* The default approx sample count for n points: ceil(sqrt(n)), at most
 * PS_MAX_DEFAULT_SAMPLES.  The error of a mean distance over samples that
 * cover the shape depends on their number, not on n, so beyond ~1M points
 * more samples cost time and memory (a float per cell and sample) for no
 * better f. */
int ps_centrality_default_samples(size_t n);

typedef struct ps_centrality_input {
    const ps_graph *graph;     /* #P vertices; its weights are the edge lengths */
    const int *component;      /* #P from ps_graph_components */
    int n_components;
    ps_centrality_mode mode;   /* EXACT or APPROX (the caller resolves AUTO) */
    int samples;               /* approx: S in total (0: ps_centrality_default_samples) */
    int threads;               /* ps_parallel_threads; f is the same for any count */
    size_t coarse_min;         /* approx takes the two-level scheme from this many
                                  vertices on: PS_COARSE_MIN_POINTS (tests and tuning:
                                  0 always, SIZE_MAX never) */
    const ps_control *ctl;     /* progress and cancel; may be NULL */
} ps_centrality_input;

/* f #P out.  sample_ids, if not NULL, receives a malloc'ed list of the
 * sample vertices (#samples_used).  In exact mode no samples are drawn:
 * *samples_used = 0 and *sample_ids = NULL.  Checks in->ctl's cancel flag
 * between Dijkstra runs (PS_ERR_CANCELLED) and reports progress through it
 * from one thread at a time, with nondecreasing fractions. */
ps_status ps_centrality(const ps_centrality_input *in, double *f, uint32_t **sample_ids,
                        int *samples_used, ps_error *err);

/* ps_centrality (the same outputs) on a graph it borrows: g, in place of
 * in->graph, which is not read (leave it NULL).  g's arrays move into the
 * breadth-first copy (bfs_order.h) while the centrality runs and move back,
 * byte-identical, before it returns, so the peak holds one copy of the
 * graph instead of two.  Out of memory, g may come back freed. */
ps_status ps_centrality_borrowing(const ps_centrality_input *in, ps_graph *g, double *f,
                                  uint32_t **sample_ids, int *samples_used, ps_error *err);

#endif
