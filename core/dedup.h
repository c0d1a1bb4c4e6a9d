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
    size_t n_unique;   /* #U distinct points */
    size_t *unique_of; /* #P: index in 0..#U-1 of each input point */
    size_t *first;     /* #U: lowest input index of each distinct point, increasing */
} ps_dedup;

/* points #P by dim.  Distinct points keep their input order (by first). */
ps_status ps_dedup_build(const double *points, size_t n, int dim, ps_dedup *d,
                         ps_error *err);
void ps_dedup_free(ps_dedup *d);

#endif
