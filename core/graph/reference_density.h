/*
 * reference_density.h: the sampling density the method is made for.
 *
 * The crease steps compare normals edge by edge, so what they call a
 * crease depends on the spacing of the points.  The method's thresholds
 * were chosen at 40,000 points; two thirds of that segments the 228
 * development models as well at two thirds of the time (docs/method.md,
 * "The reference sampling").  A sparser mesh is filled up to it
 * (surface_fill.h), a denser input is segmented in draws of this many
 * points (ensemble.h), and the draws of an input more than
 * PS_ENSEMBLE_MAX_DRAWS times denser have their normals smoothed to its
 * scale (normals_smooth.h).
 */
#ifndef PS_REFERENCE_DENSITY_H
#define PS_REFERENCE_DENSITY_H

/* Points of the reference sampling. */
#define PS_DENSITY_REFERENCE_POINTS 26667

#endif
