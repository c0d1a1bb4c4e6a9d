/*
 * crease_merge.h: adjacent segments whose shared boundary is not a concave
 * crease merge (method auto, 3-D; runs after the boundary cut).
 *
 * People cut a shape where it bends inwards (the minima rule of Hoffman and
 * Richards): a boundary across a smooth or convex stretch of surface, such
 * as the inside of a cup split from its wall, or a limb split halfway, is
 * not a part boundary.  The boundary between segments A and B is the set of
 * kNN edges joining them; its concavity is the mean concave angular term
 * ang(p,q) of crease.h (0 on convex edges) over those edges, divided by the
 * mean of ang over all edges of the graph (scale free, and relative to how
 * bumpy the whole surface is).  While some pair's concavity is below
 * threshold, the pair with the lowest (ties: lowest ids) merges: the
 * segment with fewer points goes into the other (ties: the higher id into
 * the lower), its boundaries adding up with the survivor's.
 * Deterministic; no threads.
 */
#ifndef PS_CREASE_MERGE_H
#define PS_CREASE_MERGE_H

#include "knn_graph.h"

/* PSB dev set, mean 1 - RI (without the merge 0.1721): threshold 0.5
 * 0.1650, 1 0.1579, 1.5 0.1586, 2 0.1613, 3 0.1693.  1 reads plainly: a
 * boundary less concave than the average edge is no crease.  Measuring
 * concavity against the two segments' own edges instead of the whole
 * graph's was no better (0.1610 at 1 and 2). */
#define PS_CREASE_MERGE_THRESHOLD 1.0

typedef struct ps_crease_merge_input {
    const ps_graph *graph;   /* kNN graph on #P points (weights not used) */
    const double *points;    /* #P by 3 */
    const double *normals;   /* #P by 3, outward unit normals (normals.h) */
    const double *f;         /* #P centrality, for the merges' feature sizes */
    int n_groups;            /* segment ids are in [0, n_groups) */
    double threshold;        /* merge while a boundary's concavity is below this */
} ps_crease_merge_input;

/* group_of_point #P in/out: each point's segment id.  group_of_leaf
 * #n_groups in/out: ids (or -1) rewritten to their surviving segment.
 * merges / n_merges in/out: a malloc'ed list (may be NULL with 0) that the
 * new merges are appended to. */
ps_status ps_crease_merge(const ps_crease_merge_input *in, int *group_of_point,
                          int *group_of_leaf, ps_merge **merges, int *n_merges,
                          ps_error *err);

#endif
