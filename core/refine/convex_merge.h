/*
 * convex_merge.h: two adjacent segments whose union is convex are one part
 * (method auto, 3-D; runs after the crease merge, before the patch merge).
 *
 * People cut a shape into nearly convex pieces (Hoffman and Richards' minima
 * rule cuts at concavities; approximate convex decomposition, e.g. Kaick et
 * al., "Shape segmentation by approximate convexity analysis", 2014, uses
 * convexity as the test of a part).  A creased boundary alone does not make
 * two parts: a face's features crease the head of a bust everywhere.  Two
 * segments A and B together are convex when each lies behind the other's
 * tangent planes: for points p of A and q of B, (q - p) . n_p <= 0 and
 * (p - q) . n_q <= 0, with n the outward normals, each up to
 * PS_CONVEX_MERGE_TOLERANCE times |q - p| (a pair on one flat side, such
 * as the two halves of a beam have by the thousand, would pass or fail by
 * the estimated normals' last fraction of a degree).  A limb fails it against
 * its body (it stands above the body's tangent planes near its root), as do
 * a table's legs against its top and a wing against its fuselage.  The
 * normals are patch normals (patch_normal.h): a scan's kNN normals lean
 * by several degrees under noise of a sixth of the spacing, and a noisy
 * beam, board or cube failed the test in pieces.  Convexity is evidence
 * only where the union has depth: the points of a flat sheet all lie in
 * each other's tangent planes, so a flat hand is "convex" whatever its
 * outline, where its parts are.  So at least PS_CONVEX_MERGE_DEPTH of the
 * pairs must have one point behind the other's plane by more than the
 * tolerance (a noisy flat hand's pairs 0.04 to 0.13, a beam's, a board's or a
 * cube's 0.57 to 0.90).
 *
 * Each segment keeps a sample of at most PS_CONVEX_MERGE_SAMPLES of its
 * points: evenly spaced through its points in index order at the start;
 * a merged segment's sample is taken from the two samples in proportion to
 * the segments' sizes.  A pair's convexity is the fraction of the sample
 * pairs (p, q) that pass, 0 without the depth.  A pair is judged on two kinds of evidence
 * together: a boundary creased nearly all along (more than
 * PS_CONVEX_MERGE_OPEN_CREASED of its edges, by the crease merge's test)
 * needs a convexity of PS_CONVEX_MERGE_FRACTION to merge; a boundary that
 * crosses smooth surface for part of its length only
 * PS_CONVEX_MERGE_OPEN (a fuselage cut into nose, middle and tail around
 * the wing roots, a bird's body cut behind its wings: nearly convex
 * across the cut, but creased just over the crease merge's half).  While
 * some adjacent pair reaches its threshold, the most convex of them (ties:
 * the first in (a, b) order) merges, the smaller segment into the larger
 * (ties: the higher id into the lower); the creased edges add up.
 * Rotation and scale invariant; deterministic; no threads; O(points) to
 * set up, then O(pairs x samples^2) per merge.  A flat surface (crease.h,
 * PS_CREASE_FLAT) has no depth anywhere and is left alone.
 */
#ifndef PS_CONVEX_MERGE_H
#define PS_CONVEX_MERGE_H

#include "refine/segment_graph.h"

/* Sample points per segment. */
#define PS_CONVEX_MERGE_SAMPLES 48
/* How far in front of a tangent plane a point still counts as behind it,
 * in its distance (about 1 degree).  Chosen on synthetic beams and boards
 * and the 228 development models (docs/method.md). */
#define PS_CONVEX_MERGE_TOLERANCE 0.02
/* The share of a pair's sample pairs with one point behind the other's
 * tangent plane (by more than the tolerance) that its union needs to be
 * judged convex at all.  Chosen on synthetic flat hands and solids (see
 * above); on the 228 development models 0.25 and 0.4 move no label of the
 * whole surface (docs/method.md). */
#define PS_CONVEX_MERGE_DEPTH (1.0 / 3)
/* Convexity at which a pair merges.  Chosen on the 228 development models
 * (docs/method.md). */
#define PS_CONVEX_MERGE_FRACTION 0.95
/* ... and the lower convexity at which a pair merges when at most
 * PS_CONVEX_MERGE_OPEN_CREASED of its boundary is creased (the crease
 * merge's test, crease_merge.h).  Chosen on the 228 development models
 * (docs/method.md). */
#define PS_CONVEX_MERGE_OPEN 0.85
#define PS_CONVEX_MERGE_OPEN_CREASED 0.85

/* A ps_merge_fn (segment_graph.h). */
ps_merge_fn ps_convex_merge;

#endif
