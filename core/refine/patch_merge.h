/*
 * patch_merge.h: a segment that is a crumb or a nearly flat patch of
 * surface is no part, and merges into its neighbour (method auto, 3-D;
 * runs after the crease merge).
 *
 * A crumb has fewer than PS_PATCH_MERGE_MIN_SHARE of the points, the
 * crease split's smallest piece (crease_split.h): what the boundary cut
 * left of a segment, a bump under a handful of points.  People draw no
 * such part, and whether one survives the other merges turns on the last
 * bits of a rotated copy's coordinates.  While there is one with a
 * neighbour, the smallest (ties: the lowest id) merges into the neighbour
 * it shares the most kNN edges with, whatever that neighbour's size.
 *
 * People see parts that protrude (Hoffman and Singh, "Salience of visual
 * parts", 1997: a part's salience grows with how far it sticks out); a
 * patch whose normals all point about the same way, such as a bump on the
 * back of a hand ringed by shallow grooves, one face of a table top or
 * the flat base of a scan, sticks out of nothing.  Flatness is the length
 * of the mean of the segment's unit normals, R in [0, 1]: 1 for a plane, (1 +
 * cos t) / 2 for a spherical cap of half-angle t, near 0 for a limb, whose
 * normals point all around it.  Then, while some segment has R above
 * PS_PATCH_MERGE_FLATNESS, the flattest (ties: the lowest id) merges into
 * the neighbour it shares the most kNN edges with (ties: the lowest id),
 * unless that neighbour has fewer points: a patch larger than its
 * neighbour is the surface the parts stand on (the palm of a hand scanned
 * from one side), and stays; nor does a patch merge that sticks out of
 * that boundary, its feature size over PS_PATCH_MERGE_PROTRUSION times the
 * boundary's width (ps_segment_protrudes): the fingers of a flat hand or
 * the arms of a star scanned with noise, every piece of which is flat.
 * Rotation and scale invariant; deterministic; no threads.  A flat
 * surface (crease.h, PS_CREASE_FLAT: 2-D points given with z = 0) is one
 * patch: only its crumbs merge.
 */
#ifndef PS_PATCH_MERGE_H
#define PS_PATCH_MERGE_H

#include "features/crease_split.h"
#include "refine/segment_graph.h"

/* A segment this flat (a cap of half-angle 37 degrees) is a patch; the
 * sweep is in docs/method.md, "Constants". */
#define PS_PATCH_MERGE_FLATNESS 0.9
/* A flat patch this many times longer (feature size, in f) than its
 * boundary is wide stays: more than the crease merge asks
 * (PS_CREASE_MERGE_PROTRUSION), since the corner of a noisy square sheet
 * reaches about as far as it is wide. */
#define PS_PATCH_MERGE_PROTRUSION 1.5
/* A crumb's share of the points: one notion of too small to be a part with
 * the crease split's pieces. */
#define PS_PATCH_MERGE_MIN_SHARE PS_CREASE_SPLIT_MIN_FRACTION

/* A ps_merge_fn (segment_graph.h). */
ps_merge_fn ps_patch_merge;

#endif
