/*
 * boundary_cut_pieces.c: after a pair's cut (boundary_cut.h), the pieces
 * of a segment the cut left inside the band apart from the rest go to the
 * other segment, except the segment's largest piece.  Pieces are found
 * inside the band; only when one is loose does a search outside it,
 * stopped once a piece is larger, tell whether an anchored piece is the
 * largest.  The state is the driver's cut_context (boundary_cut_context.h,
 * private).
 */
#include "refine/boundary_cut_context.h"

/* Pieces of the band points labelled x (connected within the band, in
 * order of their lowest point), over the band's arcs of the flow network
 * (band nodes first in each row, in graph order); a piece with an x
 * neighbour outside the band (outside has bit) is anchored.  Returns the
 * count. */
static int band_pieces(cut_context *cx, size_t nb, int x, unsigned char bit) {
    int n_pieces = 0;
    for (size_t i = 0; i < nb; i++) cx->s.piece[i] = -1;
    for (uint32_t start = 0; start < nb; start++) {
        if (cx->s.piece[start] >= 0 || ps_bc_group(cx, cx->s.band[start]) != x) continue;
        size_t head = 0, tail = 0;
        cx->s.piece[start] = n_pieces;
        cx->s.anchored[n_pieces] = 0;
        cx->s.queue[tail++] = start;
        while (head < tail) {
            uint32_t i = cx->s.queue[head++];
            if (cx->s.outside[i] & bit) cx->s.anchored[n_pieces] = 1;
            for (size_t k = cx->s.net_offsets[i]; k < cx->s.net_offsets[i + 1]; k++) {
                uint32_t u = cx->s.net_heads[k];
                if (u >= nb || cx->s.piece[u] >= 0 || ps_bc_group(cx, cx->s.band[u]) != x)
                    continue;
                cx->s.piece[u] = n_pieces;
                cx->s.queue[tail++] = u;
            }
        }
        cx->s.piece_start[n_pieces] = start;
        cx->s.piece_size[n_pieces++] = tail;
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
    cx->s.visited[start] = cx->s.stamp;
    cx->s.queue[tail++] = start;
    while (head < tail) {
        uint32_t p = cx->s.queue[head++];
        if (p < lowest) lowest = p;
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            uint32_t q = g->neighbors[e];
            if (ps_bc_group(cx, q) != x || cx->s.visited[q] == cx->s.stamp) continue;
            cx->s.visited[q] = cx->s.stamp;
            cx->s.queue[tail++] = q;
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
    size_t cap = cx->s.piece_size[best], explored = 0;
    uint32_t loose_start = cx->s.band[cx->s.piece_start[best]];
    cx->s.stamp++;
    for (size_t i = 0; i < nb; i++)
        if (cx->s.piece[i] >= 0 && !cx->s.anchored[cx->s.piece[i]])
            cx->s.visited[cx->s.band[i]] = cx->s.stamp;
    for (size_t i = 0; i < nb; i++) {
        uint32_t p = cx->s.band[i];
        if (cx->s.piece[i] < 0 || !cx->s.anchored[cx->s.piece[i]] ||
            cx->s.visited[p] == cx->s.stamp)
            continue;
        if (comes_first(cx, p, x, cap, loose_start, &explored)) return 1;
    }
    if (cx->size[x] - loose - explored < cap) return 0;
    for (uint32_t p = 0; p < cx->in->graph->n; p++)
        if (ps_bc_group(cx, p) == x && cx->s.visited[p] != cx->s.stamp &&
            comes_first(cx, p, x, cap, loose_start, &explored))
            return 1;
    return 0;
}

/* Pieces of x the cut made (wholly inside the band), except the largest
 * of all x's pieces (ties: the lowest point), become y. */
void ps_bc_keep_largest_piece(cut_context *cx, size_t nb, int x, int y) {
    int n_pieces = band_pieces(cx, nb, x, x < y ? OUTSIDE_A : OUTSIDE_B), best = -1;
    size_t loose = 0;
    for (int k = 0; k < n_pieces; k++) {
        if (cx->s.anchored[k]) continue;
        loose += cx->s.piece_size[k];
        if (best < 0 || cx->s.piece_size[k] > cx->s.piece_size[best]) best = k;
    }
    if (best < 0) return;
    if (anchored_piece_first(cx, nb, x, best, loose)) best = -1;
    for (size_t i = 0; i < nb; i++)
        if (cx->s.piece[i] >= 0 && cx->s.piece[i] != best && !cx->s.anchored[cx->s.piece[i]])
            ps_bc_set_group(cx, cx->s.band[i], y);
}
