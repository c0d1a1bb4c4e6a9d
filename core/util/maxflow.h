/*
 * maxflow.h: maximum flow and minimum s-t cut on an undirected graph in CSR
 * form (the Boykov-Kolmogorov algorithm: search trees from both terminals,
 * augmenting where they meet, orphans re-adopted; fast on the small,
 * grid-like band graphs of boundary_cut.h).  Deterministic: arcs are
 * visited in row order, no threads, no randomness.  The cut does not depend
 * on the algorithm: the nodes reachable from s in the residual
 * graph are the same for every maximum flow (up to the tolerance below).
 *
 * The graph is symmetric: row p holds q iff row q holds p, each row sorted
 * by neighbour index (as ps_graph rows are).  capacity[e] is the capacity of
 * the edge {p, q} of arc e and must equal that of the reverse arc; flow may
 * go either way.
 */
#ifndef PS_MAXFLOW_H
#define PS_MAXFLOW_H

#include "pointseg.h"

typedef struct ps_maxflow_graph {
    size_t n;                /* #V nodes */
    const size_t *offsets;   /* #V+1 row p is [offsets[p], offsets[p+1]) */
    const uint32_t *heads;   /* #E neighbour of each arc, rows sorted */
    const double *capacity;  /* #E >= 0, equal on an arc and its reverse */
} ps_maxflow_graph;

/* Scratch space of ps_maxflow_with, grown to the largest graph it has
 * solved; reusing one across many graphs saves an allocation per call. */
typedef struct ps_maxflow_workspace ps_maxflow_workspace;

/* An empty workspace; NULL when out of memory. */
ps_maxflow_workspace *ps_maxflow_workspace_new(void);
void ps_maxflow_workspace_free(ps_maxflow_workspace *ws);

/* Maximum flow from the terminal s to the terminal t (s != t; "sink" is
 * the gradient flow's word, flow.h).
 * s_side, if not NULL, #V out: 1 for the nodes on s's side of the minimum
 * cut (those reachable from s in the residual graph), 0 otherwise.  *flow out:
 * the flow value, which equals the capacity of that cut.  Fails only when
 * out of memory. */
ps_status ps_maxflow(const ps_maxflow_graph *g, uint32_t s, uint32_t t, double *flow,
                     unsigned char *s_side, ps_error *err);

/* ps_maxflow in the scratch space of ws (same results, bit for bit); ws
 * grows when g is larger than any graph it has held.  One thread at a time
 * per workspace. */
ps_status ps_maxflow_with(ps_maxflow_workspace *ws, const ps_maxflow_graph *g, uint32_t s,
                          uint32_t t, double *flow, unsigned char *s_side,
                          ps_error *err);

#endif
