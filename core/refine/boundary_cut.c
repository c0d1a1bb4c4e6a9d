/*
 * boundary_cut.c: boundaries between adjacent segments moved onto minimum
 * cuts along concave creases (boundary_cut.h).  This file is the driver:
 * the state's set-up, the edge capacities, the adjacent pairs and their
 * order, each pair's cut (undone if a segment lost its last sink point),
 * and the supernodes reassigned at the end.  A pair's boundary, band and
 * flow network are in boundary_cut_band.c, the keep-largest-piece search
 * in boundary_cut_pieces.c, the state they share in boundary_cut_context.h
 * (private to these three files).  Pairs with no segment in common run side
 * by side (keyed_tasks.h), each worker with its own scratch arrays.
 *
 * Per pair (A, B) the work follows the band, not the segments:
 *   - the shared boundary comes from the pair's boundary points found once
 *     at the start plus the points moved into A or B by earlier cuts (and
 *     their neighbours), each checked against the current segments;
 *   - ball Dijkstras on the kNN graph itself (edge lengths measured
 *     between the points as they go, no copy of the graph), one per
 *     segment from its own boundary points (no shortest path from the
 *     boundary into A passes through B), measure the distance from the
 *     boundary: the first, into the smaller segment, out to the distance
 *     beyond which the band's width is capped; the second only as far as
 *     the first one's extent leaves the width open;
 *   - a segment's extent is that distance when its ball missed some of its
 *     points (per-segment point counts are kept up to date), else the
 *     largest distance reached, exactly as a scan of all members would
 *     give;
 *   - a segment with a witness (one of its extreme points along the axes
 *     at the start, still in it) that far from every boundary point in a
 *     straight line extends that far, since no path is shorter: its ball
 *     goes only as far as the band, whose width the other segment fixes;
 *   - a piece a cut leaves inside the band is found inside the band; only
 *     when one is loose does a search outside it, stopped once a piece is
 *     larger, tell whether an anchored piece is the largest;
 *   - per-segment sink counts say whether a cut left a segment without one.
 * A sink point's "infinite" tie to its side is one plus every capacity of
 * the band's network, so no pass covers the whole pair.  An arc's capacity
 * is computed when a band first needs it (most arcs never are).  Every
 * scratch array is sized once.
 */
#include "refine/boundary_cut.h"
#include "refine/boundary_cut_context.h"

#include "features/crease.h"
#include "graph/dijkstra.h"
#include "util/control.h"
#include "util/keyed_tasks.h"
#include "util/maxflow.h"
#include "util/parallel.h"
#include "util/sort_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct pair {
    int a, b;             /* a < b */
    size_t small, large;  /* sizes of the smaller and larger segment */
} pair;

/* L, A0 and whether the surface has creases, from the edges' scales. */
static void edge_scales(cut_context *cx) {
    cx->mean_edge = cx->in->scales.mean_length;
    cx->angle_scale = PS_BOUNDARY_CUT_ANGLE * cx->in->scales.mean_concave;
    cx->creased = cx->in->scales.mean_concave >= PS_CREASE_FLAT;
}

/* The arc of row q leading to p (rows are sorted and the graph is
 * symmetric, so there is one): a binary search whose steps depend only on
 * the row's length, each a conditional move rather than a branch. */
static size_t reverse_arc(const ps_graph *g, size_t q, uint32_t p) {
    const uint32_t *at = g->neighbors + g->offsets[q];
    size_t n = g->offsets[q + 1] - g->offsets[q];
    while (n > 1) {
        size_t half = n / 2;
        at = at[half] <= p ? at + half : at;
        n -= half;
    }
    return (size_t)(at - g->neighbors);
}

/* capacity[e] = |p-q| / L * exp(-ang / A0) of arc e out of p, set for
 * both arcs of the edge: ps_crease_angular and ps_distance3 give the same
 * bits either way round.  The reverse arc leaves a point of the same pair,
 * so its worker owns it. */
double ps_bc_new_capacity(cut_context *cx, uint32_t p, size_t e) {
    const double *x = cx->in->points, *nx = cx->in->normals;
    size_t q = cx->in->graph->neighbors[e], i = p;
    double ang = ps_crease_angular(x + 3 * i, nx + 3 * i, x + 3 * q, nx + 3 * q, 0.0);
    double crease = cx->creased && ang > 0 ? exp(-ang / cx->angle_scale) : 1;
    double c = ps_distance3(x + 3 * i, x + 3 * q) / cx->mean_edge * crease;
    cx->capacity[e] = cx->capacity[reverse_arc(cx->in->graph, q, p)] = c;
    return c;
}

/* Segment of p becomes g, keeping the per-segment counts. */
void ps_bc_set_group(cut_context *cx, uint32_t p, int g) {
    int old = ps_bc_group(cx, p);
    if (old == g) return;
    cx->size[old]--;
    cx->size[g]++;
    cx->sinks_in[old] -= cx->is_sink[p];
    cx->sinks_in[g] += cx->is_sink[p];
    __atomic_store_n(&cx->group[p], g, __ATOMIC_RELAXED);
}

static int log_move(move_log *log, uint32_t p, int g) {
    if (log->count[g] == log->capacity[g]) {
        size_t capacity = log->capacity[g] ? 2 * log->capacity[g] : 64;
        uint32_t *point = realloc(log->point[g], capacity * sizeof *point);
        if (!point) return -1;
        log->point[g] = point, log->capacity[g] = capacity;
    }
    log->point[g][log->count[g]++] = p;
    return 0;
}

/* Relabels the band by the cut, keeps both segments whole, undoes it all
 * if a segment lost its last sink point. */
static void apply_cut(cut_context *cx, size_t nb, int a, int b) {
    for (size_t i = 0; i < nb; i++) ps_bc_set_group(cx, cx->s.band[i], cx->s.side[i] ? a : b);
    ps_bc_keep_largest_piece(cx, nb, a, b);
    ps_bc_keep_largest_piece(cx, nb, b, a);
    if (cx->sinks_in[a] > 0 && cx->sinks_in[b] > 0) return;
    for (size_t i = 0; i < nb; i++) ps_bc_set_group(cx, cx->s.band[i], cx->s.old_group[i]);
}

/* Logs the band points that changed segment; clears the band and ball. */
static int finish_pair(cut_context *cx, size_t nb, size_t n_reached) {
    int failed = 0;
    for (size_t i = 0; i < nb; i++) {
        uint32_t p = cx->s.band[i];
        int now = ps_bc_group(cx, p);
        if (now != cx->s.old_group[i] && !failed) failed = log_move(cx->moves, p, now) != 0;
        cx->s.band_of[p] = NOT_IN_BAND;
    }
    for (size_t i = 0; i < n_reached; i++) cx->s.dist[cx->s.reached[i]] = INFINITY;
    return failed ? -1 : 0;
}

static ps_status cut_pair(cut_context *cx, int a, int b, ps_error *err) {
    if (ps_bc_boundary_points(cx, a, b) == 0) return PS_OK;
    double reach = PS_BOUNDARY_CUT_MAX_EDGES * cx->mean_edge / PS_BOUNDARY_CUT_BAND;
    double width;
    size_t n_reached = ps_bc_boundary_distances(cx, a, b, reach, &width);
    size_t nb = ps_bc_mark_band(cx, n_reached, width, a, b);
    ps_maxflow_graph net;
    double flow;
    ps_status st = PS_OK;
    if (ps_bc_build_network(cx, nb, &net)) {
        st = ps_maxflow_with(cx->s.flow_space, &net, (uint32_t)nb, (uint32_t)nb + 1, &flow,
                             cx->s.side, err);
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

/* Appends (a, b, p) to the n entries of list (room for *room, grown as
 * needed); -1 when out of memory. */
static int append_entry(boundary_entry **list, size_t *n, size_t *room, boundary_entry entry) {
    if (*n == *room) {
        size_t more = *room ? 2 * *room : 1024;
        boundary_entry *grown = realloc(*list, more * sizeof *grown);
        if (!grown) return -1;
        *list = grown, *room = more;
    }
    (*list)[(*n)++] = entry;
    return 0;
}

/* Each point's entries, one per other segment next to it, in point order;
 * the count, or SIZE_MAX when out of memory. */
static size_t boundary_entries(const cut_context *cx, boundary_entry **list) {
    const ps_graph *g = cx->in->graph;
    size_t n = 0, room = 0;
    *list = NULL;
    for (uint32_t p = 0; p < g->n; p++) {
        size_t first = n;
        int x = cx->group[p];
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            int y = cx->group[g->neighbors[e]];
            if (x == y) continue;
            boundary_entry entry = {x < y ? x : y, x < y ? y : x, p};
            size_t i = first;
            while (i < n && ((*list)[i].a != entry.a || (*list)[i].b != entry.b)) i++;
            if (i == n && append_entry(list, &n, &room, entry) != 0) return SIZE_MAX;
        }
    }
    return n;
}

/* Stable counting sort of the n entries of from into to by their a (first
 * 1) or b (first 0) over groups segments; count: groups + 1 scratch. */
static void sort_entries(const boundary_entry *from, boundary_entry *to, size_t n, int first,
                         size_t groups, size_t *count) {
    for (size_t g = 0; g <= groups; g++) count[g] = 0;
    for (size_t i = 0; i < n; i++) count[(size_t)(first ? from[i].a : from[i].b) + 1]++;
    for (size_t g = 0; g < groups; g++) count[g + 1] += count[g];
    for (size_t i = 0; i < n; i++) to[count[first ? from[i].a : from[i].b]++] = from[i];
}

/* Every pair's boundary points at the start, sorted by (a, b, point): the
 * entries in point order, sorted stably by b, then by a. */
static int initial_boundaries(cut_context *cx) {
    size_t groups = cx->in->n_groups > 0 ? (size_t)cx->in->n_groups : 1;
    boundary_entry *list;
    size_t n = boundary_entries(cx, &list);
    boundary_entry *by_b = malloc((n && n != SIZE_MAX ? n : 1) * sizeof *by_b);
    size_t *count = malloc((groups + 1) * sizeof *count);
    int ok = n != SIZE_MAX && by_b && count;
    if (ok) {
        sort_entries(list, by_b, n, 0, groups, count);
        sort_entries(by_b, list, n, 1, groups, count);
        cx->initial = list, cx->n_initial = n;
    } else {
        free(list);
    }
    free(by_b);
    free(count);
    return ok ? 0 : -1;
}

/* Points whose supernode's sink left their segment join a neighbour's
 * supernode in their own segment, breadth first from every other point in
 * point order; one with no such neighbour anywhere goes back to its
 * supernode's segment.  The search starts from the other points next to
 * one of them in their segment, in point order, the only ones of the
 * first round that reach any. */
static void reassign_supernodes(cut_context *cx, int *supernode_of) {
    const ps_graph *g = cx->in->graph;
    const uint32_t *sinks = cx->in->sinks;
    unsigned char *settled = cx->is_sink; /* reused: sinks are no longer needed */
    uint32_t *loose = cx->s.band, *next = cx->s.reached; /* free after the pairs */
    size_t n_loose = 0, head = 0, tail = 0;
    for (uint32_t p = 0; p < g->n; p++) {
        settled[p] = cx->group[p] == cx->group[sinks[supernode_of[p]]];
        if (!settled[p]) loose[n_loose++] = p;
    }
    for (size_t i = 0; i < n_loose; i++)
        for (size_t e = g->offsets[loose[i]]; e < g->offsets[loose[i] + 1]; e++) {
            uint32_t v = g->neighbors[e];
            if (settled[v] == 1 && cx->group[v] == cx->group[loose[i]])
                settled[v] = 2, cx->s.queue[tail++] = v;
        }
    ps_sort_u32(cx->s.queue, tail, next);
    while (head < tail) {
        uint32_t v = cx->s.queue[head++];
        for (size_t e = g->offsets[v]; e < g->offsets[v + 1]; e++) {
            uint32_t u = g->neighbors[e];
            if (settled[u] || cx->group[u] != cx->group[v]) continue;
            settled[u] = 1;
            supernode_of[u] = supernode_of[v];
            cx->s.queue[tail++] = u;
        }
    }
    for (size_t i = 0; i < n_loose; i++)
        if (!settled[loose[i]]) cx->group[loose[i]] = cx->group[sinks[supernode_of[loose[i]]]];
}

/* s's arrays; s is then empty. */
static void scratch_free(cut_scratch *s) {
    free(s->block);
    ps_dijkstra_free(s->dijkstra);
    ps_maxflow_workspace_free(s->flow_space);
    *s = (cut_scratch){0};
}

static void moves_free(move_log *log, size_t groups) {
    for (size_t g = 0; log && log->point && g < groups; g++) free(log->point[g]);
    if (log) free(log->point), free(log->count), free(log->capacity);
    free(log);
}

/* The shared arrays. */
static void context_free(cut_context *cx) {
    free(cx->size);
    free(cx->sinks_in);
    free(cx->capacity);
    free(cx->is_sink);
    free(cx->witness);
    free(cx->initial);
    moves_free(cx->moves, cx->in->n_groups > 0 ? (size_t)cx->in->n_groups : 1);
}

/* p becomes a witness of its segment where it is lower or higher along an
 * axis than the witness so far; at: #groups by WITNESSES, each witness's
 * coordinate along its axis. */
static void consider_witness(cut_context *cx, uint32_t p, double *at) {
    const double *x = cx->in->points + 3 * (size_t)p;
    size_t first = (size_t)cx->group[p] * WITNESSES;
    uint32_t *w = cx->witness + first;
    double *w_at = at + first;
    for (int d = 0; d < 3; d++) {
        if (w[2 * d] == NO_WITNESS || x[d] < w_at[2 * d]) w[2 * d] = p, w_at[2 * d] = x[d];
        if (w[2 * d + 1] == NO_WITNESS || x[d] > w_at[2 * d + 1])
            w[2 * d + 1] = p, w_at[2 * d + 1] = x[d];
    }
}

/* Per-point, per-segment and per-arc state from the input segments; -1
 * when out of memory. */
static int shared_fill(cut_context *cx) {
    const ps_boundary_cut_input *in = cx->in;
    size_t n = in->graph->n, witnesses = (size_t)in->n_groups * WITNESSES;
    double *at = malloc((witnesses ? witnesses : 1) * sizeof *at);
    if (!at) return -1;
    for (int s = 0; s < in->n_supernodes; s++) cx->is_sink[in->sinks[s]] = 1;
    for (size_t i = 0; i < witnesses; i++) cx->witness[i] = NO_WITNESS;
    for (uint32_t p = 0; p < n; p++) {
        cx->size[cx->group[p]]++;
        cx->sinks_in[cx->group[p]] += cx->is_sink[p];
        consider_witness(cx, p, at);
    }
    free(at);
    return 0;
}

static int shared_init(cut_context *cx, const ps_boundary_cut_input *in, int *group) {
    size_t n = in->graph->n, arcs = in->graph->offsets[n] + 1;
    size_t groups = in->n_groups > 0 ? (size_t)in->n_groups : 1;
    *cx = (cut_context){.in = in, .group = group};
    cx->size = calloc(groups, sizeof *cx->size);
    cx->sinks_in = calloc(groups, sizeof *cx->sinks_in);
    cx->capacity = calloc(arcs, sizeof *cx->capacity);
    cx->is_sink = calloc(n, sizeof *cx->is_sink);
    cx->witness = malloc(groups * WITNESSES * sizeof *cx->witness);
    cx->moves = calloc(1, sizeof *cx->moves);
    if (cx->moves) {
        cx->moves->point = calloc(groups, sizeof *cx->moves->point);
        cx->moves->count = calloc(groups, sizeof *cx->moves->count);
        cx->moves->capacity = calloc(groups, sizeof *cx->moves->capacity);
    }
    if (!cx->size || !cx->sinks_in || !cx->capacity || !cx->is_sink || !cx->witness ||
        !cx->moves || !cx->moves->point || !cx->moves->count || !cx->moves->capacity)
        return -1;
    if (shared_fill(cx) != 0) return -1;
    return initial_boundaries(cx);
}

/* The start of count items of size bytes from byte *at of block (64-byte
 * aligned), *at then past them; NULL with no block (sizing only). */
static void *carve(unsigned char *block, size_t *at, size_t count, size_t size) {
    size_t start = (*at + 63) & ~(size_t)63;
    *at = start + (count ? count : 1) * size;
    return block ? block + start : NULL;
}

/* s's arrays for n points, net_arcs network arcs and groups segments,
 * carved out of block (or only sized, with no block); the block's size. */
static size_t carve_scratch(cut_scratch *s, unsigned char *block, size_t n, size_t net_arcs,
                            size_t groups) {
    size_t at = 0;
    s->sources = carve(block, &at, n, sizeof *s->sources);
    s->region_mark = carve(block, &at, groups, sizeof *s->region_mark);
    s->seen = carve(block, &at, n, sizeof *s->seen);
    s->visited = carve(block, &at, n, sizeof *s->visited);
    s->dist = carve(block, &at, n, sizeof *s->dist);
    s->reached = carve(block, &at, n, sizeof *s->reached);
    s->band_of = carve(block, &at, n, sizeof *s->band_of);
    s->band = carve(block, &at, n, sizeof *s->band);
    s->old_group = carve(block, &at, n, sizeof *s->old_group);
    s->tie_a = carve(block, &at, n, sizeof *s->tie_a);
    s->tie_b = carve(block, &at, n, sizeof *s->tie_b);
    s->outside = carve(block, &at, n, sizeof *s->outside);
    s->net_offsets = carve(block, &at, n + 3, sizeof *s->net_offsets);
    s->net_heads = carve(block, &at, net_arcs, sizeof *s->net_heads);
    s->net_capacity = carve(block, &at, net_arcs, sizeof *s->net_capacity);
    s->side = carve(block, &at, n + 2, sizeof *s->side);
    s->piece = carve(block, &at, n, sizeof *s->piece);
    s->piece_start = carve(block, &at, n, sizeof *s->piece_start);
    s->piece_size = carve(block, &at, n, sizeof *s->piece_size);
    s->anchored = carve(block, &at, n, sizeof *s->anchored);
    s->queue = carve(block, &at, n, sizeof *s->queue);
    return at;
}

/* s's arrays for in, in the state between pairs, all in one block (one
 * allocation and one release a worker); -1 when out of memory (s is then
 * empty). */
static int scratch_alloc(cut_scratch *s, const ps_boundary_cut_input *in) {
    size_t n = in->graph->n, net_arcs = in->graph->offsets[n] + 1 + 4 * n;
    size_t groups = in->n_groups > 0 ? (size_t)in->n_groups : 1;
    *s = (cut_scratch){0};
    s->block = malloc(carve_scratch(s, NULL, n, net_arcs, groups));
    s->dijkstra = ps_dijkstra_new(n);
    s->flow_space = ps_maxflow_workspace_new();
    if (!s->block || !s->dijkstra || !s->flow_space) {
        scratch_free(s);
        return -1;
    }
    carve_scratch(s, s->block, n, net_arcs, groups);
    memset(s->region_mark, 0, groups * sizeof *s->region_mark);
    memset(s->seen, 0, n * sizeof *s->seen);
    memset(s->visited, 0, n * sizeof *s->visited);
    for (size_t p = 0; p < n; p++) s->band_of[p] = NOT_IN_BAND, s->dist[p] = INFINITY;
    return 0;
}

/* How many pairs may run side by side: one per thread, at most
 * PS_BOUNDARY_CUT_WORKERS, and one alone above PS_BOUNDARY_CUT_SIDE_BY_SIDE
 * points (each worker has its own per-point scratch). */
static int worker_count(const ps_boundary_cut_input *in) {
    int threads = ps_parallel_threads(in->threads);
    if (in->graph->n > PS_BOUNDARY_CUT_SIDE_BY_SIDE) return 1;
    return threads < PS_BOUNDARY_CUT_WORKERS ? threads : PS_BOUNDARY_CUT_WORKERS;
}

typedef struct cut_run {
    cut_context *workers;     /* #workers; the first is the driver's */
    const pair *pairs;
    size_t n_pairs;
    ps_error *errors;         /* #workers */
} cut_run;

static ps_status cut_task(void *ctx, size_t i, int worker) {
    cut_run *r = ctx;
    cut_context *cx = &r->workers[worker];
    const ps_progress_span *span = cx->in->span;
    if (span && ps_control_cancelled(span->ctl))
        return ps_fail(&r->errors[worker], PS_ERR_CANCELLED, "cancelled");
    return cut_pair(cx, r->pairs[i].a, r->pairs[i].b, &r->errors[worker]);
}

static void cut_report(void *ctx, size_t done) {
    const cut_run *r = ctx;
    const ps_progress_span *span = r->workers[0].in->span;
    if (span)
        ps_control_progress(span->ctl, span->phase,
                            ps_progress_span_at(span, (double)done / (double)r->n_pairs));
}

/* Every pair, side by side where they share no segment (keyed_tasks.h:
 * the result is that of one worker taking them in order).  The workers
 * are copies of first with scratch of their own: the first first's,
 * worker i scratch[i] (scratch: #PS_BOUNDARY_CUT_WORKERS), allocated
 * here; each is left where it came from (the caller frees them). */
static ps_status cut_pairs(cut_context *first, cut_scratch *scratch, const pair *pairs,
                           size_t n_pairs, ps_error *err) {
    int workers = worker_count(first->in);
    cut_context *w = calloc((size_t)workers, sizeof *w);
    ps_error *errors = calloc((size_t)workers, sizeof *errors);
    int *keys = malloc(2 * (n_pairs ? n_pairs : 1) * sizeof *keys);
    ps_status st = PS_OK;
    if (!w || !errors || !keys) st = ps_fail(err, PS_ERR_NOMEM, "out of memory (boundary cut)");
    for (int i = 1; st == PS_OK && i < workers; i++)
        if (scratch_alloc(&scratch[i], first->in) != 0)
            st = ps_fail(err, PS_ERR_NOMEM, "out of memory (boundary cut)");
    if (st == PS_OK) {
        for (int i = 0; i < workers; i++) w[i] = *first, w[i].s = i ? scratch[i] : first->s;
        for (size_t i = 0; i < n_pairs; i++) keys[i] = pairs[i].a, keys[n_pairs + i] = pairs[i].b;
        cut_run r = {w, pairs, n_pairs, errors};
        ps_keyed_tasks tasks = {.count = n_pairs, .key_a = keys, .key_b = keys + n_pairs,
                                .n_keys = first->in->n_groups, .run = cut_task,
                                .report = cut_report, .ctx = &r};
        int failed = -1;
        st = ps_keyed_tasks_run(&tasks, workers, &failed);
        if (st != PS_OK && failed >= 0 && err) *err = errors[failed];
        else if (st != PS_OK) ps_fail(err, st, "out of memory (boundary cut)");
        first->s = w[0].s;
        for (int i = 1; i < workers; i++) scratch[i] = w[i].s;
    }
    free(w), free(errors), free(keys);
    return st;
}

ps_status ps_boundary_cut(const ps_boundary_cut_input *in, int *group, int *supernode_of,
                          ps_error *err) {
    if (in->graph->n == 0 || in->graph->offsets[in->graph->n] == 0) return PS_OK;
    cut_scratch scratch[PS_BOUNDARY_CUT_WORKERS] = {{0}};
    cut_context cx;
    size_t n_pairs = 0;
    pair *pairs = NULL;
    ps_status st = PS_OK;
    if (shared_init(&cx, in, group) != 0 || scratch_alloc(&scratch[0], in) != 0 ||
        !(pairs = adjacent_pairs(&cx, &n_pairs)))
        st = ps_fail(err, PS_ERR_NOMEM, "out of memory (boundary cut)");
    cx.s = scratch[0];
    if (st == PS_OK) edge_scales(&cx);
    if (st == PS_OK) st = cut_pairs(&cx, scratch, pairs, n_pairs, err);
    if (st == PS_OK) reassign_supernodes(&cx, supernode_of);
    scratch[0] = cx.s;
    free(pairs);
    context_free(&cx);
    for (int i = 0; i < PS_BOUNDARY_CUT_WORKERS; i++) scratch_free(&scratch[i]);
    return st;
}
