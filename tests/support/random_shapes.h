/*
 * random_shapes.h: points drawn at random on simple surfaces, for the
 * end-to-end tests (test_segment*.c): balls, plain sheets and box surfaces
 * (shapes without parts), a flat hand and a bent plus (sheets with parts).
 * Beside shapes.h's unions of primitives, these are the shapes a scan of a
 * sheet or a solid gives.  Deterministic: random_bits.h's sequence, seeded
 * by the caller or by a constant of the shape's.
 */
#ifndef PS_RANDOM_SHAPES_H
#define PS_RANDOM_SHAPES_H

#include <stddef.h>
#include <stdint.h>

/* n points drawn at random on a unit sphere centred at (cx, 0, 0), its z
 * stretched by `stretch` (an egg above 1), written to pts #n by 3. */
void ps_random_ball(double *pts, size_t n, double cx, double stretch, uint64_t seed);

/* n points drawn at random on a sheet without parts, by `kind`: 0 a
 * square, 1 a disc, 2 a hemisphere (a cap, open at its rim).  Returns a
 * malloc'ed #n by 3 array (free it), NULL without memory. */
double *ps_plain_sheet(int kind, size_t n);

/* n points drawn at random, uniform by area, on the closed surface of an
 * a by b by c box (its six sides).  Returns a malloc'ed #n by 3 array
 * (free it), NULL without memory. */
double *ps_random_box(double a, double b, double c, size_t n, uint64_t seed);

/* A flat hand in the plane z = 0: a unit disc (part 0) and five strips
 * (parts 1..5) fanning out from it, sampled uniformly.  Returns a malloc'ed
 * #P by 3 array and sets *n = #P and *part to a malloc'ed #P array of part
 * ids (free both; either NULL without memory). */
double *ps_flat_hand(size_t *n, int **part);

/* A plus-shaped sheet (arms 2 wide reaching `reach` from the centre) bent
 * round a cylinder of radius 3: an open surface with no concave edge,
 * whose parts are its outline's.  Part 0 the centre square, 1..4 the
 * arms.  Returns a malloc'ed #P by 3 array and sets *n = #P and *part to a
 * malloc'ed #P array of part ids (free both; either NULL without memory). */
double *ps_bent_plus(double reach, size_t *n, int **part);

#endif
