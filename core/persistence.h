/*
 * persistence.h: merging the flow's insignificant sinks (topological
 * persistence, as in ToMATo clustering: Chazal, Guibas, Oudot, Skraba 2013).
 *
 * Noise and flat regions (rims, CAD faces, plateaus) give f many shallow
 * local maxima.  Two adjacent basins meet at a saddle: the highest point
 * where they touch, h = max over kNN edges (p, q) joining them of
 * min(f(p), f(q)).  Sweeping the saddles from high to low, the basin whose
 * peak is lower merges into the other when its persistence, f(peak) - h, is
 * below `fraction` times the range of f in its component.  Significant
 * peaks (limb tips) survive; ripples join their neighbour.
 */
#ifndef PS_PERSISTENCE_H
#define PS_PERSISTENCE_H

#include "flow.h"

/* f #P, component #P (n_components of them).  flow is updated in place:
 * fewer sinks (still increasing vertex ids), sink_of remapped.  fraction 0
 * changes nothing. */
ps_status ps_flow_simplify(const ps_graph *g, const double *f, const int *component,
                           int n_components, double fraction, ps_flow *flow,
                           ps_error *err);

#endif
