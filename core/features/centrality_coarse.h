/*
 * centrality_coarse.h: the two-level approximate centrality, for large
 * inputs (centrality.h chooses it).
 *
 * Coarse level (coarse_graph.h): cells of ~10-30 points, their seeds and a
 * graph on the seeds.  Samples are chosen by farthest-point sampling on the
 * coarse graph per component (start at the component's root cell, whose
 * seed is its lowest vertex), so every sample is a seed; one Dijkstra per
 * sample on the coarse graph gives D(c, s) for every cell c.
 * Fine level: d_s(p) = min over the cells c near p's cell of
 * D(c, s) + g(c, p), g the local geodesic distance; f(p) = mean over the
 * component's samples of d_s(p); d_s(s) = 0 at a sample.  The set of cells
 * changes from one cell to the next, which leaves small steps in f at cell
 * borders (spurious flow sinks: 477 on the horse); SMOOTH_STEPS rounds of
 * averaging f over each vertex and its graph neighbours remove them (21
 * sinks, against 76 with full Dijkstras from the same number of samples).
 * Accuracy (RMS of f normalized per component vs exact): dumbbell 0.063,
 * star 0.062, hand 0.062; on the PSB dev set it is a little rougher than
 * the full-Dijkstra path below 20,000 points (centrality.h's threshold).
 * Each vertex is computed by one worker summing its samples in a fixed
 * order, so f is bit-identical for any thread count.
 */
#ifndef PS_CENTRALITY_COARSE_H
#define PS_CENTRALITY_COARSE_H

#include "graph/bfs_order.h"

/* o: the breadth-first relabelled graph.  samples: S in total, shared among
 * components in proportion to their sizes (at least 1, at most the
 * component's cells).  f #P out, in o's old ids.  sample_ids out: malloc'ed
 * #samples_used old ids of the samples, component by component.  Checks
 * ctl->cancel (PS_ERR_CANCELLED) and reports nondecreasing progress from one
 * thread at a time. */
ps_status ps_centrality_coarse(const ps_bfs_order *o, size_t samples, int threads,
                               const ps_control *ctl, double *f, uint32_t **sample_ids,
                               size_t *samples_used, ps_error *err);

#endif
