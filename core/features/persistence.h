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
 * peaks (limb tips) survive; ripples join their neighbour.  A basin of
 * fewer than PS_PERSISTENCE_MIN_BASIN points is noise whatever its height
 * (a spike next to a crease, say) and joins its neighbour at its highest
 * saddle too; the merged basin is represented by the larger peak's sink
 * when the higher peak's basin is the tiny one.
 */
#define PS_PERSISTENCE_MIN_BASIN 16
#ifndef PS_PERSISTENCE_H
#define PS_PERSISTENCE_H

#include "features/flow.h"

typedef struct ps_persistence_input {
    const ps_graph *graph;   /* kNN graph on #P points (weights not used) */
    const double *f;         /* #P the function whose flow is simplified */
    const int *component;    /* #P each point's connected component */
    int n_components;
    double fraction;         /* a basin merges below this x the range of f in its
                                component (0 changes nothing) */
    size_t min_size;         /* basins of fewer points merge whatever their persistence
                                (PS_PERSISTENCE_MIN_BASIN, or 0 for none) */
} ps_persistence_input;

/* flow: in->f's flow (#S sinks) on in->graph, updated in place: fewer
 * sinks (still increasing vertex ids), sink_of #P remapped. */
ps_status ps_persistence_simplify(const ps_persistence_input *in, ps_flow *flow, ps_error *err);

/* A kNN edge joining two basins, at the height where they meet there. */
typedef struct ps_saddle {
    double height; /* min(f(p), f(q)) */
    uint32_t p, q; /* the edge, p < q */
} ps_saddle;

/* Every edge whose ends lie in different basins of flow, sorted from high to
 * low (ties: by p, then q).  *count out.  Returns NULL when out of memory;
 * the caller frees. */
ps_saddle *ps_flow_border_saddles(const ps_graph *g, const double *f, const ps_flow *flow,
                                  size_t *count);

/* Keeps, in order, the saddles of s (#*count) whose ends lie in different
 * basins of flow: after basins merge (ps_persistence_merge), the border saddles
 * of the merged flow from those of the flow before. */
void ps_saddles_keep_borders(const ps_flow *flow, ps_saddle *s, size_t *count);

/* ps_persistence_simplify on flow's border saddles s (#*count, as
 * ps_flow_border_saddles gives them), which become the simplified flow's
 * (*count updated; untouched when nothing merges). */
ps_status ps_persistence_simplify_along(const ps_persistence_input *in, ps_saddle *s,
                                        size_t *count, ps_flow *flow, ps_error *err);

/* Merges the basins as the union-find forest parent (#S) says: each tree
 * becomes its root's basin; surviving sinks keep increasing order and
 * sink_of (#n) is remapped.  new_id #S scratch. */
void ps_persistence_merge(ps_flow *flow, int *parent, int *new_id, size_t n);

#endif
