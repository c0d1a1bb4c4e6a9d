/*
 * random_graph.h: random symmetric graphs for the shortest-path tests
 * (test_dijkstra.c, test_dial.c), in the kNN graph's CSR form.
 */
#ifndef PS_TEST_RANDOM_GRAPH_H
#define PS_TEST_RANDOM_GRAPH_H

#include "graph/knn_graph.h"

#include <stdint.h>

/* A seeded generator (random_bits.h's sequence). */
typedef struct test_rng {
    uint64_t s;
} test_rng;

/* Uniform in [0, bound). */
unsigned test_rng_below(test_rng *r, unsigned bound);

/* Uniform in [0, 1). */
double test_rng_unit(test_rng *r);

/* g out (freed with ps_graph_free): n vertices, about `degree` edges a
 * vertex among the first n - isolated (the rest have none), lengths
 * uniform in [lo, hi]; whole numbers from lo to hi when whole is set, so
 * that sums of lengths tie exactly. */
void test_random_graph(size_t n, int degree, double lo, double hi, int whole, size_t isolated,
                       unsigned long long seed, ps_graph *g);

#endif
