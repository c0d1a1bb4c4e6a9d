/*
 * normals_smooth.h: how noisy a scan is, and PCA normals smoothed to match.
 *
 * PCA normals from k = 7 neighbours follow the noise of a scan: with
 * Gaussian noise of a quarter of the point spacing the crease steps of
 * method auto see creases everywhere (PSB dev 0.116 -> 0.236, bench_quality
 * --noise 0.25).  The noise is measured as the median, over the points, of
 * the RMS distance of a point's neighbourhood to its PCA plane divided by
 * the point's mean kNN edge length.  On clean surfaces that ratio stays
 * below about 0.10 (curvature alone: the 38 PSB dev meshes give 0 to 0.10);
 * noise of 0.1, 0.25, 0.5 spacings gives about 0.09, 0.18, 0.28.  When
 * asked (ps_params.smooth_normals, on by default: docs/method.md has the
 * figures), above PS_NOISE_FLOOR the oriented normals are averaged with their
 * kNN neighbours, one iteration per PS_NOISE_STEP of the ratio above the
 * floor, at most PS_SMOOTH_MAX: clean input is left exactly as it was.
 *
 * Density.  The crease steps compare normals edge by edge, so what they
 * call a crease depends on the spacing: the facets of a coarse mesh
 * sampled densely, or a rounded bend, look sharper against the mean
 * angular term the closer the points.  PCA normals from k neighbours
 * average over about k spacings squared of surface, and each smoothing
 * iteration adds about as much again; so n points smoothed n /
 * PS_DENSITY_REFERENCE_POINTS - 1 times average over as much surface as
 * the reference sampling's raw normals, and the crease steps see the same
 * creases at any density above it (fractional iterations blend the last
 * one in; at most PS_SMOOTH_MAX, so beyond about 360,000 points the scale
 * shrinks again).  Below the reference nothing changes; an input is
 * segmented in draws of the reference sampling (ensemble.h) up to
 * PS_ENSEMBLE_MAX_DRAWS times it, so only denser draws than that smooth.
 */
#ifndef PS_NORMALS_SMOOTH_H
#define PS_NORMALS_SMOOTH_H

#include "graph/knn_graph.h"
#include "graph/reference_density.h"

/* The constants (docs/method.md, "Constants", has their sweeps): */
#define PS_NOISE_FLOOR 0.12 /* noise ratio above which normals are smoothed */
#define PS_NOISE_STEP 0.02  /* one iteration per this much of the ratio above it */
#define PS_SMOOTH_MAX 8     /* iterations at most */
#define PS_NOISE_BINS 1024 /* histogram of the ratio over [0, 1) */

typedef struct ps_noise_estimate {
    size_t counts[PS_NOISE_BINS]; /* ratios >= 1 go to the last bin */
    size_t n;
} ps_noise_estimate;

/* Adds one point's ratio (residual / mean edge length, >= 0). */
void ps_noise_add(ps_noise_estimate *e, double ratio);

/* The median ratio (the middle of its bin); 0 when nothing was added. */
double ps_noise_median(const ps_noise_estimate *e);

/* Whether a median ratio is clean: at most PS_NOISE_FLOOR (or not a
 * number), so the scan needs no smoothing. */
int ps_noise_clean(double noise);

/* Smoothing iterations for a median ratio: 0 when clean. */
int ps_noise_iterations(double noise);

/* Smoothing iterations that bring the normals of n points to the scale of
 * the reference sampling: n / PS_DENSITY_REFERENCE_POINTS - 1, 0 below it,
 * at most PS_SMOOTH_MAX; fractional. */
double ps_density_iterations(size_t n);

/* normals #P by 3 in/out (unit, consistently oriented): each iteration
 * replaces every normal by the normalized sum of itself and its kNN
 * neighbours' normals (all at once); a fractional last iteration blends
 * each normal with that average by its fraction.  iterations <= 0 leaves
 * them alone.  threads: as ps_parallel_threads; the result does not
 * depend on it. */
ps_status ps_normals_smooth(const ps_graph *g, double *normals, double iterations, int threads,
                            ps_error *err);

#endif
