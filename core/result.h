/*
 * result.h: assembling the public ps_result from what the phases produced
 * for the distinct points, mapped back onto every input point.  Labels come
 * from each point's group (the boundary cut may move points between
 * segments); a supernode belongs to the segment holding its sink.
 */
#ifndef PS_RESULT_H
#define PS_RESULT_H

#include "pointseg.h"

typedef struct ps_result_parts {
    size_t n_input;              /* #P input points (the caller's) */
    const uint32_t *host_of_added; /* points added after the #P (surface_fill.h):
                                    each one's stand-in among them; NULL if none */
    int dim;
    size_t n_unique;             /* #U distinct points */
    const uint32_t *unique_of;   /* #P distinct index of each input point */
    const uint32_t *first_of;    /* #U lowest index of each distinct point (an
                                    added point's when >= #P) */
    const double *f;             /* #U centrality */
    int n_components;
    int normal_smoothing;        /* normals.h */
    size_t n_filled;             /* points added after the #P (surface_fill.h) */
    size_t n_outliers;           /* outliers.h */
    int n_supernodes;            /* #S */
    const uint32_t *sinks;       /* #S distinct index of each sink */
    const int *is_minimum;       /* #S */
    const int *supernode_of;     /* #U */
    ps_tree_node *tree;          /* #n_tree, ownership moves into the result */
    int n_tree;
    const int *group_of_leaf;    /* #n_tree (refine.h) */
    const int *group_of_point;   /* #U final group (a surviving leaf id) of each point;
                                    a supernode's points all share its sink's group */
    const ps_merge *merges;      /* #n_merges, copied */
    int n_merges;
} ps_result_parts;

/* Builds *out (free with ps_result_free).  On success the result owns
 * parts->tree; on failure the caller still does. */
ps_status ps_result_build(const ps_result_parts *parts, const ps_params *params,
                          ps_result **out, ps_error *err);

#endif
