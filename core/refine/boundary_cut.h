/*
 * boundary_cut.h: moves each boundary between two adjacent segments onto
 * the cheapest cut nearby, preferring concave creases (method auto, 3-D;
 * runs after refinement).
 *
 * The hierarchy finds the right parts, but its boundaries follow level sets
 * of the centrality f, not the creases where people cut.  For each pair of
 * adjacent segments (A, B), smaller pairs first (by the smaller segment's
 * size, then the larger's, then ids), within the kNN graph restricted to
 * A and B:
 *   - band: the points within geodesic (Euclidean edge length) distance
 *     w of the shared boundary, w = PS_BOUNDARY_CUT_BAND x the smaller of
 *     the two segments' extents (each segment's largest distance from the
 *     boundary), so the band scales with the part and never swallows it,
 *     and at most PS_BOUNDARY_CUT_MAX_EDGES mean edge lengths;
 *   - network: band points; A's points outside the band are tied to the
 *     terminal s, B's to t, and every supernode's sink point to its own
 *     side (sinks never move, so no segment loses all its supernodes);
 *   - capacities: c(p,q) = |p-q| / L x exp(-ang(p,q) / A0), ang the
 *     concave angular term of crease.h (0 on convex edges), L the mean edge
 *     length and A0 = PS_BOUNDARY_CUT_ANGLE x the mean angular term, over
 *     the whole graph: the minimum cut is a short loop, through concave
 *     edges where there are some;
 *   - the band is relabelled by the minimum cut (maxflow.h); a piece of A or
 *     B the cut left inside the band, apart from the rest of its segment,
 *     goes to the other one (the largest piece always stays), and a pair
 *     whose cut would leave a segment without a sink point is undone.
 * Finally a point whose supernode's sink is now in another segment joins
 * the supernode of a neighbour in its own segment (breadth first), so a
 * supernode's points all lie in the segment holding its sink.
 * Pairs that share no segment run side by side, on up to
 * PS_BOUNDARY_CUT_WORKERS threads when the input has at most
 * PS_BOUNDARY_CUT_SIDE_BY_SIDE points (each worker holds its own per-point
 * scratch in one block, about 340 bytes a point allocated, 20 of them
 * touched for every point, the rest over the largest band); a pair waits for every earlier pair that shares a segment with
 * it, so the result is the same for any thread count.  Progress is
 * reported after each pair, and a raised cancel flag stops it between
 * pairs.
 */
#ifndef PS_BOUNDARY_CUT_H
#define PS_BOUNDARY_CUT_H

#include "features/crease.h"
#include "graph/knn_graph.h"

/* The constants (docs/method.md, "Constants", has their sweeps): */
#define PS_BOUNDARY_CUT_BAND 0.3      /* the band's width over the smaller extent */
#define PS_BOUNDARY_CUT_ANGLE 0.5     /* A0 over the mean angular term */
/* The band's width at most, in mean edge lengths: the cost grows with the
 * boundary's length, not the parts' area. */
#define PS_BOUNDARY_CUT_MAX_EDGES 10
#define PS_BOUNDARY_CUT_WORKERS 2              /* pairs side by side at most */
#define PS_BOUNDARY_CUT_SIDE_BY_SIDE 131072    /* points up to which they may be */

typedef struct ps_boundary_cut_input {
    const ps_graph *graph;   /* kNN graph on #P points (its weights are not used) */
    const double *points;    /* #P by 3 */
    const double *normals;   /* #P by 3, outward unit normals (normals.h) */
    ps_edge_scales scales;   /* of graph over normals (ps_crease_scales; the
                                metric's pass gives them too) */
    int n_groups;            /* segment ids are in [0, n_groups) */
    int n_supernodes;        /* #S */
    const uint32_t *sinks;   /* #S sink point of each supernode */
    const ps_progress_span *span; /* progress over the pairs, and cancel; may be NULL */
    int threads;             /* ps_parallel_threads (0: all cores) */
} ps_boundary_cut_input;

/* group #P in/out: each point's segment; supernode_of #P in/out: each
 * point's supernode, consistent with group on input (a supernode's points
 * share a segment).  Both are rewritten as described above.  Fails with
 * PS_ERR_CANCELLED (group and supernode_of then half done) when the span's
 * cancel flag is raised. */
ps_status ps_boundary_cut(const ps_boundary_cut_input *in, int *group, int *supernode_of,
                          ps_error *err);

#endif
