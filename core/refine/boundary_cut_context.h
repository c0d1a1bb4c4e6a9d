/*
 * boundary_cut_context.h: PRIVATE to the boundary cut, not part of the
 * public API; only boundary_cut.c (the driver), boundary_cut_band.c (a
 * pair's boundary, band and flow network) and boundary_cut_pieces.c (the
 * keep-largest-piece search) include it.  The public interface is
 * boundary_cut.h.
 *
 * It holds the state one ps_boundary_cut call shares between those files
 * (every scratch array sized once, for #P points, #E graph arcs and
 * #groups segments) and the functions one of them calls in another.
 * Pairs that share no segment may run side by side (boundary_cut.c), one
 * cut_context per worker: the fields marked "shared" point at the same
 * arrays in every worker's context, and a pair writes in them only what
 * belongs to its own two segments (their points, their counts, the arcs
 * out of their points); its cut_scratch is its own.
 */
#ifndef PS_BOUNDARY_CUT_CONTEXT_H
#define PS_BOUNDARY_CUT_CONTEXT_H

#include "graph/dijkstra.h"
#include "refine/boundary_cut.h"
#include "util/maxflow.h"

#include <stddef.h>
#include <stdint.h>

#define NOT_IN_BAND UINT32_MAX
#define NO_WITNESS UINT32_MAX
#define WITNESSES 6 /* per segment: its lowest and highest point along x, y and z */
#define OUTSIDE_A 1 /* a band point's neighbour outside the band in a (outside) */
#define OUTSIDE_B 2 /* ... in b */

/* A point on the boundary between segments a < b at the start. */
typedef struct boundary_entry {
    int a, b;
    uint32_t point;
} boundary_entry;

/* Points moved into each segment by the cuts so far, one list per segment,
 * oldest first: only the pairs of a segment, which run one after the
 * other, append to its list or read it. */
typedef struct move_log {
    uint32_t **point;   /* #groups lists */
    size_t *count;      /* #groups */
    size_t *capacity;   /* #groups */
} move_log;

/* A worker's own scratch, every array sized once.  Between pairs band_of
 * is NOT_IN_BAND and dist INFINITY at every point, the Dijkstra heap is
 * empty, and no stamp in seen, visited or region_mark is above stamp. */
typedef struct cut_scratch {
    void *block;               /* the arrays below but the Dijkstra and max flow
                                  workspaces, in one allocation */
    uint32_t *sources;         /* #P the pair's boundary points, the ball's sources */
    size_t n_sources;
    ps_dijkstra *dijkstra;     /* for #P vertices */
    uint32_t stamp;            /* bumped for each ball, boundary and piece search */
    uint32_t *region_mark;     /* #groups stamp of the segment a ball may enter */
    uint32_t *seen;            /* #P stamp of the boundary candidates checked */
    uint32_t *visited;         /* #P stamp of the points a piece search reached */
    double *dist;              /* #P INFINITY outside a pair's ball */
    uint32_t *reached;         /* #P */
    uint32_t *band_of;         /* #P band index of each point, or NOT_IN_BAND */
    uint32_t *band;            /* #P band points, increasing */
    int *old_group;            /* #P group of each band point before the cut */
    double *tie_a;        /* #P */
    double *tie_b;          /* #P */
    unsigned char *outside;    /* #P OUTSIDE_A | OUTSIDE_B: band point i has neighbours
                                  outside the band in a, in b */
    size_t *net_offsets;       /* #P+3 */
    uint32_t *net_heads;       /* #E+4#P+1 */
    double *net_capacity;      /* #E+4#P+1 */
    unsigned char *side;       /* #P+2 */
    ps_maxflow_workspace *flow_space;  /* reused by every pair's max flow */
    int *piece;                /* #P piece of each band point of the segment searched */
    uint32_t *piece_start;     /* #P first band index of each piece (its lowest point) */
    size_t *piece_size;        /* #P */
    unsigned char *anchored;   /* #P 1 for a piece with a neighbour outside the band */
    uint32_t *queue;           /* #P: the breadth-first queues (pieces, supernodes), and
                                  the scratch of the band's sort before them */
} cut_scratch;

typedef struct cut_context {
    const ps_boundary_cut_input *in;
    int *group;                /* #P in/out, shared (read with ps_bc_group) */
    size_t *size;              /* #groups points of each segment, kept current; shared */
    size_t *sinks_in;          /* #groups sink points of each segment, kept current; shared */
    double *capacity;          /* #E cut capacity of each graph arc, 0 until needed; shared */
    unsigned char *is_sink;    /* #P, shared */
    double mean_edge;          /* mean Euclidean kNN edge length L */
    double angle_scale;        /* A0 of the capacities */
    int creased;               /* 0 on a flat shape: capacities are lengths alone */
    move_log *moves;           /* shared */
    uint32_t *witness;         /* #groups by WITNESSES extreme points of each segment at
                                  the start (NO_WITNESS: none), see far_beyond; shared */
    boundary_entry *initial;   /* #I initial boundary points, sorted by (a, b, point); shared */
    size_t n_initial;
    cut_scratch s;             /* the worker's own */
} cut_context;

/* Segment of p.  A point outside a running pair's segments may be moving
 * between the segments of another pair at that moment; it reads as some
 * other segment either way, and relaxed atomic loads and stores (here and
 * in ps_bc_set_group) keep such concurrent reads well defined. */
static inline int ps_bc_group(const cut_context *cx, uint32_t p) {
    return __atomic_load_n(&cx->group[p], __ATOMIC_RELAXED);
}

/* boundary_cut.c */

/* The cut capacity of graph arc e out of point p (boundary_cut.h),
 * computed and stored for e and its reverse arc; both ends of e lie in the
 * running pair's segments. */
double ps_bc_new_capacity(cut_context *cx, uint32_t p, size_t e);

/* The cut capacity of graph arc e out of point p, computed on first use
 * (0 marks an arc not computed yet); both ends of e lie in the running
 * pair's segments. */
static inline double ps_bc_capacity(cut_context *cx, uint32_t p, size_t e) {
    double c = cx->capacity[e];
    return c != 0.0 ? c : ps_bc_new_capacity(cx, p, e);
}

/* Point p (< #P) joins segment g: group[p] and the per-segment
 * size and sinks_in counts of cx are updated; nothing if p is in g. */
void ps_bc_set_group(cut_context *cx, uint32_t p, int g);

/* boundary_cut_band.c; a < b are the pair's segments throughout. */

/* Lists the pair's current boundary points (in a or b, next to the other)
 * in sources, bumping the stamp.  Returns their count, 0 when the pair no
 * longer touches. */
size_t ps_bc_boundary_points(cut_context *cx, int a, int b);

/* The distances from the pair's boundary (Euclidean edge lengths, each
 * segment's from its own boundary points) of the points the band's width
 * depends on or may take: dist for them and reached[0..count), the count
 * returned.  *width out: the band's half-width, PS_BOUNDARY_CUT_BAND x the
 * smaller segment's extent (its largest distance; reach, the distance
 * from which the width is capped, for a segment extending beyond it), at
 * most PS_BOUNDARY_CUT_MAX_EDGES x mean_edge.  Every point within *width
 * is reached.  Bumps the stamp; call after ps_bc_boundary_points (it
 * reorders the sources). */
size_t ps_bc_boundary_distances(cut_context *cx, int a, int b, double reach, double *width);

/* The reached points within width become band[0..nb) in point order, with
 * band_of, old_group, the terminal ties tie_a / tie_b (to a's side, s, and b's, t) (#nb each;
 * infinite for a sink point) and outside (#nb); the band's arcs go to the net_*
 * arrays, each band point's from net_offsets[i] on, two slots apart, for
 * ps_bc_build_network.  Returns nb. */
size_t ps_bc_mark_band(cut_context *cx, size_t n_reached, double width, int a, int b);

/* net: the band's flow network, #nb+2 nodes (band nodes 0..nb-1,
 * terminals s = nb and t = nb+1), over cx's net_* arrays (after ps_bc_mark_band).  Returns 0 (net unset) when a
 * terminal has no tie, so there is nothing to cut; else 1. */
int ps_bc_build_network(cut_context *cx, size_t nb, ps_maxflow_graph *net);

/* boundary_cut_pieces.c */

/* Pieces of segment x the cut left wholly inside band[0..nb), except the
 * largest of all x's pieces (ties: the lowest point), join segment y
 * (through ps_bc_set_group); x and y are the pair's segments, and the band
 * is the flow network's (net_* and outside as ps_bc_mark_band and
 * ps_bc_build_network left them). */
void ps_bc_keep_largest_piece(cut_context *cx, size_t nb, int x, int y);

#endif
