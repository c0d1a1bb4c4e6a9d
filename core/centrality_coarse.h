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
 * component's samples of d_s(p).  The minimum over several cells keeps f
 * continuous across cell borders; d_s(s) = 0 at a sample.
 * Each vertex is computed by one worker summing its samples in a fixed
 * order, so f is bit-identical for any thread count.
 */
#ifndef PS_CENTRALITY_COARSE_H
#define PS_CENTRALITY_COARSE_H

#include "bfs_order.h"

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
