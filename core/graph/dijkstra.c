/*
 * dijkstra.c: shortest paths on a ps_graph (dijkstra.h) with a 4-ary
 * min-heap and decrease-key through a position array.
 *
 * The workspace keeps the heap and positions between runs; every run empties
 * the heap, so positions are back to NOT_IN_HEAP and nothing is reset or
 * allocated per run.  All runs share one settling loop; a ball run adds its
 * limits (checked only on an improving edge), its reached list and, with
 * points, edge lengths measured between the points (the settled point's
 * coordinates read once).
 */
#include "graph/dijkstra.h"

#include "util/control.h"

#include <math.h>
#include <stdlib.h>

#define NOT_IN_HEAP UINT32_MAX
#define PROGRESS_STEP 16384 /* settled vertices between reports of a tracked run */

typedef struct heap_entry {
    double key;
    uint32_t vertex;
} heap_entry;

struct ps_dijkstra {
    size_t n;
    size_t size;       /* entries in heap */
    heap_entry *heap;  /* #n */
    uint32_t *pos;     /* #n heap slot of each vertex or NOT_IN_HEAP */
};

ps_dijkstra *ps_dijkstra_new(size_t n) {
    ps_dijkstra *w = calloc(1, sizeof *w);
    if (!w) return NULL;
    size_t alloc_n = n ? n : 1;
    w->n = n;
    w->heap = malloc(alloc_n * sizeof *w->heap);
    w->pos = malloc(alloc_n * sizeof *w->pos);
    if (!w->heap || !w->pos) {
        ps_dijkstra_free(w);
        return NULL;
    }
    for (size_t v = 0; v < n; v++) w->pos[v] = NOT_IN_HEAP;
    return w;
}

void ps_dijkstra_free(ps_dijkstra *w) {
    if (!w) return;
    free(w->heap);
    free(w->pos);
    free(w);
}

static void sift_up(ps_dijkstra *w, size_t i, heap_entry e) {
    while (i > 0) {
        size_t parent = (i - 1) / 4;
        if (w->heap[parent].key <= e.key) break;
        w->heap[i] = w->heap[parent];
        w->pos[w->heap[i].vertex] = (uint32_t)i;
        i = parent;
    }
    w->heap[i] = e;
    w->pos[e.vertex] = (uint32_t)i;
}

static void sift_down(ps_dijkstra *w, size_t i, heap_entry e) {
    for (;;) {
        size_t child = 4 * i + 1, best = i;
        double best_key = e.key;
        size_t last = child + 4 < w->size ? child + 4 : w->size;
        for (size_t c = child; c < last; c++)
            if (w->heap[c].key < best_key) best = c, best_key = w->heap[c].key;
        if (best == i) break;
        w->heap[i] = w->heap[best];
        w->pos[w->heap[i].vertex] = (uint32_t)i;
        i = best;
    }
    w->heap[i] = e;
    w->pos[e.vertex] = (uint32_t)i;
}

/* Inserts v or lowers its key. */
static void heap_set(ps_dijkstra *w, uint32_t v, double key) {
    heap_entry e = {key, v};
    size_t i = w->pos[v] == NOT_IN_HEAP ? w->size++ : w->pos[v];
    sift_up(w, i, e);
}

static uint32_t heap_pop(ps_dijkstra *w) {
    uint32_t top = w->heap[0].vertex;
    w->pos[top] = NOT_IN_HEAP;
    if (--w->size > 0) sift_down(w, 0, w->heap[w->size]);
    return top;
}

/* A shorter path, or an equally short one from a lower source (only while v
 * is still in the heap, so settled vertices never change). */
static int improves(const ps_dijkstra *w, double nd, double old, const int *owner,
                    uint32_t u, uint32_t v) {
    if (nd < old) return 1;
    return owner && nd == old && w->pos[v] != NOT_IN_HEAP && owner[u] < owner[v];
}

/* A ball run's limits and the list of what it settled. */
typedef struct ball {
    const ps_dijkstra_limits *limits;
    uint32_t *reached;
    size_t count;
} ball;

static int within(const ps_dijkstra_limits *l, double nd, uint32_t v) {
    if (!l->label) return nd <= l->radius;
    uint32_t cell = __atomic_load_n(&l->label[v], __ATOMIC_RELAXED); /* see dijkstra.h */
    return l->mark[cell] == l->stamp && nd <= l->radius;
}

/* Pops the heap until it is empty, relaxing each popped vertex's edges;
 * with b, only into vertices within its limits, listing each popped one;
 * with span, reporting the share of g's vertices settled so far.  Always
 * inlined into the callers below, each with constant NULLs where it has no
 * owner, ball or span, so that each gets a loop without their tests. */
static inline __attribute__((always_inline)) void settle_with(ps_dijkstra *w, const ps_graph *g,
                                                              double *dist, int *owner, ball *b,
                                                              const ps_progress_span *span) {
    const double *points = b ? b->limits->points : NULL;
    size_t settled = 0;
    while (w->size > 0) {
        uint32_t u = heap_pop(w);
        if (b) b->reached[b->count++] = u;
        if (span && ++settled % PROGRESS_STEP == 0)
            ps_control_progress(span->ctl, span->phase,
                                ps_progress_span_at(span, (double)settled / (double)g->n));
        double du = dist[u], pu[3] = {0, 0, 0};
        for (int d = 0; points && d < 3; d++) pu[d] = points[3 * (size_t)u + d];
        for (size_t e = g->offsets[u]; e < g->offsets[u + 1]; e++) {
            uint32_t v = g->neighbors[e];
            double nd = du + (points ? ps_distance3(pu, points + 3 * (size_t)v) : g->weights[e]);
            if (!improves(w, nd, dist[v], owner, u, v)) continue;
            if (b && !within(b->limits, nd, v)) continue;
            dist[v] = nd;
            if (owner) owner[v] = owner[u];
            heap_set(w, v, nd);
        }
    }
}

/* A plain run: no owner, ball or progress. */
static void settle(ps_dijkstra *w, const ps_graph *g, double *dist) {
    settle_with(w, g, dist, NULL, NULL, NULL);
}

static void settle_owned(ps_dijkstra *w, const ps_graph *g, double *dist, int *owner,
                         const ps_progress_span *span) {
    settle_with(w, g, dist, owner, NULL, span);
}

static void settle_ball(ps_dijkstra *w, const ps_graph *g, double *dist, ball *b) {
    settle_with(w, g, dist, NULL, b, NULL);
}

void ps_dijkstra_run(ps_dijkstra *w, const ps_graph *g, const uint32_t *sources,
                     size_t n_sources, double *dist, int *owner) {
    ps_dijkstra_run_tracked(w, g, sources, n_sources, dist, owner, NULL);
}

void ps_dijkstra_run_tracked(ps_dijkstra *w, const ps_graph *g, const uint32_t *sources,
                             size_t n_sources, double *dist, int *owner,
                             const ps_progress_span *span) {
    for (size_t v = 0; v < g->n; v++) dist[v] = INFINITY;
    if (owner)
        for (size_t v = 0; v < g->n; v++) owner[v] = -1;
    for (size_t s = 0; s < n_sources; s++) {
        uint32_t v = sources[s];
        if (dist[v] == 0.0) continue; /* a repeated source keeps its first index */
        dist[v] = 0.0;
        if (owner) owner[v] = (int)s;
        heap_set(w, v, 0.0);
    }
    if (owner || span) settle_owned(w, g, dist, owner, span);
    else settle(w, g, dist);
    if (span) ps_control_progress(span->ctl, span->phase, span->hi);
}

void ps_dijkstra_lower(ps_dijkstra *w, const ps_graph *g, uint32_t source, double *dist) {
    if (dist[source] > 0.0) {
        dist[source] = 0.0;
        heap_set(w, source, 0.0);
    }
    settle(w, g, dist);
}

size_t ps_dijkstra_ball(ps_dijkstra *w, const ps_graph *g, uint32_t source,
                        const ps_dijkstra_limits *limits, double *dist, uint32_t *reached) {
    return ps_dijkstra_ball_from(w, g, &source, 1, limits, dist, reached);
}

size_t ps_dijkstra_ball_from(ps_dijkstra *w, const ps_graph *g, const uint32_t *sources,
                             size_t n_sources, const ps_dijkstra_limits *limits, double *dist,
                             uint32_t *reached) {
    ball b = {limits, reached, 0};
    for (size_t s = 0; s < n_sources; s++) {
        dist[sources[s]] = 0.0;
        heap_set(w, sources[s], 0.0);
    }
    settle_ball(w, g, dist, &b);
    return b.count;
}
