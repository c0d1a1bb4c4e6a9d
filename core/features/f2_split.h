/*
 * f2_split.h: the paper's second function f2, for features that a ridge
 * separates but that flow into one sink.
 *
 * Inside each supernode, f2(p) is the geodesic distance from p to the
 * supernode's representative, over kNN edges that stay inside it.  The
 * maxima of f2 are the supernode's far ends; ascending f2 within the
 * supernode and merging shallow maxima by persistence (persistence.h,
 * relative to each supernode's f2 range) splits a supernode that holds two
 * ridge-separated features into one supernode per feature.
 */
#ifndef PS_F2_SPLIT_H
#define PS_F2_SPLIT_H

#include "features/supernodes.h"

/* f #P the centrality (sets the representatives of the new supernodes).
 * sn is replaced by its refinement: every new supernode lies inside one old
 * one and keeps its is_minimum. */
ps_status ps_f2_split(const ps_graph *g, const double *f, double persistence, ps_supernodes *sn,
                      ps_error *err);

#endif
