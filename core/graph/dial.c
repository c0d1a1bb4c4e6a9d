/*
 * dial.c: Dial's shortest paths (dial.h).
 *
 * The buckets are a ring of lists threaded through one pool of entries: a
 * run relaxes each edge once, so it pushes at most #E + 1 entries, and the
 * pool, sized so at build time, makes a run allocate nothing.  A vertex
 * lowered twice waits in two buckets; the run stamp marks it settled at
 * the first, so the second is skipped.
 */
#include "graph/dial.h"

#include "graph/dijkstra.h"

#include <math.h>
#include <stdlib.h>

#define NO_ENTRY UINT32_MAX

typedef struct entry {
    uint32_t vertex;
    uint32_t next;  /* the next entry of its bucket, or NO_ENTRY */
} entry;

struct ps_dial {
    const ps_graph *g;
    double inv_delta;  /* 1 / the bucket width */
    size_t n_buckets;  /* the ring's length: no edge reaches further ahead */
    uint32_t *head;    /* #n_buckets first entry of each bucket, or NO_ENTRY */
    entry *pool;       /* #E+1 */
    uint32_t *stamp;   /* #P the run that settled each vertex */
    uint32_t run;
    ps_dijkstra *heap; /* instead of the buckets, for a graph they do not suit */
};

/* The shortest and longest edge of g (0 and 0 when it has none). */
static void edge_range(const ps_graph *g, double *shortest, double *longest) {
    size_t edges = g->offsets[g->n];
    *shortest = edges ? INFINITY : 0.0;
    *longest = 0.0;
    for (size_t e = 0; e < edges; e++) {
        if (g->weights[e] < *shortest) *shortest = g->weights[e];
        if (g->weights[e] > *longest) *longest = g->weights[e];
    }
}

static int buckets_suit(const ps_graph *g, double shortest, double longest) {
    if (g->offsets[g->n] >= UINT32_MAX) return 0; /* the pool's entries are 32-bit */
    if (longest == 0.0) return 1; /* no edge of positive length: no bucket past the first */
    return shortest > 0.0 && longest <= PS_DIAL_MAX_SPAN * shortest;
}

ps_dial *ps_dial_new(const ps_graph *g) {
    ps_dial *w = calloc(1, sizeof *w);
    if (!w) return NULL;
    w->g = g;
    double shortest, longest;
    edge_range(g, &shortest, &longest);
    if (!buckets_suit(g, shortest, longest)) {
        w->heap = ps_dijkstra_new(g->n);
        if (!w->heap) ps_dial_free(w), w = NULL;
        return w;
    }
    double delta = longest > 0.0 ? shortest / 2.0 : 1.0;
    w->inv_delta = 1.0 / delta;
    w->n_buckets = (size_t)ceil(longest / delta) + 2;
    w->head = malloc(w->n_buckets * sizeof *w->head);
    w->pool = malloc((g->offsets[g->n] + 1) * sizeof *w->pool);
    w->stamp = calloc(g->n ? g->n : 1, sizeof *w->stamp);
    if (!w->head || !w->pool || !w->stamp) {
        ps_dial_free(w);
        return NULL;
    }
    for (size_t b = 0; b < w->n_buckets; b++) w->head[b] = NO_ENTRY;
    return w;
}

void ps_dial_free(ps_dial *w) {
    if (!w) return;
    free(w->head), free(w->pool), free(w->stamp);
    ps_dijkstra_free(w->heap);
    free(w);
}

/* A fresh stamp for a run (the stamps start over when they wrap). */
static uint32_t next_run(ps_dial *w) {
    if (++w->run == 0) {
        for (size_t v = 0; v < w->g->n; v++) w->stamp[v] = 0;
        w->run = 1;
    }
    return w->run;
}

/* Settles the vertices waiting in absolute bucket i (all final: see
 * dial.h) and pushes what their edges lower.  *top: the pool's next free
 * entry.  Returns the entries taken off the bucket. */
static size_t settle_bucket(ps_dial *w, size_t i, uint32_t run, double *dist, uint32_t *top) {
    const ps_graph *g = w->g;
    size_t slot = i % w->n_buckets, taken = 0;
    uint32_t e = w->head[slot];
    w->head[slot] = NO_ENTRY;
    for (; e != NO_ENTRY; e = w->pool[e].next, taken++) {
        uint32_t u = w->pool[e].vertex;
        if (w->stamp[u] == run) continue;
        w->stamp[u] = run;
        double du = dist[u];
        for (size_t k = g->offsets[u]; k < g->offsets[u + 1]; k++) {
            uint32_t v = g->neighbors[k];
            double nd = du + g->weights[k];
            if (!(nd < dist[v])) continue;
            dist[v] = nd;
            size_t b = (size_t)(nd * w->inv_delta);
            if (b <= i) b = i + 1; /* an edge spans two buckets: only rounding gets here */
            uint32_t slot_v = (uint32_t)(b % w->n_buckets);
            w->pool[*top] = (entry){v, w->head[slot_v]};
            w->head[slot_v] = (*top)++;
        }
    }
    return taken;
}

/* Settles everything source lowers: dist[source] is 0, the rest as the
 * caller left it. */
static void run_from(ps_dial *w, uint32_t source, double *dist) {
    uint32_t run = next_run(w), top = 1;
    w->pool[0] = (entry){source, NO_ENTRY};
    w->head[0] = 0;
    size_t waiting = 1;
    for (size_t i = 0; waiting > 0; i++) {
        uint32_t before = top;
        waiting -= settle_bucket(w, i, run, dist, &top);
        waiting += top - before;
    }
}

void ps_dial_run(ps_dial *w, uint32_t source, double *dist) {
    if (w->heap) {
        ps_dijkstra_run(w->heap, w->g, &source, 1, dist, NULL);
        return;
    }
    for (size_t v = 0; v < w->g->n; v++) dist[v] = INFINITY;
    dist[source] = 0.0;
    run_from(w, source, dist);
}

void ps_dial_lower(ps_dial *w, uint32_t source, double *dist) {
    if (w->heap) {
        ps_dijkstra_lower(w->heap, w->g, source, dist);
        return;
    }
    if (!(dist[source] > 0.0)) return;
    dist[source] = 0.0;
    run_from(w, source, dist);
}
