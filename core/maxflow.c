/*
 * maxflow.c: Dinic's maximum flow on a symmetric CSR graph (maxflow.h).
 *
 * Residual capacities live per arc: pushing x along p->q lowers r(p->q) and
 * raises r(q->p) by x, which is exactly an undirected edge of capacity c
 * with r = c on both arcs at the start.  Residuals at or below a tolerance
 * (1e-12 of the largest capacity) count as saturated, so rounding never
 * leaves endless tiny augmenting paths.
 */
#include "maxflow.h"

#include <stdlib.h>

struct ps_maxflow_workspace {
    size_t nodes, arcs;  /* sizes the arrays below hold */
    size_t *reverse;     /* arcs: index of the reverse arc */
    double *residual;    /* arcs */
    int *level;          /* nodes: BFS depth from the source, -1 unreached or dead */
    size_t *next_arc;    /* nodes: current arc of each node in the blocking flow */
    uint32_t *queue;     /* nodes */
    size_t *path;        /* nodes: arcs of the current path from the source */
};

typedef struct flow_state {
    const ps_flow_graph *g;
    size_t *reverse;   /* #E */
    double *residual;  /* #E */
    int *level;        /* #V */
    size_t *next_arc;  /* #V */
    uint32_t *queue;   /* #V */
    size_t *path;      /* #V */
    double tolerance;
} flow_state;

/* Reverse arcs in one pass over the rows in order: as the rows are sorted,
 * the arcs into q met for increasing p are row q's entries in order, so a
 * cursor per row (next_arc, reset by each phase) finds each one.  -1 if
 * the graph is not symmetric. */
static int find_reverse_arcs(flow_state *st) {
    const ps_flow_graph *g = st->g;
    size_t *cursor = st->next_arc;
    for (size_t v = 0; v < g->n; v++) cursor[v] = g->offsets[v];
    for (uint32_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            uint32_t q = g->heads[e];
            if (q >= g->n || cursor[q] == g->offsets[q + 1] || g->heads[cursor[q]] != p)
                return -1;
            st->reverse[e] = cursor[q]++;
        }
    return 0;
}

/* Levels from the source over unsaturated arcs; 1 if the sink is reached.
 * The search stops as soon as the sink has its level d: every node nearer
 * than d has its level by then, and the nodes left unreached (at d or
 * beyond) could never lead to the sink in this phase, so the blocking flow
 * finds the same paths as after a full search.  When the sink is not
 * reached the levels are complete: the source side of the cut. */
static int build_levels(flow_state *st, uint32_t source, uint32_t sink) {
    const ps_flow_graph *g = st->g;
    for (size_t v = 0; v < g->n; v++) st->level[v] = -1;
    size_t head = 0, tail = 0;
    st->level[source] = 0;
    st->queue[tail++] = source;
    while (head < tail) {
        uint32_t v = st->queue[head++];
        for (size_t e = g->offsets[v]; e < g->offsets[v + 1]; e++) {
            uint32_t u = g->heads[e];
            if (st->level[u] >= 0 || st->residual[e] <= st->tolerance) continue;
            st->level[u] = st->level[v] + 1;
            if (u == sink) return 1;
            st->queue[tail++] = u;
        }
    }
    return 0;
}

/* Node at depth k of the current path. */
static uint32_t path_node(const flow_state *st, uint32_t source, size_t k) {
    return k == 0 ? source : st->g->heads[st->path[k - 1]];
}

/* Pushes the bottleneck along the path; returns it and the depth of the
 * first arc it saturated. */
static double push_path(flow_state *st, size_t depth, size_t *saturated) {
    double bottleneck = st->residual[st->path[0]];
    for (size_t i = 1; i < depth; i++)
        if (st->residual[st->path[i]] < bottleneck) bottleneck = st->residual[st->path[i]];
    *saturated = depth;
    for (size_t i = 0; i < depth; i++) {
        size_t e = st->path[i];
        st->residual[e] -= bottleneck;
        st->residual[st->reverse[e]] += bottleneck;
        if (*saturated == depth && st->residual[e] <= st->tolerance) *saturated = i;
    }
    return bottleneck;
}

/* An admissible arc out of v (unsaturated, one level deeper), advancing
 * v's current arc; the row's end when there is none. */
static size_t admissible_arc(flow_state *st, uint32_t v) {
    const ps_flow_graph *g = st->g;
    for (; st->next_arc[v] < g->offsets[v + 1]; st->next_arc[v]++) {
        size_t e = st->next_arc[v];
        if (st->residual[e] > st->tolerance && st->level[g->heads[e]] == st->level[v] + 1)
            break;
    }
    return st->next_arc[v];
}

/* One phase: augment along shortest paths until none is left. */
static double blocking_flow(flow_state *st, uint32_t source, uint32_t sink) {
    const ps_flow_graph *g = st->g;
    for (size_t v = 0; v < g->n; v++) st->next_arc[v] = g->offsets[v];
    double total = 0;
    size_t depth = 0;
    uint32_t v = source;
    for (;;) {
        if (v == sink) {
            total += push_path(st, depth, &depth);
            v = path_node(st, source, depth);
            continue;
        }
        size_t e = admissible_arc(st, v);
        if (e < g->offsets[v + 1]) {
            st->path[depth++] = e;
            v = g->heads[e];
            continue;
        }
        if (v == source) return total;
        st->level[v] = -1;
        v = path_node(st, source, --depth);
        st->next_arc[v]++;
    }
}

static double largest_capacity(const ps_flow_graph *g) {
    double largest = 0;
    for (size_t e = 0; e < g->offsets[g->n]; e++)
        if (g->capacity[e] > largest) largest = g->capacity[e];
    return largest;
}

static void *fresh_array(void *old, size_t count, size_t size) {
    free(old);
    return malloc(count * size);
}

/* Room for g in ws; -1 when out of memory (ws is then empty). */
static int workspace_reserve(ps_maxflow_workspace *ws, const ps_flow_graph *g) {
    size_t nodes = g->n, arcs = g->offsets[g->n] ? g->offsets[g->n] : 1;
    if (nodes > ws->nodes) {
        ws->nodes = nodes;
        ws->level = fresh_array(ws->level, nodes, sizeof *ws->level);
        ws->next_arc = fresh_array(ws->next_arc, nodes, sizeof *ws->next_arc);
        ws->queue = fresh_array(ws->queue, nodes, sizeof *ws->queue);
        ws->path = fresh_array(ws->path, nodes, sizeof *ws->path);
    }
    if (arcs > ws->arcs) {
        ws->arcs = arcs;
        ws->reverse = fresh_array(ws->reverse, arcs, sizeof *ws->reverse);
        ws->residual = fresh_array(ws->residual, arcs, sizeof *ws->residual);
    }
    if (ws->level && ws->next_arc && ws->queue && ws->path && ws->reverse && ws->residual)
        return 0;
    ws->nodes = ws->arcs = 0;
    return -1;
}

ps_maxflow_workspace *ps_maxflow_workspace_new(void) {
    return calloc(1, sizeof(ps_maxflow_workspace));
}

void ps_maxflow_workspace_free(ps_maxflow_workspace *ws) {
    if (!ws) return;
    free(ws->reverse);
    free(ws->residual);
    free(ws->level);
    free(ws->next_arc);
    free(ws->queue);
    free(ws->path);
    free(ws);
}

static void state_init(flow_state *st, ps_maxflow_workspace *ws, const ps_flow_graph *g) {
    *st = (flow_state){.g = g, .reverse = ws->reverse, .residual = ws->residual,
                       .level = ws->level, .next_arc = ws->next_arc, .queue = ws->queue,
                       .path = ws->path, .tolerance = 1e-12 * largest_capacity(g)};
    for (size_t e = 0; e < g->offsets[g->n]; e++) st->residual[e] = g->capacity[e];
}

ps_status ps_maxflow_with(ps_maxflow_workspace *ws, const ps_flow_graph *g, uint32_t source,
                          uint32_t sink, double *flow, unsigned char *source_side,
                          ps_error *err) {
    if (source >= g->n || sink >= g->n || source == sink)
        return ps_fail(err, PS_ERR_INVALID, "max flow: bad source %u or sink %u of %zu nodes",
                       source, sink, g->n);
    if (workspace_reserve(ws, g) != 0)
        return ps_fail(err, PS_ERR_NOMEM, "out of memory (max flow)");
    flow_state st;
    state_init(&st, ws, g);
    if (find_reverse_arcs(&st) != 0)
        return ps_fail(err, PS_ERR_INVALID, "max flow: the graph is not symmetric");
    double total = 0;
    while (build_levels(&st, source, sink)) total += blocking_flow(&st, source, sink);
    if (source_side)
        for (size_t v = 0; v < g->n; v++) source_side[v] = st.level[v] >= 0;
    *flow = total;
    return PS_OK;
}

ps_status ps_maxflow(const ps_flow_graph *g, uint32_t source, uint32_t sink, double *flow,
                     unsigned char *source_side, ps_error *err) {
    ps_maxflow_workspace *ws = ps_maxflow_workspace_new();
    if (!ws) return ps_fail(err, PS_ERR_NOMEM, "out of memory (max flow)");
    ps_status st = ps_maxflow_with(ws, g, source, sink, flow, source_side, err);
    ps_maxflow_workspace_free(ws);
    return st;
}
