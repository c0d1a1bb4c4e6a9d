/*
 * morton.h: a spatially coherent order of points (Z-order of their first
 * three coordinates), so that consecutive kd-tree queries touch nearby
 * nodes whatever the input order.
 */
#ifndef PS_MORTON_H
#define PS_MORTON_H

#include "pointseg.h"

/* points #P by dim (dim >= 1); order #P out: a permutation of 0..#P-1 by
 * increasing Morton code (ties by index).  Returns PS_OK or PS_ERR_NOMEM. */
ps_status ps_morton_order(const double *points, size_t n, int dim, uint32_t *order);

#endif
