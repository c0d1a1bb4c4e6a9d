/*
 * reference_density.h: the sampling density the method is made for.
 *
 * The crease steps compare normals edge by edge, so what they call a
 * crease depends on the spacing of the points; the method's thresholds
 * were chosen on surfaces of about this many points.  A sparser mesh is
 * filled up to it (surface_fill.h), a denser input has its normals
 * smoothed to its scale (normals_smooth.h) and, from three times it on,
 * is segmented in draws of about this many points (ensemble.h).
 */
#ifndef PS_REFERENCE_DENSITY_H
#define PS_REFERENCE_DENSITY_H

/* Points of the reference sampling. */
#define PS_DENSITY_REFERENCE_POINTS 40000

#endif
