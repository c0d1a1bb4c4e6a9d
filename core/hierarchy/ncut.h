/*
 * ncut.h: phase 2, the supernode hierarchy by recursive normalized-cut
 * bisection (Shi and Malik).
 *
 * Similarity of supernodes u, v: W(u,v) = s_u s_v exp(-d(u,v) / sigma), with
 * d the geodesic distance between their sinks, s the number of points each
 * stands for (so a cut measures what it would on the points; W(u,u) = s_u^2)
 * and sigma a length taken from the data (scale invariant; see ncut.c).  W is
 * 0 across components.  A node is split by the 2nd smallest generalized
 * eigenvector of (D - W) y = lambda D y, thresholded at the best of evenly
 * spaced candidate values; the split is kept while its NCut is at most
 * ncut_threshold, and the halves are split in turn.
 */
#ifndef PS_NCUT_H
#define PS_NCUT_H

#include "graph/knn_graph.h"
#include "hierarchy/ncut_tree.h"

/* sigma of a component = PS_NCUT_SIGMA_SCALE * (mean geodesic distance
 * between two of its sinks), the one knob of W (docs/method.md,
 * "Constants", has its sweep). */
#define PS_NCUT_SIGMA_SCALE 0.1

typedef struct ps_supernode_graph {
    int m;                  /* #S supernodes */
    const uint32_t *sinks;  /* #S sink vertex of each */
    const size_t *sizes;    /* #S points per supernode */
    const int *supernode_of;/* #P supernode of each vertex */
    const int *component;   /* #P component of each vertex */
} ps_supernode_graph;

/* tree: malloc'ed #n_tree nodes, tree[0] the root (all supernodes), each
 * node's supernodes increasing; free with ps_tree_free (ncut_tree.h). */
ps_status ps_ncut_hierarchy(const ps_graph *g, const ps_supernode_graph *sg,
                            double ncut_threshold, int threads,
                            const ps_control *ctl, ps_tree_node **tree,
                            int *n_tree, ps_error *err);

#endif
