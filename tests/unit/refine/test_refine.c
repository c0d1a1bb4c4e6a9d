/* test_refine.c: phase 3 on hand-made graphs and trees (refine.h): which
 * segment merges, into which neighbour, in which order, and which stay. */
#include "hand_graph.h"
#include "refine/refine.h"
#include "testlib.h"

#include <stdlib.h>

/* Tree: root 0 = {0, 1, 2} -> 1 = {0} and 2 = {1, 2}; 2 -> 3 = {1}, 4 = {2}. */
static int all3[3] = {0, 1, 2}, only0[1] = {0}, pair12[2] = {1, 2}, only1[1] = {1},
           only2[1] = {2};
static const ps_tree_node tree5[5] = {
    {0, -1, {1, 2}, 3, all3, 0.1}, {1, 0, {-1, -1}, 1, only0, -1},
    {2, 0, {3, 4}, 2, pair12, 0.1}, {3, 2, {-1, -1}, 1, only1, -1},
    {4, 2, {-1, -1}, 1, only2, -1},
};

/* Supernode 1 (points 0, 1; f 5, 5.1) touches supernode 0 (points 2..5,
 * f 0..4) by 3 edges and supernode 2 (points 6..9, f 6..10) by 1; both
 * have feature size 4, so it merges into 0's leaf.  Points 10..12 (f 0,
 * 0.01, 0) are a component of their own, one leaf holding supernode 3 in a
 * tree with one more node: it never merges. */
static void test_merges_into_longer_border(void) {
    static const int edges[][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 3}, {1, 6}, {2, 3}, {3, 4},
                                   {4, 5}, {6, 7}, {7, 8}, {8, 9}, {5, 9}, {10, 11},
                                   {11, 12}};
    static const double f[13] = {5, 5.1, 0, 1, 2, 4, 6, 7, 8, 10, 0, 0.01, 0};
    static const int supernode_of[13] = {1, 1, 0, 0, 0, 0, 2, 2, 2, 2, 3, 3, 3};
    static const int component[13] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1};
    static int all4[4] = {0, 1, 2, 3}, only3[1] = {3};
    ps_tree_node tree[7] = {{0, -1, {1, 2}, 4, all4, 0}};
    for (int i = 0; i < 5; i++) tree[i + 1] = tree5[i], tree[i + 1].id = i + 1;
    tree[1].parent = 0;
    tree[1].children[0] = 2, tree[1].children[1] = 3;
    tree[3].children[0] = 4, tree[3].children[1] = 5;
    tree[2].parent = tree[3].parent = 1;
    tree[4].parent = tree[5].parent = 3;
    tree[6] = (ps_tree_node){6, 0, {-1, -1}, 1, only3, -1};
    tree[0].children[1] = 6;
    /* leaves: 2 = {0}, 4 = {1}, 5 = {2}, 6 = {3} */
    ps_hand_graph h;
    ps_hand_graph_edges(&h, 13, edges, (int)(sizeof edges / sizeof edges[0]), 1);
    int group[7];
    ps_merge *merges;
    int n_merges;
    ps_refine_input in = {.graph = &h.g, .f = f, .supernode_of = supernode_of,
                          .component = component, .tree = tree, .n_tree = 7,
                          .feature_threshold = 0.1};
    REQUIRE(ps_refine(&in, group, &merges, &n_merges, NULL) == PS_OK);
    REQUIRE(n_merges == 1);
    CHECK(merges[0].segment == 4 && merges[0].into == 2);
    CHECK_NEAR(merges[0].feature_size, 0.1, 1e-12);
    static const int expected[7] = {-1, -1, 2, -1, 2, 5, 6};
    for (int i = 0; i < 7; i++) CHECK_MSG(group[i] == expected[i], "group[%d] = %d", i, group[i]);
    free(merges);
}

/* A path 0..9 with f = p: leaf 1 = points 0..5 (feature 5), leaf 3 = 6, 7
 * and leaf 4 = 8, 9 (feature 1 each; threshold 0.5 * 9).  Leaf 3 goes
 * first (tie, lower id) into leaf 1 (1 edge * 5 beats 1 edge * 1); then
 * leaf 4, whose border with 3 now belongs to 1, follows into 1. */
static void test_merge_order_and_borders_move(void) {
    int edges[9][2];
    double f[10];
    int supernode_of[10], component[10] = {0};
    for (int p = 0; p < 10; p++) {
        f[p] = p;
        supernode_of[p] = p < 6 ? 0 : p < 8 ? 1 : 2;
        if (p < 9) edges[p][0] = p, edges[p][1] = p + 1;
    }
    ps_hand_graph h;
    ps_hand_graph_edges(&h, 10, (const int(*)[2])edges, 9, 1);
    int group[5];
    ps_merge *merges;
    int n_merges;
    ps_refine_input in = {.graph = &h.g, .f = f, .supernode_of = supernode_of,
                          .component = component, .tree = tree5, .n_tree = 5,
                          .feature_threshold = 0.5};
    REQUIRE(ps_refine(&in, group, &merges, &n_merges, NULL) == PS_OK);
    REQUIRE(n_merges == 2);
    CHECK(merges[0].segment == 3 && merges[0].into == 1);
    CHECK_NEAR(merges[0].feature_size, 1, 1e-12);
    CHECK(merges[1].segment == 4 && merges[1].into == 1);
    CHECK_NEAR(merges[1].feature_size, 1, 1e-12);
    static const int expected[5] = {-1, 1, -1, 1, 1};
    for (int i = 0; i < 5; i++) CHECK_MSG(group[i] == expected[i], "group[%d] = %d", i, group[i]);
    free(merges);

    /* threshold 0: every leaf stays */
    in.feature_threshold = 0;
    REQUIRE(ps_refine(&in, group, &merges, &n_merges, NULL) == PS_OK);
    CHECK(n_merges == 0);
    CHECK(group[1] == 1 && group[3] == 3 && group[4] == 4 && group[0] == -1);
    free(merges);
}

/* The larger neighbour across the shorter border wins: the product
 * border edges * feature size decides. */
static void test_large_feature_outweighs_border(void) {
    static const int edges[][2] = {{0, 1}, {0, 2}, {1, 2}, {2, 3}, {3, 4}, {4, 5},
                                   {5, 6}, {6, 7}, {7, 8}, {8, 9}};
    /* leaf 1 = {0, 1} f 0..1 (feature 1), leaf 3 = {2} f 3 (feature 0),
     * leaf 4 = {3..9} f 4..10 (feature 6); leaf 3 touches 1 twice, 4 once */
    static const double f[10] = {0, 1, 3, 4, 5, 6, 7, 8, 9, 10};
    static const int supernode_of[10] = {0, 0, 1, 2, 2, 2, 2, 2, 2, 2};
    static const int component[10] = {0};
    ps_hand_graph h;
    ps_hand_graph_edges(&h, 10, edges, (int)(sizeof edges / sizeof edges[0]), 1);
    int group[5];
    ps_merge *merges;
    int n_merges;
    ps_refine_input in = {.graph = &h.g, .f = f, .supernode_of = supernode_of,
                          .component = component, .tree = tree5, .n_tree = 5,
                          .feature_threshold = 0.15};
    REQUIRE(ps_refine(&in, group, &merges, &n_merges, NULL) == PS_OK);
    /* threshold 1.5: leaf 3 (0) into 4 (1 * 6 > 2 * 1), then leaf 1 (1) into 4 */
    REQUIRE(n_merges == 2);
    CHECK(merges[0].segment == 3 && merges[0].into == 4 && merges[0].feature_size == 0);
    CHECK(merges[1].segment == 1 && merges[1].into == 4);
    CHECK_NEAR(merges[1].feature_size, 1, 1e-12);
    CHECK(group[1] == 4 && group[3] == 4 && group[4] == 4);
    free(merges);
}

static void test_bad_supernode(void) {
    static const int edges[][2] = {{0, 1}};
    static const double f[2] = {0, 1};
    static const int supernode_of[2] = {0, 7}, component[2] = {0, 0};
    ps_hand_graph h;
    ps_hand_graph_edges(&h, 2, edges, 1, 1);
    int group[5];
    ps_merge *merges;
    int n_merges;
    ps_error err = {0};
    ps_refine_input in = {.graph = &h.g, .f = f, .supernode_of = supernode_of,
                          .component = component, .tree = tree5, .n_tree = 5,
                          .feature_threshold = 0.1};
    CHECK(ps_refine(&in, group, &merges, &n_merges, &err) == PS_ERR_INVALID);
    CHECK(merges == NULL && n_merges == 0);
}

PS_TEST_MAIN(TEST(test_merges_into_longer_border), TEST(test_merge_order_and_borders_move),
             TEST(test_large_feature_outweighs_border), TEST(test_bad_supernode))
