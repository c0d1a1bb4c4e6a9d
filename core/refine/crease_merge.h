/*
 * crease_merge.h: adjacent segments whose shared boundary is not a concave
 * crease merge (method auto, 3-D; runs after the boundary cut).
 *
 * People cut a shape where it bends inwards (the minima rule of Hoffman and
 * Richards): a boundary across a smooth or convex stretch of surface, such
 * as the inside of a cup split from its wall, or a limb split halfway, is
 * not a part boundary.  The boundary between segments A and B is the set
 * of kNN edges joining them; such an edge is creased when one of its ends
 * has an edge into A or B whose angular term ang(p,q) (crease.h; 0 on
 * convex edges) is at least PS_CREASE_MERGE_STRENGTH times the crease
 * scale: the mean of ang over all edges (scale free, and relative to how
 * bumpy the whole surface is) or, when larger, PS_CREASE_MERGE_NOISE times
 * the median crease strength (the surface's own noise, crease.h: on a noisy
 * scan every boundary has edges over the mean), a little over the scale
 * the crease split's points reach (PS_CREASE_NOISE, crease_split.h), since
 * a noise ring the split cut along must not hold its pieces apart; and
 * which runs within 60 degrees of the boundary edge's line (it bends
 * across the boundary).  Edges into a third segment do not count: a wing
 * root running next to the boundary between a nose and a fuselage is the
 * wing's crease, not theirs; nor do edges running along the boundary: the
 * fillet under a wing that the boundary crosses bends along it.
 * While some pair's creased fraction is below PS_CREASE_MERGE_FRACTION,
 * the pair with the lowest (ties: lowest ids) merges: the segment with fewer
 * points goes into the other (ties: the higher id into the lower), its
 * boundaries adding up with the survivor's.  A pair one of whose segments
 * protrudes stays apart whatever its creases: people also cut off what
 * sticks out (Hoffman and Singh, 1997), such as a limb joined to the body
 * over smooth surface.  The segment that may stick out is the smaller,
 * or the other when the smaller is the core (the segment holding the
 * least f: the centre of a plus sign can be smaller than each arm); it
 * protrudes when its feature size (max f - min f) is over
 * PS_CREASE_MERGE_PROTRUSION times the width of the boundary
 * (ps_boundary_width).  A cavity is no part
 * either: a smaller segment that curves inwards, its outward normals
 * pointing towards its centre (ps_segment_bulge below
 * -PS_CREASE_MERGE_CAVITY; the inside of a cup), merges as if none of its
 * boundary were creased, since the concave bend of its own surface marks
 * its boundary edges as creased wherever they run.  A surface without concave edges (crease.h, PS_CREASE_FLAT: a
 * plane, a ball, a cube) has no creases to judge by: every pair merges
 * but the protruding, so that a ball, an egg, a disc or a square sheet
 * is one part (on a ball f is flat, its basins the sampling's noise)
 * and the fingers of a flat hand or the arms of a plus sign stay apart.
 * Deterministic; no threads.
 */
#ifndef PS_CREASE_MERGE_H
#define PS_CREASE_MERGE_H

#include "refine/segment_graph.h"

/* The constants (docs/method.md, "Constants", has their sweeps): */
/* An edge is creased above this many times the crease scale (above). */
#define PS_CREASE_MERGE_STRENGTH 1.5
/* The noise term of the crease scale: this many median crease strengths
 * (crease.h; the crease split uses PS_CREASE_NOISE, 3). */
#define PS_CREASE_MERGE_NOISE 4.0
/* cos of the widest angle between an edge that can crease a boundary and
 * the boundary edge (60 degrees). */
#define PS_CREASE_MERGE_CONE 0.5
/* A boundary creased along less than this fraction of its edges merges. */
#define PS_CREASE_MERGE_FRACTION 0.5
/* A part at least this many times longer (feature size, in f) than its
 * boundary is wide (ps_boundary_width) stays without a crease. */
#define PS_CREASE_MERGE_PROTRUSION 1.0
/* A smaller segment whose bulge is below minus this is a cavity. */
#define PS_CREASE_MERGE_CAVITY 0.35

/* The test of a boundary edge above, for the other merges that weigh
 * creases (convex_merge.h): a ps_boundary_mark_fn, ps_crease_marked_edge,
 * with a ps_crease_test as its context. */
typedef struct ps_crease_test {
    const ps_merge_input *in;
    double crease; /* the angular term that makes a crease */
} ps_crease_test;

ps_crease_test ps_crease_test_of(const ps_merge_input *in);
int ps_crease_marked_edge(void *context, const int *group, size_t p, size_t q);

/* A ps_merge_fn (segment_graph.h). */
ps_merge_fn ps_crease_merge;

#endif
