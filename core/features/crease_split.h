/*
 * crease_split.h: supernodes cut along closed concave creases (method
 * auto, 3-D), so that a part with no maximum of its own (a head below its
 * ears, a neck, a vase's foot) gets a supernode of its own.
 *
 * A point is on a crease when its crease strength (crease.h) is at least
 * PS_CREASE_SPLIT_STRENGTH times the mean angular term, among the
 * PS_CREASE_SPLIT_MAX_POINTS strongest points (creases are lines; on a
 * noisy scan most points pass the first test), and at least
 * PS_CREASE_NOISE times the median strength (crease.h): noise creases
 * closed into rings would cut pieces out of smooth parts.  Inside each
 * supernode, the points off creases fall into connected pieces (kNN edges
 * inside the supernode between two such points); a crease that closes
 * around the surface separates two pieces.  A piece of at least
 * PS_CREASE_SPLIT_MIN_FRACTION of all the points (and of
 * PS_PERSISTENCE_MIN_BASIN points) is kept; every other point
 * of the supernode joins the nearest kept piece (breadth first inside the
 * supernode, ties to the piece reached first in point order).  A supernode
 * with no kept piece stays whole, and so do all when the split would give
 * more than PS_MAX_SUPERNODES.  Splits that a boundary does not justify are
 * undone later by the crease merge (crease_merge.h).
 */
#ifndef PS_CREASE_SPLIT_H
#define PS_CREASE_SPLIT_H

#include "features/crease.h"
#include "features/supernodes.h"

/* The constants (docs/method.md, "Constants", has their sweeps): */
/* A crease point's strength, in mean angular terms. */
#define PS_CREASE_SPLIT_STRENGTH 1.0
/* A kept piece's share of all the points, at least. */
#define PS_CREASE_SPLIT_MIN_FRACTION 0.005
/* The share of the points, strongest first, that may be crease points. */
#define PS_CREASE_SPLIT_MAX_POINTS 0.45

/* creases: the crease strengths of the #P points (crease.h); f #P the
 * centrality (picks the representatives).  sn is replaced by its
 * refinement: every new supernode lies inside one old one and keeps its
 * is_minimum. */
ps_status ps_crease_split(const ps_graph *g, const ps_crease_points *creases, const double *f,
                          ps_supernodes *sn, ps_error *err);

#endif
