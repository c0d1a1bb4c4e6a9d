/*
 * maxflow.c: maximum flow on a symmetric CSR graph (maxflow.h) by the
 * Boykov-Kolmogorov algorithm: a search tree grows from the terminal s (the
 * S tree) and one from t (the T tree) over unsaturated arcs; where they
 * touch, the path through both is augmented; nodes cut off from their
 * tree by a saturated arc (orphans) look for a new parent in the same tree
 * or are freed.  When no tree can grow the flow is maximum, and a
 * breadth-first search from s over unsaturated arcs gives the cut's s
 * side.  Trees are kept shallow by Boykov and Kolmogorov's own heuristic:
 * each node knows its depth as of a round (a stamp per augmentation), an
 * orphan takes the valid parent nearest its root, and growing reparents a
 * neighbour whose known depth is larger, so paths to augment and to check
 * stay short.
 *
 * Residual capacities live per arc: pushing x along p->q lowers r(p->q) and
 * raises r(q->p) by x, which is exactly an undirected edge of capacity c
 * with r = c on both arcs at the start.  Residuals at or below a tolerance
 * (1e-12 of the largest capacity) count as saturated, so rounding never
 * leaves endless tiny augmenting paths.
 */
#include "util/maxflow.h"

#include <stdlib.h>

#define FREE 0
#define S_TREE 1
#define T_TREE 2
#define NO_ARC SIZE_MAX /* parent arc of a root or an orphan */

/* A node's search state, in one place: the searches read and write these
 * fields together. */
typedef struct maxflow_node {
    size_t parent_arc;       /* S tree: the arc parent -> v; T tree: the
                                arc v -> parent; NO_ARC */
    uint64_t checked;        /* stamp of the last round v's origin was found to
                                be its tree's root */
    uint32_t parent;
    uint32_t depth;          /* arcs from v up to its root, as of round checked */
    unsigned char tree;      /* FREE, S_TREE or T_TREE */
    unsigned char queued;    /* in the active queue */
} maxflow_node;

struct ps_maxflow_workspace {
    size_t nodes, arcs;      /* sizes the arrays below hold */
    size_t *reverse;         /* arcs: index of the reverse arc (pairs up: the
                                reverse of reverse[e] is e) */
    double *residual;        /* arcs */
    maxflow_node *node;      /* nodes */
    size_t *cursor;          /* nodes: the reverse arcs' search */
    uint32_t *active;        /* nodes: FIFO ring of active nodes */
    uint32_t *orphans;       /* nodes: stack */
};

typedef struct maxflow_state {
    const ps_maxflow_graph *g;
    ps_maxflow_workspace *w;
    uint32_t s, t;           /* the terminals */
    double tolerance;
    size_t head, count;      /* active ring */
    size_t n_orphans;
    uint64_t round;          /* one per augmentation */
} maxflow_state;

/* Reverse arcs in one pass over the rows in order: as the rows are sorted,
 * the arcs into q met for increasing p are row q's entries in order, so a
 * cursor per row finds each one.  -1 if the graph is not symmetric. */
static int find_reverse_arcs(maxflow_state *st) {
    const ps_maxflow_graph *g = st->g;
    size_t *cursor = st->w->cursor;
    for (size_t v = 0; v < g->n; v++) cursor[v] = g->offsets[v];
    for (uint32_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            uint32_t q = g->heads[e];
            if (q >= g->n || cursor[q] == g->offsets[q + 1] || g->heads[cursor[q]] != p)
                return -1;
            st->w->reverse[e] = cursor[q]++;
        }
    return 0;
}

static void activate(maxflow_state *st, uint32_t v) {
    ps_maxflow_workspace *w = st->w;
    if (w->node[v].queued) return;
    w->node[v].queued = 1;
    size_t at = st->head + st->count++;
    w->active[at < st->g->n ? at : at - st->g->n] = v;
}

/* The next active node still in a tree, or UINT32_MAX. */
static uint32_t next_active(maxflow_state *st) {
    ps_maxflow_workspace *w = st->w;
    while (st->count > 0) {
        uint32_t v = w->active[st->head];
        st->head = st->head + 1 < st->g->n ? st->head + 1 : 0, st->count--;
        w->node[v].queued = 0;
        if (w->node[v].tree != FREE) return v;
    }
    return UINT32_MAX;
}

/* The arc along which tree's flow would enter q from p (S tree: p -> q,
 * arc e of row p; T tree: q -> p, its reverse). */
static size_t tree_arc(const maxflow_state *st, unsigned char tree, size_t e) {
    return tree == S_TREE ? e : st->w->reverse[e];
}

/* Grows p's tree by its free neighbours; returns the first arc from the
 * S tree into the T tree met on the way, or NO_ARC.  p's own state
 * does not change on the way (no arc leads from p to p's tree root through
 * p itself), so it is read once. */
static size_t grow(maxflow_state *st, uint32_t p) {
    const ps_maxflow_graph *g = st->g;
    ps_maxflow_workspace *w = st->w;
    const unsigned char tree = w->node[p].tree;
    const uint64_t checked = w->node[p].checked;
    const uint32_t depth = w->node[p].depth + 1; /* of a child of p */
    for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
        size_t a = tree_arc(st, tree, e);
        if (w->residual[a] <= st->tolerance) continue;
        uint32_t q = g->heads[e];
        maxflow_node *nq = &w->node[q];
        if (nq->tree == FREE) {
            nq->tree = tree, nq->parent = p, nq->parent_arc = a;
            nq->checked = checked, nq->depth = depth;
            activate(st, q);
        } else if (nq->tree != tree) {
            return a;
        } else if (nq->parent_arc != NO_ARC && nq->checked <= checked && nq->depth > depth) {
            nq->parent = p, nq->parent_arc = a;
            nq->checked = checked, nq->depth = depth;
        }
    }
    return NO_ARC;
}

static void make_orphan(maxflow_state *st, uint32_t v) {
    st->w->node[v].parent_arc = NO_ARC;
    st->w->orphans[st->n_orphans++] = v;
}

static double path_bottleneck(const maxflow_state *st, uint32_t v, uint32_t root, double least) {
    const ps_maxflow_workspace *w = st->w;
    for (; v != root; v = w->node[v].parent)
        if (w->residual[w->node[v].parent_arc] < least) least = w->residual[w->node[v].parent_arc];
    return least;
}

/* Pushes x along the tree path from v to root; the nodes whose parent arc
 * it saturates become orphans. */
static void push_path(maxflow_state *st, uint32_t v, uint32_t root, double x) {
    ps_maxflow_workspace *w = st->w;
    while (v != root) {
        size_t a = w->node[v].parent_arc;
        uint32_t up = w->node[v].parent;
        w->residual[a] -= x;
        w->residual[w->reverse[a]] += x;
        if (w->residual[a] <= st->tolerance) make_orphan(st, v);
        v = up;
    }
}

/* Augments s -> ... -> tail -bridge-> head -> ... -> t. */
static double augment(maxflow_state *st, size_t bridge) {
    ps_maxflow_workspace *w = st->w;
    uint32_t head = st->g->heads[bridge], tail = st->g->heads[w->reverse[bridge]];
    double x = path_bottleneck(st, tail, st->s, w->residual[bridge]);
    x = path_bottleneck(st, head, st->t, x);
    w->residual[bridge] -= x;
    w->residual[w->reverse[bridge]] += x;
    push_path(st, tail, st->s, x);
    push_path(st, head, st->t, x);
    return x;
}

/* q's depth when its parent chain reaches its tree's root, else
 * UINT32_MAX; the nodes on the chain are then stamped with this round and
 * their depths, which ends later walks early. */
static uint32_t rooted_depth(maxflow_state *st, uint32_t q) {
    ps_maxflow_workspace *w = st->w;
    uint32_t v = q, d = 0;
    for (; v != st->s && v != st->t; v = w->node[v].parent, d++) {
        if (w->node[v].checked == st->round) {
            d += w->node[v].depth;
            break;
        }
        if (w->node[v].parent_arc == NO_ARC) return UINT32_MAX;
    }
    uint32_t total = d;
    for (v = q; v != st->s && v != st->t && w->node[v].checked != st->round;
         v = w->node[v].parent)
        w->node[v].checked = st->round, w->node[v].depth = d--;
    return total;
}

/* Orphan p takes the rooted neighbour of its tree nearest the root (the
 * first of those) that reaches it along an unsaturated arc; failing that it
 * is freed, its children become orphans and the neighbours that could
 * reach it become active. */
static void adopt(maxflow_state *st, uint32_t p) {
    const ps_maxflow_graph *g = st->g;
    ps_maxflow_workspace *w = st->w;
    unsigned char tree = w->node[p].tree;
    uint32_t best = UINT32_MAX, best_depth = UINT32_MAX;
    size_t best_arc = NO_ARC;
    for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
        uint32_t q = g->heads[e];
        if (w->node[q].tree != tree) continue;
        size_t a = tree == S_TREE ? w->reverse[e] : e; /* the arc q's tree would use into p */
        if (w->residual[a] <= st->tolerance) continue;
        uint32_t d = rooted_depth(st, q);
        if (d < best_depth) best = q, best_depth = d, best_arc = a;
    }
    if (best != UINT32_MAX) {
        w->node[p].parent = best, w->node[p].parent_arc = best_arc;
        w->node[p].checked = st->round, w->node[p].depth = best_depth + 1;
        return;
    }
    for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
        uint32_t q = g->heads[e];
        if (w->node[q].tree != tree) continue;
        if (w->residual[tree == S_TREE ? w->reverse[e] : e] > st->tolerance) activate(st, q);
        if (w->node[q].parent_arc != NO_ARC && w->node[q].parent == p) make_orphan(st, q);
    }
    w->node[p].tree = FREE;
}

/* Grows the trees and augments until neither can grow; the flow value. */
static double max_flow(maxflow_state *st) {
    double total = 0;
    activate(st, st->s);
    activate(st, st->t);
    for (uint32_t p; (p = next_active(st)) != UINT32_MAX;) {
        for (size_t bridge; st->w->node[p].tree != FREE && (bridge = grow(st, p)) != NO_ARC;) {
            st->round++;
            st->w->node[st->s].checked = st->w->node[st->t].checked = st->round;
            total += augment(st, bridge);
            while (st->n_orphans > 0) adopt(st, st->w->orphans[--st->n_orphans]);
        }
    }
    return total;
}

/* s_side: the nodes reachable from s over unsaturated arcs
 * (the active ring serves as the queue). */
static void s_side_of(maxflow_state *st, unsigned char *side) {
    const ps_maxflow_graph *g = st->g;
    uint32_t *queue = st->w->active;
    size_t head = 0, tail = 0;
    for (size_t v = 0; v < g->n; v++) side[v] = 0;
    side[st->s] = 1;
    queue[tail++] = st->s;
    while (head < tail) {
        uint32_t v = queue[head++];
        for (size_t e = g->offsets[v]; e < g->offsets[v + 1]; e++) {
            uint32_t q = g->heads[e];
            if (side[q] || st->w->residual[e] <= st->tolerance) continue;
            side[q] = 1;
            queue[tail++] = q;
        }
    }
}

static void *fresh_array(void *old, size_t count, size_t size) {
    free(old);
    return malloc(count * size);
}

/* Room for g in ws; -1 when out of memory (ws is then empty). */
static int workspace_reserve(ps_maxflow_workspace *ws, const ps_maxflow_graph *g) {
    size_t nodes = g->n, arcs = g->offsets[g->n] ? g->offsets[g->n] : 1;
    if (nodes > ws->nodes) {
        ws->nodes = nodes;
        ws->node = fresh_array(ws->node, nodes, sizeof *ws->node);
        ws->cursor = fresh_array(ws->cursor, nodes, sizeof *ws->cursor);
        ws->active = fresh_array(ws->active, nodes, sizeof *ws->active);
        ws->orphans = fresh_array(ws->orphans, nodes, sizeof *ws->orphans);
    }
    if (arcs > ws->arcs) {
        ws->arcs = arcs;
        ws->reverse = fresh_array(ws->reverse, arcs, sizeof *ws->reverse);
        ws->residual = fresh_array(ws->residual, arcs, sizeof *ws->residual);
    }
    if (ws->node && ws->cursor && ws->active && ws->orphans && ws->reverse && ws->residual)
        return 0;
    ws->nodes = ws->arcs = 0;
    return -1;
}

ps_maxflow_workspace *ps_maxflow_workspace_new(void) {
    return calloc(1, sizeof(ps_maxflow_workspace));
}

void ps_maxflow_workspace_free(ps_maxflow_workspace *ws) {
    if (!ws) return;
    free(ws->reverse), free(ws->residual), free(ws->node), free(ws->cursor), free(ws->active);
    free(ws->orphans);
    free(ws);
}

static void state_init(maxflow_state *st, ps_maxflow_workspace *ws, const ps_maxflow_graph *g,
                       uint32_t s, uint32_t t) {
    double largest = 0;
    for (size_t e = 0; e < g->offsets[g->n]; e++) {
        ws->residual[e] = g->capacity[e];
        if (g->capacity[e] > largest) largest = g->capacity[e];
    }
    *st = (maxflow_state){.g = g, .w = ws, .s = s, .t = t,
                       .tolerance = 1e-12 * largest};
    for (size_t v = 0; v < g->n; v++)
        ws->node[v] = (maxflow_node){.parent_arc = NO_ARC, .tree = FREE};
    ws->node[s].tree = S_TREE;
    ws->node[t].tree = T_TREE;
}

ps_status ps_maxflow_with(ps_maxflow_workspace *ws, const ps_maxflow_graph *g, uint32_t s,
                          uint32_t t, double *flow, unsigned char *s_side,
                          ps_error *err) {
    if (s >= g->n || t >= g->n || s == t)
        return ps_fail(err, PS_ERR_INVALID, "max flow: bad terminal s %u or t %u of %zu nodes",
                       s, t, g->n);
    if (workspace_reserve(ws, g) != 0)
        return ps_fail(err, PS_ERR_NOMEM, "out of memory (max flow)");
    maxflow_state st;
    state_init(&st, ws, g, s, t);
    if (find_reverse_arcs(&st) != 0)
        return ps_fail(err, PS_ERR_INVALID, "max flow: the graph is not symmetric");
    *flow = max_flow(&st);
    if (s_side) s_side_of(&st, s_side);
    return PS_OK;
}

ps_status ps_maxflow(const ps_maxflow_graph *g, uint32_t s, uint32_t t, double *flow,
                     unsigned char *s_side, ps_error *err) {
    ps_maxflow_workspace *ws = ps_maxflow_workspace_new();
    if (!ws) return ps_fail(err, PS_ERR_NOMEM, "out of memory (max flow)");
    ps_status st = ps_maxflow_with(ws, g, s, t, flow, s_side, err);
    ps_maxflow_workspace_free(ws);
    return st;
}
