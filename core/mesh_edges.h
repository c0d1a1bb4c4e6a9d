/*
 * mesh_edges.h: a triangle mesh's edges join the pieces of a kNN graph
 * that the mesh connects.
 *
 * A coarse CAD mesh samples a turned part in rings farther apart than the
 * spacing along each ring; every point's k nearest then lie on its own
 * ring, the kNN graph falls apart into dozens of rings and each becomes a
 * segment.  The mesh's edges are surface adjacency whatever the sampling:
 * those between two components of the kNN graph are added to it.  Edges
 * within a component are not (the kNN graph already holds that surface,
 * and a coarse mesh's long edges would blur its normals and creases).
 */
#ifndef PS_MESH_EDGES_H
#define PS_MESH_EDGES_H

#include "knn_graph.h"

typedef struct ps_mesh_bridge_input {
    const double *points;      /* #U by dim: the graph's points */
    int dim;
    const uint32_t *faces;     /* #F by 3: triangles over the #P input points */
    size_t n_faces;            /* #F */
    const uint32_t *unique_of; /* #P: each input point's vertex of the graph */
    size_t n_input;            /* #P */
    const int *component;      /* #U: the graph's components (ps_graph_components) */
} ps_mesh_bridge_input;

/* Adds to g (#U vertices) every face edge whose ends lie in different
 * components, both directions, weighted by its Euclidean length; rows stay
 * sorted and free of duplicates, and g is untouched when there is none.
 * Face indices must be < #P (the caller checks).  *added out: the
 * undirected edges added.  O(F + E) plus the sort of the rows that gain. */
ps_status ps_mesh_bridges_add(ps_graph *g, const ps_mesh_bridge_input *in, size_t *added,
                              ps_error *err);

#endif
