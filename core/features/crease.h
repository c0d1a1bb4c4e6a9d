/*
 * crease.h: a concavity-aware metric on the kNN graph.
 *
 * People cut shapes along concave creases (where a limb meets a body), and
 * nothing in plain geodesic distance sees a crease.  Following Katz and Tal
 * (2003), each edge's length becomes a blend of its Euclidean length and an
 * angular distance that is large across concave creases:
 *
 *   w'(p,q) = L * [ DELTA * |p-q| / L + (1 - DELTA) * ang(p,q) / A ]
 *   ang(p,q) = eta * (1 - n_p . n_q),  eta = 1 if the edge is concave,
 *                                      ETA_CONVEX if convex
 *
 * with L and A the mean Euclidean length and mean angular term over all
 * edges (so the metric is scale free and its two parts weigh alike).  An
 * edge is concave when the outward normals close in along it:
 * (n_q - n_p) . (q - p) < 0 (the convexity test of LCCP, Stein et al. 2014).
 * docs/method.md ("Constants") has the sweeps behind the constants.
 */
#define PS_CREASE_DELTA 0.7 /* weight of the Euclidean part */
/* A surface whose mean angular term is below this is flat (a plane, or
 * 2-D points given with z = 0): it has no creases, and the crease steps
 * (metric, split, merge, the cut's preference) leave it alone.  1 - cos of
 * 0.08 degrees. */
#define PS_CREASE_FLAT 1e-6
#define PS_CREASE_ETA_CONVEX 0.0 /* eta of a convex edge */
/* The crease scale: the crease split and merge read normals smoothed this
 * many times in all, counting the smoothing against noise
 * (normals_smooth.h; ps_crease_scale_iterations), so that a crease must
 * hold at that scale and the sharp facet edges of a coarse mesh sampled
 * densely do not cut thin parts into rings.  Noisy normals left
 * unsmoothed stay so. */
#define PS_CREASE_SCALE_SMOOTHING 2
/* A crease must stand out of the surface's own noise: the crease split's
 * points are at least this many times the median crease strength
 * (ps_crease_points.median; the merges' creased edges have their own
 * factor, PS_CREASE_MERGE_NOISE in crease_merge.h).
 * Noise bends the normals everywhere alike; on clean shapes most points
 * lie on convex or flat surface and the median is 0 or nearly so (under
 * 0.34 mean angular terms on the PSB models, about 2 on noisy scans). */
#define PS_CREASE_NOISE 3.0
#ifndef PS_CREASE_H
#define PS_CREASE_H

#include "graph/knn_graph.h"

/* The scales of a kNN graph's edges over given normals, which the metric
 * and the boundary cut (boundary_cut.h) measure their edges by. */
typedef struct ps_edge_scales {
    double mean_length;   /* L: mean Euclidean length of the arcs */
    double mean_concave;  /* mean angular term with eta_convex 0 (concave arcs only) */
} ps_edge_scales;

/* g's edge scales over points #P by 3 and normals #P by 3 (outward,
 * unit), on threads (ps_parallel_threads) threads; the same for any count.
 * g's weights must be its Euclidean edge lengths, as the kNN graph is
 * built (not yet rewritten by ps_crease_weights). */
ps_status ps_crease_scales(const ps_graph *g, const double *points, const double *normals,
                           int threads, ps_edge_scales *scales, ps_error *err);

/* points #P by 3, normals #P by 3 (outward, unit).  Rewrites g->weights,
 * which must be its Euclidean edge lengths as the kNN graph is built (the
 * weighing computes them again from the points, ps_distance3), on threads
 * (ps_parallel_threads) threads; the same for any count.
 * scales out (may be NULL): g's scales as ps_crease_scales gives them, from
 * the same pass.  spacing #P out (may be NULL): each point's mean edge
 * length before the rewrite (0 without edges), from the same pass. */
ps_status ps_crease_weights(ps_graph *g, const double *points, const double *normals,
                            int threads, ps_edge_scales *scales, double *spacing,
                            ps_error *err);

/* An edge is concave when (n_q - n_p) . (q - p) < 0 by more than this
 * fraction of |n_q - n_p| |q - p|: where the two are nearly perpendicular
 * (points side by side on the two faces of a thin slab, normals opposite)
 * the sign is rounding, and a rotated copy flipped it (PSB 114). */
#define PS_CREASE_CONCAVE_TOLERANCE 1e-9

/* The angular term of one edge: eta * (1 - n_p . n_q), eta 1 when the edge
 * is concave, eta_convex otherwise.  p, q: 3 coordinates; np, nq: their
 * unit normals.  Symmetric in (p, np) and (q, nq). */
static inline double ps_crease_angular(const double *p, const double *np, const double *q,
                                       const double *nq, double eta_convex) {
    double cosine = np[0] * nq[0] + np[1] * nq[1] + np[2] * nq[2];
    double dn[3] = {nq[0] - np[0], nq[1] - np[1], nq[2] - np[2]};
    double dq[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    double opening = dn[0] * dq[0] + dn[1] * dq[1] + dn[2] * dq[2];
    const double tolerance2 = PS_CREASE_CONCAVE_TOLERANCE * PS_CREASE_CONCAVE_TOLERANCE;
    /* Both tests always, and eta picked by index: no branch on the sign,
     * which is a coin toss where smoothed normals are nearly parallel. */
    int concave = (opening < 0) &
                  (opening * opening > tolerance2 *
                                           (dn[0] * dn[0] + dn[1] * dn[1] + dn[2] * dn[2]) *
                                           (dq[0] * dq[0] + dq[1] * dq[1] + dq[2] * dq[2]));
    const double eta[2] = {eta_convex, 1.0};
    return eta[concave] * (1 - cosine);
}

/* How strongly each point lies on a concave crease: strength[p] is p's
 * largest angular term (eta_convex 0) over its incident edges; mean is the
 * mean angular term over all edges (0 for none), the scale the crease
 * steps measure strengths against, and median the median strength, the
 * surface's own noise (PS_CREASE_NOISE). */
typedef struct ps_crease_points {
    double *strength;  /* #P */
    double mean;
    double median;
} ps_crease_points;

/* The smoothing iterations the crease steps' normals take beyond the
 * normals themselves: PS_CREASE_SCALE_SMOOTHING in all, counting the
 * `smoothed` ones against noise (normals_smooth.h); none for noisy
 * normals left unsmoothed, whose noise smoothing would turn into blobs
 * that close loops.  noisy: the noise measure is over its floor. */
int ps_crease_scale_iterations(int noisy, int smoothed);

/* cp->strength: #P, allocated by the caller; all fields are written, on
 * threads threads; the same for any count. */
ps_status ps_crease_strengths(const ps_graph *g, const double *points, const double *normals,
                              int threads, ps_crease_points *cp, ps_error *err);

/* cp->median from cp->strength (#n; 0 for none), on a copy; after the
 * strengths change (ps_crease_strengths calls it). */
ps_status ps_crease_median(size_t n, ps_crease_points *cp, ps_error *err);

#endif
