/*
 * merge_tree.h: parts made of several basins of f, found on the merge tree
 * of its superlevel sets.
 *
 * Sweeping the saddles between the basins of the simplified ascent flow
 * from high to low (persistence.h), two groups of basins that meet become
 * one: a node of the merge tree, born at that saddle, alive down to the
 * saddle where its group meets another one.  A leaf is a single basin, born
 * at its peak.  The minima step keeps only each basin's part above its
 * highest saddle (its leaf's arc, supernodes.h); what lies below belongs to
 * the nodes above the central region.  A node that lives long is a part
 * with several tips: the head that ears and horns top, the tail fin whose
 * two lobes meet in its middle.  Such a node's points become a part of
 * their own, and the children that are short against it (the ears, the
 * lobes) join it.
 */
#ifndef PS_MERGE_TREE_H
#define PS_MERGE_TREE_H

#include "features/persistence.h"

/* A node is a part when it lives longer than this times the persistence
 * threshold (a fraction of f's range in its component). */
#define PS_PART_PERSISTENCE 2.0
/* A child that lives less than this share of its part's life joins it. */
#define PS_PART_ABSORB 0.5
/* A part reaches below its birth saddle at most this times the life of its
 * longest child: further down its group is body, not part. */
#define PS_PART_REACH 1.0

typedef struct ps_merge_tree_input {
    const ps_graph *graph;     /* kNN graph on #P points (weights not used) */
    const double *f;           /* #P the centrality, whose ascent flow up is */
    const int *component;      /* #P each point's connected component */
    int n_components;
    double persistence;        /* the fraction of f's range in a component below
                                  which peaks merged (0: no parts) */
    const ps_flow *up;         /* the simplified ascent flow: #S basins */
    const ps_saddle *saddles;  /* #n_saddles up's border saddles, in
                                  ps_flow_border_saddles's order (persistence.h) */
    size_t n_saddles;
} ps_merge_tree_input;

/* part_of #P out: the part each point belongs to, in [0, *n_parts), or -1
 * (its basin above the basin's highest saddle, or the central region
 * below). */
ps_status ps_merge_tree_parts(const ps_merge_tree_input *in, int *part_of, int *n_parts,
                              ps_error *err);

#endif
