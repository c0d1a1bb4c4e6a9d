/*
 * boundary_cut_band.c: one pair's band for the boundary cut
 * (boundary_cut.h): its current shared boundary, the distances from it,
 * the band's width, the band points with their ties to the terminals, and
 * the flow network the minimum cut runs on.  The state is the driver's
 * cut_context (boundary_cut_context.h, private).
 */
#include "boundary_cut_context.h"

#include "sort_util.h"

#include <math.h>
#include <stdlib.h>

static int in_pair(int g, int a, int b) {
    return g == a || g == b;
}

/* p joins the boundary points if it lies in a or b next to the other one;
 * each point is checked once per pair. */
static void consider(cut_context *cx, uint32_t p, int a, int b) {
    const ps_graph *g = cx->in->graph;
    if (cx->s.seen[p] == cx->s.stamp) return;
    cx->s.seen[p] = cx->s.stamp;
    if (!in_pair(ps_bc_group(cx, p), a, b)) return;
    int other = ps_bc_group(cx, p) == a ? b : a;
    for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
        if (ps_bc_group(cx, g->neighbors[e]) == other) {
            cx->s.sources[cx->s.n_sources++] = p;
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

/* The current boundary of (a, b) becomes the sources; returns their
 * count.  A point is on it now only if it was at the start or it or a
 * neighbour has moved into a or b since. */
size_t ps_bc_boundary_points(cut_context *cx, int a, int b) {
    const ps_graph *g = cx->in->graph;
    cx->s.n_sources = 0;
    cx->s.stamp++;
    for (size_t i = first_initial(cx, a, b);
         i < cx->n_initial && cx->initial[i].a == a && cx->initial[i].b == b; i++)
        consider(cx, cx->initial[i].point, a, b);
    int ends[2] = {a, b};
    for (int k = 0; k < 2; k++)
        for (size_t m = cx->moves->count[ends[k]]; m-- > 0;) {
            uint32_t p = cx->moves->point[ends[k]][m];
            consider(cx, p, a, b);
            for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
                consider(cx, g->neighbors[e], a, b);
        }
    return cx->s.n_sources;
}

/* Whether some witness of segment s, still in s, is at least reach away
 * (in a straight line) from every boundary point: no path is shorter than
 * a straight line, so s then extends beyond reach. */
static int far_beyond(const cut_context *cx, int s, double reach) {
    const double *x = cx->in->points;
    for (int k = 0; k < WITNESSES; k++) {
        uint32_t w = cx->witness[(size_t)s * WITNESSES + (size_t)k];
        if (w == NO_WITNESS || ps_bc_group(cx, w) != s) continue;
        size_t i = 0;
        while (i < cx->s.n_sources &&
               ps_distance3(x + 3 * (size_t)w, x + 3 * (size_t)cx->s.sources[i]) >= reach)
            i++;
        if (i == cx->s.n_sources) return 1;
    }
    return 0;
}

/* dist of the points of a and b within reach of the boundary (the extent
 * from which the band's width is capped), or within the cap in a segment
 * known to extend beyond reach; returns the reached count, the boundary
 * points first.  Segment ids are the ball's region labels (a group is
 * never negative, so it reads the same as a uint32_t). */
size_t ps_bc_boundary_distances(cut_context *cx, int a, int b, double reach) {
    cx->s.region_mark[a] = cx->s.region_mark[b] = cx->s.stamp;
    double cap = PS_BOUNDARY_CUT_BAND * reach;
    cx->s.radius_of[a] = far_beyond(cx, a, reach) ? cap : reach;
    cx->s.radius_of[b] = far_beyond(cx, b, reach) ? cap : reach;
    ps_dijkstra_limits limits = {.label = (const uint32_t *)cx->group,
                                 .mark = cx->s.region_mark, .stamp = cx->s.stamp,
                                 .radius_of = cx->s.radius_of, .points = cx->in->points};
    return ps_dijkstra_ball_from(cx->s.dijkstra, cx->in->graph, cx->s.sources, cx->s.n_sources,
                                 &limits, cx->s.dist, cx->s.reached);
}

/* Band half-width: PS_BOUNDARY_CUT_BAND x the smaller segment's extent, at
 * most PS_BOUNDARY_CUT_MAX_EDGES mean edge lengths.  A segment with points
 * beyond reach (unreached, or known from a witness) has the extent reach. */
double ps_bc_band_width(const cut_context *cx, size_t n_reached, int a, int b, double reach) {
    double extent_a = 0, extent_b = 0;
    size_t reached_a = 0;
    for (size_t i = 0; i < n_reached; i++) {
        uint32_t p = cx->s.reached[i];
        if (ps_bc_group(cx, p) == a) extent_a = fmax(extent_a, cx->s.dist[p]), reached_a++;
        else extent_b = fmax(extent_b, cx->s.dist[p]);
    }
    if (reached_a < cx->size[a] || cx->s.radius_of[a] < reach) extent_a = fmax(extent_a, reach);
    if (n_reached - reached_a < cx->size[b] || cx->s.radius_of[b] < reach)
        extent_b = fmax(extent_b, reach);
    return fmin(PS_BOUNDARY_CUT_BAND * fmin(extent_a, extent_b),
                PS_BOUNDARY_CUT_MAX_EDGES * cx->mean_edge);
}

static void add_arc(cut_context *cx, size_t *arcs, uint32_t head, double capacity) {
    cx->s.net_heads[*arcs] = head;
    cx->s.net_capacity[(*arcs)++] = capacity;
}

/* Ties of band point i to the terminals: its arcs to a and b outside the
 * band.  Its arcs inside the band go to the network from *arcs on, *arcs
 * then left two past them (room for its terminal arcs).  Returns the ties
 * plus the arcs inside the band. */
static double tie_band_point(cut_context *cx, size_t i, int a, int b, size_t *arcs) {
    const ps_graph *g = cx->in->graph;
    uint32_t p = cx->s.band[i];
    double inside = 0;
    cx->s.tie_source[i] = cx->s.tie_sink[i] = 0;
    for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
        uint32_t q = g->neighbors[e], u = cx->s.band_of[q];
        if (u != NOT_IN_BAND) {
            double c = ps_bc_capacity(cx, p, e);
            inside += c;
            add_arc(cx, arcs, u, c);
            continue;
        }
        int s = ps_bc_group(cx, q);
        if (s == a) cx->s.tie_source[i] += ps_bc_capacity(cx, p, e);
        else if (s == b) cx->s.tie_sink[i] += ps_bc_capacity(cx, p, e);
    }
    *arcs += 2;
    return cx->s.tie_source[i] + cx->s.tie_sink[i] + inside;
}

/* Band points (reached within width) in point order, ties to the
 * terminals and the band's arcs (net_offsets[i]: where band point i's
 * begin, two slots apart); returns the count.  A sink point's tie to its
 * own side is "infinite": one plus every capacity of the network, more
 * than any cut. */
size_t ps_bc_mark_band(cut_context *cx, size_t n_reached, double width, int a, int b) {
    size_t nb = 0, arcs = 0;
    for (size_t i = 0; i < n_reached; i++)
        if (cx->s.dist[cx->s.reached[i]] <= width) cx->s.band[nb++] = cx->s.reached[i];
    ps_sort_u32(cx->s.band, nb, cx->s.queue); /* the queue is free until the pieces */
    for (size_t i = 0; i < nb; i++) {
        cx->s.band_of[cx->s.band[i]] = (uint32_t)i;
        cx->s.old_group[i] = ps_bc_group(cx, cx->s.band[i]);
    }
    double infinite = 1;
    for (size_t i = 0; i < nb; i++) {
        cx->s.net_offsets[i] = arcs;
        infinite += tie_band_point(cx, i, a, b, &arcs);
    }
    cx->s.net_offsets[nb] = arcs;
    for (size_t i = 0; i < nb; i++) {
        if (!cx->is_sink[cx->s.band[i]]) continue;
        if (cx->s.old_group[i] == a) cx->s.tie_source[i] += infinite;
        else cx->s.tie_sink[i] += infinite;
    }
    return nb;
}

/* The flow network: band nodes 0..nb-1, source nb, sink nb+1; each band
 * point's arcs inside the band (from ps_bc_mark_band) move down to close
 * the gaps, its terminal arcs after them.  Returns 0 when a terminal has
 * no tie (nothing to cut). */
int ps_bc_build_network(cut_context *cx, size_t nb, ps_flow_graph *net) {
    uint32_t source = (uint32_t)nb, sink = (uint32_t)nb + 1;
    size_t arcs = 0;
    for (size_t i = 0; i < nb; i++) {
        size_t from = cx->s.net_offsets[i], end = cx->s.net_offsets[i + 1] - 2;
        cx->s.net_offsets[i] = arcs;
        for (size_t k = from; k < end; k++)
            add_arc(cx, &arcs, cx->s.net_heads[k], cx->s.net_capacity[k]);
        if (cx->s.tie_source[i] > 0) add_arc(cx, &arcs, source, cx->s.tie_source[i]);
        if (cx->s.tie_sink[i] > 0) add_arc(cx, &arcs, sink, cx->s.tie_sink[i]);
    }
    cx->s.net_offsets[nb] = arcs;
    for (uint32_t i = 0; i < nb; i++)
        if (cx->s.tie_source[i] > 0) add_arc(cx, &arcs, i, cx->s.tie_source[i]);
    cx->s.net_offsets[nb + 1] = arcs;
    if (arcs == cx->s.net_offsets[nb]) return 0;
    for (uint32_t i = 0; i < nb; i++)
        if (cx->s.tie_sink[i] > 0) add_arc(cx, &arcs, i, cx->s.tie_sink[i]);
    cx->s.net_offsets[nb + 2] = arcs;
    if (arcs == cx->s.net_offsets[nb + 1]) return 0;
    *net = (ps_flow_graph){.n = nb + 2, .offsets = cx->s.net_offsets, .heads = cx->s.net_heads,
                           .capacity = cx->s.net_capacity};
    return 1;
}
