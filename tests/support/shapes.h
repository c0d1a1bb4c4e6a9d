/*
 * shapes.h: synthetic point sets with known parts, made by code so tests and
 * benchmarks need no data files.  Every generator is deterministic (seeded
 * xorshift), samples the surface roughly uniformly, and writes part ids.
 *
 * Each returns a malloc'ed #P by 3 array (free it) and sets *n; part, if not
 * NULL, receives a malloc'ed #P array of part ids (0 = the body/core, 1.. =
 * the protrusions).  `density` is points per unit area (the shapes are about
 * 2 to 10 units across); pass 0 for the default (a few thousand points).
 */
#ifndef PS_SHAPES_H
#define PS_SHAPES_H

#include <stddef.h>

/* two spheres (radius 1, centres 4 apart) joined by a tube of radius 0.25:
 * parts 1 and 2 are the spheres, 0 the tube. */
double *ps_shape_dumbbell(double density, size_t *n, int **part);

/* a palm (flattened ellipsoid) with five fingers (capsules) of different
 * lengths spread in a fan: part 0 palm, 1..5 fingers. */
double *ps_shape_hand(double density, size_t *n, int **part);

/* a central sphere with six arms (capsules) along +-x, +-y, +-z:
 * part 0 the centre, 1..6 the arms. */
double *ps_shape_star(double density, size_t *n, int **part);

/* a unit sphere surface (one part, 0). */
double *ps_shape_sphere(double density, size_t *n, int **part);

/* Applies x -> s * R x + t to #P by 3 points in place, R the rotation by
 * `angle` radians about the unit axis (ax, ay, az). */
void ps_shape_transform(double *pts, size_t n, double ax, double ay, double az,
                        double angle, double s, const double t[3]);

#endif
