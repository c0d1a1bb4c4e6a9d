/*
 * supernodes.h: phase 1's last step, the supernodes.
 *
 * Every point follows the steepest ascent of f to a sink (flow.h); shallow
 * sinks merge by persistence (persistence.h).  With use_minima, the paper's
 * "minima as well as maxima": a basin is only the part of the shape above
 * its highest saddle (where it meets another basin, the root of a limb),
 * and the points below it, the central regions that have no maximum of
 * their own, form supernodes around the minima of f instead (descent flow,
 * simplified the same way), except where several basins make a part
 * together (a head topped by ears: merge_tree.h).
 */
#ifndef PS_SUPERNODES_H
#define PS_SUPERNODES_H

#include "graph/knn_graph.h"

/* The hierarchy holds a dense #S by #S similarity: when the persistence
 * asked for leaves more supernodes than this, it is doubled until they fit
 * (noisy scans of millions of points), and the result reports the value
 * used. */
#define PS_MAX_SUPERNODES 3000

typedef struct ps_supernodes {
    int m;               /* #S */
    uint32_t *sinks;     /* #S representative vertex: the max (or min) */
    int *is_minimum;     /* #S 1 for a minimum's supernode */
    size_t *sizes;       /* #S vertices */
    int *supernode_of;   /* #P */
} ps_supernodes;

typedef struct ps_supernodes_input {
    const ps_graph *graph;   /* kNN graph on #P points; its weights are the edge lengths */
    const double *f;         /* #P centrality */
    const int *component;    /* #P from ps_graph_components */
    int n_components;
    double persistence;      /* fraction of each component's f range under which sinks
                                merge (0 keeps every sink); raised when needed (see
                                PS_MAX_SUPERNODES) */
    int use_minima;          /* supernodes around the minima of f as well (above) */
    int threads;             /* ps_parallel_threads: with use_minima the ascent and descent
                                flows run side by side; the result is the same for any
                                count */
} ps_supernodes_input;

/* out: the supernodes of the #P points (ps_supernodes_free).
 * *persistence_used out: in->persistence, or the value it was raised to. */
ps_status ps_supernodes_build(const ps_supernodes_input *in, ps_supernodes *out,
                              double *persistence_used, ps_error *err);

/* The same, reporting progress over span (span->ctl may be NULL) after
 * each flow and merge step of the first try. */
ps_status ps_supernodes_build_tracked(const ps_supernodes_input *in,
                                      const ps_progress_span *span, ps_supernodes *out,
                                      double *persistence_used, ps_error *err);
void ps_supernodes_free(ps_supernodes *s);

/* Replaces sn by a refinement of it: label #P gives each point its new
 * supernode in [0, m); a new supernode lies inside one old one and keeps
 * its is_minimum; its representative is its highest point (lowest for a
 * minimum).  Used by the splits (f2_split.h, crease_split.h). */
ps_status ps_supernodes_relabel(ps_supernodes *sn, const int *label, int m, const double *f,
                                size_t n, ps_error *err);

#endif
