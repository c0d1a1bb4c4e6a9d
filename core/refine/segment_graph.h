/*
 * segment_graph.h: segments as the nodes of a small graph whose edges are
 * their shared boundaries, for the merges that run after the boundary cut
 * (crease_merge.h, patch_merge.h).
 *
 * The boundaries are gathered once, in O(E): one record per kNN edge
 * joining two segments, with whether the caller marks it (the crease
 * merge marks the creased ones), sorted and summed into one record per
 * adjacent pair.  A merge renames the loser in every record and sums the
 * records again; there are only as many records as adjacent pairs, so the
 * merges are cheap.  Each segment keeps its point count and f range, so
 * a merge can be recorded with its feature size (ps_merge).  Given the
 * points, a boundary also keeps the sums that give its width
 * (ps_boundary_width).
 */
#ifndef PS_SEGMENT_GRAPH_H
#define PS_SEGMENT_GRAPH_H

#include "graph/knn_graph.h"

typedef struct ps_boundary {
    int a, b;     /* segment ids, a < b */
    long marked;  /* edges the caller's mark accepted */
    long edges;   /* kNN edges joining a and b */
    double midpoint_sum[3]; /* sum of the edges' midpoints, relative to point
                               0 (0 without points) */
    double norm2_sum;       /* sum of their squared norms */
    size_t position;        /* the record's index before a sort: ties keep
                               their order whatever qsort the C library has */
} ps_boundary;

/* Twice the RMS distance of the boundary's edge midpoints from their
 * centroid: the diameter of a circular boundary.  0 without points. */
double ps_boundary_width(const ps_boundary *r);

/* Sums over a segment's points (relative to point 0) and their outward
 * normals, for ps_segment_bulge; they add up when segments merge. */
typedef struct ps_segment_sums {
    double point_sum[3];
    double normal_sum[3];
    double dot_sum;   /* sum of n . p */
    double norm2_sum; /* sum of |p|^2 */
} ps_segment_sums;

typedef struct ps_segment_graph {
    int n_groups;          /* segment ids are in [0, n_groups) */
    size_t *size;          /* #n_groups points */
    double *f_min, *f_max; /* #n_groups */
    ps_segment_sums *sums; /* #n_groups, or NULL without points and normals */
    int *alias;            /* #n_groups the segment it merged into, or itself */
    ps_boundary *list;     /* #count, sorted by (a, b) */
    size_t count;
} ps_segment_graph;

/* kNN edges p-q, p < q, in the order of one pass over the arcs. */
typedef struct ps_edge_list {
    uint32_t *ends;  /* #count by 2: p, q (malloc'ed) */
    size_t count;
} ps_edge_list;

/* Whether the kNN edge p-q, joining segments group[p] != group[q], is
 * marked. */
typedef int (*ps_boundary_mark_fn)(void *context, const int *group, size_t p, size_t q);

typedef struct ps_segment_graph_input {
    const ps_graph *graph;    /* kNN graph on #P points */
    const double *f;          /* #P centrality */
    const double *points;     /* #P by 3, or NULL: no boundary widths */
    const double *normals;    /* #P by 3 outward unit normals, or NULL: no bulges */
    const int *group;         /* #P segment ids in [0, n_groups) */
    int n_groups;
    ps_boundary_mark_fn mark; /* may be NULL: nothing marked; called from several
                                 threads at once */
    void *context;            /* passed to mark */
    int threads;              /* gathering the boundaries (ps_parallel_threads: 0 = all
                                 cores); the graph is the same for any count */
    const ps_edge_list *candidates; /* may be NULL: every kNN edge is looked at; else
                                       only these, which must include every edge
                                       joining two segments (the boundary edges of
                                       groups these ones merged from) */
    ps_edge_list *found;      /* out, may be NULL: the edges joining two segments
                                 (the caller frees ends) */
} ps_segment_graph_input;

/* What each merge after the boundary cut reads (crease_merge.h,
 * convex_merge.h, patch_merge.h). */
typedef struct ps_merge_input {
    const ps_graph *graph;   /* kNN graph on #P points (weights not used) */
    const double *points;    /* #P by 3 */
    const double *normals;   /* #P by 3, outward unit normals (normals.h) */
    const double *f;         /* #P centrality, for the merges' feature sizes */
    double mean_angular;     /* mean angular term over all edges (ps_crease_points.mean) */
    double median_strength;  /* median crease strength (ps_crease_points.median) */
    int n_groups;            /* segment ids are in [0, n_groups) */
    int threads;             /* ps_parallel_threads; the merges are the same for any count */
    ps_edge_list *boundary;  /* in/out, may be NULL: with ends, the edges joining two of
                                the groups passed in, or more (ps_segment_graph_input's
                                candidates); a merge that builds its segment graph
                                replaces them by those it found (still true of its
                                merged groups), freeing the old ends */
} ps_merge_input;

/* What each merge does with its input: group_of_point #P in/out, each
 * point's segment id; group_of_leaf #n_groups in/out, ids (or -1)
 * rewritten to their surviving segment; merges / n_merges in/out, a
 * malloc'ed list (may be NULL with 0) that the new merges are appended
 * to. */
typedef ps_status ps_merge_fn(const ps_merge_input *in, int *group_of_point, int *group_of_leaf,
                              ps_merge **merges, int *n_merges, ps_error *err);

/* How segment s bulges outwards: the mean over its points of n . (p - c),
 * c its centroid, over its RMS distance from c.  Positive for what sticks
 * out (a limb, a dome: normals point away from the centre), negative for a
 * cavity (the inside of a cup: they point towards it), near 0 for a flat
 * patch; in [-1, 1].  0 without sums. */
double ps_segment_bulge(const ps_segment_graph *sg, int s);

/* Whether segment s sticks out of boundary r (one of its records): its
 * feature size (max f - min f, how far it reaches) is over factor times
 * the boundary's width (Hoffman and Singh's protrusion; the crease merge
 * and the patch merge keep such parts). */
int ps_segment_protrudes(const ps_segment_graph *sg, int s, const ps_boundary *r, double factor);

/* On failure sg is freed. */
ps_status ps_segment_graph_build(ps_segment_graph *sg, const ps_segment_graph_input *in,
                                 ps_error *err);

/* ps_segment_graph_build for a merge (ps_merge_input's boundary): boundary
 * (may be NULL) gives in's candidates when it has ends, and on success is
 * replaced by the edges found (its old ends freed). */
ps_status ps_segment_graph_build_along(ps_segment_graph *sg, ps_segment_graph_input *in,
                                       ps_edge_list *boundary, ps_error *err);

/* Merges segment loser into winner (both surviving, adjacent or not) and
 * appends {loser, winner, loser's feature size} to the malloc'ed list
 * merges / n_merges, its step PS_STEP_COUNT until the step that ran the
 * merge names it (segment.c).  Returns 0 when out of memory (nothing
 * changed). */
int ps_segment_graph_merge(ps_segment_graph *sg, int loser, int winner, ps_merge **merges,
                           int *n_merges);

/* The segment that id has merged into (id itself if it survives). */
int ps_segment_graph_survivor(const ps_segment_graph *sg, int id);

/* group_of_point #P and group_of_leaf #n_groups (entries may be -1)
 * rewritten to their survivors. */
void ps_segment_graph_apply(const ps_segment_graph *sg, int *group_of_point, size_t n,
                            int *group_of_leaf);

void ps_segment_graph_free(ps_segment_graph *sg);

#endif
