/*
 * normals_outward.h: which way is out, per component of consistently
 * oriented normals (the last step of normals.h's orientation).
 *
 * Two votes over each component, each in [-1, 1], positive when the
 * normals point out as they are:
 * - divergence: sum n . (x - c) over sum |x - c|, c the component's
 *   centroid.  Outward normals of a closed surface give a positive sum
 *   (the divergence theorem), whatever its shape;
 * - convexity: over the kNN edges, the angular term 1 - n_p . n_q of the
 *   convex edges less that of the concave ones (crease.h's test), over
 *   their sum.  Seen from outside, what a scanner sees of an object is
 *   mostly convex (limbs, rims, bumps), and turning the normals round
 *   turns every convex edge concave.
 * The component's normals flip when the votes' sum is negative.  On a
 * closed surface the two agree (the 304 PSB models, all points); on an
 * open one, a scan from one side, the divergence has no theorem behind
 * it and goes wrong where the surface seen is a bowl, such as a cup seen
 * from above or a bird's spread wings (docs/method.md, section 1, "Which
 * way is out").  Each vote alone is decisive where the other is weak (a
 * noisy sphere's edges are convex and concave alike; an open sheet's
 * divergence is near 0), so the sum needs no threshold.  Both are votes
 * of every point and edge, so that no single point (an extreme one on a
 * thin fin, whose normal is sideways) decides the sign.  No rotation,
 * scaling or reordering of the points changes the result; no threads.
 */
#ifndef PS_NORMALS_OUTWARD_H
#define PS_NORMALS_OUTWARD_H

#include "graph/graph.h"

/* g: kNN graph on #P points; points #P by 3; component #P in
 * [0, n_components) (ps_graph_components); centroid #n_components by 3,
 * each component's centroid; normals #P by 3 unit normals, consistent
 * within each component, in/out: flipped per component to point out.
 * 0, or -1 when memory runs out (normals untouched). */
int ps_normals_point_outward(const ps_graph *g, const double *points, const int *component,
                             int n_components, const double *centroid, double *normals);

#endif
