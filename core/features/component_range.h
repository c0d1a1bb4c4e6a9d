/*
 * component_range.h: the range of a function over each connected
 * component (max f - min f), which the persistence, the merge tree's parts
 * and the refinement measure their thresholds against.
 */
#ifndef PS_COMPONENT_RANGE_H
#define PS_COMPONENT_RANGE_H

#include "pointseg.h"

/* f #P, component #P with values in [0, n_components), every component
 * non-empty.  range #n_components out: max f - min f over each component.
 * Returns 0, or -1 when out of memory. */
int ps_component_range(const double *f, const int *component, size_t n, int n_components,
                       double *range);

/* The same inputs; returns #n_components thresholds, fraction x each
 * component's range (the caller frees), or NULL when out of memory. */
double *ps_component_thresholds(const double *f, const int *component, size_t n,
                                int n_components, double fraction);

#endif
