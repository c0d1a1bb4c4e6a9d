/*
 * kdtree_params.h: PRIVATE to the core's FLANN users (knn_graph.c,
 * nearest.c, kdtree_query.c), not part of the public API: the one way the
 * project asks FLANN for nearest points, an exact search on a single
 * kd-tree, queried in blocks by the workers of ps_parallel_for side by
 * side (kdtree_query.h; so FLANN's own threads stay off).
 */
#ifndef PS_KDTREE_PARAMS_H
#define PS_KDTREE_PARAMS_H

#include <flann/flann.h>

#define PS_KD_LEAF_SIZE 16 /* points per kd-tree leaf (FLANN's default 4 is slower) */

static inline struct FLANNParameters ps_kd_parameters(void) {
    struct FLANNParameters fp = DEFAULT_FLANN_PARAMETERS;
    fp.algorithm = FLANN_INDEX_KDTREE_SINGLE;
    fp.checks = FLANN_CHECKS_UNLIMITED;
    fp.eps = 0.0f;
    fp.cores = 1;
    fp.leaf_max_size = PS_KD_LEAF_SIZE;
    fp.log_level = FLANN_LOG_NONE;
    return fp;
}

#endif
