/*
 * patch_normal.h: normals at a wider scale than the kNN graph's, for the
 * few points a test needs to the degree (the convex merge's samples).
 *
 * A kNN normal is a plane through 7 to 10 points: on a scan with noise of a
 * sixth of the spacing it leans by several degrees even after smoothing
 * (normals_smooth.h), where the convex merge asks whether a point of a
 * beam's flat side lies behind another's tangent plane to about a degree.
 * A patch normal is the plane through the points within
 * PS_PATCH_NORMAL_RINGS rings of p (about 100) whose kNN normals lie
 * within PS_PATCH_NORMAL_AGREE of p's, signed as p's normal: the wider fit
 * averages the noise out, and the agreement keeps a point near an edge
 * on its own side, since the other side's normals turn away.  Where fewer
 * than 4 points agree, p's own normal is kept.  Rotation, scaling and
 * order invariant; deterministic; no threads.
 */
#ifndef PS_PATCH_NORMAL_H
#define PS_PATCH_NORMAL_H

#include "graph/graph.h"
#include "pointseg.h"

#define PS_PATCH_NORMAL_RINGS 5
/* Degrees: chosen on synthetic noisy solids (docs/method.md, section 4). */
#define PS_PATCH_NORMAL_AGREE 25.0

/* g: kNN graph on #P points; points and normals #P by 3 (unit, oriented);
 * ids #m points; out #P by 3: row ids[i] gets that point's patch normal
 * (other rows untouched).  PS_OK, or PS_ERR_NOMEM with err set. */
ps_status ps_patch_normals(const ps_graph *g, const double *points, const double *normals,
                           const uint32_t *ids, size_t m, double *out, ps_error *err);

#endif
