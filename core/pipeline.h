/*
 * pipeline.h: PRIVATE to the top of core/ (segment.c, pipeline.c,
 * ensemble.c, and segment.h and ensemble.h, which take a pipeline), not
 * part of the public API: one run of the method over a
 * point set, what each step leaves for the next, the steps themselves
 * (pipeline.c; which run, in what order, is segment.c's table), and the
 * result's parts taken from it.
 */
#ifndef PS_PIPELINE_H
#define PS_PIPELINE_H

#include "features/crease.h"
#include "features/normals.h"
#include "features/supernodes.h"
#include "graph/dedup.h"
#include "graph/knn_graph.h"
#include "pointseg.h"
#include "refine/segment_graph.h"
#include "result.h"
#include "util/parallel.h"

/* Everything the phases produce for the distinct points. */
typedef struct ps_pipeline {
    const ps_input *in;    /* the caller's points, then any added on its faces */
    size_t n_input;        /* #P the caller's points */
    const uint32_t *host_of_added; /* surface_fill.h */
    const ps_control *ctl;
    ps_params params;
    int threads;
    ps_dedup dedup;
    double *points;        /* #U by dim distinct points (in->points when no dups) */
    ps_graph graph;
    ps_knn_memo *knn_memo; /* method auto, until the stray points are out */
    int *component;        /* #U */
    int n_components;
    double *normals;       /* #U by 3 outward normals (method auto, 3-D), else NULL */
    ps_normals_report normals_report; /* the noise measured, the smoothing done (normals.h) */
    size_t n_outliers;     /* distinct points dropped as stray (outliers.h) */
    double *crease_normals;   /* #U by 3 the crease split's and merge's normals
                                 (crease_scale), or normals itself */
    ps_crease_points creases; /* with normals: crease strengths of the #U points
                                 at the crease scale, and their mean */
    ps_edge_scales edge_scales; /* with normals: the graph's edges over them */
    double *spacing;       /* with normals: #U mean Euclidean kNN edge length of each
                              point (the profile split's; freed after it) */
    double *f;             /* #U centrality */
    ps_supernodes sn;
    ps_tree_node *tree;
    int n_tree;
    int *group_of_leaf;    /* #n_tree */
    int *group_of_point;   /* #U final group (surviving leaf id) of each point */
    ps_merge *merges;
    int n_merges;
    ps_edge_list boundary; /* the boundary edges one merge hands the next */
    ps_timings timings;
} ps_pipeline;

/* Milliseconds on the monotonic clock. */
double ps_now_ms(void);

/* pl->points: the distinct points of pl->in (in Morton order for a big
 * scan, dedup.h); fails when fewer than k + 1 remain.  ps_pipeline_dedup
 * finds them; ps_pipeline_distinct takes pl->dedup as built already
 * (ps_dedup_build on pl->in, not reordered). */
ps_status ps_pipeline_dedup(ps_pipeline *pl, ps_error *err);
ps_status ps_pipeline_distinct(ps_pipeline *pl, ps_error *err);

/* A step of the method (ps_step, pointseg.h) on pl, after the steps
 * before it: span is its share of its phase's progress.  One per step, in
 * the order they run: */
typedef ps_status ps_pipeline_step_fn(ps_pipeline *pl, const ps_progress_span *span,
                                      ps_error *err);
ps_pipeline_step_fn ps_pipeline_knn_graph, ps_pipeline_outliers, ps_pipeline_components,
    ps_pipeline_normals, ps_pipeline_crease_metric, ps_pipeline_centrality,
    ps_pipeline_supernodes, ps_pipeline_f2_split, ps_pipeline_crease_split,
    ps_pipeline_profile_split, ps_pipeline_ncut, ps_pipeline_feature_merge,
    ps_pipeline_boundary_cut, ps_pipeline_crease_merge, ps_pipeline_convex_merge,
    ps_pipeline_patch_merge;

/* Frees what only the phases read (the kNN graph, components, normals,
 * crease strengths), keeping what the result and the distinct points
 * need (after every phase). */
void ps_pipeline_shed(ps_pipeline *pl);

/* The result's parts for pl's own input points (after every phase). */
ps_result_parts ps_pipeline_parts(const ps_pipeline *pl);

/* *out built from parts (ps_pipeline_parts, or adjusted for a draw's
 * callers) with pl's parameters; on success pl's tree has moved into it. */
ps_status ps_pipeline_result(ps_pipeline *pl, const ps_result_parts *parts, ps_result **out,
                             ps_error *err);

void ps_pipeline_free(ps_pipeline *pl);

#endif
