/*
 * normals.h: consistently oriented unit normals of a 3-D point set.
 *
 * Given normals (from the input file) are kept; otherwise each point's
 * normal is the least-variance direction (PCA) of itself and its kNN
 * neighbours.  Orientation is then made consistent by propagation over a
 * minimum spanning tree of the kNN graph with edge cost 1 - |n_p . n_q|
 * (Hoppe et al. 1992), rooted at the point farthest from the component's
 * centroid, and made outward per component by two votes, the divergence
 * theorem's and the surface's convexity (normals_outward.h; input normals
 * that point inward, as some meshes' do, are flipped).  No
 * rotation, scaling or reordering of the points changes the result.
 * When asked, estimated normals are then smoothed over the kNN graph, as
 * much as the scan's measured noise asks and not at all on clean input
 * (normals_smooth.h).
 */
#ifndef PS_NORMALS_H
#define PS_NORMALS_H

#include "graph/knn_graph.h"

/* What a build measured and did. */
typedef struct ps_normals_report {
    int smoothing; /* iterations applied: 0 unless smooth and estimated
                      normals on a noisy scan */
    double noise;  /* the median noise ratio (normals_smooth.h); 0 with given
                      normals */
} ps_normals_report;

typedef struct ps_normals_input {
    const ps_graph *graph;   /* kNN graph on #P points; its weights are the Euclidean
                                edge lengths (the noise is measured against them) */
    const double *points;    /* #P by 3 */
    const double *given;     /* #P by 3 normals from the input file, or NULL: PCA */
    const int *component;    /* #P from ps_graph_components */
    int n_components;
    int smooth;              /* smooth estimated normals by the measured noise */
} ps_normals_input;

/* normals #P by 3 out.  report out (may be NULL). */
ps_status ps_normals_build(const ps_normals_input *in, double *normals,
                           ps_normals_report *report, ps_error *err);

/* The same with the PCA on threads (ps_parallel_threads), reporting
 * progress from span->lo to span->hi (span->ctl may be NULL) and stopping
 * with PS_ERR_CANCELLED when its cancel flag is raised.  The normals do
 * not depend on threads. */
ps_status ps_normals_build_tracked(const ps_normals_input *in, int threads,
                                   const ps_progress_span *span, double *normals,
                                   ps_normals_report *report, ps_error *err);

#endif
