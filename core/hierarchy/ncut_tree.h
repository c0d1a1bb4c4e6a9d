/*
 * ncut_tree.h: the supernode hierarchy from a dense similarity matrix W, by
 * recursive normalized-cut bisection (the eigen/bisection half of phase 2,
 * testable without any graph; ncut.c builds W and calls it).
 *
 * A node with supernode set U (|U| >= 2) is split
 *   - when U spans several components: the component of U's lowest
 *     supernode against the rest, NCut 0;
 *   - otherwise by y = D^{-1/2} z, z the eigenvector of the 2nd largest
 *     eigenvalue of D^{-1/2} W_U D^{-1/2} (D the degrees of W_U, self weights
 *     included), i.e. the 2nd smallest of (D - W) y = lambda D y, its sign
 *     fixed by ps_sign_normalize.  A = {y > t} for the one of
 *     PS_NCUT_CANDIDATES values t evenly spaced strictly between min y and
 *     max y that minimizes NCut = cut/assoc(A,U) + cut/assoc(B,U) (ties: the
 *     lowest t).
 * The split is kept when NCut <= threshold; otherwise the node is a leaf
 * with ncut = the refused value (-1 for one supernode, or when all y are
 * equal).  Nodes are made breadth first: root 0, then children in the order
 * their parents were made; children[0] holds the lower supernode ids' side
 * (the side of the node's lowest supernode).
 */
#ifndef PS_NCUT_TREE_H
#define PS_NCUT_TREE_H

#include "pointseg.h"

#define PS_NCUT_CANDIDATES 32

/* W: #S by #S symmetric, row major, W >= 0, W(u,u) > 0, 0 across components.
 * component: #S component of each supernode.  threshold: largest NCut kept.
 * ctl (may be NULL): cancel is checked between bisections, progress
 * (PS_PHASE_HIERARCHY) counts supernodes that reached a leaf.  tree out as in
 * ps_ncut_hierarchy (ncut.h): #n_tree nodes, free with ps_tree_free. */
ps_status ps_ncut_tree_build(const double *W, int m, const int *component,
                             double threshold, const ps_control *ctl,
                             ps_tree_node **tree, int *n_tree, ps_error *err);

/* Frees the #n_tree nodes of tree and their supernode lists; tree may be
 * NULL. */
void ps_tree_free(ps_tree_node *tree, int n_tree);

#endif
