/*
 * dedup.h: collapse exactly coincident points.
 *
 * Scans repeat points (and the kNN graph cannot weigh a zero-length edge);
 * the core segments the distinct points and gives each duplicate the label
 * of its representative.
 */
#ifndef PS_DEDUP_H
#define PS_DEDUP_H

#include "pointseg.h"

typedef struct ps_dedup {
    size_t n_unique;     /* #U distinct points */
    uint32_t *unique_of; /* #P: index in 0..#U-1 of each input point */
    uint32_t *first;     /* #U: lowest input index of each distinct point
                            (increasing unless ps_dedup_morton reordered them) */
} ps_dedup;

/* From this many distinct points on, the pipeline (segment.c) renumbers
 * them in Morton order: a big scan in any input order (random, as sampled
 * points are) then walks its arrays nearly in sequence, where random
 * neighbours would miss the caches at every edge (4M random-order horse
 * points: the kNN graph 10.1 -> 3.3 s, normals 8.7 -> 4.1 s, the crease
 * weights 3.3 -> 0.5 s).  Below it everything fits in the caches and the
 * distinct points keep their input order, as do the labels' tie breaks. */
#define PS_DEDUP_MORTON_MIN 131072

/* points #P by dim, #P < UINT32_MAX.  Distinct points keep their input
 * order (by first). */
ps_status ps_dedup_build(const double *points, size_t n, int dim, ps_dedup *d,
                         ps_error *err);

/* 1 when the distinct points are the n input points in their order. */
int ps_dedup_is_identity(const ps_dedup *d, size_t n);

/* Renumbers d's distinct points in the Morton order (morton.h) of their
 * coordinates (points #P by dim, the input d was built on). */
ps_status ps_dedup_morton(ps_dedup *d, const double *points, size_t n, int dim, ps_error *err);
void ps_dedup_free(ps_dedup *d);

#endif
