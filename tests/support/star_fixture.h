/*
 * star_fixture.h: the star of shapes.h (a sphere with six capsule arms
 * along +-x, +-y, +-z, meeting it along concave creases) with its kNN graph
 * (k = 7) and PCA normals, for the tests of the crease-aware steps.
 */
#ifndef PS_STAR_FIXTURE_H
#define PS_STAR_FIXTURE_H

#include "graph/knn_graph.h"

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

/* Coordinate of x along the axis of arm k (1..6). */
double ps_star_along_arm(const double *x, int k);

#endif
