/* test_graph.c: a CSR graph's components (graph.h) are numbered in order
 * of their lowest vertex, whatever the order of the edges; an isolated
 * vertex is a component of its own; ps_graph_free zeroes the graph. */
#include "graph/graph.h"
#include "testlib.h"

#include <stdlib.h>

/* A symmetric CSR graph on n vertices from m undirected edges (both
 * arcs each); rows need not be sorted for the components. */
static ps_graph graph_of(size_t n, const uint32_t (*edges)[2], size_t m) {
    ps_graph g = {.n = n, .offsets = calloc(n + 1, sizeof(size_t)),
                  .neighbors = malloc((2 * m + 1) * sizeof(uint32_t)),
                  .weights = malloc((2 * m + 1) * sizeof(double))};
    if (!g.offsets || !g.neighbors || !g.weights) return g;
    for (size_t i = 0; i < m; i++) g.offsets[edges[i][0] + 1]++, g.offsets[edges[i][1] + 1]++;
    for (size_t p = 0; p < n; p++) g.offsets[p + 1] += g.offsets[p];
    size_t *at = malloc((n ? n : 1) * sizeof *at);
    if (!at) return g;
    for (size_t p = 0; p < n; p++) at[p] = g.offsets[p];
    for (size_t i = 0; i < m; i++) {
        uint32_t a = edges[i][0], b = edges[i][1];
        g.weights[at[a]] = 1, g.neighbors[at[a]++] = b;
        g.weights[at[b]] = 1, g.neighbors[at[b]++] = a;
    }
    free(at);
    return g;
}

/* Even vertices in one chain, odd ones in another joined from the top
 * down, and vertex 9 alone: labels 0, 1, 2 by lowest vertex. */
static void test_components_by_lowest_vertex(void) {
    const uint32_t edges[][2] = {{8, 6}, {6, 4}, {2, 4}, {0, 2}, {7, 5}, {5, 3}, {3, 1}};
    ps_graph g = graph_of(10, edges, sizeof edges / sizeof edges[0]);
    REQUIRE(g.offsets && g.neighbors && g.weights);
    int comp[10];
    CHECK(ps_graph_components(&g, comp) == 3);
    for (int p = 0; p < 9; p++) CHECK_MSG(comp[p] == p % 2, "vertex %d in %d", p, comp[p]);
    CHECK(comp[9] == 2);
    ps_graph_free(&g);
    CHECK(g.n == 0 && g.offsets == NULL && g.neighbors == NULL && g.weights == NULL);
}

/* No edges: every vertex is its own component, in order. */
static void test_no_edges(void) {
    ps_graph g = graph_of(4, NULL, 0);
    REQUIRE(g.offsets);
    int comp[4];
    CHECK(ps_graph_components(&g, comp) == 4);
    for (int p = 0; p < 4; p++) CHECK(comp[p] == p);
    ps_graph_free(&g);
    ps_graph_free(NULL);
}

PS_TEST_MAIN(TEST(test_components_by_lowest_vertex), TEST(test_no_edges))
