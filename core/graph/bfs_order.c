/* bfs_order.c: relabel a ps_graph in breadth-first order (bfs_order.h). */
#include "graph/bfs_order.h"

#include "util/parallel.h"

#include <stdlib.h>
#include <string.h>

#define UNSEEN UINT32_MAX

/* BFS visiting order: old_of lists the vertices, components contiguous. */
static int visit_order(const ps_graph *g, uint32_t *old_of, uint32_t *new_of, size_t *start) {
    size_t n = g->n, tail = 0;
    int count = 0;
    for (size_t v = 0; v < n; v++) new_of[v] = UNSEEN;
    for (size_t root = 0; root < n; root++) {
        if (new_of[root] != UNSEEN) continue;
        start[count++] = tail;
        new_of[root] = (uint32_t)tail;
        old_of[tail++] = (uint32_t)root;
        for (size_t head = start[count - 1]; head < tail; head++) {
            uint32_t u = old_of[head];
            for (size_t e = g->offsets[u]; e < g->offsets[u + 1]; e++) {
                uint32_t q = g->neighbors[e];
                if (new_of[q] != UNSEEN) continue;
                new_of[q] = (uint32_t)tail;
                old_of[tail++] = q;
            }
        }
    }
    start[count] = n;
    return count;
}

static void relabel_rows(const ps_graph *g, const ps_bfs_order *o) {
    size_t out = 0;
    for (size_t i = 0; i < g->n; i++) {
        uint32_t u = o->old_of[i];
        o->g.offsets[i] = out;
        for (size_t e = g->offsets[u]; e < g->offsets[u + 1]; e++, out++) {
            o->g.neighbors[out] = o->new_of[g->neighbors[e]];
            o->g.weights[out] = g->weights[e];
        }
    }
    o->g.offsets[g->n] = out;
}

ps_status ps_bfs_order_build(const ps_graph *g, ps_bfs_order *o, ps_error *err) {
    memset(o, 0, sizeof *o);
    size_t n = g->n, edges = g->offsets[n], alloc_n = n ? n : 1;
    o->g.n = n;
    o->g.offsets = malloc((n + 1) * sizeof *o->g.offsets);
    o->g.neighbors = malloc((edges ? edges : 1) * sizeof *o->g.neighbors);
    o->g.weights = malloc((edges ? edges : 1) * sizeof *o->g.weights);
    o->old_of = malloc(alloc_n * sizeof *o->old_of);
    o->new_of = malloc(alloc_n * sizeof *o->new_of);
    o->start = malloc((n + 1) * sizeof *o->start);
    if (!o->g.offsets || !o->g.neighbors || !o->g.weights || !o->old_of || !o->new_of ||
        !o->start) {
        ps_bfs_order_free(o);
        return ps_fail(err, PS_ERR_NOMEM, "bfs order: out of memory for %zu vertices", n);
    }
    o->n_components = visit_order(g, o->old_of, o->new_of, o->start);
    relabel_rows(g, o);
    return PS_OK;
}

/* Rows of dst from rows of src: dst's row v is src's row map_row[v],
 * neighbours renamed by rename (NULL: the weights' pass). */
typedef struct row_move {
    const ps_graph *src;
    ps_graph *dst;
    const uint32_t *map_row, *rename;
} row_move;

static void move_range(void *ctx, size_t begin, size_t end, int worker) {
    (void)worker;
    const row_move *m = ctx;
    for (size_t v = begin; v < end; v++) {
        size_t from = m->src->offsets[m->map_row[v]], len = m->dst->offsets[v + 1] - m->dst->offsets[v];
        if (m->rename)
            for (size_t i = 0; i < len; i++)
                m->dst->neighbors[m->dst->offsets[v] + i] = m->rename[m->src->neighbors[from + i]];
        else
            memcpy(m->dst->weights + m->dst->offsets[v], m->src->weights + from,
                   len * sizeof *m->dst->weights);
    }
}

/* dst's rows from src's with vertex v of dst being map_row[v] of src and
 * neighbours renamed by rename, on threads; each of src's arrays is freed
 * once read, so at most three of the four big arrays exist at once.
 * dst->offsets (#n+1) is given; returns 0, or -1 out of memory (src
 * freed, dst partly built). */
static int move_rows(ps_graph *src, const uint32_t *map_row, const uint32_t *rename,
                     int threads, ps_graph *dst) {
    size_t n = src->n, edges = src->offsets[n];
    dst->offsets[0] = 0;
    for (size_t v = 0; v < n; v++)
        dst->offsets[v + 1] = dst->offsets[v] + src->offsets[map_row[v] + 1] - src->offsets[map_row[v]];
    row_move m = {src, dst, map_row, rename};
    threads = ps_parallel_threads(threads);
    dst->neighbors = malloc((edges ? edges : 1) * sizeof *dst->neighbors);
    if (dst->neighbors) ps_parallel_for(threads, n, 0, move_range, &m);
    free(src->neighbors), src->neighbors = NULL;
    dst->weights = dst->neighbors ? malloc((edges ? edges : 1) * sizeof *dst->weights) : NULL;
    m.rename = NULL;
    if (dst->weights) ps_parallel_for(threads, n, 0, move_range, &m);
    ps_graph_free(src);
    return dst->weights ? 0 : -1;
}

ps_status ps_bfs_order_take(ps_graph *g, int threads, ps_bfs_order *o, ps_error *err) {
    memset(o, 0, sizeof *o);
    size_t n = g->n, alloc_n = n ? n : 1;
    o->g.n = n;
    o->g.offsets = malloc((n + 1) * sizeof *o->g.offsets);
    o->old_of = malloc(alloc_n * sizeof *o->old_of);
    o->new_of = malloc(alloc_n * sizeof *o->new_of);
    o->start = malloc((n + 1) * sizeof *o->start);
    if (!o->g.offsets || !o->old_of || !o->new_of || !o->start) {
        ps_bfs_order_free(o);
        return ps_fail(err, PS_ERR_NOMEM, "bfs order: out of memory for %zu vertices", n);
    }
    o->n_components = visit_order(g, o->old_of, o->new_of, o->start);
    if (move_rows(g, o->old_of, o->new_of, threads, &o->g) == 0) return PS_OK;
    ps_bfs_order_free(o);
    return ps_fail(err, PS_ERR_NOMEM, "bfs order: out of memory for %zu vertices", n);
}

ps_status ps_bfs_order_give_back(ps_bfs_order *o, int threads, ps_graph *g, ps_error *err) {
    size_t n = o->g.n;
    memset(g, 0, sizeof *g);
    g->n = n;
    g->offsets = malloc((n + 1) * sizeof *g->offsets);
    int ok = g->offsets && move_rows(&o->g, o->new_of, o->old_of, threads, g) == 0;
    ps_bfs_order_free(o);
    if (ok) return PS_OK;
    ps_graph_free(g);
    return ps_fail(err, PS_ERR_NOMEM, "bfs order: out of memory giving back %zu vertices", n);
}

void ps_bfs_order_free(ps_bfs_order *o) {
    if (!o) return;
    ps_graph_free(&o->g);
    free(o->old_of), free(o->new_of), free(o->start);
    memset(o, 0, sizeof *o);
}
