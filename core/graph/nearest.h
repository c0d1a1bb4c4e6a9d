/*
 * nearest.h: for each query point, the nearest point of a set (exact
 * Euclidean nearest, FLANN's single kd-tree, as the kNN graph's).
 */
#ifndef PS_NEAREST_H
#define PS_NEAREST_H

#include "pointseg.h"

#include <stdint.h>

typedef struct ps_nearest_index ps_nearest_index;

/* An index over points (#N by dim, N >= 1, kept by the caller until the
 * index is freed); NULL when out of memory. */
ps_nearest_index *ps_nearest_build(const double *points, size_t n, int dim);
void ps_nearest_free(ps_nearest_index *index);

/* queries: #Q by dim.  nearest out: #Q, the index in the indexed points of
 * each query's nearest (ties: whichever the kd-tree meets first, the same
 * for any thread count).  Queries close in the array run faster. */
ps_status ps_nearest_query(const ps_nearest_index *index, const double *queries, size_t m,
                           int threads, uint32_t *nearest, ps_error *err);

#endif
