/* test_bfs_order.c: the BFS relabelling is a permutation that maps every
 * edge to an edge of the same weight, keeps components contiguous with
 * their lowest vertex first, and numbers them as ps_graph_components;
 * taking a graph into the order and giving it back restores it exactly. */
#include "graph/bfs_order.h"
#include "graph/knn_graph.h"
#include "testlib.h"

#include <stdlib.h>
#include <string.h>

/* n random points in the unit cube, every point whose index is 1 mod
 * period shifted 50 away: two components. */
static double *two_clusters(size_t n, unsigned seed, size_t period) {
    double *p = malloc(n * 3 * sizeof *p);
    for (size_t i = 0; p && i < 3 * n; i++) {
        seed = seed * 1103515245u + 12345u;
        p[i] = (double)(seed >> 8) / 16777216.0 + ((i / 3) % period == 1 ? 50.0 : 0.0);
    }
    return p;
}

static void test_relabelled_graph(void) {
    size_t n = 300;
    double *p = two_clusters(n, 99, 3);
    REQUIRE(p);
    ps_graph g;
    REQUIRE(ps_knn_graph_build(p, n, 3, 5, 2, &g, NULL) == PS_OK);
    int *comp = malloc(n * sizeof *comp);
    REQUIRE(comp);
    int count = ps_graph_components(&g, comp);
    ps_bfs_order o;
    REQUIRE(ps_bfs_order_build(&g, &o, NULL) == PS_OK);
    CHECK(count == 2 && o.n_components == 2);
    CHECK(o.start[0] == 0 && o.start[o.n_components] == n);
    for (size_t i = 0; i < n; i++) CHECK(o.new_of[o.old_of[i]] == i);
    for (int c = 0; c < o.n_components; c++) {
        uint32_t root = o.old_of[o.start[c]];
        CHECK(comp[root] == c);
        for (size_t i = o.start[c]; i < o.start[c + 1]; i++)
            CHECK(comp[o.old_of[i]] == c && o.old_of[i] >= root);
    }
    CHECK(o.g.offsets[n] == g.offsets[n]);
    for (size_t i = 0; i < n; i++) {
        uint32_t u = o.old_of[i];
        REQUIRE(o.g.offsets[i + 1] - o.g.offsets[i] == g.offsets[u + 1] - g.offsets[u]);
        for (size_t k = 0; k < g.offsets[u + 1] - g.offsets[u]; k++) {
            CHECK(o.g.neighbors[o.g.offsets[i] + k] == o.new_of[g.neighbors[g.offsets[u] + k]]);
            CHECK(o.g.weights[o.g.offsets[i] + k] == g.weights[g.offsets[u] + k]);
        }
    }
    ps_bfs_order_free(&o);
    ps_graph_free(&g);
    free(comp), free(p);
}

static int same_arrays(const ps_graph *a, const ps_graph *b) {
    size_t edges = a->offsets[a->n];
    return a->n == b->n && b->offsets[b->n] == edges &&
           !memcmp(a->offsets, b->offsets, (a->n + 1) * sizeof *a->offsets) &&
           !memcmp(a->neighbors, b->neighbors, edges * sizeof *a->neighbors) &&
           !memcmp(a->weights, b->weights, edges * sizeof *a->weights);
}

/* Taking a graph gives the order a copy gives, and empties the graph;
 * giving it back restores every byte. */
static void test_take_and_give_back(void) {
    size_t n = 2000;
    double *p = two_clusters(n, 7, 5);
    REQUIRE(p);
    ps_graph g, kept;
    REQUIRE(ps_knn_graph_build(p, n, 3, 6, 2, &g, NULL) == PS_OK);
    REQUIRE(ps_knn_graph_build(p, n, 3, 6, 2, &kept, NULL) == PS_OK);
    ps_bfs_order copied, taken;
    REQUIRE(ps_bfs_order_build(&kept, &copied, NULL) == PS_OK);
    REQUIRE(ps_bfs_order_take(&g, 2, &taken, NULL) == PS_OK);
    CHECK(g.offsets == NULL && g.neighbors == NULL && g.weights == NULL);
    CHECK(same_arrays(&copied.g, &taken.g) && copied.n_components == taken.n_components &&
          !memcmp(copied.old_of, taken.old_of, n * sizeof *copied.old_of));
    REQUIRE(ps_bfs_order_give_back(&taken, 3, &g, NULL) == PS_OK);
    CHECK(same_arrays(&kept, &g));
    CHECK(taken.g.offsets == NULL && taken.old_of == NULL);
    ps_bfs_order_free(&copied);
    ps_graph_free(&g), ps_graph_free(&kept);
    free(p);
}

PS_TEST_MAIN(TEST(test_relabelled_graph), TEST(test_take_and_give_back))
