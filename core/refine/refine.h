/*
 * refine.h: phase 3, merging segments whose feature is too small.
 *
 * A segment (a leaf of the hierarchy) has feature size max f - min f over its
 * points.  While some segment's feature size is under feature_threshold *
 * (range of f in its component), it merges into the adjacent segment (kNN
 * edges crossing) that has the longest shared boundary and a large feature
 * size, as in the paper; smallest features merge first.  Deterministic.
 * A segment holding a minimum's supernode (supernodes.h) is a central
 * region, not a feature, and never merges away (others may merge into it).
 */
#ifndef PS_REFINE_H
#define PS_REFINE_H

#include "graph/knn_graph.h"

typedef struct ps_refine_input {
    const ps_graph *graph;      /* kNN graph on #P points (weights not used) */
    const double *f;            /* #P centrality */
    const int *supernode_of;    /* #P each point's supernode, in [0, #S) */
    const int *is_minimum;      /* #S 1 for a minimum's supernode (supernodes.h), or NULL */
    const int *component;       /* #P each point's connected component */
    const ps_tree_node *tree;   /* #n_tree the hierarchy; its leaves hold the supernodes */
    int n_tree;
    double feature_threshold;   /* a segment merges below this x the range of f over its
                                   component */
} ps_refine_input;

/* group_of_leaf #n_tree out: for each leaf, the tree id of the leaf whose
 * segment it ends in (itself when not merged); -1 for inner nodes.
 * merges: malloc'ed, #n_merges, in order. */
ps_status ps_refine(const ps_refine_input *in, int *group_of_leaf, ps_merge **merges,
                    int *n_merges, ps_error *err);

#endif
