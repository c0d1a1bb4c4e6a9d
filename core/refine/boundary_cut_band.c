/*
 * boundary_cut_band.c: one pair's band for the boundary cut
 * (boundary_cut.h): its current shared boundary, the distances from it,
 * the band's width, the band points with their ties to the terminals, and
 * the flow network the minimum cut runs on.  The state is the driver's
 * cut_context (boundary_cut_context.h, private).
 */
#include "refine/boundary_cut_context.h"

#include "util/sort_util.h"

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

/* Moves the sources in segment s to the front; returns their count. */
static size_t sources_first(cut_context *cx, int s) {
    size_t front = 0;
    for (size_t i = 0; i < cx->s.n_sources; i++) {
        uint32_t p = cx->s.sources[i];
        if (ps_bc_group(cx, p) != s) continue;
        cx->s.sources[i] = cx->s.sources[front];
        cx->s.sources[front++] = p;
    }
    return front;
}

/* The ball within segment s from its n boundary points, out to radius:
 * its points go to reached from index at on, with their dist.  Returns
 * how many.  Segment ids are the ball's region labels (a group is never
 * negative, so it reads the same as a uint32_t). */
static size_t segment_ball(cut_context *cx, int s, const uint32_t *sources, size_t n,
                           double radius, size_t at) {
    cx->s.region_mark[s] = ++cx->s.stamp;
    ps_dijkstra_limits limits = {.radius = radius, .label = (const uint32_t *)cx->group,
                                 .mark = cx->s.region_mark, .stamp = cx->s.stamp,
                                 .points = cx->in->points};
    return ps_dijkstra_ball_from(cx->s.dijkstra, cx->in->graph, sources, n, &limits, cx->s.dist,
                                 cx->s.reached + at);
}

/* Segment s's extent from the count points of its ball at reached[at..):
 * their largest distance when the ball covered s, else cover (a bound
 * the extent is known to reach). */
static double ball_extent(const cut_context *cx, int s, size_t at, size_t count, double cover) {
    double extent = 0;
    for (size_t i = at; i < at + count; i++) extent = fmax(extent, cx->s.dist[cx->s.reached[i]]);
    return count < cx->size[s] ? fmax(extent, cover) : extent;
}

/* The band's half-width from the two extents. */
static double band_width(const cut_context *cx, double extent_a, double extent_b) {
    return fmin(PS_BOUNDARY_CUT_BAND * fmin(extent_a, extent_b),
                PS_BOUNDARY_CUT_MAX_EDGES * cx->mean_edge);
}

/* No shortest path from the boundary to a point of a passes through b: a
 * point of a next to b is itself on the boundary.  So each segment's
 * distances come from a ball of its own from its own boundary points, and
 * the second ball need go only as far as the first one's extent allows:
 * the band's width is fixed by the smaller extent, and a segment not
 * covered within the first's extent has the larger one.  A segment that a
 * witness shows to extend beyond reach needs no ball to know its extent;
 * only the band's width of it is explored. */
size_t ps_bc_boundary_distances(cut_context *cx, int a, int b, double reach, double *width) {
    int far_a = far_beyond(cx, a, reach), far_b = far_beyond(cx, b, reach);
    int first = a, second = b;
    if (far_a || (!far_b && cx->size[b] < cx->size[a])) first = b, second = a;
    size_t n_first = sources_first(cx, first);
    const uint32_t *first_sources = cx->s.sources, *second_sources = cx->s.sources + n_first;
    size_t n_second = cx->s.n_sources - n_first;
    if (far_a && far_b) {
        *width = band_width(cx, reach, reach);
        size_t count = segment_ball(cx, first, first_sources, n_first, *width, 0);
        return count + segment_ball(cx, second, second_sources, n_second, *width, count);
    }
    size_t count = segment_ball(cx, first, first_sources, n_first, reach, 0);
    double extent = ball_extent(cx, first, 0, count, reach);
    if (far_a || far_b) {
        *width = band_width(cx, extent, reach);
        return count + segment_ball(cx, second, second_sources, n_second, *width, count);
    }
    size_t more = segment_ball(cx, second, second_sources, n_second, extent, count);
    *width = band_width(cx, extent, ball_extent(cx, second, count, more, reach));
    return count + more;
}

static void add_arc(cut_context *cx, size_t *arcs, uint32_t head, double capacity) {
    cx->s.net_heads[*arcs] = head;
    cx->s.net_capacity[(*arcs)++] = capacity;
}

/* Ties of band point i to the terminals: its arcs to a and b outside the
 * band, which outside[i] notes (OUTSIDE_A, OUTSIDE_B).  Its arcs inside
 * the band go to the network from *arcs on, *arcs then left two past them
 * (room for its terminal arcs).  Returns the ties plus the arcs inside the
 * band. */
static double tie_band_point(cut_context *cx, size_t i, int a, int b, size_t *arcs) {
    const ps_graph *g = cx->in->graph;
    uint32_t p = cx->s.band[i];
    double inside = 0;
    unsigned char outside = 0;
    cx->s.tie_a[i] = cx->s.tie_b[i] = 0;
    for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
        uint32_t q = g->neighbors[e], u = cx->s.band_of[q];
        if (u != NOT_IN_BAND) {
            /* an earlier band point's row set this arc's capacity with its own */
            double c = u < i ? cx->capacity[e] : ps_bc_capacity(cx, p, e);
            inside += c;
            add_arc(cx, arcs, u, c);
            continue;
        }
        int s = ps_bc_group(cx, q);
        if (s == a) cx->s.tie_a[i] += ps_bc_capacity(cx, p, e), outside |= OUTSIDE_A;
        else if (s == b) cx->s.tie_b[i] += ps_bc_capacity(cx, p, e), outside |= OUTSIDE_B;
    }
    cx->s.outside[i] = outside;
    *arcs += 2;
    return cx->s.tie_a[i] + cx->s.tie_b[i] + inside;
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
        if (cx->s.old_group[i] == a) cx->s.tie_a[i] += infinite;
        else cx->s.tie_b[i] += infinite;
    }
    return nb;
}

/* The flow network: band nodes 0..nb-1, terminals s = nb, t = nb+1; each band
 * point's arcs inside the band (from ps_bc_mark_band) move down to close
 * the gaps, its terminal arcs after them.  Returns 0 when a terminal has
 * no tie (nothing to cut). */
int ps_bc_build_network(cut_context *cx, size_t nb, ps_maxflow_graph *net) {
    uint32_t s = (uint32_t)nb, t = (uint32_t)nb + 1;
    size_t arcs = 0;
    for (size_t i = 0; i < nb; i++) {
        size_t from = cx->s.net_offsets[i], end = cx->s.net_offsets[i + 1] - 2;
        cx->s.net_offsets[i] = arcs;
        for (size_t k = from; k < end; k++)
            add_arc(cx, &arcs, cx->s.net_heads[k], cx->s.net_capacity[k]);
        if (cx->s.tie_a[i] > 0) add_arc(cx, &arcs, s, cx->s.tie_a[i]);
        if (cx->s.tie_b[i] > 0) add_arc(cx, &arcs, t, cx->s.tie_b[i]);
    }
    cx->s.net_offsets[nb] = arcs;
    for (uint32_t i = 0; i < nb; i++)
        if (cx->s.tie_a[i] > 0) add_arc(cx, &arcs, i, cx->s.tie_a[i]);
    cx->s.net_offsets[nb + 1] = arcs;
    if (arcs == cx->s.net_offsets[nb]) return 0;
    for (uint32_t i = 0; i < nb; i++)
        if (cx->s.tie_b[i] > 0) add_arc(cx, &arcs, i, cx->s.tie_b[i]);
    cx->s.net_offsets[nb + 2] = arcs;
    if (arcs == cx->s.net_offsets[nb + 1]) return 0;
    *net = (ps_maxflow_graph){.n = nb + 2, .offsets = cx->s.net_offsets, .heads = cx->s.net_heads,
                           .capacity = cx->s.net_capacity};
    return 1;
}
