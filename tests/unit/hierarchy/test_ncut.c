/* test_ncut.c: phase 2 on hand-made graphs (ncut.h): sink distances through
 * cell borders, the scale-free similarity, components, shared sinks. */
#include "hand_graph.h"
#include "hierarchy/ncut.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>

typedef struct hand_supernodes {
    ps_supernode_graph sg;
    uint32_t sinks[PS_HAND_GRAPH_MAX_V];
    size_t sizes[PS_HAND_GRAPH_MAX_V];
    int supernode_of[PS_HAND_GRAPH_MAX_V];
    int component[PS_HAND_GRAPH_MAX_V];
} hand_supernodes;

/* Supernode u has sink sinks[u] and owns the vertices nearest to it. */
static void make_supernodes(hand_supernodes *s, const ps_hand_graph *h, const uint32_t *sinks,
                            int m) {
    for (int u = 0; u < m; u++) s->sinks[u] = sinks[u], s->sizes[u] = 0;
    for (size_t p = 0; p < h->g.n; p++) {
        int best = 0;
        for (int u = 1; u < m; u++)
            if (labs((long)sinks[u] - (long)p) < labs((long)sinks[best] - (long)p)) best = u;
        s->supernode_of[p] = best;
        s->sizes[best]++;
    }
    ps_graph_components(&h->g, s->component);
    s->sg = (ps_supernode_graph){.m = m, .sinks = s->sinks, .sizes = s->sizes,
                                 .supernode_of = s->supernode_of, .component = s->component};
}

static double pair_ncut(const double W[3][3], int alone) {
    double cut = 0, assoc_alone = 0, assoc_rest = 0;
    for (int u = 0; u < 3; u++)
        for (int v = 0; v < 3; v++) {
            if (u == alone) assoc_alone += W[u][v];
            else assoc_rest += W[u][v];
            if (u == alone && v != alone) cut += W[u][v];
        }
    return cut / assoc_alone + cut / assoc_rest;
}

/* Sinks at 0, 4, 10 on a unit path: d = 4, 6, 10 exactly (each border path
 * dist[p] + 1 + dist[q]); sigma = PS_NCUT_SIGMA_SCALE * (4 + 6 + 10) / 3.
 * The root keeps the best single split, whose NCut is checked against W
 * computed here. */
static void test_path_distances_and_sigma(void) {
    static const uint32_t sinks[3] = {0, 4, 10};
    ps_hand_graph h;
    hand_supernodes s;
    ps_hand_graph_path(&h, 11, 1, 0);
    make_supernodes(&s, &h, sinks, 3);
    double d[3][3] = {{0, 4, 10}, {4, 0, 6}, {10, 6, 0}}, W[3][3];
    double sigma = PS_NCUT_SIGMA_SCALE * 20.0 / 3;
    for (int u = 0; u < 3; u++)
        for (int v = 0; v < 3; v++)
            W[u][v] = (double)s.sizes[u] * (double)s.sizes[v] * exp(-d[u][v] / sigma);
    double expected = fmin(pair_ncut(W, 0), pair_ncut(W, 2));
    ps_tree_node *tree;
    int n;
    REQUIRE(ps_ncut_hierarchy(&h.g, &s.sg, 2.0, 1, NULL, &tree, &n, NULL) == PS_OK);
    REQUIRE(n >= 3);
    CHECK_NEAR(tree[0].ncut, expected, 1e-9);
    ps_tree_free(tree, n);
}

static void run_two_groups(double length, ps_tree_node **tree, int *n) {
    static const uint32_t sinks[6] = {1, 3, 5, 40, 42, 44};
    ps_hand_graph h;
    hand_supernodes s;
    ps_hand_graph_path(&h, 46, length, 0);
    make_supernodes(&s, &h, sinks, 6);
    *tree = NULL;
    REQUIRE(ps_ncut_hierarchy(&h.g, &s.sg, 0.3, 2, NULL, tree, n, NULL) == PS_OK);
}

/* Two groups of sinks far apart on a path split; the result does not
 * change when every length is scaled by 1000. */
static void test_two_groups_scale_free(void) {
    static const int left[3] = {0, 1, 2}, right[3] = {3, 4, 5};
    ps_tree_node *tree, *scaled;
    int n, n_scaled;
    run_two_groups(1, &tree, &n);
    REQUIRE(tree);
    REQUIRE(n == 3);
    CHECK(tree[0].ncut < 0.01);
    for (int i = 0; i < 3; i++) {
        CHECK(tree[1].supernodes[i] == left[i]);
        CHECK(tree[2].supernodes[i] == right[i]);
    }
    CHECK(tree[1].ncut > 0.3 && tree[2].ncut > 0.3);
    run_two_groups(1000, &scaled, &n_scaled);
    REQUIRE(scaled);
    REQUIRE(n_scaled == n);
    for (int i = 0; i < n; i++) CHECK_NEAR(scaled[i].ncut, tree[i].ncut, 1e-9);
    ps_tree_free(tree, n);
    ps_tree_free(scaled, n_scaled);
}

/* Two path components (vertices 0..4 and 5..9) and a lone vertex 10 that is
 * the sink of two supernodes: components split off with NCut 0 (threshold 0
 * keeps only those splits). */
static void test_components_and_shared_sink(void) {
    static const uint32_t sinks[6] = {0, 10, 4, 10, 5, 9};
    ps_hand_graph h;
    hand_supernodes s;
    ps_hand_graph_path(&h, 10, 1, 5);
    h.offsets[11] = h.offsets[10]; /* vertex 10: no edges */
    h.g.n = 11;
    make_supernodes(&s, &h, sinks, 6);
    s.sizes[3] = 1; /* vertex 10 stands for both supernodes 1 and 3 */
    ps_tree_node *tree;
    int n;
    REQUIRE(ps_ncut_hierarchy(&h.g, &s.sg, 0.0, 1, NULL, &tree, &n, NULL) == PS_OK);
    REQUIRE(n >= 5);
    CHECK(tree[0].ncut == 0);
    REQUIRE(tree[1].n_supernodes == 2 && tree[2].n_supernodes == 4);
    CHECK(tree[1].supernodes[0] == 0 && tree[1].supernodes[1] == 2); /* component 0 */
    CHECK(tree[2].ncut == 0);
    CHECK(tree[3].n_supernodes == 2 && tree[3].supernodes[0] == 1 &&
          tree[3].supernodes[1] == 3); /* the shared sink, component 1 */
    CHECK(tree[4].n_supernodes == 2 && tree[4].supernodes[0] == 4 &&
          tree[4].supernodes[1] == 5);
    ps_tree_free(tree, n);
}

static void test_empty_supernode_rejected(void) {
    static const uint32_t sinks[2] = {0, 3};
    ps_hand_graph h;
    hand_supernodes s;
    ps_hand_graph_path(&h, 4, 1, 0);
    make_supernodes(&s, &h, sinks, 2);
    s.sizes[1] = 0;
    ps_tree_node *tree;
    int n;
    ps_error err = {0};
    CHECK(ps_ncut_hierarchy(&h.g, &s.sg, 0.3, 1, NULL, &tree, &n, &err) == PS_ERR_INVALID);
    CHECK(tree == NULL && n == 0);
}

PS_TEST_MAIN(TEST(test_path_distances_and_sigma), TEST(test_two_groups_scale_free),
             TEST(test_components_and_shared_sink), TEST(test_empty_supernode_rejected))
