/*
 * boundary_cut.c: boundaries between adjacent segments moved onto minimum
 * cuts along concave creases (boundary_cut.h).
 *
 * Per pair (A, B) the work follows the band, not the segments:
 *   - the shared boundary comes from the pair's boundary points found once
 *     at the start plus the points moved into A or B by earlier cuts (and
 *     their neighbours), each checked against the current segments;
 *   - one ball Dijkstra on the whole graph, kept to A and B and to the
 *     distance beyond which the band's width is capped, measures the
 *     distance from the boundary; a last graph vertex whose row is the
 *     boundary (zero lengths) is its single source;
 *   - a segment's extent is that cap when the ball missed some of its points
 *     (per-segment point counts are kept up to date), else the largest
 *     distance reached, exactly as a scan of all members would give;
 *   - a piece a cut leaves inside the band is found inside the band; only
 *     when one is loose does a search outside it, stopped once a piece is
 *     larger, tell whether an anchored piece is the largest;
 *   - per-segment sink counts say whether a cut left a segment without one.
 * The only whole-pair pass left is the terminals' "infinite" tie (one plus
 * every capacity of the pair, summed in point order as before), needed
 * when a sink point lies in the band.  Every scratch array is sized once.
 */
#include "boundary_cut.h"

#include "crease.h"
#include "dijkstra.h"
#include "maxflow.h"
#include "sort_util.h"

#include <math.h>
#include <stdlib.h>

#define NOT_IN_BAND UINT32_MAX
#define NO_MOVE SIZE_MAX

typedef struct pair {
    int a, b;             /* a < b */
    size_t small, large;  /* sizes of the smaller and larger segment */
} pair;

/* A point on the boundary between segments a < b at the start. */
typedef struct boundary_entry {
    int a, b;
    uint32_t point;
} boundary_entry;

/* Points moved into each segment by the cuts so far: one list per segment,
 * linked through next, newest first. */
typedef struct move_log {
    uint32_t *point;  /* #count */
    size_t *next;     /* #count the segment's previous entry, or NO_MOVE */
    size_t *head;     /* #groups newest entry of each segment, or NO_MOVE */
    size_t count, capacity;
} move_log;

typedef struct cut_context {
    const ps_boundary_cut_input *in;
    int *group;                /* #P in/out */
    uint32_t *label;           /* #P+1 group as uint32_t, the ball's region labels */
    size_t *size;              /* #groups points of each segment, kept current */
    size_t *sinks_in;          /* #groups sink points of each segment, kept current */
    double *capacity;          /* #E cut capacity of every graph arc */
    unsigned char *is_sink;    /* #P */
    double mean_edge;          /* mean Euclidean kNN edge length */
    ps_graph geo;              /* #P+1 vertices: the graph, Euclidean lengths, and a
                                * source vertex whose row is the pair's boundary */
    ps_dijkstra *dijkstra;     /* for #P+1 vertices */
    uint32_t stamp;            /* bumped for each ball, boundary and piece search */
    uint32_t *region_mark;     /* #groups stamp of the segments the ball may enter */
    uint32_t *seen;            /* #P stamp of the boundary candidates checked */
    uint32_t *visited;         /* #P stamp of the points a piece search reached */
    double *dist;              /* #P+1 INFINITY outside a pair's ball */
    uint32_t *reached;         /* #P+1 */
    boundary_entry *initial;   /* #I initial boundary points, sorted by (a, b, point) */
    size_t n_initial;
    move_log moves;
    uint32_t *band_of;         /* #P band index of each point, or NOT_IN_BAND */
    uint32_t *band;            /* #P band points, increasing */
    int *old_group;            /* #P group of each band point before the cut */
    double *tie_source;        /* #P */
    double *tie_sink;          /* #P */
    size_t *net_offsets;       /* #P+3 */
    uint32_t *net_heads;       /* #E+4#P */
    double *net_capacity;      /* #E+4#P */
    unsigned char *side;       /* #P+2 */
    ps_maxflow_workspace *flow_space;  /* reused by every pair's max flow */
    int *piece;                /* #P piece of each band point of the segment searched */
    uint32_t *piece_start;     /* #P first band index of each piece (its lowest point) */
    size_t *piece_size;        /* #P */
    unsigned char *anchored;   /* #P 1 for a piece with a neighbour outside the band */
    uint32_t *queue;           /* #P */
} cut_context;

static double distance3(const double *p, const double *q) {
    double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* capacity[e] = |p-q| / L * exp(-ang / A0) (boundary_cut.h) and the
 * Euclidean lengths of geo; the first pass keeps ang in capacity[e]. */
static void edge_capacities(cut_context *cx) {
    const ps_graph *g = cx->in->graph;
    const double *x = cx->in->points, *nx = cx->in->normals;
    size_t edges = g->offsets[g->n];
    double sum_len = 0, sum_ang = 0;
    for (size_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            size_t q = g->neighbors[e];
            cx->geo.weights[e] = distance3(x + 3 * p, x + 3 * q);
            sum_len += cx->geo.weights[e];
            cx->capacity[e] = ps_crease_angular(x + 3 * p, nx + 3 * p, x + 3 * q, nx + 3 * q, 0.0);
            sum_ang += cx->capacity[e];
        }
    double L = sum_len / (double)edges;
    cx->mean_edge = L;
    double A0 = PS_BOUNDARY_CUT_ANGLE * sum_ang / (double)edges;
    for (size_t e = 0; e < edges; e++) {
        double crease = sum_ang / (double)edges >= PS_CREASE_FLAT
                            ? exp(-cx->capacity[e] / A0) : 1;
        cx->capacity[e] = cx->geo.weights[e] / L * crease;
    }
}

/* Segment of p becomes g, keeping the per-segment counts. */
static void set_group(cut_context *cx, uint32_t p, int g) {
    int old = cx->group[p];
    if (old == g) return;
    cx->size[old]--;
    cx->size[g]++;
    cx->sinks_in[old] -= cx->is_sink[p];
    cx->sinks_in[g] += cx->is_sink[p];
    cx->group[p] = g;
    cx->label[p] = (uint32_t)g;
}

static int log_move(move_log *log, uint32_t p, int g) {
    if (log->count == log->capacity) {
        size_t capacity = log->capacity ? 2 * log->capacity : 1024;
        uint32_t *point = realloc(log->point, capacity * sizeof *point);
        if (point) log->point = point;
        size_t *next = realloc(log->next, capacity * sizeof *next);
        if (next) log->next = next;
        if (!point || !next) return -1;
        log->capacity = capacity;
    }
    log->point[log->count] = p;
    log->next[log->count] = log->head[g];
    log->head[g] = log->count++;
    return 0;
}

static int in_pair(int g, int a, int b) {
    return g == a || g == b;
}

/* p joins the boundary row (geo's last) if it lies in a or b next to the
 * other one; each point is checked once per pair. */
static void consider(cut_context *cx, uint32_t p, int a, int b, size_t *n_sources) {
    const ps_graph *g = cx->in->graph;
    if (cx->seen[p] == cx->stamp) return;
    cx->seen[p] = cx->stamp;
    if (!in_pair(cx->group[p], a, b)) return;
    int other = cx->group[p] == a ? b : a;
    for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
        if (cx->group[g->neighbors[e]] == other) {
            cx->geo.neighbors[g->offsets[g->n] + (*n_sources)++] = p;
            return;
        }
}

/* First initial entry of the pair (a, b). */
static size_t first_initial(const cut_context *cx, int a, int b) {
    size_t lo = 0, hi = cx->n_initial;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        const boundary_entry *m = &cx->initial[mid];
        if (m->a < a || (m->a == a && m->b < b)) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

/* The current boundary of (a, b) becomes geo's source row; returns its
 * size.  A point is on it now only if it was at the start or it or a
 * neighbour has moved into a or b since. */
static size_t boundary_points(cut_context *cx, int a, int b) {
    const ps_graph *g = cx->in->graph;
    size_t n_sources = 0;
    cx->stamp++;
    for (size_t i = first_initial(cx, a, b);
         i < cx->n_initial && cx->initial[i].a == a && cx->initial[i].b == b; i++)
        consider(cx, cx->initial[i].point, a, b, &n_sources);
    int ends[2] = {a, b};
    for (int k = 0; k < 2; k++)
        for (size_t m = cx->moves.head[ends[k]]; m != NO_MOVE; m = cx->moves.next[m]) {
            uint32_t p = cx->moves.point[m];
            consider(cx, p, a, b, &n_sources);
            for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
                consider(cx, g->neighbors[e], a, b, &n_sources);
        }
    cx->geo.offsets[g->n + 1] = g->offsets[g->n] + n_sources;
    return n_sources;
}

/* dist of the points of a and b within reach of the boundary (the extent
 * from which the band's width is capped); returns the reached count, the
 * boundary row's vertex first. */
static size_t boundary_distances(cut_context *cx, int a, int b, double reach) {
    cx->region_mark[a] = cx->region_mark[b] = cx->stamp;
    ps_dijkstra_limits limits = {.radius = reach, .label = cx->label,
                                 .mark = cx->region_mark, .stamp = cx->stamp};
    return ps_dijkstra_ball(cx->dijkstra, &cx->geo, (uint32_t)cx->in->graph->n, &limits,
                            cx->dist, cx->reached);
}

/* Band half-width: PS_BOUNDARY_CUT_BAND x the smaller segment's extent, at
 * most PS_BOUNDARY_CUT_MAX_EDGES mean edge lengths.  A segment with points
 * beyond reach has the extent reach. */
static double band_width(const cut_context *cx, size_t n_reached, int a, int b, double reach) {
    double extent_a = 0, extent_b = 0;
    size_t reached_a = 0;
    for (size_t i = 1; i < n_reached; i++) {
        uint32_t p = cx->reached[i];
        if (cx->group[p] == a) extent_a = fmax(extent_a, cx->dist[p]), reached_a++;
        else extent_b = fmax(extent_b, cx->dist[p]);
    }
    if (reached_a < cx->size[a]) extent_a = fmax(extent_a, reach);
    if (n_reached - 1 - reached_a < cx->size[b]) extent_b = fmax(extent_b, reach);
    return fmin(PS_BOUNDARY_CUT_BAND * fmin(extent_a, extent_b),
                PS_BOUNDARY_CUT_MAX_EDGES * cx->mean_edge);
}

/* One plus the capacities of all arcs within a and b, in point order. */
static double pair_capacity(const cut_context *cx, int a, int b) {
    const ps_graph *g = cx->in->graph;
    double total = 1;
    for (size_t p = 0; p < g->n; p++) {
        if (!in_pair(cx->group[p], a, b)) continue;
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
            if (in_pair(cx->group[g->neighbors[e]], a, b)) total += cx->capacity[e];
    }
    return total;
}

/* Ties of band point i to the terminals: its arcs to a and b outside the
 * band, plus infinite for a sink point. */
static void tie_band_point(cut_context *cx, size_t i, int a, int b, double infinite) {
    const ps_graph *g = cx->in->graph;
    uint32_t p = cx->band[i];
    int own_a = cx->group[p] == a;
    cx->tie_source[i] = cx->is_sink[p] && own_a ? infinite : 0;
    cx->tie_sink[i] = cx->is_sink[p] && !own_a ? infinite : 0;
    for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
        uint32_t q = g->neighbors[e];
        if (!in_pair(cx->group[q], a, b) || cx->band_of[q] != NOT_IN_BAND) continue;
        if (cx->group[q] == a) cx->tie_source[i] += cx->capacity[e];
        else cx->tie_sink[i] += cx->capacity[e];
    }
}

/* Band points (reached within width) in point order, ties to the
 * terminals; returns the count. */
static size_t mark_band(cut_context *cx, size_t n_reached, double width, int a, int b) {
    size_t nb = 0;
    for (size_t i = 1; i < n_reached; i++)
        if (cx->dist[cx->reached[i]] <= width) cx->band[nb++] = cx->reached[i];
    qsort(cx->band, nb, sizeof *cx->band, ps_compare_u32);
    int has_sink = 0;
    for (size_t i = 0; i < nb; i++) {
        cx->band_of[cx->band[i]] = (uint32_t)i;
        cx->old_group[i] = cx->group[cx->band[i]];
        has_sink |= cx->is_sink[cx->band[i]];
    }
    double infinite = has_sink ? pair_capacity(cx, a, b) : 0;
    for (size_t i = 0; i < nb; i++) tie_band_point(cx, i, a, b, infinite);
    return nb;
}

static void add_arc(cut_context *cx, size_t *arcs, uint32_t head, double capacity) {
    cx->net_heads[*arcs] = head;
    cx->net_capacity[(*arcs)++] = capacity;
}

/* The flow network: band nodes 0..nb-1, source nb, sink nb+1.  Returns 0
 * when a terminal has no tie (nothing to cut). */
static int build_network(cut_context *cx, size_t nb, ps_flow_graph *net) {
    const ps_graph *g = cx->in->graph;
    uint32_t source = (uint32_t)nb, sink = (uint32_t)nb + 1;
    size_t arcs = 0;
    for (size_t i = 0; i < nb; i++) {
        uint32_t p = cx->band[i];
        cx->net_offsets[i] = arcs;
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            uint32_t u = cx->band_of[g->neighbors[e]];
            if (u != NOT_IN_BAND) add_arc(cx, &arcs, u, cx->capacity[e]);
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

/* Pieces of the band points labelled x (connected within the band, in
 * order of their lowest point); a piece with an x neighbour outside the
 * band is anchored.  Returns the count. */
static int band_pieces(cut_context *cx, size_t nb, int x) {
    const ps_graph *g = cx->in->graph;
    int n_pieces = 0;
    for (size_t i = 0; i < nb; i++) cx->piece[i] = -1;
    for (uint32_t start = 0; start < nb; start++) {
        if (cx->piece[start] >= 0 || cx->group[cx->band[start]] != x) continue;
        size_t head = 0, tail = 0;
        cx->piece[start] = n_pieces;
        cx->anchored[n_pieces] = 0;
        cx->queue[tail++] = start;
        while (head < tail) {
            uint32_t p = cx->band[cx->queue[head++]];
            for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
                uint32_t q = g->neighbors[e], u = cx->band_of[q];
                if (cx->group[q] != x) continue;
                if (u == NOT_IN_BAND) cx->anchored[n_pieces] = 1;
                else if (cx->piece[u] < 0) cx->piece[u] = n_pieces, cx->queue[tail++] = u;
            }
        }
        cx->piece_start[n_pieces] = start;
        cx->piece_size[n_pieces++] = tail;
    }
    return n_pieces;
}

/* Breadth first over the unvisited points labelled x from start, stopped
 * once it holds more than cap points.  1 if that piece comes before the
 * loose piece of cap points whose lowest point is loose_start (larger, or
 * as large with a lower point); else adds its size to *explored. */
static int comes_first(cut_context *cx, uint32_t start, int x, size_t cap,
                       uint32_t loose_start, size_t *explored) {
    const ps_graph *g = cx->in->graph;
    size_t head = 0, tail = 0;
    uint32_t lowest = start;
    cx->visited[start] = cx->stamp;
    cx->queue[tail++] = start;
    while (head < tail) {
        uint32_t p = cx->queue[head++];
        if (p < lowest) lowest = p;
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            uint32_t q = g->neighbors[e];
            if (cx->group[q] != x || cx->visited[q] == cx->stamp) continue;
            cx->visited[q] = cx->stamp;
            cx->queue[tail++] = q;
            if (tail > cap) return 1;
        }
    }
    *explored += tail;
    return tail == cap && lowest < loose_start;
}

/* Whether a piece of x holding points outside the band comes before the
 * loose piece best (x's pieces, whole, ordered by size, then lowest
 * point).  Those joined to the band are searched first; the rest, not
 * joined to it, only if their points could make one as large. */
static int anchored_piece_first(cut_context *cx, size_t nb, int x, int best, size_t loose) {
    size_t cap = cx->piece_size[best], explored = 0;
    uint32_t loose_start = cx->band[cx->piece_start[best]];
    cx->stamp++;
    for (size_t i = 0; i < nb; i++)
        if (cx->piece[i] >= 0 && !cx->anchored[cx->piece[i]]) cx->visited[cx->band[i]] = cx->stamp;
    for (size_t i = 0; i < nb; i++) {
        uint32_t p = cx->band[i];
        if (cx->piece[i] < 0 || !cx->anchored[cx->piece[i]] || cx->visited[p] == cx->stamp)
            continue;
        if (comes_first(cx, p, x, cap, loose_start, &explored)) return 1;
    }
    if (cx->size[x] - loose - explored < cap) return 0;
    for (uint32_t p = 0; p < cx->in->graph->n; p++)
        if (cx->group[p] == x && cx->visited[p] != cx->stamp &&
            comes_first(cx, p, x, cap, loose_start, &explored))
            return 1;
    return 0;
}

/* Pieces of x the cut made (wholly inside the band), except the largest
 * of all x's pieces (ties: the lowest point), become y. */
static void keep_largest_piece(cut_context *cx, size_t nb, int x, int y) {
    int n_pieces = band_pieces(cx, nb, x), best = -1;
    size_t loose = 0;
    for (int k = 0; k < n_pieces; k++) {
        if (cx->anchored[k]) continue;
        loose += cx->piece_size[k];
        if (best < 0 || cx->piece_size[k] > cx->piece_size[best]) best = k;
    }
    if (best < 0) return;
    if (anchored_piece_first(cx, nb, x, best, loose)) best = -1;
    for (size_t i = 0; i < nb; i++)
        if (cx->piece[i] >= 0 && cx->piece[i] != best && !cx->anchored[cx->piece[i]])
            set_group(cx, cx->band[i], y);
}

/* Relabels the band by the cut, keeps both segments whole, undoes it all
 * if a segment lost its last sink point. */
static void apply_cut(cut_context *cx, size_t nb, int a, int b) {
    for (size_t i = 0; i < nb; i++) set_group(cx, cx->band[i], cx->side[i] ? a : b);
    keep_largest_piece(cx, nb, a, b);
    keep_largest_piece(cx, nb, b, a);
    if (cx->sinks_in[a] > 0 && cx->sinks_in[b] > 0) return;
    for (size_t i = 0; i < nb; i++) set_group(cx, cx->band[i], cx->old_group[i]);
}

/* Logs the band points that changed segment; clears the band and ball. */
static int finish_pair(cut_context *cx, size_t nb, size_t n_reached) {
    int failed = 0;
    for (size_t i = 0; i < nb; i++) {
        uint32_t p = cx->band[i];
        if (cx->group[p] != cx->old_group[i] && !failed)
            failed = log_move(&cx->moves, p, cx->group[p]) != 0;
        cx->band_of[p] = NOT_IN_BAND;
    }
    for (size_t i = 0; i < n_reached; i++) cx->dist[cx->reached[i]] = INFINITY;
    return failed ? -1 : 0;
}

static ps_status cut_pair(cut_context *cx, int a, int b, ps_error *err) {
    if (boundary_points(cx, a, b) == 0) return PS_OK;
    double reach = PS_BOUNDARY_CUT_MAX_EDGES * cx->mean_edge / PS_BOUNDARY_CUT_BAND;
    size_t n_reached = boundary_distances(cx, a, b, reach);
    size_t nb = mark_band(cx, n_reached, band_width(cx, n_reached, a, b, reach), a, b);
    ps_flow_graph net;
    double flow;
    ps_status st = PS_OK;
    if (build_network(cx, nb, &net)) {
        st = ps_maxflow_with(cx->flow_space, &net, (uint32_t)nb, (uint32_t)nb + 1, &flow,
                             cx->side, err);
        if (st == PS_OK) apply_cut(cx, nb, a, b);
    }
    if (finish_pair(cx, nb, n_reached) != 0 && st == PS_OK)
        st = ps_fail(err, PS_ERR_NOMEM, "out of memory (boundary cut)");
    return st;
}

static int by_size_then_ids(const void *x, const void *y) {
    const pair *p = x, *q = y;
    if (p->small != q->small) return p->small < q->small ? -1 : 1;
    if (p->large != q->large) return p->large < q->large ? -1 : 1;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    return (p->b > q->b) - (p->b < q->b);
}

/* Adjacent segment pairs (those with initial boundary points), in
 * processing order; NULL when out of memory. */
static pair *adjacent_pairs(const cut_context *cx, size_t *count) {
    pair *pairs = malloc((cx->n_initial ? cx->n_initial : 1) * sizeof *pairs);
    if (!pairs) return NULL;
    size_t n_pairs = 0;
    for (size_t i = 0; i < cx->n_initial; i++) {
        int a = cx->initial[i].a, b = cx->initial[i].b;
        if (n_pairs > 0 && pairs[n_pairs - 1].a == a && pairs[n_pairs - 1].b == b) continue;
        size_t sa = cx->size[a], sb = cx->size[b];
        pairs[n_pairs++] = (pair){a, b, sa < sb ? sa : sb, sa < sb ? sb : sa};
    }
    qsort(pairs, n_pairs, sizeof *pairs, by_size_then_ids);
    *count = n_pairs;
    return pairs;
}

static int by_pair_then_point(const void *x, const void *y) {
    const boundary_entry *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return (p->point > q->point) - (p->point < q->point);
}

/* Every pair's boundary points at the start, in one pass over the arcs. */
static int initial_boundaries(cut_context *cx) {
    const ps_graph *g = cx->in->graph;
    size_t arcs = 0, n = 0;
    for (size_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
            arcs += cx->group[g->neighbors[e]] != cx->group[p];
    cx->initial = malloc((arcs ? arcs : 1) * sizeof *cx->initial);
    if (!cx->initial) return -1;
    for (uint32_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            int x = cx->group[p], y = cx->group[g->neighbors[e]];
            if (x != y) cx->initial[n++] = (boundary_entry){x < y ? x : y, x < y ? y : x, p};
        }
    qsort(cx->initial, n, sizeof *cx->initial, by_pair_then_point);
    size_t kept = 0;
    for (size_t i = 0; i < n; i++)
        if (kept == 0 || by_pair_then_point(&cx->initial[kept - 1], &cx->initial[i]) != 0)
            cx->initial[kept++] = cx->initial[i];
    cx->n_initial = kept;
    return 0;
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
    free(cx->label);
    free(cx->size);
    free(cx->sinks_in);
    free(cx->capacity);
    free(cx->is_sink);
    free(cx->geo.offsets);
    free(cx->geo.neighbors);
    free(cx->geo.weights);
    ps_dijkstra_free(cx->dijkstra);
    free(cx->region_mark);
    free(cx->seen);
    free(cx->visited);
    free(cx->dist);
    free(cx->reached);
    free(cx->initial);
    free(cx->moves.point);
    free(cx->moves.next);
    free(cx->moves.head);
    free(cx->band_of);
    free(cx->band);
    free(cx->old_group);
    free(cx->tie_source);
    free(cx->tie_sink);
    free(cx->net_offsets);
    free(cx->net_heads);
    free(cx->net_capacity);
    free(cx->side);
    ps_maxflow_workspace_free(cx->flow_space);
    free(cx->piece);
    free(cx->piece_start);
    free(cx->piece_size);
    free(cx->anchored);
    free(cx->queue);
}

/* geo: the graph's rows, then an empty source row with room for #P. */
static int geo_init(cut_context *cx) {
    const ps_graph *g = cx->in->graph;
    size_t n = g->n, arcs = g->offsets[n];
    cx->geo.n = n + 1;
    cx->geo.offsets = malloc((n + 2) * sizeof *cx->geo.offsets);
    cx->geo.neighbors = malloc((arcs + n) * sizeof *cx->geo.neighbors);
    cx->geo.weights = malloc((arcs + n) * sizeof *cx->geo.weights);
    if (!cx->geo.offsets || !cx->geo.neighbors || !cx->geo.weights) return -1;
    for (size_t p = 0; p <= n; p++) cx->geo.offsets[p] = g->offsets[p];
    cx->geo.offsets[n + 1] = arcs;
    for (size_t e = 0; e < arcs; e++) cx->geo.neighbors[e] = g->neighbors[e];
    for (size_t e = arcs; e < arcs + n; e++) cx->geo.weights[e] = 0.0;
    return 0;
}

/* Per-point, per-segment and per-arc state from the input segments. */
static void context_fill(cut_context *cx) {
    const ps_boundary_cut_input *in = cx->in;
    size_t n = in->graph->n;
    for (int s = 0; s < in->n_supernodes; s++) cx->is_sink[in->sinks[s]] = 1;
    for (size_t p = 0; p < n; p++) {
        cx->label[p] = (uint32_t)cx->group[p];
        cx->size[cx->group[p]]++;
        cx->sinks_in[cx->group[p]] += cx->is_sink[p];
        cx->band_of[p] = NOT_IN_BAND;
    }
    cx->label[n] = 0;
    for (size_t p = 0; p <= n; p++) cx->dist[p] = INFINITY;
    for (int g = 0; g < in->n_groups; g++) cx->moves.head[g] = NO_MOVE;
}

static int context_init(cut_context *cx, const ps_boundary_cut_input *in, int *group) {
    size_t n = in->graph->n, arcs = in->graph->offsets[n] + 1, net_arcs = arcs + 4 * n;
    size_t groups = in->n_groups > 0 ? (size_t)in->n_groups : 1;
    *cx = (cut_context){.in = in, .group = group};
    cx->label = malloc((n + 1) * sizeof *cx->label);
    cx->size = calloc(groups, sizeof *cx->size);
    cx->sinks_in = calloc(groups, sizeof *cx->sinks_in);
    cx->capacity = malloc(arcs * sizeof *cx->capacity);
    cx->is_sink = calloc(n, sizeof *cx->is_sink);
    cx->dijkstra = ps_dijkstra_new(n + 1);
    cx->region_mark = calloc(groups, sizeof *cx->region_mark);
    cx->seen = calloc(n, sizeof *cx->seen);
    cx->visited = calloc(n, sizeof *cx->visited);
    cx->dist = malloc((n + 1) * sizeof *cx->dist);
    cx->reached = malloc((n + 1) * sizeof *cx->reached);
    cx->moves.head = malloc(groups * sizeof *cx->moves.head);
    cx->band_of = malloc(n * sizeof *cx->band_of);
    cx->band = malloc(n * sizeof *cx->band);
    cx->old_group = malloc(n * sizeof *cx->old_group);
    cx->tie_source = malloc(n * sizeof *cx->tie_source);
    cx->tie_sink = malloc(n * sizeof *cx->tie_sink);
    cx->net_offsets = malloc((n + 3) * sizeof *cx->net_offsets);
    cx->net_heads = malloc(net_arcs * sizeof *cx->net_heads);
    cx->net_capacity = malloc(net_arcs * sizeof *cx->net_capacity);
    cx->side = malloc((n + 2) * sizeof *cx->side);
    cx->flow_space = ps_maxflow_workspace_new();
    cx->piece = malloc(n * sizeof *cx->piece);
    cx->piece_start = malloc(n * sizeof *cx->piece_start);
    cx->piece_size = malloc(n * sizeof *cx->piece_size);
    cx->anchored = malloc(n * sizeof *cx->anchored);
    cx->queue = malloc(n * sizeof *cx->queue);
    if (geo_init(cx) != 0 || !cx->label || !cx->size || !cx->sinks_in || !cx->capacity ||
        !cx->is_sink || !cx->dijkstra || !cx->region_mark || !cx->seen || !cx->visited ||
        !cx->dist || !cx->reached || !cx->moves.head || !cx->band_of || !cx->band ||
        !cx->old_group || !cx->tie_source || !cx->tie_sink || !cx->net_offsets ||
        !cx->net_heads || !cx->net_capacity || !cx->side || !cx->flow_space || !cx->piece ||
        !cx->piece_start || !cx->piece_size || !cx->anchored || !cx->queue)
        return -1;
    context_fill(cx);
    return initial_boundaries(cx);
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
