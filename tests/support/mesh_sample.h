/*
 * mesh_sample.h: points sampled uniformly by area on a triangle mesh, for
 * the benchmarks' scan-like inputs (bench_speed's 1M horse, bench_quality's
 * surface:N and uneven:N modes), and the area itself (--scan-noise's
 * spacing).  Deterministic: the same mesh and seed give the same
 * points on every machine.
 */
#ifndef PS_MESH_SAMPLE_H
#define PS_MESH_SAMPLE_H

#include <stddef.h>
#include <stdint.h>

#include "pointset.h"

/* Writes n points uniform by area on mesh's #F by 3 triangles into the
 * malloc'ed #n by 3 array *out (xorshift64 seeded by seed).  0, or -1 when
 * the mesh has no faces of positive area or memory runs out. */
int ps_mesh_sample_surface(const ps_pointset *mesh, size_t n, uint64_t seed, double **out);

/* The mesh's surface area: the sum of its #F triangles' areas. */
double ps_mesh_area(const ps_pointset *mesh);

/* The low and high corners of the bounding box of the mesh's #P vertices
 * (both 0 without vertices). */
void ps_mesh_bounds(const ps_pointset *mesh, double lo[3], double hi[3]);

/* The same, but with the density falling linearly along the longest axis
 * of the mesh's bounding box, from 1 at its low end to `far` (0 < far <= 1)
 * at its high end, like a scan taken from one side: uniform samples kept
 * with that probability until n are kept. */
int ps_mesh_sample_graded(const ps_pointset *mesh, size_t n, double far, uint64_t seed,
                          double **out);

#endif
