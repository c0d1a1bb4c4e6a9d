/*
 * boundary_cut.c: boundaries between adjacent segments moved onto minimum
 * cuts along concave creases (boundary_cut.h).
 *
 * Per pair (A, B) the work is local: the points of A and B get local indices
 * (in increasing point order, so local rows stay sorted), their subgraph is
 * copied with Euclidean lengths and cut capacities, Dijkstra from the shared
 * boundary measures the band, the band becomes a flow network with two
 * terminal nodes after it, and the cut relabels it.  Every scratch array is
 * sized once for the whole graph.
 */
#include "boundary_cut.h"

#include "crease.h"
#include "dijkstra.h"
#include "maxflow.h"

#include <math.h>
#include <stdlib.h>

#define NOT_LOCAL UINT32_MAX

typedef struct pair {
    int a, b;             /* a < b */
    size_t small, large;  /* sizes of the smaller and larger segment */
} pair;

typedef struct cut_context {
    const ps_boundary_cut_input *in;
    int *group;              /* #P in/out */
    double *capacity;        /* #E cut capacity of every graph arc */
    unsigned char *is_sink;  /* #P */
    uint32_t *local_of;      /* #P local index in the current pair, or NOT_LOCAL */
    uint32_t *members;       /* #P points of the current pair, increasing */
    int *old_group;          /* #P groups of the members before the cut */
    double mean_edge;        /* mean Euclidean kNN edge length */
    ps_graph sub;            /* the pair's subgraph, Euclidean weights */
    double *sub_capacity;    /* #E */
    uint32_t *sources;       /* #P boundary points, local */
    double *dist;            /* #P distance from the boundary, local */
    ps_dijkstra *dijkstra;
    uint32_t *band_of;       /* #P band index of each local point, or NOT_LOCAL */
    uint32_t *band;          /* #P local point of each band index */
    double *tie_source;      /* #P */
    double *tie_sink;        /* #P */
    size_t *net_offsets;     /* #P+3 */
    uint32_t *net_heads;     /* #E+4#P */
    double *net_capacity;    /* #E+4#P */
    unsigned char *side;     /* #P+2 */
    int *component;          /* #P */
    size_t *component_size;  /* #P */
    unsigned char *anchored; /* #P 1 for a component reaching outside the band */
    uint32_t *queue;         /* #P */
} cut_context;

static double distance3(const double *p, const double *q) {
    double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* capacity[e] = |p-q| / L * exp(-ang / A0) (boundary_cut.h); the first
 * pass keeps ang in capacity[e] for the second. */
static void edge_capacities(cut_context *cx) {
    const ps_graph *g = cx->in->graph;
    const double *x = cx->in->points, *nx = cx->in->normals;
    size_t edges = g->offsets[g->n];
    double sum_len = 0, sum_ang = 0;
    for (size_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            size_t q = g->neighbors[e];
            sum_len += distance3(x + 3 * p, x + 3 * q);
            cx->capacity[e] = ps_crease_angular(x + 3 * p, nx + 3 * p, x + 3 * q, nx + 3 * q, 0.0);
            sum_ang += cx->capacity[e];
        }
    double L = sum_len / (double)edges;
    cx->mean_edge = L;
    double A0 = PS_BOUNDARY_CUT_ANGLE * sum_ang / (double)edges;
    for (size_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            size_t q = g->neighbors[e];
            double crease = sum_ang / (double)edges >= PS_CREASE_FLAT
                                ? exp(-cx->capacity[e] / A0) : 1;
            cx->capacity[e] = distance3(x + 3 * p, x + 3 * q) / L * crease;
        }
}

/* Points of segments a and b, local indices set; returns their count. */
static size_t collect_members(cut_context *cx, int a, int b) {
    size_t m = 0;
    for (uint32_t p = 0; p < cx->in->graph->n; p++)
        if (cx->group[p] == a || cx->group[p] == b) {
            cx->local_of[p] = (uint32_t)m;
            cx->old_group[m] = cx->group[p];
            cx->members[m++] = p;
        }
    return m;
}

/* The pair's subgraph with Euclidean weights; returns the boundary point
 * count (written to sources). */
static size_t build_subgraph(cut_context *cx, size_t m) {
    const ps_graph *g = cx->in->graph;
    const double *x = cx->in->points;
    size_t arcs = 0, n_sources = 0;
    cx->sub.n = m;
    cx->sub.offsets[0] = 0;
    for (uint32_t v = 0; v < m; v++) {
        uint32_t p = cx->members[v];
        int on_boundary = 0;
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            uint32_t q = g->neighbors[e];
            if (cx->local_of[q] == NOT_LOCAL) continue;
            on_boundary |= cx->group[q] != cx->group[p];
            cx->sub.neighbors[arcs] = cx->local_of[q];
            cx->sub.weights[arcs] = distance3(x + 3 * (size_t)p, x + 3 * (size_t)q);
            cx->sub_capacity[arcs++] = cx->capacity[e];
        }
        cx->sub.offsets[v + 1] = arcs;
        if (on_boundary) cx->sources[n_sources++] = v;
    }
    return n_sources;
}

/* dist of the members: their distance from the boundary, explored only up
 * to the extent from which the band's width is capped (beyond it dist
 * stays at that reach), so the cost follows the band, not the segments. */
static void boundary_distances(cut_context *cx, size_t m, size_t n_sources) {
    double reach = PS_BOUNDARY_CUT_MAX_EDGES * cx->mean_edge / PS_BOUNDARY_CUT_BAND;
    for (size_t v = 0; v < m; v++) cx->dist[v] = reach;
    ps_dijkstra_lower_many(cx->dijkstra, &cx->sub, cx->sources, n_sources, cx->dist);
}

/* Band half-width: PS_BOUNDARY_CUT_BAND x the smaller segment's extent, at
 * most PS_BOUNDARY_CUT_MAX_EDGES mean edge lengths. */
static double band_width(const cut_context *cx, size_t m, int a) {
    double extent_a = 0, extent_b = 0;
    for (size_t v = 0; v < m; v++) {
        double d = cx->dist[v];
        if (!isfinite(d)) continue;
        if (cx->old_group[v] == a) extent_a = fmax(extent_a, d);
        else extent_b = fmax(extent_b, d);
    }
    return fmin(PS_BOUNDARY_CUT_BAND * fmin(extent_a, extent_b),
                PS_BOUNDARY_CUT_MAX_EDGES * cx->mean_edge);
}

/* Band points in local order; ties to the terminals; returns the count. */
static size_t mark_band(cut_context *cx, size_t m, double width, int a) {
    double infinite = 1;
    for (size_t e = 0; e < cx->sub.offsets[m]; e++) infinite += cx->sub_capacity[e];
    size_t nb = 0;
    for (uint32_t v = 0; v < m; v++) {
        cx->band_of[v] = cx->dist[v] <= width ? (uint32_t)nb : NOT_LOCAL;
        if (cx->band_of[v] != NOT_LOCAL) cx->band[nb++] = v;
    }
    for (size_t i = 0; i < nb; i++) {
        uint32_t v = cx->band[i];
        int own_a = cx->old_group[v] == a;
        cx->tie_source[i] = cx->is_sink[cx->members[v]] && own_a ? infinite : 0;
        cx->tie_sink[i] = cx->is_sink[cx->members[v]] && !own_a ? infinite : 0;
        for (size_t e = cx->sub.offsets[v]; e < cx->sub.offsets[v + 1]; e++) {
            uint32_t u = cx->sub.neighbors[e];
            if (cx->band_of[u] != NOT_LOCAL) continue;
            if (cx->old_group[u] == a) cx->tie_source[i] += cx->sub_capacity[e];
            else cx->tie_sink[i] += cx->sub_capacity[e];
        }
    }
    return nb;
}

static void add_arc(cut_context *cx, size_t *arcs, uint32_t head, double capacity) {
    cx->net_heads[*arcs] = head;
    cx->net_capacity[(*arcs)++] = capacity;
}

/* The flow network: band nodes 0..nb-1, source nb, sink nb+1.  Returns 0
 * when a terminal has no tie (nothing to cut). */
static int build_network(cut_context *cx, size_t nb, ps_flow_graph *net) {
    uint32_t source = (uint32_t)nb, sink = (uint32_t)nb + 1;
    size_t arcs = 0;
    for (size_t i = 0; i < nb; i++) {
        uint32_t v = cx->band[i];
        cx->net_offsets[i] = arcs;
        for (size_t e = cx->sub.offsets[v]; e < cx->sub.offsets[v + 1]; e++) {
            uint32_t u = cx->band_of[cx->sub.neighbors[e]];
            if (u != NOT_LOCAL) add_arc(cx, &arcs, u, cx->sub_capacity[e]);
        }
        if (cx->tie_source[i] > 0) add_arc(cx, &arcs, source, cx->tie_source[i]);
        if (cx->tie_sink[i] > 0) add_arc(cx, &arcs, sink, cx->tie_sink[i]);
    }
    cx->net_offsets[nb] = arcs;
    for (uint32_t i = 0; i < nb; i++)
        if (cx->tie_source[i] > 0) add_arc(cx, &arcs, i, cx->tie_source[i]);
    cx->net_offsets[nb + 1] = arcs;
    if (arcs == cx->net_offsets[nb]) return 0;
    for (uint32_t i = 0; i < nb; i++)
        if (cx->tie_sink[i] > 0) add_arc(cx, &arcs, i, cx->tie_sink[i]);
    cx->net_offsets[nb + 2] = arcs;
    if (arcs == cx->net_offsets[nb + 1]) return 0;
    *net = (ps_flow_graph){.n = nb + 2, .offsets = cx->net_offsets, .heads = cx->net_heads,
                           .capacity = cx->net_capacity};
    return 1;
}

/* Components of the members labelled x; those the cut made (wholly inside
 * the band), except the largest (ties: the first found), become y. */
static void keep_largest_piece(cut_context *cx, size_t m, int x, int y) {
    int n_components = 0, best = -1;
    for (size_t v = 0; v < m; v++) cx->component[v] = -1;
    for (uint32_t start = 0; start < m; start++) {
        if (cx->component[start] >= 0 || cx->group[cx->members[start]] != x) continue;
        size_t head = 0, tail = 0;
        cx->component[start] = n_components;
        cx->anchored[n_components] = 0;
        cx->queue[tail++] = start;
        while (head < tail) {
            uint32_t v = cx->queue[head++];
            cx->anchored[n_components] |= cx->band_of[v] == NOT_LOCAL;
            for (size_t e = cx->sub.offsets[v]; e < cx->sub.offsets[v + 1]; e++) {
                uint32_t u = cx->sub.neighbors[e];
                if (cx->component[u] >= 0 || cx->group[cx->members[u]] != x) continue;
                cx->component[u] = n_components;
                cx->queue[tail++] = u;
            }
        }
        cx->component_size[n_components] = tail;
        if (best < 0 || tail > cx->component_size[best]) best = n_components;
        n_components++;
    }
    for (size_t v = 0; v < m; v++)
        if (cx->component[v] >= 0 && cx->component[v] != best &&
            !cx->anchored[cx->component[v]])
            cx->group[cx->members[v]] = y;
}

static int holds_sink(const cut_context *cx, size_t m, int x) {
    for (size_t v = 0; v < m; v++)
        if (cx->is_sink[cx->members[v]] && cx->group[cx->members[v]] == x) return 1;
    return 0;
}

/* Relabels the band by the cut, keeps both segments whole, undoes it all
 * if a segment lost its last sink point. */
static void apply_cut(cut_context *cx, size_t m, size_t nb, int a, int b) {
    for (size_t i = 0; i < nb; i++) cx->group[cx->members[cx->band[i]]] = cx->side[i] ? a : b;
    keep_largest_piece(cx, m, a, b);
    keep_largest_piece(cx, m, b, a);
    if (holds_sink(cx, m, a) && holds_sink(cx, m, b)) return;
    for (size_t v = 0; v < m; v++) cx->group[cx->members[v]] = cx->old_group[v];
}

static ps_status cut_pair(cut_context *cx, int a, int b, ps_error *err) {
    size_t m = collect_members(cx, a, b);
    size_t n_sources = build_subgraph(cx, m);
    ps_status st = PS_OK;
    if (n_sources > 0) {
        boundary_distances(cx, m, n_sources);
        size_t nb = mark_band(cx, m, band_width(cx, m, a), a);
        ps_flow_graph net;
        double flow;
        if (build_network(cx, nb, &net)) {
            st = ps_maxflow(&net, (uint32_t)nb, (uint32_t)nb + 1, &flow, cx->side, err);
            if (st == PS_OK) apply_cut(cx, m, nb, a, b);
        }
    }
    for (size_t v = 0; v < m; v++) cx->local_of[cx->members[v]] = NOT_LOCAL;
    return st;
}

static int by_size_then_ids(const void *x, const void *y) {
    const pair *p = x, *q = y;
    if (p->small != q->small) return p->small < q->small ? -1 : 1;
    if (p->large != q->large) return p->large < q->large ? -1 : 1;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    return (p->b > q->b) - (p->b < q->b);
}

/* Adjacent segment pairs, in processing order; NULL when out of memory. */
static pair *adjacent_pairs(const cut_context *cx, size_t *count) {
    const ps_graph *g = cx->in->graph;
    size_t crossing = 0, n_pairs = 0;
    for (size_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
            crossing += g->neighbors[e] > p && cx->group[g->neighbors[e]] != cx->group[p];
    pair *pairs = malloc((crossing ? crossing : 1) * sizeof *pairs);
    size_t *size = calloc((size_t)cx->in->n_groups, sizeof *size);
    if (!pairs || !size) {
        free(pairs);
        free(size);
        return NULL;
    }
    for (size_t p = 0; p < g->n; p++) size[cx->group[p]]++;
    for (size_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            int x = cx->group[p], y = cx->group[g->neighbors[e]];
            if (g->neighbors[e] <= p || x == y) continue;
            int a = x < y ? x : y, b = x < y ? y : x;
            size_t sa = size[a], sb = size[b];
            pairs[n_pairs++] = (pair){a, b, sa < sb ? sa : sb, sa < sb ? sb : sa};
        }
    qsort(pairs, n_pairs, sizeof *pairs, by_size_then_ids);
    size_t kept = 0;
    for (size_t i = 0; i < n_pairs; i++)
        if (kept == 0 || pairs[kept - 1].a != pairs[i].a || pairs[kept - 1].b != pairs[i].b)
            pairs[kept++] = pairs[i];
    free(size);
    *count = kept;
    return pairs;
}

/* Points whose supernode's sink left their segment join a neighbour's
 * supernode in their own segment, breadth first; one with no such
 * neighbour anywhere goes back to its supernode's segment. */
static void reassign_supernodes(cut_context *cx, int *supernode_of) {
    const ps_graph *g = cx->in->graph;
    const uint32_t *sinks = cx->in->sinks;
    unsigned char *settled = cx->is_sink; /* reused: sinks are no longer needed */
    size_t head = 0, tail = 0;
    for (uint32_t p = 0; p < g->n; p++) {
        settled[p] = cx->group[p] == cx->group[sinks[supernode_of[p]]];
        if (settled[p]) cx->queue[tail++] = p;
    }
    while (head < tail) {
        uint32_t v = cx->queue[head++];
        for (size_t e = g->offsets[v]; e < g->offsets[v + 1]; e++) {
            uint32_t u = g->neighbors[e];
            if (settled[u] || cx->group[u] != cx->group[v]) continue;
            settled[u] = 1;
            supernode_of[u] = supernode_of[v];
            cx->queue[tail++] = u;
        }
    }
    for (size_t p = 0; p < g->n; p++)
        if (!settled[p]) cx->group[p] = cx->group[sinks[supernode_of[p]]];
}

static void context_free(cut_context *cx) {
    free(cx->capacity);
    free(cx->is_sink);
    free(cx->local_of);
    free(cx->members);
    free(cx->old_group);
    free(cx->sub.offsets);
    free(cx->sub.neighbors);
    free(cx->sub.weights);
    free(cx->sub_capacity);
    free(cx->sources);
    free(cx->dist);
    ps_dijkstra_free(cx->dijkstra);
    free(cx->band_of);
    free(cx->band);
    free(cx->tie_source);
    free(cx->tie_sink);
    free(cx->net_offsets);
    free(cx->net_heads);
    free(cx->net_capacity);
    free(cx->side);
    free(cx->component);
    free(cx->component_size);
    free(cx->anchored);
    free(cx->queue);
}

static int context_init(cut_context *cx, const ps_boundary_cut_input *in, int *group) {
    size_t n = in->graph->n, arcs = in->graph->offsets[n] + 1, net_arcs = arcs + 4 * n;
    *cx = (cut_context){.in = in, .group = group};
    cx->capacity = malloc(arcs * sizeof *cx->capacity);
    cx->is_sink = calloc(n, sizeof *cx->is_sink);
    cx->local_of = malloc(n * sizeof *cx->local_of);
    cx->members = malloc(n * sizeof *cx->members);
    cx->old_group = malloc(n * sizeof *cx->old_group);
    cx->sub.offsets = malloc((n + 1) * sizeof *cx->sub.offsets);
    cx->sub.neighbors = malloc(arcs * sizeof *cx->sub.neighbors);
    cx->sub.weights = malloc(arcs * sizeof *cx->sub.weights);
    cx->sub_capacity = malloc(arcs * sizeof *cx->sub_capacity);
    cx->sources = malloc(n * sizeof *cx->sources);
    cx->dist = malloc(n * sizeof *cx->dist);
    cx->dijkstra = ps_dijkstra_new(n);
    cx->band_of = malloc(n * sizeof *cx->band_of);
    cx->band = malloc(n * sizeof *cx->band);
    cx->tie_source = malloc(n * sizeof *cx->tie_source);
    cx->tie_sink = malloc(n * sizeof *cx->tie_sink);
    cx->net_offsets = malloc((n + 3) * sizeof *cx->net_offsets);
    cx->net_heads = malloc(net_arcs * sizeof *cx->net_heads);
    cx->net_capacity = malloc(net_arcs * sizeof *cx->net_capacity);
    cx->side = malloc((n + 2) * sizeof *cx->side);
    cx->component = malloc(n * sizeof *cx->component);
    cx->component_size = malloc(n * sizeof *cx->component_size);
    cx->anchored = malloc(n * sizeof *cx->anchored);
    cx->queue = malloc(n * sizeof *cx->queue);
    if (!cx->capacity || !cx->is_sink || !cx->local_of || !cx->members || !cx->old_group ||
        !cx->sub.offsets || !cx->sub.neighbors || !cx->sub.weights || !cx->sub_capacity ||
        !cx->sources || !cx->dist || !cx->dijkstra || !cx->band_of || !cx->band ||
        !cx->tie_source || !cx->tie_sink || !cx->net_offsets || !cx->net_heads ||
        !cx->net_capacity || !cx->side || !cx->component || !cx->component_size || !cx->anchored ||
        !cx->queue)
        return -1;
    for (size_t p = 0; p < n; p++) cx->local_of[p] = NOT_LOCAL;
    for (int s = 0; s < in->n_supernodes; s++) cx->is_sink[in->sinks[s]] = 1;
    return 0;
}

ps_status ps_boundary_cut(const ps_boundary_cut_input *in, int *group, int *supernode_of,
                          ps_error *err) {
    if (in->graph->n == 0 || in->graph->offsets[in->graph->n] == 0) return PS_OK;
    cut_context cx;
    size_t n_pairs = 0;
    pair *pairs = NULL;
    ps_status st = PS_OK;
    if (context_init(&cx, in, group) != 0 || !(pairs = adjacent_pairs(&cx, &n_pairs)))
        st = ps_fail(err, PS_ERR_NOMEM, "out of memory (boundary cut)");
    if (st == PS_OK) edge_capacities(&cx);
    for (size_t i = 0; st == PS_OK && i < n_pairs; i++)
        st = cut_pair(&cx, pairs[i].a, pairs[i].b, err);
    if (st == PS_OK) reassign_supernodes(&cx, supernode_of);
    free(pairs);
    context_free(&cx);
    return st;
}
