/* test_dial.c: Dial's buckets give, bit for bit, the distances of the
 * heap's Dijkstra (dijkstra.h) from every source of random graphs whose
 * edge lengths are not integers (so sums round), through many runs on one
 * workspace; lowering from a sequence of sources equals ps_dijkstra_lower
 * bit for bit; unreachable vertices get INFINITY; graphs the buckets do
 * not suit (an edge of length 0, a span of lengths over PS_DIAL_MAX_SPAN)
 * and a graph without edges answer the same. */
#include "graph/dial.h"
#include "graph/dijkstra.h"
#include "graph/knn_graph.h"
#include "random_graph.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A random graph, lengths uniform in [lo, hi], the last `isolated`
 * vertices without edges. */
static void random_graph(size_t n, int degree, double lo, double hi, size_t isolated,
                         unsigned long long seed, ps_graph *g) {
    test_random_graph(n, degree, lo, hi, 0, isolated, seed, g);
}

/* Every source of g: ps_dial_run equals ps_dijkstra_run bit for bit. */
static int same_as_heap(const ps_graph *g) {
    ps_dial *dial = ps_dial_new(g);
    ps_dijkstra *heap = ps_dijkstra_new(g->n);
    double *a = malloc(g->n * sizeof *a), *b = malloc(g->n * sizeof *b);
    int same = dial && heap && a && b;
    for (uint32_t s = 0; same && s < g->n; s++) {
        ps_dial_run(dial, s, a);
        ps_dijkstra_run(heap, g, &s, 1, b, NULL);
        same = memcmp(a, b, g->n * sizeof *a) == 0;
    }
    ps_dial_free(dial);
    ps_dijkstra_free(heap);
    free(a), free(b);
    return same;
}

static void test_runs_equal_dijkstra(void) {
    for (unsigned long long seed = 1; seed <= 4; seed++) {
        ps_graph g;
        random_graph(300, 6, 1.0, 2.7, 0, seed, &g);
        CHECK_MSG(same_as_heap(&g), "seed %llu", seed);
        ps_graph_free(&g);
    }
    ps_graph g; /* a wide span of lengths, still within the buckets' */
    random_graph(200, 5, 0.01, 4.9, 0, 9, &g);
    CHECK(same_as_heap(&g));
    ps_graph_free(&g);
}

static void test_unreachable_is_infinity(void) {
    ps_graph g;
    random_graph(120, 4, 1.0, 2.0, 3, 5, &g);
    ps_dial *dial = ps_dial_new(&g);
    double *d = malloc(g.n * sizeof *d);
    CHECK(dial && d);
    if (dial && d) {
        ps_dial_run(dial, 0, d);
        for (size_t v = g.n - 3; v < g.n; v++) CHECK(isinf(d[v]));
        ps_dial_run(dial, (uint32_t)g.n - 1, d);
        CHECK(d[g.n - 1] == 0.0 && isinf(d[0]));
    }
    CHECK(same_as_heap(&g));
    ps_dial_free(dial);
    free(d);
    ps_graph_free(&g);
}

static void test_lower_equals_dijkstra_lower(void) {
    ps_graph g;
    random_graph(250, 6, 1.0, 3.0, 2, 11, &g);
    ps_dial *dial = ps_dial_new(&g);
    ps_dijkstra *heap = ps_dijkstra_new(g.n);
    double *a = malloc(g.n * sizeof *a), *b = malloc(g.n * sizeof *b);
    CHECK(dial && heap && a && b);
    if (dial && heap && a && b) {
        for (size_t v = 0; v < g.n; v++) a[v] = b[v] = INFINITY;
        uint32_t sources[] = {7, 7, 120, 3, 249, 60, 200};
        for (size_t i = 0; i < sizeof sources / sizeof *sources; i++) {
            ps_dial_lower(dial, sources[i], a);
            ps_dijkstra_lower(heap, &g, sources[i], b);
            CHECK_MSG(memcmp(a, b, g.n * sizeof *a) == 0, "after source %zu", i);
        }
        CHECK(a[120] == 0.0 && a[7] == 0.0);
    }
    ps_dial_free(dial);
    ps_dijkstra_free(heap);
    free(a), free(b);
    ps_graph_free(&g);
}

/* Sets the length of g's first edge, in both directions. */
static void set_first_edge(ps_graph *g, double length) {
    uint32_t q = g->neighbors[0];
    g->weights[0] = length;
    for (size_t e = g->offsets[q]; e < g->offsets[q + 1]; e++)
        if (g->neighbors[e] == 0) g->weights[e] = length;
}

static void test_unsuited_graphs_answer_the_same(void) {
    double lengths[] = {0.0, 1e-3}; /* no bucket width; a span over PS_DIAL_MAX_SPAN */
    for (int i = 0; i < 2; i++) {
        ps_graph g;
        random_graph(150, 5, 1.0, 2.0, 0, 21 + (unsigned long long)i, &g);
        set_first_edge(&g, lengths[i]);
        CHECK_MSG(same_as_heap(&g), "first edge %g", lengths[i]);
        ps_graph_free(&g);
    }
}

static void test_graph_without_edges(void) {
    ps_graph g;
    random_graph(5, 0, 1.0, 2.0, 5, 1, &g);
    CHECK(g.offsets[g.n] == 0);
    ps_dial *dial = ps_dial_new(&g);
    double d[5];
    CHECK(dial != NULL);
    if (dial) {
        ps_dial_run(dial, 2, d);
        CHECK(d[2] == 0.0 && isinf(d[0]) && isinf(d[4]));
    }
    ps_dial_free(dial);
    ps_graph_free(&g);
}

PS_TEST_MAIN(TEST(test_runs_equal_dijkstra), TEST(test_unreachable_is_infinity),
             TEST(test_lower_equals_dijkstra_lower), TEST(test_unsuited_graphs_answer_the_same),
             TEST(test_graph_without_edges))
