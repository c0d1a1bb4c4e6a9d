/*
 * input_scale.h: PRIVATE to the top of core/ (segment.c, memory_estimate.c):
 * the power of two ps_segment scales a point set by, so that the method's
 * arithmetic runs at the magnitudes it runs at on ordinary input, and its
 * result back to the caller's units.
 *
 * The squared distance of points 1e-160 apart underflows to 0 (the kNN
 * search then takes any points for neighbours), the single-precision
 * distances of the kNN ties and of the coarse centrality lose their digits
 * below 1e-38 and overflow above 3e38, and the PCA's sweeps stop at an
 * absolute 1e-30: the hand scaled by 2^-48 or 2^150 moved labels, by
 * 2^-600 fell into 239 components.  A scaling by a power of two is exact,
 * so a point set whose typical extent lies outside
 * [2^PS_SCALE_MIN_EXPONENT, 2^PS_SCALE_MAX_EXPONENT] is segmented as its
 * copy of extent about 1, and gets that copy's labels; a point set inside
 * is segmented as it is.  The extent, not the distance from the origin:
 * a small object far from the origin (1e-12 across at 1e-3) is as small,
 * and a large one far away must not be scaled to a speck.
 */
#ifndef PS_INPUT_SCALE_H
#define PS_INPUT_SCALE_H

#include "pointseg.h"

#define PS_SCALE_MIN_EXPONENT (-16)
#define PS_SCALE_MAX_EXPONENT 64
#define PS_SCALE_CEILING_EXPONENT 498 /* 2^498 < PS_MAX_COORDINATE */

/* e such that the #n by dim points times 2^e have their typical extent
 * (the median over the points of the largest |coordinate - that axis's
 * median|: a few far outliers do not move it, nor does a place far from
 * the origin) in [0.5, 1): 0 when it lies within the range above already,
 * or without memory; a scaling up stops short of moving a coordinate past
 * 2^PS_SCALE_CEILING_EXPONENT.  *short_of (short_of may be NULL): 1 when
 * it stopped so short that the extent stays below the range (a tiny
 * extent beside coordinates some 2^514 times larger, where the arithmetic
 * does not hold: segment.c refuses such a point set), else 0. */
int ps_input_scale_exponent(const double *points, size_t n, int dim, int *short_of);

/* r's values in the points' units (centralities, feature sizes) times
 * 2^-e: the caller's units again after a run on the points times 2^e. */
void ps_result_unscale(ps_result *r, int e);

#endif
