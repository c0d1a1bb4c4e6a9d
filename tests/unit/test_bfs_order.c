/* test_bfs_order.c: the BFS relabelling is a permutation that maps every
 * edge to an edge of the same weight, keeps components contiguous with
 * their lowest vertex first, and numbers them as ps_graph_components. */
#include "bfs_order.h"
#include "knn_graph.h"
#include "testlib.h"

#include <stdlib.h>

static void test_relabelled_graph(void) {
    size_t n = 300;
    double *p = malloc(n * 3 * sizeof *p);
    REQUIRE(p);
    unsigned s = 99;
    for (size_t i = 0; i < 3 * n; i++) {
        s = s * 1103515245u + 12345u;
        p[i] = (double)(s >> 8) / 16777216.0 + ((i / 3) % 3 == 1 ? 50.0 : 0.0);
    }
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

PS_TEST_MAIN(TEST(test_relabelled_graph))
