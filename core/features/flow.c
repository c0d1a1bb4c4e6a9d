/*
 * flow.c: steepest-ascent (or descent) pointers on the kNN graph, the sinks
 * they end in, and each vertex's sink (flow.h).
 *
 * Only strictly higher neighbours count, so a plateau of equal f (rare with
 * real-valued centrality) makes each of its vertices without a higher
 * neighbour a sink of its own.  The pointers strictly increase f, so they
 * have no cycles; each path is walked once and its vertices get the sink
 * of where it ends (iteratively, no recursion).
 */
#include "features/flow.h"

#include <stdlib.h>
#include <string.h>

#define UNKNOWN (-1)

/* Steepest neighbour of p along direction * f, or p itself. */
static uint32_t steepest_neighbor(const ps_graph *g, const double *f, double direction,
                                  uint32_t p) {
    uint32_t best = p;
    double best_slope = 0.0;
    for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
        uint32_t q = g->neighbors[e];
        double rise = direction * (f[q] - f[p]);
        if (!(rise > 0.0)) continue;
        double slope = rise / g->weights[e];
        if (best == p || slope > best_slope) best = q, best_slope = slope;
    }
    return best;
}

/* Follows next[] from every vertex; path #P scratch stack. */
static void assign_sinks(size_t n, const uint32_t *next, int *sink_of, uint32_t *path) {
    for (size_t start = 0; start < n; start++) {
        size_t len = 0;
        uint32_t v = (uint32_t)start;
        while (sink_of[v] == UNKNOWN) {
            path[len++] = v;
            v = next[v];
        }
        while (len > 0) sink_of[path[--len]] = sink_of[v];
    }
}

ps_status ps_flow_build(const ps_graph *g, const double *f, int direction, ps_flow *flow,
                        ps_error *err) {
    memset(flow, 0, sizeof *flow);
    if (direction != 1 && direction != -1)
        return ps_fail(err, PS_ERR_INVALID, "flow: direction must be +1 or -1, got %d", direction);
    size_t n = g->n, alloc_n = n ? n : 1;
    uint32_t *next = malloc(alloc_n * sizeof *next);
    uint32_t *path = malloc(alloc_n * sizeof *path);
    flow->sink_of = malloc(alloc_n * sizeof *flow->sink_of);
    flow->sinks = malloc(alloc_n * sizeof *flow->sinks);
    if (!next || !path || !flow->sink_of || !flow->sinks) {
        free(next), free(path);
        ps_flow_free(flow);
        return ps_fail(err, PS_ERR_NOMEM, "flow: out of memory for %zu vertices", n);
    }
    for (size_t p = 0; p < n; p++) {
        next[p] = steepest_neighbor(g, f, (double)direction, (uint32_t)p);
        flow->sink_of[p] = UNKNOWN;
        if (next[p] == p) {
            flow->sink_of[p] = flow->n_sinks;
            flow->sinks[flow->n_sinks++] = (uint32_t)p;
        }
    }
    assign_sinks(n, next, flow->sink_of, path);
    free(next), free(path);
    uint32_t *shrunk = realloc(flow->sinks, (flow->n_sinks ? (size_t)flow->n_sinks : 1) *
                                                sizeof *shrunk);
    if (shrunk) flow->sinks = shrunk;
    return PS_OK;
}

void ps_flow_free(ps_flow *flow) {
    if (!flow) return;
    free(flow->sinks), free(flow->sink_of);
    memset(flow, 0, sizeof *flow);
}
