/*
 * outliers.h: stray points of a scan (method auto), found on the kNN graph
 * and left out of the segmentation.
 *
 * A scanner's stray point joins the kNN graph through edges many spacings
 * long, and through it geodesics take shortcuts between parts that are
 * far apart along the surface (20 random points in the horse's bounding
 * box, 0.04% of its points, moved its segmentation 0.18 in 1 - RI away from
 * the clean one).  A point is an outlier when its median kNN edge is more
 * than PS_OUTLIER_RATIO times the median, over its neighbours, of their own
 * median edge (a local outlier factor, after Breunig et al. 2000; medians
 * so that one long edge to a stray point does not make its neighbours look
 * stray), and it has a neighbour that is no outlier.  Such points are
 * dropped from the distinct points (dedup.h) and take the answers of their
 * nearest kept neighbour, as duplicates take their representative's.
 * Outliers in a cluster of their own (no kept neighbour) stay.  The
 * pipeline (segment.c) repeats the search on the kept points, up to
 * PS_OUTLIER_ROUNDS times, until a round finds none: a stray point beside
 * a farther one shows only once that one is gone.
 */
#ifndef PS_OUTLIERS_H
#define PS_OUTLIERS_H

#include "graph/dedup.h"
#include "graph/knn_graph.h"

/* The constants (docs/method.md, "Constants", has their sweeps): */
#define PS_OUTLIER_RATIO 5.0 /* an outlier's median edge over its neighbours' */
#define PS_OUTLIER_ROUNDS 4  /* searches at most */

/* g: kNN graph on #U distinct points, weights Euclidean lengths; threads
 * as ps_parallel_threads (the answer does not depend on them).
 * keep_for #U out: for an outlier (see above), its nearest neighbour that
 * is kept; for any other point, itself.  *count out: the outliers. */
ps_status ps_outliers_find(const ps_graph *g, int threads, uint32_t *keep_for, size_t *count,
                           ps_error *err);

/* Drops the outliers from d (built on n_points input points): its distinct
 * points become the kept ones, in the same order, and every input point of
 * an outlier maps to its keep_for point.  keep_for #U as from
 * ps_outliers_find (a kept point's keep_for is itself). */
ps_status ps_outliers_drop(ps_dedup *d, size_t n_points, const uint32_t *keep_for,
                           ps_error *err);

#endif
