/*
 * star_fixture.h: the star of shapes.h (a sphere with six capsule arms
 * along +-x, +-y, +-z, meeting it along concave creases) with its kNN graph
 * (k = 7) and PCA normals, for the tests of the crease-aware steps, and a
 * merge's run on it (the tests of the merges after the boundary cut).
 */
#ifndef PS_STAR_FIXTURE_H
#define PS_STAR_FIXTURE_H

#include "graph/knn_graph.h"
#include "refine/segment_graph.h"

#define PS_STAR_PARTS 7      /* sphere 0, arms 1..6 */
#define PS_STAR_CREASE 1.1475 /* sqrt(1.2^2 - 0.35^2): where an arm meets the sphere */
#define PS_STAR_ARM 3.5      /* an arm's axis runs from the centre to this far */

typedef struct ps_star {
    double *points;   /* #n by 3 */
    double *normals;  /* #n by 3, outward unit normals */
    int *part;        /* #n true part, 0..PS_STAR_PARTS-1 */
    size_t n;
    ps_graph graph;
} ps_star;

/* 1 on success; ps_star_free in any case. */
int ps_star_build(ps_star *s);
/* The same at density (ps_shape_star's; 0 is ps_star_build's). */
int ps_star_build_dense(ps_star *s, double density);
void ps_star_free(ps_star *s);

/* What a merge (ps_merge_fn) reads on the star beside its graph. */
typedef struct ps_star_merge_input {
    const double *points;   /* #n by 3, or NULL: the star's */
    const double *normals;  /* #n by 3, or NULL: the star's */
    const double *f;        /* #n, or NULL: 0 everywhere */
    double mean_angular;    /* ps_merge_input's */
    double median_strength; /* ps_merge_input's */
    int n_groups;           /* segment ids are in [0, n_groups) */
} ps_star_merge_input;

/* Runs merge on s's graph with in, one thread: group #n in/out, each
 * point's segment; leaf #n_groups out, set to 0, 1, ... before the run and
 * renamed by it; *merges (malloc'ed, the caller frees) and *n_merges out. */
ps_status ps_star_merge(const ps_star *s, ps_merge_fn *merge, const ps_star_merge_input *in,
                        int *group, int *leaf, ps_merge **merges, int *n_merges);

/* Coordinate of x along the axis of arm k (1..6). */
double ps_star_along_arm(const double *x, int k);

#endif
